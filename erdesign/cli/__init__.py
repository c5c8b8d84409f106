"""The ``erdesign`` command line: one module per command, registered on the group by importing it here."""

from . import app, design, diagnose, fit, identify, magnetics, materials, models, report, simulate, size  # noqa: F401  (registers commands)
from .main import cli, install_option_checks, main, run

install_option_checks(cli)

__all__ = ["cli", "main", "run"]
