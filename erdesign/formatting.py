"""The one unit-formatting helper: every number a report, a figure or the app prints goes through :func:`show`.

Neutral ground for the report (:mod:`erdesign.report`), the figures (:mod:`erdesign.report.plots`) and the app, none of
which depends on another for it; :mod:`erdesign.report.formatting` re-exports it under its former name.

:func:`show` takes a pint quantity (or a plain number for a dimensionless value) and the unit to show it in, and
converts with pint, so a quantity of the wrong dimension is a :class:`~erdesign.errors.UnitError` that names the
entry, never a silently wrong number.  It rounds to :data:`SIGNIFICANT_DIGITS` significant figures (the same for
every quantity of a report) and keeps the SI magnitude beside the text so the HTML carries both.

:func:`pick_unit` chooses, once per table column or figure axis, the unit from a short list that keeps the
largest magnitude between 1 and 1000, so that a column reads in one unit.
"""

from __future__ import annotations

import contextlib
import contextvars
import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ._pint import pint  # not `import pint`: erdesign/_pint.py
from .errors import UnitError
from .units import Q_, dimension_name, ureg

__all__ = [
    "Shown",
    "show",
    "shown_list",
    "pick_unit",
    "round_significant",
    "SIGNIFICANT_DIGITS",
    "UNIT_CHOICES",
    "UNIT_SYSTEMS",
    "unit_system",
    "use_unit_system",
    "field_text",
    "kind_of",
    "show_in_system",
    "CONTROL_LABELS",
    "control_label",
    "esr_shown",
    "SI_UNITS",
    "si_unit_text",
]

#: Significant figures of every quantity a report prints.
SIGNIFICANT_DIGITS = 4

#: Display units to choose from, by dimension (smallest first), for :func:`pick_unit`.
UNIT_CHOICES: dict[str, tuple[str, ...]] = {
    "force": ("mN", "N", "kN", "MN"),
    "pressure": ("Pa", "kPa", "MPa", "GPa"),
    "length": ("µm", "mm", "m"),
    "velocity": ("µm/s", "mm/s", "m/s"),
    "area": ("mm^2", "cm^2", "m^2"),
    "volume": ("mm^3", "cm^3", "L", "m^3"),
    "flow": ("mm^3/s", "mL/s", "L/s", "m^3/s"),
    "viscosity": ("mPa*s", "Pa*s", "kPa*s"),
    "damping": ("N*s/m", "kN*s/m", "MN*s/m"),
    "stiffness": ("N/m", "kN/m", "MN/m"),
    "energy": ("mJ", "J", "kJ", "MJ"),
    "frequency": ("Hz", "kHz"),
    "electric field": ("V/mm", "kV/mm"),
    "magnetic field": ("A/m", "kA/m", "MA/m"),
    "density": ("kg/m^3",),
    "mass": ("g", "kg", "t"),
    "time": ("µs", "ms", "s"),
}

#: Unit systems for displayed numbers: name -> the units of each kind that differ from :data:`UNIT_CHOICES`.
#: ``"SI"`` picks among SI multiples (:data:`UNIT_CHOICES`); the others fix one unit per kind, so that every
#: number of a kind reads in the same unit.  Controls (fields, currents, voltages) are never converted to a unit
#: system: they are shown in the unit of the fluid's control (kV/mm, kA/m, A, V).
UNIT_SYSTEMS: dict[str, dict[str, tuple[str, ...]]] = {
    "SI": {},
    "mm-kN-s": {
        "force": ("kN",),
        "pressure": ("MPa",),
        "length": ("mm",),
        "velocity": ("mm/s",),
        "area": ("mm^2",),
        "volume": ("mm^3",),
        "flow": ("mm^3/s",),
        "viscosity": ("Pa*s",),
        "damping": ("kN*s/mm",),
        "stiffness": ("kN/mm",),
        "energy": ("kN*mm",),
        "density": ("kg/m^3",),
        "mass": ("kg",),
        "time": ("s",),
    },
    "in-lbf-s": {
        "force": ("lbf",),
        "pressure": ("psi",),
        "length": ("in",),
        "velocity": ("in/s",),
        "area": ("in^2",),
        "volume": ("in^3",),
        "flow": ("in^3/s",),
        "viscosity": ("psi*s",),
        "damping": ("lbf*s/in",),
        "stiffness": ("lbf/in",),
        "energy": ("in*lbf",),
        "density": ("lb/in^3",),
        "mass": ("lb",),
        "time": ("s",),
    },
}

