r"""Semi-active control laws of the quarter vehicle: passive, skyhook, groundhook and clipped-optimal.

Each law sees the vehicle at a run of samples (:class:`VehicleState`, arrays) and gives a desired damper force F_d
[N], realised by the damper's inverse model (:func:`erdesign.identification.inverse.inverse_control`, which clips the
control to its range: a semi-active damper can only dissipate), or, for the clipped-optimal law, by switching the
control between its limits.  Sign convention as Butz and von Stryk (2002) eqs 31-32: the damper force F acts on the
axle as +F and on the body as -F, and F = c (v2 - v1) for a dashpot.

* skyhook (Karnopp, Crosby and Harwood 1974): F_d = c_sky v2, a dashpot from the body to the "sky";
* groundhook (Valasek et al. 1997): F_d = -c_gnd v1, a dashpot from the axle to the ground;
* clipped-optimal (Dyke, Spencer, Sain and Carlson 1996): full control when the damper force F of the step before has
  the sign of F_d and is smaller in magnitude, ((F_d - F) F > 0), none otherwise, with F_d the optimal active force
  of the linear vehicle (:func:`lqr_gains`).

The linear-quadratic regulator minimises

.. math:: J = \int_0^\infty \ddot u_2^2 + q_t (u_2 - u_1)^2 + q_d (u_1 - u_0)^2 \, dt

over the active force F = -K s, s = (u1 - u0, v1, u2 - u1, v2), the road velocity being the disturbance.  Dyke et
al. design their primary controller by H2/LQG for a structure; for the vehicle the weights are this project's
choice (:data:`LQR_WEIGHTS`: travel and tyre deflection weighted so that 1 cm of either costs as much as 1 m/s^2
and 3.2 m/s^2 of body acceleration).  The body acceleration contains F, so J has a cross term
(:func:`scipy.linalg.solve_continuous_are` with ``s``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..errors import ErdesignError

__all__ = ["VehicleState", "ControlLaw", "CONTROLLERS", "get_controller", "lqr_gains", "LQR_WEIGHTS"]

#: Weights of the regulator of the clipped-optimal law: suspension travel q_t and tyre deflection q_d [1/s^4].
LQR_WEIGHTS = {"q_t": 1e4, "q_d": 1e5}


@dataclass(frozen=True)
class VehicleState:
    """Road u0, axle u1 and body u2 displacement [m], axle and body velocity v1, v2 [m/s] and the damper force of
    the step before F [N], one value per sample."""

    u0: np.ndarray
    u1: np.ndarray
    u2: np.ndarray
    v1: np.ndarray
    v2: np.ndarray
    force: np.ndarray


@dataclass(frozen=True)
class ControlLaw:
    """A control law: ``primary(car, gain)`` builds the desired-force function of the vehicle ``car`` (state ->
    F_d [N]; None for passive); ``on_off`` True when the law switches the control between its limits itself instead
    of asking the inverse model for F_d; ``uses_gain`` True when ``gain`` (a damping, N s/m) sets F_d."""

    name: str
    primary: Callable | None
    on_off: bool = False
    uses_gain: bool = False
    description: str = ""


def lqr_gains(car, q_t: float = LQR_WEIGHTS["q_t"], q_d: float = LQR_WEIGHTS["q_d"]) -> np.ndarray:
    """Gains K of the optimal active force F = -K (u1 - u0, v1, u2 - u1, v2) of the linear quarter vehicle ``car``
    ([N/m, N s/m, N/m, N s/m]).

    >>> from erdesign.simulation.vehicle import QuarterCar
    >>> K = lqr_gains(QuarterCar())
    >>> round(float(K[3]))          # the body-velocity gain: a skyhook term of about 19 kN s/m
    -19454
    """
    m1, m2, K, C, k = car.m1, car.m2, car.K, car.C, car.k
    from scipy.linalg import solve_continuous_are

    A = np.array([[0, 1, 0, 0], [-K / m1, -C / m1, k / m1, 0], [0, -1, 0, 1], [0, 0, -k / m2, 0]], dtype=float)
    B = np.array([[0.0], [1 / m1], [0.0], [-1 / m2]])
    c_a, d_a = np.array([[0.0, 0.0, -k / m2, 0.0]]), -1 / m2  # body acceleration = c_a s + d_a F
    Q = c_a.T @ c_a + np.diag([q_d, 0.0, q_t, 0.0])
    N = c_a.T * d_a
    R = np.array([[d_a**2]])
    P = solve_continuous_are(A, B, Q, R, s=N)
    return np.linalg.solve(R, B.T @ P + N.T).ravel()


def _skyhook(car, gain):
    return lambda s: gain * s.v2


def _groundhook(car, gain):
    return lambda s: -gain * s.v1


def _optimal(car, gain):
    K = lqr_gains(car)
    return lambda s: -(K[0] * (s.u1 - s.u0) + K[1] * s.v1 + K[2] * (s.u2 - s.u1) + K[3] * s.v2)


#: ``erdesign vehicle --control`` names -> laws.
CONTROLLERS: dict[str, ControlLaw] = {
    "passive": ControlLaw("passive", None, description="constant control"),
    "skyhook": ControlLaw("skyhook", _skyhook, uses_gain=True, description="F_d = c_sky v2 (Karnopp 1974)"),
    "groundhook": ControlLaw("groundhook", _groundhook, uses_gain=True, description="F_d = -c_gnd v1 (Valasek 1997)"),
    "clipped-optimal": ControlLaw(
        "clipped-optimal",
        _optimal,
        on_off=True,
        description="full control when (F_d - F) F > 0, F_d the LQR force (Dyke 1996)",
    ),
}


def get_controller(name: str) -> ControlLaw:
    try:
        return CONTROLLERS[name]
    except KeyError:
        raise ErdesignError(f"control: expected one of {', '.join(CONTROLLERS)}, got {name!r}") from None
