"""Fitting machinery (erdesign.identification.fit) on a model whose answer is known: round trips, uncertainties,
criteria."""

import math

import numpy as np
import pytest

from erdesign.data.measurement import Measurement
from erdesign.identification.fit import FitError, fit
from erdesign.models.base import Model, Parameter, ParameterError


class DashpotFriction(Model):
    """F = c v + f sgn(v) + k x: linear in its parameters, so least squares has a unique, known answer."""

    name = "test_dashpot"
    title = "dashpot with friction (test)"
    source = "test"
    parameters = (
        Parameter("c", "N*s/m", 1000.0, 0.0, 1e7, "damping", log_scale=False),
        Parameter("f", "N", 10.0, 0.0, 1e5, "friction"),
        Parameter("k", "N/m", 100.0, 0.0, 1e7, "stiffness"),
    )

    def force(self, record, values):
        return (
            values["c"] * record.velocity
            + values["f"] * np.tanh(record.velocity / 1e-3)
            + values["k"] * record.displacement
        )


def record(noise=5.0, seed=0, f_hz=1.5):
    t = np.linspace(0, 4 / f_hz, 4001)
    x = 0.01 * np.sin(2 * np.pi * f_hz * t)
    m = Measurement.from_arrays(t, x)
    true = {"c": 5000.0, "f": 120.0, "k": 2.0e4}
    F = DashpotFriction().force(m, true)
    rng = np.random.default_rng(seed)
    return m.with_force(F + noise * rng.standard_normal(t.size)), true


def test_round_trip_recovers_parameters_within_their_standard_errors():
    m, true = record()
    r = fit(DashpotFriction(), m, starts=3)
    for name, v in true.items():
        # Unbiased estimator: within 4 standard errors (false alarm ~6e-5 per parameter).
        assert abs(r.values[name] - v) < 4 * r.stderr[name]
        assert r.stderr[name] < 0.02 * v
    # ESR at the noise floor: noise variance / force variance.
    assert r.esr == pytest.approx(25.0 / np.var(m.force), rel=0.15)
    assert r.success


def test_standard_errors_match_monte_carlo_scatter():
    # The covariance s^2 (J^T J)^-1 must describe the scatter of repeated fits on new noise (within 35 % for 30 runs).
    fits = [fit(DashpotFriction(), record(noise=20.0, seed=s)[0]) for s in range(30)]
    scatter = np.std([f.values["f"] for f in fits], ddof=1)
    predicted = np.mean([f.stderr["f"] for f in fits])
    assert scatter == pytest.approx(predicted, rel=0.35)


def test_fixed_parameters_stay_and_aic_prefers_the_true_model():
    m, true = record()
    full = fit(DashpotFriction(), m)
    no_friction = fit(DashpotFriction(), m, fixed={"f": 0.0})
    assert no_friction.values["f"] == 0.0 and no_friction.k == 2
    assert full.aic < no_friction.aic - 10 and full.bic < no_friction.bic - 10
    # A parameter the data do not need (here: friction when the truth has none) must not win by BIC.
    m0 = m.with_force(
        DashpotFriction().force(m, {**true, "f": 0.0}) + 5.0 * np.random.default_rng(1).standard_normal(len(m))
    )
    assert fit(DashpotFriction(), m0).bic > fit(DashpotFriction(), m0, fixed={"f": 0.0}).bic - 2 * math.log(len(m))


def test_validation_on_a_held_out_record():
    train, _ = record(seed=0)
    test, _ = record(seed=9, f_hz=3.0)
    r = fit(DashpotFriction(), train)
    assert r.validate(test) < 2 * 25.0 / np.var(test.force) + 1e-4


def test_bad_setups_are_clear_errors():
    m, _ = record()
    with pytest.raises(ParameterError, match="no parameter 'q'"):
        fit(DashpotFriction(), m, fixed={"q": 1.0})
    with pytest.raises(FitError, match="no free parameter"):
        fit(DashpotFriction(), m, fixed={"c": 1.0, "f": 1.0, "k": 1.0})
    with pytest.raises(ParameterError, match="outside its bounds"):
        DashpotFriction().simulate(m, {"c": -1.0})


def test_report_has_units():
    m, _ = record()
    text = fit(DashpotFriction(), m).report()
    assert "N·s/m" in text and "ESR" in text and "AIC" in text
    assert fit(DashpotFriction(), m).parameters_with_units()["c"].endswith("N·s/m")
