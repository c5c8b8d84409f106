"""erdesign.numerics.find_root: Chandrupatla's method without scipy's array-API framework gives scipy's
``find_root`` result element for element (the same iterates, the same stopping rules)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize.elementwise import find_root as scipy_find_root

from erdesign.damper.quasi_steady import mixed_gap_table
from erdesign.numerics import find_root


def _scipy(f, a, b, args, xatol, xrtol, maxiter=100):
    return scipy_find_root(f, (a, b), args=args, tolerances={"xatol": xatol, "xrtol": xrtol}, maxiter=maxiter).x


def test_smooth_roots_are_scipys_to_the_last_bit():
    rng = np.random.default_rng(7)
    c = rng.uniform(-5.0, 5.0, 500)
    p = rng.uniform(1.0, 7.0, 500)

    def f(x, c, p):
        return np.sign(x) * np.abs(x) ** p + x - c

    ours = find_root(f, np.full(500, -10.0), np.full(500, 10.0), args=(c, p), xatol=1e-12, xrtol=1e-14)
    theirs = _scipy(f, np.full(500, -10.0), np.full(500, 10.0), (c, p), 1e-12, 1e-14)
    assert np.array_equal(ours, theirs)
    assert np.max(np.abs(f(ours, c, p))) < 1e-9  # and they are roots


def test_a_root_on_a_jump_a_bad_bracket_and_the_iteration_limit_are_scipys():
    """A step (bisection-like convergence), a bracket without a sign change (NaN) and a stop at ``maxiter``."""
    x0 = np.array([0.3, -0.7, 0.1, 2.0])

    def f(x, x0):
        return np.where(x < x0, -1.0, 1.0) + 1e-3 * (x - x0)

    a, b = np.array([-1.0, -1.0, -1.0, -1.0]), np.array([1.0, 1.0, 1.0, 1.0])
    for maxiter in (5, 100):
        ours = find_root(f, a, b, args=(x0,), xatol=1e-10, xrtol=1e-12, maxiter=maxiter)
        theirs = _scipy(f, a, b, (x0,), 1e-10, 1e-12, maxiter)
        assert np.array_equal(ours, theirs, equal_nan=True)
    assert np.isnan(ours[3]) and ours[:3] == pytest.approx(x0[:3], abs=1e-9)


def test_the_leaky_gap_of_a_mixed_damper_is_scipys():
    """The residual of erdesign.effects.leakage on the moving-electrode table of a head, over a cycle with field."""
    table = mixed_gap_table(1e-3, 0.03, 0.01)
    n = 2000
    v = 0.05 * np.sin(np.linspace(0.0, 12.0, n))
    tau_y = np.resize([0.0, 5e3, 2e4], n)
    eta = np.full(n, 1.2)
    k = np.pi / 4 * (0.03**2 - 0.01**2) / 3e4

    def residual(dp, v, tau_y, eta):
        return dp - table.forces(v - dp * k, tau_y, eta, 0.02)[0]

    dp0 = table.forces(v, tau_y, eta, 0.02)[0]
    lo, hi = np.minimum(0.0, dp0) - 1.0, np.maximum(0.0, dp0) + 1.0
    scale = float(np.max(np.abs(dp0))) + 1.0
    ours = find_root(residual, lo, hi, args=(v, tau_y, eta), xatol=1e-10 * scale, xrtol=1e-12, maxiter=200)
    theirs = _scipy(residual, lo, hi, (v, tau_y, eta), 1e-10 * scale, 1e-12, 200)
    assert np.array_equal(ours, theirs)
