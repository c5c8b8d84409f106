"""Bingham plastic through a thin gap with stationary walls: Makris eqs 5-7, corrected (h^3), closed-form root."""

import math

import numpy as np
import pint
import pytest
import sympy as sp

from erdesign.flow import (
    bingham_flow_rate,
    bingham_number,
    bingham_plug_fraction,
    bingham_pressure_drop,
    bingham_slit_flow,
    slit_pressure_drop,
    yield_pressure_drop,
)
from erdesign.units import Q_

from .conftest import MAKRIS, MAKRIS_AP

DUCT = (MAKRIS["L"], MAKRIS["d"], MAKRIS["h"])


def _derived_flow_rate():
    """Q(dp) of slit flow of a Bingham plastic, derived from the constitutive law (Makris eq 5) with sympy."""
    y, s, G, eta, tau_y, h, L, d, dp = sp.symbols("y s G eta tau_y h L d dp", positive=True)
    y0 = tau_y / G  # plug half-thickness: |tau| = G |y| < tau_y
    # Upper half, y from the centre plane: tau = G y (Makris eq 2 in slit form); eta du/dy = -(G y - tau_y) in the
    # sheared layer, u(h/2) = 0 (no slip).
    u = sp.integrate(-(G * s - tau_y) / eta, (s, h / 2, y))
    q_half = sp.integrate(u, (y, y0, h / 2)) + y0 * u.subs(y, y0)
    Q = (2 * sp.pi * d * q_half).subs(G, dp / L)  # both halves, width pi d
    return sp.simplify(Q), (eta, tau_y, h, L, d, dp)


def test_eq6_with_h_cubed_follows_from_the_bingham_law():
    Q, (eta, tau_y, h, L, d, dp) = _derived_flow_rate()
    x = tau_y * L / (dp * h)
    eq6_corrected = sp.pi * d * h**3 * dp / (12 * eta * L) * (1 - 3 * x + 4 * x**3)
    assert sp.simplify(Q - eq6_corrected) == 0
    # ... and the printed form with h^2 does not (it differs by a factor h):
    eq6_printed = sp.pi * d * h**2 * dp / (12 * eta * L) * (1 - 3 * x + 4 * x**3)
    assert sp.simplify(Q / eq6_printed) == h


def test_corrected_cubic_eq7_is_satisfied_by_the_derived_flow():
    Q, (eta, tau_y, h, L, d, dp) = _derived_flow_rate()
    cubic = dp**3 - (3 * tau_y * L / h + 12 * eta * L * Q / (sp.pi * d * h**3)) * dp**2 + 4 * tau_y**3 * (L / h) ** 3
    assert sp.simplify(sp.expand(cubic)) == 0


def test_printed_eq7_fails_a_pint_dimension_check_and_the_corrected_one_passes():
    tau_y, L, h, d = Q_(1.8, "kPa"), Q_(54.6, "mm"), Q_(0.8, "mm"), Q_(14.3, "mm")
    eta, Q = Q_(13, "Pa*s"), Q_(20, "mL/s")
    with pytest.raises(pint.DimensionalityError):
        3 * tau_y * L / h + 12 * eta * L * Q / (math.pi * d * h**2)  # as printed (Makris eq 7)
    coefficient = 3 * tau_y * L / h + 12 * eta * L * Q / (math.pi * d * h**3)
    assert coefficient.check("[pressure]")


def test_corrected_cubic_reduces_to_eq4_as_tau_y_vanishes():
    dp, dpN, ty, L, h = sp.symbols("dp dp_N tau_y L h", positive=True)
    cubic = dp**3 - (3 * ty * L / h + dpN) * dp**2 + 4 * ty**3 * (L / h) ** 3
    roots = sp.solve(cubic.subs(ty, 0), dp)
    assert max(roots, key=lambda r: r.subs(dpN, 1)) == dpN  # Makris eq 4
    # Numerically: tau_y -> 0 approaches the Newtonian pressure drop; the first-order correction is +3 tau_y L/h /2
    # per unit of dp_y... so the relative gap must shrink in proportion to tau_y.
    Q = 2e-5
    newtonian = slit_pressure_drop(Q, 7.0, *DUCT)
    gaps = [bingham_pressure_drop(Q, ty_, 7.0, *DUCT) / newtonian - 1 for ty_ in (1.0, 1e-3, 1e-6)]
    assert gaps[1] == pytest.approx(gaps[0] * 1e-3, rel=1e-3) and abs(gaps[2]) < 1e-9


