"""The bundled examples reach a user without a clone (issue 26): the package ships every example file, and the paths
the documentation writes (``examples/makris.toml``, ``examples/requirements/...``, ``examples/measurements/...``)
work from any folder, so nothing depends on the repository's top-level ``examples`` and ``materials`` links (a copy
that loses them, or an installed package, behaves the same)."""

from __future__ import annotations

import fnmatch
import json
import re
import sys
from pathlib import Path

import pytest

from erdesign import load_example
from erdesign.cli import main
from erdesign.data.measurement import read_measurement
from erdesign.design import load_example_requirements, read_requirements

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]
PACKAGE_EXAMPLES = ROOT / "erdesign" / "examples"


def test_every_example_file_is_package_data():
    """What a wheel ships: pyproject's package-data globs cover every data file of erdesign/examples."""
    globs = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-data"]
    patterns = globs["erdesign.examples"]
    data = [
        p.relative_to(PACKAGE_EXAMPLES).as_posix()
        for p in PACKAGE_EXAMPLES.rglob("*")
        if p.is_file() and p.suffix in (".toml", ".csv")
    ]
    assert data and not [f for f in data if not any(fnmatch.fnmatch(f, g) for g in patterns)]


def test_documented_paths_work_from_a_folder_without_examples(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["size", "examples/makris.toml", "--velocity", "1 in/s", "--field", "3 kV/mm", "--json"]) == 0
    # Damper.size's doctest: 6.07 kN at 1 in/s and 3 kV/mm (Makris et al. 1996's damper)
    assert json.loads(capsys.readouterr().out)["force_N"] == pytest.approx(
        load_example("makris").size("1 in/s", "3 kV/mm").force.m_as("N"), rel=1e-12
    )
    path = "examples/requirements/makris_requirements.toml"
    assert read_requirements(path) == load_example_requirements("makris_requirements")
    record = read_measurement("examples/measurements/makris_hidden_seal_friction.csv")
    assert record.time.size > 100
    assert main(["size", "examples/no_such_damper.toml", "--velocity", "1 in/s"]) == 1
    assert "examples/no_such_damper.toml: no such file" in capsys.readouterr().err


def test_a_file_of_the_users_own_at_that_path_wins(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "examples").mkdir()
    text = (PACKAGE_EXAMPLES / "makris.toml").read_text().replace('gap = "0.8 mm"', 'gap = "0.6 mm"')
    assert 'gap = "0.6 mm"' in text
    (tmp_path / "examples" / "makris.toml").write_text(text)
    assert main(["size", "examples/makris.toml", "--velocity", "1 in/s", "--json"]) == 0
    own = json.loads(capsys.readouterr().out)["force_N"]
    assert own > 1.5 * load_example("makris").size("1 in/s").force.m_as("N")  # (0.8/0.6)^3 more viscous force


def test_no_code_reads_through_the_top_level_links():
    """Tests, benchmarks and the package name erdesign/examples and erdesign/materials, never the links."""
    link = re.compile(r"""(ROOT|parents\[\d\]|parent\.parent)\s*/\s*["'](examples|materials)["']""")
    offenders = [
        f"{p.relative_to(ROOT)}:{i}"
        for folder in ("tests", "benchmarks", "erdesign")
        for p in (ROOT / folder).rglob("*.py")
        for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), start=1)
        if link.search(line)
    ]
    assert offenders == []


def test_erdesign_examples_lists_the_requirements_too(capsys):
    from erdesign.design import example_requirements_names

    assert main(["examples", "--json"]) == 0
    listed = json.loads(capsys.readouterr().out)["requirements"]
    assert [r["name"] for r in listed] == example_requirements_names()
    assert {r["name"]: r["configuration"] for r in listed}["mr_coil_requirements"] == "mixed"
    for r in listed:  # each listed name is accepted by erdesign design as it is
        assert read_requirements(r["name"]).name == r["title"]


def test_an_example_name_works_in_every_command_that_takes_a_damper_file(tmp_path, monkeypatch, capsys):
    """CONTRACTS "Bundled examples by name": ``magnetics`` and ``report`` used to answer "makris: no such file"."""
    monkeypatch.chdir(tmp_path)
    assert main(["magnetics", "mr_coil", "--current", "1 A", "--json"]) == 0
    by_name = json.loads(capsys.readouterr().out)
    assert main(["magnetics", "examples/mr_coil.toml", "--current", "1 A", "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == by_name
    assert main(["report", "makris", "--out", "r.md"]) == 0
    capsys.readouterr()
    assert "Makris" in (tmp_path / "r.md").read_text()
    assert main(["report", "no_such_damper", "--out", "s.md"]) == 1
    assert "no_such_damper: no such file" in capsys.readouterr().err
    assert not (tmp_path / "s.md").exists()
