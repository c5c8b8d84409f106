"""Inverse models: forward(inverse(F)) = F where reachable; unreachable forces clipped and reported."""

import numpy as np
import pytest

from erdesign.data.measurement import Measurement
from erdesign.identification.inverse import InverseError, inverse_control
from erdesign.models.registry import get_model

T = np.linspace(0, 2, 801)
REC = Measurement.from_arrays(T, 0.01 * np.sin(2 * np.pi * T))
CASES = {
    "kwok_tanh": {"alpha_u": 800.0, "c_u": 1000.0},
    "magic_formula": {"D_u": 800.0},
    "bouc_wen_normalized": {"k_w_u": 800.0, "k_v_u": 1000.0},
    "lugre_modified": {"sigma0": 1e6, "a0": 2e-3, "sigma_b": 1000.0},
    "biviscous": {"F_y_u": 800.0},
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_forward_of_inverse_returns_reachable_forces(name):
    model = get_model(name)
    vals = model.check_values(CASES[name])
    # a force the damper can produce: the model's own force at a varying current inside [0, 1] A
    i_true = 0.5 + 0.4 * np.sin(2 * np.pi * 3 * T)
    F_target = model.force(Measurement.from_arrays(T, REC.displacement, control=i_true, control_kind="current"), vals)
    r = inverse_control(model, REC, F_target, vals, control_range=(0.0, 1.0))
    ok = ~r.unreachable
    assert ok.mean() > 0.9, name  # almost all reachable (those at v = 0 have no authority)
    # forward(inverse(F)) = F to round-off where reachable (root finding to its default tolerance: 1e-6 N)
    assert np.max(np.abs(r.force[ok] - F_target[ok])) < 1e-6 * np.max(np.abs(F_target)) + 1e-6


def test_unreachable_forces_are_clipped_and_reported():
    model = get_model("kwok_tanh")
    vals = model.check_values(CASES["kwok_tanh"])
    F_big = np.full(T.size, 1e5)
    r = inverse_control(model, REC, F_big, vals, control_range=(0.0, 1.0))
    assert r.n_clipped == T.size
    assert np.all((r.control == 0.0) | (r.control == 1.0))


def test_models_without_inverse_say_so():
    with pytest.raises(InverseError, match="no inverse"):
        inverse_control(get_model("bouc_wen_modified"), REC, np.zeros(T.size), {})
    with pytest.raises(InverseError, match="does not depend on the control"):
        inverse_control(get_model("lugre"), REC, np.zeros(T.size), {})
