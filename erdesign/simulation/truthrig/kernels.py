r"""Compiled kernels of the truth rig: flow paths in parallel, the steady force, and the time-stepping loop.

Sign convention (shared with :mod:`erdesign.simulation.rig` and the effect library): ``x`` grows as the rod goes in
(compression), and the force ``F`` is the force the test machine applies in the direction of ``+x``, so that a
damper resists with ``F`` of the sign of ``v``.  Compression is ``v > 0``, rebound (extension) ``v < 0``.

The fluid element is a set of flow paths in parallel between the two chambers, all driven by the same pressure
drop :math:`\Delta p = F/A` (``A`` the area of the pressurised chamber: the compression or the rebound area):

* ``ducts`` annular ducts with the Herschel-Bulkley / Bingham slit law of :mod:`erdesign.simulation.truthrig.valve`;
* a laminar bypass, :math:`Q_l = g_l \Delta p` (``g_l = A_p^2 / C_l``);
* a rebound blow-off valve, :math:`Q_b = g_b (\Delta p - p_c)` above its cracking pressure, in rebound only.

:func:`passed_speed` is the piston speed these paths pass at a force, :math:`v_d(F) = \sum Q / A`, monotone
non-decreasing in ``F``; every force in the rig is a root of a monotone scalar equation built on it
(:func:`monotone_root`, Newton steps inside a shrinking bracket, bisection as the fall-back).

The moving-electrode (mixed-mode) head has one gap whose inner wall is the head itself: the gap's flow depends on
the pressure drop and on the head's speed (:func:`erdesign.simulation.truthrig.valve.moving_wall_flow`), and the head
feels the wall stress besides the pressure.  Its steady force (:func:`mixed_steady_force`) is the pressure drop at which
the gap and the bypass send the displaced volume :math:`A_p v` back past the head, a root of a monotone equation in
:math:`\Delta p` (:func:`mixed_pressure`, the Illinois method on a doubled bracket), plus wall stress times wall
area.  No blow-off, cavitation or single rod for this head
(:data:`erdesign.simulation.truthrig.simulate.MIXED_MECHANISMS`).

:func:`run` integrates, on a fine grid of substeps, the states that need time stepping (each optional):

* compliance with the slug in series, states :math:`P` (pressure force) and :math:`w` (speed the ducts pass),
  :math:`\dot P = k_c (v - w)`, :math:`m \dot w = P - F_v(w)`, backward Euler with the exact stroke increment
  :math:`\Delta x` in place of :math:`h v`; eliminating :math:`P` leaves one monotone equation in the valve force
  :math:`F_v` per step, :math:`F_v + (m/h + k_c h)\,v_d(F_v) = m w/h + P + k_c \Delta x`; on the mixed head
  (no slug in series: its slug is rigid) :math:`P = P_0 + k_c(\Delta x + h\,Q(P/A_p, v)/A_p)`, monotone in
  :math:`P`, and the force on the head adds the wall stress at that pressure;
* the damper-level Makris eq 8 (pre-yield), :math:`\dot F = K v\,(1 - F / F_r(v))`, linear in the force over a
  step and integrated exactly with the rate coefficient frozen at mid-step;
* compliance and pre-yield together: the column's spring in series with the Makris element, one force through
  both; per step the element's stroke :math:`\Delta u` solves
  :math:`M(P, \Delta u) = P + k_c(\Delta x - \Delta u)`, with :math:`M` the exact step of the element above at
  its speed :math:`\Delta u/h` (Illinois method; the residual grows without bound both ways);
* the lumped temperature rise, trapezoidal rule on its linear cooling and the energy dissipated in the step,
  which makes heat stored + heat lost = work dissipated hold to round-off over every step.

Departures from the printed Makris eq 8,
:math:`\tau + [(\eta\dot\gamma + \tau_y \operatorname{sgn}\dot\gamma)/(G\dot\gamma)]\,\dot\tau
= \eta\dot\gamma + \tau_y \operatorname{sgn}\dot\gamma` (its right side prints :math:`\nu_0` for
:math:`\eta_0`): (1) it is used multiplied through by :math:`G\dot\gamma/(\eta\dot\gamma + \tau_y
\operatorname{sgn}\dot\gamma)`, which is the same law where both are defined and regular at
:math:`\dot\gamma = 0`, where the printed coefficient is 0/0 (the stress is then held); (2) it is written for the
damper, not a material point: stress -> force, :math:`G\dot\gamma \to K v` with
:math:`K = 12 G L A_p^2/(n\pi d h^3)` (an elastic solid in the slit deflects in the parabola the Newtonian fluid
flows in), and the steady stress :math:`\eta\dot\gamma + \tau_y\operatorname{sgn}\dot\gamma` -> the exact
steady force :math:`F_r(v)` of the flow paths (Buckingham-Reiner, not :math:`C v + F_y`), so that the law relaxes
onto the rigid damper at large amplitude.  With :math:`\tau_y = 0` it is the Maxwell element (Makris eq 13).

References
----------
Makris, Burton, Hill and Jordan (1996), eqs 6, 8 and 13.
"""

