r"""Compiled (numba) time-stepping loops of the hysteretic models (SI floats / arrays; not public API).

Imported lazily by :mod:`erdesign.models._kernels` the first time a hysteretic model is simulated, so that
``import erdesign.models`` does not pay for numba; compiled code is cached on disk (``cache=True``), so a new
process loads it instead of compiling again.

* :func:`riccati_step` - exact travel of the Bouc-Wen variable along a monotone input (n = 1, 2 in closed form);
* :func:`bouc_wen_state` - the Bouc-Wen variable for a piecewise-linear displacement (exact per sample);
* :func:`modified_bouc_wen` - Spencer et al. (1997): the filtered control, the internal displacement and the
  Bouc-Wen variable, by classical Runge-Kutta sub-steps in w with z exact along the step (see its docstring);
* :func:`extended_bingham_force` - the Gamota-Filisko model by backward Euler on its dead-zone form;
* :func:`affine_recurrence` - :math:`y_{n+1} = c_n y_n + d_n` (Dahl, LuGre, first-order lags) in one pass;
* :func:`stop_operator`, :func:`series_viscoplastic`, :func:`mass_on_damper` - the elasto-slide element (SVES,
  Zhang-Huang), the series visco-plastic element (VEP, nkVEP) and a mass on a nonlinear damper (Bass, Sims) of the
  MR-model review's catalogue.

The arithmetic is that of the Python kernels it replaces; tests/test_models.py checks it against
:func:`scipy.integrate.solve_ivp` (LSODA / Radau at rtol 1e-10), never against itself.
"""

from __future__ import annotations

import math

import numpy as np

from .._compile import njit

__all__ = [
    "riccati_step",
    "bouc_wen_state",
    "modified_bouc_wen",
    "extended_bingham_force",
    "affine_recurrence",
    "stop_operator",
    "series_viscoplastic",
    "mass_on_damper",
    "bouc_wen_state_varying",
]

_jit = njit(cache=True, nogil=True)


@_jit
def _linear_const(z, L, a, delta):
    """dz/dxi = delta - a z over L (exact)."""
    if a == 0.0:
        return z + delta * L
    zeq = delta / a
    return zeq + (z - zeq) * math.exp(-a * L)


@_jit
def _linear_distance_to_zero(z, a, delta):
    """Travel for dz/dxi = delta - a z to bring z < 0 up to 0 (inf if it never does)."""
    if a == 0.0:
        return -z / delta
    zeq = delta / a
    if zeq <= 0.0 and z <= zeq:
        return math.inf
    ratio = (0.0 - zeq) / (z - zeq)
    return -math.log(ratio) / a if ratio > 0.0 else math.inf


@_jit
def _riccati_const(z, L, a, delta):
    """dz/dxi = delta - a z^2 over L with a constant (exact)."""
    if a > 0.0:
        r = math.sqrt(delta / a)
        q = z / r
        if abs(q) < 1.0:
            return r * math.tanh(math.atanh(q) + a * r * L)
        if q == 1.0 or q == -1.0:
            return z
        # |z| > r: coth branch (decays towards r from above; from below -r it diverges, clipped to stay finite)
        arg = 0.5 * math.log((q + 1.0) / (q - 1.0)) + a * r * L
        if arg == 0.0:
            return -1e300
        return r / math.tanh(arg)
    if a == 0.0:
        return z + delta * L
    b = -a
    r = math.sqrt(delta / b)
    arg = math.atan(z / r) + b * r * L
    return r * math.tan(min(arg, 0.5 * math.pi - 1e-9))


