"""Public, unit-aware API of the magnetic circuit: build it from a damper file, evaluate it at coil currents.

>>> from erdesign.magnetics import load_magnetic_circuit
>>> from importlib import resources
>>> with resources.as_file(resources.files("erdesign.examples") / "mr_coil.toml") as path:
...     circuit = load_magnetic_circuit(path)
>>> r = circuit.at("2 A")
>>> f"{r.gap_flux_density:.2f~P}", f"{r.coil_resistance:.3f~P}", r.limiting_part
('0.52 T', '2.648 Ω', 'core')
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from .. import materials
from .._pint import pint  # not `import pint`: erdesign/_pint.py
from ..errors import DamperFileError, ErdesignError, PlausibilityWarning
from ..units import Q_, to_si
from .circuit import MagneticCircuit, piston_head
from .coil import Coil, coil_from_table

__all__ = ["CircuitReport", "build_circuit", "circuit_from_damper_dict", "load_magnetic_circuit", "MagneticCircuit"]


@dataclass(frozen=True)
class CircuitReport:
    """The circuit at one or more coil currents, as pint quantities (arrays when several currents)."""

    current: pint.Quantity
    gap_flux_density: pint.Quantity
    gap_field: pint.Quantity
    yield_stress: pint.Quantity
    coil_resistance: pint.Quantity
    inductance: pint.Quantity
    incremental_inductance: pint.Quantity
    time_constant: pint.Quantity
    power: pint.Quantity
    voltage: pint.Quantity
    current_density: pint.Quantity
    flux_linkage: pint.Quantity
    leakage_fraction: Any
    saturated: Any
    limiting_part: str | None
    knee_current: pint.Quantity
    part_knee_currents: dict

    def as_json(self) -> dict:
        """The JSON of ``erdesign magnetics --json`` (docs/file_formats.md, [coil]): SI numbers; lists when the
        report holds several currents (then with ``current_A``)."""

        def si(q, unit):
            m = np.asarray(q.to(unit).magnitude, dtype=float)
            return m.tolist() if m.ndim else float(m)

        out = {
            "gap_flux_density_T": si(self.gap_flux_density, "T"),
            "gap_field_A_per_m": si(self.gap_field, "A/m"),
            "yield_stress_Pa": si(self.yield_stress, "Pa"),
            "coil_resistance_ohm": float(self.coil_resistance.to("ohm").magnitude),
            "inductance_H": si(self.inductance, "H"),
            "time_constant_s": si(self.time_constant, "s"),
            "power_W": si(self.power, "W"),
            "saturated": (np.asarray(self.saturated).tolist() if np.ndim(self.saturated) else bool(self.saturated)),
            "limiting_part": self.limiting_part,
        }
        if np.ndim(self.current.magnitude):
            out["current_A"] = si(self.current, "A")
        return out


#: Current density in the coil's copper wire [A/m^2] above which a warning says the coil overheats (air-cooled
#: windings are designed for a few A/mm^2 and take some ten times that for seconds), and above which the current is
#: refused (the wire melts within milliseconds: a unit slip, mA given as A or a stray exponent).
PLAUSIBLE_CURRENT_DENSITY = 30e6
POSSIBLE_CURRENT_DENSITY = 1000e6


def check_current_density(current: float, wire_area: float, name: str = "current") -> None:
    """Refuse a coil current [A] whose density in the wire of cross-section ``wire_area`` [m^2] no coil survives,
    warn beyond what it carries for more than seconds (:data:`PLAUSIBLE_CURRENT_DENSITY`)."""
    J = float(current) / wire_area
    text = f"{name}: {float(current):.4g} A is {J / 1e6:.4g} A/mm^2 in the coil's {1e6 * wire_area:.3g} mm^2 wire"
    if J > POSSIBLE_CURRENT_DENSITY:
        raise ErdesignError(
            f"{text}, beyond {POSSIBLE_CURRENT_DENSITY / 1e6:g} A/mm^2 where copper melts within "
            "milliseconds; check the value and its unit"
        )
    if J > PLAUSIBLE_CURRENT_DENSITY:
        warnings.warn(
            f"{text}, beyond the {PLAUSIBLE_CURRENT_DENSITY / 1e6:g} A/mm^2 a coil carries for more than "
            "seconds: it overheats",
            PlausibilityWarning,
            stacklevel=3,
        )


class _Circuit(MagneticCircuit):
    """:class:`MagneticCircuit` with the unit-aware :meth:`at`."""

    def at(self, current: Any) -> CircuitReport:
        """The circuit at coil current(s) ``current`` (``"2 A"``, a quantity, or a number/array in A)."""
        if isinstance(current, (list, tuple, np.ndarray, int, float)) and not isinstance(current, bool):
            I = np.asarray(current, dtype=float)  # plain numbers: amperes
        else:
            I = to_si(current, "A", "current")
        scalar = np.ndim(I) == 0
        Ia = np.atleast_1d(np.asarray(I, dtype=float))
        if not np.all(np.isfinite(Ia)):
            raise ErdesignError(f"current: must be finite, got {current!r}")
        wire_area = math.pi * self.head.wire_diameter**2 / 4.0
        check_current_density(np.max(np.abs(Ia)), wire_area)
        st = self.state(Ia)
        R = self.resistance
        L = self.inductance(Ia)
        Ld = self.incremental_inductance(Ia)
        pick = (lambda a: float(np.asarray(a)[0])) if scalar else (lambda a: np.asarray(a))
        knees = self.part_knee_currents()
        return CircuitReport(
            current=Q_(pick(Ia), "A"),
            gap_flux_density=Q_(pick(np.abs(st.gap_flux_density)), "T"),
            gap_field=Q_(pick(np.abs(st.gap_field)), "A/m"),
            yield_stress=Q_(pick(st.yield_stress), "Pa"),
            coil_resistance=Q_(R, "ohm"),
            inductance=Q_(pick(L), "H"),
            incremental_inductance=Q_(pick(Ld), "H"),
            time_constant=Q_(pick(L / R), "s"),
            power=Q_(pick(Ia**2 * R), "W"),
            voltage=Q_(pick(np.abs(Ia) * R), "V"),
            current_density=Q_(pick(np.abs(Ia) / wire_area), "A/m^2"),
            flux_linkage=Q_(pick(np.abs(st.flux_linkage)), "Wb"),
            leakage_fraction=pick(st.leakage_fraction),
            saturated=bool(st.saturated[0]) if scalar else st.saturated,
            limiting_part=self.limiting_part(),
            knee_current=Q_(self.knee_current(), "A"),
            part_knee_currents={k: Q_(v, "A") for k, v in knees.items()},
        )


def build_circuit(
    geometry: Any, coil: Coil, fluid_material: str, *, temperature: float = 20.0, name: str = "", where: str = "coil"
) -> _Circuit:
    """The circuit of a damper geometry, its coil and the fluid of the materials database (by name)."""
    head = piston_head(geometry, coil, where=where)
    steel = materials.steel_curve(coil.steel)
    try:
        fluid = materials.magnetization_curve(fluid_material)
    except ErdesignError as exc:
        raise DamperFileError(f"fluid.material: {exc}") from None
    law = materials.material_fluid(fluid_material).yield_curve
    if law is None or law.control_unit != "A/m":
        raise DamperFileError(
            f"fluid.material: {fluid_material!r} has no yield curve against field strength "
            "(A/m); the magnetic circuit needs one"
        )
    return _Circuit(head, steel, fluid, law, temperature=temperature, name=name)


def circuit_from_damper_dict(data: Mapping[str, Any]) -> _Circuit:
    """The circuit of a parsed damper file with a ``[coil]`` (errors name the key)."""
    from ..geometry import Geometry

    if "coil" not in data:
        raise DamperFileError(
            "[coil]: missing table (the magnetic circuit needs the coil; docs/file_formats.md, [coil])"
        )
    coil = coil_from_table(data["coil"])
    geo = data.get("geometry")
    if not isinstance(geo, Mapping):
        raise DamperFileError("[geometry]: missing table")
    geometry = Geometry.create(**geo)
    fluid = data.get("fluid")
    if not isinstance(fluid, Mapping) or "material" not in fluid:
        raise DamperFileError(
            "fluid.material: a damper with a [coil] takes its fluid's B-H and yield curves from "
            "the materials database; name it (materials with one: "
            f"{', '.join(n for n in materials.names() if 'magnetization' in materials.load(n))})"
        )
    return build_circuit(geometry, coil, fluid["material"], name=str(data.get("name", "")))


def load_magnetic_circuit(path: str | Path) -> _Circuit:
    """The circuit of a damper file with a ``[coil]`` (errors start with the file name)."""
    from ..damper.files import damper_file_path, read_toml

    try:
        return circuit_from_damper_dict(read_toml(damper_file_path(path)))
    except ErdesignError as exc:
        if str(exc).startswith(str(path)):
            raise
        raise type(exc)(f"{path}: {exc}") from None
