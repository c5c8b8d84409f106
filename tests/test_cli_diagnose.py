"""``erdesign diagnose`` and ``erdesign fit``: exactly the JSON keys of shared/CONTRACTS.md, readable reports,
one-line errors."""

import json

import pytest

import erdesign.cli.diagnose
import erdesign.cli.fit  # noqa: F401
from erdesign import load_example
from erdesign.cli.main import main
from erdesign.measurement import write_measurement
from erdesign.rig import run_rig, sweep

ROOT = __import__("pathlib").Path(__file__).resolve().parents[1]
MAKRIS = str(ROOT / "examples" / "makris.toml")
MR = str(ROOT / "examples" / "mr_mixed.toml")


@pytest.fixture(scope="module")
def friction_csv(tmp_path_factory):
    d = load_example("makris")
    motion = sweep([0.004, 0.008], [1.0, 2.5], [0.0, 3e6, 1.8e6], cycles=2, rate=300)
    rig = run_rig(d, motion, hidden={"seal_friction": {"friction_force": 800.0}}, viscosity_factor=1.2,
                  yield_stress_factor=0.8, seed=1)
    path = tmp_path_factory.mktemp("m") / "friction.csv"
    write_measurement(path, rig.record, units={"displacement": "in", "force": "lbf", "field": "kV/mm"},
                      comment=rig.comment)
    return str(path)


def run(capsys, *args):
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


def test_diagnose_json_has_exactly_the_contract_keys(capsys, friction_csv):
    code, out, err = run(capsys, "diagnose", friction_csv, "--damper", MAKRIS, "--json")
    assert code == 0, err
    data = json.loads(out)                         # exactly one JSON object on stdout
    assert set(data) == {"baseline_esr", "ranking", "missing_effect"}
    assert data["missing_effect"] == "seal_friction"
    assert [r["effect"] for r in data["ranking"]][0] == "seal_friction"
    for r in data["ranking"]:
        assert set(r) == {"effect", "esr", "parameters"}
    # the friction in N with its unit: 800 N hidden, noise 0.5 % of the RMS force -> within 3 %
    value, unit = data["ranking"][0]["parameters"]["friction_force"].split()
    assert unit == "N" and float(value) == pytest.approx(800.0, rel=0.03)
    assert data["ranking"][0]["esr"] < data["baseline_esr"] / 3


def test_diagnose_report_is_readable(capsys, friction_csv):
    code, out, _ = run(capsys, "diagnose", friction_csv, "--damper", MAKRIS)
    assert code == 0
    assert "where the model fails" in out and "Coulomb-like" in out and "verdict: missing effect: seal_friction" in out


def test_fit_json_and_report(capsys, friction_csv):
    code, out, err = run(capsys, "fit", friction_csv, "--damper", MAKRIS, "--effects", "seal_friction", "--json")
    assert code == 0, err
    data = json.loads(out)
    assert set(data) == {"esr", "parameters"}
    assert set(data["parameters"]) == {"viscosity_factor", "yield_stress_factor", "friction_force"}
    assert float(data["parameters"]["viscosity_factor"]) == pytest.approx(1.2, rel=0.01)   # the true fluid
    code, out, _ = run(capsys, "fit", friction_csv, "--damper", MAKRIS)
    assert code == 0 and "ESR" in out and "viscosity_factor" in out


@pytest.mark.parametrize("args, message", [
    (["--damper", MAKRIS, "--effects", "seal_friction,stiction"], "unknown effect 'stiction'"),
    (["--damper", MR], "electric field (V/m) but the damper file's reference_field is a magnetic field"),
])
@pytest.mark.parametrize("command", ["diagnose", "fit"])
def test_errors_are_one_line_on_stderr(capsys, friction_csv, command, args, message):
    code, out, err = run(capsys, command, friction_csv, *args, "--json")
    assert code == 1 and out == ""
    assert err.count("\n") == 1 and message in err and "Traceback" not in err


def test_record_too_short_is_one_line(capsys, tmp_path):
    d = load_example("makris")
    from erdesign.rig import sine

    rig = run_rig(d, sine(0.005, 2.0, 3e6, cycles=2, rate=300), seed=1)
    p = tmp_path / "short.csv"
    write_measurement(p, rig.record)
    code, out, err = run(capsys, "diagnose", str(p), "--damper", MAKRIS, "--effects", "field_lag")
    assert code == 1 and "field_lag: cannot be judged" in err and "field never changes" in err
    assert err.count("\n") == 1
