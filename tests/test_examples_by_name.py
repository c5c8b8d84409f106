"""Bundled examples by name (CONTRACTS.md section 6): wherever a command takes a damper file, an example's name works
when no such file exists; ``erdesign examples`` lists them."""

from __future__ import annotations

import json

import pytest

from erdesign.cli.main import main
from erdesign.damper.files import example_names, load_damper, load_example
from erdesign.errors import ErdesignError


def test_a_name_loads_the_example_and_a_file_of_that_name_wins(tmp_path, monkeypatch):
    assert load_damper("makris").damping_constant_si() == pytest.approx(load_example("makris").damping_constant_si())
    # Makris's damping constant, 120 kN s/m from his geometry (Makris et al. 1996, eq 15)
    assert load_damper("makris").damping_constant_si() == pytest.approx(120e3, rel=0.01)
    monkeypatch.chdir(tmp_path)
    (tmp_path / "makris").write_text("not toml [")
    with pytest.raises(ErdesignError):
        load_damper("makris")  # an existing file is read, never shadowed by the example
    with pytest.raises(ErdesignError):
        load_damper("no_such_example")


def test_erdesign_examples_lists_every_example(capsys):
    assert main(["examples", "--json"]) == 0
    listed = json.loads(capsys.readouterr().out)["examples"]
    assert [e["name"] for e in listed] == example_names()
    assert main(["size", "mr_valve", "--velocity", "0.1 m/s", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["force_N"] > 0
