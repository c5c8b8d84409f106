r"""Compiled (numba) element loops of the flow kernels (SI floats / arrays; not public API).

Imported on first use by :mod:`erdesign.flow.mixed_mode`, :mod:`erdesign.flow.annulus_bingham` and
:mod:`erdesign.flow.bingham`, so that ``import erdesign.flow`` does not pay for numba; compiled code is cached on
disk (``cache=True``).  Each loop runs the scalar form of the closed forms documented in those modules, one element
at a time, so that a root is found per element from a good start instead of by whole-array iterations:

* :func:`find_root` - Chandrupatla's bracketed root finder with the tolerances of
  :func:`scipy.optimize.elementwise.find_root` (which the numpy kernels used before), for one element of the
  residuals it knows (:data:`MIXED_FLOW`: the fallback of the mixed-mode iteration; the leaky gaps below);
* :func:`couette_poiseuille`, :func:`mixed_gap_state` - Bingham Couette-Poiseuille flow in a slit with one moving
  wall (:func:`erdesign.flow.mixed_mode.couette_poiseuille_bingham`);
* :func:`annulus_shape_offset`, :func:`annulus_plug_fraction` - the exact Bingham annulus
  (:mod:`erdesign.flow.annulus_bingham`): plug position by safeguarded Newton, flow rate by Gauss-Legendre;
* :func:`slit_flow`, :func:`slit_flow_one_duct` - the thin-gap Bingham pressure drop dp(Q) in one pass
  (:func:`erdesign.flow.bingham.bingham_slit_flow`);
* :func:`hb_slit_pressure_drop` - the thin-gap Herschel-Bulkley pressure drop of a flow, by Newton on the log of
  the stress above yield, per element (:func:`erdesign.flow.herschel_bulkley.herschel_bulkley_pressure_drop`).
* :func:`head_table_forces` - the pressure drop and shear drag of a moving-electrode head read from its table
  (:class:`erdesign.damper.quasi_steady.MixedGapTable`), one pass;
* :func:`leaky_pressure_drop` - the pressure drop of a damper whose flow splits between its gap (a moving-electrode
  head read from its table, or thin valve slits) and a laminar bypass, by :func:`find_root` per element
  (:func:`erdesign.effects.leakage.leaky_pressure_drop`, whose generic path runs the same iteration on whole arrays).

``error_model="numpy"``: a division by zero gives inf or NaN as in numpy, never an exception, so the branches read
as the ``np.where`` forms they replace.  tests/test_flow_compiled.py checks these loops against independent
solutions (scipy's root finder and quadrature), never against themselves.
"""

from __future__ import annotations

import math

import numpy as np

from .._compile import guvectorize, njit

__all__ = [
    "annulus_plug_fraction",
    "annulus_shape_offset",
    "annulus_velocity",
    "couette_poiseuille",
    "find_root",
    "hb_slit_pressure_drop",
    "head_table_forces",
    "leaky_pressure_drop",
    "mixed_gap_state",
    "slit_flow",
    "slit_flow_one_duct",
]

_jit = njit(cache=True, nogil=True, error_model="numpy")

_EPS = float(np.finfo(float).eps)
_TINY = float(np.finfo(float).tiny)
_NO_TABLE = np.zeros(2)  # the table argument of a residual that reads none
#: the codes of erdesign.flow.mixed_mode.GapFlowRegime (tests/test_flow_compiled.py checks they agree)
FULLY_YIELDED, FLOATING_PLUG, PLUG_AT_MOVING_WALL, PLUG_AT_FIXED_WALL, BLOCKED = 0, 1, 2, 3, 4


# ------------------------------------------------------------------------------------------------------------------
# Root finding
# ------------------------------------------------------------------------------------------------------------------


#: The residuals :func:`find_root` solves (``kind``): the mixed-mode flow of one element (:func:`_mixed_residual`),
#: and the pressure drop of a damper whose flow splits between its gap and a laminar bypass
#: (:func:`_leaky_residual`: a moving-electrode head read from its table, or thin valve slits).
MIXED_FLOW, LEAKY_MIXED_HEAD, LEAKY_SLIT = 0, 1, 2


@_jit
def _residual(kind, x, p, table):
    """The residual of ``kind`` at x, with its parameters ``p`` (a tuple of 8 floats) and a table (or a dummy)."""
    if kind == MIXED_FLOW:
        return _mixed_residual(x, p[0], p[1], p[2])
    return _leaky_residual(kind, x, p, table)


