r"""Time-stepping kernels shared by the damper models (SI floats / numpy arrays; not public API).

* :func:`first_order_lag` - the exact discrete-time response of :math:`\tau\dot y + y = u` to a piecewise-linear
  input (first-order hold): a two-tap IIR filter run by :func:`scipy.signal.lfilter` on even steps, or the
  affine prefix scan of :mod:`erdesign.constitutive.makris` on uneven ones.  Maxwell, BingMax, the Jeffreys
  (three-parameter fluid) branch of Kamath-Wereley and Spencer's control filter use it: no loop per sample.
* :func:`dahl_state` - the Dahl / LuGre bristle state, whose equation is linear in the state on each step (exact
  affine recurrence, prefix scan).
* :func:`bouc_wen_state` - the Bouc-Wen hysteretic variable for a given input history; :func:`modified_bouc_wen`
  - Spencer's two-state model.  These are nonlinear and sequential; each step is exact in z (closed-form Riccati
  solution for n = 2, classical RK4 sub-steps in the displacement variable otherwise), so the step is set by the
  sampling, not by the stiffness of z near saturation.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.signal import lfilter

from ..constitutive.makris import _affine_recurrence

__all__ = ["first_order_lag", "dahl_state", "bouc_wen_state", "riccati_step", "modified_bouc_wen", "is_uniform"]


def is_uniform(t: np.ndarray, rtol: float = 1e-6) -> bool:
    """True when the time steps of ``t`` agree to ``rtol`` of the mean step."""
    dt = np.diff(t)
    mean = (t[-1] - t[0]) / (t.size - 1)
    return bool(np.max(np.abs(dt - mean)) <= rtol * mean)


def first_order_lag(t, u, tau, y0=0.0):
    r"""Exact response of :math:`\tau\dot y + y = u` to an input that is linear between samples.

    On a step h with :math:`e = e^{-h/\tau}` and slope :math:`r = (u_{n+1} - u_n)/h`,

    .. math:: y_{n+1} = e\,y_n + u_{n+1} - r\tau - e\,(u_n - r\tau).

    ``tau = 0`` returns ``u`` itself (no lag).
    """
    t = np.asarray(t, dtype=float)
    u = np.asarray(u, dtype=float)
    if tau <= 0:
        return u.copy()
    if is_uniform(t):
        h = (t[-1] - t[0]) / (t.size - 1)
        e = math.exp(-h / tau)
        g = tau * (1.0 - e) / h
        b = [1.0 - g, g - e]
        a = [1.0, -e]
        # Initial condition of the direct-form II transposed filter for y[0] = y0 with u[-1] = u[0].
        zi = np.array([y0 - b[0] * u[0]])
        y, _ = lfilter(b, a, u, zi=zi)
        return y
    h = np.diff(t)
    e = np.exp(-h / tau)
    r = np.diff(u) / h
    return _affine_recurrence(e, u[1:] - r * tau - e * (u[:-1] - r * tau), y0)


def dahl_state(x, rho, z0=0.0):
    r"""Dahl state for a displacement that is linear between samples: :math:`\dot z = \rho(\dot x - |\dot x| z)`.

    On a step the direction :math:`s = \operatorname{sgn}\Delta x` is fixed and :math:`dz/dx = \rho(1 - s z)`, so

    .. math:: z_{n+1} = s + (z_n - s)\,e^{-\rho|\Delta x_n|}

    exactly (an affine recurrence, solved by a prefix scan).  ``rho`` may be an array of one value per step
    (LuGre with a field-dependent rate).
    """
    dx = np.diff(np.asarray(x, dtype=float))
    s = np.sign(dx)
    e = np.exp(-np.asarray(rho, dtype=float) * np.abs(dx))
    return _affine_recurrence(e, s * (1.0 - e), z0)


def riccati_step(z, L, beta, gamma, delta, n):
    r"""Advance :math:`dz/d\xi = \delta - \gamma z|z|^{n-1} - \beta|z|^n` by :math:`\xi = L \ge 0` (Bouc-Wen in the
    direction of motion).  Exact for n = 2 (tanh / tan / linear solutions on each side of z = 0) and n = 1
    (exponentials), RK4 sub-steps otherwise."""
    if L <= 0.0:
        return z
    if n == 2.0:
        if z < 0.0:
            a = beta - gamma
            # distance to reach z = 0 under dz = delta - a z^2 (z < 0 increases when delta > a z^2)
            if a > 0.0:
                r = math.sqrt(delta / a)
                if z <= -r:  # outside the attracting range: decays / diverges, never reaches 0
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
            z, L = 0.0, L - L0
        return _riccati_const(z, L, beta + gamma, delta)
    if n == 1.0:
        # dz/dxi = delta - (gamma + beta sgn z) z: linear on each side of z = 0, exponential solutions
        if z < 0.0:
            a = gamma - beta
            L0 = _linear_distance_to_zero(z, a, delta)
            if L0 >= L:
                return _linear_const(z, L, a, delta)
            z, L = 0.0, L - L0
        return _linear_const(z, L, gamma + beta, delta)
    lam = n * (abs(beta) + abs(gamma)) * max(abs(z), (delta / max(abs(beta) + abs(gamma), 1e-300)) ** (1.0 / n)) ** (n - 1.0)
    m = 1 + int(L * lam / 0.5)
    h = L / m

    def f(q):
        aq = abs(q)
        return delta - (gamma * q + beta * aq) * aq ** (n - 1.0)

    for _ in range(m):
        k1 = f(z)
        k2 = f(z + 0.5 * h * k1)
        k3 = f(z + 0.5 * h * k2)
        k4 = f(z + h * k3)
        z += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
    return z


def _linear_const(z, L, a, delta):
    """dz/dxi = delta - a z over L (exact)."""
    if a == 0.0:
        return z + delta * L
    zeq = delta / a
    return zeq + (z - zeq) * math.exp(-a * L)


def _linear_distance_to_zero(z, a, delta):
    """Travel for dz/dxi = delta - a z to bring z < 0 up to 0 (inf if it never does)."""
    if a == 0.0:
        return -z / delta
    zeq = delta / a
    if zeq <= 0.0 and z <= zeq:
        return math.inf
    ratio = (0.0 - zeq) / (z - zeq)
    return -math.log(ratio) / a if ratio > 0.0 else math.inf


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


def bouc_wen_state(x, beta, gamma, delta, n, z0=0.0):
    r"""Bouc-Wen hysteretic variable driven by a displacement that is linear between samples.

    .. math:: \dot z = -\gamma|\dot x| z|z|^{n-1} - \beta\dot x|z|^n + \delta\dot x

    On each step the direction :math:`s` of motion is fixed and, in :math:`\tilde z = s z` and the travelled
    distance :math:`\xi`, the equation is autonomous: :math:`d\tilde z/d\xi = \delta - \gamma\tilde z|\tilde z|^{n-1}
    - \beta|\tilde z|^n` (:func:`riccati_step`).
    """
    xs = np.asarray(x, dtype=float).tolist()
    out = [0.0] * len(xs)
    z = float(z0)
    out[0] = z
    beta, gamma, delta, n = float(beta), float(gamma), float(delta), float(n)
    for i in range(1, len(xs)):
        dx = xs[i] - xs[i - 1]
        if dx > 0.0:
            z = riccati_step(z, dx, beta, gamma, delta, n)
        elif dx < 0.0:
            z = -riccati_step(-z, -dx, beta, gamma, delta, n)
        out[i] = z
    return np.array(out)


def modified_bouc_wen(t, x, alpha, c0, c1, k0, beta, gamma, delta, n):
    r"""States of Spencer's modified Bouc-Wen model (seed 001 eqs 10-12) for a piecewise-linear displacement.

    With the relative displacement :math:`w = x - y` of the Bouc-Wen element,

    .. math::
        \dot w = \frac{c_1\dot x - \alpha z - k_0 w}{c_0 + c_1},\qquad
        \dot z = -\gamma|\dot w| z|z|^{n-1} - \beta\dot w|z|^n + \delta\dot w .

    Each sample step is a Heun (trapezoidal predictor-corrector) step for w whose z update is the exact
    solution for the step's travel :math:`\Delta w` (:func:`riccati_step`): second order in the coupling, exact in the
    stiff saturation of z.  ``alpha``, ``c0``, ``c1`` may be arrays (one value per sample: the filtered control).

    Returns
    -------
    (w, z) : arrays, [m], [m] (z has the units of x when delta is dimensionless)
    """
    t = np.asarray(t, dtype=float)
    N = t.size
    xs = np.asarray(x, dtype=float).tolist()
    ts = t.tolist()
    al = np.broadcast_to(np.asarray(alpha, dtype=float), (N,)).tolist()
    a0 = np.broadcast_to(np.asarray(c0, dtype=float), (N,)).tolist()
    a1 = np.broadcast_to(np.asarray(c1, dtype=float), (N,)).tolist()
    beta, gamma, delta, n, k0 = float(beta), float(gamma), float(delta), float(n), float(k0)
    W = [0.0] * N
    Z = [0.0] * N
    w = z = 0.0
    step = riccati_step
    for i in range(N - 1):
        h = ts[i + 1] - ts[i]
        xd = (xs[i + 1] - xs[i]) / h
        wd0 = (a1[i] * xd - al[i] * z - k0 * w) / (a0[i] + a1[i])
        dw = wd0 * h
        zp = step(z, dw, beta, gamma, delta, n) if dw >= 0.0 else -step(-z, -dw, beta, gamma, delta, n)
        wd1 = (a1[i + 1] * xd - al[i + 1] * zp - k0 * (w + dw)) / (a0[i + 1] + a1[i + 1])
        dw = 0.5 * (wd0 + wd1) * h
        z = step(z, dw, beta, gamma, delta, n) if dw >= 0.0 else -step(-z, -dw, beta, gamma, delta, n)
        w += dw
        W[i + 1] = w
        Z[i + 1] = z
    return np.array(W), np.array(Z)
