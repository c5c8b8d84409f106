"""Identification workflows (erdesign.identification.identify): one record, several records jointly, cross-validation
tables (in the style of Vivas-López et al., Table 4), and bad input - all by round trip on records whose answer is
known."""

import numpy as np
import pytest

from erdesign.data.measurement import Measurement, MeasurementError
from erdesign.identification.fit import FitError
from erdesign.identification.identify import cross_validation, identify, identify_joint
from erdesign.models.base import ModelInputError, ParameterError
from erdesign.models.registry import get_model

# Bingham with a current-dependent yield force and damping (Butz and von Stryk 2002, eq 1 with Spencer's linear
# control law)
TRUE = {"c0": 3000.0, "f_c": 150.0, "f0": 5.0, "f_c_u": 600.0, "c0_u": 4000.0}


def record(amplitude=0.01, f_hz=1.0, current=None, noise_n=5.0, seed=0, n=401):
    t = np.linspace(0.0, 1.0 / f_hz, n)
    x = amplitude * np.sin(2 * np.pi * f_hz * t)
    kw = {} if current is None else {"control": current, "control_kind": "current"}
    rec = Measurement.from_arrays(t, x, **kw, name=f"{amplitude * 1e3:g} mm {f_hz:g} Hz {current} A")
    clean = get_model("bingham").simulate(
        rec, TRUE if current is not None else {k: TRUE[k] for k in ("c0", "f_c", "f0")}
    )
    return rec.with_force(clean + noise_n * np.random.default_rng(seed).standard_normal(n))


def test_identify_round_trip_single_record():
    rec = record(current=0.5)
    r = identify(get_model("bingham"), rec, starts=1)
    # one current: only the coefficients at that current are seen, c0 + 0.5 c0_u and f_c + 0.5 f_c_u
    assert r.values["c0"] + 0.5 * r.values["c0_u"] == pytest.approx(3000 + 0.5 * 4000, rel=0.01)
    assert r.values["f_c"] + 0.5 * r.values["f_c_u"] == pytest.approx(150 + 0.5 * 600, rel=0.01)
    # ESR at the noise floor (5 N white noise): within 20 % for 400 samples (chi-square spread ~ 2/sqrt(400))
    assert r.esr == pytest.approx(25.0 / np.var(rec.force), rel=0.2)


def test_the_reference_model_is_not_a_poor_fit_of_itself():
    """Bingham without a control input is the reference fit (c0 v + f_c sgn v + f0) that decides a poor fit: the two
    solutions agree to rounding only, and equal ESRs must not read as "worse than the reference"."""
    from erdesign.identification.engine import worse_than_reference

    for seed in range(6):
        r = identify(get_model("bingham"), record(seed=seed, noise_n=0.5), starts=4)
        assert r.esr == pytest.approx(r.baseline_esr, rel=1e-6)
        assert r.success and not r.poor_fit and not any("poor fit" in w for w in r.warnings), seed
    assert worse_than_reference(1.0 + 1e-6, 1.0) and not worse_than_reference(1.0 + 1e-12, 1.0)


def test_identify_joint_recovers_current_dependence():
    recs = [record(current=i, seed=k) for k, i in enumerate((0.0, 0.5, 1.0))]
    res = identify_joint(get_model("bingham"), recs)
    assert res.success and res.names == [r.name for r in recs]
    for k in ("c0", "f_c", "f_c_u", "c0_u"):
        # 1200 samples with 5 N noise on forces of 150-1000 N: the slopes are known to well under 2 %
        assert res.values[k] == pytest.approx(TRUE[k], rel=0.02), k
    for r, e in zip(recs, res.record_esr):
        # every record at its own noise floor (within 25 %: 400 samples each)
        assert e == pytest.approx(25.0 / np.var(r.force), rel=0.25)
    assert res.esr == pytest.approx(np.mean(res.record_esr))  # a FitResult: its ESR is the records' mean