from __future__ import annotations

import math

import numpy as np

from ..._compile import njit
from .valve import moving_wall_flow_from, slit_flow, slit_flow_slope

__all__ = [
    "N_PARAMETERS",
    "passed_speed",
    "steady_force",
    "monotone_root",
    "mixed_flow",
    "mixed_pressure",
    "mixed_steady_force",
    "any_steady_force",
    "series_step",
    "run",
    "first_order_lag",
    "two_stage_lag",
    "play_operator",
]

# Indices into the parameter vector of the kernels (SI).
I_L, I_B, I_H, I_DUCTS, I_M, I_GAMMA_REF = 0, 1, 2, 3, 4, 5
I_GL, I_GB, I_PC = 6, 7, 8  # bypass conductance, blow-off conductance, cracking pressure
I_AC, I_AR, I_CAP = 9, 10, 11  # compression area, rebound area, rebound force cap (inf: none)
I_KC, I_MSLUG, I_KPRE = 12, 13, 14  # compliance stiffness, slug mass, pre-yield stiffness (0: off)
I_HEAT_CAPACITY, I_COOLING_TIME, I_ALPHA = 15, 16, 17  # heat capacity 0: no thermal state
I_MIXED, I_AWALL = 18, 19  # 1: moving-electrode head (0: valve); area of the head's wall
N_PARAMETERS = 20


@njit(cache=True)
def _area(direction, p):
    return p[I_AC] if direction > 0 else p[I_AR]


@njit(cache=True)
def passed_speed(F, direction, tau_y, eta, thermal, p):
    """Piston speed [m/s] passed by all flow paths at force magnitude ``F`` >= 0 [N] in ``direction`` (+1
    compression, -1 rebound); ``thermal`` = eta(T)/eta(T0) scales the bypass conductance."""
    A = _area(direction, p)
    dp = F / A
    m = p[I_M]
    K = eta * p[I_GAMMA_REF] ** (1.0 - m)
    q = p[I_DUCTS] * slit_flow(dp, tau_y, K, m, p[I_L], p[I_B], p[I_H])
    q += p[I_GL] / thermal * dp
    if direction < 0 and dp > p[I_PC]:
        q += p[I_GB] * (dp - p[I_PC])
    return q / A


@njit(cache=True)
def _passed_speed_slope(F, direction, tau_y, eta, thermal, p):
    A = _area(direction, p)
    dp = F / A
    m = p[I_M]
    K = eta * p[I_GAMMA_REF] ** (1.0 - m)
    s = p[I_DUCTS] * slit_flow_slope(dp, tau_y, K, m, p[I_L], p[I_B], p[I_H]) + p[I_GL] / thermal
    if direction < 0 and dp > p[I_PC]:
        s += p[I_GB]
    return s / (A * A)


