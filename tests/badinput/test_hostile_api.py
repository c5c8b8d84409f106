"""Issue 27: the public API checks the shapes, types and dimensions of its arguments and names the one at fault
(never a raw numpy ValueError, a TypeError from pathlib, a stripped unit or a silent NaN); files a loader cannot
read safely (huge, binary, deeply nested) are refused in one line; implausible controls are warned."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import erdesign
from erdesign import Q_
from erdesign.data.measurement import Measurement
from erdesign.errors import ErdesignError, PlausibilityWarning, one_line

from .corpus import MAKRIS

MAKRIS_DAMPER = erdesign.load_example("makris")
DUCT = dict(Q="1 mL/s", tau_y="1.8 kPa", eta="13 Pa*s", L="54.6 mm", d="14.3 mm", h="0.8 mm")
T = np.linspace(0.0, 2.0, 401)
X = 0.01 * np.sin(2 * np.pi * T)


def _refused(call, *needles):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(ErdesignError) as info:
            call()
    message = str(info.value)
    for needle in needles:
        assert needle in message, (needle, message)
    assert message == one_line(message), message
    return message


API_CASES = [
    # (id, call, texts the message must hold)
    ("force_si shapes", lambda: MAKRIS_DAMPER.force_si(np.ones(3), np.ones(4)), ["v and field", "(3,)", "(4,)"]),
    ("force_si nan", lambda: MAKRIS_DAMPER.force_si([0.1, math.nan]), ["v: element 1 is nan"]),
    ("force_si inf field", lambda: MAKRIS_DAMPER.force_si(0.1, [0.0, math.inf]), ["field: element 1 is inf"]),
    ("force_si text", lambda: MAKRIS_DAMPER.force_si("fast"), ["v: expected a number", "'fast'"]),
    ("force_si None", lambda: MAKRIS_DAMPER.force_si(None), ["v: expected a number"]),
    ("force_si quantity", lambda: MAKRIS_DAMPER.force_si(Q_(25.0, "mm/s")), ["v: expected SI numbers", "mm/s"]),
    ("state shapes", lambda: MAKRIS_DAMPER.state(np.ones((2, 3)), np.ones(2)), ["v and field"]),
    ("force() shapes", lambda: MAKRIS_DAMPER.force(Q_(np.ones(3), "m/s"), Q_(np.ones(2), "kV/mm")), ["v and field"]),
    (
        "bingham_pressure_drop shapes",
        lambda: erdesign.bingham_pressure_drop(**{**DUCT, "Q": Q_(np.ones(3), "mL/s"), "tau_y": Q_(np.ones(4), "kPa")}),
        ["Q and tau_y", "(3,)", "(4,)"],
    ),
    (
        "bingham_pressure_drop 2-D against 1-D",
        lambda: erdesign.bingham_pressure_drop(**{**DUCT, "h": Q_(np.ones((2, 3)), "mm"), "L": Q_(np.ones(2), "m")}),
        ["L and h"],
    ),
    (
        "SI kernel shapes",
        lambda: erdesign.flow.bingham.bingham_pressure_drop(
            1e-6, np.ones(4) * 1e3, 1.0, 0.05, np.ones(3) * 0.014, 8e-4
        ),
        ["tau_y and d"],
    ),
    ("esr shapes", lambda: erdesign.esr(np.arange(3.0), np.arange(4.0)), ["F_measured and F_model", "3 and 4"]),
    ("esr nan", lambda: erdesign.esr([1.0, 2.0, math.nan], [1.0, 2.0, 3.0]), ["F_measured: element 2 is nan"]),
    ("esr nan model", lambda: erdesign.esr([1.0, 2.0, 3.0], [1.0, math.nan, 3.0]), ["F_model: element 1 is nan"]),
    ("esr text", lambda: erdesign.esr("abc", [1.0, 2.0, 3.0]), ["F_measured: expected a number"]),
    ("load_damper None", lambda: erdesign.load_damper(None), ["path: expected the name of a damper file", "None"]),
    ("load_damper number", lambda: erdesign.load_damper(3), ["path:", "int"]),
    ("load_damper bytes", lambda: erdesign.load_damper(b"makris.toml"), ["path:", "bytes"]),
    ("read_measurement None", lambda: erdesign.read_measurement(None), ["path: expected the name"]),
    (
        "from_arrays force as displacement",
        lambda: Measurement.from_arrays(T, Q_(X, "N")),
        ["displacement: expected a length", "a force"],
    ),
    ("from_arrays time in metres", lambda: Measurement.from_arrays(Q_(T, "m"), X), ["time: expected a time"]),
    (
        "from_arrays control of another kind",
        lambda: Measurement.from_arrays(T, X, control=Q_(3.0, "kA/m"), control_kind="electric field"),
        ["control: expected an electric field"],
    ),
    (
        "sine_response amplitude 0",
        lambda: MAKRIS_DAMPER.sine_response("0 mm", "1 Hz"),
        ["amplitude: must be positive, got '0 mm'"],
    ),
    (
        "sine_response frequency negative",
        lambda: MAKRIS_DAMPER.sine_response("10 mm", "\u22121 Hz"),
        ["frequency: must be positive"],
    ),
    ("size velocity en dash", lambda: MAKRIS_DAMPER.size(velocity="\u201325 mm/s"), ["velocity:", "en dash"]),
    ("size velocity decimal comma", lambda: MAKRIS_DAMPER.size(velocity="25,4 mm/s"), ["velocity:", "'25.4 mm/s'"]),
    (
        "Fluid digit separator",
        lambda: erdesign.Fluid.create(
            viscosity="7 Pa*s",
            yield_stress="1_800 Pa",
            reference_field="3 kV/mm",
            yield_exponent=2.0,
            density="1290 kg/m^3",
        ),
        ["fluid.yield_stress", "digit separator"],
    ),
]


@pytest.mark.parametrize("case", API_CASES, ids=[c[0] for c in API_CASES])
def test_api_names_the_argument(case):
    _, call, needles = case
    _refused(call, *needles)


def test_arguments_are_not_changed_by_a_refused_call():
    v = np.array([0.1, math.nan])
    before = v.copy()
    _refused(lambda: MAKRIS_DAMPER.force_si(v), "v:")
    np.testing.assert_array_equal(v, before)


def test_from_arrays_converts_quantities_instead_of_stripping_their_unit():
    """Quantities were stripped to their magnitude (a time in ms read as s); they are converted to SI."""
    m = Measurement.from_arrays(
        Q_(T * 1e3, "ms"),
        Q_(X * 1e3, "mm"),
        Q_(np.ones_like(T), "kN"),
        control=Q_(3.0, "kV/mm"),
        control_kind="electric field",
    )
    np.testing.assert_allclose(m.time, T, rtol=1e-12)
    np.testing.assert_allclose(m.displacement, X, rtol=1e-12)
    assert m.force[0] == pytest.approx(1000.0) and m.control[0] == pytest.approx(3e6)


def test_the_checked_functions_still_broadcast_what_numpy_broadcasts():
    """One velocity against many controls (and a column against a row) is a sweep, not an error."""
    F = MAKRIS_DAMPER.force_si(0.0254, np.array([0.0, 1.5e6, 3e6]))
    assert F.shape == (3,) and F[0] < F[1] < F[2]
    grid = MAKRIS_DAMPER.force_si(np.array([[0.01], [0.02]]), np.array([0.0, 3e6]))
    assert grid.shape == (2, 2)
    dp = erdesign.bingham_pressure_drop(**{**DUCT, "Q": Q_(np.array([1.0, 2.0]), "mL/s")})
    assert dp.shape == (2,) and dp[1] > dp[0]


# ------------------------------------------------------------------------------------------ loaders
def _damper_file(tmp_path, text, name="d.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


@pytest.mark.parametrize("depth", [500, 100_000])
def test_deeply_nested_toml_is_one_line(tmp_path, depth):
    """Deeply nested TOML ended in a RecursionError."""
    path = _damper_file(tmp_path, MAKRIS.replace("[fluid]", "[fluid]\nx = " + "[" * depth + "]" * depth, 1))
    _refused(lambda: erdesign.load_damper(path), str(path), "nested too deeply")


def test_a_huge_damper_file_is_refused_unread(tmp_path):
    path = _damper_file(tmp_path, MAKRIS + "\n# " + "x" * (2**20 + 10) + "\n")
    _refused(lambda: erdesign.load_damper(path), "larger than 1 MB")


@pytest.mark.parametrize("where", ["/dev/zero"])
def test_a_device_as_damper_file(where):
    _refused(lambda: erdesign.load_damper(where), where, "binary")


def test_a_number_of_200k_digits_is_invalid_toml_not_a_python_limit(tmp_path):
    """tomllib raised a bare ValueError (Python's 4300-digit limit of int()) for a gigantic integer."""
    path = _damper_file(tmp_path, MAKRIS.replace('name = "makris-1996"', "name = " + "3" * 200_000))
    message = _refused(lambda: erdesign.load_damper(path), str(path), "invalid TOML", "thousands of digits")
    assert "sys." not in message and len(message) < 200 + len(str(path))


# ------------------------------------------------------------------------------------------ controls
@pytest.mark.parametrize(
    "material, reference_field, said",
    [
        ("lord-versaflo-er100", "40 kA/m", "is a magnetic field, but material 'lord-versaflo-er100' is an ER fluid"),
        ("lord-versaflo-er100", "2 A", "is a current, but material 'lord-versaflo-er100' is an ER fluid"),
        ("lord-mrf-132dg", "3 kV/mm", "is an electric field, but material 'lord-mrf-132dg' is an MR fluid"),
    ],
)
def test_a_control_of_the_other_kind_of_fluid_is_warned(tmp_path, material, reference_field, said):
    text = MAKRIS.replace("[fluid]", f'[fluid]\nmaterial = "{material}"', 1).replace(
        'reference_field = "3 kV/mm"', f'reference_field = "{reference_field}"', 1
    )
    assert f'reference_field = "{reference_field}"' in text
    with pytest.warns(PlausibilityWarning, match="fluid.reference_field: .*" + said.replace("(", r"\(")):
        erdesign.load_damper(_damper_file(tmp_path, text))


@pytest.mark.parametrize(
    "material, reference_field",
    [("lord-versaflo-er100", "3 kV/mm"), ("lord-mrf-132dg", "100 kA/m"), ("lord-mrf-132dg", "1 A")],
)
def test_a_control_of_the_right_kind_is_silent(tmp_path, material, reference_field):
    text = MAKRIS.replace("[fluid]", f'[fluid]\nmaterial = "{material}"', 1).replace(
        'reference_field = "3 kV/mm"', f'reference_field = "{reference_field}"', 1
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        erdesign.load_damper(_damper_file(tmp_path, text))


def test_coil_currents_no_wire_carries_are_refused_and_hot_ones_warned():
    """`--current "1e6 A"` passed; the current density in the coil's wire (I / (pi d^2 / 4)) decides."""
    circuit = erdesign.magnetics.load_magnetic_circuit(erdesign.__path__[0] + "/examples/mr_coil.toml")
    area = math.pi * circuit.head.wire_diameter**2 / 4
    _refused(lambda: circuit.at("1e6 A"), "current:", f"{1e6 / area / 1e6:.4g} A/mm^2", "melts")
    hot = 40e6 * area  # 40 A/mm^2: beyond the 30 A/mm^2 of a coil
    with pytest.warns(PlausibilityWarning, match="overheats"):
        circuit.at(Q_(hot, "A"))
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        circuit.at("2 A")


# ------------------------------------------------------------------------------------------ gigantic and subnormal
def test_esr_of_gigantic_forces_is_the_same_as_of_small_ones():
    """Sums of squares of 1e200 N overflowed to a silent NaN; the ESR is scale-free (Vivas-Lopez et al., eq 7), so
    it is computed on scaled forces: the same number at any scale."""
    F = np.array([1.0, -1.0, 0.5, 0.0])
    M = np.array([0.9, -1.0, 0.5, 0.1])
    small = erdesign.esr(F, M)
    assert small == pytest.approx(0.02 / 2.1875)  # sum (F - M)^2 = 0.02; mean 0.125, sum (F - mean)^2 = 2.1875
    assert erdesign.esr(F * 1e200, M * 1e200) == pytest.approx(small, rel=1e-12)
    assert erdesign.esr(F * 1e-300, M * 1e-300) == pytest.approx(small, rel=1e-12)


@pytest.mark.parametrize(
    "call, said",
    [
        (lambda: Measurement.from_arrays(T * 1e-310, X), "time: a mean time step of"),
        (lambda: Measurement.from_arrays(T, X * 1e300), "displacement: 1e+298 m is beyond any damper record"),
        (lambda: Measurement.from_arrays(T, X, np.full_like(T, 1e300)), "force: 1e+300 N is beyond"),
    ],
)
def test_from_arrays_refuses_values_no_record_holds(call, said):
    """A subnormal time step ended in a LinAlgError (and LAPACK's messages on the terminal), a gigantic displacement
    in an OverflowError."""
    _refused(call, said)


def test_a_non_finite_result_of_a_unit_aware_function_is_warned():
    """A flow of 1e300 m^3/s or a gap of 1e-320 m gave an infinite pressure drop without a word.  (The text
    "1e-320 m" is now refused by the unit parser, test_hostile_round4.py: the quantity still reaches the kernel.)"""
    for change in ({"Q": "1e300 m^3/s"}, {"h": Q_(1e-320, "m")}):
        with pytest.warns(PlausibilityWarning, match="bingham_pressure_drop: the result is not finite"):
            dp = erdesign.bingham_pressure_drop(**{**DUCT, **change})
        assert not np.isfinite(dp.magnitude)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert np.isfinite(erdesign.bingham_pressure_drop(**DUCT).magnitude)