_SYSTEM: contextvars.ContextVar[str] = contextvars.ContextVar("erdesign_unit_system", default="SI")


def unit_system() -> str:
    """The unit system displayed numbers are shown in (:data:`UNIT_SYSTEMS`; ``"SI"`` unless changed)."""
    return _SYSTEM.get()


@contextlib.contextmanager
def use_unit_system(name: str) -> Iterator[str]:
    """Show numbers in the unit system ``name`` inside the ``with`` block (this thread or task only).

    >>> with use_unit_system("in-lbf-s"):
    ...     pick_unit(Q_(6070.0, "N"), "force"), pick_unit(Q_(3e6, "V/m"), "electric field")
    ('lbf', 'kV/mm')
    """
    if name not in UNIT_SYSTEMS:
        raise UnitError(f"unit system: expected one of {', '.join(UNIT_SYSTEMS)}, got {name!r}")
    token = _SYSTEM.set(name)
    try:
        yield name
    finally:
        _SYSTEM.reset(token)


#: What each kind of control (:data:`erdesign.fluid.CONTROL_UNITS`) is called on a label, and its symbol.
CONTROL_LABELS: dict[str, tuple[str, str]] = {
    "electric field": ("field", "E"),
    "magnetic field": ("field", "H"),
    "magnetic flux density": ("flux density", "B"),
    "current": ("coil current", "I"),
    "voltage": ("driver voltage", "U"),
}


def control_label(kind: str | None, prefix: str = "") -> str:
    """The label of a control of ``kind`` (a key of :data:`CONTROL_LABELS`), ``"design coil current I"``; a kind
    not known yet (an input being typed) reads ``"control"``.

    >>> control_label("current", "design"), control_label("electric field"), control_label(None, "design")
    ('design coil current I', 'field E', 'design control')
    """
    name, symbol = CONTROL_LABELS.get(kind or "", ("control", ""))
    return " ".join(part for part in (prefix, name, symbol) if part)


def field_text(value: float, control_unit: str, field_unit: str) -> str:
    """A control (SI magnitude in ``control_unit``) in the fluid's own unit, ``"3 kV/mm"``; never ``3e+06``.

    >>> field_text(3e6, "V/m", "kV/mm"), field_text(2.5e5, "A/m", "kA/m"), field_text(0.5, "A", "A")
    ('3 kV/mm', '250 kA/m', '0.5 A')
    """
    return show(Q_(value, control_unit), field_unit, name="control").text


def round_significant(x: float, digits: int = SIGNIFICANT_DIGITS) -> str:
    """``x`` as text with ``digits`` significant figures, in plain decimal notation where that stays short.

    >>> round_significant(120345.6), round_significant(0.0436611), round_significant(2.0), round_significant(3e-9)
    ('120300', '0.04366', '2', '3e-09')
    """
    if x == 0 or not math.isfinite(x):
        return f"{x:g}"
    exponent = math.floor(math.log10(abs(x)))
    rounded = float(f"{x:.{digits - 1}e}")
    if -5 <= exponent < 9:
        exponent = math.floor(math.log10(abs(rounded)))
        decimals = max(digits - 1 - exponent, 0)
        text = f"{rounded:.{decimals}f}"
        if "." in text:
            text = text.rstrip("0").rstrip(".")
        return text
    return f"{rounded:.{digits}g}"


@dataclass(frozen=True)
class Shown:
    """A quantity as a report prints it."""

    text: str
    """Number and unit, ``"120.3 kN·s/m"`` (the number alone for a dimensionless value)."""
    number: str
    """The rounded number, ``"120.3"``."""
    unit: str
    """The unit as printed, ``"kN·s/m"``; empty for a dimensionless value."""
    si: float
    """Magnitude in SI base units (for data attributes and tests)."""
    si_unit: str
    """The SI unit of :attr:`si`, ``"kilogram / second"``; ``"dimensionless"`` for a dimensionless value."""

    def __str__(self) -> str:
        return self.text


