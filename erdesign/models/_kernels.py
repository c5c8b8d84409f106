r"""Time-stepping kernels shared by the damper models (SI floats / numpy arrays; not public API).

* :func:`first_order_lag` - the exact discrete-time response of :math:`\tau\dot y + y = u` to a piecewise-linear
  input (first-order hold): a two-tap IIR filter run by :func:`scipy.signal.lfilter` on even steps, or the
  affine prefix scan of :mod:`erdesign.constitutive.makris` on uneven ones.  Maxwell, BingMax, the Jeffreys
  (three-parameter fluid) branch of Kamath-Wereley and Spencer's control filter use it: no loop per sample.
* :func:`dahl_state` - the Dahl / LuGre bristle state, whose equation is linear in the state on each step (exact
  affine recurrence, prefix scan).
* :func:`bouc_wen_state` - the Bouc-Wen hysteretic variable for a given input history; :func:`modified_bouc_wen`
  - Spencer's model (filtered control, internal displacement, Bouc-Wen variable).  These are nonlinear and
  sequential: compiled loops (:mod:`erdesign.models._compiled`, numba, imported on first use).  Each step is exact
  in z along the travel (closed-form Riccati solution for n = 1, 2), so the step is set by the sampling and the
  coupling, not by the stiffness of z near saturation.
"""

from __future__ import annotations

import hashlib
import math
from contextvars import ContextVar
from dataclasses import dataclass, replace

import numpy as np

from ..numerics import affine_recurrence

__all__ = [
    "first_order_lag",
    "dahl_state",
    "bouc_wen_state",
    "riccati_step",
    "modified_bouc_wen",
    "is_uniform",
    "stop_operator",
    "series_viscoplastic",
    "mass_on_damper",
    "per_sample",
    "bouc_wen_state_varying",
]


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
        from scipy.signal import lfilter  # imported on use: scipy.signal costs start-up time

        y, _ = lfilter(b, a, u, zi=zi)
        return y
    h = np.diff(t)
    e = np.exp(-h / tau)
    r = np.diff(u) / h
    return affine_recurrence(e, u[1:] - r * tau - e * (u[:-1] - r * tau), y0)


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
    return affine_recurrence(e, s * (1.0 - e), z0)


def _compiled():
    """The numba kernels (:mod:`erdesign.models._compiled`), imported on first use: numba costs about a second
    of start-up, which commands that simulate no hysteretic model should not pay."""
    from . import _compiled as compiled

    return compiled


def riccati_step(z, L, beta, gamma, delta, n):
    r"""Advance :math:`dz/d\xi = \delta - \gamma z|z|^{n-1} - \beta|z|^n` by :math:`\xi = L \ge 0` (Bouc-Wen in the
    direction of motion).  Exact for n = 2 (tanh / tan / linear solutions on each side of z = 0) and n = 1
    (exponentials), RK4 sub-steps otherwise (compiled: :func:`erdesign.models._compiled.riccati_step`)."""
    return _compiled().riccati_step(float(z), float(L), float(beta), float(gamma), float(delta), float(n))


def bouc_wen_state(x, beta, gamma, delta, n, z0=0.0):
    r"""Bouc-Wen hysteretic variable driven by a displacement that is linear between samples.

    .. math:: \dot z = -\gamma|\dot x| z|z|^{n-1} - \beta\dot x|z|^n + \delta\dot x

    On each step the direction :math:`s` of motion is fixed and, in :math:`\tilde z = s z` and the travelled
    distance :math:`\xi`, the equation is autonomous: :math:`d\tilde z/d\xi = \delta - \gamma\tilde z|\tilde z|^{n-1}
    - \beta|\tilde z|^n` (:func:`riccati_step`).  Compiled loop (:mod:`erdesign.models._compiled`).
    """
    x = np.ascontiguousarray(x, dtype=float)
    return _compiled().bouc_wen_state(x, float(beta), float(gamma), float(delta), float(n), float(z0))


#: Largest product of the sub-step and the coupling rate of :func:`modified_bouc_wen` (RK4): 0.3 keeps the force
#: within 4e-5 of its range of LSODA at rtol 1e-10 at 3 kHz on Spencer's dampers (tests/test_models.py; 0.5 gave
#: 7e-5, 1.0 gave 1.4e-4 on the random-voltage record).
RK4_THETA = 0.3
#: Most sub-steps per sample (a bound on the cost of wild parameter values met while fitting).
MAX_SUBSTEPS = 256


@dataclass(frozen=True)
class StepSettings:
    """How :func:`modified_bouc_wen` sub-steps a sample: ``theta`` (the largest product of the sub-step and the
    coupling rate), ``max_substeps`` per sample, and ``plans`` (``None``, or a dict of frozen sub-step counts per
    record, see :class:`frozen_substeps`)."""

    theta: float = RK4_THETA
    max_substeps: int = MAX_SUBSTEPS
    plans: dict | None = None


