r"""The coil of an MR piston head: the ``[coil]`` table of a damper file, the winding window and the copper.

The coil is wound on the steel core (diameter :math:`d_c`) between the two poles and fills the window up to the
outer radius of the head :math:`R_p`; its axial length is the head length less the two poles,
:math:`L_c = L - 2 L_p`.  Its resistance follows from the mean turn length (the circumference at the mean radius of
the window) and the copper's resistivity:

.. math:: R = \rho_\text{Cu}(T)\,\frac{N\,\pi(r_c + R_p)}{\pi d_w^2/4},\qquad
          \rho_\text{Cu}(T) = \rho_{20}\,[1 + \alpha_{20}(T - 20\,^\circ\mathrm{C})]

with the International Annealed Copper Standard :math:`\rho_{20} = 1/58` ohm mm^2/m = 1.7241e-8 ohm m and
:math:`\alpha_{20}` = 0.00393 1/K (US Bureau of Standards, Circular 31, Copper wire tables, 1914; the IEC standard of
resistance for copper, IEC 60028).  Magnet wire is commonly 97-101 % IACS; the enamel is not part of
``wire_diameter`` (the bare copper diameter) but takes room in the window: the copper fill factor
:math:`N\pi d_w^2/4 / ((R_p - r_c)L_c)` of a round-wire coil lies near 0.5-0.6 and cannot exceed
:math:`\pi/(2\sqrt3)` = 0.907 (hexagonal packing of bare wires).

Example
-------
>>> round(coil_resistance(turns=400, wire_diameter=0.5e-3, inner_radius=9e-3, outer_radius=20e-3), 3)   # ohm
3.2
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Any

from ..errors import DamperFileError, ErdesignError, PlausibilityWarning, ValidityWarning
from ..schema import Table, checked, field, validate
from ..units import to_si

__all__ = [
    "Coil",
    "CoilTable",
    "coil_from_table",
    "coil_resistance",
    "current_rise_time",
    "COIL_KEYS",
    "OPTIONAL_COIL_KEYS",
    "COPPER_RESISTIVITY_20C",
    "COPPER_TEMPERATURE_COEFFICIENT",
    "MAX_FILL_FACTOR",
]


#: Resistivity of annealed copper at 20 degC [ohm m]: 100 % IACS = 58 MS/m (Circular 31, 1914; IEC 60028).
COPPER_RESISTIVITY_20C = 1.0 / 58.0e6
#: Temperature coefficient of the resistance of annealed copper at 20 degC [1/K] (the same sources).
COPPER_TEMPERATURE_COEFFICIENT = 0.00393
#: Largest copper fill factor of a round-wire coil (hexagonal packing of bare wires), [-].
MAX_FILL_FACTOR = math.pi / (2.0 * math.sqrt(3.0))


def coil_resistance(turns, wire_diameter, inner_radius, outer_radius, temperature=20.0):
    r"""DC resistance of a coil filling the window between two radii.

    .. math:: R = \rho_{20}[1 + \alpha_{20}(T - 20)]\,\frac{N\pi(r_i + r_o)}{\pi d_w^2/4}

    Parameters
    ----------
    turns : float
        N, [-].
    wire_diameter : float
        Bare copper diameter d_w, [m].
    inner_radius, outer_radius : float
        Radii of the winding window r_i (the core) and r_o, [m].
    temperature : float
        Copper temperature, [degC].

    Returns
    -------
    float
        Resistance, [ohm].

    Notes
    -----
    The mean turn length is the circumference at the mean radius of the window, exact for a uniformly filled
    rectangular window.  Resistivity: 100 % IACS (US Bureau of Standards, Circular 31, 1914).

    Examples
    --------
    >>> round(coil_resistance(1, 1e-3, 0.5 / math.pi, 0.5 / math.pi), 6)   # 1 m of 1 mm wire: 21.95 mohm
    0.021952

    References
    ----------
    US Bureau of Standards, Copper wire tables, Circular 31 (1914): 0.15328 ohm (m, g) at 20 degC, 58 MS/m.
    """
    rho = COPPER_RESISTIVITY_20C * (1.0 + COPPER_TEMPERATURE_COEFFICIENT * (temperature - 20.0))
    return rho * turns * math.pi * (inner_radius + outer_radius) / (math.pi * wire_diameter**2 / 4.0)


def current_rise_time(inductance, resistance, current, supply_voltage=None, fraction=1.0 - math.exp(-1.0)):
    r"""Time for the coil current to rise from 0 to ``fraction`` of ``current`` after a step command, [s].

    A driver that applies its whole supply voltage :math:`V_s` until the commanded current is reached (a
    current-controlled amplifier at its voltage limit) drives the coil along
    :math:`i(t) = (V_s/R)(1 - e^{-tR/L})`, so the current reaches :math:`f I` at

    .. math:: t_f = -\frac{L}{R}\ln\left(1 - \frac{f I R}{V_s}\right).

    Without a driver (``supply_voltage`` None) the coil is driven by the voltage :math:`IR` of its steady state,
    a first-order response of time constant :math:`L/R`: with :math:`V_s = IR` and :math:`f = 1 - e^{-1}` the
    formula gives exactly :math:`t_f = L/R`.

    Parameters
    ----------
    inductance : float
        L, [H] (secant inductance at ``current``).
    resistance : float
        R, [ohm].
    current : float
        Commanded current I > 0, [A].
    supply_voltage : float or None
        V_s, [V]; must exceed f I R.
    fraction : float
        f, [-]; default 1 - 1/e = 0.632, the first-order time constant's point.

    Returns
    -------
    float
        t_f, [s].

    Examples
    --------
    >>> round(current_rise_time(0.12, 2.65, 2.0) * 1e3, 2)           # L/R in ms
    45.28
    >>> round(current_rise_time(0.12, 2.65, 2.0, 24.0) * 1e3, 2)     # a 24 V driver forcing it
    6.81

    References
    ----------
    Series RL circuit step response; Gavin, Hoagg and Dobossy (2001) minimise L/R for a fast damper.
    """
    tau = inductance / resistance
    V = current * resistance if supply_voltage is None else float(supply_voltage)
    x = fraction * current * resistance / V
    if not x < 1.0:
        raise ErdesignError(
            f"coil.supply_voltage: {V:.4g} V cannot drive {current:.4g} A through "
            f"{resistance:.4g} ohm (needs more than {fraction * current * resistance:.4g} V)"
        )
    return -tau * math.log1p(-x)


@dataclass(frozen=True)
class Coil:
    """The ``[coil]`` table of a damper file in SI units (lengths in m); ``steel`` names a steel of materials/."""

    turns: int
    wire_diameter: float
    core_diameter: float
    pole_length: float
    housing_outer_diameter: float
    steel: str = "steel-1018"
    supply_voltage: float | None = None
    """Voltage the driver can apply, [V] (optional)."""

    def as_table(self) -> dict[str, Any]:
        """The ``[coil]`` table of a damper file (strings with units)."""
        table = {
            "turns": self.turns,
            "wire_diameter": f"{self.wire_diameter * 1e3:.6g} mm",
            "core_diameter": f"{self.core_diameter * 1e3:.6g} mm",
            "pole_length": f"{self.pole_length * 1e3:.6g} mm",
            "housing_outer_diameter": f"{self.housing_outer_diameter * 1e3:.6g} mm",
            "steel": self.steel,
        }
        if self.supply_voltage is not None:
            table["supply_voltage"] = f"{self.supply_voltage:.6g} V"
        return table


def _turns(value: Any, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise DamperFileError(f"{name}: expected a positive whole number of turns, got {value!r}")
    if value > 20000:
        warnings.warn(
            f"{name}: {value} turns is implausibly many for a damper piston coil", ValidityWarning, stacklevel=2
        )
    return value


#: The supply voltages of damper coil drivers (V), from a 0.1 V bench supply to a 1 kV drive: beyond, a warning
#: (a unit mistake: "1e9 V"); a damper file's [coil] and a requirements file's [design.coil] share it.
PLAUSIBLE_SUPPLY_VOLTAGE = (0.1, 1e3, "the supply of any damper coil")


def _positive(unit: str, what: str, plausible: tuple[float, float, str] | None = None):
    """A check of a positive quantity; outside ``plausible`` (low, high, whose range it is; SI) a warning."""

    def check(value: Any, name: str) -> Any:
        si = to_si(value, unit, name)
        if not (isinstance(si, float) and si > 0 and math.isfinite(si)):
            raise DamperFileError(f"{name}: must be a positive {what}, got {value!r}")
        if plausible is not None and not plausible[0] <= si <= plausible[1]:
            warnings.warn(
                f"{name}: {si:.4g} {unit} is {'below' if si < plausible[0] else 'beyond'} {plausible[2]} "
                f"({plausible[0]:g} to {plausible[1]:g} {unit}); check the value and its unit",
                PlausibilityWarning,
                stacklevel=2,
            )
        return value

    return check


def _steel(value: Any, name: str) -> str:
    from .. import materials

    if not isinstance(value, str) or value not in materials.steel_names():
        raise DamperFileError(f"{name}: unknown steel {value!r}; known steels: {', '.join(materials.steel_names())}")
    return value


class CoilTable(Table):
    """``[coil]`` of a damper file: the coil of an MR damper's piston head."""

    turns: checked(_turns, "whole number >= 1") = field("turns of the coil")
    wire_diameter: checked(_positive("m", "length"), "length > 0, with a unit") = field(
        "copper wire diameter; the resistance follows from the mean turn length"
    )
    core_diameter: checked(_positive("m", "length"), "length > 0, with a unit") = field("steel core under the winding")
    pole_length: checked(_positive("m", "length"), "length > 0, with a unit") = field(
        "axial length of each of the two poles (the field acts over 2 x pole_length)"
    )
    housing_outer_diameter: checked(_positive("m", "length"), "length > 0, with a unit") = field(
        "outer diameter of the steel cylinder (the return path)"
    )
    steel: checked(_steel, "name of a steel of the materials database") = field("B-H curve of the steel parts")
    supply_voltage: checked(_positive("V", "voltage", PLAUSIBLE_SUPPLY_VOLTAGE), "voltage > 0, with a unit") = field(
        "the driver's supply (I R at the rated current must stay below it)", default=None
    )


