"""``python -m erdesign`` runs the command line."""

__all__: list[str] = []

from .cli import run

if __name__ == "__main__":
    run()
