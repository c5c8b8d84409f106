"""``python -m erdesign`` runs the command line."""

from .cli import run

run()