@_jit
def find_root(kind, x1, x2, p, table, xatol, xrtol):
    """Root of the residual ``kind`` (:func:`_residual`) in the bracket [x1, x2] (ends of opposite signs), by
    Chandrupatla's method (1997).

    The iteration and the stopping rule of :func:`scipy.optimize.elementwise.find_root`: stop when
    ``|f| <= tiny`` or the bracket is narrower than ``|x_min| xrtol + xatol``; at most 200 steps; returns
    (x, converged).  NaN where the bracket does not hold a sign change."""
    f1 = _residual(kind, x1, p, table)
    f2 = _residual(kind, x2, p, table)
    # scipy's first step: t = 1/2 between the ends, x3 the end that is dropped
    t = 0.5
    x3, f3 = x2, f2
    for iteration in range(200):
        xmin, fmin = (x1, f1) if abs(f1) < abs(f2) else (x2, f2)
        if abs(fmin) <= _TINY:
            return xmin, True
        if (f1 > 0.0) == (f2 > 0.0) and f1 != 0.0 and f2 != 0.0:
            return math.nan, False
        if not (math.isfinite(x1) and math.isfinite(x2)) or (math.isnan(f1) and math.isnan(f2)):
            return math.nan, False
        dx = abs(x2 - x1)
        tol = abs(xmin) * xrtol + xatol
        if dx < tol:
            return xmin, True
        if iteration > 0:
            xi1 = (x1 - x2) / (x3 - x2)
            phi1 = (f1 - f2) / (f3 - f2)
            alpha = (x3 - x1) / (x2 - x1)
            t = 0.5
            if (1.0 - math.sqrt(1.0 - xi1)) < phi1 < math.sqrt(xi1):
                t = f1 / (f1 - f2) * f3 / (f3 - f2) - alpha * f1 / (f3 - f1) * f2 / (f2 - f3)
            tl = 0.5 * tol / dx
            t = min(max(t, tl), 1.0 - tl)
        x = x1 + t * (x2 - x1)
        fx = _residual(kind, x, p, table)
        if (fx > 0.0) == (f1 > 0.0) and fx != 0.0 and f1 != 0.0 or (fx == 0.0 and f1 == 0.0):
            x3, f3 = x1, f1
        else:
            x3, f3 = x2, f2
            x2, f2 = x1, f1
        x1, f1 = x, fx
    xmin = x1 if abs(f1) < abs(f2) else x2
    return xmin, False


# ------------------------------------------------------------------------------------------------------------------
# Mixed mode: Bingham Couette-Poiseuille flow in a slit (erdesign.flow.mixed_mode, module notes).  Stresses in units
# of tau_s, lengths in units of h, eps = tau_y/tau_s; the state is oriented so that G >= 0 and carried as the four
# offsets of the wall stresses from the band edges, lo0 = t0 + eps, hi0 = t0 - eps, lo1 = t1 + eps, hi1 = t1 - eps.
# ------------------------------------------------------------------------------------------------------------------


@_jit
def _offsets_pos(G, m, eps):
    """Band-edge offsets (lo0, hi0, lo1, hi1) of the wall stresses for G >= 0 and a mean strain rate m >= 0.

    Solves  mean of D over [t0, t0 + G] = m  for t0 in closed form, zone by zone.  The mean is non-decreasing in
    t0; it equals c = max(G - 2 eps, 0)^2 / (2 G) at t0 = -eps and G/2 at t0 = +eps."""
    excess = G - 2.0 * eps  # how far the stress span exceeds the band (straddle if > 0)
    two = 2.0 * eps
    if m == 0.0 and excess <= 0.0:  # D = 0 on the span: any t0 in the band; take the centre
        return eps - G / 2.0, -eps - G / 2.0, eps + G / 2.0, G / 2.0 - eps
    if m >= G / 2.0:  # the whole span above the band
        return m - G / 2.0 + two, m - G / 2.0, m + G / 2.0 + two, m + G / 2.0
    c = max(excess, 0.0) ** 2 / (2.0 * G)
    if m > c:
        # t0 inside the band, t1 above it: (t1 - eps)^2 = 2 G m.  lo0 = root - excess and hi0 = root - G are
        # written without cancellation (difference of squares).
        root = math.sqrt(2.0 * G * m)
        if excess > 0.0:
            lo0 = (2.0 * G * m - excess * excess) / (root + abs(excess))
        else:
            lo0 = root - excess
        return lo0, G * (2.0 * m - G) / (root + G), root + two, root
    # t0 below, t1 above the band: the mean of D is linear in t0.
    lo0 = G * m / excess - excess / 2.0
    hi1 = G * m / excess + excess / 2.0
    return lo0, lo0 - two, hi1 + two, hi1


@_jit
def mixed_state(G, U_bar, eps):
    """Oriented state (s, |G|, lo0, hi0, lo1, hi1) satisfying no slip, for a dimensionless gradient G of any sign."""
    s = -1.0 if G < 0.0 else 1.0
    Gp, mp = s * G, -s * U_bar  # the mean of D over the gap is -U_bar
    lo0, hi0, lo1, hi1 = _offsets_pos(Gp, abs(mp), eps)
    if mp < 0.0:
        # the mean of D is odd under t0 -> -t0 - G (then t1 -> -t0), which maps the offsets so
        return s, Gp, -hi1, -lo1, -hi0, -lo0
    return s, Gp, lo0, hi0, lo1, hi1


