"""Result of a design search: design records, the JSON of ``erdesign design --json`` and the CSV of ``--out``.

A *design record* is a plain dictionary (JSON-ready, SI numbers) with the keys of docs/cli.md -
``geometry`` (a damper-file ``[geometry]`` table, values as strings with units), ``force_N``,
``zero_field_force_N``, ``dynamic_range``, ``fluid_volume_m3`` (at the first design point) and
``active_constraints`` - and these documented extras:

===========================  ===================================================================================
``rank``                     1 for the best design (ranked designs only)
``origin``                   ``"refined"`` (SLSQP from a sample), ``"sampled"``, or ``"nearest"`` (infeasible)
``controllable_force_N``     force at field minus force at zero field, first point
``pressure_drop_Pa``         pressure drop across the piston at field, first point
``reynolds``                 Makris eq 1 at field, first point
``bingham_number``           tau_y h / (eta u): yield over viscous stress, first point
``plug_fraction``            plug thickness / gap at field, first point
``gap_ratio``                h / d (thin-gap model: <= 0.1)
``piston_area_m2``           pi/4 (Dp^2 - dr^2)
``outer_diameter_m``         envelope model (:mod:`erdesign.design.envelope`)
``length_m``                 body length of the envelope model
``total_fluid_volume_m3``    A_p x stroke + fluid in the gap(s)
``voltage_V``                electrode voltage E h at the first point (ER fluids only)
``margins``                  constraint name -> relative margin (>= 0 met)
``points``                   per design point: velocity, field and the figures above
``violations``               nearest design only: constraint name -> shortfall as a fraction of the limit
===========================  ===================================================================================
"""

from __future__ import annotations

import csv
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ErdesignError
from ..units import Q_
from .evaluate import CandidateFigures, Constraint
from .requirements import VARIABLES, Requirements

__all__ = ["DesignResult", "design_record", "CSV_COLUMNS", "RECORD_KEYS", "figure_value"]

#: Columns of the CSV file written by :meth:`DesignResult.write_csv`: (header with unit, record key, scale).
CSV_COLUMNS = (
    ("force [N]", "force_N", 1.0),
    ("zero_field_force [N]", "zero_field_force_N", 1.0),
    ("controllable_force [N]", "controllable_force_N", 1.0),
    ("dynamic_range [1]", "dynamic_range", 1.0),
    ("fluid_volume [cm^3]", "fluid_volume_m3", 1e6),
    ("total_fluid_volume [cm^3]", "total_fluid_volume_m3", 1e6),
    ("outer_diameter [mm]", "outer_diameter_m", 1e3),
    ("length [mm]", "length_m", 1e3),
    ("pressure_drop [MPa]", "pressure_drop_Pa", 1e-6),
    ("reynolds [1]", "reynolds", 1.0),
    ("bingham_number [1]", "bingham_number", 1.0),
    ("plug_fraction [1]", "plug_fraction", 1.0),
    ("gap_ratio [1]", "gap_ratio", 1.0),
)


#: Where each figure of :data:`~erdesign.design.figures.FIGURES` sits in a design record (first design point).
RECORD_KEYS = {
    "force": ("force_N",),
    "controllable_force": ("controllable_force_N",),
    "zero_field_force": ("zero_field_force_N",),
    "dynamic_range": ("dynamic_range",),
    "fluid_volume": ("fluid_volume_m3",),
    "total_fluid_volume": ("total_fluid_volume_m3",),
    "outer_diameter": ("outer_diameter_m",),
    "length": ("length_m",),
    "coil_power": ("magnetics", "power_W"),
    "time_constant": ("magnetics", "time_constant_s"),
}


def figure_value(record: dict, figure: str) -> float | None:
    """The SI value of the figure ``figure`` (a name of ``FIGURES``) of a design record; None where undefined.

    >>> figure_value({"force_N": 6020.0, "magnetics": {"power_W": 7.5}}, "coil_power")
    7.5
    """
    value: Any = record
    for key in RECORD_KEYS[figure]:
        value = value.get(key) if isinstance(value, dict) else None
    return None if value is None else float(value)


def _finite(x: float) -> float | None:
    x = float(x)
    return x if np.isfinite(x) else None