# The settings in force.  A context variable, not a module global: each thread (and each asyncio task) sees the
# settings of its own ``with`` blocks, so two fits running at once in threads cannot change each other's steps.
_STEPS: ContextVar[StepSettings] = ContextVar("erdesign_kernel_steps", default=StepSettings())


def step_settings() -> StepSettings:
    """The sub-step settings in force in this thread / context."""
    return _STEPS.get()


class _StepBlock:
    """A ``with`` block that replaces some fields of the step settings of the current context and restores them."""

    def _changes(self) -> dict:
        raise NotImplementedError

    def __enter__(self):
        self._token = _STEPS.set(replace(_STEPS.get(), **self._changes()))
        return self

    def __exit__(self, *exc):
        _STEPS.reset(self._token)
        return False


class coarse_steps(_StepBlock):
    """Context manager: a looser sub-step (theta 1.0, at most 64 sub-steps per sample) while an optimiser
    explores - about 1e-4 of the force range instead of 4e-6, far below any real model error, at a third of the
    cost; identification scores its result with the default steps."""

    def __init__(self, theta: float = 1.0, max_substeps: int = 64):
        self.theta, self.max_substeps = theta, max_substeps

    def _changes(self):
        return {"theta": self.theta, "max_substeps": self.max_substeps}


_EMPTY_PLAN = np.zeros(0, dtype=np.int64)


class frozen_substeps(_StepBlock):
    """Context manager: the first simulation of a record inside the block records the number of sub-steps of each
    step of :func:`modified_bouc_wen` (into ``plans``, a dict returned by ``with``; pass it again to reuse the
    counts); later simulations of the same record reuse them.  The states are then smooth in the parameters, as a
    finite-difference Jacobian needs (the adaptive count jumps by one somewhere in the record for almost any
    parameter step, and each jump moves the force by the discretisation error: far more than the step's effect when
    the step is small).  A record is known by a digest of its time and displacement samples, so two records of one
    length keep their own counts.  Models without sub-steps ignore it."""

    def __init__(self, plans: dict | None = None):
        self.plans = {} if plans is None else plans

    def _changes(self):
        return {"plans": self.plans}

    def __enter__(self) -> dict:
        """The plans: record digest -> sub-step counts (filled by the first simulation of each record)."""
        super().__enter__()
        return self.plans


def _plan(settings: StepSettings, t: np.ndarray, x: np.ndarray) -> np.ndarray:
    """The sub-step counts to reuse (or fill) for this record, or an empty array when counts are adaptive."""
    if settings.plans is None:
        return _EMPTY_PLAN
    key = (t.size, hashlib.blake2b(t.tobytes() + x.tobytes(), digest_size=16).digest())
    return settings.plans.setdefault(key, np.zeros(max(t.size - 1, 0), dtype=np.int64))


def modified_bouc_wen(t, x, u, eta, alpha, c0, c1, k0, beta, gamma, delta, n):
    r"""States of Spencer's modified Bouc-Wen model (Butz and von Stryk 2002, eqs 10-12; Spencer et al. 1997) for a
    displacement
    and a dimensionless control that are linear between samples.

    With the relative displacement :math:`w = x - y` of the Bouc-Wen element and the filtered control :math:`u_f`,

    .. math::
        \dot u_f = -\eta(u_f - u),\qquad
        \dot w = \frac{c_1\dot x - \alpha z - k_0 w}{c_0 + c_1},\qquad
        \dot z = -\gamma|\dot w| z|z|^{n-1} - \beta\dot w|z|^n + \delta\dot w ,

    :math:`\alpha`, :math:`c_0`, :math:`c_1` polynomials of degree up to three in :math:`u_f` (Spencer's linear law,
    Quiroz's and Spaggiari's quadratic laws, Yang's cubic law).  The filter is exact; w is stepped by RK4 with z carried exactly along each
    sub-step's travel (:func:`erdesign.models._compiled.modified_bouc_wen`).

    Parameters
    ----------
    t, x, u : arrays
        [s], [m], [-] (dimensionless control).
    eta : float
        Filter rate, [1/s]; ``inf`` for no filter.
    alpha, c0, c1 : tuples
        Polynomial coefficients in u_f, constant first, up to four each: (alpha_a, alpha_b, ...) [N/m],
        (c0a, c0b, ...), (c1a, c1b, ...) [N s/m].
    k0, beta, gamma, delta, n : float
        [N/m], [1/m^n], [1/m^n], [-], [-].

    Returns
    -------
    (u_f, w, z) : arrays, [-], [m], [m]
    """
    t = np.ascontiguousarray(t, dtype=float)
    x = np.ascontiguousarray(x, dtype=float)
    u = np.ascontiguousarray(np.broadcast_to(np.asarray(u, dtype=float), t.shape))
    eta = float(eta) if math.isfinite(eta) else 1e300
    alpha, c0, c1 = (tuple(float(c) for c in coeffs) + (0.0,) * (4 - len(coeffs)) for coeffs in (alpha, c0, c1))
    steps = _STEPS.get()
    return _compiled().modified_bouc_wen(
        t,
        x,
        u,
        eta,
        *alpha,
        *c0,
        *c1,
        float(k0),
        float(beta),
        float(gamma),
        float(delta),
        float(n),
        steps.theta,
        steps.max_substeps,
        _plan(steps, t, x),
    )


