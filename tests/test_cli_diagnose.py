"""``erdesign diagnose`` and ``erdesign fit``: exactly the JSON keys of docs/cli.md, readable reports,
one-line errors."""

import json
import math

import pytest

import erdesign.cli.diagnose
import erdesign.cli.fit  # noqa: F401
from erdesign import load_example
from erdesign.cli.main import main
from erdesign.data.measurement import write_measurement
from erdesign.simulation.rig import run_rig, stepped_sine

ROOT = __import__("pathlib").Path(__file__).resolve().parents[1]
MAKRIS = str(ROOT / "erdesign" / "examples" / "makris.toml")
MR = str(ROOT / "erdesign" / "examples" / "mr_mixed.toml")


@pytest.fixture(scope="module")
def friction_csv(tmp_path_factory):
    d = load_example("makris")
    motion = stepped_sine([0.004, 0.008], [1.0, 2.5], [0.0, 3e6, 1.8e6], cycles=2, rate=300)
    rig = run_rig(
        d,
        motion,
        hidden={"seal_friction": {"friction_force": 800.0}},
        viscosity_factor=1.2,
        yield_stress_factor=0.8,
        seed=1,
    )
    path = tmp_path_factory.mktemp("m") / "friction.csv"
    write_measurement(
        path, rig.record, units={"displacement": "in", "force": "lbf", "field": "kV/mm"}, comment=rig.comment
    )
    return str(path)


def run(capsys, *args):
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


#: Keys of ``erdesign diagnose --json`` (docs/cli.md).
CONTRACT_KEYS = {
    "baseline_esr",
    "ranking",
    "missing_effect",
    "verdict",
    "noise_floor_esr",
    "noise_floor_method",
    "findings",
    "records",
    "missing_effects",
}
VERDICTS = {"missing_effect", "nothing_missing", "unexplained"}


def _no_constant(name):
    raise AssertionError(f"{name} in the JSON output")


def strict_json(out: str) -> dict:
    """Exactly one JSON object, with no NaN, Infinity or -Infinity anywhere."""
    return json.loads(out, parse_constant=_no_constant)


def check_contract(data: dict) -> None:
    assert set(data) == CONTRACT_KEYS
    assert data["verdict"] in VERDICTS
    assert (data["missing_effect"] is not None) == (data["verdict"] == "missing_effect")
    # CONTRACTS.md section 6: the effects to add next as a list (a pair whole), the first is missing_effect
    assert data["missing_effects"][:1] == ([data["missing_effect"]] if data["missing_effect"] else [])
    assert len(data["missing_effects"]) <= 2
    assert isinstance(data["noise_floor_method"], str) and data["noise_floor_method"]
    for f in data["findings"]:
        assert {"kind", "message", "record", "where"} <= set(f)
    assert data["records"] and all({"name", "samples", "esr"} == set(r) for r in data["records"])
    assert isinstance(data["noise_floor_esr"], float) and math.isfinite(data["noise_floor_esr"])
    assert isinstance(data["baseline_esr"], float) and math.isfinite(data["baseline_esr"])
    for r in data["ranking"]:
        assert {"effect", "esr", "parameters"} <= set(r) <= {"effect", "esr", "parameters", "reason", "effects"}
        if r["esr"] is None:
            assert r["reason"], r  # a candidate that could not be evaluated says why
        else:
            assert isinstance(r["esr"], float) and math.isfinite(r["esr"])


def test_diagnose_json_has_exactly_the_contract_keys(capsys, friction_csv):
    code, out, err = run(capsys, "diagnose", friction_csv, "--damper", MAKRIS, "--json")
    assert code == 0, err
    data = strict_json(out)  # exactly one JSON object on stdout
    check_contract(data)
    assert data["verdict"] == "missing_effect"
    assert data["missing_effect"] == "seal_friction"
    assert [r["effect"] for r in data["ranking"]][0] == "seal_friction"
    # the friction explains the record down to its noise: the named model at the floor (a fitted model may leave a
    # little less than the noise, by k/n), the baseline far above it
    assert 0 < data["noise_floor_esr"] < data["baseline_esr"] / 10
    assert 0.5 * data["noise_floor_esr"] < data["ranking"][0]["esr"] < 2 * data["noise_floor_esr"]
    # the friction in N with its unit: 800 N hidden, noise 0.5 % of the RMS force -> within 3 %
    value, unit = data["ranking"][0]["parameters"]["friction_force"].split()
    assert unit == "N" and float(value) == pytest.approx(800.0, rel=0.03)
    assert data["ranking"][0]["esr"] < data["baseline_esr"] / 3


@pytest.fixture(scope="module")
def truth_csvs(tmp_path_factory):
    """Records of the truth rig on the Makris damper (physics independent of the diagnosed model): nothing hidden,
    and a rebound blow-off valve (outside the effect library)."""
    from erdesign.simulation.truthrig import TruthDamper, simulate_truth

    folder = tmp_path_factory.mktemp("truth")
    motion = stepped_sine([0.01], [1.0], [3e6, 1.5e6], cycles=2, rate=100)
    return {
        name: str(
            simulate_truth(TruthDamper(load_example("makris"), mechanisms), motion, seed=1, name=name).write(
                folder / f"{name}.csv"
            )
        )
        for name, mechanisms in (("clean", {}), ("blowoff", {"blowoff": {}}))
    }


