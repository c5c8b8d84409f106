"""The compiled element loops of the flow kernels (erdesign/flow/_compiled.py) against independent solutions.

The closed forms themselves are checked elsewhere (tests/test_flow_bingham.py against np.roots and sympy,
tests/test_flow_mixed_mode.py against brute force and the brief's equations, tests/test_flow_numerical.py against
scikit-fem and adaptive quadrature); here the new parts are checked: each root the loops find against scipy's
bracketed root finder run on the same equation to the last bit, the Gauss-Legendre rule the annulus picks by h/d
against adaptive quadrature, and the compiled one-pass thin-gap dp(Q) against the numpy path it replaces for large
arrays.  Speed is measured by benchmarks/bench_kernels_speed.py, never asserted here.
"""

import math

import numpy as np
import pytest
from scipy import integrate
from scipy.optimize import brentq

from erdesign.flow import _compiled as compiled
from erdesign.flow.annulus_bingham import annulus_bingham_flow
from erdesign.flow.bingham import COMPILED_MIN_SIZE, bingham_slit_flow
from erdesign.flow.mixed_mode import GapFlowRegime, couette_poiseuille_bingham

EPS = np.finfo(float).eps


def _brentq_decreasing(f, x0, step):
    """Root of a non-increasing f by brentq to the last bit, from a bracket grown around x0."""
    lo, hi = x0 - step, x0 + step
    while f(lo) < 0.0:
        lo -= step
        step *= 2.0
    while f(hi) > 0.0:
        hi += step
        step *= 2.0
    return brentq(f, lo, hi, xtol=1e-300, rtol=4 * EPS, maxiter=500)


# ------------------------------------------------------------------------------------------------------------------
# Thin-gap dp(Q): one compiled pass from COMPILED_MIN_SIZE elements on, numpy below.
# ------------------------------------------------------------------------------------------------------------------


def test_slit_compiled_pass_equals_the_numpy_path_to_a_few_ulp():
    # Flow ratios N = dp_N/dp_y from 1e-30 (a nearly blocked gap, where the sheared fraction comes from Newton
    # steps) to 1e8 (nearly Newtonian), both signs, Q = +-0, and yield stresses of zero and 1e-300 (the
    # large-ratio branch).
    rng = np.random.default_rng(7)
    L, d, h, eta = 0.0546, 0.0143, 0.0008, 13.0
    n = 2 * COMPILED_MIN_SIZE
    N = 10.0 ** rng.uniform(-30, 8, n)
    tau_y = np.full(n, 1800.0)
    tau_y[:50], tau_y[50:100] = 0.0, 1e-300
    dp_y = 2 * tau_y * L / h
    Q = N * np.where(tau_y == 1800.0, dp_y, 1.0) * np.pi * d * h**3 / (12 * eta * L) * rng.choice([-1.0, 1.0], n)
    Q[100:104] = [0.0, -0.0, 0.0, -0.0]
    big = bingham_slit_flow(Q, tau_y, eta, L, d, h)  # compiled
    assert big.pressure_drop.shape == (n,)
    small = [bingham_slit_flow(Q[i : i + 1000], tau_y[i : i + 1000], eta, L, d, h) for i in range(0, n, 1000)]
    dp_ref = np.concatenate([s.pressure_drop for s in small])  # numpy, below the threshold
    phi_ref = np.concatenate([s.plug_fraction for s in small])
    # measured 1.1e-15 (the libm's and numpy's sin/arcsin differ in the last bit); at N < 0.5 the sheared fraction
    # 1 - phi comes from the same Newton steps, so the round trip of tests/test_flow_bingham.py holds for both
    np.testing.assert_allclose(big.pressure_drop, dp_ref, rtol=8 * EPS, atol=0)
    np.testing.assert_allclose(big.plug_fraction, phi_ref, rtol=8 * EPS, atol=0)
    np.testing.assert_array_equal(np.signbit(big.pressure_drop), np.signbit(dp_ref))  # -0.0 gives -dp_y


