"""Data-quality findings (erdesign.data.findings): each lab artefact is found on a truth-rig record that has it, with
its size, and nothing is found on clean truth-rig records of every example damper and motion nor on physical lags.

The artefacts are made by erdesign.simulation.truthrig.artefacts, written apart from the detectors; the real records
(shared/data/README.md) are read when ../shared/data is present.
"""

from __future__ import annotations

import functools
import json
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from erdesign.damper.files import load_example
from erdesign.data.findings import (
    FINDING_KINDS,
    LAG_EFFECTS,
    Finding,
    excluded_mask,
    find_data_problems,
    find_time_problems,
)
from erdesign.data.measurement import Measurement, MeasurementError
from erdesign.simulation.truthrig import TruthDamper, simulate_truth
from erdesign.simulation.truthrig import artefacts as A
from erdesign.simulation.truthrig.cases import DAMPERS, EXCITATIONS, benchmark_cases

DATA = Path(__file__).resolve().parents[2] / "shared" / "data"
needs_data = pytest.mark.skipif(
    not DATA.is_dir(), reason="../shared/data (third-party measured records) is absent in this checkout"
)


@functools.lru_cache(maxsize=None)
def _catalogue():
    return {c.name: c for c in benchmark_cases()}


@functools.lru_cache(maxsize=None)
def _clean_case(damper: str, excitation: str):
    """The catalogue's clean case of this damper and motion (exactly Bingham, perturbed calibration)."""
    return next(
        c for c in _catalogue().values() if c.kind == "clean" and c.damper == damper and c.excitation == excitation
    )


@functools.lru_cache(maxsize=None)
def _record(damper: str, excitation: str, rate: float = 1000.0) -> Measurement:
    """A clean truth-rig record at ``rate`` (1 kHz: a skew of 0.8 ms is under a sample)."""
    return replace(_clean_case(damper, excitation), rate=rate, noise=0.01).make().measured


def _kinds(findings):
    return [f.kind for f in findings]


# ---------------------------------------------------------------------------------------------------- clean
@pytest.mark.parametrize("damper", DAMPERS)
@pytest.mark.parametrize("excitation", EXCITATIONS)
def test_clean_truth_records_raise_no_finding(damper, excitation):
    """The catalogue's clean records (500 Hz, 1 or 3 % force noise, displacement noise 1e-4 of the peak): no
    finding, and none with the mean force a double-ended damper without preload shows (0 N)."""
    m = _clean_case(damper, excitation).make().measured
    assert _kinds(find_data_problems(m)) == []
    assert _kinds(find_data_problems(m, expected_mean_force=0.0)) == []


def _lab_programmes(damper):
    """Programmes a lab runs (issue 23): stepped sines of whole cycles over frequencies and field levels, field
    steps, sine sweeps and DoE programmes."""
    from erdesign.simulation.rig import field_steps, stepped_sine
    from erdesign.simulation.truthrig.motions import sine_programme, swept_sine

    ref = damper.fluid.reference_field
    return {
        "stepped_1_2Hz_3cycles": stepped_sine([0.01], [1.0, 2.0], [ref, 0.5 * ref], cycles=3, rate=500),
        "stepped_1_2Hz_3cycles_1kHz": stepped_sine([0.01], [1.0, 2.0], [ref, 0.5 * ref], cycles=3, rate=1000),
        "stepped_1_2Hz_3cycles_2kHz": stepped_sine([0.01], [1.0, 2.0], [ref, 0.5 * ref], cycles=3, rate=2000),
        "stepped_4_segments": stepped_sine(
            [0.01], [0.5, 1.0, 2.0, 3.0], [ref, 0.5 * ref, 0.0, ref], cycles=4, rate=500
        ),
        "stepped_1_2_4_8Hz_fields": stepped_sine(
            [0.008, 0.004, 0.002, 0.001], [1.0, 2.0, 4.0, 8.0], [ref, 0.3 * ref], cycles=3, rate=2000
        ),
        "field_steps": field_steps(0.01, 1.0, ref, cycles=4, step_period=0.5, rate=1000),
        "sine_sweep": swept_sine(0.2, 0.5, 5.0, duration=20.0, rate=500),
        "doe_programme": sine_programme([0.01, 0.005, 0.003, 0.01], [1.0, 2.0, 0.5, 2.0], duration=12.0, rate=500),
    }


