"""Effects carry their own composition: a new effect is a class plus one registration line (issue 13).

The toy effects below live in this file only; the force chain of erdesign.effects.chain is not touched to use them.
"""

import numpy as np
import pytest

from erdesign import load_example
from erdesign.data.measurement import Measurement
from erdesign.diagnosis.diagnose import calibrate
from erdesign.effects import (
    EFFECT_NAMES,
    EFFECTS,
    Effect,
    EffectError,
    parse_effect_names,
    register_effect,
    unregister_effect,
)
from erdesign.effects.base import STAGES
from erdesign.effects.chain import PhysicsDamper
from erdesign.parameters import Parameter


class ForceOffset(Effect):
    """A constant force on the rod (a load-cell zero error): the smallest additive effect."""

    name = "force_offset"
    title = "Force offset"
    mechanism = "a constant force added to the damper force"
    signature = "a constant residual"
    stage = "additive"

    def parameters(self, damper):
        return (Parameter("offset_force", "N", 0.0, -1e4, 1e4, "constant force on the rod"),)

    def additive_forces(self, record, sign, damper, values):
        return {"offset": np.full(len(record), values["offset_force"])}


class FieldGain(Effect):
    """The fluid sees a multiple of the control applied: the smallest state-stage effect."""

    name = "field_gain"
    title = "Field gain"
    mechanism = "the field in the gap is a multiple of the control applied"
    signature = "a residual proportional to the yield force"
    stage = "state"

    def parameters(self, damper):
        return (Parameter("field_gain", "", 1.0, 0.1, 10.0, "field seen over control applied"),)

    def fluid_control(self, t, control, values):
        return values["field_gain"] * control


@pytest.fixture
def toy_effects():
    added = [register_effect(ForceOffset()), register_effect(FieldGain())]
    yield added
    for effect in added:
        unregister_effect(effect.name)


def _record(damper, field_fraction=1.0):
    # a stroke whose field steps (0, full, 60 %), so the state stage and the yield force are both exercised
    t = np.linspace(0.0, 1.5, 751)
    w = 2 * np.pi * 2.0
    E = damper.fluid.reference_field * np.where(t < 0.5, 0.0, np.where(t < 1.0, field_fraction, 0.6 * field_fraction))
    return Measurement(
        t,
        0.005 * np.sin(w * t),
        None,
        0.005 * w * np.cos(w * t),
        -0.005 * w**2 * np.sin(w * t),
        E,
        damper.fluid.control,
        name="toy stroke",
    )


@pytest.mark.parametrize("example, others", [("makris", ["seal_friction"]), ("mr_mixed", ["compressibility"])])
def test_an_additive_toy_effect_adds_its_force_and_nothing_else(toy_effects, example, others):
    d = load_example(example)
    rec = _record(d)
    base = PhysicsDamper(d, others)
    toy = PhysicsDamper(d, [*others, "force_offset"])
    values = {**base.initial_guess(rec), "viscosity_factor": 1.3, "yield_stress_factor": 0.8}
    F0 = base.components(rec, values)
    F1 = toy.components(rec, {**values, "offset_force": 250.0})
    # the same chain plus one component: equal to round-off of the last addition (1e-12 of the force)
    np.testing.assert_allclose(F1["force"], F0["force"] + 250.0, rtol=0, atol=1e-12 * np.abs(F0["force"]).max())
    np.testing.assert_array_equal(F1["offset"], 250.0)
    for part in ("fluid", "friction", "inertia", "gas_spring", "yield_force"):
        np.testing.assert_array_equal(F1[part], F0[part])


def test_a_state_toy_effect_is_the_baseline_at_the_scaled_control(toy_effects):
    # the fluid seeing 1.5 x the control is the baseline driven by 1.5 x the control, sample for sample
    d = load_example("mr_valve")
    rec = _record(d, field_fraction=0.5)
    scaled = Measurement(
        rec.time,
        rec.displacement,
        None,
        rec.velocity,
        rec.acceleration,
        1.5 * rec.control,
        rec.control_kind,
        name="scaled",
    )
    expected = PhysicsDamper(d).components(scaled, {"viscosity_factor": 1.1, "yield_stress_factor": 0.9})
    got = PhysicsDamper(d, ["field_gain"]).components(
        rec, {"viscosity_factor": 1.1, "yield_stress_factor": 0.9, "field_gain": 1.5}
    )
    for part in ("force", "yield_force"):
        np.testing.assert_allclose(got[part], expected[part], rtol=1e-12)


def test_fit_recovers_the_offset_of_a_record_made_with_it(toy_effects):
    # round trip: simulate with known calibration and offset, fit, compare (noise-free data: the optimiser's
    # tolerance, well below 1e-6 of the force scale, is all that separates the fit from the truth)
    d = load_example("makris")
    rec = _record(d)
    truth = {"viscosity_factor": 1.2, "yield_stress_factor": 0.85, "offset_force": -180.0}
    model = PhysicsDamper(d, ["force_offset"])
    measured = Measurement(
        rec.time,
        rec.displacement,
        model.simulate(rec, truth),
        rec.velocity,
        rec.acceleration,
        rec.control,
        rec.control_kind,
        name="with offset",
    )
    res = calibrate(d, measured, ["force_offset"])
    assert res.values["offset_force"] == pytest.approx(-180.0, abs=1e-3)
    assert res.values["viscosity_factor"] == pytest.approx(1.2, rel=1e-6)
    assert res.values["yield_stress_factor"] == pytest.approx(0.85, rel=1e-6)


def test_registration_is_checked_and_leaves_the_contract_names(toy_effects):
    assert parse_effect_names("seal_friction,force_offset") == ("seal_friction", "force_offset")
    assert "force_offset" in EFFECTS and "force_offset" not in EFFECT_NAMES
    assert len(EFFECT_NAMES) == 9 and all(EFFECTS[n].stage in STAGES for n in EFFECT_NAMES)
    with pytest.raises(EffectError, match="'force_offset' is empty or already registered"):
        register_effect(ForceOffset())
    with pytest.raises(EffectError, match="stage must be one of state, constitutive, parallel"):
        register_effect(type("Nowhere", (ForceOffset,), {"name": "nowhere", "stage": "sideways"})())
    with pytest.raises(EffectError, match="seal_friction is one of the library's effects"):
        unregister_effect("seal_friction")


def test_two_effects_of_a_one_effect_stage_are_refused():
    bypass = register_effect(type("Bypass", (ForceOffset,), {"name": "second_bypass", "stage": "parallel"})())
    try:
        with pytest.raises(EffectError, match="leakage, second_bypass: .* one effect of the parallel stage"):
            PhysicsDamper(load_example("makris"), ["leakage", "second_bypass"])
    finally:
        unregister_effect(bypass.name)
    assert "second_bypass" not in EFFECTS
