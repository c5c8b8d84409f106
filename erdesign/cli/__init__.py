"""The ``erdesign`` command line: one module per command, registered on the group by importing it here."""

from . import app, design, diagnose, fit, identify, magnetics, materials, models, report, simulate, size  # noqa: F401  (registers commands)
from .main import cli, main, run

__all__ = ["cli", "main", "run"]