@pytest.mark.parametrize("damper", ["mr_valve", "kamath_wereley", "makris"])
@pytest.mark.parametrize("programme", list(_lab_programmes(load_example("mr_valve"))))
def test_clean_lab_programmes_are_not_smoothed(damper, programme):
    """Issue 23: a clean stepped sine (1 Hz then 2 Hz, 3 cycles each) was called smoothed over 125 samples - whole
    cycles of a force with odd harmonics only leave no power at the multiples of 4 Hz.  No smoothing on any of these
    programmes at 1 % force noise, nor when the force is clipped at 95 % or 80 % of its peak (then: clipped only)."""
    d = load_example(damper)
    truth = TruthDamper(d, {}, viscosity_factor=1.1, yield_stress_factor=0.9)
    m = simulate_truth(truth, _lab_programmes(d)[programme], force_noise=0.01, seed=4).measured
    assert "smoothed" not in _kinds(find_data_problems(m))
    for level in (0.95, 0.8):
        clipped = m.with_force(np.minimum(m.force, level * m.force.max()))
        assert "smoothed" not in _kinds(find_data_problems(clipped))


@pytest.mark.parametrize("level", [0.95, 0.8])
def test_the_issue_record_clipped_is_clipped_and_nothing_else(level):
    """The issue's record (MR valve, 1 Hz then 2 Hz, 3 cycles each, 500 Hz, 1 % noise) clipped at 95 % and 80 % of
    its peak force: one finding, clipped, excluding exactly the clipped samples."""
    d = load_example("mr_valve")
    truth = TruthDamper(d, {}, viscosity_factor=1.1, yield_stress_factor=0.9)
    m = simulate_truth(truth, _lab_programmes(d)["stepped_1_2Hz_3cycles"], force_noise=0.01, seed=4).measured
    assert find_data_problems(m) == []
    cap = level * m.force.max()
    (f,) = find_data_problems(m.with_force(np.minimum(m.force, cap)))
    assert f.kind == "clipped" and np.array_equal(f.excluded, m.force >= cap)


@pytest.mark.parametrize("frequency,rate", [(5.0, 500.0), (10.0, 1000.0)])
@pytest.mark.parametrize("seed", [0, 1])
def test_reversals_on_samples_are_not_a_channel_skew(frequency, rate, seed):
    """A sine whose frequency divides the sampling rate puts every reversal on a sample, and the force of a clean
    MR valve jumps just after it - half a sample "late" at every reversal with no delay at all; this was called a
    1 ms skew on every seed (found with issue 23's clean programmes)."""
    from erdesign.simulation.rig import sine

    d = load_example("mr_valve")
    truth = TruthDamper(d, {}, viscosity_factor=1.1, yield_stress_factor=0.9)
    motion = sine(0.01 / frequency * 2, frequency, d.fluid.reference_field, cycles=8, rate=rate)
    m = simulate_truth(truth, motion, force_noise=0.01, seed=seed).measured
    assert _kinds(find_data_problems(m)) == []


@pytest.mark.parametrize(
    "name", [n for n in (f"compressibility-{s}-{d}" for s in ("moderate", "large") for d in DAMPERS)]
)
def test_a_compressible_column_is_not_called_channel_skew(name):
    """A compressible column makes the force lag the motion (truth rig: compliance, 1 kHz); the lag rounds the
    force's reversals and grows with the force, so it is physics, not skew, and nothing else is found either."""
    case = next(c for n, c in _catalogue().items() if n.startswith(name))
    assert _kinds(find_data_problems(case.make().measured)) == []


def test_preyield_elasticity_is_not_called_channel_skew():
    """The catalogue's large pre-yield case on Makris's damper at 500 Hz and 3 % noise: its rounded reversals
    once passed as a 6 ms skew when jumps of 10 noise levels counted as sharp."""
    case = _catalogue()["preyield_elasticity-large-makris-sine-3pct"]
    assert "channel_skew" not in _kinds(find_data_problems(case.make().measured))