@njit(cache=True)
def monotone_root(c0, c1, R, direction, tau_y, eta, thermal, p):
    """F >= 0 with c0 F + c1 v_d(F) = R (R >= 0; c0, c1 >= 0, not both 0): the function is non-decreasing in F and
    -R at F = 0.  Converged to a relative 1e-14 of F (or the bracket collapsed)."""
    if R <= 0.0:
        return 0.0
    lo = 0.0
    if c0 > 0.0:
        hi = R / c0
    else:
        # the Bingham bound dp <= dp_Newtonian + 1.5 dp_y for a start, doubled until it brackets (Herschel-Bulkley)
        A = _area(direction, p)
        K = eta * p[I_GAMMA_REF] ** (1.0 - p[I_M])
        cond = p[I_DUCTS] * p[I_B] * p[I_H] ** 3 / (12.0 * K * p[I_L])
        hi = A * (1.5 * 2.0 * tau_y * p[I_L] / p[I_H] + R / c1 * A / cond) * 1.01 + 1e-300
        for _ in range(2000):
            if c0 * hi + c1 * passed_speed(hi, direction, tau_y, eta, thermal, p) >= R:
                break
            lo = hi
            hi *= 2.0
    x = 0.5 * (lo + hi)
    for _ in range(200):
        f = c0 * x + c1 * passed_speed(x, direction, tau_y, eta, thermal, p) - R
        if f == 0.0:
            return x
        if f < 0.0:
            lo = x
        else:
            hi = x
        slope = c0 + c1 * _passed_speed_slope(x, direction, tau_y, eta, thermal, p)
        x_new = x - f / slope if slope > 0.0 else 0.5 * (lo + hi)
        if not (lo < x_new < hi):
            x_new = 0.5 * (lo + hi)
        if abs(x_new - x) <= 1e-14 * x_new or hi - lo <= 1e-15 * hi:
            return x_new
        x = x_new
    return x


@njit(cache=True)
def steady_force(v, tau_y, eta, thermal, p):
    """Signed steady force [N] of the rigid fluid at piston speed ``v`` [m/s] (0 at v = 0), rebound cap applied."""
    if v == 0.0:
        return 0.0
    direction = 1 if v > 0.0 else -1
    F = monotone_root(0.0, 1.0, abs(v), direction, tau_y, eta, thermal, p)
    if direction < 0:
        F = min(F, p[I_CAP])
    return direction * F


# ---------------------------------------------------------------------------------------------------- mixed mode
@njit(cache=True)
def mixed_flow(dp, U, tau_y, eta, thermal, p, guess=math.nan):
    """(Q, tau_h, tau_0) of the moving-electrode head: flow along the head's motion through its gap and the bypass
    [m^3/s] at pressure drop ``dp`` (ahead minus behind) and head speed ``U``, the stress on the head's wall [Pa],
    and the stress on the cylinder's wall (``guess`` for the next call; :func:`erdesign.simulation.truthrig.valve.
    moving_wall_flow`)."""
    m = p[I_M]
    K = eta * p[I_GAMMA_REF] ** (1.0 - m)
    q, tau_h, tau0 = moving_wall_flow_from(dp, U, tau_y, K, m, p[I_L], p[I_H], guess)
    return p[I_B] * q - p[I_GL] / thermal * dp, tau_h, tau0


@njit(cache=True)
def mixed_pressure(c0, c1, R, U, tau_y, eta, thermal, p, guess=math.nan):
    """The pressure drop dp with c0 dp - c1 Q(dp, U) = R (c0 >= 0, c1 > 0; Q of :func:`mixed_flow` falls as dp
    rises, so the left side increases), started from ``guess`` (the previous step's root): a bracket widened until
    it holds the root, then the Illinois method.  Returns (dp, tau_h at dp)."""
    A = p[I_AC]
    yield_drop = 2.0 * tau_y * p[I_L] / p[I_H]
    w = p[I_B] * p[I_H] ** 3 / (12.0 * eta * p[I_L])
    scale = yield_drop + (abs(R) / c1 + p[I_B] * p[I_H] * abs(U)) / w + 1e-12 * A
    if guess == guess:
        step = 1e-3 * (abs(guess) + yield_drop) + 1e-12 * A
        lo, hi = guess - step, guess + step
    else:
        step = scale
        lo, hi = -scale, scale
    f_lo, _, t_lo = mixed_flow(lo, U, tau_y, eta, thermal, p)
    f_lo = c0 * lo - c1 * f_lo - R
    f_hi, _, t_hi = mixed_flow(hi, U, tau_y, eta, thermal, p, t_lo)
    f_hi = c0 * hi - c1 * f_hi - R
    for _ in range(400):
        if f_lo <= 0.0:
            break
        hi, f_hi, t_hi = lo, f_lo, t_lo
        step *= 2.0
        lo -= step
        f_lo, _, t_lo = mixed_flow(lo, U, tau_y, eta, thermal, p, t_lo)
        f_lo = c0 * lo - c1 * f_lo - R
    for _ in range(400):
        if f_hi >= 0.0:
            break
        lo, f_lo, t_lo = hi, f_hi, t_hi
        step *= 2.0
        hi += step
        f_hi, _, t_hi = mixed_flow(hi, U, tau_y, eta, thermal, p, t_hi)
        f_hi = c0 * hi - c1 * f_hi - R
    x, t_x = hi, t_hi
    if f_lo == 0.0:
        x, t_x = lo, t_lo
    elif f_hi != 0.0:
        side = 0
        for _ in range(300):
            x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
            if not (lo < x < hi):
                x = 0.5 * (lo + hi)
            f, _, t_x = mixed_flow(x, U, tau_y, eta, thermal, p, 0.5 * (t_lo + t_hi))
            f = c0 * x - c1 * f - R
            if f == 0.0 or hi - lo <= 1e-14 * max(abs(lo), abs(hi)):
                break
            if f < 0.0:
                lo, f_lo, t_lo = x, f, t_x
                if side == -1:
                    f_hi *= 0.5
                side = -1
            else:
                hi, f_hi, t_hi = x, f, t_x
                if side == 1:
                    f_lo *= 0.5
                side = 1
    return x, mixed_flow(x, U, tau_y, eta, thermal, p, t_x)[1]