def test_slit_one_duct_loop_equals_the_numpy_path():
    # Many flows through one duct (scalar duct arguments) take the plain loop with the duct's constants hoisted.
    rng = np.random.default_rng(8)
    L, d, h, eta, tau_y = 0.0546, 0.0143, 0.0008, 13.0, 1800.0
    N = 10.0 ** rng.uniform(-30, 14, (2, COMPILED_MIN_SIZE))  # beyond 1e12: the large-ratio limit
    Q = N * (2 * tau_y * L / h) * np.pi * d * h**3 / (12 * eta * L) * rng.choice([-1.0, 1.0], N.shape)
    Q[0, :3] = [0.0, -0.0, np.nan]
    big = bingham_slit_flow(Q, tau_y, eta, L, d, h)
    assert big.pressure_drop.shape == Q.shape
    small = [bingham_slit_flow(Q[:, i : i + 1000], tau_y, eta, L, d, h) for i in range(0, Q.shape[1], 1000)]
    np.testing.assert_allclose(big.pressure_drop, np.hstack([s.pressure_drop for s in small]), rtol=8 * EPS, atol=0)
    np.testing.assert_allclose(big.plug_fraction, np.hstack([s.plug_fraction for s in small]), rtol=8 * EPS, atol=0)
    assert big.pressure_drop[0, 1] == -2 * tau_y * L / h
    # the pressure drop alone (the loop skips the plug fraction) is the same array
    from erdesign.flow.bingham import bingham_pressure_drop

    np.testing.assert_array_equal(bingham_pressure_drop(Q, tau_y, eta, L, d, h), big.pressure_drop)


def test_slit_broadcasts_like_the_numpy_path():
    Q = np.linspace(-1e-4, 1e-4, COMPILED_MIN_SIZE)[:, None]
    tau_y = np.array([0.0, 500.0, 1800.0])
    r = bingham_slit_flow(Q, tau_y, 13.0, 0.0546, 0.0143, 0.0008)
    assert r.pressure_drop.shape == r.plug_fraction.shape == (COMPILED_MIN_SIZE, 3)
    ref = bingham_slit_flow(Q[:1000], tau_y, 13.0, 0.0546, 0.0143, 0.0008)
    np.testing.assert_allclose(r.pressure_drop[:1000], ref.pressure_drop, rtol=8 * EPS, atol=0)


# ------------------------------------------------------------------------------------------------------------------
# Mixed mode: the gradient of Bingham Couette-Poiseuille flow.
# ------------------------------------------------------------------------------------------------------------------


