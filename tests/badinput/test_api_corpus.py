"""Issue 15: the Python API refuses what the files refuse, with an :class:`~erdesign.errors.ErdesignError` naming the
argument (never a bare ZeroDivisionError, TypeError or IsADirectoryError), and warns on implausible values."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import erdesign
from erdesign.data.measurement import Measurement, check_against_damper, read_measurement
from erdesign.errors import ErdesignError, PlausibilityWarning
from erdesign.fluid import Fluid
from erdesign.geometry import Geometry

from .corpus import MAKRIS_FLUID, MAKRIS_GEOMETRY

GEO = MAKRIS_GEOMETRY
FLUID = MAKRIS_FLUID
DUCT = ("1 mL/s", "1.8 kPa", "13 Pa*s", "54.6 mm", "14.3 mm", "0.8 mm")


def _duct(**change):
    names = ("Q", "tau_y", "eta", "L", "d", "h")
    args = dict(zip(names, DUCT))
    args.update(change)
    return lambda f: f(**args)


def _geometry(**change):
    return lambda: Geometry.create(**{**GEO, **change})


def _geometry_init(**change):
    return lambda: Geometry(**{**GEO, **change})


def _fluid(**change):
    return lambda: Fluid.create(**{**FLUID, **change})


def _size(**kwargs):
    return lambda: erdesign.load_example("makris").size(**kwargs)


API_CASES = [
    # flow functions of the top-level namespace (pint quantities or strings)
    *[
        (f"bingham_pressure_drop {k}={v}", lambda k=k, v=v: _duct(**{k: v})(erdesign.bingham_pressure_drop), k)
        for k, v in [
            ("h", "0 mm"),
            ("h", "-0.8 mm"),
            ("tau_y", "-1.8 kPa"),
            ("eta", "0 Pa*s"),
            ("eta", "-13 Pa*s"),
            ("L", "0 mm"),
            ("d", "-14.3 mm"),
            ("h", "abc"),
            ("h", "3 kg"),
            ("Q", "1 kg"),
            ("tau_y", "nan Pa"),
            ("h", 0.8),
        ]
    ],
    ("bingham_plug_fraction h=0", lambda: _duct(h="0 mm")(erdesign.bingham_plug_fraction), "h"),
    (
        "bingham_flow_rate eta=0",
        lambda: erdesign.bingham_flow_rate("1 MPa", "1.8 kPa", "0 Pa*s", "54.6 mm", "14.3 mm", "0.8 mm"),
        "eta",
    ),
    ("annulus_bingham_pressure_drop h=0", lambda: _duct(h="0 mm")(erdesign.annulus_bingham_pressure_drop), "h"),
    (
        "annulus_bingham_pressure_drop tau_y<0",
        lambda: _duct(tau_y="-1 kPa")(erdesign.annulus_bingham_pressure_drop),
        "tau_y",
    ),
    (
        "slit_pressure_drop eta<0",
        lambda: erdesign.slit_pressure_drop("1 mL/s", "-1 Pa*s", "50 mm", "14 mm", "1 mm"),
        "eta",
    ),
    ("yield_pressure_drop h=0", lambda: erdesign.yield_pressure_drop("1 kPa", "50 mm", "0 mm"), "h"),
    # Geometry, through create and through the constructor (strings are accepted by both)
    *[
        (f"Geometry.create {k}={v}", _geometry(**{k: v}), f"geometry.{k}")
        for k, v in [
            ("gap", "0 mm"),
            ("gap", "1e-300 m"),
            ("gap", "abc"),
            ("gap", "3 kg"),
            ("gap", 0.0008),
            ("duct_length", "1e300 m"),
            ("piston_diameter", "1e308 m"),
            ("rod_diameter", "-1 mm"),
            ("rod_diameter", "40 mm"),
            ("ducts", 0),
            ("ducts", 1.5),
            ("ducts", 10**12),
            ("configuration", "pump"),
        ]
    ],
    *[
        (f"Geometry() {k}={v!r}", _geometry_init(**{k: v}), f"geometry.{k}")
        for k, v in [
            ("gap", "0 mm"),
            ("gap", "abc"),
            ("gap", None),
            ("gap", float("nan")),
            ("gap", -1e-3),
            ("ducts", True),
        ]
    ],
    # Fluid
    *[
        (f"Fluid.create {k}={v!r}", _fluid(**{k: v}), f"fluid.{k}")
        for k, v in [
            ("viscosity", "0 Pa*s"),
            ("viscosity", "1e30 Pa*s"),
            ("yield_stress", "-1 kPa"),
            ("density", "1e30 kg/m^3"),
            ("reference_field", "abc"),
            ("reference_field", "1e9 kV/mm"),
            ("reference_field", "3 kg"),
            ("yield_exponent", -1.0),
            ("yield_exponent", "two"),
            ("yield_exponent", [1, 2]),
        ]
    ],
    # sizing
    ("size velocity text", _size(velocity="fast"), "velocity"),
    ("size velocity mass", _size(velocity="3 kg"), "velocity"),
    ("size field impossible", _size(velocity="1 in/s", field="1e9 kV/mm"), "field"),
    ("size field of another kind", _size(velocity="1 in/s", field="3 kA/m"), "field"),
    # measurements
    ("read_measurement folder", lambda: read_measurement(erdesign.__path__[0]), "folder"),
    ("read_measurement missing", lambda: read_measurement("no/such/file.csv"), "no such file"),
    (
        "from_arrays nan",
        lambda: Measurement.from_arrays([0, 1, 2, 3, 4], [0, 1, np.nan, 1, 0], [0] * 5),
        "displacement",
    ),
    ("from_arrays short", lambda: Measurement.from_arrays([0, 1, 2], [0, 1, 0], [0] * 3), "time"),
    ("from_arrays 2-D", lambda: Measurement.from_arrays(np.zeros((5, 2)), [0] * 5, [0] * 5), "time"),
    ("from_arrays lengths", lambda: Measurement.from_arrays([0, 1, 2, 3, 4], [0, 1, 0], [0] * 5), "displacement"),
    ("from_arrays time backwards", lambda: Measurement.from_arrays([0, 1, 3, 2, 4], [0, 1, 0, 1, 0], [0] * 5), "time"),
]


@pytest.mark.parametrize("case", API_CASES, ids=[c[0] for c in API_CASES])
def test_api_refuses_with_the_argument_named(case):
    _, call, field = case
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(ErdesignError) as info:
            call()
    message = str(info.value)
    assert field in message and "\n" not in message.strip(), message


def test_geometry_accepts_strings_in_the_constructor():
    """The issue's example: Geometry(gap="0.8 mm", ...) raised TypeError though strings are documented."""
    g = Geometry(**GEO)
    assert g == Geometry.create(**GEO) and g.gap == pytest.approx(8e-4)


