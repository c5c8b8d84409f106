"""Tests of the Makris elastic-viscoplastic law and its limits (erdesign.constitutive.makris).

Source: Makris, Burton, Hill and Jordan, "ER damper with annular ducts for seismic protection applications"
(Makris et al. 1996), eqs 8-13 and Figs 3-4.  Figure 3 fluid at 3 kV/mm: tau_y = 1.8 kPa, G = 17 kPa, eta = 13 Pa s.
Independent references: scipy.integrate.quad (eq 11), scipy.integrate.solve_ivp (eq 8), scipy.signal.lfilter
(eq 13) and closed forms derived in docs/theory/makris.md.
"""

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.signal import lfilter

from erdesign.constitutive.makris import (
    elastic_plastic_stress,
    integration_factor_exponent,
    makris_stress,
    maxwell_stress,
)
from erdesign.errors import ErdesignError

TAU_Y, G, ETA = 1800.0, 17000.0, 13.0  # Makris, text after eq 11 (Fig 3 fluid at 3 kV/mm)


def harmonic(omega, gamma0, cycles, per_cycle):
    """Sample times and strain gamma0 sin(omega t), with samples on every reversal (per_cycle divisible by 4)."""
    t = np.linspace(0.0, cycles * 2 * np.pi / omega, cycles * per_cycle + 1)
    return t, gamma0 * np.sin(omega * t)


def eq8_rhs(gamma_dot):
    """d tau/dt of eq 8 (= eqs 9-10 form G gdot - R tau) for a strain-rate function gamma_dot(t)."""

    def rhs(t, tau):
        gd = gamma_dot(t)
        return G * gd - G * abs(gd) / (ETA * abs(gd) + TAU_Y) * tau

    return rhs


def solve_eq8(gamma_dot, breaks, t_eval):
    """Reference solution of eq 8 by LSODA, restarted at each kink of |gdot| (the strain reversals)."""
    tau = np.empty_like(t_eval)
    tau0 = 0.0
    for a, b in zip(breaks[:-1], breaks[1:]):
        sol = solve_ivp(eq8_rhs(gamma_dot), (a, b), [tau0], method="LSODA", rtol=1e-10, atol=1e-8, dense_output=True)
        inside = (t_eval >= a) & (t_eval <= b)
        tau[inside] = sol.sol(t_eval[inside])[0]
        tau0 = sol.y[0, -1]
    return tau


# --- 1. eq 11 against quadrature, and its a -> 0 limit ----------------------------------------------------------


@pytest.mark.parametrize("a", [3.0, 1.0, 0.3, 2000.0, 0.0])
def test_eq11_matches_quadrature_on_the_printed_interval(a):
    omega = 2 * np.pi * 5.0
    phases = np.linspace(-np.pi / 2, np.pi / 2, 41)
    closed = integration_factor_exponent(phases, a, G, ETA, omega)
    for phase, value in zip(phases, closed):
        # the integrand printed above eq 11, with gamma0 = 1 and tau_y = a eta omega gamma0
        ref, _ = quad(
            lambda t: G * omega * np.cos(omega * t) / (ETA * omega * np.cos(omega * t) + a * ETA * omega),
            0.0,
            phase / omega,
            epsabs=0.0,
            epsrel=1e-13,
        )
        # Makris eq 11: 1e-10 relative; quad reaches ~1e-14, the closed form loses ~a*eps to cancellation
        assert value == pytest.approx(ref, rel=1e-10, abs=1e-12)


