r"""Field laws from the ``[yield_curve]`` table of a material file (docs/materials.md)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from ...errors import ErdesignError, UnitError
from ...units import Q_, to_si
from .kernels import CARLSON_FIELD_COEFFICIENT, CARLSON_STRESS_COEFFICIENT, CARLSON_VOLUME_EXPONENT, control_unit_of
from .laws import FieldLaw, PowerLaw, SaturatingLaw, TabulatedLaw

__all__ = ["field_law_from_dict"]

_LAW_KEYS = {
    "power": ("yield_stress", "reference_field", "yield_exponent"),
    "saturating": ("saturation_stress", "saturation_field"),
    "carlson": ("volume_fraction", "carrier_factor"),
    "table": ("field", "yield_stress", "field_unit", "yield_stress_unit"),
}
_COMMON_KEYS = ("law", "fit_range", "control")


def _number(value: Any, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ErdesignError(f"{name}: expected a number, got {value!r}")
    return float(value)


def _column(values: Any, unit: str | None, si_unit: str, name: str) -> np.ndarray:
    """A list of strings with units (``["0 kA/m", ...]``), or of numbers with ``unit`` given, in SI."""
    if not isinstance(values, list) or not values:
        raise ErdesignError(f"{name}: expected a list of values")
    if unit is not None:
        return np.array(
            [to_si(Q_(_number(v, f"{name}[{i}]"), unit), si_unit, f"{name}[{i}]") for i, v in enumerate(values)]
        )
    return np.array([to_si(v, si_unit, f"{name}[{i}]") for i, v in enumerate(values)])


def field_law_from_dict(
    table: Mapping[str, Any], *, where: str = "yield_curve", control_unit: str | None = None
) -> FieldLaw:
    """A :class:`FieldLaw` from the ``[yield_curve]`` table of a material file (docs/materials.md).

    ``law`` selects the form; each form has its keys (values are strings with units, pint-parsed):

    * ``law = "power"``: ``yield_stress``, ``reference_field``, ``yield_exponent``;
    * ``law = "saturating"``: ``saturation_stress``, ``saturation_field``;
    * ``law = "carlson"``: ``volume_fraction`` and ``carrier_factor`` of :func:`carlson_yield_stress` (magnetic
      field in A/m);
    * ``law = "table"``: ``field`` and ``yield_stress`` lists, of strings with units, or of numbers with
      ``field_unit`` / ``yield_stress_unit``.

    ``fit_range`` (``["0 kA/m", "250 kA/m"]``) is the range of the material's power-law summary; it is read by
    :mod:`erdesign.materials`, not here.  Unknown keys are errors naming the key.  ``control_unit``, when given, is
    the SI unit the control must have (the material's reference field).

    >>> law = field_law_from_dict({"law": "carlson", "volume_fraction": 0.32, "carrier_factor": 1.0})
    >>> type(law).__name__, round(law.saturation_stress), round(law.saturation_field)
    ('SaturatingLaw', 47862, 157978)
    """
    if not isinstance(table, Mapping):
        raise ErdesignError(f"{where}: expected a table, got {table!r}")
    law = table.get("law")
    if law not in _LAW_KEYS:
        raise ErdesignError(f"{where}.law: expected one of {', '.join(map(repr, _LAW_KEYS))}, got {law!r}")
    allowed = _LAW_KEYS[law] + _COMMON_KEYS
    for key in table:
        if key not in allowed:
            raise ErdesignError(f"{where}.{key}: unknown key for law = {law!r}; allowed keys: {', '.join(allowed)}")
    missing = [k for k in _LAW_KEYS[law] if k not in table and not k.endswith("_unit") and k != "carrier_factor"]
    if missing:
        raise ErdesignError(f"{where}.{missing[0]}: missing (law = {law!r} needs {', '.join(_LAW_KEYS[law])})")

    try:
        return _BUILDERS[law](table, where, control_unit)
    except ErdesignError as exc:
        if str(exc).startswith(where):
            raise
        raise type(exc)(f"{where}: {exc}") from None


def _power(table: Mapping[str, Any], where: str, control_unit: str | None) -> FieldLaw:
    unit = _control_unit_checked(table["reference_field"], f"{where}.reference_field", control_unit)
    return PowerLaw(
        unit,
        yield_stress_ref=to_si(table["yield_stress"], "Pa", f"{where}.yield_stress"),
        reference_field=to_si(table["reference_field"], unit, f"{where}.reference_field"),
        exponent=_number(table["yield_exponent"], f"{where}.yield_exponent"),
    )


def _saturating(table: Mapping[str, Any], where: str, control_unit: str | None) -> FieldLaw:
    unit = _control_unit_checked(table["saturation_field"], f"{where}.saturation_field", control_unit)
    return SaturatingLaw(
        unit,
        saturation_stress=to_si(table["saturation_stress"], "Pa", f"{where}.saturation_stress"),
        saturation_field=to_si(table["saturation_field"], unit, f"{where}.saturation_field"),
    )


def _carlson(table: Mapping[str, Any], where: str, control_unit: str | None) -> FieldLaw:
    if control_unit not in (None, "A/m"):
        raise UnitError(
            f"{where}.law: Carlson's law takes a magnetic field in A/m, but the fluid's reference "
            f"field is in {control_unit}"
        )
    phi = _number(table["volume_fraction"], f"{where}.volume_fraction")
    factor = _number(table.get("carrier_factor", 1.0), f"{where}.carrier_factor")
    if not (0 < phi < 1 and factor > 0):
        raise ErdesignError(f"{where}: need 0 < volume_fraction < 1 and carrier_factor > 0")
    return SaturatingLaw(
        "A/m",
        saturation_stress=factor * CARLSON_STRESS_COEFFICIENT * phi**CARLSON_VOLUME_EXPONENT,
        saturation_field=1.0 / CARLSON_FIELD_COEFFICIENT,
    )


def _table(table: Mapping[str, Any], where: str, control_unit: str | None) -> FieldLaw:
    field_unit, stress_unit = table.get("field_unit"), table.get("yield_stress_unit")
    fields = table["field"]
    if not isinstance(fields, list) or not fields:
        raise ErdesignError(f"{where}.field: expected a list of values")
    first = Q_(_number(fields[0], f"{where}.field[0]"), field_unit) if field_unit else fields[0]
    unit = _control_unit_checked(first, f"{where}.field", control_unit)
    E = _column(fields, field_unit, unit, f"{where}.field")
    tau = _column(table["yield_stress"], stress_unit, "Pa", f"{where}.yield_stress")
    return TabulatedLaw(unit, fields=tuple(E.tolist()), stresses=tuple(tau.tolist()))


#: law name of a ``[yield_curve]`` table -> builder (table, where, control unit) -> FieldLaw.
_BUILDERS = {"power": _power, "saturating": _saturating, "carlson": _carlson, "table": _table}


def _control_unit_checked(value: Any, name: str, control_unit: str | None) -> str:
    """SI control unit of ``value``, checked against the fluid's ``control_unit`` when given."""
    unit = control_unit_of(value, name)
    if control_unit is not None and unit != control_unit:
        raise UnitError(
            f"{name}: the control of the yield curve ({unit}) is not of the kind of the fluid's "
            f"reference field ({control_unit})"
        )
    return unit