@pytest.fixture
def two_candidates(monkeypatch):
    """The command judging two candidates only (fast; the ranking itself is tests/test_diagnose.py's), with
    ``seal_friction`` shown as not evaluated: the JSON must carry a null ESR and the reason."""
    real = erdesign.cli.diagnose.run_diagnosis

    def diagnose(damper, record, effects=(), **options):
        d = real(damper, record, effects, candidates=("gas_spring", "seal_friction"), **options)
        for c in d.ranking:
            if c.effect == "seal_friction":
                c.result, c.esr, c.reason = None, None, "could not be evaluated: a test says so"
        return d

    monkeypatch.setattr(erdesign.cli.diagnose, "run_diagnosis", diagnose)


@pytest.mark.parametrize("record, verdict", [("clean", "nothing_missing"), ("blowoff", "unexplained")])
def test_diagnose_json_verdicts_exit_0(capsys, truth_csvs, two_candidates, record, verdict):
    code, out, err = run(capsys, "diagnose", truth_csvs[record], "--damper", MAKRIS, "--json")
    assert code == 0, err
    data = strict_json(out)
    check_contract(data)
    assert data["verdict"] == verdict and data["missing_effect"] is None
    (spoiled,) = [r for r in data["ranking"] if r["effect"] == "seal_friction"]
    assert spoiled["esr"] is None and spoiled["reason"] == "could not be evaluated: a test says so"
    if verdict == "unexplained":
        # a one-sided relief valve leaves far more than erdesign.diagnosis.diagnose.WELL_ABOVE x the noise floor
        assert data["baseline_esr"] > 10 * data["noise_floor_esr"]
    code, out, _ = run(capsys, "diagnose", truth_csvs[record], "--damper", MAKRIS)
    assert code == 0
    assert f"verdict: {verdict.replace('_', ' ')}: " in out
    if verdict == "unexplained":
        assert "outside the effect library" in out
    assert "seal_friction        not evaluated: could not be evaluated: a test says so" in out


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
    assert float(data["parameters"]["viscosity_factor"]) == pytest.approx(1.2, rel=0.01)  # the true fluid
    code, out, _ = run(capsys, "fit", friction_csv, "--damper", MAKRIS)
    assert code == 0 and "ESR" in out and "viscosity_factor" in out


@pytest.mark.parametrize(
    "args, message",
    [
        (["--damper", MAKRIS, "--effects", "seal_friction,stiction"], "unknown effect 'stiction'"),
        (["--damper", MR], "electric field (V/m) but the damper file's reference_field is a magnetic field"),
    ],
)
@pytest.mark.parametrize("command", ["diagnose", "fit"])
def test_errors_are_one_line_on_stderr(capsys, friction_csv, command, args, message):
    code, out, err = run(capsys, command, friction_csv, *args, "--json")
    assert code == 1 and out == ""
    assert err.count("\n") == 1 and message in err and "Traceback" not in err


def test_record_too_short_is_one_line(capsys, tmp_path):
    d = load_example("makris")
    from erdesign.simulation.rig import sine

    rig = run_rig(d, sine(0.005, 2.0, 3e6, cycles=2, rate=300), seed=1)
    p = tmp_path / "short.csv"
    write_measurement(p, rig.record)
    code, out, err = run(capsys, "diagnose", str(p), "--damper", MAKRIS, "--effects", "field_lag")
    assert code == 1 and "field_lag: cannot be judged" in err and "field never changes" in err
    assert err.count("\n") == 1


def test_diagnose_text_ends_with_the_next_command(capsys, friction_csv):
    """Issue 14: after a missing effect the text report prints the command that adds it; the JSON is unchanged."""
    code, out, _ = run(capsys, "diagnose", friction_csv, "--damper", MAKRIS)
    assert code == 0
    last = out.strip().splitlines()[-1].strip()
    assert last == f"erdesign diagnose {friction_csv} --damper {MAKRIS} --effects seal_friction"
    # run it: the effect is in the model now, and the verdict no longer names it
    code, out, _ = run(capsys, *last.split()[1:], "--json")
    assert code == 0
    data = strict_json(out)
    check_contract(data)
    assert data["missing_effect"] != "seal_friction"


def test_fit_says_when_a_parameter_ends_at_a_bound(capsys):
    # the record hides friction and a slug, no gas spring: a gas spring fitted to it has nothing to hold its stiffness
    # off zero (its lower bound), and the command says so on stderr; the friction effect alone does not
    csv = ROOT / "erdesign" / "examples" / "measurements" / "makris_two_hidden_effects.csv"
    damper = ROOT / "erdesign" / "examples" / "makris.toml"
    code, out, err = run(capsys, "fit", str(csv), "--damper", str(damper), "--effects", "gas_spring", "--json")
    assert code == 0, err
    assert set(json.loads(out)) == {"esr", "parameters"}  # the contract's keys, nothing more
    assert "warning: the fit ends at a bound: gas_stiffness at its lower bound" in err
    code, out, err = run(capsys, "fit", str(csv), "--damper", str(damper), "--effects", "seal_friction", "--json")
    assert code == 0 and "bound" not in err