def show(value: Any, unit: str, *, name: str, digits: int = SIGNIFICANT_DIGITS) -> Shown:
    """A scalar quantity, converted to ``unit`` and rounded: the only way a report prints a number.

    Parameters
    ----------
    value : pint.Quantity or float
        The quantity.  A plain number is accepted only when ``unit`` is dimensionless (``""``), because a number
        without its unit cannot be checked.
    unit : str
        Unit to show it in (``"kN"``, ``"kV/mm"``, ``""`` for a ratio).
    name : str
        What the quantity is, for the error message.
    digits : int
        Significant figures.

    Raises
    ------
    UnitError
        The quantity's dimension is not the unit's, or a plain number was given for a dimensional unit.

    Examples
    --------
    >>> show(Q_(120345.6, "N*s/m"), "kN*s/m", name="C").text
    '120.3 kN·s/m'
    >>> show(Q_(3, "kg"), "kN", name="force")
    Traceback (most recent call last):
    ...
    erdesign.errors.UnitError: report: force: cannot show 3 kg (a mass) in kN (a force)
    """
    target = ureg.Unit(unit) if unit else ureg.dimensionless
    if isinstance(value, pint.Quantity):
        q = value
    elif isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool):
        if not target.dimensionless:
            raise UnitError(
                f"report: {name}: the number {value!r} has no unit; expected "
                f"{dimension_name(target.dimensionality)} in {unit}"
            )
        q = Q_(float(value), "")
    else:
        raise UnitError(f"report: {name}: expected a quantity, got {value!r}")
    if np.ndim(q.magnitude) != 0:
        raise UnitError(f"report: {name}: expected one value, got an array")
    if q.dimensionality != target.dimensionality:
        raise UnitError(
            f"report: {name}: cannot show {q:~P} ({dimension_name(q.dimensionality)}) in "
            f"{unit or 'no unit'} ({dimension_name(target.dimensionality)})"
        )
    magnitude = float(q.to(target).magnitude)
    number = round_significant(magnitude, digits) if math.isfinite(magnitude) else "undefined"
    unit_text = f"{target:~P}" if unit and not _is_plain_ratio(target) else ""
    si = q.to_base_units()
    si_unit = "dimensionless" if target.dimensionless else f"{si.units}"
    text = f"{number} {unit_text}".strip() if math.isfinite(magnitude) else number
    return Shown(text=text, number=number, unit=unit_text, si=float(si.magnitude), si_unit=si_unit)


def esr_shown(x: float, *, name: str = "ESR") -> Shown:
    """An ESR (Vivas-López et al., eq 7) or a noise floor as the diagnosis' verdict states it, to 3 significant
    figures in ``%.3g`` form: the app's metrics, the report and the verdict's sentence print the same text.

    >>> esr_shown(0.0023797).text, esr_shown(2.7114e-05).text
    ('0.00238', '2.71e-05')
    """
    x = float(x)
    if not math.isfinite(x):
        raise UnitError(f"report: {name}: expected a finite number, got {x!r}")
    return Shown(text=f"{x:.3g}", number=f"{x:.3g}", unit="", si=x, si_unit="dimensionless")


def _is_plain_ratio(unit: pint.Unit) -> bool:
    return unit.dimensionless and str(unit) in ("dimensionless", "")


def pick_unit(values: Any, kind: str) -> str:
    """The unit of ``UNIT_CHOICES[kind]`` in which the largest |value| lies in [1, 1000) (else the nearest end).

    ``values`` is a quantity (scalar or array).  In a unit system other than SI (:func:`use_unit_system`) the
    choices are that system's.

    >>> pick_unit(Q_([120.0, 6070.0], "N"), "force"), pick_unit(Q_(3e6, "V/m"), "electric field")
    ('kN', 'kV/mm')
    """
    choices = UNIT_SYSTEMS[_SYSTEM.get()].get(kind) or UNIT_CHOICES[kind]
    mags = np.abs(np.asarray(values.to(choices[0]).magnitude, dtype=float))
    biggest = float(np.nanmax(mags)) if mags.size and np.any(np.isfinite(mags)) else 0.0
    if biggest == 0.0:
        return choices[min(1, len(choices) - 1)]
    best = choices[0]
    for unit in choices:
        if float(Q_(biggest, choices[0]).to(unit).magnitude) >= 1.0:
            best = unit
    return best