# ---------------------------------------------------------------------------------------------------- artefacts
ON = [("mr_valve", "sine"), ("mr_valve_current", "sine"), ("kamath_wereley", "earthquake")]


@pytest.mark.parametrize("damper,excitation", ON + [("makris", "random")])
def test_a_clipped_force_is_found_and_excluded(damper, excitation):
    m = _record(damper, excitation)
    level = 0.8 * float(m.force.max())
    (f,) = find_data_problems(A.clip_force(m, level))
    assert f.kind == "clipped"
    assert np.array_equal(f.excluded, m.force >= level)  # every clipped sample, nothing else
    assert f"{int((m.force >= level).sum())} samples" in f.where
    assert excluded_mask([f], len(m)).sum() == (m.force >= level).sum()


@pytest.mark.parametrize("damper,excitation", ON + [("makris", "random")])
def test_a_saturated_displacement_channel_is_found_and_excluded(damper, excitation):
    m = _record(damper, excitation)
    level = 0.85 * float(np.max(np.abs(m.displacement)))
    (f,) = find_data_problems(A.saturate_displacement(m, level))
    assert f.kind == "saturated_displacement"
    assert np.array_equal(f.excluded, np.abs(m.displacement) >= level)


@pytest.mark.parametrize("damper,excitation", ON + [("makris", "random")])
@pytest.mark.parametrize("window", [4, 30])
def test_a_causal_moving_average_is_found_with_its_window(damper, excitation, window):
    (f,) = find_data_problems(A.moving_average(_record(damper, excitation), window))
    assert f.kind == "smoothed"
    assert f"{window} samples" in f.where  # the window exactly: the nulls sit at k fs / N
    assert {"compressibility", "preyield_elasticity", "field_lag"} <= set(f.unsafe_for)


@pytest.mark.parametrize("damper,excitation", ON + [("makris", "random"), ("makris", "sine")])
@pytest.mark.parametrize("skew", [0.8e-3, -2e-3])
def test_a_channel_skew_is_estimated_within_a_sample(damper, excitation, skew):
    """0.8 ms at 1 kHz (the issue's example) and the force leading by 2 ms; one sample is 1 ms."""
    (f,) = find_data_problems(A.skew_force(_record(damper, excitation), skew))
    assert f.kind == "channel_skew"
    assert f.skew_s == pytest.approx(skew, abs=0.5e-3)  # measured within 0.2 ms
    assert set(LAG_EFFECTS) <= set(f.unsafe_for)
    assert f.as_json()["skew_s"] == f.skew_s


def test_a_time_gap_is_found_with_its_length():
    m = _record("mr_valve", "sine")
    (f,) = find_data_problems(A.cut_time_gap(m, 2.0, 1.0))
    assert f.kind == "time_gap"
    gap = re.search(r"\(([\d.]+) s missing, about (\d+) samples", f.message)
    assert float(gap[1]) == pytest.approx(1.0, abs=2e-3) and int(gap[2]) == pytest.approx(1000, abs=2)


def test_time_that_goes_back_is_a_finding_on_arrays_and_an_error_in_a_record():
    m = _record("mr_valve", "sine")
    arrays = A.shuffle_time(m, 100, rows=3)
    (f,) = find_time_problems(arrays["time"], record="shuffled")
    assert f.kind == "non_monotonic_time" and "sample 101" in f.where and f.record == "shuffled"
    with pytest.raises(MeasurementError, match="time must increase"):
        Measurement.from_arrays(arrays["time"], arrays["displacement"], arrays["force"])
    assert find_time_problems(m.time) == []