def _mixed_cases(n, seed=3):
    """Scaled cases (U_bar, q_bar, eps) with eps + |U_bar| + |q_bar| = 1: valve mode, back-flow (the damper),
    plain shear, nearly blocked and nearly Newtonian."""
    rng = np.random.default_rng(seed)
    w = rng.dirichlet([1.0, 1.0, 1.0], n) * rng.choice([-1.0, 1.0], (n, 3))
    eps = np.abs(w[:, 0]) * 10.0 ** np.where(rng.random(n) < 0.2, rng.uniform(-12, 0, n), 0.0)
    eps[: n // 10] = 1.0 - 10.0 ** rng.uniform(-9, -1, n // 10)  # nearly blocked
    U, q = w[:, 1], w[:, 2]
    U[n // 10 : n // 5] = 0.0  # valve mode
    q[n // 5 : n // 4] = -U[n // 5 : n // 4] * rng.uniform(1, 10, n // 4 - n // 5)  # the damper's back-flow
    scale = (1.0 - eps) / np.maximum(np.abs(U) + np.abs(q), 1e-300)
    cases = np.column_stack([U * scale, q * scale, eps])
    # a case where the secant iteration stalls and Chandrupatla's method takes over (found by a random search)
    return np.vstack([cases, [-0.003944445304448165, -0.000145416010646081, 0.9959101386849057]])


def test_mixed_gradient_is_the_root_brentq_finds():
    for U_bar, q_bar, eps in _mixed_cases(400):
        G = compiled._mixed_gradient(U_bar, q_bar, eps)
        ref = _brentq_decreasing(
            lambda g, a=U_bar, b=q_bar, e=eps: compiled._mixed_residual(g, a, b, e),
            12.0 * (U_bar / 2 - q_bar),
            3 * eps + 1e-3,
        )
        # both converge to the round-off of G (an O(1) number in these units): measured 2.6e-18 absolute
        assert G == pytest.approx(ref, rel=1e-13, abs=1e-16), (U_bar, q_bar, eps)
        assert compiled._mixed_gradient_bracketed(U_bar, q_bar, eps) == pytest.approx(ref, rel=1e-13, abs=1e-16)


@pytest.mark.parametrize("scale", [1e-300, 1e-200, 1e-100, 1e-40, 1e-31, 1e-25])
def test_mixed_gradient_of_vanishing_flows_is_the_root_brentq_finds(scale):
    # a head creeping at 1e-300 to 1e-25 of its speed scale (the flow of a piston head, q = -7.2 U, dimensionless):
    # the root sits just outside the yield band, on the side the flow sets; the secant steps once returned the
    # other side's break-away value below about 1e-40
    for sign in (1.0, -1.0):
        U_bar, q_bar, eps = sign * 1.47 * scale, -sign * 10.6 * scale, 1.0
        ref = _brentq_decreasing(lambda g: compiled._mixed_residual(g, U_bar, q_bar, eps), 0.0, 1.0)
        G = compiled._mixed_gradient(U_bar, q_bar, eps)
        assert G == pytest.approx(ref, rel=1e-13) and ref == pytest.approx(2.0 * sign, rel=1e-9)


def test_mixed_regime_codes_are_the_enum():
    assert [
        compiled.FULLY_YIELDED,
        compiled.FLOATING_PLUG,
        compiled.PLUG_AT_MOVING_WALL,
        compiled.PLUG_AT_FIXED_WALL,
        compiled.BLOCKED,
    ] == [int(r) for r in GapFlowRegime]


def test_mixed_solution_is_the_same_in_any_array_layout():
    # The loop runs on flattened contiguous copies: a transposed, strided input gives the same numbers.
    U = np.linspace(-0.2, 0.2, 12).reshape(3, 4)
    q = -U.T.copy().T * 7e-4
    a = couette_poiseuille_bingham(U.T, q.T, 2000.0, 0.1, 1e-3)
    b = couette_poiseuille_bingham(np.ascontiguousarray(U.T), np.ascontiguousarray(q.T), 2000.0, 0.1, 1e-3)
    for x, y in zip(a, b):
        np.testing.assert_array_equal(x, y)


# ------------------------------------------------------------------------------------------------------------------
# Exact Bingham annulus: plug position, plug fraction and the Gauss-Legendre rule.
# ------------------------------------------------------------------------------------------------------------------

H_OVER_D = [1e-3, 0.02, 0.1, 0.15, 0.3, 0.5, 0.85]


@pytest.mark.parametrize("eps", H_OVER_D)
def test_annulus_plug_position_is_the_root_brentq_finds(eps):
    R1 = 0.5 * (1 / eps - 1)
    for phi in [0.0, 1e-6, 0.1, 0.5, 0.9, 1 - 1e-9]:
        t1 = compiled._plug_offset(phi, R1, 0.5 * (1 - phi))
        ref = brentq(lambda t, p=phi: compiled._continuity(t, p, R1)[0], 0.0, 1 - phi, xtol=1e-300, rtol=4 * EPS)
        # the continuity residual is a difference of two plug speeds, each rounded: measured 3e-15 relative
        assert t1 == pytest.approx(ref, rel=2e-14, abs=1e-300), phi


@pytest.mark.parametrize("eps", H_OVER_D)
def test_annulus_gauss_legendre_rule_equals_adaptive_quadrature(eps):
    # The rule of 8, 16 or 32 points picked by h/d against scipy.integrate.quad of the same layer integrands.
    R1, R2 = 0.5 * (1 / eps - 1), 0.5 * (1 / eps + 1)
    for phi in [0.0, 0.3, 0.8]:
        t1 = compiled._plug_offset(phi, R1, 0.5 * (1 - phi))
        r_a, r_b, t2 = R1 + t1, R1 + t1 + phi, 1 - phi - t1
        j_in = integrate.quad(
            lambda s, t1=t1, r_b=r_b: s * (2 * R1 + s) * (t1 - s) * (r_b + R1 + s) / (R1 + s),
            0,
            t1,
            epsabs=0,
            epsrel=1e-13,
        )[0]
        j_out = integrate.quad(
            lambda s, t2=t2, r_a=r_a: s * (2 * R2 - s) * (t2 - s) * (R2 - s + r_a) / (R2 - s),
            0,
            t2,
            epsabs=0,
            epsrel=1e-13,
        )[0]
        assert compiled._layer_integrals(t1, phi, R1, eps) == pytest.approx(j_in + j_out, rel=1e-13)


def test_annulus_plug_fraction_is_the_root_brentq_finds():
    for eps in H_OVER_D:
        for N in [1e-12, 1e-3, 0.1, 1.0, 10.0, 1e3, 1e8, 1e12]:
            phi, t1 = compiled._annulus_phi(N, eps)
            ref = brentq(
                lambda p, e=eps, N=N: compiled._annulus_shape(p, e, 0.5 * (1 - p))[0] - N * p,
                0.0,
                1.0,
                xtol=1e-300,
                rtol=4 * EPS,
                maxiter=500,
            )
            # measured 1e-15; the shape factor's own rounding (P(x) near its series switch) is ~2e-14
            assert phi == pytest.approx(ref, rel=1e-13), (eps, N)
            # the plug offset returned with it is the plug position at that phi (warm-started Newton)
            assert t1 == pytest.approx(compiled._plug_offset(phi, 0.5 * (1 / eps - 1), 0.5 * (1 - phi)), rel=2e-14)


def test_annulus_flow_keeps_its_special_cases():
    # Q = 0: the break-away pressure drop with the sign bit of Q and a plug filling the gap; tau_y = 0: Newtonian.
    r = annulus_bingham_flow(np.array([0.0, -0.0, 1e-6]), np.array([1800.0, 1800.0, 0.0]), 13.0, 0.0546, 0.0143, 0.0008)
    dp_y = 2 * 1800.0 * 0.0546 / 0.0008
    assert r.pressure_drop[:2].tolist() == [dp_y, -dp_y]
    assert r.plug_fraction.tolist()[:2] == [1.0, 1.0] and r.plug_fraction[2] == 0.0
    assert math.isfinite(r.pressure_drop[2]) and r.pressure_drop[2] > 0
    # a denormal yield stress (its flow ratio overflows): the Newtonian annulus, not NaN (found by
    # tests/badinput/test_flow_properties.py; the previous implementation returned NaN too)
    newtonian = annulus_bingham_flow(1e-3, 0.0, 41.1, 0.21, 0.037, 0.017).pressure_drop
    assert annulus_bingham_flow(1e-3, 5e-324, 41.1, 0.21, 0.037, 0.017).pressure_drop == pytest.approx(
        newtonian, rel=1e-12
    )


# ------------------------------------------------------------------------------------------------------------------
# Herschel-Bulkley thin slit: the pressure drop of a flow (Newton on ln(tau_w - tau_y), one element at a time).
# ------------------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("m", [1.0, 0.6, 0.35, 1.4])
def test_herschel_bulkley_pressure_drop_is_the_root_brentq_finds(m):
    # Independent: brentq on the explicit flow rate q(dp) (scipy, to the last bit) from the yield pressure drop up,
    # over flows from 1e-12 to 1e-3 m^3/s and yield stresses from 0 to 1e5 Pa (near yield and far above it).
    from erdesign.flow.herschel_bulkley import herschel_bulkley_pressure_drop, herschel_bulkley_slit_flow_rate

    rng = np.random.default_rng(7)
    L, d, h = 0.0546, 0.0143, 0.0008
    n = 60
    Q = np.sign(rng.normal(size=n)) * 10 ** rng.uniform(-12, -3, n)
    tau_y = np.where(np.arange(n) % 6 == 0, 0.0, 10 ** rng.uniform(-2, 5, n))
    K = 13.0 * 1000 ** (1 - m) * np.exp(rng.normal(size=n))
    got = herschel_bulkley_pressure_drop(Q, tau_y, K, m, L, d, h)
    for q, ty, k, dp in zip(Q, tau_y, K, got):
        flow = lambda x: herschel_bulkley_slit_flow_rate(x, ty, k, m, L, d, h) - abs(q)  # noqa: E731, B023
        lo = 2 * ty * L / h
        hi = max(lo, 1.0) * 2
        while flow(hi) < 0:
            hi *= 2
        ref = brentq(flow, lo, hi, xtol=1e-300, rtol=4 * EPS, maxiter=500)
        assert dp == pytest.approx(math.copysign(ref, q), rel=2e-13)
    # no flow: the break-away pressure drop, with the sign bit of the flow
    assert herschel_bulkley_pressure_drop(-0.0, 100.0, 1.0, m, L, d, h) == -2 * 100.0 * L / h
    # a scalar stays a scalar; arrays of any shape broadcast
    assert isinstance(herschel_bulkley_pressure_drop(1e-6, 100.0, 1.0, m, L, d, h), float)
    grid = herschel_bulkley_pressure_drop(np.full((2, 3), 1e-6), [0.0, 1e2, 1e4], 1.0, m, [[L], [2 * L]], d, h)
    assert grid.shape == (2, 3) and grid[1, 0] == pytest.approx(2 * grid[0, 0], rel=1e-12)  # tau_y = 0: dp ~ L
