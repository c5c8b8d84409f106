"""``erdesign design REQUIREMENTS.toml --write-damper N OUT.toml`` (CONTRACTS.md section 6): the N-th ranked design
as a damper file that every command loads, and ``erdesign size`` of it gives the design's own numbers."""

import json

import pytest

import erdesign.cli.design  # noqa: F401  (registers the command)
from erdesign.cli import main
from erdesign.damper.files import load_damper

from .test_design import INFEASIBLE_REQ, MAKRIS_REQ, small_copy

COIL_REQ = MAKRIS_REQ.replace("makris_requirements", "mr_coil_requirements")


def _design_json(capsys, args):
    assert main(["design", *args, "--json"]) == 0
    captured = capsys.readouterr()
    return json.loads(captured.out), captured.err


def _size_json(capsys, path, velocity, field):
    assert main(["size", str(path), "--velocity", velocity, "--field", field, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("rank", [1, 2])
def test_size_of_the_written_file_gives_the_design_numbers(tmp_path, capsys, rank):
    req = small_copy(tmp_path, MAKRIS_REQ, 2048)
    out = tmp_path / "best.toml"
    found, err = _design_json(capsys, [req, "--write-damper", str(rank), str(out)])
    rec = found["designs"][rank - 1]
    assert f"design {rank} written to {out}" in err
    # makris_requirements' point: 1 in/s at 3 kV/mm; the file is read back by the same loader every command uses
    sized = _size_json(capsys, out, "1 in/s", "3 kV/mm")
    # the same geometry strings and fluid, the same quasi-steady kernel: equal to round-off
    assert sized["force_N"] == pytest.approx(rec["force_N"], rel=1e-12)
    assert sized["zero_field_force_N"] == pytest.approx(rec["zero_field_force_N"], rel=1e-12)
    assert sized["force_N"] >= 6000.0  # the requirement min_force = 6 kN holds for the written file
    damper = load_damper(str(out))
    assert damper.geometry.gap == pytest.approx(float(rec["geometry"]["gap"].removesuffix(" mm")) * 1e-3, rel=1e-15)
    assert damper.geometry.ducts == rec["geometry"]["ducts"]
    assert damper.seal_friction == 112.0  # the requirements' [fluid] seal friction, kept


def test_a_coil_design_is_written_with_its_coil_and_rated_current(tmp_path, capsys):
    req = small_copy(tmp_path, COIL_REQ, 512)
    out = tmp_path / "coil.toml"
    found, _ = _design_json(capsys, [req, "--write-damper", "1", str(out)])
    rec = found["designs"][0]
    sized = _size_json(capsys, out, "0.1 m/s", "2 A")
    # the coil's magnetic circuit is rebuilt from the written [coil]: the same force within the root find's 1e-4
    assert sized["force_N"] == pytest.approx(rec["force_N"], rel=1e-4)
    assert sized["dynamic_range"] >= 5.0
    damper = load_damper(str(out))
    assert damper.fluid.control_unit == "A" and damper.fluid.reference_field == 2.0


def test_an_existing_file_is_kept_without_force_and_replaced_with_it(tmp_path, capsys):
    req = small_copy(tmp_path, MAKRIS_REQ, 1024)
    out = tmp_path / "mine.toml"
    out.write_text("keep me\n")
    assert main(["design", req, "--write-damper", "1", str(out)]) == 1
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "--write-damper" in err and "--force" in err
    assert out.read_text() == "keep me\n"
    assert main(["design", req, "--write-damper", "1", str(out), "--force"]) == 0
    assert load_damper(str(out)).geometry.configuration == "valve"


@pytest.mark.parametrize(
    "args, words",
    [
        (["--write-damper", "0", "x.toml"], "designs 1 (the best) to 10"),
        (["--write-damper", "11", "x.toml"], "designs 1 (the best) to 10"),
        (["--write-damper", "1", "x.csv"], "ending in .toml"),
    ],
)
def test_a_bad_rank_or_name_is_refused_before_the_search(tmp_path, capsys, args, words):
    req = small_copy(tmp_path, MAKRIS_REQ, 1024)
    assert main(["design", req, *args]) == 1
    captured = capsys.readouterr()
    assert captured.out == ""  # refused before any search ran
    assert "\n" not in captured.err.strip() and words in captured.err
    assert not (tmp_path / "x.toml").exists()


def test_nothing_feasible_prints_the_conflicts_and_writes_nothing(tmp_path, capsys):
    req = small_copy(tmp_path, INFEASIBLE_REQ, 1024)
    out = tmp_path / "none.toml"
    assert main(["design", req, "--write-damper", "1", str(out)]) == 1
    captured = capsys.readouterr()
    assert "conflicts:" in captured.out  # the table says why
    assert "nothing is feasible" in captured.err and "\n" not in captured.err.strip()
    assert not out.exists()


def test_a_bundled_requirements_name_loads_the_example_and_a_file_of_that_name_wins(tmp_path, monkeypatch):
    from erdesign.design import load_example_requirements, read_requirements
    from erdesign.errors import ErdesignError

    assert read_requirements("makris_requirements") == load_example_requirements("makris_requirements")
    monkeypatch.chdir(tmp_path)
    (tmp_path / "makris_requirements").write_text("not toml [")
    with pytest.raises(ErdesignError, match="makris_requirements: invalid TOML"):
        read_requirements("makris_requirements")  # an existing file is read, never shadowed by the example