@pytest.mark.parametrize("damper,excitation", ON + [("makris", "random")])
def test_a_force_drift_is_found_and_an_offset_with_the_expected_mean(damper, excitation):
    """A drift of 8 % of the RMS force over the record (a load cell warming); an offset of 10 % is found only when
    the caller says what the mean should be (a gas preload would look the same)."""
    m = _record(damper, excitation)
    rms = float(np.sqrt(np.mean(m.force**2)))
    (f,) = find_data_problems(A.offset_and_drift(m, 0.05 * rms, 0.08 * rms))
    assert f.kind == "force_offset_drift"
    drift = float(re.search(r"drifts by ([-+\d.e]+) N", f.message)[1])
    assert drift == pytest.approx(0.08 * rms, rel=0.25)
    offset_only = A.offset_and_drift(m, 0.1 * rms, 0.0)
    assert find_data_problems(offset_only) == []
    (g,) = find_data_problems(offset_only, expected_mean_force=0.0)
    assert g.kind == "force_offset_drift" and "offset by" in g.message


@pytest.mark.parametrize(
    "damper,excitation,rate",
    [
        ("mr_valve", "sine", 1000.0),
        ("makris", "random", 1000.0),
        ("kamath_wereley", "earthquake", 1000.0),
        ("mr_valve_current", "sine", 100.0),
    ],
)
def test_quantized_displacement_is_found_with_its_step(damper, excitation, rate):
    """5 um steps (the issue's shaking-table record: 0.005 mm at 100 Hz)."""
    (f,) = find_data_problems(A.quantize_displacement(_record(damper, excitation, rate), 5e-6))
    assert f.kind == "quantized_displacement"
    step = float(re.search(r"grid of ([\d.]+) um", f.message)[1])
    assert step == pytest.approx(5.0, rel=0.1)


# ---------------------------------------------------------------------------------------------------- API
def test_exclude_clipped_decides_where_the_detector_is_unsure():
    t = np.linspace(0, 2, 2001)
    x = 0.01 * np.sin(2 * np.pi * t) + 1e-6 * np.random.default_rng(0).standard_normal(t.size)
    F = np.round(1000 * np.cos(2 * np.pi * t))  # a force quantised to 1 N: its crests are flat for ~11 samples
    m = Measurement.from_arrays(t, x, F)
    (f,) = find_data_problems(m)  # as many at 999 N as at 1000 N: no pile-up at a limit
    assert f.kind == "clipped" and f.excluded is None and "--exclude-clipped" in f.message
    (g,) = find_data_problems(m, exclude_clipped=True)
    assert np.array_equal(g.excluded, np.abs(F) == 1000)
    clipped = A.clip_force(_record("mr_valve", "sine"), 1000.0)
    (h,) = find_data_problems(clipped, exclude_clipped=False)
    assert h.excluded is None and excluded_mask([h], len(clipped)).sum() == 0


def test_as_json_has_the_contract_keys_and_no_nan():
    f = Finding("channel_skew", "m", "r", "w", skew_s=8e-4, unsafe_for=LAG_EFFECTS)
    assert f.as_json() == {"kind": "channel_skew", "message": "m", "record": "r", "where": "w", "skew_s": 8e-4}
    g = Finding("time_gap", "m", "r", "w")
    assert set(g.as_json()) == {"kind", "message", "record", "where"}
    assert str(g) == "time_gap (w): m"
    json.dumps([Finding("channel_skew", "m", "r", "w", skew_s=float("nan")).as_json()], allow_nan=False)
    with pytest.raises(ValueError, match="kind"):
        Finding("noise", "m", "r", "w")
    with pytest.raises(ValueError, match="findings"):
        excluded_mask([Finding("clipped", "m", "r", "w", excluded=np.ones(3, bool))], 4)
    with pytest.raises(ValueError, match="exclude_clipped"):
        find_data_problems(_record("mr_valve", "sine"), exclude_clipped="yes")
    assert set(FINDING_KINDS) >= {"clipped", "smoothed", "channel_skew", "quantized_displacement"}


