r"""The Makris elastic-viscoplastic law of an ER fluid and its two limits (SI kernels).

Makris et al. (1996) write the shear stress :math:`\tau` of an electrorheological fluid under a shear-strain
history :math:`\gamma(t)` as (their eq 8)

.. math::
    \tau + \frac{\eta\dot\gamma + \tau_y\operatorname{sgn}\dot\gamma}{G\,\dot\gamma}\,\frac{d\tau}{dt}
    = \eta\dot\gamma + \tau_y\operatorname{sgn}\dot\gamma ,

a Maxwell element whose relaxation time :math:`(\eta + \tau_y/|\dot\gamma|)/G` grows without bound as the strain
rate falls, so that the fluid is an elastic solid (modulus :math:`G`) at rest and a Bingham plastic (yield stress
:math:`\tau_y`, plastic viscosity :math:`\eta`) in steady flow.  It is the linear first-order equation (eqs 9-10)

.. math::
    \frac{d\tau}{dt} = G\dot\gamma - R(t)\,\tau, \qquad R = \frac{G|\dot\gamma|}{\eta|\dot\gamma| + \tau_y}
    \qquad\Longleftrightarrow\qquad \frac{d\tau}{dt} = R\,\big(\tau_B - \tau\big),
    \quad \tau_B = \eta\dot\gamma + \tau_y\operatorname{sgn}\dot\gamma ,

that relaxes the stress towards the Bingham stress :math:`\tau_B` (Makris eq 5) at the rate :math:`R`.

Contents
--------
* :func:`makris_stress` - stress for any sampled strain history, by the exact solution over each step.
* :func:`integration_factor_exponent` - :math:`\int R\,dt` for a harmonic strain (eq 11, any :math:`\omega t`).
* :func:`maxwell_stress` - the high-frequency limit :math:`a \to 0`, the linear Maxwell model (eq 13).
* :func:`elastic_plastic_stress` - the zero-frequency limit :math:`a \to \infty`, rate independent, closed form.

Here :math:`a = \tau_y/(\eta\omega\gamma_0)` is Makris's ratio of the yield stress to the peak viscous stress of
a harmonic strain :math:`\gamma_0\sin\omega t`.  The paper writes the viscosity as :math:`\eta_0` on the left of
eq 8 and :math:`v_0` on the right; both are the same field-dependent plastic ("zero-shear-rate") viscosity,
``eta`` here.  The derivations, limits and the departures from the printed paper are in docs/theory/makris.md.
"""

from __future__ import annotations

import numpy as np

from ..errors import ErdesignError
from ..numerics import affine_recurrence

__all__ = [
    "makris_stress",
    "maxwell_stress",
    "elastic_plastic_stress",
    "integration_factor_exponent",
]


def _check_history(t, gamma):
    """Validate a sampled strain history; return float arrays t (N,) and gamma (N, ...)."""
    t = np.asarray(t, dtype=float)
    gamma = np.asarray(gamma, dtype=float)
    if t.ndim != 1:
        raise ErdesignError(f"t: expected a 1-D array of sample times, got shape {t.shape}")
    if gamma.ndim == 0 or gamma.shape[0] != t.shape[0]:
        raise ErdesignError(
            f"gamma: expected {t.shape[0]} samples along axis 0 (one per time in t), got shape {gamma.shape}"
        )
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(gamma))):
        raise ErdesignError("t, gamma: expected finite values")
    if np.any(np.diff(t) <= 0.0):
        raise ErdesignError("t: expected strictly increasing sample times")
    return t, gamma


