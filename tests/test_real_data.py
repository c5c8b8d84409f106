"""The real-data study (docs/case_studies/quiroz.md): measured MR-damper sinusoids at five coil currents (Quiroz 2022).

The data live in ../shared/data relative to the repository root (present in CI, absent in a fresh clone: then
every test here skips).  The doc is written by docs/case_studies/make_real_data.py from docs/case_studies/quiroz.json;
these tests re-compute its ESRs from the documented parameters and re-run the cheap joint identification (Bingham).
"""

import importlib.util
import json
from pathlib import Path

import numpy as np
import pytest

from erdesign.case_studies.quiroz import QUIROZ_STUDY_MODELS
from erdesign.data.metrics import esr
from erdesign.data.quiroz import (
    QUIROZ_CURRENTS,
    QUIROZ_TESTS,
    quiroz_folder,
    read_quiroz_sinusoid,
    read_quiroz_validation,
)
from erdesign.identification.identify import identify_joint
from erdesign.models.registry import get_model

ROOT = Path(__file__).resolve().parents[1]
FOLDER = quiroz_folder(ROOT)
pytestmark = pytest.mark.skipif(
    FOLDER is None,
    reason="../shared/data/quiroz2022_utfsm_mr is absent (the measured MR-damper data are not part of the repository)",
)
STUDY = json.loads((ROOT / "docs" / "case_studies" / "quiroz.json").read_text())


@pytest.fixture(scope="module")
def training():
    return [read_quiroz_sinusoid(FOLDER, test, i) for test, _ in QUIROZ_TESTS for i in QUIROZ_CURRENTS]


def _make_script():
    spec = importlib.util.spec_from_file_location(
        "make_real_data", ROOT / "docs" / "case_studies" / "make_real_data.py"
    )
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_doc_is_the_rendering_of_the_study():
    # the Markdown is generated from the JSON, never edited by hand
    # (the generated part ends where the hand-written command-line study of Dyke's record begins)
    assert (ROOT / "docs" / "case_studies" / "quiroz.md").read_text().split("\n<!-- dyke-cli -->")[
        0
    ] == _make_script().render(STUDY).rstrip("\n") + ("\n" if _make_script().render(STUDY).endswith("\n") else "")


def test_documented_training_esrs_reproduce(training):
    for name, d in STUDY["models"].items():
        model = get_model(name)
        for rec in training:
            # same data, same parameters, same deterministic simulation: equal to round-off
            assert esr(rec.force, model.simulate(rec, d["values"])) == pytest.approx(
                d["training_esr"][rec.name], rel=1e-9, abs=1e-12
            ), (name, rec.name)


def test_documented_validation_esrs_reproduce():
    validation = read_quiroz_validation(FOLDER, step=2)
    for name, d in STUDY["models"].items():
        model = get_model(name)
        for rec in validation:
            assert esr(rec.force, model.simulate(rec, d["values"])) == pytest.approx(
                d["validation_esr"][rec.name], rel=1e-9, abs=1e-12
            ), (name, rec.name)


def test_bingham_joint_identification_reproduces_the_doc(training):
    res = identify_joint(get_model("bingham"), training, fixed=QUIROZ_STUDY_MODELS["bingham"])
    doc = STUDY["models"]["bingham"]
    for k, v in doc["values"].items():
        # a deterministic trust-region run from the same start: same optimum to the solver's tolerance (the
        # offset f0 is ~1 N, so an absolute 0.05 N as well)
        assert res.values[k] == pytest.approx(v, rel=1e-4, abs=0.05), k
    assert np.mean(res.esr) == pytest.approx(np.mean(list(doc["training_esr"].values())), rel=1e-4)


