"""Newtonian flow: thin-gap (Makris eq 4) and exact annulus (Bird, Stewart and Lightfoot eq 2.4-17)."""

import math

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import quad

from erdesign.flow import (
    annulus_conductance_ratio,
    annulus_flow_rate,
    slit_flow_rate,
    slit_pressure_drop,
    thin_gap_error,
)


def _annulus_flow_by_quadrature(dp, eta, L, R1, R2):
    """Independent: integrate the exact annulus velocity profile 2 pi r u(r) numerically."""
    G = dp / L
    c = (R2**2 - R1**2) / math.log(R2 / R1)

    def u(r):
        return G / (4 * eta) * (R2**2 - r**2 - c * math.log(R2 / r))

    return quad(lambda r: 2 * math.pi * r * u(r), R1, R2, epsabs=0, epsrel=1e-13)[0]


@pytest.mark.parametrize("h_over_d", [0.02, 0.056, 0.2, 0.5, 0.9])
def test_exact_annulus_matches_quadrature_of_its_profile(h_over_d):
    d, L, eta, dp = 0.0143, 0.0546, 7.0, 1e5
    h = h_over_d * d
    expected = _annulus_flow_by_quadrature(dp, eta, L, (d - h) / 2, (d + h) / 2)
    # quad to 1e-13; the closed form loses a few digits to cancellation at small h/d: 1e-9 is ample.
    assert annulus_flow_rate(dp, eta, L, d, h) == pytest.approx(expected, rel=1e-9)


def test_conductance_ratio_series_derived_with_sympy():
    e = sp.symbols("e", positive=True)
    exact = sp.Rational(3, 2) / e**3 * (sp.Rational(1, 2) * e * (1 + e**2) - e**2 / (sp.log(1 + e) - sp.log(1 - e)))
    series = sp.series(exact, e, 0, 10).removeO()
    assert (
        sp.simplify(
            series
            - (
                1
                + e**2 / 15
                + sp.Rational(11, 315) * e**4
                + sp.Rational(107, 4725) * e**6
                + sp.Rational(2549, 155925) * e**8
            )
        )
        == 0
    )
    # The kernel uses this series below h/d = 0.05 and the closed form above: on both sides it must match the
    # closed form evaluated in 50-digit arithmetic to 1e-13 (float cancellation costs 4e-14 at h/d = 0.05).
    for value in (1e-4, 0.01, 0.0499999, 0.0500001, 0.2, 0.9):
        reference = float(exact.subs(e, sp.Float(value, 50)).evalf(50))
        assert annulus_conductance_ratio(1.0, value) == pytest.approx(reference, abs=1e-13)


def test_thin_gap_error_grows_as_h_over_d_squared_over_15():
    # Leading term of the series above: (h/d)^2/15; for Makris's duct (h/d = 0.056) the slit is 0.021 % high.
    assert thin_gap_error(0.8 / 14.3) == pytest.approx((0.8 / 14.3) ** 2 / 15, rel=2e-3)
    assert thin_gap_error(0.5) == pytest.approx(0.01928, rel=1e-3)  # from the closed form, checked by quadrature
    errs = thin_gap_error(np.array([0.01, 0.1, 0.3, 0.6]))
    assert np.all(np.diff(errs) > 0)


def test_slit_is_inverse_of_itself_and_linear():
    dp = slit_pressure_drop(np.array([-2e-6, 1e-6, 3e-6]), 7.0, 0.0546, 0.0143, 0.0008)
    np.testing.assert_allclose(slit_flow_rate(dp, 7.0, 0.0546, 0.0143, 0.0008), [-2e-6, 1e-6, 3e-6], rtol=1e-14)
    assert dp[2] == pytest.approx(3 * dp[1]) and dp[0] == pytest.approx(-2 * dp[1])


def test_slit_is_limit_of_exact_annulus():
    # As h/d -> 0 the annulus collapses to parallel plates (Makris, after eq 2).
    for e in (1e-2, 1e-3):
        ratio = annulus_flow_rate(1.0, 1.0, 1.0, 1.0, e) / slit_flow_rate(1.0, 1.0, 1.0, 1.0, e)
        assert ratio == pytest.approx(1.0, abs=e**2 / 14)