@njit(cache=True)
def mixed_steady_force(v, tau_y, eta, thermal, p, guess=math.nan):
    """Signed steady force [N] of the rigid moving-electrode head at speed ``v`` (0 at v = 0): the pressure drop
    that sends the displaced volume A_p v back past the head, times A_p, plus the wall stress times the head's wall
    area; ``guess`` a pressure drop to start from."""
    if v == 0.0:
        return 0.0
    dp, tau_h = mixed_pressure(0.0, 1.0, p[I_AC] * v, v, tau_y, eta, thermal, p, guess)
    return dp * p[I_AC] + tau_h * p[I_AWALL]


@njit(cache=True)
def any_steady_force(v, tau_y, eta, thermal, p):
    """:func:`steady_force` of the valve or :func:`mixed_steady_force` of the moving-electrode head."""
    if p[I_MIXED] > 0.0:
        return mixed_steady_force(v, tau_y, eta, thermal, p)
    return steady_force(v, tau_y, eta, thermal, p)


@njit(cache=True)
def _steady_from(v, tau_y, eta, thermal, p, guess):
    """(steady force, pressure drop to start the next root from): :func:`any_steady_force` started from ``guess``
    on the mixed head (consecutive substeps differ little)."""
    if p[I_MIXED] == 0.0:
        return steady_force(v, tau_y, eta, thermal, p), math.nan
    if v == 0.0:
        return 0.0, guess
    dp, tau_h = mixed_pressure(0.0, 1.0, p[I_AC] * v, v, tau_y, eta, thermal, p, guess)
    return dp * p[I_AC] + tau_h * p[I_AWALL], dp


@njit(cache=True)
def _makris_step(F, du, kpre, tau_y, eta, thermal, hi, p):
    """Force after a step of the damper-level Makris eq 8 element that strokes by ``du`` in time ``hi`` from force
    ``F`` (rate coefficient at the step's mean speed, exact for it frozen)."""
    if du == 0.0:
        return F
    Fr = abs(any_steady_force(du / hi, tau_y, eta, thermal, p))
    if Fr <= 0.0:
        return 0.0
    z = kpre * abs(du) / Fr
    phi = (1.0 - math.exp(-z)) / z if z > 1e-8 else 1.0 - 0.5 * z
    return F * math.exp(-z) + kpre * du * phi


