"""Fluid and field law: tau_y = tau_ref (E/E_ref)^n (Butz and von Stryk 2002), field-dependent viscosity (Makris),
controls."""

import numpy as np
import pytest

from erdesign import Fluid
from erdesign.errors import UnitError


def makris_fluid(**kw):
    args = dict(
        viscosity="7 Pa*s",
        yield_stress="1.8 kPa",
        reference_field="3 kV/mm",
        yield_exponent=2.0,
        density="1290 kg/m^3",
        viscosity_at_reference_field="13 Pa*s",
    )
    args.update(kw)
    return Fluid.create(**args)


def test_power_law_and_viscosity_end_points():
    f = makris_fluid()
    E = np.array([0.0, 1.5e6, 3e6, -3e6])
    # Makris: 1.8 kPa and 13 Pa s at 3 kV/mm, 7 Pa s at 0; the law is even in the field.
    np.testing.assert_allclose(f.yield_stress_at(E), [0.0, 450.0, 1800.0, 1800.0])
    np.testing.assert_allclose(f.viscosity_at(E), [7.0, 8.5, 13.0, 13.0])


@pytest.mark.parametrize("n", [1.2, 1.5, 2.5])
def test_exponent_range_of_seed_001(n):
    # Butz and von Stryk (2002), section 2: n from 1.2 to 2.5. Doubling the field multiplies tau_y by 2^n.
    f = makris_fluid(yield_exponent=n)
    assert f.yield_stress_at(6e6) / f.yield_stress_at(3e6) == pytest.approx(2**n)


@pytest.mark.parametrize(
    "reference, kind, si",
    [
        ("3 kV/mm", "electric field", 3e6),
        ("200 kA/m", "magnetic field", 2e5),
        ("0.8 T", "magnetic flux density", 0.8),
        ("1 A", "current", 1.0),
        ("5 V", "voltage", 5.0),
    ],
)
def test_kinds_of_control(reference, kind, si):
    f = makris_fluid(reference_field=reference)
    assert f.control == kind and f.reference_field == pytest.approx(si)
    assert f.field_si(reference) == pytest.approx(si)


def test_control_of_the_wrong_kind_is_refused_by_name():
    f = makris_fluid(reference_field="200 kA/m")
    with pytest.raises(UnitError, match="field: expected a magnetic field strength .* got '3 kV/mm'"):
        f.field_si("3 kV/mm")
    with pytest.raises(UnitError, match="fluid.reference_field: expected an electric field"):
        makris_fluid(reference_field="3 mm")


@pytest.mark.parametrize(
    "key, value, message",
    [
        ("viscosity", "-7 Pa*s", "fluid.viscosity: must be positive"),
        ("yield_stress", "-1 kPa", "fluid.yield_stress: must not be negative"),
        ("yield_exponent", 0.0, "fluid.yield_exponent: must lie in"),
        ("density", "0 kg/m^3", "fluid.density: must be positive"),
        ("reference_field", "0 kV/mm", "fluid.reference_field: must be positive"),
    ],
)
def test_bad_values_name_the_key(key, value, message):
    with pytest.raises(UnitError, match=message):
        makris_fluid(**{key: value})
