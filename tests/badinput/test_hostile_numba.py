"""Issue 27: a user who cannot write the package's ``__pycache__`` nor a home folder still runs erdesign: numba's
cache falls back to an in-memory compile (:func:`erdesign._compile.njit`) instead of ``cannot cache function ...: no
locator available`` before any input is read.

The tests run as whatever user the suite runs as (often root, for whom a read-only folder is still writable), so the
unwritable places are made by putting a *file* named ``__pycache__`` where numba would make its folder and by
pointing ``HOME`` and ``XDG_CACHE_HOME`` below ``/dev/null``: no user can make a folder there.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _no_cache_env(pythonpath: Path) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "PYTHONPATH")}
    env.update(
        HOME="/dev/null",
        XDG_CACHE_HOME="/dev/null/cache",
        PYTHONDONTWRITEBYTECODE="1",
        PYTHONPATH=str(pythonpath),
        NUMBA_DISABLE_PERFORMANCE_WARNINGS="1",
    )
    return env


def _block_caches(folder: Path) -> None:
    """A file named ``__pycache__`` in ``folder`` and every folder below it: no cache folder can be made there."""
    for path in [folder, *[p for p in folder.rglob("*") if p.is_dir()]]:
        (path / "__pycache__").write_text("")


def _run(code: str, cwd: Path, env: dict) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)], cwd=cwd, env=env, capture_output=True, text=True, timeout=300
    )


MODULE = """
from {decorator} import njit

@njit(cache=True)
def add_one(x):
    return x + 1.0
"""


@pytest.mark.parametrize("decorator, works", [("numba", False), ("erdesign._compile", True)])
def test_a_cached_function_where_no_cache_folder_can_be_made(tmp_path, decorator, works):
    """numba's own njit(cache=True) fails in this setting (so the setting reproduces the issue); erdesign's njit
    compiles in memory and gives the same result."""
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    (pkg / "kernel.py").write_text(MODULE.format(decorator=decorator))
    _block_caches(pkg)
    env = _no_cache_env(f"{pkg}{os.pathsep}{ROOT}")
    done = _run("import kernel; print(kernel.add_one(2.0))", pkg, env)
    if works:
        assert done.returncode == 0, done.stderr
        assert done.stdout.strip() == "3.0"
    else:
        assert done.returncode != 0 and "no locator available" in done.stderr, done.stderr


@pytest.mark.slow
def test_erdesign_runs_from_a_package_whose_caches_cannot_be_written(tmp_path):
    """A copy of the package with no writable cache folder anywhere: the modules with compiled loops import and a
    compiled model runs (Bouc-Wen from rest on a sine: a finite force that varies)."""
    shutil.copytree(ROOT / "erdesign", tmp_path / "erdesign", ignore=shutil.ignore_patterns("__pycache__"))
    _block_caches(tmp_path / "erdesign")
    done = _run(
        """
        import numpy as np
        import erdesign.effects.compressibility, erdesign.simulation.truthrig.kernels, erdesign.flow._compiled
        import erdesign
        assert erdesign.annulus_bingham_pressure_drop("1 mL/s", "1.8 kPa", "13 Pa*s", "54.6 mm", "14.3 mm",
                                                      "0.8 mm").magnitude > 0
        from erdesign.data.measurement import Measurement
        from erdesign.models.registry import get_model
        t = np.linspace(0.0, 2.0, 401)
        record = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
        F = get_model("bouc_wen").simulate(record)
        print(bool(np.all(np.isfinite(F)) and np.ptp(F) > 0), erdesign.__file__)
    """,
        tmp_path,
        _no_cache_env(tmp_path),
    )
    assert done.returncode == 0, done.stderr[-2000:]
    ok, where = done.stdout.split()
    assert ok == "True" and where.startswith(str(tmp_path))
    assert "no locator" not in done.stderr


def test_every_compiled_loop_goes_through_the_fallback():
    """No module decorates with numba directly (``numba.njit``, ``from numba import njit``...): a new kernel that did
    would bring back 'no locator available' for users who cannot write the package's folder."""
    import re

    direct = re.compile(
        r"^\s*(?:@numba\.(?:njit|jit|vectorize|guvectorize)\b|from numba import .*\b(?:njit|jit|"
        r"vectorize|guvectorize)\b|[A-Za-z_]+ = numba\.(?:njit|jit)\()",
        re.M,
    )
    offenders = [
        str(p.relative_to(ROOT))
        for p in (ROOT / "erdesign").rglob("*.py")
        if p.name != "_compile.py" and direct.search(p.read_text(encoding="utf-8"))
    ]
    assert offenders == [], f"use erdesign._compile.njit / vectorize / guvectorize in {offenders}"
