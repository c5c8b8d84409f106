"""The repository keeps ruff's lint rules and its formatting (configured in pyproject.toml, ``[tool.ruff]``); the
same checks run before each commit through ``.pre-commit-config.yaml``.  CI runs them here, in the README's test
command, so a change that breaks either fails the suite."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _ruff() -> list[str]:
    exe = shutil.which("ruff")
    if exe:
        return [exe]
    try:
        import ruff  # noqa: F401  (the wheel ships the binary; `python -m ruff` finds it)
    except ImportError:
        pytest.skip("ruff is not installed (it comes with the test extra: pip install '.[test]')")
    return [sys.executable, "-m", "ruff"]


@pytest.mark.parametrize("check", [["check", "."], ["format", "--check", "."]], ids=["lint", "format"])
def test_ruff(check):
    done = subprocess.run(_ruff() + check, cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, (done.stdout + done.stderr)[-4000:]