def design_record(
    req: Requirements,
    constraints: tuple[Constraint, ...],
    fig: CandidateFigures,
    geometry: dict,
    tol: float,
    origin: str,
) -> dict:
    """JSON-ready record of one design (``fig`` holds exactly that design; ``geometry`` its [geometry] table)."""
    margins = fig.margins[:, 0]
    geometry = dict(geometry)
    coil_table = geometry.pop("coil", None)
    active = [c.name for c, m in zip(constraints, margins) if 0.0 <= m <= tol]
    for name in req.free_variables:
        lo, hi = req.bounds[name]
        x = float(getattr(fig, name)[0])
        if name == "ducts":
            at_lo, at_hi = x == lo, x == hi
        else:
            at_lo, at_hi = np.log(x / lo) <= tol, np.log(hi / x) <= tol
        if at_lo:
            active.append(f"bounds.{name} (low)")
        if at_hi:
            active.append(f"bounds.{name} (high)")
    control = req.fluid.control_unit
    field_unit = req.fluid.field_unit
    points = []
    for i, p in enumerate(req.points):
        points.append(
            {
                "velocity_m_per_s": p.velocity,
                "field": f"{Q_(p.field, control).to(field_unit).magnitude:.6g} {field_unit}",
                "force_N": float(fig.force[i, 0]),
                "zero_field_force_N": float(fig.zero_field_force[i, 0]),
                "dynamic_range": _finite(fig.dynamic_range[i, 0]),
                "pressure_drop_Pa": float(fig.pressure_drop[i, 0]),
                "reynolds": float(fig.reynolds[i, 0]),
                "bingham_number": _finite(fig.bingham_number[i, 0]),
                "plug_fraction": float(fig.plug_fraction[i, 0]),
            }
        )
    first = points[0]
    record: dict[str, Any] = {
        "geometry": geometry,
        "force_N": first["force_N"],
        "zero_field_force_N": first["zero_field_force_N"],
        "dynamic_range": first["dynamic_range"],
        "fluid_volume_m3": float(fig.fluid_volume[0]),
        "active_constraints": active,
        "origin": origin,
        "controllable_force_N": float(fig.controllable_force[0, 0]),
        "pressure_drop_Pa": first["pressure_drop_Pa"],
        "reynolds": first["reynolds"],
        "bingham_number": first["bingham_number"],
        "plug_fraction": first["plug_fraction"],
        "gap_ratio": float(fig.gap_ratio[0]),
        "piston_area_m2": float(fig.piston_area[0]),
        "outer_diameter_m": float(fig.outer_diameter[0]),
        "length_m": float(fig.length[0]),
        "total_fluid_volume_m3": float(fig.total_fluid_volume[0]),
        "margins": {c.name: _finite(m) for c, m in zip(constraints, margins)},
        "points": points,
    }
    if req.fluid.control == "electric field":
        record["voltage_V"] = float(fig.voltage[0, 0])
    if coil_table is not None:
        record["coil"] = coil_table
        record["magnetics"] = {
            "design_current_A": float(max(p.field for p in req.points)),
            "coil_resistance_ohm": float(fig.coil_resistance[0]),
            "power_W": float(fig.coil_power[0]),
            "time_constant_s": _finite(fig.time_constant[0]),
            "fill_factor": float(fig.fill_factor[0]),
        }
        for i, p in enumerate(points):
            p.update(
                yield_stress_Pa=float(fig.yield_stress[i, 0]),
                gap_flux_density_T=float(fig.gap_flux_density[i, 0]),
                coil_voltage_V=float(fig.voltage[i, 0]),
                current_density_A_per_m2=float(fig.current_density[i, 0]),
                saturation_ratio=float(fig.saturation[i, 0]),
            )
    return record


