"""The test programmes of Vivas-López et al. (n.d.) Table 1 (erdesign.simulation.programmes, erdesign doe)."""

import json

import numpy as np
import pytest

from erdesign.cli import main
from erdesign.data.measurement import read_measurement
from erdesign.simulation.programmes import (
    EXPERIMENTS,
    PRBS_TAPS,
    ProgrammeError,
    dsfs,
    icps,
    prbs,
    prbs_bits,
    programme,
    road_profile,
    stepped_control,
)


def _runs(u):
    """(level, length in samples) of each run of equal values."""
    edges = np.flatnonzero(np.diff(u) != 0) + 1
    starts = np.concatenate([[0], edges])
    lengths = np.diff(np.concatenate([starts, [u.size]]))
    return u[starts], lengths


# ------------------------------------------------------------------------------------------------------- DSFS
def test_dsfs_steps_follow_table_1():
    # Vivas-López et al. Table 1: amplitude +-8 down to +-1 mm over 0.5-14.5 Hz; 1 Hz steps, 4 cycles each (ours)
    m = dsfs(rate=1000.0)
    f = np.arange(0.5, 14.6, 1.0)
    A = np.linspace(8e-3, 1e-3, f.size)
    starts = np.concatenate([[0.0], np.cumsum(4 / f)])
    # duration is the steps' cycles, to one sample
    assert m.time[-1] == pytest.approx(starts[-1], abs=1.5e-3)
    for k in range(f.size):
        # the second half of a step is past the quarter-cycle blend: a pure sine of A_k at f_k
        inside = (m.time > starts[k] + 0.5 * (starts[k + 1] - starts[k])) & (m.time < starts[k + 1])
        assert np.max(np.abs(m.displacement[inside])) == pytest.approx(A[k], rel=0.01)
        # frequency from the peak speed: v_max = 2 pi f A
        assert np.max(np.abs(m.velocity[inside])) / (2 * np.pi * A[k]) == pytest.approx(f[k], rel=0.02)


def test_dsfs_rejects_what_no_rig_can_play():
    with pytest.raises(ProgrammeError, match="frequency"):
        dsfs(rate=100.0)  # 14.5 Hz needs at least 8 samples a period
    with pytest.raises(ProgrammeError, match="frequency_range"):
        dsfs(frequency_range=(5.0, 1.0))


# ------------------------------------------------------------------------------------------------ road profile
def test_road_profile_band_peaks_and_rest():
    levels = (1e-3, 4e-3, 8e-3)
    m = road_profile(levels, duration=30.0, rate=200.0, seed=4)
    x, t = m.displacement, m.time
    # band-limited to the paper's 0-3 Hz: (almost) no power above 3.5 Hz
    P = np.abs(np.fft.rfft(x)) ** 2
    f = np.fft.rfftfreq(x.size, t[1] - t[0])
    assert P[f > 3.5].sum() < 1e-3 * P.sum()
    # each segment peaks at its level (to the sampling of the fine grid)
    edges = np.linspace(0, t[-1], 4)
    for k, level in enumerate(levels):
        seg = x[(t >= edges[k]) & (t < edges[k + 1])]
        assert np.max(np.abs(seg)) == pytest.approx(level, rel=0.01)
    # the actuator starts and ends at rest
    assert abs(x[0]) < 1e-12 and abs(x[-1]) < 1e-12 and abs(m.velocity[0]) < 1e-3
    # seeded: same seed, same record; another seed, another record
    assert np.array_equal(x, road_profile(levels, duration=30.0, rate=200.0, seed=4).displacement)
    assert not np.allclose(x, road_profile(levels, duration=30.0, rate=200.0, seed=5).displacement)


# ------------------------------------------------------------------------------------------- actuation signals
def test_stepped_control_staircase():
    t = np.arange(0.0, 16.0, 0.01)
    u = stepped_control(t, 0.1, 0.8, steps=8, hold=1.0)
    levels, lengths = _runs(u)
    np.testing.assert_allclose(np.unique(u), np.linspace(0.1, 0.8, 8), atol=1e-12)  # 10 % increments of duty
    assert np.all(lengths == 100)  # 1 s at 100 Hz each
    np.testing.assert_allclose(levels[:8], np.linspace(0.1, 0.8, 8))  # rising, then repeated


def test_icps_clock_period_increases():
    t = np.linspace(0.0, 40.0, 40001)
    u = icps(t, 0.5, 4.0, period_range=(0.05, 2.0), seed=3)
    assert u.min() >= 0.5 and u.max() <= 4.0
    # the levels cover the range (ICPS "covers the whole force range")
    assert u.max() - u.min() > 0.8 * 3.5
    _, lengths = _runs(u)
    dt = t[1] - t[0]
    # hold times grow along the record from 0.05 s to about 2 s (random levels may repeat only by chance)
    assert lengths[0] * dt == pytest.approx(0.05, abs=2 * dt)
    assert lengths[-2] * dt > 1.0
    assert np.all(np.diff(lengths[:-1]) >= -1)


@pytest.mark.parametrize("order", sorted(PRBS_TAPS))
def test_prbs_is_maximal_length(order):
    n = 2**order - 1
    bits = prbs_bits(order, 2 * n)
    # the period is exactly 2^n - 1: the sequence repeats then and its state visits every nonzero value
    assert np.array_equal(bits[:n], bits[n:])
    b = bits[:n]
    # balance: one more one than zeros over a period
    assert int(b.sum()) == 2 ** (order - 1)
    # two-valued circular autocorrelation of the +-1 sequence: N at lag 0, -1 at every other lag
    s = 2.0 * b - 1.0
    r = np.real(np.fft.ifft(np.abs(np.fft.fft(s)) ** 2))
    assert r[0] == pytest.approx(n)
    np.testing.assert_allclose(r[1:], -1.0, atol=1e-6)