def makris_stress(t, gamma, tau_y, eta, G, tau0=0.0):
    r"""Shear stress of the Makris elastic-viscoplastic fluid for a sampled strain history.

    Between samples the strain is taken as linear in time (rate :math:`\dot\gamma_n = \Delta\gamma_n/\Delta t_n`
    constant over the step); eq 8 then has constant coefficients on the step and is solved exactly:

    .. math::
        \tau_{n+1} = \tau_{B,n} + (\tau_n - \tau_{B,n})\,
        \exp\!\left(-\frac{G\,|\Delta\gamma_n|}{\eta|\dot\gamma_n| + \tau_y}\right),
        \qquad \tau_{B,n} = \eta\dot\gamma_n + \tau_y\operatorname{sgn}\dot\gamma_n .

    Parameters
    ----------
    t : array, shape (N,)
        Sample times, strictly increasing, [s].
    gamma : array, shape (N, ...)
        Shear strain at the sample times, [-].  Extra trailing axes are independent histories on the same time
        grid (e.g. one per radius across a gap, or one per parameter set).
    tau_y : float or array
        Yield stress, [Pa], >= 0.  Broadcasts against ``gamma``; a value that varies along axis 0 (shape (N,) for
        a 1-D ``gamma``, (N, 1, ...) otherwise) is a field switched in time, held over each step at its value at
        the start of the step.
    eta : float or array
        Plastic viscosity (Makris's eta_0 = v_0), [Pa s], >= 0.  Broadcasts like ``tau_y``.
    G : float or array
        Elastic shear modulus of the fluid before yield, [Pa], > 0.  Broadcasts like ``tau_y``.
    tau0 : float or array, optional
        Stress at ``t[0]``, [Pa]; default 0 (a fluid at rest and unstressed).  Broadcasts against
        ``gamma.shape[1:]``.

    Returns
    -------
    array, shape of ``gamma`` broadcast with the parameters
        Shear stress at the sample times, [Pa].

    Notes
    -----
    *Exactness.*  For a piecewise-linear strain history (a ramp between samples) the result is the exact
    solution of eq 8 at the samples, at any step size: no tolerance, no stability limit (each step is a convex
    combination of the old stress and the Bingham stress, so :math:`|\tau|` never exceeds
    :math:`\max(|\tau_0|, \max_n |\tau_{B,n}|)`).  For a smooth history sampled at step :math:`\Delta t` the
    error is that of the linear interpolant, second order in :math:`\Delta t` (measured in
    tests/test_constitutive_makris.py).

    *Rest.*  A step with :math:`\Delta\gamma = 0` holds the stress when :math:`\tau_y > 0` (the relaxation rate
    :math:`R` vanishes with the strain rate).  With :math:`\tau_y = 0` the law is Maxwell's, and the stress relaxes
    by :math:`e^{-G\Delta t/\eta}` during the hold, the limit of :math:`R` as :math:`\dot\gamma \to 0`.

    *Limits.*  ``tau_y = 0`` gives :func:`maxwell_stress` (eq 13); ``eta = 0`` gives the rate-independent
    :func:`elastic_plastic_stress`; ``G -> inf`` gives the rigid-viscoplastic Bingham law
    :math:`\tau = \tau_B` (eq 5).

    *Solver.*  The update is an affine recurrence :math:`\tau_{n+1} = c_n\tau_n + d_n`; it is evaluated with
    log2(N) vectorised passes of a prefix scan instead of a loop over the samples.

    Examples
    --------
    One cycle of the Figure 3 fluid (tau_y = 1.8 kPa, eta = 13 Pa s, G = 17 kPa) at 5 Hz, unit strain amplitude:

    >>> import numpy as np
    >>> t = np.linspace(0.0, 0.2, 2001)
    >>> tau = makris_stress(t, np.sin(2 * np.pi * 5.0 * t), tau_y=1800.0, eta=13.0, G=17000.0)
    >>> round(float(tau.max()))    # Pa; just below the Bingham bound tau_y + eta*omega*gamma0 = 2208 Pa
    2200

    References
    ----------
    Makris, Burton, Hill and Jordan, ER damper with annular ducts for seismic protection applications, eq 8
    (constitutive law), eqs 9-10 (linear first-order form and its integrating factor).
    """
    t, gamma = _check_history(t, gamma)
    tau_y, eta, G = (np.asarray(p, dtype=float) for p in (tau_y, eta, G))
    try:
        shape = np.broadcast_shapes(gamma.shape, tau_y.shape, eta.shape, G.shape)
    except ValueError:
        shape = None
    if shape is None or shape[0] != t.shape[0]:
        raise ErdesignError(
            f"tau_y, eta, G: shapes {tau_y.shape}, {eta.shape}, {G.shape} do not broadcast against gamma "
            f"{gamma.shape} without changing its number of samples"
        )
    gamma = np.broadcast_to(gamma, shape)
    # Parameters held over step n at their value at sample n (first N-1 entries along the time axis).
    tau_y, eta, G = (np.broadcast_to(p, shape)[:-1] for p in (tau_y, eta, G))
    if np.any(tau_y < 0.0) or np.any(eta < 0.0) or np.any(G <= 0.0):
        raise ErdesignError("tau_y, eta, G: expected tau_y >= 0, eta >= 0 and G > 0")

    dt = np.diff(t).reshape((-1,) + (1,) * (len(shape) - 1))
    dgamma = np.diff(gamma, axis=0)
    abs_dgamma = np.abs(dgamma)
    # exponent G |dgamma| / (eta |gdot| + tau_y), multiplied through by dt so that a rest step (dgamma = 0) is
    # 0 / tau_y = 0 (stress held) and, for tau_y = 0, the limit G dt / eta (Maxwell relaxation) is kept.
    num = G * abs_dgamma * dt
    den = eta * abs_dgamma + tau_y * dt
    with np.errstate(divide="ignore", invalid="ignore"):
        exponent = np.where(den > 0.0, num / den, G * dt / eta)
    decay = np.exp(-exponent)
    tau_bingham = eta * dgamma / dt + tau_y * np.sign(dgamma)
    drive = -np.expm1(-exponent) * tau_bingham
    return affine_recurrence(decay, drive, tau0)