#: Keys of a damper file's ``[coil]`` table (docs/file_formats.md, [coil]).
COIL_KEYS = tuple(k for k, info in CoilTable.model_fields.items() if info.is_required())
#: Optional keys of ``[coil]`` beyond the contract: ``supply_voltage``, the voltage the coil's driver can apply
#: (a current-controlled driver forces the current up with it; docs/magnetics.md).
OPTIONAL_COIL_KEYS = tuple(k for k in CoilTable.model_fields if k not in COIL_KEYS)


def coil_from_table(table: Any, where: str = "coil") -> Coil:
    """A :class:`Coil` from a ``[coil]`` table (:class:`CoilTable`); a bad value is a :class:`DamperFileError`
    naming the key.

    Only the table itself is checked here (types, units, signs, the steel's name); how the coil fits the head is
    checked with the geometry (:func:`erdesign.magnetics.circuit.piston_head`).

    >>> coil_from_table({"turns": 400, "wire_diameter": "0.5 mm", "core_diameter": "18 mm",
    ...                  "pole_length": "8 mm", "housing_outer_diameter": "50 mm", "steel": "steel-1018"}).turns
    400
    """
    spec = validate(CoilTable, table, where, error=DamperFileError)
    lengths = {
        k: float(to_si(getattr(spec, k), "m", f"{where}.{k}"))
        for k in ("wire_diameter", "core_diameter", "pole_length", "housing_outer_diameter")
    }
    d_w = lengths["wire_diameter"]
    if not 0.05e-3 <= d_w <= 3e-3:
        warnings.warn(
            f"{where}.wire_diameter: {d_w * 1e3:.4g} mm is outside the usual magnet-wire range "
            "0.05-3 mm; check the unit",
            ValidityWarning,
            stacklevel=2,
        )
    turns, steel = spec.turns, spec.steel
    supply = None if spec.supply_voltage is None else float(to_si(spec.supply_voltage, "V", f"{where}.supply_voltage"))
    return Coil(turns=turns, steel=steel, supply_voltage=supply, **lengths)