def test_identify_joint_without_control_holds_the_slopes():
    recs = [record(amplitude=a, seed=k) for k, a in enumerate((0.005, 0.01))]
    res = identify_joint(get_model("bingham"), recs)
    # no control column: the current-dependent coefficients are identified as constants (slopes held at 0)
    assert res.values["f_c_u"] == 0.0 and res.values["c0_u"] == 0.0
    assert res.values["c0"] == pytest.approx(3000.0, rel=0.02)
    assert res.values["f_c"] == pytest.approx(150.0, rel=0.03)


def test_cross_validation_table():
    """Vivas-López et al. Table 4: identify on each experiment, score on every other; a right model generalises, so every
    entry is near the noise floor of its validation record, and the diagonal is the identification ESR."""
    recs = [record(amplitude=a, f_hz=f, seed=k) for k, (a, f) in enumerate(((0.005, 1.0), (0.01, 1.0), (0.01, 2.0)))]
    cv = cross_validation(lambda: get_model("bingham"), recs, starts=1)
    assert cv.table.shape == (3, 3)
    floors = np.array([25.0 / np.var(r.force) for r in recs])
    # off-diagonal entries of a correct model: within 40 % of the floor (extrapolation adds parameter error)
    assert np.all(np.abs(cv.table / floors[:, None] - 1.0) < 0.4)
    assert cv.average == pytest.approx(cv.table.mean(axis=0))
    md = cv.markdown()
    assert md.count("\n") == len(recs) + 2 and "average" in md
    # a wrong model (a pure dashpot: Maxwell with a stiff spring) fitted at small amplitude fails at large
    # amplitude, where the yield force is a smaller part of the force: the table shows it
    cv_bad = cross_validation(lambda: get_model("maxwell"), recs[:2], starts=1)
    assert cv_bad.table[1, 0] > 10 * floors[1]


def test_bad_input_is_named():
    ok = record()
    with pytest.raises(FitError, match="no records"):
        identify_joint(get_model("bingham"), [])
    with pytest.raises(MeasurementError, match="at least 5 samples, got 4"):
        Measurement.from_arrays(np.linspace(0, 1, 4), np.linspace(0, 1e-3, 4), np.zeros(4))
    short = Measurement.from_arrays(np.linspace(0, 1, 5), np.linspace(0, 1e-3, 5), np.zeros(5))
    # Kwok without a control column has six free parameters
    with pytest.raises(FitError, match="5 samples cannot determine 6 parameters"):
        identify(get_model("kwok_tanh"), short)
    with pytest.raises(FitError, match="5 samples cannot determine 6 parameters"):
        identify_joint(get_model("kwok_tanh"), [short])
    strict = get_model("bingham")
    strict.min_samples = 10
    with pytest.raises(ModelInputError, match="5 samples; this model needs at least 10"):
        identify_joint(strict, [ok, short])
    # a model whose force needs the control, on a record without a control column
    with pytest.raises(ModelInputError, match="no control column"):
        identify(get_model("lugre_modified"), ok)
    with pytest.raises(ModelInputError, match="no control column"):
        identify_joint(get_model("lugre_modified"), [ok])
    with pytest.raises(MeasurementError, match="no force column"):
        identify_joint(get_model("bingham"), [Measurement.from_arrays(ok.time, ok.displacement)])
    # parameters out of bounds, or unknown
    with pytest.raises(ParameterError, match="c0 = -5.0 N\\*s/m is outside its bounds"):
        identify(get_model("bingham"), ok, start={"c0": -5.0})
    with pytest.raises(ParameterError, match="c0 = -5.0 N\\*s/m is outside its bounds"):
        identify_joint(get_model("bingham"), [ok], fixed={"c0": -5.0})
    with pytest.raises(ParameterError, match="no parameter 'nope'"):
        identify(get_model("bingham"), ok, fixed={"nope": 1.0})
