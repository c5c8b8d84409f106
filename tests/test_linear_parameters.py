"""Every model's declaration of the parameters that enter its force linearly (``Model.linear_parameters``), which
variable projection in :func:`erdesign.identification.identify.identify` relies on, checked numerically: the force must
be exactly affine in them whatever the other parameters' values, and ``Model.linear_terms`` must give the same force."""

import numpy as np
import pytest

from erdesign.data.measurement import Measurement
from erdesign.models.registry import get_model, model_names


def _record():
    t = np.linspace(0.0, 2.0, 801)
    x = 0.01 * np.sin(2 * np.pi * t) + 0.004 * np.sin(2 * np.pi * 3.3 * t + 0.4)
    u = 1.0 + 0.8 * np.sin(2 * np.pi * 0.7 * t)
    return Measurement.from_arrays(t, x, control=u, control_kind="voltage", name="affinity probe")


MODELS = [n for n in model_names() if n != "physics"]


def test_models_that_declare_linear_parameters():
    """The declarations are where the derivations put them (a change here should be a deliberate one)."""
    declared = {n: get_model(n).linear_parameters for n in MODELS}
    assert declared["bingham"] == ("c0", "f_c", "f0", "f_c_u", "c0_u")
    assert declared["bouc_wen_modified"] == ("k1",)  # the rest enter the internal displacement's equation
    assert set(declared["bouc_wen"]) == {"c0a", "k0", "alpha_a", "c0b", "alpha_b"}  # not x0: k0 x0 is a product
    assert "sigma0" not in declared["lugre"] and "C" not in declared["maxwell"]
    assert sum(1 for v in declared.values() if v) >= 15


@pytest.mark.parametrize("name", MODELS)
def test_force_is_affine_in_the_declared_parameters(name):
    """F(a + b) - F(a) - F(b) + F(0) = 0 and F(2a) - 2 F(a) + F(0) = 0 in the linear parameters, at other
    parameters away from their defaults; rounding only (1e-9 of the force scale: the sums are of O(1) terms)."""
    model = get_model(name)
    rec = _record()
    linear = model.linear_parameters
    if not linear:
        pytest.skip(f"{name} declares no linear parameter")
    for k in linear:
        model.parameter(k)  # a declared name must be a parameter
    rng = np.random.default_rng(7)
    values = model.defaults()
    for p in model.parameters:  # move the nonlinear ones off their defaults, within their bounds
        if p.name not in linear and p.fitted and np.isfinite(p.lower) and np.isfinite(p.upper):
            values[p.name] = float(
                np.clip(
                    p.default * (1.0 + 0.2 * rng.uniform(-1, 1))
                    if p.default
                    else 0.1 * rng.uniform(0, 1) * min(p.upper, 1.0),
                    p.lower,
                    p.upper,
                )
            )
    values = model.check_values(values)

    def force(theta):
        return np.asarray(model.force(rec, {**values, **dict(zip(linear, theta))}), dtype=float)

    scale = np.array([max(abs(model.parameter(k).default), 1.0) for k in linear])
    a = scale * rng.normal(size=len(linear))
    b = scale * rng.normal(size=len(linear))
    F0, Fa, Fb, Fab, F2a = force(0 * a), force(a), force(b), force(a + b), force(2 * a)
    size = max(np.max(np.abs(F)) for F in (F0, Fa, Fb, Fab, F2a))
    assert np.max(np.abs(Fab - Fa - Fb + F0)) <= 1e-9 * size
    assert np.max(np.abs(F2a - 2 * Fa + F0)) <= 1e-9 * size
    # and linear_terms reproduces the force at a
    cols, rest = model.linear_terms(rec, {**values, **dict(zip(linear, a))})
    assert set(cols) == set(linear)
    rebuilt = rest + sum(a[j] * cols[k] for j, k in enumerate(linear))
    assert np.max(np.abs(rebuilt - Fa)) <= 1e-9 * size
