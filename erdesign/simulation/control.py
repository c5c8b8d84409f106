r"""Semi-active control laws of the quarter vehicle: passive, skyhook, groundhook and clipped-optimal.

Each law sees the vehicle at a run of samples (:class:`VehicleState`, arrays) and returns either a desired damper force F_d [N]
(realised by the damper's inverse model, :func:`erdesign.identification.inverse.inverse_control`, which clips the
control to its range: a semi-active damper can only dissipate) or, for the clipped-optimal law, the control
directly.  Sign convention as Butz and von Stryk (2002) eqs 31-32: the damper force F acts on the axle as +F and on
the body as -F, and F = c (v2 - v1) for a dashpot.

* skyhook (Karnopp, Crosby and Harwood 1974): F_d = c_sky v2, a dashpot from the body to the "sky";
* groundhook (Valasek et al. 1997): F_d = -c_gnd v1, a dashpot from the axle to the ground;
* clipped-optimal (Dyke, Spencer, Sain and Carlson 1996): full control when the damper force F of the last step has
  the sign of F_d and is smaller in magnitude, ((F_d - F) F > 0), none otherwise.  Dyke et al. take F_d from an
  H2/LQG design; here the primary controller is the skyhook force (a departure, said in docs/vehicle.md).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..errors import ErdesignError

__all__ = ["VehicleState", "ControlLaw", "CONTROLLERS", "get_controller"]


@dataclass(frozen=True)
class VehicleState:
    """Axle and body velocity v1, v2 [m/s] and the damper force of the step before F [N], one value per sample."""

    v1: np.ndarray
    v2: np.ndarray
    force: np.ndarray


@dataclass(frozen=True)
class ControlLaw:
    """A control law: ``desired(state, gain)`` -> desired damper force [N] (None for passive); ``on_off`` True when
    the law switches the control between its limits itself instead of asking the inverse model for F_d."""

    name: str
    desired: Callable[[VehicleState, float], float] | None
    on_off: bool = False
    description: str = ""


def _skyhook(s: VehicleState, gain: float) -> float:
    return gain * s.v2


def _groundhook(s: VehicleState, gain: float) -> float:
    return -gain * s.v1


#: ``erdesign vehicle --control`` names -> laws.
CONTROLLERS: dict[str, ControlLaw] = {
    "passive": ControlLaw("passive", None, description="constant control"),
    "skyhook": ControlLaw("skyhook", _skyhook, description="F_d = c_sky v2 (Karnopp 1974)"),
    "groundhook": ControlLaw("groundhook", _groundhook, description="F_d = -c_gnd v1 (Valasek 1997)"),
    "clipped-optimal": ControlLaw("clipped-optimal", _skyhook, on_off=True,
                                  description="full control when (F_d - F) F > 0, F_d = c_sky v2 (Dyke 1996)"),
}


def get_controller(name: str) -> ControlLaw:
    try:
        return CONTROLLERS[name]
    except KeyError:
        raise ErdesignError(f"control: expected one of {', '.join(CONTROLLERS)}, got {name!r}") from None