def maxwell_stress(t, gamma, eta, G, tau0=0.0):
    r"""Shear stress of a linear Maxwell fluid (the high-frequency limit of the Makris law) for a strain history.

    .. math::
        \tau(t) = e^{-(G/\eta)t}\int_{-\infty}^{t} G\dot\gamma(\xi)\,e^{(G/\eta)\xi}\,d\xi ,
        \qquad\text{on a step:}\quad
        \tau_{n+1} = \eta\dot\gamma_n + (\tau_n - \eta\dot\gamma_n)\,e^{-G\Delta t_n/\eta}

    Parameters
    ----------
    t : array, shape (N,)
        Sample times, strictly increasing, [s].
    gamma : array, shape (N, ...)
        Shear strain at the sample times, [-].
    eta : float or array
        Viscosity (dashpot), [Pa s], > 0.
    G : float or array
        Shear modulus (spring), [Pa], > 0.
    tau0 : float or array, optional
        Stress at ``t[0]``, [Pa]; default 0.

    Returns
    -------
    array, shape (N, ...)
        Shear stress at the sample times, [Pa].

    Notes
    -----
    :func:`makris_stress` with ``tau_y = 0``: exact for a strain that is linear between samples (on a uniform
    grid it equals the first-order IIR filter ``scipy.signal.lfilter([k, -k], [1, -c], gamma)`` with
    :math:`c = e^{-G\Delta t/\eta}`, :math:`k = \eta(1 - c)/\Delta t`).  Makris obtains it as the
    :math:`a = \tau_y/(\eta\omega\gamma_0) \to 0` limit of eq 11, where :math:`\int R\,dt \to G t/\eta`.
    Relaxation time :math:`\lambda = \eta/G`; steady harmonic response
    :math:`G^* = G\,i\omega\lambda/(1 + i\omega\lambda)`.

    Examples
    --------
    A strain step (a ramp over 1 ms) relaxes with the time constant eta/G = 1 ms:

    >>> import numpy as np
    >>> t = np.array([0.0, 1e-3, 2e-3])
    >>> tau = maxwell_stress(t, [0.0, 1.0, 1.0], eta=13.0, G=13000.0)
    >>> np.round(tau, 1)   # 13000 * (1 - 1/e), then / e
    array([   0. , 8217.6, 3023.1])

    References
    ----------
    Makris et al., eq 13 (the linear Maxwell model, Bird et al. 1987), reached from eqs 11-12 as a -> 0.
    """
    return makris_stress(t, gamma, 0.0, eta, G, tau0)