@_jit
def riccati_step(z, L, beta, gamma, delta, n):
    r"""Advance :math:`dz/d\xi = \delta - \gamma z|z|^{n-1} - \beta|z|^n` by :math:`\xi = L \ge 0`.  Exact for
    n = 2 (tanh / tan / linear solutions on each side of z = 0) and n = 1 (exponentials), RK4 sub-steps with
    :math:`h\lambda \le 1/2` otherwise."""
    if L <= 0.0:
        return z
    if n == 2.0:
        if z < 0.0:
            a = beta - gamma
            if a > 0.0:
                r = math.sqrt(delta / a)
                if z <= -r:  # outside the attracting range: never reaches 0
                    return _riccati_const(z, L, a, delta)
                L0 = -math.atanh(z / r) / (a * r)
            elif a == 0.0:
                L0 = -z / delta
            else:
                b = -a
                r = math.sqrt(delta / b)
                L0 = -math.atan(z / r) / (b * r)
            if L0 >= L:
                return _riccati_const(z, L, a, delta)
            z = 0.0
            L = L - L0
        return _riccati_const(z, L, beta + gamma, delta)
    if n == 1.0:
        if z < 0.0:
            a = gamma - beta
            L0 = _linear_distance_to_zero(z, a, delta)
            if L0 >= L:
                return _linear_const(z, L, a, delta)
            z = 0.0
            L = L - L0
        return _linear_const(z, L, gamma + beta, delta)
    s = abs(beta) + abs(gamma)
    lam = n * s * max(abs(z), (delta / max(s, 1e-300)) ** (1.0 / n)) ** (n - 1.0)
    m = 1 + int(L * lam / 0.5)
    h = L / m
    for _ in range(m):
        q = z
        aq = abs(q)
        k1 = delta - (gamma * q + beta * aq) * aq ** (n - 1.0)
        q = z + 0.5 * h * k1
        aq = abs(q)
        k2 = delta - (gamma * q + beta * aq) * aq ** (n - 1.0)
        q = z + 0.5 * h * k2
        aq = abs(q)
        k3 = delta - (gamma * q + beta * aq) * aq ** (n - 1.0)
        q = z + h * k3
        aq = abs(q)
        k4 = delta - (gamma * q + beta * aq) * aq ** (n - 1.0)
        z += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
    return z


@_jit
def _travel(z, dw, beta, gamma, delta, n):
    """z after a monotone travel dw (either sign) of the Bouc-Wen input."""
    if dw >= 0.0:
        return riccati_step(z, dw, beta, gamma, delta, n)
    return -riccati_step(-z, -dw, beta, gamma, delta, n)


@_jit
def bouc_wen_state(x, beta, gamma, delta, n, z0):
    """Bouc-Wen variable at the samples of a displacement that is linear between them (exact steps)."""
    N = x.size
    out = np.empty(N)
    z = z0
    out[0] = z
    for i in range(1, N):
        z = _travel(z, x[i] - x[i - 1], beta, gamma, delta, n)
        out[i] = z
    return out


@_jit
def _lagged(u0, r, C, tau, s):
    """First-order lag of u0 + r s at time s into the step, from its value u0 - r tau + C at s = 0."""
    return u0 + r * (s - tau) + C * math.exp(-s / tau)


@_jit
def _setup2(q0, beta, gamma, delta, r1, k1, r2, k2):
    """Constants of the n = 2 travel from q0 in one direction (see :func:`riccati_step`): the distance L0 to
    q = 0 (0 when q0 >= 0, inf when never reached) and the tanh phases c1 (q < 0) and c2 (q >= 0); a NaN phase
    means 'not the tanh branch: use _riccati_const'."""
    nan = math.nan
    c1 = nan
    if q0 >= 0.0:
        L0 = 0.0
        q2 = q0
    else:
        a1 = beta - gamma
        if a1 > 0.0:
            if q0 <= -r1:
                L0 = math.inf
            else:
                c1 = math.atanh(q0 / r1)
                L0 = -c1 / k1
        elif a1 == 0.0:
            L0 = -q0 / delta
        else:
            b = -a1
            rb = math.sqrt(delta / b)
            L0 = -math.atan(q0 / rb) / (b * rb)
        q2 = 0.0
    c2 = nan
    if k2 > 0.0 and abs(q2) < r2:
        c2 = math.atanh(q2 / r2)
    return L0, c1, c2


