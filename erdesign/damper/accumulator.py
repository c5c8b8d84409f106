r"""Gas accumulator of a single-ended damper: the preload and stiffness it puts on the rod.

A damper whose rod leaves the cylinder on one side only (most commercial MR dampers: monotube, floating piston,
gas behind it on the head side) must make room for the rod volume that enters the cylinder.  A gas volume
:math:`V_0` charged to :math:`p_0` does it; the gas pressure acts on the rod's cross-section :math:`A_r` and gives

.. math::
    F_g = p\,A_r, \qquad p\,V^{n} = p_0 V_0^{n}, \qquad V = V_0 - A_r x

(x: rod travel into the cylinder from the reference position where the gas holds :math:`p_0` and :math:`V_0`).
Linearised about that position (the mid-stroke of a test):

.. math::
    f_0 = p_0 A_r, \qquad k = \left.\frac{dF_g}{dx}\right|_0 = \frac{n\,p_0 A_r^2}{V_0}

the preload :math:`f_0` and the stiffness :math:`k` of the gas spring effect
(:mod:`erdesign.effects.gas_spring`; the f_0 and k terms of the MR-model review, its eqs 2 and 23, and k_1 of
Spencer et al. 1997's modified Bouc-Wen model).  The flow through the gap is still :math:`v A_p` with
:math:`A_p = \pi (D_p^2 - d_r^2)/4` and the pressure force :math:`\Delta p\,A_p` (the chamber on the rod side
has the annular area; the gas takes the rod volume), so the quasi-steady force of a single-ended damper with the
accumulator on the head side is that of the double-ended one plus :math:`F_g`.

The polytropic index n is 1 for an isothermal gas (slow strokes: the gas keeps the temperature of the body) and
1.4 for adiabatic nitrogen (strokes faster than the gas exchanges heat, a second or so in a small accumulator);
erdesign takes :data:`DEFAULT_POLYTROPIC_INDEX` = 1.4 because dynamic tests (Hz) are closer to adiabatic.

Example
-------
>>> acc = Accumulator(precharge=1.0e6, gas_volume=20e-6)
>>> round(acc.preload(0.010), 1), round(acc.stiffness(0.010), 1)      # 1 MPa on a 10 mm rod, 20 cm^3 of gas
(78.5, 431.8)
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Any

from ..errors import DamperFileError, PlausibilityWarning
from ..schema import Number, Table, field, quantity, validate
from ..units import to_si

__all__ = [
    "Accumulator",
    "accumulator_from_table",
    "accumulator_table",
    "accumulator_preload",
    "accumulator_stiffness",
    "AccumulatorTable",
    "ACCUMULATOR_KEYS",
    "DEFAULT_POLYTROPIC_INDEX",
    "ROD_KINDS",
    "PLAUSIBLE_PRECHARGE",
    "PLAUSIBLE_GAS_VOLUME",
    "POSSIBLE_PRECHARGE",
    "POSSIBLE_GAS_VOLUME",
]

#: Values of ``[geometry] rod``: a rod on both sides of the piston (the default) or on one side only.
ROD_KINDS = ("double", "single")
#: Polytropic index taken when the file gives none: adiabatic nitrogen (dynamic tests at Hz rates).
DEFAULT_POLYTROPIC_INDEX = 1.4


class AccumulatorTable(Table):
    """``[accumulator]`` of a damper file with a single-ended rod."""

    precharge: quantity("Pa", "positive") = field("p_0, gas pressure with the rod at mid-stroke")
    gas_volume: quantity("m^3", "positive") = field("V_0, gas volume with the rod at mid-stroke")
    polytropic_index: Number = field(
        "n of p V^n = const (1 isothermal, 1.4 adiabatic air or nitrogen)", default=DEFAULT_POLYTROPIC_INDEX
    )


#: Keys of the damper file's ``[accumulator]`` table (docs/file_formats.md).
ACCUMULATOR_KEYS = tuple(AccumulatorTable.model_fields)

#: Plausible charge pressure [Pa]: small dampers are charged to 0.3-3 MPa, seismic ones to a few MPa; outside
#: 0.1-10 MPa a unit mistake ("bar" for "MPa") is likely and erdesign warns.
PLAUSIBLE_PRECHARGE = (1.0e5, 1.0e7)
#: Plausible gas volume [m^3]: 1 cm^3 to 10 litres.
PLAUSIBLE_GAS_VOLUME = (1.0e-6, 1.0e-2)
#: Possible charge pressure [Pa] and gas volume [m^3]: beyond them the value is refused, not warned (a gas at
#: 1e30 Pa or in 1e-30 m^3 is a unit mistake or a typo, and its spring would swamp every force of the record).
POSSIBLE_PRECHARGE = (1.0e2, 1.0e9)
POSSIBLE_GAS_VOLUME = (1.0e-9, 1.0)
#: Possible polytropic index: isothermal (1) to adiabatic monatomic gas (5/3).
POLYTROPIC_RANGE = (1.0, 5.0 / 3.0)


def accumulator_preload(precharge, rod_area):
    r"""Static force of the charged gas on the rod, :math:`f_0 = p_0 A_r`.

    Parameters
    ----------
    precharge : float
        p_0, gas pressure at the reference position, [Pa].
    rod_area : float
        A_r, cross-section of the rod, [m^2].

    Returns
    -------
    float
        f_0, [N].

    Examples
    --------
    >>> accumulator_preload(2.0e6, 1.0e-4)
    200.0

    References
    ----------
    The MR-model review, eq 2 (the offset f_0 of an accumulator).
    """
    return precharge * rod_area


def accumulator_stiffness(precharge, gas_volume, rod_area, polytropic_index=DEFAULT_POLYTROPIC_INDEX):
    r"""Stiffness of the gas spring on the rod, linearised at the reference position.

    .. math:: k = \frac{n\,p_0 A_r^2}{V_0}

    from :math:`p V^n = p_0 V_0^n` with :math:`V = V_0 - A_r x` and :math:`F = p A_r`.

    Parameters
    ----------
    precharge : float
        p_0, [Pa].
    gas_volume : float
        V_0, gas volume at the reference position, [m^3].
    rod_area : float
        A_r, [m^2].
    polytropic_index : float
        n, [-] (1 isothermal, 1.4 adiabatic nitrogen).

    Returns
    -------
    float
        k, [N/m].

    Examples
    --------
    >>> round(accumulator_stiffness(2.0e6, 20e-6, 1.0e-4, 1.0), 6)     # 2 MPa, 1 cm^2 rod, 20 cm^3, isothermal
    1000.0

    References
    ----------
    The MR-model review, eq 23 (the accumulator stiffness k); Spencer et al. (1997), k_1 of the modified Bouc-Wen
    model.
    """
    return polytropic_index * precharge * rod_area**2 / gas_volume


@dataclass(frozen=True)
class Accumulator:
    """Gas accumulator of a single-ended damper (SI floats; the ``[accumulator]`` table of a damper file).

    Attributes
    ----------
    precharge : float
        p_0, gas pressure at the reference position (mid-stroke of the test, x = 0), [Pa].
    gas_volume : float
        V_0, gas volume at the reference position, [m^3].
    polytropic_index : float
        n, [-].
    """

    precharge: float
    gas_volume: float
    polytropic_index: float = DEFAULT_POLYTROPIC_INDEX

    def __post_init__(self) -> None:
        for key in ("precharge", "gas_volume", "polytropic_index"):
            value = getattr(self, key)
            if (
                isinstance(value, bool)
                or not isinstance(value, (int, float))
                or not math.isfinite(value)
                or not value > 0
            ):
                raise DamperFileError(f"accumulator.{key}: must be a positive finite number, got {value!r}")
            object.__setattr__(self, key, float(value))
        for key, (lo, hi), unit, scale in (
            ("precharge", POSSIBLE_PRECHARGE, "MPa", 1e-6),
            ("gas_volume", POSSIBLE_GAS_VOLUME, "cm^3", 1e6),
        ):
            value = getattr(self, key)
            if not lo <= value <= hi:
                raise DamperFileError(
                    f"accumulator.{key}: {value * scale:.4g} {unit} is outside the possible range {lo * scale:g} to "
                    f"{hi * scale:g} {unit} of a damper's accumulator (a unit mistake?)"
                )
        lo, hi = POLYTROPIC_RANGE
        if not lo <= self.polytropic_index <= hi:
            raise DamperFileError(
                f"accumulator.polytropic_index: must lie between {lo:g} (isothermal) and "
                f"{hi:.4g} (adiabatic monatomic gas), got {self.polytropic_index:g}"
            )

    @staticmethod
    def rod_area(rod_diameter: float) -> float:
        """A_r = pi d_r^2 / 4, [m^2] from the rod diameter [m]."""
        return math.pi / 4.0 * rod_diameter**2

    def preload(self, rod_diameter: float) -> float:
        """f_0 = p_0 A_r, [N], for a rod of diameter ``rod_diameter`` [m]."""
        return accumulator_preload(self.precharge, self.rod_area(rod_diameter))

    def stiffness(self, rod_diameter: float) -> float:
        """k = n p_0 A_r^2 / V_0, [N/m], for a rod of diameter ``rod_diameter`` [m]."""
        return accumulator_stiffness(
            self.precharge, self.gas_volume, self.rod_area(rod_diameter), self.polytropic_index
        )


def accumulator_from_table(table: Any, where: str = "accumulator") -> Accumulator:
    """An :class:`Accumulator` from a damper file's ``[accumulator]`` table (values with units as strings).

    Errors name the key (``accumulator.gas_volume: ...``); a charge pressure or gas volume outside the plausible
    ranges (:data:`PLAUSIBLE_PRECHARGE`, :data:`PLAUSIBLE_GAS_VOLUME`) warns with a
    :class:`~erdesign.errors.PlausibilityWarning`.
    """
    given = validate(AccumulatorTable, table, where, error=DamperFileError)
    p0 = to_si(given.precharge, "Pa", f"{where}.precharge")
    V0 = to_si(given.gas_volume, "m^3", f"{where}.gas_volume")
    n = given.polytropic_index
    acc = Accumulator(precharge=p0, gas_volume=V0, polytropic_index=float(n))
    for key, value, (lo, hi), unit, scale in (
        ("precharge", p0, PLAUSIBLE_PRECHARGE, "MPa", 1e-6),
        ("gas_volume", V0, PLAUSIBLE_GAS_VOLUME, "cm^3", 1e6),
    ):
        if not lo <= value <= hi:
            warnings.warn(
                f"{where}.{key}: {value * scale:.4g} {unit} is outside the plausible range "
                f"{lo * scale:g} to {hi * scale:g} {unit} of a damper's accumulator (a unit mistake?)",
                PlausibilityWarning,
                stacklevel=3,
            )
    return acc


def accumulator_table(acc: Accumulator) -> dict:
    """The ``[accumulator]`` table of a damper file for ``acc`` (values as strings with units; the inverse of
    :func:`accumulator_from_table`, for writing a damper file back)."""
    return {
        "precharge": f"{acc.precharge!r} Pa",
        "gas_volume": f"{acc.gas_volume!r} m^3",
        "polytropic_index": acc.polytropic_index,
    }
