"""The unit-formatting helpers of :mod:`erdesign.formatting`, under the name the report has always used.

They moved to :mod:`erdesign.formatting` so that the figures (:mod:`erdesign.report.plots`) need not import the report;
every name here is that module's object itself (one unit system in force for both).
"""

from __future__ import annotations

from ..formatting import (
    SIGNIFICANT_DIGITS,
    UNIT_CHOICES,
    UNIT_SYSTEMS,
    Shown,
    control_label,
    field_text,
    kind_of,
    pick_unit,
    round_significant,
    show,
    show_in_system,
    shown_list,
    unit_system,
    use_unit_system,
)

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
    "control_label",
]