@_jit
def _flow_pos(G, lo0, hi0, lo1, hi1):
    """q_bar = -int_0^1 Y D(t0 + G Y) dY for G >= 0, one closed form per sheared layer."""
    # Below the band, D = lo0 + G Y: the whole gap (lo1 <= 0), a layer at the moving wall (lo0 < 0), or none.
    if lo1 <= 0.0:
        below = lo1 / 2.0 - G / 6.0
    elif lo0 < 0.0:
        below = lo0**3 / (6.0 * G**2)
    else:
        below = 0.0
    # Above the band, D = hi0 + G Y: the whole gap (hi0 >= 0), a layer of thickness w = hi1/G at the fixed wall
    # (hi1 > 0), or none.
    if hi0 >= 0.0:
        above = hi0 / 2.0 + G / 3.0
    elif hi1 > 0.0:
        w = hi1 / G
        above = hi1 * w / 2.0 * (1.0 - w / 3.0)
    else:
        above = 0.0
    return -(below + above)


@_jit
def _mixed_residual(G, U_bar, q_bar, eps):
    """q_bar(G) - q_bar with no slip enforced; non-increasing in G."""
    s, Gp, lo0, hi0, lo1, hi1 = mixed_state(G, U_bar, eps)
    return s * _flow_pos(Gp, lo0, hi0, lo1, hi1) - q_bar


@_jit
def _mixed_gradient_bracketed(U_bar, q_bar, eps):
    """G by Chandrupatla's method from the bracket G_N -+ (3 eps + 1e-3), widened should it miss; robust, and
    the fallback of :func:`_mixed_gradient`."""
    G_newton = 12.0 * (U_bar / 2.0 - q_bar)
    half = 3.0 * eps + 1e-3
    lo, hi = G_newton - half, G_newton + half
    for _ in range(60):
        if _mixed_residual(lo, U_bar, q_bar, eps) >= 0.0:
            break
        lo -= half
        half *= 2.0
    half = 3.0 * eps + 1e-3
    for _ in range(60):
        if _mixed_residual(hi, U_bar, q_bar, eps) <= 0.0:
            break
        hi += half
        half *= 2.0
    G, converged = find_root(
        MIXED_FLOW, lo, hi, (U_bar, q_bar, eps, 0.0, 0.0, 0.0, 0.0, 0.0), _NO_TABLE, 4.0 * _TINY, 4.0 * _EPS
    )
    return G if converged else math.nan


@_jit
def _mixed_gradient(U_bar, q_bar, eps):
    """Dimensionless gradient G of one element (NaN for non-finite input), the root of the non-increasing
    q_bar(G) - q_bar.

    The start is the valve-mode slit (the trigonometric root of :func:`erdesign.flow.bingham.bingham_slit_flow`)
    for the flow q_bar - U_bar/2 that the pressure drives in the Newtonian fluid: exact for U = 0 and for
    tau_y = 0.  One step with the slope of that slit, -(1 - phi)^2 (1 + 2 phi)/12, follows, then secant steps,
    kept inside G_N -+ (3 eps + 1e-3) (|G - G_N| <= 3 eps held on 4e5 random cases) by bisection, to a step below
    4 ulp: 3-6 evaluations of the closed forms instead of 9-21 for Chandrupatla's method from that bracket,
    which remains the fallback should the iteration stall or end on an end of the bracket it has not checked."""
    if not (math.isfinite(U_bar) and math.isfinite(q_bar) and math.isfinite(eps)):
        return math.nan
    G_newton = 12.0 * (U_bar / 2.0 - q_bar)  # exact for tau_y = 0
    if eps == 0.0:
        return G_newton
    if U_bar == 0.0 and q_bar == 0.0:  # blocked: the break-away value with the sign bit of q
        return -math.copysign(2.0 * eps, q_bar)
    if abs(U_bar) + abs(q_bar) < 1e-30 * eps:
        # flows some 30 decades below the yield stress's scale: the residual is flat to 1e-30 across the band and
        # the secant steps below lose its sign (a head creeping at 1e-100 m/s read the break-away drop with the
        # wrong sign); the bracketed root does not
        return _mixed_gradient_bracketed(U_bar, q_bar, eps)
    half = 3.0 * eps + 1e-3
    lo, hi = G_newton - half, G_newton + half  # residual >= 0 at lo, <= 0 at hi, until checked
    lo_checked = hi_checked = False
    q_valve = q_bar - 0.5 * U_bar
    N = 6.0 * abs(q_valve) / eps
    if N > 1e12:
        x0, slope = G_newton, -1.0 / 12.0
    else:
        m = math.sqrt(1.0 + (2.0 / 3.0) * N)
        phi = 2.0 * m * math.sin(math.asin(m**-3) / 3.0)
        x0 = -math.copysign(2.0 * eps / phi, q_valve)
        slope = -((1.0 - phi) ** 2) * (1.0 + 2.0 * phi) / 12.0
    x0 = min(max(x0, lo), hi)
    f0 = _mixed_residual(x0, U_bar, q_bar, eps)
    if f0 == 0.0:
        return x0
    if f0 > 0.0:
        lo, lo_checked = x0, True
    else:
        hi, hi_checked = x0, True
    x1 = x0 - f0 / slope if slope != 0.0 else 0.5 * (lo + hi)
    for _ in range(60):
        if abs(x1 - x0) <= 4.0 * _EPS * abs(x1) + 4.0 * _TINY:
            x = min(max(x1, lo), hi)
            tol = 8.0 * _EPS * abs(x) + 8.0 * _TINY
            if (abs(x - lo) <= tol and not lo_checked) or (abs(x - hi) <= tol and not hi_checked):
                break  # ended on an end never evaluated: the root may lie beyond
            return x
        if not (lo < x1 < hi):
            x1 = 0.5 * (lo + hi)
        f1 = _mixed_residual(x1, U_bar, q_bar, eps)
        if f1 == 0.0:
            return x1
        if f1 > 0.0:
            lo, lo_checked = x1, True
        else:
            hi, hi_checked = x1, True
        x2 = x1 - f1 * (x1 - x0) / (f1 - f0) if f1 != f0 else 0.5 * (lo + hi)
        x0, f0, x1 = x1, f1, x2
    return _mixed_gradient_bracketed(U_bar, q_bar, eps)