def test_findings_of_the_study():
    m = STUDY["models"]
    mean = {n: np.mean(list(d["training_esr"].values())) for n, d in m.items()}
    val = {n: np.mean(list(d["validation_esr"].values())) for n, d in m.items()}
    # The hysteretic models explain the measured loops better than the rigid-plastic Bingham model, on the
    # training sinusoids and, more so, on the unseen earthquake-type record (measured: 0.019 / 0.036 / 0.074
    # training, 0.06 / 0.17 / 0.43 validation)
    assert mean["bouc_wen_modified"] < mean["kwok_tanh"] < mean["bingham"]
    assert val["bouc_wen_modified"] < val["kwok_tanh"] < val["bingham"]
    # The modified Bouc-Wen generalises: validation ESR below 0.15 at every current (measured 0.03-0.11)
    assert max(m["bouc_wen_modified"]["validation_esr"].values()) < 0.15
    # its viscous coefficient c0 grows with current like the source's own fit (c0 = 925 + 7626 i N s/m):
    # within 30 % at 1 A (measured 9.6 vs 8.6 kN s/m)
    v = m["bouc_wen_modified"]["values"]
    assert v["c0a"] + v["c0b"] == pytest.approx(925.0 + 7626.0, rel=0.3)


def test_source_parameters_with_the_hidden_constants():
    src = list(STUDY["source"].values())
    plain, estimated = src[0], src[1]
    mean = {k: np.mean(list(d["validation_esr"].values())) for k, d in (("plain", plain), ("est", estimated))}
    # the source's twelve published parameters with A = 1, beta = gamma do not reproduce the force (measured
    # validation ESR 0.77); with only A and beta/gamma estimated they do about as well as our joint fit
    # (measured 0.064 vs 0.066): evidence that A of order 100 sits in the source's Simulink model.  The two are
    # poorly determined: with the Heun kernel of the modified Bouc-Wen model (0.3 % of the force range) the
    # estimate was A = 95.5, beta = -0.34 gamma; with the compiled RK4 kernel (4e-6) another basin wins,
    # A = 179, beta = 0.14 gamma (training ESR 0.022 against 0.036), so only the order of A is asserted
    assert mean["plain"] > 0.5
    assert mean["est"] < 0.1
    assert 50.0 < estimated["A"] < 300.0


# ------------------------------------------------------------------ raw records, the source's smoothing
def test_raw_records_force_levels():
    # the six raw DAQ files give five records each, in rising current order: the force's peak-to-peak grows
    # record by record in every file (measured at 10 mm 2 Hz: 494, 1125, 1927, 2634, 3178 N)
    from erdesign.data.quiroz import QUIROZ_RAW_TESTS, read_quiroz_raw

    for test, freq, _ in QUIROZ_RAW_TESTS:
        recs = read_quiroz_raw(FOLDER, test)
        assert [float(r.control[0]) for r in recs] == list(QUIROZ_CURRENTS)
        ptp = [float(np.ptp(r.force)) for r in recs]
        assert all(b > a for a, b in zip(ptp, ptp[1:])), (test, ptp)
        # the last 3 periods at the file's own rate (1 ms, or 5 ms where the channels are swapped)
        assert recs[0].time[-1] == pytest.approx(3.0 / freq, abs=0.01)
    ptp = [float(np.ptp(r.force)) for r in read_quiroz_raw(FOLDER, "10mm2Hz")]
    assert ptp == pytest.approx([494, 1125, 1927, 2634, 3178], abs=1.0)


def test_equivalent_damper_file_matches_the_measured_force_levels():
    # examples/quiroz2022.toml: the quasi-steady force at each raw test's peak speed against the measured mean |F|
    # there (|v| > 90 % of the peak): 0.79-0.96 x at 0 A (friction-dominated, the peaks of the measured force
    # sit above it) and 1.01-1.08 x at 1 A
    from erdesign.damper.files import load_example
    from erdesign.data.quiroz import QUIROZ_RAW_TESTS, read_quiroz_raw

    damper = load_example("quiroz2022")
    ratios = {0.0: [], 1.0: []}
    for test, _, _ in QUIROZ_RAW_TESTS:
        recs = read_quiroz_raw(FOLDER, test)
        for r in (recs[0], recs[-1]):
            fast = np.abs(r.velocity) > 0.9 * np.max(np.abs(r.velocity))
            speed = float(np.mean(np.abs(r.velocity[fast])))
            current = float(r.control[0])
            model = damper.size(f"{speed} m/s", f"{current} A").force.m
            ratios[current].append(model / float(np.mean(np.abs(r.force[fast]))))
    assert 0.75 < min(ratios[0.0]) and max(ratios[0.0]) < 1.0
    assert 0.98 < min(ratios[1.0]) and max(ratios[1.0]) < 1.1


