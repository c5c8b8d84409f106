"""The inter-process lock around numba's cache (:func:`erdesign._compile.cache_lock`).

Two processes that compiled the same cached generalised ufunc at once could leave a mismatched pair of cache files
that crashed every later process loading them (numba issue #10128; seen as a segmentation fault of a parallel test
worker).  Every first compile of a cached erdesign loop now holds a lock file per user and cache folder.
"""

from __future__ import annotations

import logging
import os
import select
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from erdesign import _compile

ROOT = Path(__file__).resolve().parents[1]

pytestmark = pytest.mark.skipif(_compile.fcntl is None, reason="no fcntl.flock on this platform")


def _env(cache: Path, pythonpath: str = str(ROOT)) -> dict:
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env.update(NUMBA_CACHE_DIR=str(cache), PYTHONPATH=pythonpath, PYTHONDONTWRITEBYTECODE="1")
    return env


#: Imports the loops that compile at import (the slit flow's generalised ufunc, the valve's ufuncs) and calls a
#: lazily compiled one, all into an empty cache, starting together at the time given as argv[1].
TOGETHER = """
import sys, time
import numpy as np
import numba
time.sleep(max(0.0, float(sys.argv[1]) - time.time()))
from erdesign.flow import _compiled as flow
from erdesign.simulation.truthrig import valve
from erdesign.models import _compiled as models
dp, phi = flow.slit_flow(np.array([1e-6, -2e-6]), 1800.0, 13.0, 0.0546, 0.0143, 0.0008)
z = models.bouc_wen_state(0.01 * np.sin(np.linspace(0.0, 6.0, 200)), 3e5, 2e5, 1.0, 2.0, 0.0)
print(repr(dp.tolist()), repr(phi.tolist()), repr(float(z[-1])))
"""


def test_two_processes_compiling_into_an_empty_cache_at_once(tmp_path):
    """Both processes succeed with the same numbers, and a third that loads what they cached gets them too (a
    mismatched cache pair would crash it)."""
    cache = tmp_path / "numba-cache"
    cache.mkdir()
    start = f"{time.time() + 4.0:.3f}"  # both past their numba import by then
    runs = [
        subprocess.Popen(
            [sys.executable, "-c", textwrap.dedent(TOGETHER), start],
            cwd=tmp_path,
            env=_env(cache),
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        for _ in range(2)
    ]
    outputs = [run.communicate(timeout=600) for run in runs]
    for run, (out, err) in zip(runs, outputs):
        assert run.returncode == 0, err[-2000:]
    assert outputs[0][0] == outputs[1][0] != ""
    assert any(cache.rglob("*.nbi")), "nothing was cached"
    again = subprocess.run(
        [sys.executable, "-c", textwrap.dedent(TOGETHER), "0"],
        cwd=tmp_path,
        env=_env(cache),
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert again.returncode == 0, again.stderr[-2000:]
    assert again.stdout == outputs[0][0]


#: A cached function of its own (so that its compile is short), compiled after printing "ready".
WAITER = """
import sys, time
import numba
from erdesign._compile import njit

@njit(cache=True)
def add_one(x):
    return x + 1.0

print("ready", flush=True)
print(add_one(2.0), time.time(), flush=True)
"""


def test_a_compile_waits_while_another_process_holds_the_lock(tmp_path, monkeypatch):
    """While this process holds the lock of a cache folder, another process's first compile into that folder
    waits (without the lock its compile of a one-line function takes well under the second waited here), then
    completes once the lock is released."""
    cache = tmp_path / "numba-cache"
    cache.mkdir()
    (tmp_path / "waiter.py").write_text(textwrap.dedent(WAITER))
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(cache))  # the lock file of that cache folder
    with _compile.cache_lock():
        run = subprocess.Popen(
            [sys.executable, "waiter.py"],
            cwd=tmp_path,
            env=_env(cache, f"{tmp_path}{os.pathsep}{ROOT}"),
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        ready, _, _ = select.select([run.stdout], [], [], 120.0)  # never hang the suite if it never gets there
        assert ready and run.stdout.readline().strip() == "ready", run.stderr.read() if run.poll() is not None else ""
        time.sleep(3.0)
        assert run.poll() is None, "the compile did not wait for the lock"
        released = time.time()
    out, err = run.communicate(timeout=300)
    assert run.returncode == 0, err[-2000:]
    value, finished = out.split()
    assert value == "3.0" and float(finished) >= released


def test_the_lock_is_reentrant_and_released():
    """A compile that compiles the functions it calls takes the lock again in the same process; after the
    outermost hold the lock file is free for another descriptor."""
    with _compile.cache_lock(), _compile.cache_lock():
        assert _compile._depth == 2
    assert _compile._depth == 0 and _compile._held_file is None
    with open(_compile._lock_path(), "a+b") as other:
        _compile.fcntl.flock(other.fileno(), _compile.fcntl.LOCK_EX | _compile.fcntl.LOCK_NB)  # raises if held


class _Messages(logging.Handler):
    def __init__(self):
        super().__init__(logging.INFO)
        self.messages = []

    def emit(self, record):
        self.messages.append(record.getMessage())


def test_no_lock_file_compiles_unlocked(monkeypatch):
    """Where the lock file cannot be made, the lock is skipped (said in the log), as numba's own compiles are."""
    monkeypatch.setattr(_compile, "_lock_path", lambda: Path("/dev/null/erdesign.lock"))
    log, handler = logging.getLogger("erdesign._compile"), _Messages()
    monkeypatch.setattr(log, "level", logging.INFO)
    log.addHandler(handler)
    try:
        with _compile.cache_lock():
            assert _compile._depth == 1 and _compile._held_file is None
    finally:
        log.removeHandler(handler)
    assert len(handler.messages) == 1 and handler.messages[0].startswith("numba cache lock unavailable")