#: Kinds that are controls: shown in the fluid's own unit (kV/mm, kA/m), never converted to a unit system.
_CONTROL_KINDS = ("electric field", "magnetic field")


def kind_of(unit: str) -> str | None:
    """The kind of :data:`UNIT_CHOICES` whose dimension is ``unit``'s (controls and plain numbers excepted), or None.

    >>> kind_of("N*s/m"), kind_of("lbf"), kind_of("N/m"), kind_of("1/m"), kind_of("")
    ('damping', 'force', 'stiffness', None, None)
    """
    if not unit:
        return None
    dimensionality = ureg.Unit(unit).dimensionality
    for kind, choices in UNIT_CHOICES.items():
        if kind not in _CONTROL_KINDS and ureg.Unit(choices[0]).dimensionality == dimensionality:
            return kind
    return None


#: The coherent SI unit of each kind of :data:`UNIT_CHOICES` (CSV headers: numbers in SI, ``force [N]``).
SI_UNITS: dict[str, str] = {
    "force": "N",
    "pressure": "Pa",
    "length": "m",
    "velocity": "m/s",
    "area": "m^2",
    "volume": "m^3",
    "flow": "m^3/s",
    "viscosity": "Pa*s",
    "damping": "N*s/m",
    "stiffness": "N/m",
    "energy": "J",
    "frequency": "Hz",
    "electric field": "V/m",
    "magnetic field": "A/m",
    "density": "kg/m^3",
    "mass": "kg",
    "time": "s",
}


def si_unit_text(unit: str) -> str:
    """The SI unit of ``unit``'s dimension as a CSV header writes it: ``N`` for ``kilogram * meter / second ** 2``,
    ``V/m`` for ``kV/mm``, ``1`` for a ratio; other dimensions in pint's short form of the base units.

    >>> si_unit_text("kilogram * meter / second ** 2"), si_unit_text("kV/mm"), si_unit_text(""), si_unit_text("A")
    ('N', 'V/m', '1', 'A')
    """
    if unit in ("", "dimensionless"):
        return "1"
    dimensionality = ureg.Unit(unit).dimensionality
    for si in SI_UNITS.values():
        if ureg.Unit(si).dimensionality == dimensionality:
            return si
    return f"{Q_(1.0, unit).to_base_units().units:~C}"


def show_in_system(value: Any, *, name: str, digits: int = SIGNIFICANT_DIGITS, like: Any = None) -> Shown:
    """A scalar quantity in the unit the current unit system (:func:`use_unit_system`) gives its kind.

    The unit is :func:`pick_unit` of ``like`` (a quantity of the same dimension: the value an uncertainty belongs
    to, so that both read in one unit) or of the value itself.  A quantity of no known kind (``1/m``) and a plain
    number are shown as they are; controls should be shown with :func:`field_text` instead.

    >>> with use_unit_system("in-lbf-s"):
    ...     show_in_system(Q_(5000.0, "N*s/m"), name="c").text, show_in_system(Q_(400.0, "N"), name="F").text
    ('28.55 lbf·s/in', '89.92 lbf')
    >>> show_in_system(Q_(30, "N"), name="se", like=Q_(4000, "N")).text, show_in_system(1.2, name="factor").text
    ('0.03 kN', '1.2')
    """
    if not isinstance(value, pint.Quantity):
        return show(value, "", name=name, digits=digits)
    kind = kind_of(f"{value.units}")
    if kind is None:
        unit = "" if value.dimensionless else f"{value.units}"
        return show(value.to(unit) if not unit else value, unit, name=name, digits=digits)
    reference = like if isinstance(like, pint.Quantity) else value
    return show(value, pick_unit(abs(reference), kind), name=name, digits=digits)


def shown_list(values: Sequence[Any], unit: str, *, name: str) -> list[Shown]:
    """:func:`show` applied to each element of a quantity array or sequence."""
    return [show(v, unit, name=f"{name}[{i}]") for i, v in enumerate(values)]