@_jit
def _eval2(q0, L, L0, c1, c2, beta, gamma, delta, r1, k1, r2, k2):
    """q after a travel L >= 0 from q0 (n = 2), from the constants of :func:`_setup2`: one tanh."""
    if L <= 0.0:
        return q0
    q = q0
    if q0 < 0.0:
        if L0 >= L:
            if c1 == c1:
                return r1 * math.tanh(c1 + k1 * L)
            return _riccati_const(q0, L, beta - gamma, delta)
        L = L - L0
        q = 0.0
    if c2 == c2:
        return r2 * math.tanh(c2 + k2 * L)
    return _riccati_const(q, L, beta + gamma, delta)


@_jit
def _rate(uf, xd, w, dw, zz, laws):
    """dw/dt at control uf, w + dw, with the Bouc-Wen variable zz there; ``laws`` = (the coefficients of alpha, c0
    and c1 in uf, four each, constant first; k0)."""
    aa, ab, ac, ad, c0a, c0b, c0c, c0d, c1a, c1b, c1c, c1d, k0 = laws
    al = aa + (ab + (ac + ad * uf) * uf) * uf
    c0 = c0a + (c0b + (c0c + c0d * uf) * uf) * uf
    c1 = c1a + (c1b + (c1c + c1d * uf) * uf) * uf
    return (c1 * xd - al * zz - k0 * (w + dw)) / (c0 + c1)


@_jit
def _zt(z, dw, C, beta, gamma, delta, r1, k1, r2, k2):
    """z after a travel dw from z (n = 2), with the travel constants of either direction computed on first use
    and kept in C = [have+, L0+, c1+, c2+, have-, L0-, c1-, c2-] for the rest of the sub-step."""
    if dw >= 0.0:
        if C[0] == 0.0:
            C[1], C[2], C[3] = _setup2(z, beta, gamma, delta, r1, k1, r2, k2)
            C[0] = 1.0
        return _eval2(z, dw, C[1], C[2], C[3], beta, gamma, delta, r1, k1, r2, k2)
    if C[4] == 0.0:
        C[5], C[6], C[7] = _setup2(-z, beta, gamma, delta, r1, k1, r2, k2)
        C[4] = 1.0
    return -_eval2(-z, -dw, C[5], C[6], C[7], beta, gamma, delta, r1, k1, r2, k2)


@_jit
def _z_after(z, dw, two, C, beta, gamma, delta, n, r1, k1, r2, k2):
    """z after a travel dw from z: by the travel constants kept in C for n = 2 (:func:`_zt`), else
    :func:`_travel`."""
    if two:
        return _zt(z, dw, C, beta, gamma, delta, r1, k1, r2, k2)
    return _travel(z, dw, beta, gamma, delta, n)


