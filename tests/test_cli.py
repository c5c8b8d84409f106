"""The command line (docs/cli.md): JSON output, readable table, one-line errors."""

import json
import shutil
import subprocess
import sys
from importlib import resources

import pytest

from erdesign.cli import main

MAKRIS = str(resources.files("erdesign.examples") / "makris.toml")
SIZE_KEYS = [
    "piston_area_m2",
    "flow_m3_per_s",
    "pressure_drop_Pa",
    "force_N",
    "zero_field_force_N",
    "dynamic_range",
    "damping_constant_N_s_per_m",
    "reynolds",
    "laminar",
    "plug_fraction",
]


def run(capsys, *args):
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


def test_size_json_is_one_object_with_the_contract_keys(capsys):
    code, out, err = run(capsys, "size", MAKRIS, "--velocity", "1 in/s", "--field", "3 kV/mm", "--json")
    assert code == 0 and err == ""
    data = json.loads(out)
    assert set(data) == set(SIZE_KEYS)
    # Makris eq 15 (C = 120 kN s/m) and eq 14 (force = dp A_p + 112 N).
    assert data["damping_constant_N_s_per_m"] == pytest.approx(120e3, rel=0.01)
    assert data["force_N"] == pytest.approx(data["pressure_drop_Pa"] * data["piston_area_m2"] + 112.0)
    assert data["laminar"] is True


def test_size_accepts_any_unit_and_plain_si_numbers(capsys):
    _, a, _ = run(capsys, "size", MAKRIS, "--velocity", "1 in/s", "--field", "3 kV/mm", "--json")
    _, b, _ = run(capsys, "size", MAKRIS, "--velocity", "0.0254", "--field", "3e6", "--json")
    _, c, _ = run(capsys, "size", MAKRIS, "--velocity", "91.44 m/hr", "--field", "3000 V/mm", "--json")
    fa, fb, fc = (json.loads(x)["force_N"] for x in (a, b, c))
    assert fa == pytest.approx(fb, rel=1e-12) and fa == pytest.approx(fc, rel=1e-12)


def test_size_default_field_is_zero(capsys):
    _, out, _ = run(capsys, "size", MAKRIS, "--velocity", "1 in/s", "--json")
    data = json.loads(out)
    assert data["force_N"] == data["zero_field_force_N"] and data["dynamic_range"] == 1.0
    assert data["plug_fraction"] == 0.0


def test_size_table_shows_units(capsys):
    code, out, _ = run(capsys, "size", MAKRIS, "--velocity", "1 in/s", "--field", "3 kV/mm")
    assert code == 0
    for text in ("cm²", "MPa", "kN", "kN·s/m", "laminar", "control = 3 kV/mm", "makris-1996"):
        assert text in out


@pytest.mark.parametrize(
    "args, fragment, code",
    [
        (["size", MAKRIS, "--velocity", "1 kg", "--json"], "velocity: expected a velocity", 1),
        (["size", MAKRIS, "--velocity", "1 in/s", "--field", "40 kA/m", "--json"], "field: expected an electric", 1),
        (["size", MAKRIS, "--velocity", "nan", "--json"], "velocity: value must be finite", 1),
        (["size", "missing.toml", "--velocity", "1 in/s", "--json"], "missing.toml: no such file", 1),
        (["size", MAKRIS, "--json"], "Missing option '--velocity'", 2),
        (["size", MAKRIS, "--velocity", "1 in/s", "--colour", "red"], "No such option", 2),
        (["sizing"], "No such command", 2),
    ],
)
def test_errors_are_one_line_on_stderr_with_nonzero_exit(capsys, args, fragment, code):
    rc, out, err = run(capsys, *args)
    assert rc == code and out == ""
    assert fragment in err and err.count("\n") == 1 and "Traceback" not in err


def test_warnings_go_to_stderr_and_json_stays_clean(capsys, tmp_path):
    text = open(MAKRIS).read().replace('gap = "0.8 mm"', 'gap = "5 mm"')
    path = tmp_path / "thick.toml"
    path.write_text(text)
    rc, out, err = run(capsys, "size", str(path), "--velocity", "1 in/s", "--json")
    assert rc == 0 and json.loads(out)["laminar"] is True
    assert err.startswith("warning: geometry.gap: h/d = 0.35") and "exact annulus is used" in err


@pytest.mark.slow
def test_console_script_installed():
    # The installed `erdesign` console script (pyproject [project.scripts]) runs end to end.
    exe = shutil.which("erdesign")
    if exe is None:
        pytest.skip("erdesign console script not on PATH (package not installed)")
    res = subprocess.run(
        [exe, "size", MAKRIS, "--velocity", "1 in/s", "--json"], capture_output=True, text=True, timeout=120
    )
    assert res.returncode == 0 and json.loads(res.stdout)["laminar"] is True
    res = subprocess.run(
        [exe, "size", MAKRIS, "--velocity", "1 kg", "--json"], capture_output=True, text=True, timeout=120
    )
    assert res.returncode == 1 and res.stdout == "" and res.stderr.count("\n") == 1


def test_module_entry_point():
    res = subprocess.run(
        [sys.executable, "-m", "erdesign", "size", MAKRIS, "--velocity", "1 in/s", "--json"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert res.returncode == 0 and "force_N" in json.loads(res.stdout)


def test_a_bare_number_for_a_dimension_warns(capsys):
    """Issue 14: `--velocity 25` (meant mm/s) silently meant m/s.  It still reads SI (the contract) but says so."""
    code, out, err = run(capsys, "size", MAKRIS, "--velocity", "0.0254", "--field", "3 kV/mm", "--json")
    assert code == 0 and json.loads(out)["force_N"] > 0
    assert err == 'warning: --velocity 0.0254: a bare number, read as 0.0254 m/s; give the unit, e.g. "0.0254 m/s"\n'
    code, _, err = run(capsys, "size", MAKRIS, "--velocity", "1 in/s", "--field", "0", "--json")
    assert code == 0 and err == ""  # zero is zero in any unit


@pytest.mark.parametrize("command", ["size", "report", "design", "diagnose"])
def test_help_has_examples(capsys, command):
    import erdesign.cli.design  # noqa: F401
    import erdesign.cli.report  # noqa: F401

    code, out, _ = run(capsys, command, "--help")
    assert code == 0 and "Examples:" in out and f"erdesign {command} " in out.split("Examples:")[1]


def test_every_subpackage_is_listed_for_installation():
    # pyproject.toml lists the packages by hand; a new subpackage left out installs without it (the console script
    # then fails with ModuleNotFoundError while a source checkout works)
    import tomllib
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    listed = set(tomllib.loads((root / "pyproject.toml").read_text())["tool"]["setuptools"]["packages"])
    found = {".".join(p.parent.relative_to(root).parts) for p in (root / "erdesign").rglob("__init__.py")}
    assert found <= listed, sorted(found - listed)
