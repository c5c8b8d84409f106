"""The unit registry's start-up (erdesign/_pint.py, issue 26): pint imported without dask and scipy, its parsed
definitions cached on disk, and the cache never the reason a command fails.  Each case runs a fresh interpreter."""

import json
import os
import subprocess
import sys

import pytest

#: Conversions checked in every case: a registry from the cache must convert exactly as one parsed from pint's file.
PROBE = """
import json, sys
from erdesign.units import Q_, ureg
values = {u: Q_(1.0, u).to_base_units().magnitude for u in ("in/s", "kV/mm", "lbf", "psi", "degF", "kA/m", "cSt")}
print(json.dumps({"values": values, "modules": sorted(m for m in sys.modules if m.split(".")[0] in ("dask", "scipy")),
                  "same": ureg is __import__("pint").get_application_registry()}))
"""


def _run(cache, code=PROBE):
    env = {**os.environ, "ERDESIGN_UNIT_CACHE": str(cache)}
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120, check=False
    )
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])


@pytest.fixture(scope="module")
def uncached():
    return _run("off")


def test_the_values_are_pints_own(uncached):
    # 1 in/s = 0.0254 m/s and 1 psi = 6894.757 Pa are exact definitions (NIST SP 811, B.8); 1 lbf = 4.448222 N
    assert uncached["values"]["in/s"] == pytest.approx(0.0254, rel=1e-15)
    assert uncached["values"]["psi"] == pytest.approx(6894.757293168361, rel=1e-12)
    assert uncached["values"]["kV/mm"] == pytest.approx(1e6, rel=1e-15)
    assert uncached["modules"] == []  # neither dask nor scipy imported with the units
    assert uncached["same"]  # still pint's application registry


def test_a_cached_registry_converts_as_the_parsed_one(tmp_path, uncached):
    first = _run(tmp_path)  # writes the cache
    cache = tmp_path / f"pint-{__import__('pint').__version__}"
    written = sorted(p.name for p in cache.iterdir())
    assert any(name.endswith(".pickle") for name in written)
    second = _run(tmp_path)  # reads it
    assert sorted(p.name for p in cache.iterdir()) == written
    assert first["values"] == second["values"] == uncached["values"]


def test_an_unwritable_cache_folder_falls_back_to_parsing(tmp_path, uncached):
    blocker = tmp_path / "a_file"
    blocker.write_text("not a folder")
    assert _run(blocker / "cache")["values"] == uncached["values"]  # mkdir fails: no cache, no error


def test_a_damaged_cache_is_removed_and_written_again(tmp_path, uncached):
    mine = tmp_path / "notes.txt"
    mine.write_text("the user's own file beside the cache")
    _run(tmp_path)
    cache = tmp_path / f"pint-{__import__('pint').__version__}"
    (cache / "unrelated.txt").write_text("not pint's")
    for p in cache.glob("*.pickle"):
        p.write_bytes(b"\x80\x04 cut short")  # a write cut short
    assert _run(tmp_path)["values"] == uncached["values"]
    assert _run(tmp_path)["values"] == uncached["values"]
    rebuilt = list(cache.glob("*.pickle"))
    assert rebuilt and all(p.stat().st_size > 100 for p in rebuilt)  # rebuilt whole
    assert mine.exists() and (cache / "unrelated.txt").exists()  # only pint's files were removed


def test_a_registry_the_user_set_first_is_kept(tmp_path):
    code = (
        "import pint\nmine = pint.UnitRegistry()\nmine.define('widget = 3 m')\npint.set_application_registry(mine)\n"
        "from erdesign.units import ureg, to_si\nimport json\n"
        "print(json.dumps({'kept': ureg.get() is mine, 'widget': to_si('2 widget', 'm', 'x')}))"
    )
    found = _run(tmp_path / "cache", code)
    assert found == {"kept": True, "widget": 6.0}


def test_dask_and_scipy_import_normally_afterwards(tmp_path):
    code = (
        "import erdesign.units, json, dask, scipy.optimize\n"
        "print(json.dumps({'root': scipy.optimize.brentq(lambda x: x * x - 2.0, 0.0, 2.0)}))"
    )
    assert _run(tmp_path / "cache", code)["root"] == pytest.approx(2.0**0.5, rel=1e-12)
