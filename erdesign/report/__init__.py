"""Unit-checked engineering reports on a damper (HTML or Markdown).

>>> from erdesign.report import build_report, render_markdown
>>> from erdesign.damper.files import load_example
>>> report = build_report(load_example("makris"), velocity_range=("0 in/s", "1 in/s"), fields=["3 kV/mm"])
>>> [c.status for c in report.checks]
['pass', 'pass', 'info', 'pass', 'pass']
>>> "| damping constant C (zero field) | 120.3 kN·s/m | Makris eq 15 |" in render_markdown(report)
True

Layers: :mod:`erdesign.damper.curves` (the numbers, from the library), :mod:`~erdesign.report.builder` (what a
report contains), :mod:`~erdesign.report.formatting` (the one unit helper every number goes through),
:mod:`~erdesign.report.render` (jinja2 templates in ``templates/``).
"""

from ..damper.curves import (
    ForceVelocityCurves,
    SineLoops,
    VelocitySweep,
    force_velocity_curves,
    sine_loops,
    velocity_sweep,
)
from .builder import (
    Check,
    ErrorHistoryStep,
    InputRow,
    MeasurementComparison,
    Report,
    Row,
    Table,
    build_report,
)
from .formatting import Shown, pick_unit, show
from .render import render_html, render_markdown, write_report

__all__ = [
    "build_report",
    "render_html",
    "render_markdown",
    "write_report",
    "Report",
    "Row",
    "InputRow",
    "Check",
    "Table",
    "MeasurementComparison",
    "ErrorHistoryStep",
    "Shown",
    "show",
    "pick_unit",
    "ForceVelocityCurves",
    "force_velocity_curves",
    "SineLoops",
    "sine_loops",
    "VelocitySweep",
    "velocity_sweep",
]