@_jit
def modified_bouc_wen(
    t,
    x,
    u,
    eta,
    aa,
    ab,
    ac,
    ad,
    c0a,
    c0b,
    c0c,
    c0d,
    c1a,
    c1b,
    c1c,
    c1d,
    k0,
    beta,
    gamma,
    delta,
    n,
    theta,
    max_sub,
    plan,
):
    r"""States (u_f, w, z) of Spencer's modified Bouc-Wen model at the samples.

    Input: displacement and dimensionless control linear between samples.  On each step:

    * the filtered control :math:`\dot u_f = -\eta(u_f - u)` is exact at any time in the step;
    * along a monotone travel of :math:`w = x - y` the Bouc-Wen variable is a function of w alone,
      :math:`z = Z(w; z_n, w_n)` (:func:`riccati_step`, exact for n = 1, 2), so
      :math:`\dot w = (c_1\dot x - \alpha Z(w) - k_0 w)/(c_0 + c_1)` is one scalar ODE: classical RK4 in w on
      m sub-steps, with m chosen so that :math:`h\lambda \le \theta`, :math:`\lambda = (|\alpha|\max|dZ/dw| + |k_0|)
      /(c_0 + c_1)` the rate of the coupling (the stiff saturation of z is inside Z, exact).

    A sub-step in which w reverses direction is first order (z takes one branch of its hysteresis); reversals are
    rare, so the global error stays fourth order in the sub-step in practice (tests/test_models.py: relative
    error <= 1e-4 at 3 kHz against LSODA at rtol 1e-10).  For n = 2 the travel constants (atanh phases, distance
    to z = 0) are computed once per sub-step, so each stage costs one tanh.

    ``plan`` (int array of N - 1 entries, or empty): the number of sub-steps of each step.  An entry > 0 is used as
    given; an entry <= 0 is replaced by the number chosen as above.  Held fixed, it makes the states smooth functions
    of the parameters (the chosen number jumps with them), which finite-difference Jacobians need.
    """
    N = t.size
    UF = np.empty(N)
    W = np.zeros(N)
    Z = np.zeros(N)
    w = 0.0
    z = 0.0
    y = u[0]
    UF[0] = y
    filt = eta < 1e300
    tau = 1.0 / eta if filt else 0.0
    two = n == 2.0 and delta > 0.0
    a1 = beta - gamma
    a2 = beta + gamma
    r1 = math.sqrt(delta / a1) if two and a1 > 0.0 else 0.0
    k1c = a1 * r1
    r2 = math.sqrt(delta / a2) if two and a2 > 0.0 else 0.0
    k2c = a2 * r2 if a2 > 0.0 else 0.0
    planned = plan.size == N - 1
    C = np.zeros(8)  # travel constants of the current sub-step (_zt)
    laws = (aa, ab, ac, ad, c0a, c0b, c0c, c0d, c1a, c1b, c1c, c1d, k0)
    for i in range(N - 1):
        h = t[i + 1] - t[i]
        xd = (x[i + 1] - x[i]) / h
        r = (u[i + 1] - u[i]) / h
        Cf = y - u[i] + r * tau
        y1 = _lagged(u[i], r, Cf, tau, h) if filt else u[i + 1]
        # coupling rate at both ends of the step (the larger bounds the step)
        # |dZ/dw| at z for either direction of travel: |delta - (beta +- gamma)|z|^n|
        zn = z * z if n == 2.0 else abs(z) ** n
        dz = max(abs(delta - (beta + gamma) * zn), abs(delta - (beta - gamma) * zn))
        lam = 0.0
        for uf in (y, y1):
            al = aa + (ab + (ac + ad * uf) * uf) * uf
            cc = c0a + (c0b + (c0c + c0d * uf) * uf) * uf + c1a + (c1b + (c1c + c1d * uf) * uf) * uf
            lam = max(lam, (abs(al) * dz + abs(k0)) / abs(cc))
        if planned and plan[i] > 0:
            m = plan[i]
        else:
            m = 1 + int(h * lam / theta)
            if m > max_sub:
                m = max_sub
            if planned:
                plan[i] = m
        H = h / m
        if filt:  # the lag's exponential at the sub-step's start, middle and end, by products of one factor
            eh = math.exp(-0.5 * H / tau)
            E = 1.0
        for j in range(m):
            s0 = j * H
            if filt:
                base = u[i] + r * (s0 - tau)
                ua = base + Cf * E
                E *= eh
                um = base + r * 0.5 * H + Cf * E
                E *= eh
                ub = base + r * H + Cf * E
            else:
                ua = u[i] + r * s0
                um = ua + r * 0.5 * H
                ub = ua + r * H
            if two:
                C[0] = 0.0
                C[4] = 0.0
                k1 = _rate(ua, xd, w, 0.0, z, laws)
                d = 0.5 * H * k1
                k2 = _rate(um, xd, w, d, _zt(z, d, C, beta, gamma, delta, r1, k1c, r2, k2c), laws)
                d = 0.5 * H * k2
                k3 = _rate(um, xd, w, d, _zt(z, d, C, beta, gamma, delta, r1, k1c, r2, k2c), laws)
                d = H * k3
                k4 = _rate(ub, xd, w, d, _zt(z, d, C, beta, gamma, delta, r1, k1c, r2, k2c), laws)
                dw = H / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
                z = _zt(z, dw, C, beta, gamma, delta, r1, k1c, r2, k2c)
            else:
                k1 = _rate(ua, xd, w, 0.0, z, laws)
                d = 0.5 * H * k1
                k2 = _rate(um, xd, w, d, _travel(z, d, beta, gamma, delta, n), laws)
                d = 0.5 * H * k2
                k3 = _rate(um, xd, w, d, _travel(z, d, beta, gamma, delta, n), laws)
                d = H * k3
                k4 = _rate(ub, xd, w, d, _travel(z, d, beta, gamma, delta, n), laws)
                dw = H / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
                z = _travel(z, dw, beta, gamma, delta, n)
            w += dw
        y = y1
        UF[i + 1] = y
        W[i + 1] = w
        Z[i + 1] = z
    return UF, W, Z