@_jit
def _mixed_solution(U, q, tau_y, eta, h):
    """(tau_s, eps, U_bar, G, s, lo0, hi0, lo1, hi1) of one element, in SI input (mixed_mode, module notes)."""
    scale = tau_y + eta * (abs(U) / h + abs(q) / h**2)
    if scale == 0.0:  # tau_y = U = q = 0: nothing moves, no stress
        scale = 1.0
    eps = tau_y / scale  # inf/inf for infinite inputs: NaN out
    U_bar = eta * U / (scale * h)
    q_bar = eta * q / (scale * h**2)
    G = _mixed_gradient(U_bar, q_bar, eps)
    s, _, lo0, hi0, lo1, hi1 = mixed_state(G, U_bar, eps)
    return scale, eps, U_bar, G, s, lo0, hi0, lo1, hi1


@_jit
def mixed_gap_state(U, q, tau_y, eta, h, out):
    """out[:, i] = (tau_s, G, s, lo0, hi0, lo1, hi1) of every element (1-D arrays of one size): the state from
    which the velocity profile is integrated."""
    for i in range(U.size):
        scale, _, _, G, s, lo0, hi0, lo1, hi1 = _mixed_solution(U[i], q[i], tau_y[i], eta[i], h[i])
        out[0, i], out[1, i], out[2, i] = scale, G, s
        out[3, i], out[4, i], out[5, i], out[6, i] = lo0, hi0, lo1, hi1
    return out


@_jit
def couette_poiseuille(U, q, tau_y, eta, h, out):
    """out[:, i] = (g, tau(0), tau(h), y1, y2, plug fraction, regime code) of every element (1-D arrays of one
    size, SI), the fields of :func:`erdesign.flow.mixed_mode.couette_poiseuille_bingham`."""
    for i in range(U.size):
        scale, eps, _, G, s, lo0, hi0, lo1, hi1 = _mixed_solution(U[i], q[i], tau_y[i], eta[i], h[i])
        Gp = s * G
        # plug edges: where the stress t0 + G Y crosses -eps and +eps (oriented frame), clipped to [0, 1]
        if Gp > 0.0:
            y1 = min(max(-lo0 / Gp, 0.0), 1.0)
            y2 = min(max(-hi0 / Gp, 0.0), 1.0)
        else:
            y1 = 1.0 if lo0 < 0.0 else 0.0
            y2 = 0.0 if hi0 > 0.0 else 1.0
        plug = y2 > y1 and eps > 0.0
        if not plug:
            y2 = y1  # no plug: a single point (the Newtonian fluid at rest too)
        at_moving = plug and lo0 >= 0.0
        at_fixed = plug and hi1 <= 0.0
        # wall stresses in the oriented frame, each from its nearer band edge, then back to the sign of G
        t0 = lo0 - eps if abs(lo0) < abs(hi0) else hi0 + eps
        t1 = lo1 - eps if abs(lo1) < abs(hi1) else hi1 + eps
        if math.isnan(G):
            y1 = y2 = math.nan
            regime = -1
        elif not plug:
            regime = FULLY_YIELDED
        elif at_moving and at_fixed:
            regime = BLOCKED
        elif at_moving:
            regime = PLUG_AT_MOVING_WALL
        elif at_fixed:
            regime = PLUG_AT_FIXED_WALL
        else:
            regime = FLOATING_PLUG
        hh = h[i]
        out[0, i] = G * scale / hh
        out[1, i] = s * t0 * scale
        out[2, i] = s * t1 * scale
        out[3, i] = y1 * hh
        out[4, i] = y2 * hh
        out[5, i] = y2 - y1
        out[6, i] = regime
    return out


# ------------------------------------------------------------------------------------------------------------------
# Exact Bingham annulus (erdesign.flow.annulus_bingham, module notes).  Lengths in units of h; R1 = inner radius,
# t1 = distance of the plug's inner edge from the inner wall, phi = plug thickness, eps = h/d.
# ------------------------------------------------------------------------------------------------------------------


def _gauss_legendre(n):
    """Gauss-Legendre nodes and weights on [0, 1]."""
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (x + 1.0), 0.5 * w


# Rules of 8, 16 and 32 points, chosen per element by h/d (see _layer_integrals).
_GL8_X, _GL8_W = _gauss_legendre(8)
_GL16_X, _GL16_W = _gauss_legendre(16)
_GL32_X, _GL32_W = _gauss_legendre(32)