def test_prbs_signal_levels_and_clock():
    t = np.arange(0.0, 25.5, 0.01)
    u = prbs(t, 0.1, 0.8, clock=0.1, order=8)
    assert set(np.unique(u)) == {0.1, 0.8}
    _, lengths = _runs(u)
    assert np.all(lengths % 10 == 0)  # changes only on the clock
    assert np.max(lengths) == 8 * 10  # longest run of an order-8 m-sequence: 8 bits
    with pytest.raises(ProgrammeError, match="order"):
        prbs_bits(20)


# --------------------------------------------------------------------------------------------- the experiments
@pytest.mark.parametrize("name", sorted(EXPERIMENTS))
def test_experiments_pair_table_1_signals(name):
    m = programme(name, control_range=(0.5e6, 4e6), rate=200.0)
    e = EXPERIMENTS[name]
    levels = np.unique(m.control)
    assert levels.min() >= 0.5e6 and levels.max() <= 4e6
    if e.actuation == "prbs":
        assert levels.size == 2
    elif e.actuation == "sc":
        assert levels.size == 8
    else:
        assert levels.size > 8
    peak = np.max(np.abs(m.displacement))
    assert peak == pytest.approx(8e-3, rel=0.01)  # +-8 mm at most in every row of Table 1
    assert m.description.startswith(name.upper())


def test_programme_names_and_errors():
    assert np.all(programme("rp", rate=200.0).control == 0)
    with pytest.raises(ProgrammeError, match="actuation signal; pair it"):
        programme("prbs")
    with pytest.raises(ProgrammeError, match="unknown 'x'"):
        programme("x")
    with pytest.raises(ProgrammeError, match="control_range"):
        programme("dsfs+sc")
    with pytest.raises(ProgrammeError, match="control_range"):
        programme("dsfs+sc", control_range=(2.0, 1.0))
    # nothing given is silently ignored
    with pytest.raises(ProgrammeError, match="control_range: 'rp' has no actuation signal"):
        programme("rp", control_range=(0.0, 1.0))
    with pytest.raises(ProgrammeError, match="actuation_options"):
        programme("dsfs", actuation_options={"clock": 0.2})
    with pytest.raises(ProgrammeError, match="displacement_options: .*unexpected keyword"):
        programme("E5", control_range=(0.0, 1.0), displacement_options={"amplitude": 0.01})


# -------------------------------------------------------------------------------------------------- the command
def test_doe_writes_a_playable_record(tmp_path, capsys):
    out = tmp_path / "e5.csv"
    code = main(["doe", "--programme", "E5", "--control-range", "0.2 A, 1.6 A", "--out", str(out), "--json"])
    assert code == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["programme"] == "E5" and doc["control_kind"] == "current" and doc["control_levels"] == 2
    rec = read_measurement(out, require_force=False)
    assert rec.force is None and rec.control_kind == "current"
    assert set(np.unique(rec.control)) == {0.2, 1.6}
    assert np.max(np.abs(rec.displacement)) == pytest.approx(8e-3, rel=1e-6)
    assert doc["samples"] == len(rec) and doc["duration_s"] == pytest.approx(rec.duration)
    # never overwritten silently
    code = main(["doe", "--programme", "E5", "--out", str(out)])
    assert code != 0 and "exists" in capsys.readouterr().err


@pytest.mark.parametrize(
    "args, words",
    [
        (["--programme", "sc"], "pair it with a displacement"),
        (["--programme", "E1", "--amplitudes", "8 mm"], "--amplitudes"),
        (["--programme", "dsfs", "--duration", "3 s"], "--duration"),
        (["--programme", "E2", "--control-range", "1 m, 2 m"], "--control-range"),
    ],
)
def test_doe_bad_options_are_one_line(tmp_path, capsys, args, words):
    code = main(["doe", *args, "--out", str(tmp_path / "p.csv")])
    err = capsys.readouterr().err.strip()
    assert code != 0 and words in err and "\n" not in err and "Traceback" not in err
    assert not (tmp_path / "p.csv").exists()


def test_simulate_runs_a_plan_without_scoring_it(tmp_path, capsys):
    plan, forces = tmp_path / "e2.csv", tmp_path / "forces.csv"
    assert main(["doe", "--programme", "E2", "--control-range", "0 A, 1 A", "--out", str(plan)]) == 0
    capsys.readouterr()
    code = main(
        [
            "simulate",
            str(plan),
            "--model",
            "bingham",
            "--params",
            "c0=2 kN*s/m, f_c=0.5 kN, f_c_u=1 kN",
            "--control-reference",
            "1 A",
            "--out",
            str(forces),
            "--json",
        ]
    )
    assert code == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["esr"] is None and doc["samples_scored"] == 0 and doc["samples"] > 0
    rec = read_measurement(forces)
    # Bingham: F = c0 v + (f_c + f_c_u u) sgn v; the plan's PRBS steps u between 0 and 1 A
    expected = 2000.0 * rec.velocity + (500.0 + 1000.0 * rec.control) * np.sign(rec.velocity)
    np.testing.assert_allclose(rec.force, expected, atol=1e-6 * np.max(np.abs(expected)))