@_jit
def extended_bingham_force(t, x, c0, f_c, k1, c1, k2, substeps):
    """Force of the extended Bingham model (backward Euler on the dead-zone form; see models/bingham.py), from rest
    at the first sample (springs relaxed: x1 = x2 = x[0], F = 0)."""
    N = x.size
    F = np.zeros(N)
    x1 = x[0]
    e = 0.0
    f = 0.0
    inv_c0 = 1.0 / c0
    for i in range(N - 1):
        h = (t[i + 1] - t[i]) / substeps
        q = 1.0 + h * k1 / c1
        inv_q = 1.0 / q
        A = 1.0 + k2 * h / (c1 * q)
        B = k2 * h * inv_c0
        inv_A = 1.0 / A
        inv_AB = 1.0 / (A + B)
        Af = A * f_c
        Bf = B * f_c
        dx = (x[i + 1] - x[i]) / substeps
        hf = h / c1
        hd = h * inv_c0
        for j in range(1, substeps + 1):
            xn = x[i] + dx * j
            R = k2 * (xn - x1 - e * inv_q)
            if abs(R) <= Af:
                f = R * inv_A
                d = 0.0
            elif R > 0.0:
                f = (R + Bf) * inv_AB
                d = f - f_c
            else:
                f = (R - Bf) * inv_AB
                d = f + f_c
            x1 += hd * d
            e = (e + hf * f) * inv_q
        F[i + 1] = f
    return F


@_jit
def affine_recurrence(c, d, y0):
    """y[0] = y0, y[k + 1] = c[k] y[k] + d[k] (one sequential pass)."""
    N = c.size + 1
    y = np.empty(N)
    y[0] = y0
    for k in range(N - 1):
        y[k + 1] = c[k] * y[k] + d[k]
    return y


# ---------------------------------------------------------------------------------------------------------------
# Kernels of the catalogue models (the MR-model review): a stop operator, a series visco-plastic element and a
# mass on a nonlinear damper.  Each advances its state exactly (the stop operator) or by the implicit midpoint rule
# (second order, A-stable) with the monotone scalar equation of each sub-step solved by a bracketed Illinois
# (false-position) root.


@_jit
def stop_operator(x, k, N, s0):
    """Elasto-slide element (a spring k in series with a Coulomb slider N, a per-sample array) driven by a
    displacement that is linear between samples: s[i] = clip(s[i-1] + k (x[i] - x[i-1]), -N[i], N[i]), exact for a
    monotone step."""
    n = x.size
    s = np.empty(n)
    cur = min(max(s0, -N[0]), N[0])
    s[0] = cur
    for i in range(1, n):
        cur = min(max(cur + k * (x[i] - x[i - 1]), -N[i]), N[i])
        s[i] = cur
    return s


@_jit
def _vep_residual(s, xm, y, h, xd, k0, q, nexp, rho, d, c, A, alpha):
    """Spring force minus element force at the midpoint for the element rate s (nkVEP, the MR-model review eqs
    83-84; q = 0 is the continuous VEP of eq 82)."""
    w = xm - y - 0.5 * h * s
    k = k0
    if q != 0.0:
        k += q * abs(w - math.tanh(rho * (xd - s)) * d) ** nexp
    return k * w - c * s - A * math.tanh(alpha * s)


