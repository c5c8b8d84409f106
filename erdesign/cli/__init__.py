"""The ``erdesign`` command line: one module per command, imported by the group only when its command runs
(:data:`erdesign.cli.main.COMMANDS`)."""

from .main import cli, main, run

__all__ = ["cli", "main", "run"]