def elastic_plastic_stress(gamma, tau_y, G, tau0=0.0):
    r"""Shear stress of the rate-independent limit of the Makris law (:math:`a \to \infty`), closed form.

    When the viscous stress is negligible (:math:`\eta|\dot\gamma| \ll \tau_y`), eq 8 loses time and becomes
    :math:`d\tau/d\gamma = G\,(1 - \tau\operatorname{sgn}(\dot\gamma)/\tau_y)`.  On each branch of monotone
    strain, with direction :math:`s = \pm 1` and starting at the reversal point :math:`(\gamma_r, \tau_r)`:

    .. math::
        \tau(\gamma) = s\,\tau_y + (\tau_r - s\,\tau_y)\,\exp\!\left(-\frac{G\,|\gamma - \gamma_r|}{\tau_y}\right)

    Parameters
    ----------
    gamma : array, shape (N,)
        Shear-strain path, [-] (only the order of the samples matters, not their timing).
    tau_y : float
        Yield stress, [Pa], > 0.
    G : float
        Elastic shear modulus, [Pa], > 0.
    tau0 : float, optional
        Stress at the first sample, [Pa]; default 0.

    Returns
    -------
    array, shape (N,)
        Shear stress at the samples, [Pa].

    Notes
    -----
    The initial slope of every branch is :math:`G(1 + |\tau_r|/\tau_y)` when the branch unloads a stress of the
    opposite sign (up to :math:`2G` after a reversal from the yield plateau), :math:`G` where the stress crosses
    zero, and the stress tends to :math:`\pm\tau_y` (elastic-perfectly-plastic with exponential rounding).  It is
    Bouc-Wen's hysteresis with :math:`n = 1`, :math:`A = G`, :math:`\beta = G/\tau_y`, :math:`\gamma_{BW} = 0`.
    Makris et al. compare this closed form (their reference Makris et al. 1996) with the full model at
    :math:`a = 2000` in their Fig 4 (top); the two differ by :math:`O(\tau_y/a)`.  1-D paths only (the reversal
    points differ from one history to the next); for many histories call :func:`makris_stress` with ``eta = 0``,
    which gives the same stress step by step.

    Examples
    --------
    Monotone loading from rest, :math:`\tau = \tau_y(1 - e^{-G\gamma/\tau_y})`, then unloading by 0.1:
    :math:`-\tau_y + (1799.9 + \tau_y)\,e^{-0.944}`

    >>> import numpy as np
    >>> tau = elastic_plastic_stress([0.0, 0.1, 1.0, 0.9], tau_y=1800.0, G=17000.0)
    >>> np.round(tau, 1)
    array([   0. , 1100. , 1799.9, -400. ])

    References
    ----------
    Makris et al., eq 8 with eta = 0 (the "zero frequency limit", a = infinity, their Fig 4 top).
    """
    gamma = np.asarray(gamma, dtype=float)
    if gamma.ndim != 1:
        raise ErdesignError(f"gamma: expected a 1-D strain path, got shape {gamma.shape}")
    if not np.all(np.isfinite(gamma)):
        raise ErdesignError("gamma: expected finite values")
    if not (np.ndim(tau_y) == 0 and np.ndim(G) == 0 and np.ndim(tau0) == 0):
        raise ErdesignError("tau_y, G, tau0: expected scalars")
    if not (tau_y > 0.0 and G > 0.0):
        raise ErdesignError("tau_y, G: expected tau_y > 0 and G > 0")
    tau = np.full(gamma.shape, float(tau0))
    direction = np.sign(np.diff(gamma))
    moving = np.flatnonzero(direction)
    if moving.size == 0:
        return tau
    # Direction of the branch each step belongs to: a rest step keeps the previous direction (stress held).
    last_moving = np.maximum.accumulate(np.where(direction != 0, np.arange(direction.size), -1))
    first = moving[0]
    s = direction[np.maximum(last_moving, first)]
    # Branch k starts at sample starts[k] (a reversal point) and is followed until the next one.
    starts = first + np.flatnonzero(np.diff(s[first:], prepend=0.0) != 0.0)
    ends = np.append(starts[1:], gamma.size - 1)
    s_branch = s[starts]
    # Stress at each reversal point: branch k maps tau_r,k to tau_r,k+1 (affine in tau_r, closed form above).
    exponent = G * np.abs(gamma[ends] - gamma[starts]) / tau_y
    tau_r = affine_recurrence(np.exp(-exponent), -np.expm1(-exponent) * s_branch * tau_y, tau0)[:-1]
    branch = np.searchsorted(starts, np.arange(gamma.size), side="right") - 1
    on_branch = branch >= 0
    k = branch[on_branch]
    g_r = gamma[starts[k]]
    tau[on_branch] = s_branch[k] * tau_y + (tau_r[k] - s_branch[k] * tau_y) * np.exp(
        -G * np.abs(gamma[on_branch] - g_r) / tau_y
    )
    return tau