@_jit
def _illinois_update(x, fx, lo, hi, f_lo, f_hi, side):
    """One bracket update of the Illinois false-position method for a residual that falls through zero in
    [lo, hi] (f_lo > 0 > f_hi) and is fx at x: the new (lo, hi, f_lo, f_hi, side); the end kept twice in a row
    has its value halved, which keeps the convergence superlinear."""
    if fx > 0.0:
        lo, f_lo = x, fx
        if side == -1:
            f_hi *= 0.5
        side = -1
    else:
        hi, f_hi = x, fx
        if side == 1:
            f_lo *= 0.5
        side = 1
    return lo, hi, f_lo, f_hi, side


@_jit
def _illinois_vep(lo, hi, f_lo, f_hi, xm, y, h, xd, k0, q, nexp, rho, d, c, A, alpha):
    """Root of the (decreasing) VEP residual in [lo, hi] (f_lo > 0 > f_hi) by the Illinois false-position method,
    which keeps the bracket and converges superlinearly."""
    side = 0
    x = 0.5 * (lo + hi)
    for _ in range(200):
        x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
        fx = _vep_residual(x, xm, y, h, xd, k0, q, nexp, rho, d, c, A, alpha)
        if fx == 0.0 or hi - lo <= 1e-13 * (abs(x) + 1e-12):
            return x
        lo, hi, f_lo, f_hi, side = _illinois_update(x, fx, lo, hi, f_lo, f_hi, side)
        if abs(fx) <= 1e-13 * (abs(f_lo) + abs(f_hi)):
            return x
    return x


@_jit
def _illinois_mass(lo, hi, X, V, h, xmid, xd, m, k1, c1, k0, c_lin, f_t, v_ref, C_pre, C_post, F_y):
    """Root of the (increasing) mass residual in [lo, hi] by the Illinois false-position method, on its negative
    (which falls through zero; negation is exact, so the iterates are those of the increasing form)."""
    f_lo = -_mass_residual(lo, X, V, h, xmid, xd, m, k1, c1, k0, c_lin, f_t, v_ref, C_pre, C_post, F_y)
    f_hi = -_mass_residual(hi, X, V, h, xmid, xd, m, k1, c1, k0, c_lin, f_t, v_ref, C_pre, C_post, F_y)
    side = 0
    x = 0.5 * (lo + hi)
    for _ in range(200):
        x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
        fx = -_mass_residual(x, X, V, h, xmid, xd, m, k1, c1, k0, c_lin, f_t, v_ref, C_pre, C_post, F_y)
        if fx == 0.0 or hi - lo <= 1e-13 * (abs(x) + 1e-12):
            return x
        lo, hi, f_lo, f_hi, side = _illinois_update(x, fx, lo, hi, f_lo, f_hi, side)
        if abs(fx) <= 1e-13 * (abs(f_lo) + abs(f_hi)):
            return x
    return x


@_jit
def series_viscoplastic(t, x, k0, q, nexp, rho, d, c, A, alpha, substeps):
    r"""Internal displacement y and element rate of :math:`k(x, y)(x - y) = c\dot y + A\tanh(\alpha\dot y)` with
    :math:`k = q|(x - y) - \tanh(\rho(\dot x - \dot y))d|^n + k_0` (per-sample arrays k0, c, A, alpha: current
    laws), implicit midpoint sub-steps, each sub-step's rate by a bracketed Illinois root.  Returns (y, ydot)."""
    n = x.size
    y = np.zeros(n)
    yd = np.zeros(n)
    cur = 0.0
    sd = 0.0
    for i in range(n - 1):
        H = t[i + 1] - t[i]
        h = H / substeps
        xd = (x[i + 1] - x[i]) / H if H > 0.0 else 0.0
        for j in range(substeps):
            xm = x[i] + xd * h * (j + 0.5)
            # the residual decreases with s for large |s| (it may not be monotone near the root when q != 0): the
            # bracket grows from the previous rate, so the root found is the one the rate continues to (the
            # element's rate does not jump between roots from one sub-step to the next)
            args = (xm, cur, h, xd, k0[i], q, nexp, rho, d, c[i], A[i], alpha[i])
            span = 1e-6 * (abs(sd) + abs(xd)) + 1e-12
            lo = sd - span
            hi = sd + span
            for _ in range(400):
                if _vep_residual(lo, *args) > 0.0:
                    break
                span *= 2.0
                lo = sd - span
            span = 1e-6 * (abs(sd) + abs(xd)) + 1e-12
            for _ in range(400):
                if _vep_residual(hi, *args) < 0.0:
                    break
                span *= 2.0
                hi = sd + span
            sd = _illinois_vep(lo, hi, _vep_residual(lo, *args), _vep_residual(hi, *args), *args)
            cur += h * sd
        y[i + 1] = cur
        yd[i + 1] = sd
    return y, yd