@pytest.mark.parametrize("bingham", [1e-3, 0.1, 1.0, 6.0, 60.0, 1e3, 1e5])
def test_closed_form_root_equals_np_roots(bingham):
    L, d, h = DUCT
    tau_y, eta = 1800.0, 13.0
    Q = tau_y * h * math.pi * d * h / (eta * bingham)  # the flow that gives this Bingham number
    assert bingham_number(Q, tau_y, eta, d, h) == pytest.approx(bingham)
    dpN = 12 * eta * L * Q / (math.pi * d * h**3)
    roots = np.roots([1.0, -(3 * tau_y * L / h + dpN), 0.0, 4 * tau_y**3 * (L / h) ** 3])
    real = np.sort(roots[np.abs(roots.imag) < 1e-6 * np.abs(roots).max()].real)
    dp = bingham_pressure_drop(Q, tau_y, eta, L, d, h)
    # np.roots (companion-matrix eigenvalues) is accurate to ~1e-12 relative here; the physical root is the largest.
    assert dp == pytest.approx(real[-1], rel=1e-9)
    # The other positive root lies below the yield pressure drop: a plug thicker than the gap, not physical.
    dp_y = yield_pressure_drop(tau_y, L, h)
    assert dp > dp_y and (len(real) < 3 or real[1] < dp_y)


def test_flow_rate_is_the_inverse_of_pressure_drop():
    Q = np.geomspace(1e-12, 1e-2, 200) * np.where(np.arange(200) % 2, 1, -1)
    dp = bingham_pressure_drop(Q, 1800.0, 13.0, *DUCT)
    # Near the blocked state Q ~ (1 - phi)^2, so an error of 1e-16 in phi becomes 2e-16/(1 - phi) in Q: about
    # 2e-10 at the smallest flow here (1 - phi ~ 1e-6).  That is the conditioning of Q(dp), not an error of dp.
    np.testing.assert_allclose(bingham_flow_rate(dp, 1800.0, 13.0, *DUCT), Q, rtol=5e-10)
    assert np.max(np.abs(bingham_flow_rate(dp[100:], 1800.0, 13.0, *DUCT) / Q[100:] - 1)) < 1e-13


def test_blocked_gap_gives_the_yield_pressure_drop():
    L, d, h = DUCT
    # Q = 0: the gap is blocked; the break-away pressure drop is 2 tau_y L / h (Makris eq 2 with |tau| = tau_y at
    # both walls), 245.7 kPa for the Makris duct at 3 kV/mm.
    r = bingham_slit_flow(0.0, 1800.0, 13.0, L, d, h)
    assert r.pressure_drop == pytest.approx(2 * 1800.0 * L / h) == pytest.approx(245700.0)
    assert r.plug_fraction == 1.0
    assert bingham_pressure_drop(-0.0, 1800.0, 13.0, L, d, h) == -245700.0  # sign from the sign bit
    # Below the yield pressure drop nothing flows.
    assert bingham_flow_rate(np.array([-245699.0, 0.0, 245699.0]), 1800.0, 13.0, L, d, h).tolist() == [0, 0, 0]


def test_plug_fraction_is_yield_over_actual_pressure_drop_and_shrinks_with_flow():
    Q = np.geomspace(1e-9, 1e-3, 50)
    phi = bingham_plug_fraction(Q, 1800.0, 13.0, *DUCT)
    dp = bingham_pressure_drop(Q, 1800.0, 13.0, *DUCT)
    np.testing.assert_allclose(phi, yield_pressure_drop(1800.0, DUCT[0], DUCT[2]) / dp, rtol=1e-12)
    assert np.all(np.diff(phi) < 0) and np.all(np.diff(dp) > 0)
    assert np.all((phi > 0) & (phi < 1))


