"""The ``erdesign`` command line: one module per command, registered on the group by importing it here."""

from . import size  # noqa: F401  (registers the command)
from .main import cli, main, run

__all__ = ["cli", "main", "run"]
