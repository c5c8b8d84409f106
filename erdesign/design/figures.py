"""The figures of merit a design is ranked or traded off by, and the objectives that name them (data only).

A table of its own so that the requirements parser (:mod:`erdesign.design.requirements`) and the evaluation
(:mod:`erdesign.design.evaluate`) both read it without importing each other.
"""

from __future__ import annotations

from typing import NamedTuple

__all__ = ["Figure", "FIGURES", "OBJECTIVES"]


class Figure(NamedTuple):
    """A figure of merit of a design (registry :data:`FIGURES`)."""

    attribute: str
    """Attribute of :class:`~erdesign.design.evaluate.CandidateFigures` holding it."""
    per_point: bool
    """True: one value per design point (the first point is used for ranking and Pareto fronts)."""
    unit: str
    """SI unit."""
    better: str
    """``"max"`` or ``"min"``."""
    description: str


#: Figures a design is ranked or traded off by (``design.search.pareto`` and the objectives).
FIGURES = {
    "force": Figure("force", True, "N", "max", "total force at the design point"),
    "controllable_force": Figure("controllable_force", True, "N", "max", "force at field minus force at zero field"),
    "zero_field_force": Figure("zero_field_force", True, "N", "min", "force at zero field (passive force)"),
    "dynamic_range": Figure("dynamic_range", True, "", "max", "force at field / force at zero field"),
    "fluid_volume": Figure("fluid_volume", False, "m^3", "min", "active fluid volume between the electrodes"),
    "total_fluid_volume": Figure("total_fluid_volume", False, "m^3", "min", "fluid in cylinder and ducts"),
    "outer_diameter": Figure("outer_diameter", False, "m", "min", "outer diameter of the body"),
    "length": Figure("length", False, "m", "min", "body length"),
    "coil_power": Figure("coil_power", False, "W", "min", "coil power I^2 R at the design current ([design.coil])"),
    "time_constant": Figure(
        "time_constant", False, "s", "min", "coil time constant L/R at the design current ([design.coil])"
    ),
}

#: Objectives of ``design.objective``: name -> figure of :data:`FIGURES` (its ``better`` gives the sense).
OBJECTIVES = {
    "min_fluid_volume": "fluid_volume",
    "max_dynamic_range": "dynamic_range",
    "min_zero_field_force": "zero_field_force",
    "min_total_fluid_volume": "total_fluid_volume",
    "min_outer_diameter": "outer_diameter",
    "min_length": "length",
    "min_coil_power": "coil_power",
    "min_time_constant": "time_constant",
}
