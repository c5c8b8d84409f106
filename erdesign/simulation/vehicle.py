r"""Quarter-vehicle with a passive MR damper (Butz and von Stryk, Butz and von Stryk (2002) section 4).

.. math::
    m_1\ddot u_1 = K(u_0 - u_1) + C(\dot u_0 - \dot u_1) + k(u_2 - u_1) + F_{rh}, \qquad
    m_2\ddot u_2 = -k(u_2 - u_1) - F_{rh}

(eqs 31-32; axle m1, body m2, road u0).  The damper force F_rh is a conventional dashpot (eq 33), the Bingham model
(eq 34) or the modified Bouc-Wen model (eqs 35-37), with the paper's parameters (:data:`QUARTER_CAR`).
Simulations return a :class:`VehicleResponse` (time, displacements, velocities, damper force).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from ..errors import ErdesignError
from ..models.bouc_wen import SPENCER_PASSIVE

__all__ = ["QUARTER_CAR", "VehicleResponse", "simulate_quarter_car", "step_road", "bump_road", "settling_time"]

#: Butz and von Stryk (2002) section 4.1-4.3: masses [kg], stiffnesses [N/m], damping [N s/m], Bingham and Bouc-Wen
#: parameters (SI).
QUARTER_CAR = {"m1": 250.0, "m2": 1300.0, "K": 650e3, "C": 800.0, "k": 110e3, "c": 6000.0,
               "c0_bingham": 5000.0, "f_c": 670.0}


@dataclass
class VehicleResponse:
    """Time [s], axle and body displacement u1, u2 [m] and velocities [m/s], damper force [N]."""

    time: np.ndarray
    u1: np.ndarray
    u2: np.ndarray
    v1: np.ndarray
    v2: np.ndarray
    force: np.ndarray
    damper: str


def step_road(height=0.1):
    """Road step of ``height`` [m] at t = 0 (Butz and von Stryk 2002, section 4.4): (u0(t), du0/dt(t), impulse of C
    du0)."""
    return (lambda t: height), (lambda t: 0.0), height


def bump_road(height=0.1, duration=0.5, start=0.0):
    """Sinusoidal bump (1 - cos) of ``height`` [m] lasting ``duration`` [s] (Butz and von Stryk 2002, section 4.5;
    the paper shows
    the shape in its Figure 25 without the duration: 0.5 s is this project's assumption)."""
    w = 2 * math.pi / duration

    def u0(t):
        return 0.5 * height * (1 - math.cos(w * (t - start))) if start <= t <= start + duration else 0.0

    def du0(t):
        return 0.5 * height * w * math.sin(w * (t - start)) if start <= t <= start + duration else 0.0

    return u0, du0, 0.0


def simulate_quarter_car(damper="bingham", road=None, t_end=3.0, n=3001, *, v_eps=1e-4, params=None):
    """Simulate the quarter vehicle with a ``"conventional"``, ``"bingham"`` or ``"bouc_wen_modified"`` damper.

    Notes
    -----
    The step's tyre-damper term C du0/dt is an impulse: it is applied as the jump of the axle velocity
    C h / m1 at t = 0 (the paper's Simulink model would see a large finite spike).  The Bingham sign function is
    regularised as tanh(dv / v_eps) with v_eps = 0.1 mm/s (tests/test_vehicle.py checks the body motion does not
    change when v_eps is halved).  Integrated by LSODA (stiff-switching) with tight tolerances.
    """
    if damper not in ("conventional", "bingham", "bouc_wen_modified"):
        raise ErdesignError(f"damper: expected 'conventional', 'bingham' or 'bouc_wen_modified', got {damper!r}")
    q = {**QUARTER_CAR, **(params or {})}
    bw = {**SPENCER_PASSIVE}
    u0, du0, jump = road if road is not None else step_road()
    m1, m2, K, C, k = q["m1"], q["m2"], q["K"], q["C"], q["k"]

    def damper_force(u1, v1, u2, v2, y, z):
        dv = v2 - v1
        if damper == "conventional":
            return q["c"] * dv, 0.0, 0.0
        if damper == "bingham":
            return q["f_c"] * math.tanh(dv / v_eps) + q["c0_bingham"] * dv, 0.0, 0.0
        c0, c1 = bw["c0a"], bw["c1a"]
        yd = (bw["alpha_a"] * z + c0 * v2 + c1 * v1 + bw["k0"] * (u2 - y)) / (c0 + c1)
        w = v2 - yd
        zd = -bw["gamma"] * abs(w) * z * abs(z) - bw["beta"] * w * z * z + bw["delta"] * w
        return c1 * (yd - v1) + bw["k1"] * ((u2 - u1) - bw["x0"]), yd, zd

    def rhs(t, s):
        u1, v1, u2, v2, y, z = s
        F, yd, zd = damper_force(u1, v1, u2, v2, y, z)
        a1 = (K * (u0(t) - u1) + C * (du0(t) - v1) + k * (u2 - u1) + F) / m1
        a2 = (-k * (u2 - u1) - F) / m2
        return [v1, a1, v2, a2, yd, zd]

    t = np.linspace(0, t_end, n)
    s0 = [0.0, C * jump / m1, 0.0, 0.0, 0.0, 0.0]
    sol = solve_ivp(rhs, (0, t_end), s0, t_eval=t, method="LSODA", rtol=1e-8, atol=1e-10, max_step=1e-3)
    if not sol.success:
        raise ErdesignError(f"quarter-car simulation failed: {sol.message}")
    u1, v1, u2, v2, y, z = sol.y
    F = np.array([damper_force(*s)[0] for s in sol.y.T])
    return VehicleResponse(t, u1, u2, v1, v2, F, damper)


def settling_time(t, u, final, band):
    """Last time |u - final| exceeds ``band`` [s] (0 if never)."""
    outside = np.flatnonzero(np.abs(np.asarray(u) - final) > band)
    return float(t[outside[-1]]) if outside.size else 0.0
