"""The shortcuts that make reading a long record fast (issue 27) give the results of the plain computations.

Each is checked against the computation it replaces: numpy.median, numpy.convolve, numpy.gradient, cos/sin of the
phase, and the harmonic fit of every sample (the block means' fit must be as accurate against the exact velocity).
"""

import numpy as np
import pytest

from erdesign.data import measurement as m


@pytest.mark.parametrize("kind", ["normal", "ties", "heavy tail", "sorted", "nan", "short"])
@pytest.mark.parametrize("n", [9000, 9001, 60000])
def test_median_is_numpy_median(kind, n):
    rng = np.random.default_rng(n)
    a = {
        "normal": lambda: rng.normal(size=n),
        "ties": lambda: rng.integers(0, 4, size=n).astype(float),  # the middle values sit in a run of equals
        "heavy tail": lambda: rng.standard_cauchy(size=n),
        "sorted": lambda: np.sort(rng.normal(size=n)),  # every 16th value is then a perfect sample
        "nan": lambda: np.where(np.arange(n) == n // 3, np.nan, rng.normal(size=n)),
        "short": lambda: rng.normal(size=n % 100 + 5),
    }[kind]()
    expected = np.median(a)
    got = m._median(a)
    assert got == expected or (np.isnan(expected) and np.isnan(got))  # the same value, not an approximation


@pytest.mark.parametrize("n, k", [(7, 2), (1000, 3), (30001, 75), (30001, 150)])
def test_moving_mean_is_the_convolution(n, k):
    rng = np.random.default_rng(k)
    # a periodogram spans many decades: the block sums must keep each mean's relative accuracy
    P = rng.exponential(size=n) * np.exp(-np.arange(n) / (n / 20)) * 1e-12
    expected = np.convolve(P, np.ones(2 * k + 1) / (2 * k + 1), mode="same")
    np.testing.assert_allclose(m._moving_mean(P, k), expected, rtol=1e-13, atol=0)  # measured 2e-15


@pytest.mark.parametrize("n", [3, 5, 6, 101])
def test_central_difference_edges_are_numpy_gradient(n):
    y = np.random.default_rng(n).normal(size=n)
    expected = np.gradient(y, 0.01, edge_order=2)
    if n >= 5:
        expected[2:-2] = (-y[4:] + 8 * y[3:-1] - 8 * y[1:-3] + y[:-4]) / (12 * 0.01)
    assert np.array_equal(m._central4(y, 0.01), expected)


def test_harmonic_columns_of_an_even_record_are_cos_and_sin():
    t = np.arange(60000) / 2000.0 + 3.0
    for f in (0.37, 2.0, 13.1):
        w = 2 * np.pi * f * (t - 3.5)
        expected = np.column_stack([g(k * w) for k in range(1, 16) for g in (np.cos, np.sin)])
        got = m._harmonic_columns(t, f, 15, origin=3.5)
        # the reference's own error is ~ulp(k w): 15 x 2 pi x 13.1 x 30 = 4e4 rad -> 7e-12
        np.testing.assert_allclose(got, expected, rtol=0, atol=3e-11)
    uneven = t + 1e-6 * np.sin(t)  # steps differ by 2e-3: the direct cos and sin
    assert not m._evenly_sampled(uneven) and m._evenly_sampled(t)
    w = 2 * np.pi * 2.0 * (uneven - uneven[0])
    np.testing.assert_allclose(m._harmonic_columns(uneven, 2.0, 1), np.column_stack([np.cos(w), np.sin(w)]), atol=0)


def _noisy_sine(n, fs, noise, seed):
    rng = np.random.default_rng(seed)
    f, phase = rng.uniform(1.5, 2.5), rng.uniform(0, 6)
    t = np.arange(n) / fs
    w = 2 * np.pi * f * t
    x = 0.01 * (np.sin(w + phase) + 0.2 * np.cos(3 * w)) + noise * 0.01 * rng.normal(size=n)
    v = 0.01 * 2 * np.pi * f * (np.cos(w + phase) - 0.6 * np.sin(3 * w))
    return t, x, v


@pytest.mark.parametrize("noise", [1e-3, 3e-2])
def test_block_mean_fits_are_as_accurate_as_fits_of_every_sample(monkeypatch, noise):
    """A long even record is fitted by block means (FIT_SAMPLES of them); fitting every sample (FIT_SAMPLES raised
    beyond the record) is the reference.  Over 8 noisy sines of 60,000 samples (random frequency and phase, a third
    harmonic) the error against the exact velocity must not grow: measured mean rms errors 3.5e-4 / 3.5e-4 of the
    peak (noise 1e-3) and 5.2e-4 / 5.2e-4 (noise 3e-2), block means / every sample.  Taking every 26th sample
    instead of the means (tried) gave 1.6e-3 at noise 3e-2: the bound 1.2 x catches that."""
    errors = {"blocks": [], "every sample": []}
    for seed in range(8):
        t, x, v_exact = _noisy_sine(60000, 2000.0, noise, seed)
        peak = np.max(np.abs(v_exact))
        for name, samples in (("blocks", m.FIT_SAMPLES), ("every sample", 10**9)):
            monkeypatch.setattr(m, "FIT_SAMPLES", samples)
            v, _ = m.derivatives(t, x)
            errors[name].append(np.sqrt(np.mean((v - v_exact) ** 2)) / peak)
    blocks, full = np.mean(errors["blocks"]), np.mean(errors["every sample"])
    assert blocks <= 1.2 * full, (blocks, full)


def test_block_mean_fits_reject_what_the_full_fit_rejects(monkeypatch):
    """Motion the harmonics cannot follow (a sine plus a burst at 400 Hz, above the block means' Nyquist frequency
    of 1000 / 26 Hz): the check of the model at every sample rejects it as the full fit does."""
    t = np.arange(60000) / 2000.0
    x = 0.01 * np.sin(2 * np.pi * 2.0 * t) + 1e-4 * np.sin(2 * np.pi * 400.0 * t) * (t > 20)
    x = x + 1e-6 * np.random.default_rng(0).normal(size=t.size)
    spectrum = m._spectrum(t, x)
    f0, sigma = m._dominant_frequency(t, x, spectrum), m._noise_level(x)
    assert m._periodic_derivatives(t, x, f0, sigma) is None
    monkeypatch.setattr(m, "FIT_SAMPLES", 10**9)
    assert m._periodic_derivatives(t, x, f0, sigma) is None


@pytest.mark.parametrize("parser", ["pandas", "pyarrow", "numpy"])
@pytest.mark.parametrize("variant", ["plain", "crlf", "comments and blank lines", "spaces", "';' and decimal commas"])
def test_each_parser_gives_the_line_by_line_result(tmp_path, monkeypatch, parser, variant):
    """The reader parses a well-formed file with the fastest parser already loaded (pandas, pyarrow, numpy) and
    anything irregular line by line (forced here by quoted cells in one row): the same arrays whichever ran, to the
    bit (17 significant digits: a parser that rounds a number wrongly shows in its last bit)."""
    import sys
    import warnings

    pytest.importorskip(parser)
    if parser != "pyarrow":
        monkeypatch.delitem(sys.modules, "pyarrow", raising=False)
    if parser != "pandas":
        monkeypatch.delitem(sys.modules, "pandas", raising=False)
    rng = np.random.default_rng(2)
    rows = [
        [f"{i / 1000:.6f}", f"{x:.17g}", f"{f:.17g}"]
        for i, (x, f) in enumerate(zip(rng.normal(0, 5, 300), rng.normal(0, 300, 300)))
    ]
    sep = ";" if variant.startswith("';'") else ","

    def text(quoted_row: int | None) -> str:
        lines = ["# rig 3", sep.join(["time [s]", "displacement [mm]", "force [N]"])]
        for i, cells in enumerate(rows):
            cells = [c.replace(".", ",") for c in cells] if sep == ";" else cells
            cells = [f'"{c}"' for c in cells] if i == quoted_row else cells
            # (spaces before a quote would make it a character of the cell, as csv reads it)
            lines.append((" " + sep + " " if variant == "spaces" and i != quoted_row else sep).join(cells))
        if variant == "comments and blank lines":
            lines[100:100] = ["", "# calibration changed", "   "]
        return ("\r\n" if variant == "crlf" else "\n").join(lines) + "\n"

    (tmp_path / "fast.csv").write_bytes(text(None).encode())
    (tmp_path / "slow.csv").write_bytes(text(7).encode())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a random walk of 0.3 s: few cycles, as intended
        fast, slow = m.read_measurement(tmp_path / "fast.csv"), m.read_measurement(tmp_path / "slow.csv")
    for column in ("time", "displacement", "force", "velocity"):
        assert np.array_equal(getattr(fast, column), getattr(slow, column)), column
    assert len(fast) == 300


def test_pandas_parses_first_when_its_converter_rounds_correctly(monkeypatch):
    """pandas' C parser is taken first from pandas 3.1 on (fast_float, correctly rounded); an older pandas gives way
    to pyarrow when pyarrow is loaded.  A number whose nearest double a sloppy converter misses (pandas #17154)."""
    import sys

    pandas = pytest.importorskip("pandas")
    pytest.importorskip("pyarrow")
    assert m._pandas_rounds_correctly("3.1.0") and m._pandas_rounds_correctly("10.0")
    assert not m._pandas_rounds_correctly("3.0.2") and not m._pandas_rounds_correctly("2.3.3")
    raw = b"-15.361,1.700000000000000177635684,0.1\n" * 5
    taken = []
    monkeypatch.setattr(m, "_parse_table_pandas", lambda *a: taken.append("pandas") or [np.zeros(5)] * 3)
    monkeypatch.setattr(m, "_parse_table_arrow", lambda *a: taken.append("pyarrow") or [np.zeros(5)] * 3)
    monkeypatch.setattr(pandas, "__version__", "3.1.2")
    m._parse_table(raw, 0, 3)
    monkeypatch.setattr(pandas, "__version__", "2.2.3")
    m._parse_table(raw, 0, 3)
    monkeypatch.delitem(sys.modules, "pyarrow")
    m._parse_table(raw, 0, 3)  # an older pandas without pyarrow: still faster than numpy's
    assert taken == ["pandas", "pyarrow", "pandas"]


def test_a_large_table_imports_pyarrow_for_its_parser(tmp_path):
    """Without pandas, a table of IMPORT_PARSER_BYTES or more imports pyarrow (when installed) rather than take
    numpy's parser, five times slower; a smaller one does not (the import would cost more than it saves)."""
    import subprocess
    import sys

    pytest.importorskip("pyarrow")
    path = tmp_path / "m.csv"
    t = np.arange(2000) / 1000.0
    path.write_text("time [s],displacement [m],force [N]\n" + "\n".join(f"{a},{np.sin(a)},{np.cos(a)}" for a in t))
    code = (
        "import sys; import erdesign.data.measurement as m; m.IMPORT_PARSER_BYTES = int(sys.argv[2]); "
        "m.read_measurement(sys.argv[1]); print('pyarrow' in sys.modules, 'pandas' in sys.modules)"
    )
    for limit, imported in ((1000, "True"), (10**9, "False")):
        out = subprocess.run([sys.executable, "-c", code, str(path), str(limit)], capture_output=True, text=True)
        assert out.stdout.split() == [imported, "False"], out.stderr