# ---------------------------------------------------------------------------------------------------- real data
@needs_data
def test_dykes_ransim_u_is_clipped_and_not_smoothed():
    """shared/data/README.md: about 220 samples of ransim_u sit at +4545 N (measured 217 in 3 runs); around them, from
    19.53 to 19.91 s, the displacement is held at 10.5-11 mm - beyond the 8.4 mm the rest of the record reaches -
    while the force swings from -2.7 kN to the clip: an excursion of the actuator or transducer, left out."""
    from erdesign.data.measurement import read_measurement

    m = read_measurement(DATA / "dyke_nees" / "ransim_u.csv")
    findings = find_data_problems(m)
    assert _kinds(findings) == ["clipped", "saturated_displacement"]
    assert findings[0].excluded.sum() == pytest.approx(218, abs=3)
    assert np.all(m.force[findings[0].excluded] == pytest.approx(4545.4545))
    held = m.time[findings[1].excluded]
    assert held.min() == pytest.approx(19.53, abs=0.01) and held.max() == pytest.approx(19.91, abs=0.01)
    assert np.median(m.displacement[findings[1].excluded]) > 0.0105
    outside = ~(findings[1].excluded | findings[0].excluded)
    assert m.displacement[outside].max() < 0.0085


def _quiroz_preprocessed(path: Path) -> Measurement:
    a = np.loadtxt(path)
    return Measurement.from_arrays(a[:, 0], a[:, 1] * 1e-3, a[:, 3], name=path.name)


@needs_data
def test_quirozs_preprocessed_files_are_smoothed_over_a_tenth_of_a_period():
    """shared/data/README.md: the source smoothed every preprocessed file by a causal moving average over 1/10 of
    a period; the window is found to the sample on all 30 (5 Hz at 5 ms: 4 samples; 3 Hz at 1 ms: 33)."""
    from erdesign.data.quiroz import QUIROZ_FILE_NAME

    files = sorted((DATA / "quiroz2022_utfsm_mr" / "preprocessed").glob("*.txt"))
    assert len(files) == 30
    for path in files:
        m = _quiroz_preprocessed(path)
        freq = float(re.fullmatch(QUIROZ_FILE_NAME, path.stem)["freq"].replace("x", "."))
        dt = m.duration / (len(m) - 1)
        smoothed = [f for f in find_data_problems(m) if f.kind == "smoothed"]
        assert len(smoothed) == 1, path.name
        window = int(re.search(r"(\d+) samples", smoothed[0].where)[1])
        assert window == int(0.1 / freq / dt + 1e-9), path.name


def _quiroz_raw(path: Path) -> Measurement:
    """A raw DAQ export (README: 7 header lines; x [mm] = 10 x the displacement channel, F [N] = 980.665 x the force
    channel; the channels swapped at 0.1, 0.25, 0.5 and 5 Hz)."""
    head = path.read_text(errors="replace")[:400]
    dt = float(re.search(r"Sampling Interval:\s*([\d.]+)", head)[1])
    rows = [line.split(",") for line in path.read_text(errors="replace").splitlines()[7:]]
    a = np.array([(float(r[2]), float(r[3])) for r in rows if len(r) >= 4])
    swapped = re.search(r"mm(0x1|0x25|0x5|5)Hz", path.stem) is not None
    x, F = (a[:, 1], a[:, 0]) if swapped else (a[:, 0], a[:, 1])
    return Measurement.from_arrays(np.arange(a.shape[0]) * dt, 10e-3 * x, 980.665 * F, name=path.name)


@needs_data
def test_quirozs_raw_files_are_not_smoothed():
    files = sorted((DATA / "quiroz2022_utfsm_mr" / "raw").glob("ME*.txt"))
    assert files
    for path in files:
        assert "smoothed" not in _kinds(find_data_problems(_quiroz_raw(path))), path.name


@pytest.mark.parametrize("n", [5, 63, 1000])
def test_edge_records_raise_nothing(n):
    """Short records, a dead (constant) force, a noise-free two-level force, pure noise and no force at all: no
    exception and no finding (a two-level force is not a clipped one; a drift is not judged on fewer than 600)."""
    rng = np.random.default_rng(1)
    t = np.arange(n) * 1e-3
    x = 0.01 * np.sin(2 * np.pi * 5 * t) + 1e-6 * rng.standard_normal(n)
    for F in (None, np.zeros(n), np.full(n, 5.0), rng.standard_normal(n), 100 * np.sign(np.cos(2 * np.pi * 5 * t))):
        assert find_data_problems(Measurement.from_arrays(t, x, F)) == []