@_jit
def _p_log_of(x, log1p_x):
    """(1 + x) ln(1 + x) - x given ln(1 + x), accurate as x -> 0 (series below 1e-2, first omitted term
    x^11/110)."""
    if abs(x) < 1e-2:
        s = 0.0
        for k in range(2, 11):
            s += (-1.0) ** k * x**k / (k * (k - 1))
        return s
    return (1.0 + x) * log1p_x - x


@_jit
def _p_log(x):
    """(1 + x) ln(1 + x) - x, accurate as x -> 0."""
    return _p_log_of(x, math.log1p(x))


@_jit
def _q_log(y):
    """y - ln(1 + y), accurate as y -> 0 (series below 1e-2, first omitted term y^11/11)."""
    if abs(y) < 1e-2:
        s = 0.0
        for k in range(2, 11):
            s += (-1.0) ** k * y**k / k
        return s
    return y - math.log1p(y)


@_jit
def _plug_speed_inner(t1, phi, R1):
    """2 eta u_p / (G h^2) integrated from the inner wall."""
    r_b = R1 + t1 + phi
    return 0.5 * t1 * t1 + r_b * R1 * _p_log(t1 / R1)


@_jit
def _continuity(t1, phi, R1):
    """Plug speed from the inner wall minus plug speed from the outer wall, and its derivative in t1 (> 0)."""
    r_a = R1 + t1
    r_b = r_a + phi
    t2 = 1.0 - phi - t1
    x = t1 / R1
    log1p_x = math.log1p(x)
    p = _p_log_of(x, log1p_x)
    y = t2 / r_b
    q = _q_log(y)
    value = (0.5 * t1 * t1 + r_b * R1 * p) - (0.5 * t2 * t2 + r_a * r_b * q)  # the two plug speeds
    slope = (t1 + R1 * p + r_b * log1p_x) - (-t2 + (r_a + r_b) * q - r_a * y)
    return value, slope


@_jit
def _plug_offset(phi, R1, start):
    """t1 where the two plug speeds agree, by Newton's method kept inside the bracket [0, 1 - phi] (bisection
    where a step would leave it), to a few ulp; ``start`` is the first guess."""
    lo, hi = 0.0, 1.0 - phi
    if hi <= 0.0:
        return 0.0  # the plug fills the gap
    t = min(max(start, lo), hi)
    for _ in range(100):
        f, slope = _continuity(t, phi, R1)
        if f == 0.0:
            return t
        if f < 0.0:
            lo = t
        else:
            hi = t
        step = f / slope
        new = t - step
        if abs(step) <= 1e-9 * abs(t):
            # quadratic convergence: the error after this step is of order step^2, below rounding (iterating
            # further only chases the rounding noise of f)
            return min(max(new, lo), hi)
        if not (lo < new < hi):
            new = 0.5 * (lo + hi)
        if hi - lo <= 4.0 * _EPS * abs(new) + 1e-300:
            return new
        t = new
    return t


@_jit
def _layer_integrals(t1, phi, R1, eps):
    """J_in + J_out of the flow rate (module notes), in units of h^4, by an 8-, 16- or 32-point Gauss-Legendre
    rule: the integrands are a cubic plus a pole at a distance of at least R1 from the interval, so the error
    falls like rho^(-2n), rho = a + sqrt(a^2 - 1), a = d/h; n is the smallest rule with rho^(-2n) < 1e-20."""
    if eps <= 0.1:
        X, W = _GL8_X, _GL8_W
    elif eps <= 0.3:
        X, W = _GL16_X, _GL16_W
    else:
        X, W = _GL32_X, _GL32_W
    R2 = R1 + 1.0
    r_a = R1 + t1
    r_b = r_a + phi
    t2 = 1.0 - phi - t1
    j_in = 0.0
    j_out = 0.0
    for k in range(X.size):
        s = t1 * X[k]
        j_in += W[k] * (s * (2.0 * R1 + s) * (t1 - s) * (r_b + R1 + s) / (R1 + s))
        s = t2 * X[k]
        r = R2 - s
        j_out += W[k] * (s * (2.0 * R2 - s) * (t2 - s) * (r + r_a) / r)
    return t1 * j_in + t2 * j_out


@_jit
def _annulus_shape(phi, eps, start):
    """(S, t1): shape factor Q/Q_N and plug offset for plug fraction phi in [0, 1] and eps = h/d."""
    if not phi < 1.0:  # blocked (and NaN, as the numpy kernel did)
        return 0.0, 0.0
    R1 = 0.5 * (1.0 / eps - 1.0)
    t1 = _plug_offset(phi, R1, start)
    # S = 6 u_p - 6 (h/d)(J_in + J_out), u_p in units of G h^2/(2 eta)
    return 6.0 * _plug_speed_inner(t1, phi, R1) - 6.0 * eps * _layer_integrals(t1, phi, R1, eps), t1


@_jit
def annulus_shape_offset(phi, eps, out):
    """out[0] = S and out[1] = t1 of every element of 1-D arrays phi and eps."""
    for i in range(phi.size):
        out[0, i], out[1, i] = _annulus_shape(phi[i], eps[i], 0.5 * (1.0 - phi[i]))
    return out


