"""Shared fixtures: the Makris damper and its geometry / fluid numbers (Makris et al. 1996, section 3)."""

from __future__ import annotations

import functools
import math
import sys

import pytest

import erdesign
from erdesign.executor import dask_worker_environ

# Makris et al. (1996), section 3: L = 2.15 in, d = 0.563 in, h = 0.0315 in, Dp = 1.315 in, dr = 0.443 in.
MAKRIS = dict(L=0.0546, d=0.0143, h=0.0008, Dp=0.0334, dr=0.01125)
MAKRIS_AP = math.pi / 4 * (MAKRIS["Dp"] ** 2 - MAKRIS["dr"] ** 2)


@pytest.hookimpl(tryfirst=True)  # before pytest-xdist's own, which reads the groups into the test ids
def pytest_collection_modifyitems(config, items):
    """Under pytest-xdist (``-n auto --dist loadgroup``, pyproject's addopts), keep together the tests that share
    an expensive fixture, so that it is built once rather than once per worker: the tests of a file that share one
    of its module-scoped fixtures (a fit, a simulated record, a report, a server) on one worker, and every file
    that uses the Dask cluster (``dask_client``, session-scoped) on one worker with its other shared fixtures.
    Other tests are spread one by one."""
    shared = {item.nodeid: _shared_fixtures(item) for item in items}
    dask_files = {_file(item) for item in items if "dask_client" in shared[item.nodeid]}
    for item in items:
        if shared[item.nodeid]:
            group = "dask_client" if _file(item) in dask_files else _file(item)
            item.add_marker(pytest.mark.xdist_group(group))


def pytest_runtest_setup(item):
    """Streamlit's AppTest scans every installed distribution's metadata for Streamlit components each time an
    AppTest first runs (0.13-0.3 s of CPU, a few hundred times in the suite); the installed packages do not change
    during a test session, so the scan is made once per process, once a test module has imported AppTest."""
    if "streamlit.testing.v1" in sys.modules:
        from streamlit.components.v2 import manifest_scanner

        scan = manifest_scanner.scan_component_manifests
        if not hasattr(scan, "cache_info"):
            cached = functools.cache(scan)
            manifest_scanner.scan_component_manifests = lambda max_workers=None: list(cached(max_workers))
            manifest_scanner.scan_component_manifests.cache_info = cached.cache_info


def pytest_collection_finish(session):
    """Fail loudly, not slowly, when pytest-xdist's groups are lost (pytest 9.2 drops them silently: pytest-xdist
    issue #1386; the test extra keeps pytest below 9.2): a worker's grouped test carries ``@group`` in its id."""
    if getattr(session.config.option, "loadgroup", False):  # set on xdist workers only
        lost = [
            item.nodeid for item in session.items if item.get_closest_marker("xdist_group") and "@" not in item.nodeid
        ]
        if lost:
            raise pytest.UsageError(
                f"pytest-xdist --dist loadgroup did not group {len(lost)} tests (first: {lost[0]}); "
                "this pytest and pytest-xdist do not work together: install the test extra's versions"
            )


def _file(item) -> str:
    return item.nodeid.split("::")[0]


def _shared_fixtures(item) -> set[str]:
    """The module-, package- or session-scoped fixtures of the suite's own that ``item`` uses (pytest's built-in
    ones, such as ``tmp_path_factory``, cost nothing and are left out; a doctest uses none)."""
    info = getattr(item, "_fixtureinfo", None)
    if info is None:
        return set()
    return {
        name
        for name, defs in info.name2fixturedefs.items()
        if defs and defs[-1].scope in ("module", "package", "session") and defs[-1].baseid
    }


@pytest.fixture
def makris():
    """The damper of examples/makris.toml."""
    return erdesign.load_example("makris")


@pytest.fixture(scope="session")
def dask_client():
    """A real Dask cluster on loopback: a ``distributed.LocalCluster`` with 2 worker processes of one thread each,
    shared by every test of the session that needs one (starting it costs a few seconds)."""
    distributed = pytest.importorskip("distributed", reason="the Dask tests need the test extra (distributed)")
    import dask

    # glibc's malloc as in a plain process (docs/scale.md): Dask's default trim threshold makes every large numpy
    # array a fresh mmap, 30 % more CPU per task here; the results are the same either way
    environ = {**dask.config.get("distributed.nanny.pre-spawn-environ"), **dask_worker_environ()}
    dask.config.set({"distributed.nanny.pre-spawn-environ": environ})
    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None, host="127.0.0.1", silence_logs=40
    )
    client = distributed.Client(cluster, set_as_default=False)
    try:
        yield client
    finally:
        client.close()
        cluster.close()
