"""The virtual rig: exact kinematics, the noise it claims, the hidden truth it records."""

import numpy as np
import pytest

from erdesign import load_example
from erdesign.simulation.rig import (
    OVERSAMPLING,
    earthquake_motion,
    field_steps,
    random_motion,
    run_rig,
    sine,
    stepped_sine,
)


def test_sine_kinematics_are_exact():
    m = sine(0.005, 2.0, 3e6, cycles=2, rate=400)
    w = 4 * np.pi
    # differentiated on an 8x finer grid with second-order differences: error (w dt/8)^2 / 6 ~ 1e-7 relative
    np.testing.assert_allclose(m.velocity, 0.005 * w * np.cos(w * m.time), atol=1e-5 * 0.005 * w)
    np.testing.assert_allclose(m.acceleration[1:-1], -0.005 * w**2 * np.sin(w * m.time[1:-1]), atol=1e-4 * 0.005 * w**2)
    assert OVERSAMPLING == 8 and np.all(m.control == 3e6)


def test_sweep_is_smooth_and_steps_the_field():
    m = stepped_sine([0.004, 0.008], [1.0, 2.5], [0.0, 3e6, 1e6], cycles=2, rate=500)
    assert m.time[-1] == pytest.approx(2 / 1.0 + 2 / 2.5 + 2 / 1.0, abs=2e-3)
    assert set(np.unique(m.control)) == {0.0, 1e6, 3e6}
    # velocity continuous: no jump larger than a step's worth of the peak acceleration
    dv = np.abs(np.diff(m.velocity))
    assert dv.max() < 1.5 * np.abs(m.acceleration).max() * (m.time[1] - m.time[0])


def test_field_steps_random_and_earthquake_motions():
    m = field_steps(0.005, 2.0, 3e6, cycles=4, step_period=0.5, rate=500)
    assert set(np.unique(m.control)) == {0.0, 3e6}
    r = random_motion(0.003, (0.5, 5.0), duration=4.0, rate=500, seed=1)
    # the RMS is set on the 8x finer grid; every eighth sample keeps it to within 1 %
    assert np.sqrt(np.mean(r.displacement**2)) == pytest.approx(0.003, rel=0.01)
    q = earthquake_motion(0.01, duration=8.0, rate=500, seed=2)
    assert np.max(np.abs(q.displacement)) == pytest.approx(0.01, rel=1e-3)  # peak set on the fine grid
    assert abs(q.displacement[-1]) < 1e-6  # comes to rest


def test_noise_and_truth_are_as_requested():
    d = load_example("makris")
    rig = run_rig(
        d,
        sine(0.005, 2.0, 3e6, cycles=4, rate=500),
        hidden={"seal_friction": {"friction_force": 250.0}},
        viscosity_factor=1.3,
        force_noise=0.01,
        displacement_noise=1e-3,
        seed=3,
    )
    noise = rig.record.force - rig.true_force
    rms = np.sqrt(np.mean(rig.true_force**2))
    # 2001 samples: the sample standard deviation is within 3 / sqrt(2 n) = 5 % of the true one
    assert np.std(noise) == pytest.approx(0.01 * rms, rel=0.05)
    assert rig.truth["friction_force"] == 250.0 and rig.truth["viscosity_factor"] == 1.3
    assert rig.hidden == ("seal_friction",) and "seal_friction (friction_force = 250 N)" in rig.comment
    # the derived velocity comes from the noisy displacement, not from the truth
    assert not np.array_equal(rig.record.velocity, rig.motion.velocity)
    v_err = np.sqrt(np.mean((rig.record.velocity - rig.motion.velocity) ** 2)) / np.abs(rig.motion.velocity).max()
    assert v_err < 2e-3


def test_mr_rig_uses_the_damper_s_control():
    d = load_example("mr_mixed")
    rig = run_rig(d, sine(0.005, 2.0, 2e5, cycles=2, rate=300), seed=1)
    assert rig.record.control_kind == "magnetic field"