@_jit
def _annulus_phi(N, eps):
    """Plug fraction phi in (0, 1) of the flow ratio N = dp_N/dp_y > 0: the root of f = S(phi) - N phi.

    f(0) = S(0) > 0 and f(1) = -N < 0 bracket the root without an evaluation.  The thin-gap root (the
    trigonometric root of :func:`erdesign.flow.bingham.bingham_slit_flow`) starts the iteration, in error by
    O((h/d)^2); one step with the slope of the thin-gap f follows, then secant steps, each kept inside the
    bracket (bisection where a step would leave it), to a step below 4 ulp.  Each evaluation of S starts the plug
    position from the last one, shifted by half the change of phi, so its Newton iteration takes one or two steps.
    Returns (phi, t1), t1 the plug offset at phi."""
    lo, hi = 0.0, 1.0
    R1 = 0.5 * (1.0 / eps - 1.0)
    m = math.sqrt(1.0 + (2.0 / 3.0) * N)
    x0 = 2.0 * m * math.sin(math.asin(m**-3) / 3.0)
    S, t = _annulus_shape(x0, eps, 0.5 * (1.0 - x0))
    f0 = S - N * x0
    if f0 == 0.0:
        return x0, t
    if f0 > 0.0:
        lo = x0
    else:
        hi = x0
    x1 = x0 - f0 / (-1.5 * (1.0 - x0 * x0) - N)
    for _ in range(200):
        if abs(x1 - x0) <= 4.0 * _EPS * abs(x1):
            x1 = min(max(x1, lo), hi)  # converged (the step may round onto an end of the bracket)
            return x1, _plug_offset(x1, R1, t + 0.5 * (x0 - x1))
        if not (lo < x1 < hi):
            x1 = 0.5 * (lo + hi)
            if hi - lo <= 4.0 * _EPS * abs(x1):
                return x1, _plug_offset(x1, R1, t + 0.5 * (x0 - x1))
        S, t = _annulus_shape(x1, eps, t + 0.5 * (x0 - x1))
        f1 = S - N * x1
        if f1 == 0.0:
            return x1, t
        if f1 > 0.0:
            lo = x1
        else:
            hi = x1
        x2 = x1 - f1 * (x1 - x0) / (f1 - f0) if f1 != f0 else 0.5 * (lo + hi)
        x0, f0, x1 = x1, f1, x2
    return x1, _plug_offset(x1, R1, t + 0.5 * (x0 - x1))


@_jit
def annulus_plug_fraction(ratio, eps, out):
    """out[0] = plug fraction phi and out[1] = plug offset t1 of every element, for the flow ratio
    N = dp_N/dp_y > 0 and eps = h/d (1-D arrays)."""
    for i in range(ratio.size):
        out[0, i], out[1, i] = _annulus_phi(ratio[i], eps[i])
    return out


@_jit
def annulus_velocity(rho, phi, eps, out):
    """2 eta u/(G h^2) at radius rho = r/h of every element (1-D arrays; zero for a blocked gap, phi >= 1)."""
    for i in range(rho.size):
        p, e, r = phi[i], eps[i], rho[i]
        if not p < 1.0:
            out[i] = 0.0
            continue
        R1 = 0.5 * (1.0 / e - 1.0)
        t1 = _plug_offset(p, R1, 0.5 * (1.0 - p))
        r_a = R1 + t1
        r_b = r_a + p
        if r <= r_a:
            # every term non-negative (no cancellation as h/d -> 0)
            x = max(r - R1, 0.0) / R1
            out[i] = 0.5 * (t1 * t1 - (r_a - r) ** 2) + r_b * R1 * _p_log(x) + r_b * (r_a - r) * math.log1p(x)
        elif r >= r_b:
            t2 = 1.0 - p - t1
            y = max(R1 + 1.0 - r, 0.0) / r
            out[i] = 0.5 * (t2 * t2 - (r - r_b) ** 2) + r_a * r * _q_log(y) + r_a * (r - r_b) * math.log1p(y)
        else:
            out[i] = _plug_speed_inner(t1, p, R1)
    return out


# ------------------------------------------------------------------------------------------------------------------
# Thin-gap Bingham slit (erdesign.flow.bingham, module notes): dp(Q) in one pass.
# ------------------------------------------------------------------------------------------------------------------


@_jit
def _slit_plug_fraction(N):
    """phi in (0, 1] of phi^3 - (3 + 2N) phi + 2 = 0: the trigonometric root, and below N = 0.5 six Newton steps
    on the cubic written for the sheared fraction 1 - phi (bingham._plug_and_sheared_fractions, element-wise)."""
    if N == 0.0:
        return 1.0  # the blocked gap exactly (no 0/0 in the Newton step)
    if N < 0.5:
        e = math.sqrt(2.0 * N / 3.0)
        for _ in range(6):
            g = e * e * (3.0 - e) - 2.0 * N * (1.0 - e)
            slope = 6.0 * e - 3.0 * e * e + 2.0 * N
            if slope > 0.0:
                e = e - g / slope
        return 1.0 - e
    m = math.sqrt(1.0 + (2.0 / 3.0) * N)
    return 2.0 * m * math.sin(math.asin(m**-3) / 3.0)


