"""Every registered model (the MR-model review's whole catalogue and the rest) through simulate, identify and,
where the model is invertible, the inverse (issue 25, done-when)."""

import warnings

import numpy as np
import pytest

from erdesign.data.measurement import Measurement
from erdesign.identification.fit import evaluate
from erdesign.identification.identify import identify
from erdesign.identification.inverse import InverseError, inverse_control
from erdesign.models.registry import describe_models, get_model, model_names

NAMES = [n for n in model_names() if n != "physics"]  # the physics damper needs a damper file (tests/test_physics.py)


def record_for(model, seed=0):
    """Two cycles at 1.5 Hz, a control that sweeps 0.2-0.8 when the model uses one, and the model's own force at
    its defaults with 1 % noise."""
    t = np.linspace(0, 2 / 1.5, 801)
    x = 0.01 * np.sin(2 * np.pi * 1.5 * t)
    u = 0.5 + 0.3 * np.sin(2 * np.pi * 0.4 * t) if model.uses_control else None
    rec = Measurement.from_arrays(t, x, control=u, control_kind="current" if model.uses_control else None)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # Kamath-Wereley's record-scale warning does not concern this record
        F = model.simulate(rec)
    rng = np.random.default_rng(seed)
    return rec.with_force(F + 0.01 * (np.std(F) + 1.0) * rng.standard_normal(t.size))


def test_every_model_says_whether_it_is_invertible():
    entries = {e["name"]: e for e in describe_models()}
    assert set(entries) == set(model_names())
    assert all(isinstance(e["invertible"], bool) for e in entries.values())
    # the six models the review marks invertible (Table 1) are
    for name in (
        "kwok_tanh",
        "magic_formula",
        "lugre_modified",
        "bouc_wen_normalized",
        "li_viscoelastic_plastic",
        "cheng_tanh",
    ):
        assert entries[name]["invertible"], name
    # passive models are not
    assert not entries["bingham_extended"]["invertible"] and not entries["bouc_wen_modified"]["invertible"]


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_simulate_identify_invert(name):
    model = get_model(name)
    rec = record_for(model)
    F = model.simulate(rec)
    assert np.all(np.isfinite(F))
    # identification from the model's own guess: never worse than that guess, finite, within bounds
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = identify(model, rec, starts=1, max_nfev=200)
        guess_esr = evaluate(
            r.model, rec, {**r.model.defaults(), **r.model.initial_guess(rec), **r.model.fixed_for(rec)}
        )
    assert np.isfinite(r.esr) and r.esr <= guess_esr * (1 + 1e-6) + 1e-12, (r.esr, guess_esr)
    for p in model.parameters:
        assert p.lower <= r.values[p.name] <= p.upper
    if model.invertible:
        vals = r.model.check_values(r.values)
        res = inverse_control(r.model, rec, r.force, vals, control_range=(0.0, 1.0))
        assert np.all(np.isfinite(res.control)) and np.all((res.control >= 0) & (res.control <= 1.0))
        assert np.all(np.isfinite(res.force))
        # the force the inverse asks for is reached wherever it is not reported out of reach
        ok = ~res.unreachable
        assert np.max(np.abs(res.force - r.force)[ok], initial=0.0) <= 1e-4 * (np.ptp(r.force) + 1.0)  # root tolerance
    elif model.uses_control:
        with pytest.raises(InverseError, match="no inverse"):
            inverse_control(model, rec, F, model.defaults())