@njit(cache=True)
def series_step(P, dxi, hi, kc, kpre, tau_y, eta, thermal, p):
    """Column compliance ``kc`` in series with the Makris element (stiffness ``kpre``): the element's stroke du in a
    step with stroke ``dxi``, where the spring's force P + kc (dxi - du) equals the element's; returns the force.
    The residual grows without bound in du both ways, so a doubled bracket holds a root (Illinois method)."""
    a = abs(dxi) + abs(P) / kc + 1e-300
    lo, hi_ = -a, a
    f_lo = _makris_step(P, lo, kpre, tau_y, eta, thermal, hi, p) - P - kc * (dxi - lo)
    f_hi = _makris_step(P, hi_, kpre, tau_y, eta, thermal, hi, p) - P - kc * (dxi - hi_)
    for _ in range(200):
        if f_lo <= 0.0:
            break
        lo *= 2.0
        f_lo = _makris_step(P, lo, kpre, tau_y, eta, thermal, hi, p) - P - kc * (dxi - lo)
    for _ in range(200):
        if f_hi >= 0.0:
            break
        hi_ *= 2.0
        f_hi = _makris_step(P, hi_, kpre, tau_y, eta, thermal, hi, p) - P - kc * (dxi - hi_)
    x = 0.5 * (lo + hi_)
    side = 0
    for _ in range(300):
        if f_hi == f_lo:
            x = 0.5 * (lo + hi_)
        else:
            x = (lo * f_hi - hi_ * f_lo) / (f_hi - f_lo)
        if not (lo < x < hi_):
            x = 0.5 * (lo + hi_)
        f = _makris_step(P, x, kpre, tau_y, eta, thermal, hi, p) - P - kc * (dxi - x)
        if f == 0.0 or hi_ - lo <= 1e-14 * max(abs(lo), abs(hi_)):
            break
        if f < 0.0:
            lo, f_lo = x, f
            if side == -1:
                f_hi *= 0.5
            side = -1
        else:
            hi_, f_hi = x, f
            if side == 1:
                f_lo *= 0.5
            side = 1
    return P + kc * (dxi - x)


@njit(cache=True)
def run(v, dx, h, tau_y, eta, p):
    """Integrate the fluid element over a fine grid (module notes).

    Parameters: piston velocity ``v`` at the grid points, stroke increment ``dx`` and step ``h`` of the step that
    ends at each point (index 0 unused), yield stress and plastic viscosity (at T0) seen at each point, and the
    parameter vector.  Returns the fluid force on the piston, the valve force (the force the ducts carry), the
    temperature rise and the energy dissipated in each step, all at the grid points.
    """
    n = v.size
    force = np.zeros(n)
    valve = np.zeros(n)
    theta = np.zeros(n)
    dissipated = np.zeros(n)
    kc, mass, kpre = p[I_KC], p[I_MSLUG], p[I_KPRE]
    heat_capacity, cooling_time, alpha = p[I_HEAT_CAPACITY], p[I_COOLING_TIME], p[I_ALPHA]
    cap = p[I_CAP]
    mixed = p[I_MIXED] > 0.0
    last = math.nan  # the mixed head's previous pressure drop, where its next root is sought first
    P, w, T = 0.0, 0.0, 0.0  # stateful elements start unloaded and at rest, at the ambient temperature
    if kc == 0.0 and kpre == 0.0:
        force[0] = any_steady_force(v[0], tau_y[0], eta[0], 1.0, p)
        valve[0] = force[0]
    elif mixed and kpre == 0.0:
        force[0] = mixed_flow(0.0, v[0], tau_y[0], eta[0], 1.0, p)[1] * p[I_AWALL]  # the wall's drag, unloaded
    for i in range(1, n):
        thermal = math.exp(-alpha * T) if heat_capacity > 0.0 else 1.0
        eta_i = eta[i] * thermal
        hi = h[i]
        if kc > 0.0 and kpre > 0.0:
            # the compliant column in series with the elastic-viscoplastic fluid: one force through both
            P_new = series_step(P, dx[i], hi, kc, kpre, tau_y[i], eta_i, thermal, p)
            if P_new < -cap:
                P_new = -cap
            energy = 0.5 * (P + P_new) * dx[i] - (P_new * P_new - P * P) * (0.5 / kc + 0.5 / kpre)
            P = P_new
            force[i], valve[i] = P, P
        elif kc > 0.0 and mixed:
            # the head's pressure force P = A_p dp compresses the column; the gap's flow (with the head's wall
            # dragging it) relieves it: backward Euler, P = P_old + kc (dx + h Q(P / A_p, v) / A_p)
            Ap = p[I_AC]
            dp, tau_h = mixed_pressure(Ap, kc * hi / Ap, P + kc * dx[i], v[i], tau_y[i], eta_i, thermal, p, last)
            last = dp
            P_old = P
            P = dp * Ap
            F = P + tau_h * p[I_AWALL]
            energy = F * dx[i] - (P * P - P_old * P_old) / (2.0 * kc)
            force[i], valve[i] = F, P
        elif kc > 0.0:
            c = mass / hi + kc * hi
            R = mass * w / hi + P + kc * dx[i]
            direction = 1 if R >= 0.0 else -1
            Fv = monotone_root(1.0, c, abs(R), direction, tau_y[i], eta_i, thermal, p)
            w = direction * passed_speed(Fv, direction, tau_y[i], eta_i, thermal, p)
            Fv *= direction
            P = P + kc * (dx[i] - hi * w)
            if P < -cap:
                P = -cap
            energy = hi * Fv * w
            force[i], valve[i] = P, Fv
        elif kpre > 0.0:
            v_mid = 0.5 * (v[i - 1] + v[i])
            lam = 0.0
            if v_mid != 0.0:
                Fr, last = _steady_from(v_mid, tau_y[i], eta_i, thermal, p, last)
                Fr = abs(Fr)
                if Fr > 0.0:
                    lam = kpre * abs(v_mid) / Fr
            z = lam * hi
            phi = (1.0 - math.exp(-z)) / z if z > 1e-8 else 1.0 - 0.5 * z
            F_new = P * math.exp(-z) + kpre * dx[i] * phi
            if F_new < -cap:
                F_new = -cap
            energy = 0.5 * (P + F_new) * dx[i] - (F_new * F_new - P * P) / (2.0 * kpre)
            P = F_new
            force[i], valve[i] = P, P
        else:
            F, last = _steady_from(v[i], tau_y[i], eta_i, thermal, p, last)
            energy = 0.5 * (force[i - 1] * v[i - 1] + F * v[i]) * hi
            force[i], valve[i] = F, F
        if heat_capacity > 0.0:
            k = 0.5 * hi / cooling_time
            T = (T * (1.0 - k) + energy / heat_capacity) / (1.0 + k)
        theta[i] = T
        dissipated[i] = energy
    return force, valve, theta, dissipated