@pytest.mark.parametrize("a", [3.0, 1.0, 0.3])
def test_eq11_periodic_extension_matches_quadrature_over_two_cycles(a):
    """The closed forms shifted by pi (not 'a -> -a', which hits tan(pi/2) at omega t = pi) over [-2pi, 4pi]."""
    omega = 3.0
    phases = np.linspace(-2 * np.pi, 4 * np.pi, 49)
    closed = integration_factor_exponent(phases, a, G, ETA, omega)
    for phase, value in zip(phases, closed):
        kinks = [k * np.pi / 2 / omega for k in range(-5, 9) if k % 2 and min(0, phase) < k * np.pi / 2 < max(0, phase)]
        ref, _ = quad(
            lambda t: G * abs(np.cos(omega * t)) / (ETA * abs(np.cos(omega * t)) + a * ETA),
            0.0,
            phase / omega,
            points=kinks or None,
            epsabs=0.0,
            epsrel=1e-13,
            limit=200,
        )
        # exponent of R = G|gdot|/(eta|gdot| + tau_y), eqs 9-10; 1e-10 relative as above
        assert value == pytest.approx(ref, rel=1e-10, abs=1e-12)


def test_eq11_is_continuous_across_a_equal_one():
    phases = np.linspace(-np.pi / 2, np.pi / 2, 11)
    mid = integration_factor_exponent(phases, 1.0, 1.0, 1.0, 1.0)
    for a in (1.0 - 1e-9, 1.0 + 1e-9):
        # eq 11 middle case is the limit of the outer two; d(bracket)/da is O(1), so a 1e-9 step moves it ~1e-9
        np.testing.assert_allclose(integration_factor_exponent(phases, a, 1.0, 1.0, 1.0), mid, rtol=0, atol=3e-9)


def test_printed_a_to_minus_a_rule_fails_in_closed_form_for_small_a():
    """Makris (text after eq 11): on pi/2 <= wt <= 3pi/2 'a has to be replaced by -a'.  For a < 1 the a < 1 branch
    of eq 11 with -a takes the log of a negative number past wt = pi/2, so the rule holds for the integrand only."""
    a, phase = 0.3, 0.75 * np.pi
    k = np.sqrt((1 - a) / (1 + a))  # sqrt((1 + a')/(1 - a')) with a' = -a
    x = np.tan(phase / 2)  # 2.41 > k = 0.73
    assert (k + x) / (k - x) < 0.0  # the printed log argument is negative: no real value


def test_eq11_tends_to_maxwell_and_eq12_is_its_small_a_form():
    phases = np.linspace(-np.pi / 2, np.pi / 2, 101)
    x = np.tan(phases / 2)
    for a in (1e-2, 1e-3, 1e-4):
        bracket = integration_factor_exponent(phases, a, 1.0, 1.0, 1.0)  # G/(eta omega) = 1
        eq12 = phases - a * np.log((1 + a + x) / (1 + a - x))
        # Makris eq 12 is eq 11 with a/sqrt(1-a^2) -> a and sqrt((1+a)/(1-a)) -> 1+a; the terms it drops add up
        # to a^2/2 + O(a^3 ln a) at the ends of the interval (docs/theory/makris.md; measured 0.475 a^2 at
        # a = 0.01, 0.4995 a^2 at 1e-4), so it is a consistent first-order form with no misprint
        gap = np.abs(bracket - eq12).max()
        assert 0.4 * a**2 < gap < 0.51 * a**2
        # text after eq 12: the exponent tends to G t / eta, the gap at wt = pi/2 being a ln((2+a)/a) to first
        # order (the printed "a ln(2+a)/a"); measured relative deviation 9e-4 at a = 0.01, below 2a
        assert abs(bracket[-1] - phases[-1]) == pytest.approx(a * np.log((2 + a) / a), rel=2 * a)
    assert abs(integration_factor_exponent(np.pi / 2, 0.0, G, ETA, 10.0) - G * np.pi / 2 / (ETA * 10.0)) < 1e-12 * G


# --- 2. the exact-step integrator against solve_ivp ------------------------------------------------------------