def integration_factor_exponent(omega_t, a, G, eta, omega):
    r"""Exponent :math:`\int R\,dt` of the integrating factor of the Makris law under harmonic strain (eq 11).

    For :math:`\dot\gamma = \omega\gamma_0\cos\omega t` and :math:`-\pi/2 \le \omega t \le \pi/2`:

    .. math::
        E = \int_0^t \frac{G\omega\gamma_0\cos\omega t'}{\eta\omega\gamma_0\cos\omega t' + \tau_y}\,dt'
        = \frac{G}{\eta\omega}\begin{cases}
        \omega t - \dfrac{2a}{\sqrt{a^2-1}}\arctan\dfrac{\sqrt{a^2-1}\,\tan(\omega t/2)}{a+1} & a > 1\\[1ex]
        \omega t - \tan(\omega t/2) & a = 1\\[1ex]
        \omega t - \dfrac{a}{\sqrt{1-a^2}}\ln\dfrac{k + \tan(\omega t/2)}{k - \tan(\omega t/2)},
        \quad k = \sqrt{\dfrac{1+a}{1-a}} & 0 \le a < 1
        \end{cases}

    with :math:`a = \tau_y/(\eta\omega\gamma_0)`.  Outside that interval the integrand
    :math:`R = (G/\eta)\,|\cos\omega t|/(|\cos\omega t| + a)` is periodic with period :math:`\pi` in
    :math:`\omega t`, so :math:`E(\omega t) = m\,E_\pi + E(\omega t - m\pi)` with :math:`m` the nearest integer to
    :math:`\omega t/\pi` and :math:`E_\pi = 2E(\pi/2)` the exponent gained per half cycle.

    Parameters
    ----------
    omega_t : float or array
        Phase :math:`\omega t`, [rad]; any value (the printed eq 11 covers [-pi/2, pi/2]).
    a : float or array
        Yield stress over peak viscous stress, :math:`\tau_y/(\eta\omega\gamma_0)`, [-], >= 0.
    G : float or array
        Elastic shear modulus, [Pa].
    eta : float or array
        Plastic viscosity, [Pa s], > 0.
    omega : float or array
        Angular frequency of the strain, [rad/s].

    Returns
    -------
    float or array
        :math:`\int_0^t R\,dt'`, [-]; zero at :math:`\omega t = 0`, odd in :math:`\omega t`.  The free stress of
        eq 8 decays as :math:`e^{-E}`.

    Notes
    -----
    All three printed cases check against quadrature of the integrand to round-off (tests).  Makris states that
    for :math:`\pi/2 \le \omega t \le 3\pi/2` one replaces :math:`a` by :math:`-a`; that holds for the
    integrand, but the closed forms with :math:`-a` pass through :math:`\tan(\omega t/2) = \pm\infty` at
    :math:`\omega t = \pi` (a jump of the antiderivative) and, for :math:`a < 1`, take the logarithm of a negative
    number.  The shift by :math:`\pi` used here avoids both.  The two sides of :math:`a = 1` are evaluated in
    forms that stay accurate as :math:`a \to 1` (:math:`a^2 - 1 = (a-1)(a+1)`, ``log1p``), so the middle case is
    the continuous limit of the others.  For :math:`a \to 0` the exponent tends to :math:`G t/\eta` (eq 12 and
    the text after it), the Maxwell limit.

    Examples
    --------
    >>> import numpy as np
    >>> round(integration_factor_exponent(np.pi / 2, a=1.0, G=17000.0, eta=13.0, omega=2 * np.pi), 4)
    118.7974
    >>> round(integration_factor_exponent(np.pi / 2, a=0.0, G=1.0, eta=1.0, omega=1.0), 12)   # G t / eta
    1.570796326795

    References
    ----------
    Makris et al., eq 11 (and eq 12, its a^2 << 1 form); the text after eq 11 for the second half cycle.
    """
    omega_t, a = np.broadcast_arrays(np.asarray(omega_t, dtype=float), np.asarray(a, dtype=float))
    if np.any(a < 0.0):
        raise ErdesignError("a: expected a >= 0 (a = tau_y / (eta omega gamma0))")
    half_cycles = np.round(omega_t / np.pi)
    theta = omega_t - half_cycles * np.pi
    bracket = _eq11_bracket(theta, a) + half_cycles * 2.0 * _eq11_bracket(np.full_like(a, np.pi / 2), a)
    out = G / (eta * omega) * bracket
    return out if np.ndim(out) else float(out)


def _eq11_bracket(theta, a):
    """The square bracket of eq 11 for |theta| <= pi/2 (a >= 0), each case on its own branch."""
    x = np.tan(0.5 * theta)
    above = a > 1.0
    below = a < 1.0
    with np.errstate(divide="ignore", invalid="ignore"):
        # a > 1: sqrt(a^2 - 1) written as sqrt((a - 1)(a + 1)) to keep its digits near a = 1.
        root_above = np.sqrt((a - 1.0) * (a + 1.0))
        atan_term = np.where(above, 2.0 * a / root_above * np.arctan(root_above * x / (a + 1.0)), 0.0)
        # a < 1: ln((k + x)/(k - x)) = log1p(2x/(k - x)); k -> inf as a -> 1 and the term tends to x.
        root_below = np.sqrt((1.0 - a) * (1.0 + a))
        k = np.sqrt((1.0 + a) / (1.0 - a))
        log_term = np.where(below & (a > 0.0), a / root_below * np.log1p(2.0 * x / (k - x)), 0.0)
    return theta - np.where(above, atan_term, np.where(below, log_term, x))
