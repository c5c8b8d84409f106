"""The unit edge: parsing, dimension errors that name the argument, the application registry."""

import pickle

import numpy as np
import pint
import pytest

import erdesign
from erdesign.errors import UnitError
from erdesign.units import Q_, to_si, unit_aware, ureg


def test_one_application_registry():
    # Quantities must mix with the user's own pint application registry and survive pickling (Streamlit caches).
    assert ureg is pint.get_application_registry()
    q = pickle.loads(pickle.dumps(Q_(0.8, "mm")))
    assert q + pint.get_application_registry().Quantity(1, "mm") == Q_(1.8, "mm")


@pytest.mark.parametrize(
    "value, unit, expected",
    [
        ("0.0315 in", "m", 0.0315 * 0.0254),
        ("3 kV/mm", "V/m", 3e6),
        ("40 kA/m", "A/m", 4e4),
        ("1 in/s", "m/s", 0.0254),
        ("25 lbf", "N", 25 * 4.4482216152605),
        ("0.001 psi*s", "Pa*s", 6.894757293168),
    ],
)
def test_to_si_converts(value, unit, expected):
    # Exact definitions: 1 in = 25.4 mm, 1 lbf = 4.4482216152605 N, 1 psi = 6894.757293168 Pa.
    assert to_si(value, unit, "x") == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize(
    "value, fragment",
    [
        ("3 kg", "gap: expected a length"),
        ("0.8", "gap: '0.8' is not"),
        (0.8, "gap: 0.8 has no unit"),
        ("0.8 mmm", "gap: unknown unit"),
        ("nan mm", "gap: value must be finite"),
        ("inf m", "gap: value must be finite"),
    ],
)
def test_to_si_errors_name_the_argument(value, fragment):
    with pytest.raises(UnitError) as err:
        to_si(value, "m", "gap")
    assert fragment.split(":")[0] in str(err.value)
    if value != "0.8":
        assert fragment in str(err.value)


def test_plain_string_number_for_a_length_is_rejected():
    # "0.8" parses to a dimensionless quantity: it must be refused for a length, naming the argument.
    with pytest.raises(UnitError, match="gap: expected a length"):
        to_si("0.8", "m", "gap")


def test_arrays_pass_through_vectorised():
    out = to_si(Q_(np.array([1.0, 2.0]), "mm"), "m", "gap")
    np.testing.assert_allclose(out, [1e-3, 2e-3])


def test_unit_aware_wrapper_names_argument_and_rejects_unknown_keywords():
    with pytest.raises(UnitError, match="^h: expected a length"):
        erdesign.slit_pressure_drop("1 mL/s", "7 Pa*s", "54.6 mm", "14.3 mm", h="0.8 kg")
    with pytest.raises(TypeError):
        erdesign.slit_pressure_drop("1 mL/s", "7 Pa*s", "54.6 mm", "14.3 mm", "0.8 mm", gap="1 mm")


def test_unit_aware_result_is_the_kernel_result_with_units():
    q = erdesign.slit_pressure_drop("1 mL/s", "7 Pa*s", "2.15 in", "0.563 in", "0.0315 in")
    si = erdesign.flow.slit_pressure_drop(1e-6, 7.0, 2.15 * 0.0254, 0.563 * 0.0254, 0.0315 * 0.0254)
    assert q.to("Pa").magnitude == pytest.approx(si, rel=1e-12)


def test_unit_aware_refuses_parameters_the_kernel_does_not_have():
    with pytest.raises(TypeError, match="no parameter named"):
        unit_aware("Pa", nonsense="m")(erdesign.flow.slit_pressure_drop)