def test_odd_in_flow_and_broadcasts():
    Q = np.array([[1e-6], [-1e-6], [3e-5]])
    tau_y = np.array([0.0, 500.0, 1800.0, 5000.0])
    dp = bingham_pressure_drop(Q, tau_y, 13.0, *DUCT)
    assert dp.shape == (3, 4)
    np.testing.assert_array_equal(dp[1], -dp[0])


def test_makris_design_point():
    # Makris damper at 1 in/s and 3 kV/mm (tau_y = 1.8 kPa, eta = 13 Pa s): Q = v A_p = 19.73 mL/s.
    # Independent: the largest root of the corrected cubic by np.roots (above) at this point is 7.6744 MPa.
    Q = 0.0254 * MAKRIS_AP
    L, d, h = DUCT
    dpN = 12 * 13.0 * L * Q / (math.pi * d * h**3)
    expected = max(np.roots([1.0, -(3 * 1800.0 * L / h + dpN), 0.0, 4 * 1800.0**3 * (L / h) ** 3]).real)
    assert bingham_pressure_drop(Q, 1800.0, 13.0, L, d, h) == pytest.approx(expected, rel=1e-10)
    assert expected == pytest.approx(7.6744e6, rel=1e-4)


def _sheared_fraction_mp(N, digits=60):
    """1 - phi from the cubic eps^2 (3 - eps) = 2N (1 - eps) by bisection at ``digits`` decimal digits (mpmath)."""
    import mpmath as mp

    with mp.workdps(digits):
        n, lo, hi = mp.mpf(N), mp.mpf(0), mp.mpf(1)
        for _ in range(260):
            mid = (lo + hi) / 2
            if mid**2 * (3 - mid) - 2 * n * (1 - mid) > 0:
                hi = mid
            else:
                lo = mid
        return (lo + hi) / 2


def test_plug_and_sheared_fractions_keep_full_precision_from_blocked_gap_to_newtonian():
    # issue 13: the arcsin root lost the sheared layer 1 - phi as the gap blocks (all digits below N ~ 1e-16)
    from erdesign.flow.bingham import _plug_and_sheared_fractions

    for N in np.logspace(-30, 8, 77):
        phi, eps = _plug_and_sheared_fractions(N)
        exact = _sheared_fraction_mp(N)
        assert float(abs(eps - exact) / exact) < 1e-15, N
        assert float(abs(phi - (1 - exact)) / (1 - exact)) < 1e-15, N


def test_round_trip_near_a_blocked_gap_is_limited_by_conditioning_only():
    # Q ~ eps^2 and eps = (dp - dp_y)/dp: a pressure drop known to rounding u gives Q to about 2u/eps, no worse
    tau_y, eta, L, d, h = 1000.0, 1.0, 0.05, 0.02, 1e-3
    dp_y = 2 * tau_y * L / h
    for N in np.logspace(-24, 2, 27):
        Q = N * dp_y * np.pi * d * h**3 / (12 * eta * L)
        dp = bingham_pressure_drop(Q, tau_y, eta, L, d, h)
        eps = float(_sheared_fraction_mp(N))
        assert abs(bingham_flow_rate(dp, tau_y, eta, L, d, h) / Q - 1) < 8 * 2.2e-16 / eps + 1e-14, N
    # the case: Newtonian/yield ratio 1e-16 (the old root gave phi = 1 exactly there and Q = 0 back)
    Q = 1e-16 * dp_y * np.pi * d * h**3 / (12 * eta * L)
    assert abs(bingham_flow_rate(bingham_pressure_drop(Q, tau_y, eta, L, d, h), tau_y, eta, L, d, h) / Q - 1) < 1e-7
