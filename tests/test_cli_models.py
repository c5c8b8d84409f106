"""``erdesign models`` and ``erdesign identify`` (shared/CONTRACTS.md section 3)."""

import json

import numpy as np
import pytest

import erdesign.cli.identify  # noqa: F401  (registers the command until erdesign/cli/__init__.py imports it)
import erdesign.cli.models  # noqa: F401
from erdesign.cli import main
from erdesign.measurement import Measurement, write_measurement
from erdesign.models.registry import get_model


def run(capsys, *args):
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


def test_models_json_lists_the_contract_names(capsys):
    code, out, err = run(capsys, "models", "--json")
    assert code == 0 and err == ""
    data = json.loads(out)
    names = [m["name"] for m in data["models"]]
    assert {"bingham", "bouc_wen_modified", "kamath_wereley_6", "maxwell_neural", "physics"} <= set(names)
    bingham = next(m for m in data["models"] if m["name"] == "bingham")
    assert {"name": "c0", "unit": "N*s/m", "default": 5000.0} in bingham["parameters"]


@pytest.fixture
def bingham_csv(tmp_path):
    t = np.linspace(0, 2, 1001)
    rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    F = get_model("bingham").simulate(rec, {"c0": 4000.0, "f_c": 500.0})
    path = tmp_path / "m.csv"
    write_measurement(path, rec.with_force(F + np.random.default_rng(0).standard_normal(t.size)),
                      units={"displacement": "mm", "force": "kN"})
    return path


def test_identify_json_recovers_bingham(capsys, bingham_csv):
    code, out, err = run(capsys, "identify", str(bingham_csv), "--model", "bingham", "--json")
    assert code == 0, err
    data = json.loads(out)
    assert set(data) == {"model", "esr", "parameters"} and data["model"] == "bingham"
    # 1 N noise on a ~600 N signal: ESR ~ 1 / var(F) ~ 6e-6
    assert data["esr"] < 1e-4
    value, unit = data["parameters"]["c0"].split(" ", 1)
    assert float(value) == pytest.approx(4000.0, rel=0.01) and unit == "N·s/m"


def test_identify_errors_are_one_line(capsys, bingham_csv):
    code, out, err = run(capsys, "identify", str(bingham_csv), "--model", "nope", "--json")
    assert code == 1 and out == "" and err.count("\n") == 1 and "unknown model 'nope'" in err
    code, out, err = run(capsys, "identify", str(bingham_csv), "--model", "lugre_modified", "--json")
    assert code == 1 and "no control column" in err


def test_identify_physics_needs_the_module_or_a_damper(capsys, bingham_csv):
    code, out, err = run(capsys, "identify", str(bingham_csv), "--model", "physics", "--json")
    assert code == 1 and out == ""
    assert "erdesign.physics" in err or "--damper" in err
