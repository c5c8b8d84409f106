"""Current as the control of an MR damper with a ``[coil]``: the coil law (yield stress through the magnetic
circuit) seen by size, the physics model and the field_lag prior (issue 16)."""

import math
from importlib import resources

import numpy as np
import pytest

from erdesign.damper.files import damper_from_dict, load_example, read_toml
from erdesign.data.measurement import Measurement
from erdesign.effects import EFFECTS
from erdesign.effects.chain import PhysicsDamper
from erdesign.errors import DamperFileError
from erdesign.magnetics import load_magnetic_circuit
from erdesign.magnetics.coil import current_rise_time
from erdesign.magnetics.law import CoilLaw

MR_COIL = str(resources.files("erdesign.examples") / "mr_coil.toml")


@pytest.fixture(scope="module")
def damper():
    return load_example("mr_coil")


@pytest.fixture(scope="module")
def circuit():
    return load_magnetic_circuit(MR_COIL)


def twin_without_coil():
    """The same geometry and fluid, controlled by the gap field strength (A/m) through the fluid's own curve."""
    data = read_toml(MR_COIL)
    data.pop("coil")
    data["fluid"] = {"material": data["fluid"]["material"], "seal_friction": data["fluid"]["seal_friction"]}
    return damper_from_dict(data, source="twin")


def test_coil_law_is_the_circuit_at_any_current(damper, circuit):
    law = damper.fluid.yield_law
    assert isinstance(law, CoilLaw)
    I = np.concatenate([np.linspace(0.0, 6.0, 97) + 0.013, [1e-4, 7.5]])  # off the table's points, and above it
    st = circuit.state(I)
    # the gain H_g/I is interpolated on 601 currents: 3e-5 of the network's root (tolerance 1e-12) at worst
    np.testing.assert_allclose(law.gap_field(I), np.abs(st.gap_field), rtol=3e-5)
    np.testing.assert_allclose(law.yield_stress(I), st.yield_stress, rtol=3e-5)
    np.testing.assert_allclose(law.gap_flux_density(I), np.abs(st.gap_flux_density), rtol=3e-5)
    assert law.yield_stress(-2.0) == law.yield_stress(2.0)  # even in the current


def test_size_at_a_current_equals_size_at_the_circuits_gap_field(damper, circuit):
    twin = twin_without_coil()
    H = float(circuit.state(2.0).gap_field[0])  # 102 kA/m, B = 0.52 T in the fluid
    a = damper.size(velocity="0.1 m/s", field="2 A")
    b = twin.size(velocity="0.1 m/s", field=f"{H!r} A/m")
    assert a.yield_stress.m_as("Pa") == pytest.approx(float(circuit.state(2.0).yield_stress[0]), rel=2e-5)
    assert a.force.m_as("N") == pytest.approx(b.force.m_as("N"), rel=2e-5)
    assert a.zero_field_force.m_as("N") == pytest.approx(b.zero_field_force.m_as("N"), rel=1e-12)


def test_a_record_simulated_with_current_has_the_circuits_yield_stress(damper, circuit):
    t = np.linspace(0.0, 2.0, 2001)
    w = 2 * np.pi * 1.5
    I = 3.0 * t / t[-1]  # a current ramp 0 to 3 A, through the knee
    x, v, a = 0.01 * np.sin(w * t), 0.01 * w * np.cos(w * t), -0.01 * w**2 * np.sin(w * t)
    rec = Measurement(t, x, None, v, a, I, "current", name="ramp")
    model = PhysicsDamper(damper)
    parts = model.components(rec, model.initial_guess(rec) | {"viscosity_factor": 1.0, "yield_stress_factor": 1.0})
    st = circuit.state(I)
    # the yield force is tau_y times the head's shear and pressure areas: its ratio to the circuit's tau_y is one
    # constant of the geometry along the whole ramp
    ratio = parts["yield_force"][1:] / st.yield_stress[1:]
    np.testing.assert_allclose(ratio, ratio[0], rtol=3e-5)
    assert ratio[0] == pytest.approx(damper.yield_force_si(2.0) / float(st.yield_stress[I.searchsorted(2.0)]), rel=1e-3)
    # and the force is the twin's (controlled by the gap field) on the same motion
    twin = twin_without_coil()
    rec_H = Measurement(t, x, None, v, a, np.abs(st.gap_field), "magnetic field", name="ramp")
    F_twin = PhysicsDamper(twin).simulate(rec_H)
    np.testing.assert_allclose(model.simulate(rec), F_twin, rtol=3e-5, atol=1e-6 * np.abs(F_twin).max())


def test_field_lag_prior_is_the_coils_time_constant(damper, circuit):
    effect = EFFECTS["field_lag"]
    L_over_R = float(circuit.time_constant(2.0)[0])
    assert effect.prior(damper)["field_time_constant"] == pytest.approx(L_over_R, rel=1e-12)  # 46 ms
    assert effect.parameters(damper)[0].default == pytest.approx(L_over_R, rel=1e-12)
    assert effect.prior(load_example("makris")) == {}  # no coil, no prior
    assert effect.plausibility(damper, {"field_time_constant": 8 * L_over_R}) == "plausible"


def test_current_rise_time_closed_forms():
    # a driver at exactly the steady voltage I R is a first-order response: 63.2 % at L/R
    assert current_rise_time(0.1, 2.0, 1.5, 3.0) == pytest.approx(0.05, rel=1e-12)
    # forcing with 10 x the steady voltage: t = -(L/R) ln(1 - 0.0632) = 0.0653 L/R
    assert current_rise_time(0.1, 2.0, 1.5, 30.0) == pytest.approx(-0.05 * math.log(1 - 0.1 * (1 - math.exp(-1))))
    with pytest.raises(Exception, match="coil.supply_voltage"):
        current_rise_time(0.1, 2.0, 1.5, 1.0)


def test_field_lag_prior_with_a_driver(circuit):
    data = read_toml(MR_COIL)
    data["coil"]["supply_voltage"] = "24 V"
    d = damper_from_dict(data)
    L, R = float(circuit.inductance(2.0)[0]), circuit.resistance
    expected = -(L / R) * math.log(1 - (1 - math.exp(-1)) * 2.0 * R / 24.0)  # 6.9 ms against L/R = 46 ms
    assert EFFECTS["field_lag"].prior(d)["field_time_constant"] == pytest.approx(expected, rel=1e-12)
    data["coil"]["supply_voltage"] = "4 V"  # below I R = 5.3 V
    with pytest.raises(DamperFileError, match=r"^damper: coil.supply_voltage: 4 V cannot drive the rated current"):
        damper_from_dict(data)
    data["coil"]["supply_voltage"] = "-4 V"
    with pytest.raises(DamperFileError, match="coil.supply_voltage: must be a positive voltage"):
        damper_from_dict(data)
