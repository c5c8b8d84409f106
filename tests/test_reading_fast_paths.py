"""The third round of speed-ups of reading a long record (issue 27) changes no result and keeps its memory low.

Each shortcut is checked, bit for bit, against the computation it replaces: scipy's Butterworth design, the
smoothing of the whole periodogram, the harmonic series of the whole record in one piece (the code before, written
out here); and the read's peak memory is bounded (the cause of the slower reads in a fresh interpreter).
"""

import tracemalloc

import numpy as np
import pytest
from scipy.signal import butter

from erdesign.data import measurement as m


@pytest.mark.parametrize("order", [2, 4, 6, 8])
def test_butterworth_sections_are_scipys(order):
    rng = np.random.default_rng(order)
    for _ in range(100):
        fs = float(10 ** rng.uniform(1, 5))
        fc = float(0.5 * fs * 10 ** rng.uniform(-6, np.log10(0.99)))
        expected = butter(order, fc, fs=fs, output="sos")
        got = m._butterworth(order, 2 * fc / fs)
        # equal to the last bit: at a low cut-off one ulp of a denominator moves a section's gain by ~1e-8
        assert np.array_equal(got, expected), (order, fc, fs)
    assert not got.flags.writeable  # kept for the next record: nobody may change it


def _moving_mean_whole(P, k):
    """_moving_mean before it computed parts: every block of P at once."""
    B = 2 * k + 1
    n = P.size
    rows = -(-(n + 2 * k) // B) + 1
    Q = np.zeros((rows, B))
    Q.ravel()[k : k + n] = P
    suffix = np.ascontiguousarray(Q[:, ::-1])
    np.cumsum(suffix, axis=1, out=suffix)
    prefix = np.empty((rows, B))
    prefix[:, 0] = 0.0
    np.cumsum(Q[:, :-1], axis=1, out=prefix[:, 1:])
    return (suffix[:, ::-1].ravel()[:n] + prefix.ravel()[B : B + n]) / B


def test_moving_mean_of_a_part_is_that_part_of_the_whole(monkeypatch):
    monkeypatch.setattr(m, "MEANS_A_STEP", 300)  # several steps on these lengths
    rng = np.random.default_rng(0)
    for trial in range(600):
        n = int(rng.integers(1, 5000))
        k = int(rng.integers(1, n // 3 + 2))
        P = rng.exponential(size=n) * 10 ** rng.uniform(-30, 30)
        if trial % 3 == 0:  # a band of signal far above the noise, as a periodogram's
            P[: int(rng.integers(0, n + 1))] *= 1e6
        whole = _moving_mean_whole(P, k)
        assert np.array_equal(m._moving_mean(P, k), whole)
        lo = int(rng.integers(0, n))
        hi = int(rng.integers(lo + 1, n + 1))
        assert np.array_equal(m._moving_mean(P, k, lo, hi), whole[lo:hi])
        level = float(np.quantile(whole, rng.uniform(0.5, 1.0))) * rng.choice([0.999, 1.0, 1.001])
        above = np.flatnonzero(whole > level)
        assert m._last_mean_above(P, k, level) == (above[-1] if above.size else -1)


def test_last_mean_above_skips_lone_spikes():
    """A lone term far above the level (white noise beyond 10 x its mean: one bin in 22,000) lifts its windows'
    means by 1/(2k + 1) of itself only: the last mean above the level is the band's, found past the spike."""
    P = np.ones(30001)
    P[:300] = 1e4  # the band of the signal
    P[25000] = 50.0  # a spike, above the level 10 but not its window's mean
    k = 75
    expected = np.flatnonzero(_moving_mean_whole(P, k) > 10.0)[-1]
    assert m._last_mean_above(P, k, 10.0) == expected
    assert m._last_mean_above(P, k, 1e5) == -1


def _series_whole(t, x, f, c, kept, origin, limit):
    """_harmonic_series before it went block by block: the record's harmonics in one (n, 2K) array."""
    columns = m._harmonic_columns(t, f, max(kept), origin=origin, even=True) if kept else None
    model = np.subtract(t, origin)
    model *= c[1]
    model += c[0]
    w = 2 * np.pi * f
    v = np.full_like(t, c[1])
    a = np.zeros_like(t)
    for k in kept:
        ck, sk = c[2 * k], c[2 * k + 1]
        cos, sin = columns[:, 2 * k - 2], columns[:, 2 * k - 1]
        h = ck * cos + sk * sin
        v += (k * w) * (sk * cos - ck * sin)
        a -= (k * w) ** 2 * h
        model += h
    r = x - model
    return None if np.sqrt(np.sum(r * r) / t.size) > limit else (v, a)


@pytest.mark.parametrize("block", [1000, 16384])
@pytest.mark.parametrize("kept", [[1], [1, 3], [2, 5, 15], []])
def test_harmonic_series_by_blocks_is_the_whole_series(monkeypatch, block, kept):
    monkeypatch.setattr(m, "SERIES_BLOCK", block)
    rng = np.random.default_rng(len(kept))
    t = np.arange(60001) / 2000.0 + 1.25
    f = 1.37
    c = np.zeros(34)
    c[:2] = 1e-3, 2e-4
    for k in kept:
        c[2 * k : 2 * k + 2] = rng.normal(scale=0.01 / k, size=2)
    origin = t[13]
    x = (t - origin) * c[1] + c[0] + rng.normal(scale=1e-6, size=t.size)  # any x: its residual decides acceptance
    expected = _series_whole(t, x, f, c, kept, origin, 1.0)
    got = m._harmonic_series(t, x, f, c, kept, None, origin, 1.0)
    assert np.array_equal(got[0], expected[0]) and np.array_equal(got[1], expected[1])
    # the acceptance too: a limit below the residual's rms rejects, above it accepts
    assert m._harmonic_series(t, x, f, c, kept, None, origin, 1e-12) is None


def _write(path, t, x, F, time_unit="s"):
    with open(path, "w") as fh:
        fh.write(f"time [{time_unit}],displacement [m],force [N]\n")
        for row in zip(t, x, F):
            fh.write(",".join(repr(float(v)) for v in row) + "\n")


def test_a_read_peaks_below_one_and_a_half_files_above_its_record(tmp_path):
    """The reader frees the file's bytes before the derivatives and sums the harmonic series block by block: the
    memory it takes on the way and gives back is below 1.5 x the file's size (measured 1.0-1.3; 2.2 before).  Above
    twice the file's size, glibc's allocator (whose threshold follows the largest block freed, the file's bytes)
    gave it back to the system after every read and the next read took it again, page by page, cleared: 2-3 ms of a
    60,000-row read in a fresh interpreter."""
    n = 60_000
    t = np.arange(n) / 2000.0
    rng = np.random.default_rng(5)
    for name, x in (
        ("sine", 0.01 * np.sin(2 * np.pi * 2.0 * t) + 2e-6 * rng.normal(size=n)),
        ("random", np.convolve(rng.normal(size=n), np.ones(400) / 400, "same") * 0.05),
    ):
        path = tmp_path / f"{name}.csv"
        _write(path, t, x, 500.0 * np.tanh(np.gradient(x, t) / 0.01))
        m.read_measurement(path)  # imports and first calls
        tracemalloc.start()
        try:
            record = m.read_measurement(path)
            kept, peak = tracemalloc.get_traced_memory()
        finally:
            tracemalloc.stop()
        assert len(record) == n
        assert peak - kept < 1.5 * path.stat().st_size, name


def test_time_steps_that_round_to_nothing_in_seconds_are_refused(tmp_path):
    """Two times 1 ulp apart in ms are one time in s: refused naming the column (before, by from_arrays)."""
    t = np.arange(100) * 1.0
    t[50:] += 75.0
    t[49] = 125.15899322306439
    t[50] = np.nextafter(t[49], np.inf)
    assert t[50] * 1e-3 == t[49] * 1e-3 and np.all(np.diff(t) > 0)
    path = tmp_path / "ms.csv"
    _write(path, t, np.sin(t / 10.0) * 0.01, np.zeros(t.size), time_unit="ms")
    with pytest.raises(m.MeasurementError, match=r"column 1 \(time\).*increase strictly"):
        m.read_measurement(path)


def test_read_records_own_writable_columns(tmp_path):
    """Each column pyarrow parses is copied into an array of its own, writable (as before, when they were views of
    one table), not a view of the parser's read-only memory."""
    pytest.importorskip("pyarrow")  # loaded: the reader parses with it
    t = np.arange(200) / 100.0
    path = tmp_path / "r.csv"
    _write(path, t, 0.01 * np.sin(2 * np.pi * t), np.cos(t))
    record = m.read_measurement(path)
    for column in (record.time, record.displacement, record.force):
        assert column.flags.writeable and column.flags.c_contiguous
    assert not np.shares_memory(record.time, record.displacement)


def test_three_digit_exponents_with_a_zero_stay_on_the_fast_path(tmp_path, monkeypatch):
    """A column written with three-digit exponents (3.3e-005, as the C runtime of Windows and MATLAB write them) beside
    a zero (a command at 0 V) is read by the fast parser, exactly as the line-by-line reader reads it; an exponent of
    100 or more in size ('5e-150', '1E-0400') sends the file to the line-by-line reader, which names an underflow."""
    t = np.arange(400) / 1000.0
    rows = [
        f"{ti:.4f},{0.002 * np.sin(20 * ti):.4e},{300 * np.cos(20 * ti):.6g},{0 if i % 7 else 2}"
        for i, ti in enumerate(t)
    ]
    text = "time [s],displacement [m],force [N],voltage [V]\n" + "\n".join(rows) + "\n"
    text = text.replace("e-0", "e-00")  # 2.0000e-03 -> 2.0000e-003
    assert "e-003" in text
    path = tmp_path / "windows.csv"
    path.write_text(text)
    fast = m.read_measurement(path)
    assert m._read_fast(path.read_bytes(), "windows.csv", False) is not None  # the fast parser read it
    monkeypatch.setattr(m, "_read_fast", lambda *a: None)  # the line-by-line reader alone
    slow = m.read_measurement(path)
    assert np.array_equal(fast.displacement, slow.displacement) and np.array_equal(fast.control, slow.control)
    for number in ("5e-150", "1E-0400"):
        assert m._may_underflow(text.replace("2\n", number + "\n", 1).encode(), 0) is True