def test_undoing_the_sources_moving_average():
    # the validation record's displacement, un-smoothed and smoothed again, is the stored one (round-off), and its
    # range widens as an average's undoing must (stored -7.95..6.66 mm; before the average -8.80..7.22 mm)
    from erdesign.data.quiroz import (
        QUIROZ_VALIDATION_WINDOW,
        causal_moving_average,
        read_quiroz_validation_unsmoothed,
        undo_causal_moving_average,
    )

    stored = read_quiroz_validation(FOLDER, step=1)[0].displacement
    x = undo_causal_moving_average(stored, QUIROZ_VALIDATION_WINDOW)
    again = causal_moving_average(np.r_[np.full(QUIROZ_VALIDATION_WINDOW, x[0]), x], QUIROZ_VALIDATION_WINDOW)[
        QUIROZ_VALIDATION_WINDOW:
    ]
    assert np.max(np.abs(again - stored)) < 1e-12
    assert (x.min(), x.max()) == pytest.approx((-8.797e-3, 7.225e-3), abs=2e-6)
    assert np.array_equal(read_quiroz_validation_unsmoothed(FOLDER)[0].displacement, x)


# ------------------------------------------------------------------ the physics model of the equivalent damper file
PHYSICS = STUDY.get("physics")


@pytest.mark.slow
@pytest.mark.skipif(PHYSICS is None, reason="docs/case_studies/quiroz.json has no physics-model section")
def test_documented_physics_validation_esrs_reproduce():
    # the physics model of examples/quiroz2022.toml with the documented effects and values, simulated on the
    # validation record both ways (direct; through the source's 300-sample smoothing): the documented ESRs
    from erdesign.case_studies.quiroz import physics_validation_esr
    from erdesign.damper.files import load_example
    from erdesign.effects.chain import PhysicsDamper

    damper = load_example(PHYSICS["damper"])
    for label, d in PHYSICS["models"].items():
        got = physics_validation_esr(PhysicsDamper(damper, tuple(d["effects"])), d["values"], FOLDER)
        for how, per_current in d["validation_esr"].items():
            for name, value in per_current.items():
                assert got[how][name] == pytest.approx(value, rel=1e-6, abs=1e-9), (label, how, name)


@pytest.mark.skipif(PHYSICS is None, reason="docs/case_studies/quiroz.json has no physics-model section")
def test_findings_of_the_physics_model():
    def mean(val):
        return float(np.mean(list(val.values())))

    bw_doc = mean(STUDY["models"]["bouc_wen_modified"]["validation_esr"])  # 0.066
    bw_raw = mean(PHYSICS["bouc_wen_modified_raw"]["validation_esr"]["through_smoothing"])  # 0.037
    models = {k: mean(d["validation_esr"]["through_smoothing"]) for k, d in PHYSICS["models"].items()}
    rounds = PHYSICS["rounds"]
    # the loop names pre-yield elasticity first (ESR 0.087 -> 0.012 on the 30 raw records), then stops
    # `unexplained`: leakage, ranked first, lowers the training ESR by a fifth but explains too little of the excess
    assert rounds[0]["missing_effects"] == ["preyield_elasticity"]
    assert rounds[-1]["verdict"] == "unexplained"
    assert rounds[-1]["ranking"][0]["esr"] < 0.9 * rounds[-1]["esr"]
    # issue 23: the loop's own model predicts the validation record within 1.5 x the Bouc-Wen of the first table
    # (measured 0.0986 against 0.099), and with the candidates it ranked first it does better (0.084)
    assert models["loop"] <= 1.5 * bw_doc
    assert min(models.values()) < models["loop"]
    # but the modified Bouc-Wen fitted on the same raw records and judged the same way stays better (0.037)
    assert bw_raw < min(models.values()) / 2
    # judged directly on the smoothed record, models fitted on raw records are far off (the 0.3 s average)
    assert min(mean(d["validation_esr"]["direct"]) for d in PHYSICS["models"].values()) > 0.3