@dataclass
class DesignResult:
    """Outcome of :func:`erdesign.design.design`.

    Attributes
    ----------
    requirements : Requirements
    constraints : tuple of Constraint
    evaluated : int
        Candidates evaluated in the sweep.
    feasible_count : int
        Of those, how many met every constraint.
    feasible : bool
        True when at least one design is returned.
    designs : list of dict
        Design records (module notes), best first.
    pareto : list of dict
        Feasible sampled designs on the Pareto front of ``requirements.search.pareto``, ordered by the first figure.
    conflicts : list of str
        Why nothing is feasible (empty when feasible).
    nearest : dict or None
        The design nearest to feasibility, with ``violations``, when nothing is feasible.
    """

    requirements: Requirements
    constraints: tuple
    evaluated: int
    feasible_count: int
    feasible: bool = False
    designs: list = field(default_factory=list)
    pareto: list = field(default_factory=list)
    conflicts: list = field(default_factory=list)
    nearest: dict | None = None

    def as_json(self) -> dict:
        """The object printed by ``erdesign design --json`` (contract keys first, documented extras after)."""
        req = self.requirements
        return {
            "feasible": self.feasible,
            "designs": self.designs,
            "conflicts": self.conflicts,
            "objective": req.objective,
            "configuration": req.configuration,
            "evaluated": self.evaluated,
            "feasible_count": self.feasible_count,
            "constraints": [c.name for c in self.constraints],
            "pareto_figures": list(req.search.pareto),
            "pareto": self.pareto,
            "nearest": self.nearest,
            "ranking": self.ranking_note(),
            "gap_tolerance_m": req.search.gap_tolerance,
            "length_tolerance_m": req.search.length_tolerance,
        }

    def design(self, rank: int) -> dict:
        """The design record of rank ``rank`` (1 is the best); an :class:`~erdesign.errors.ErdesignError` naming
        the rank when there is no such design (nothing feasible, or fewer designs returned)."""
        if not self.designs:
            raise ErdesignError(
                f"rank {rank}: nothing is feasible, so there is no design to take (the search "
                f"explains {len(self.conflicts)} conflict(s))"
            )
        if isinstance(rank, bool) or not isinstance(rank, (int, np.integer)) or not 1 <= rank <= len(self.designs):
            raise ErdesignError(f"rank {rank!r}: the search returned designs 1 to {len(self.designs)}")
        return self.designs[int(rank) - 1]

    def damper_spec(self, rank: int = 1) -> dict:
        """The damper file (``name``, ``[geometry]``, ``[fluid]``, ``[coil]``) of the design of rank ``rank``.

        The geometry and the coil are the design's own tables (the rounded values that were checked); the fluid is
        the requirements' ``[fluid]`` table as written (material, seal friction, ...), so that
        :func:`erdesign.damper.files.damper_from_dict` builds the damper whose figures the design reports.  With a
        coil the fluid's ``reference_field`` is the design current (the largest current of the design points), the
        rated current of a damper file with a ``[coil]``.

        Examples
        --------
        >>> from erdesign.design import design, load_example_requirements
        >>> r = design(load_example_requirements("makris_requirements").with_search(samples=1024, refine=False))
        >>> spec = r.damper_spec(1)
        >>> sorted(spec), spec["fluid"]["material"]
        (['fluid', 'geometry', 'name'], 'makris-zeolite-silicone')
        """
        rec = self.design(rank)
        req = self.requirements
        fluid = dict(req.fluid_table)
        spec: dict[str, Any] = {
            "name": f"{req.name or 'design'} #{int(rank)}",
            "geometry": dict(rec["geometry"]),
            "fluid": fluid,
        }
        if "coil" in rec:
            fluid["reference_field"] = f"{rec['magnetics']['design_current_A']!r} A"
            spec["coil"] = dict(rec["coil"])
        return spec

    def ranking_note(self) -> str:
        """How the designs are rounded and ranked, in words (the table and the JSON state it)."""
        from .search import TIE, secondary_objective

        s = self.requirements.search
        if s.gap_tolerance and s.length_tolerance:
            rounding = (
                f"dimensions rounded to {s.gap_tolerance * 1e3:g} mm (gap) and {s.length_tolerance * 1e3:g} mm "
                "(other lengths), then re-checked"
            )
        else:
            rounding = "dimensions to six significant figures, re-checked"
        return (
            f"{rounding}; ranked by {self.requirements.objective}, designs within {TIE * 100:g} % of each other "
            f"by {secondary_objective(self.requirements)}"
        )

    def csv_rows(self) -> list[dict]:
        """Rows of the CSV file: ranked designs, then the Pareto front, then the nearest infeasible design."""
        rows = []
        sets = [("ranked", d) for d in self.designs] + [("pareto", d) for d in self.pareto]
        if self.nearest is not None:
            sets.append(("nearest", self.nearest))
        for kind, rec in sets:
            g = rec["geometry"]
            row: dict[str, Any] = {"set": kind, "rank": rec.get("rank", ""), "configuration": g["configuration"]}
            for name in VARIABLES[:-1]:
                text = g.get(name)
                row[f"{name} [mm]"] = "" if text is None else text.removesuffix(" mm")
            row["ducts [1]"] = g.get("ducts", 1)
            for header, key, scale in CSV_COLUMNS:
                value = rec[key]
                row[header] = "" if value is None else f"{value * scale:.8g}"
            for i, p in enumerate(rec["points"][1:], start=2):
                row[f"force_point{i} [N]"] = f"{p['force_N']:.8g}"
                row[f"zero_field_force_point{i} [N]"] = f"{p['zero_field_force_N']:.8g}"
                dr = p["dynamic_range"]
                row[f"dynamic_range_point{i} [1]"] = "" if dr is None else f"{dr:.8g}"
            row["active_constraints"] = "; ".join(rec["active_constraints"])
            rows.append(row)
        return rows

    def write_csv(self, path: str | Path, *, overwrite: bool = False, option: str = "path") -> None:
        """Write :meth:`csv_rows` to ``path``: first line the column names with units in brackets.  Written whole
        or not at all, an existing ``path`` only with ``overwrite`` (:mod:`erdesign.output`)."""
        rows = self.csv_rows()
        header = ["set", "rank", "configuration"] + [f"{n} [mm]" for n in VARIABLES[:-1]] + ["ducts [1]"]
        header += [h for h, _, _ in CSV_COLUMNS]
        for i in range(2, len(self.requirements.points) + 1):
            header += [f"force_point{i} [N]", f"zero_field_force_point{i} [N]", f"dynamic_range_point{i} [1]"]
        header.append("active_constraints")
        from ..output import open_output

        with open_output(path, newline="", overwrite=overwrite, option=option) as fh:
            writer = csv.DictWriter(fh, fieldnames=header)
            writer.writeheader()
            writer.writerows(rows)