@_jit
def _mass_residual(v, xm_n, v_n, h, xmid, xd, m, k1, c1, k0, c_lin, f_t, v_ref, C_pre, C_post, F_y):
    """m (dv/dt) - (forces on the mass) at the midpoint, for the midpoint velocity v; increasing in v."""
    xmass = xm_n + 0.5 * h * v
    D = c_lin * v
    if f_t != 0.0:
        D += f_t * math.tanh(v / v_ref)
    if C_pre != 0.0:
        av = abs(v)
        D += math.copysign(min(C_pre * av, C_post * av + F_y), v)
    return 2.0 * m * (v - v_n) / h - (k1 * (xmid - xmass) + c1 * (xd - v) - k0 * xmass - D)


@_jit
def mass_on_damper(t, x, m, k1, c1, k0, c_lin, f_t, v_ref, C_pre, C_post, F_y, substeps):
    r"""Displacement and velocity of an internal mass m driven through a spring k1 and a dashpot c1 by the piston
    displacement x, held by a spring k0 and a damper :math:`D(v) = c v + f_t\tanh(v/v_{ref}) +
    \operatorname{sgn}v\min(C_{pre}|v|, C_{post}|v| + F_y)` to the body:
    :math:`m\ddot x_m = k_1(x - x_m) + c_1(\dot x - \dot x_m) - k_0 x_m - D(\dot x_m)` (Bass: the MR-model review
    eqs 93-94; Sims: eqs 63-64).  f_t, C_pre, C_post, F_y are per-sample arrays (current laws).  Implicit midpoint
    sub-steps; m = 0 is allowed (the mass-less element).  Returns (x_m, v_m)."""
    n = x.size
    xm = np.zeros(n)
    vm = np.zeros(n)
    X = 0.0
    V = 0.0
    for i in range(n - 1):
        H = t[i + 1] - t[i]
        h = H / substeps
        xd = (x[i + 1] - x[i]) / H if H > 0.0 else 0.0
        for j in range(substeps):
            xmid = x[i] + xd * h * (j + 0.5)
            args = (X, V, h, xmid, xd, m, k1, c1, k0, c_lin, f_t[i], v_ref, C_pre[i], C_post[i], F_y[i])
            span = abs(V) + abs(xd) + 1e-9
            lo = -span
            hi = span
            for _ in range(200):
                if _mass_residual(lo, *args) < 0.0:
                    break
                lo *= 2.0
            for _ in range(200):
                if _mass_residual(hi, *args) > 0.0:
                    break
                hi *= 2.0
            vmid = _illinois_mass(lo, hi, *args)
            X += h * vmid
            V = 2.0 * vmid - V if m > 0.0 else vmid
        xm[i + 1] = X
        vm[i + 1] = V
    return xm, vm


@_jit
def bouc_wen_state_varying(x, beta, gamma, delta, n, z0):
    """Bouc-Wen variable for a displacement linear between samples with shape parameters that change from sample to
    sample (per-sample arrays; each step uses the values at its start, the step itself exact)."""
    N = x.size
    out = np.empty(N)
    z = z0
    out[0] = z
    for i in range(1, N):
        z = _travel(z, x[i] - x[i - 1], beta[i - 1], gamma[i - 1], delta[i - 1], n[i - 1])
        out[i] = z
    return out