@njit(cache=True)
def first_order_lag(command, h, time_constant, initial):
    """Exact response of u' = (c - u)/T at the grid points to a command ``command[i-1]`` held over step i."""
    n = command.size
    u = np.empty(n)
    u[0] = initial
    for i in range(1, n):
        e = math.exp(-h[i] / time_constant)
        u[i] = command[i - 1] + (u[i - 1] - command[i - 1]) * e
    return u


@njit(cache=True)
def two_stage_lag(command, h, first, second, initial):
    """Exact response of two first-order stages in cascade, u1' = (c - u1)/T1, u2' = (u1 - u2)/T2, at the grid
    points to a command ``command[i-1]`` held over step i; returns u2 (both stages start at ``initial``).

    Over a step of length h with the command c held, u1 = c + (u1_0 - c) exp(-t/T1) and
    u2(h) = c + (u2_0 - c) exp(-h/T2) + (u1_0 - c) T1 / (T1 - T2) (exp(-h/T1) - exp(-h/T2)), whose limit for
    T2 -> T1 is (u1_0 - c) (h/T1) exp(-h/T1).
    """
    n = command.size
    u2 = np.empty(n)
    u1 = initial
    u2[0] = initial
    for i in range(1, n):
        c = command[i - 1]
        e1, e2 = math.exp(-h[i] / first), math.exp(-h[i] / second)
        if abs(first - second) > 1e-9 * first:
            cross = first / (first - second) * (e1 - e2)
        else:
            cross = h[i] / first * e1
        u2[i] = c + (u2[i - 1] - c) * e2 + (u1 - c) * cross
        u1 = c + (u1 - c) * e1
    return u2


@njit(cache=True)
def play_operator(x, half_width, initial):
    """Play (backlash) operator: y follows x only when |x - y| reaches ``half_width``."""
    y = np.empty(x.size)
    yi = initial
    for i in range(x.size):
        yi = max(x[i] - half_width, min(x[i] + half_width, yi))
        y[i] = yi
    return y
