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
from erdesign.data.quiroz import QUIROZ_CURRENTS, QUIROZ_TESTS, quiroz_folder, read_quiroz_sinusoid, read_quiroz_validation
from erdesign.identification.identify import identify_joint
from erdesign.models.registry import get_model

ROOT = Path(__file__).resolve().parents[1]
FOLDER = quiroz_folder(ROOT)
pytestmark = pytest.mark.skipif(FOLDER is None, reason="../shared/data/quiroz2022_utfsm_mr is absent (the measured "
                                                         "MR-damper data are not part of the repository)")
STUDY = json.loads((ROOT / "docs" / "case_studies" / "quiroz.json").read_text())


@pytest.fixture(scope="module")
def training():
    return [read_quiroz_sinusoid(FOLDER, test, i) for test, _ in QUIROZ_TESTS for i in QUIROZ_CURRENTS]


def _make_script():
    spec = importlib.util.spec_from_file_location("make_real_data",
                                                  ROOT / "docs" / "case_studies" / "make_real_data.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_doc_is_the_rendering_of_the_study():
    # the Markdown is generated from the JSON, never edited by hand
    # (the generated part ends where the hand-written command-line study of Dyke's record begins)
    assert (ROOT / "docs" / "case_studies" / "quiroz.md").read_text().split("\n<!-- dyke-cli -->")[0] == \
        _make_script().render(STUDY).rstrip("\n") + ("\n" if _make_script().render(STUDY).endswith("\n") else "")


def test_documented_training_esrs_reproduce(training):
    for name, d in STUDY["models"].items():
        model = get_model(name)
        for rec in training:
            # same data, same parameters, same deterministic simulation: equal to round-off
            assert esr(rec.force, model.simulate(rec, d["values"])) == pytest.approx(d["training_esr"][rec.name],
                                                                                  rel=1e-9, abs=1e-12), (name, rec.name)


def test_documented_validation_esrs_reproduce():
    validation = read_quiroz_validation(FOLDER, step=2)
    for name, d in STUDY["models"].items():
        model = get_model(name)
        for rec in validation:
            assert esr(rec.force, model.simulate(rec, d["values"])) == pytest.approx(d["validation_esr"][rec.name],
                                                                                  rel=1e-9, abs=1e-12), (name, rec.name)


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