@_jit
def _slit_drop(dp_y, dp_n, Q):
    """(pressure drop with the sign of Q, plug fraction) of a thin Bingham slit from its yield pressure drop
    dp_y = 2 tau_y L / h and the Newtonian one dp_n = 12 eta L |Q| / (pi d h^3)."""
    if dp_y > 1e-12 * dp_n:
        p = _slit_plug_fraction(dp_n / dp_y)
        return math.copysign(dp_y / p, Q), p
    # a yield stress below 1e-12 of the viscous pressure drop: the large-ratio limit, exact to 1e-12
    return math.copysign(dp_n + 1.5 * dp_y, Q), 0.0


@guvectorize(
    ["void(float64, float64, float64, float64, float64, float64, float64[:], float64[:])"],
    "(),(),(),(),(),()->(),()",
    nopython=True,
    cache=True,
)
def slit_flow(Q, tau_y, eta, L, d, h, dp, phi):  # pragma: no cover - compiled; run by tests/test_flow_compiled.py
    """(dp, phi): pressure drop (sign of Q) and plug fraction, the fields of
    :func:`erdesign.flow.bingham.bingham_slit_flow`; a generalised ufunc, so the arguments broadcast without
    copies."""
    dp_y = 2.0 * tau_y * L / h
    dp_n = 12.0 * eta * L * abs(Q) / (math.pi * d * h**3)
    dp[0], phi[0] = _slit_drop(dp_y, dp_n, Q)


@_jit
def slit_flow_one_duct(Q, tau_y, eta, L, d, h, dp, phi):
    """:func:`slit_flow` for many flows through one duct (scalar tau_y, eta, L, d, h; 1-D contiguous Q): the
    duct's constants computed once, a plain loop (a generalised ufunc calls a function per element).  An empty
    ``phi`` is not written (the pressure drop alone)."""
    plug = phi.size > 0
    dp_y = 2.0 * tau_y * L / h
    per_flow = 12.0 * eta * L / (math.pi * d * h**3)
    for i in range(Q.size):
        dp[i], p = _slit_drop(dp_y, per_flow * abs(Q[i]), Q[i])
        if plug:
            phi[i] = p
    return dp, phi


# ------------------------------------------------------------------------------------------------------------------
# Herschel-Bulkley thin slit: the pressure drop of a flow (erdesign.flow.herschel_bulkley)
# ------------------------------------------------------------------------------------------------------------------


@_jit
def _hb_log_flow_and_slope(S, ty, p, cK):
    """ln q of the thin Herschel-Bulkley slit at the wall stress ty + S (q: flow per unit width [m^2/s]) and its
    slope in ln S.  q = cK tw^-2 G, G = S^(p+2)/(p+2) + ty S^(p+1)/(p+1), tw = ty + S, so with G' = S^p tw:
    d ln q / d ln S = S (S^p tw / G - 2 / tw)."""
    tw = ty + S
    Sp = S**p
    G = S * Sp * (S / (p + 2.0) + ty / (p + 1.0))
    return math.log(cK * G / (tw * tw)), S * (Sp * tw / G - 2.0 / tw)


@_jit
def hb_slit_pressure_drop(Qa, tau_y, K, m, L, d, h, out):
    """Pressure drop [Pa] at which the thin Herschel-Bulkley slit passes the flows ``Qa`` >= 0 [m^3/s], per element
    (every argument a 1-D array of the same length; ``out`` written and returned).

    Newton on y = ln S (S = tw - tau_y, the wall stress above yield), where ln q is nearly linear: exactly so in
    both limits, q -> cK S^p / (p + 2) far above yield (the power law) and q -> cK S^(p+1) / ((p+1) tau_y) near it.
    q lies below both limits, so the larger of their two roots is a lower bound of S and the start; a step that
    leaves the bracket is replaced by bisection.  Stops when the step or the bracket is below 1e-13 in ln S (at most
    that in ln dp: the tolerance of scipy's find_root, which this loop replaces).  Qa = 0 gives the break-away
    pressure drop dp_y."""
    for i in range(Qa.size):
        p = 1.0 / m[i]
        H2 = 0.25 * h[i] * h[i]
        to_tau = h[i] / (2.0 * L[i])
        ty = tau_y[i]
        if Qa[i] == 0.0:
            out[i] = ty / to_tau
            continue
        target = Qa[i] / (math.pi * d[i])
        cK = 2.0 * H2 * K[i] ** (-p)
        S = (target * (p + 2.0) / cK) ** (1.0 / p)  # the power law's root: exact at ty = 0
        if ty > 0.0:
            S = max(S, ((p + 1.0) * ty * target / cK) ** (1.0 / (p + 1.0)))
            lo, hi = math.log(S), math.inf
            y = lo
            goal = math.log(target)
            for _ in range(200):
                lq, slope = _hb_log_flow_and_slope(math.exp(y), ty, p, cK)
                f = lq - goal
                if f == 0.0:
                    break
                if f > 0.0:
                    hi = y
                else:
                    lo = y
                step = f / slope if slope > 0.0 else math.nan
                if abs(step) <= 1e-13:
                    y -= step  # converged (a step this small may round onto the bracket's end)
                    break
                y -= step
                if not (lo < y < hi):
                    y = 0.5 * (lo + hi) if hi < math.inf else lo + 1.0
                if hi - lo <= 1e-13:
                    break
            S = math.exp(y)
        out[i] = (ty + S) / to_tau
    return out