def per_sample(value, n: int) -> np.ndarray:
    """A scalar or per-sample parameter as a contiguous float array of n values (for the compiled kernels)."""
    return np.ascontiguousarray(np.broadcast_to(np.asarray(value, dtype=float), (n,)))


def stop_operator(x, k, N, s0=0.0):
    r"""Elasto-slide element: a spring k [N/m] in series with a Coulomb slider N [N] (a scalar or one value per
    sample), driven by a displacement x [m] linear between samples; force [N]
    :math:`s_{i} = \operatorname{clip}(s_{i-1} + k\Delta x_i, -N_i, N_i)` (exact)."""
    x = np.ascontiguousarray(x, dtype=float)
    return _compiled().stop_operator(x, float(k), per_sample(N, x.size), float(s0))


#: Implicit-midpoint sub-steps per sample of :func:`series_viscoplastic` and :func:`mass_on_damper`.
MIDPOINT_SUBSTEPS = 4


def series_viscoplastic(t, x, k0, c, A, alpha, *, q=0.0, n=1.0, rho=0.0, d=0.0, substeps=MIDPOINT_SUBSTEPS):
    r"""Internal displacement y [m] and rate [m/s] of the series visco-plastic element
    :math:`k(x - y) = c\dot y + A\tanh(\alpha\dot y)` (the MR-model review eq 82), with the nonlinear stiffness
    :math:`k = q|(x - y) - \tanh(\rho(\dot x - \dot y))d|^n + k_0` of eq 84 when q != 0.  k0, c, A, alpha may
    be per-sample arrays (current laws).  Implicit midpoint sub-steps (second order), compiled."""
    t = np.ascontiguousarray(t, dtype=float)
    N = t.size
    return _compiled().series_viscoplastic(
        t,
        np.ascontiguousarray(x, dtype=float),
        per_sample(k0, N),
        float(q),
        float(n),
        float(rho),
        float(d),
        per_sample(c, N),
        per_sample(A, N),
        per_sample(alpha, N),
        int(substeps),
    )


def mass_on_damper(
    t,
    x,
    *,
    m=0.0,
    k1=0.0,
    c1=0.0,
    k0=0.0,
    c=0.0,
    f_t=0.0,
    v_ref=1.0,
    C_pre=0.0,
    C_post=0.0,
    F_y=0.0,
    substeps=MIDPOINT_SUBSTEPS,
):
    r"""Displacement [m] and velocity [m/s] of an internal mass driven by the piston displacement x:
    :math:`m\ddot x_m = k_1(x - x_m) + c_1(\dot x - \dot x_m) - k_0x_m - D(\dot x_m)`,
    :math:`D(v) = cv + f_t\tanh(v/v_{ref}) + \operatorname{sgn}v\min(C_{pre}|v|, C_{post}|v| + F_y)` (Bass, Sims;
    :func:`erdesign.models._compiled.mass_on_damper`).  f_t, C_pre, C_post, F_y may be per-sample arrays."""
    t = np.ascontiguousarray(t, dtype=float)
    N = t.size
    return _compiled().mass_on_damper(
        t,
        np.ascontiguousarray(x, dtype=float),
        float(m),
        float(k1),
        float(c1),
        float(k0),
        float(c),
        per_sample(f_t, N),
        float(v_ref),
        per_sample(C_pre, N),
        per_sample(C_post, N),
        per_sample(F_y, N),
        int(substeps),
    )


def bouc_wen_state_varying(x, beta, gamma, delta, n, z0=0.0):
    r"""The Bouc-Wen variable (as :func:`bouc_wen_state`) with shape parameters that vary per sample (voltage laws):
    each step is exact with the values at its start."""
    x = np.ascontiguousarray(x, dtype=float)
    N = x.size
    return _compiled().bouc_wen_state_varying(
        x, per_sample(beta, N), per_sample(gamma, N), per_sample(delta, N), per_sample(n, N), float(z0)
    )