@pytest.mark.parametrize(
    "change, field",
    [
        ({"gap": "0.02 mm"}, "geometry.gap"),
        ({"duct_length": "5 m"}, "geometry.duct_length"),
        ({"ducts": 100}, "geometry.ducts"),
    ],
)
def test_geometry_warns_outside_the_plausible_range(change, field):
    with pytest.warns(PlausibilityWarning, match=field):
        Geometry.create(**{**GEO, **change})


@pytest.mark.parametrize(
    "change, field",
    [
        ({"density": "20000 kg/m^3"}, "fluid.density"),
        ({"viscosity": "5000 Pa*s"}, "fluid.viscosity"),
        ({"reference_field": "50 kV/mm"}, "fluid.reference_field"),
    ],
)
def test_fluid_warns_outside_the_plausible_range(change, field):
    with pytest.warns(PlausibilityWarning, match=field):
        Fluid.create(**{**FLUID, **change})


def test_the_makris_example_raises_no_plausibility_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        damper = erdesign.load_example("makris")
        damper.size(velocity="1 in/s", field="3 kV/mm")
        record = read_measurement(erdesign.__path__[0] + "/examples/measurements/makris_hidden_seal_friction.csv")
        assert check_against_damper(record, damper) == []


@pytest.mark.parametrize("scale, text", [(1e3, "1000 too large"), (1e-3, "1000 too small")])
def test_a_factor_1000_in_force_is_named(scale, text):
    """Issue 15, 'Done when': a factor 1000 unit mistake in force gives a warning naming it (the example record of
    the Makris damper with its force scaled)."""
    damper = erdesign.load_example("makris")
    record = read_measurement(erdesign.__path__[0] + "/examples/measurements/makris_hidden_seal_friction.csv")
    wrong = record.with_force(record.force * scale)
    with pytest.warns(PlausibilityWarning, match=text):
        messages = check_against_damper(wrong, damper)
    assert len(messages) == 1 and "force" in messages[0]


def test_the_flow_functions_never_drop_a_negative_yield_stress():
    """The issue: a negative yield stress passed to the unit-aware API was silently dropped."""
    with pytest.raises(ErdesignError, match="tau_y"):
        erdesign.bingham_pressure_drop("1 mL/s", "-1.8 kPa", "13 Pa*s", "54.6 mm", "14.3 mm", "0.8 mm")