# ------------------------------------------------------------------------------------------------------------------
# A laminar bypass in parallel with the gap (erdesign.effects.leakage): dp = dp_gap(v - dp k), k = A_p / C_l
# ------------------------------------------------------------------------------------------------------------------


@_jit
def _table_read(w, table):
    """Linear interpolation in ``table``, given on a uniform grid of w in [0, 1] (np.interp's value, for w in
    [0, 1]; NaN outside, e.g. for NaN)."""
    if not 0.0 <= w <= 1.0:
        return math.nan
    n = table.size - 1
    x = w * n
    j = min(int(x), n - 1)
    return table[j] + (x - j) * (table[j + 1] - table[j])


@_jit
def _head_w(u, tau_y, eta, h):
    """(w, scale) of a moving-electrode gap at flow speed u: w = sqrt(eta |u| / scale), scale = eta |u| + tau_y h
    (w = 1 where scale is not positive, as :meth:`MixedGapTable.forces`)."""
    scale = eta * abs(u) + tau_y * h
    return (math.sqrt(eta * abs(u) / scale) if scale > 0.0 else 1.0), scale


@_jit
def _head_table_drop(u, tau_y, eta, h, L, table):
    """Pressure drop [Pa] of a moving-electrode gap at flow speed u (= the head's speed), read from its table of
    G_p on a uniform grid of w in [0, 1] (:class:`erdesign.damper.quasi_steady.MixedGapTable`)."""
    w, scale = _head_w(u, tau_y, eta, h)
    return math.copysign(1.0, u) * _table_read(w, table) * scale / h**2 * L


@_jit
def head_table_forces(u, tau_y, eta, L, h, Dp, pressure, shear, dp, drag):
    """dp[i], drag[i] = the pressure drop [Pa] and shear drag [N] of a moving-electrode gap at flow speed u[i]
    (1-D arrays of one size; ``pressure``, ``shear``: the head's tables G_p, G_s on a uniform grid of w in [0, 1];
    an empty ``drag``: the pressure drop alone), the loop of :meth:`erdesign.damper.quasi_steady.MixedGapTable.forces`."""
    with_drag = drag.size > 0
    for i in range(u.size):
        w, scale = _head_w(u[i], tau_y[i], eta[i], h)
        sign = math.copysign(1.0, u[i])
        dp[i] = sign * _table_read(w, pressure) * scale / h**2 * L[i]
        if with_drag:
            drag[i] = -sign * _table_read(w, shear) * scale / h * math.pi * Dp * L[i]
    return dp, drag


@_jit
def _leaky_gap_drop(kind, u, p, table):
    """dp_gap(u) of a head (``kind`` LEAKY_MIXED_HEAD, p = (v, k, tau_y, eta, h, L, ...)) or of n thin valve slits
    (LEAKY_SLIT, p = (v, k, tau_y, eta, h, L, d, A_p/n)) passing the flow of a piston at speed u."""
    tau_y, eta, h, L = p[2], p[3], p[4], p[5]
    if kind == LEAKY_MIXED_HEAD:
        return _head_table_drop(u, tau_y, eta, h, L, table)
    Q = u * p[7]
    dp, _ = _slit_drop(2.0 * tau_y * L / h, 12.0 * eta * L * abs(Q) / (math.pi * p[6] * h**3), Q)
    return dp


@_jit
def _leaky_residual(kind, dp, p, table):
    """dp - dp_gap(v - dp k), increasing in dp (p as in :func:`_leaky_gap_drop`)."""
    return dp - _leaky_gap_drop(kind, p[0] - dp * p[1], p, table)


@_jit
def leaky_pressure_drop(kind, v, k, tau_y, eta, h, L, d, flow_per_speed, table, dp0, xatol, xrtol, out):
    """out[i] = the root dp of dp = dp_gap(v_i - dp k) (``kind`` LEAKY_MIXED_HEAD or LEAKY_SLIT, 1-D arrays v,
    tau_y, eta, dp0 of one size) in the bracket between 0 and the no-leak drop dp0 (dp0 itself where that is 0):
    :func:`erdesign.effects.leakage.leaky_pressure_drop` element by element, with the same root finder and
    tolerances.  ``d`` and ``flow_per_speed`` (A_p/n) are the slits'; ``table`` the head's (a dummy for slits)."""
    for i in range(v.size):
        lo, hi = min(0.0, dp0[i]), max(0.0, dp0[i])
        if math.isnan(dp0[i]) or lo == hi:
            out[i] = dp0[i]
            continue
        p = (v[i], k, tau_y[i], eta[i], h, L, d, flow_per_speed)
        creep = v[i] / k
        if abs(creep) <= _leaky_gap_drop(kind, 0.0, p, table):
            # below the break-away pressure the gap is blocked (u = 0) and the bypass passes all the flow: the
            # root on the jump of the gap law, where the bracketed iteration would end within its tolerance
            out[i] = creep
            continue
        out[i], _ = find_root(kind, lo, hi, p, table, xatol, xrtol)
    return out
