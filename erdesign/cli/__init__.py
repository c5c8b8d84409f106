"""The ``erdesign`` command line: one module per command, registered on the group by importing it here."""

from . import design, diagnose, fit, identify, materials, models, report, size  # noqa: F401  (each registers its command)
from .main import cli, main, run

__all__ = ["cli", "main", "run"]