def test_exact_for_piecewise_linear_strain_at_any_step():
    """A triangle wave (constant rate between samples) is integrated exactly with only 9 samples."""
    t = np.linspace(0.0, 0.4, 9)
    gamma = np.array([0.0, 0.5, 1.0, 0.5, 0.0, -0.5, -1.0, -0.5, 0.0])  # |gdot| = 10 1/s
    # rate +10 on (0, 0.1), -10 on (0.1, 0.3), +10 on (0.3, 0.4); the midpoint of each piece decides its sign
    ref = solve_eq8(lambda s: 10.0 if s < 0.1 or s > 0.3 else -10.0, [0.0, 0.1, 0.3, 0.4], t)
    tau = makris_stress(t, gamma, TAU_Y, ETA, G)
    # eq 8 is solved in closed form on each constant-rate step; LSODA rtol 1e-10 is the error left
    np.testing.assert_allclose(tau, ref, rtol=0, atol=1e-7 * np.abs(ref).max())


def test_sine_strain_matches_solve_ivp_with_second_order_convergence():
    omega, gamma0 = 2 * np.pi * 5.0, 1.0  # Fig 3 fluid at 5 Hz
    T = 2 * np.pi / omega
    t_ref = np.linspace(0.0, T, 201)
    ref = solve_eq8(lambda s: omega * gamma0 * np.cos(omega * s), [0.0, T / 4, 3 * T / 4, T], t_ref)
    amplitude = np.abs(ref).max()
    errors = []
    for per_cycle in (2000, 4000, 8000):
        t, gamma = harmonic(omega, gamma0, 1, per_cycle)
        tau = makris_stress(t, gamma, TAU_Y, ETA, G)[:: per_cycle // 200]
        errors.append(np.abs(tau - ref).max() / amplitude)
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    # exact-step scheme = exact solution for the piecewise-linear interpolant of the strain: O(dt^2); measured
    # orders 2.00; 1.8 leaves room for the kink of |gdot| at reversals
    assert np.all(orders > 1.8), orders
    # brief: 1e-6 of the stress amplitude with a fine step (measured 1.6e-7 at 8000 steps per cycle)
    assert errors[-1] < 1e-6


def test_decay_of_a_stress_offset_is_the_eq11_integrating_factor():
    """Two solutions of the linear eq 9 differ by delta0 exp(-int R dt) (eq 10), with int R dt from eq 11."""
    omega = 2 * np.pi
    t, gamma = harmonic(omega, 1.0, 1, 4000)
    for a in (3.0, 1.0, 0.3):
        eta = G / (0.5 * omega)  # G/(eta omega) = 0.5: offset decays to ~e^-1 per cycle
        tau_y = a * eta * omega  # gamma0 = 1
        delta = makris_stress(t, gamma, tau_y, eta, G, tau0=100.0) - makris_stress(t, gamma, tau_y, eta, G)
        exact = 100.0 * np.exp(-integration_factor_exponent(omega * t, a, G, eta, omega))
        # eq 10 / eq 11; the step uses the mean rate, O(dt^2) ~ (2 pi/4000)^2 = 2.5e-6 relative error in E
        np.testing.assert_allclose(delta, exact, rtol=1e-5)


# --- 3. the Maxwell limit (eq 13) ------------------------------------------------------------------------------


def test_zero_yield_stress_is_the_maxwell_filter_to_roundoff():
    t, gamma = harmonic(2 * np.pi * 10.0, 0.5, 3, 400)
    dt = t[1] - t[0]
    c = np.exp(-G * dt / ETA)
    k = ETA * (1 - c) / dt
    # eq 13 on a piecewise-linear strain: tau_n = c tau_{n-1} + k (gamma_n - gamma_{n-1}), tau_0 = 0
    ref = lfilter([k, -k], [1.0, -c], gamma, zi=[-k * gamma[0]])[0]
    tau = maxwell_stress(t, gamma, ETA, G)
    # round-off: ~log2(N) scan levels of a few ulps each on a stress of ~G gamma0
    np.testing.assert_allclose(tau, ref, rtol=0, atol=1e-12 * np.abs(ref).max())
    np.testing.assert_array_equal(tau, makris_stress(t, gamma, 0.0, ETA, G))


def test_maxwell_steady_state_is_the_complex_modulus():
    omega, gamma0 = 2 * np.pi * 10.0, 0.5
    t, gamma = harmonic(omega, gamma0, 10, 4000)
    lam = ETA / G
    modulus = G * 1j * omega * lam / (1 + 1j * omega * lam)  # eq 13 for gamma = Im(gamma0 e^{i w t})
    steady = np.imag(modulus * gamma0 * np.exp(1j * omega * t))
    tau = maxwell_stress(t, gamma, ETA, G)
    last = slice(-4001, None)  # transient e^{-t/lam} gone after 10 cycles
    # the step replaces gdot by its mean over the step; weighted by e^{-(t - xi)/lam} this leaves a relative error
    # (omega dt)(dt/lam)/12 = 4.3e-6 when omega lam << 1 (derived in docs/theory/makris.md); measured 4.3e-6
    dt = t[1] - t[0]
    tolerance = 2 * (omega * dt) * (dt / lam) / 12
    np.testing.assert_allclose(tau[last], steady[last], rtol=0, atol=tolerance * np.abs(modulus) * gamma0)


@pytest.mark.parametrize("deborah", [0.1, 0.5, 1.0, 10.0])
def test_small_a_tends_to_maxwell(deborah):
    """Fig 4 (bottom): a = 0.05 against the Maxwell model (eq 13), and the approach as a -> 0."""
    omega = deborah * G / ETA  # Deborah number eta omega / G
    gaps = []
    for a in (0.05, 0.0125, 0.003125):
        gamma0 = TAU_Y / (a * ETA * omega)
        per_cycle = max(1000, 4 * int(10 / a))  # >= 6 samples across the |cos wt| < a zone
        t, gamma = harmonic(omega, gamma0, 5, per_cycle)
        last = slice(-per_cycle - 1, None)
        maxwell = maxwell_stress(t, gamma, ETA, G)[last]
        gaps.append(np.abs(makris_stress(t, gamma, TAU_Y, ETA, G)[last] - maxwell).max() / np.abs(maxwell).max())
        # scale of the gap: the term a ln((2+a)/a) that eq 12 drops from the exponent (text after eq 12).  Measured
        # gap / that term: 0.09 (De = 10) to 1.06 (De = 0.5, a = 0.003); 1.5 is the margin
        assert gaps[-1] < 1.5 * a * np.log((2 + a) / a)
    # convergence to Maxwell at first order in a up to the log: a ln(2/a) predicts 0.34 per factor 4 in a,
    # pure a 0.25, sqrt(a) 0.5; measured 0.33-0.37
    ratios = np.array(gaps[1:]) / np.array(gaps[:-1])
    assert np.all((ratios > 0.25) & (ratios < 0.45)), ratios
    if deborah >= 10.0:
        # Makris, Fig 4 bottom: "the two responses are almost identical" holds at high Deborah number (measured
        # 1.6 % at De = 10, but 17 % at De = 0.5; the paper does not give its De)
        assert gaps[0] < 0.02


# --- 4. the large-a and G -> infinity limits --------------------------------------------------------------------


def test_elastic_plastic_closed_form_on_monotone_loading_and_against_eta_zero():
    gamma = np.concatenate([np.linspace(0, 0.8, 50), np.linspace(0.8, -0.3, 70), np.linspace(-0.3, 0.4, 40)])
    tau = elastic_plastic_stress(gamma, TAU_Y, G)
    # virgin branch: tau = tau_y (1 - exp(-G gamma/tau_y)), eq 8 with eta = 0 integrated from rest
    np.testing.assert_allclose(tau[:50], TAU_Y * -np.expm1(-G * gamma[:50] / TAU_Y), rtol=1e-14, atol=1e-12)
    # same law stepped sample by sample (makris_stress with eta = 0): same numbers up to round-off
    step = makris_stress(np.arange(gamma.size, dtype=float), gamma, TAU_Y, 0.0, G)
    np.testing.assert_allclose(tau, step, rtol=0, atol=1e-12 * TAU_Y)
    # independent: d tau/d gamma = G (1 - s tau / tau_y) by LSODA on each monotone branch
    tau_r = 0.0
    for lo, hi, end in ((0.0, 0.8, 49), (0.8, -0.3, 119), (-0.3, 0.4, 159)):
        s = np.sign(hi - lo)
        sol = solve_ivp(lambda g, y: G * (1 - s * y / TAU_Y), (lo, hi), [tau_r], method="LSODA", rtol=1e-11, atol=1e-9)
        tau_r = sol.y[0, -1]
        assert tau[end] == pytest.approx(tau_r, abs=1e-6 * TAU_Y)  # LSODA rtol 1e-11 at ~tau_y
    # slope just after the reversal at gamma = 0.8: G (1 + tau_r/tau_y) (derived from eq 8 as gdot -> 0)
    tip = elastic_plastic_stress([0.0, 0.8, 0.8 - 1e-6], TAU_Y, G)
    slope = (tip[2] - tip[1]) / -1e-6
    # secant over 1e-6 of strain: curvature (G/tau_y) * 1e-6 / 2 = 5e-6 relative
    assert slope == pytest.approx(G * (1 + tip[1] / TAU_Y), rel=2e-5)


def test_elastic_plastic_closed_form_on_a_random_path_with_rests():
    """Branch-wise closed form against the step-by-step law (eta = 0) on a path with many reversals and rests."""
    rng = np.random.default_rng(4)
    steps = rng.normal(0.0, 0.05, 300) * (rng.random(300) > 0.2)  # a fifth of the steps are rests
    gamma = np.concatenate([[0.0, 0.0], np.cumsum(steps)])  # starts with a rest too
    tau = elastic_plastic_stress(gamma, TAU_Y, G, tau0=500.0)
    step = makris_stress(np.arange(gamma.size, dtype=float), gamma, TAU_Y, 0.0, G, tau0=500.0)
    assert tau[1] == 500.0  # rest: stress held
    # same law (eq 8, eta = 0), two evaluation orders: round-off of a few ulps of tau_y per branch
    np.testing.assert_allclose(tau, step, rtol=0, atol=1e-11 * TAU_Y)
    assert np.abs(tau).max() < TAU_Y  # bounded by the yield stress


def test_a_2000_matches_the_zero_frequency_closed_form():
    """Fig 4 (top): the model at a = 2000 against the a = infinity closed form; gamma0 = 1 (G gamma0 = 9.4 tau_y)."""
    gamma0, a = 1.0, 2000.0
    omega = TAU_Y / (a * ETA * gamma0)  # 0.069 rad/s
    t, gamma = harmonic(omega, gamma0, 3, 2000)
    gap = np.abs(makris_stress(t, gamma, TAU_Y, ETA, G) - elastic_plastic_stress(gamma, TAU_Y, G)).max()
    # the difference is the viscous stress, at most eta omega gamma0 = tau_y/a = 0.9 Pa (measured 0.994 tau_y/a);
    # 5 % margin for O(1/a^2) and discretisation, and more than half of it so that the viscous term is seen
    assert 0.5 * TAU_Y / a < gap < 1.05 * TAU_Y / a


def test_infinite_modulus_gives_the_bingham_law():
    """G -> inf: rigid-viscoplastic, tau = tau_y sgn(gdot) + eta gdot (Makris eq 5), up to the elastic lag."""
    omega, gamma0 = 2 * np.pi * 5.0, 1.0
    t, gamma = harmonic(omega, gamma0, 2, 20000)
    dt = t[1] - t[0]
    gamma_dot = omega * gamma0 * np.cos(omega * t)
    bingham = TAU_Y * np.sign(gamma_dot) + ETA * gamma_dot
    bingham_rate = np.abs(ETA * omega**2 * gamma0 * np.sin(omega * t))
    away = (np.abs(gamma) < 0.9 * gamma0) & (t > t[-1] / 2)  # second cycle, away from the reversals
    errors = []
    for modulus in (1e6, 1e7, 1e8):
        tau = makris_stress(t, gamma, TAU_Y, ETA, modulus)
        rate = modulus * np.abs(gamma_dot) / (ETA * np.abs(gamma_dot) + TAU_Y)
        error = np.abs(tau - bingham)[away].max()
        # quasi-steady lag of eq 8, |d tau_B/dt| / R, plus one step of discretisation, |d tau_B/dt| dt
        assert error <= (bingham_rate / rate)[away].max() + bingham_rate[away].max() * dt
        errors.append(error)
    assert errors[0] > 5 * errors[1]  # lag ~ 1/G while above the dt floor
    assert errors[-1] < 1e-4 * (TAU_Y + ETA * omega * gamma0)


# --- 5. the Figure 3 setting ------------------------------------------------------------------------------------

FIG3_GAMMA0 = 1.0  # our choice (Fig 3 strain axis not in the text); a = 22.0, 4.4, 2.2 at 1, 5, 10 Hz


@pytest.fixture(scope="module")
def fig3_loops():
    loops = {}
    for f in (1.0, 5.0, 10.0):
        omega = 2 * np.pi * f
        t, gamma = harmonic(omega, FIG3_GAMMA0, 4, 4000)
        loops[f] = (omega, gamma, makris_stress(t, gamma, TAU_Y, ETA, G))
    return loops


def test_fig3_slope_after_reversal_and_at_zero_stress(fig3_loops):
    for omega, gamma, tau in fig3_loops.values():
        i = 3 * 4000 + 1000  # gamma = +gamma0: start of the 4th cycle's unloading
        tau_r = tau[i]
        slope = (tau[i + 1] - tau[i]) / (gamma[i + 1] - gamma[i])
        # eq 8 as gdot -> 0: d tau/d gamma = G (1 + |tau_r|/tau_y), not G (Makris's text reads "the slope of the
        # loop at maximum strain is equal to G" for the experiment).  Tolerance: over the first step the rate is
        # not 0 but omega gamma0 (omega dt)/2, adding eta|gdot|/tau_y <= 3.6e-4 (10 Hz) to the denominator;
        # curvature of the branch adds 6e-6 (measured 2e-4 at 10 Hz)
        assert slope == pytest.approx(G * (1 + tau_r / TAU_Y), rel=5e-4)
        assert 1.9 * G < slope < 2.3 * G
        # where the unloading branch crosses tau = 0 the slope is exactly G (eq 8 with tau = 0)
        j = i + np.flatnonzero(tau[i:] < 0)[0]
        secant = (tau[j] - tau[j - 1]) / (gamma[j] - gamma[j - 1])
        assert secant == pytest.approx(G, rel=0.01)  # secant over one step; curvature ~G/tau_y times d gamma ~1e-3


def test_fig3_peak_stress_is_below_and_near_the_bingham_bound(fig3_loops):
    for omega, gamma, tau in fig3_loops.values():
        bound = TAU_Y + ETA * omega * FIG3_GAMMA0  # max of tau_B = eta gdot + tau_y sgn(gdot)
        peak = tau[-4001:].max()
        # at a stress maximum d tau/dt = R (tau_B - tau) = 0, so peak = tau_B at a time ~1/R after the peak of
        # tau_B: gap ~ (1/2) eta omega gamma0 (omega/R)^2 (measured 0.65, 4.0, 11 Pa); the bound drops the 1/2
        rate = G * omega * FIG3_GAMMA0 / (ETA * omega * FIG3_GAMMA0 + TAU_Y)
        assert 0.0 < bound - peak < ETA * omega * FIG3_GAMMA0 * (omega / rate) ** 2


def test_fig3_loop_area_grows_with_frequency(fig3_loops):
    areas = []
    for omega, gamma, tau in fig3_loops.values():
        g, s = gamma[-4001:], tau[-4001:]
        areas.append(np.sum(0.5 * (s[1:] + s[:-1]) * np.diff(g)))  # energy per cycle per volume, [J/m^3]
    omegas = [v[0] for v in fig3_loops.values()]
    assert areas[0] < areas[1] < areas[2]  # measured 6667, 7571, 8675 J/m^3
    # the growth is the viscous loop area pi eta omega gamma0^2 of a Bingham solid, less the elastic lag
    # (measured 0.87 of it from 1 to 10 Hz)
    viscous = np.pi * ETA * FIG3_GAMMA0**2 * (omegas[2] - omegas[0])
    assert 0.7 * viscous < areas[2] - areas[0] < viscous


def test_fig3_periodic_steady_state(fig3_loops):
    for omega, gamma, tau in fig3_loops.values():
        # the offset from the periodic solution decays by exp(-int R dt) per cycle (eq 10), with int R dt over a
        # cycle = 4 E(pi/2) from eq 11 = 36, 32, 28 at 1, 5, 10 Hz: cycles 3 and 4 agree to round-off
        a = TAU_Y / (ETA * omega * FIG3_GAMMA0)
        assert 4 * integration_factor_exponent(np.pi / 2, a, G, ETA, omega) > 25
        np.testing.assert_allclose(tau[-4001:], tau[-8001:-4000], rtol=0, atol=1e-9 * TAU_Y)


# --- interface --------------------------------------------------------------------------------------------------


def test_rest_steps_hold_the_stress_unless_maxwell():
    t = np.array([0.0, 0.01, 0.02, 0.03])
    gamma = np.array([0.0, 0.05, 0.05, 0.05])
    tau = makris_stress(t, gamma, TAU_Y, ETA, G)
    assert tau[1] > 0 and tau[2] == tau[1] == tau[3]  # eq 8: R = 0 when gdot = 0 and tau_y > 0
    relaxed = makris_stress(t, gamma, 0.0, ETA, G)
    assert relaxed[2] == pytest.approx(relaxed[1] * np.exp(-G * 0.01 / ETA), rel=1e-13)  # eq 13 relaxation


def test_trailing_axes_and_time_varying_field():
    t, gamma = harmonic(2 * np.pi * 5.0, 1.0, 1, 400)
    fields = np.array([0.0, 900.0, 1800.0])
    batch = makris_stress(t, gamma[:, None], fields, ETA, G)
    assert batch.shape == (401, 3)
    for j, tau_y in enumerate(fields):
        np.testing.assert_array_equal(batch[:, j], makris_stress(t, gamma, tau_y, ETA, G))
    # field switched on at the half cycle: before it, the zero-field (Maxwell) stress
    switched = makris_stress(t, gamma, np.where(t < t[200], 0.0, TAU_Y), ETA, G)
    np.testing.assert_array_equal(switched[:201], maxwell_stress(t, gamma, ETA, G)[:201])
    assert not np.allclose(switched[201:], maxwell_stress(t, gamma, ETA, G)[201:])


@pytest.mark.parametrize(
    "args, name",
    [
        (([0.0, 1.0, 1.0], [0.0, 0.1, 0.2]), "t"),
        (([0.0, 1.0], [0.0, 0.1, 0.2]), "gamma"),
        (([0.0, 1.0, 2.0], [0.0, np.nan, 0.2]), "gamma"),
    ],
)
def test_bad_histories_name_the_argument(args, name):
    with pytest.raises(ErdesignError, match=name):
        makris_stress(*args, TAU_Y, ETA, G)


def test_bad_parameters_are_errors():
    with pytest.raises(ErdesignError, match="G"):
        makris_stress([0.0, 1.0], [0.0, 1.0], TAU_Y, ETA, 0.0)
    with pytest.raises(ErdesignError, match="a"):
        integration_factor_exponent(0.1, -1.0, G, ETA, 1.0)
    with pytest.raises(ErdesignError, match="gamma"):
        elastic_plastic_stress(np.zeros((3, 2)), TAU_Y, G)
