r"""Field lag: the yield stress follows a change of field with a first-order time constant (Butz and von Stryk 2002,
eq 16).

Butz and von Stryk (2002, eq 16) pass the command through :math:`\dot u = -\eta_f (u - v_c)` "to allow for the
fluid's dynamics of reaching rheological equilibrium".  erdesign filters the control the same way,

.. math:: \dot E_f = \frac{E - E_f}{T_f},

and evaluates the yield stress and plastic viscosity at :math:`E_f`.  The filter is solved exactly between samples
(the control linear between samples, :func:`~erdesign.effects.base.relaxation_filter`) and starts settled
(:math:`E_f = E` at the first sample).

Prior.  For an MR damper with a ``[coil]`` the current itself lags the command: the coil is an RL circuit, so
the prior of :math:`T_f` is the time the coil current takes to reach 63 % of the rated current after a step,
:math:`L/R` with the secant inductance of the magnetic circuit at the rated current, or, when the coil's
``supply_voltage`` is given (a current driver forcing the coil with its supply),
:math:`-(L/R)\ln(1 - 0.632\,I R/V_s)` (:func:`erdesign.magnetics.coil.current_rise_time`).  Eddy currents in a
solid-steel head and the fluid's own response (about a millisecond) add to it, so fitted values up to 10 times
the prior count as plausible.  Without a coil there is no prior (the default start is 5 ms).
"""

from __future__ import annotations

import numpy as np

from ..parameters import Parameter
from .base import Effect, relaxation_filter

__all__ = ["FieldLag", "lagged_control"]


def lagged_control(t, control, time_constant):
    r"""Control seen by the fluid: the applied control through a first-order lag.

    .. math:: \dot E_f = (E - E_f)/T_f, \qquad E_f(t_0) = E(t_0)

    Parameters
    ----------
    t : array
        Time, [s].
    control : array
        Applied field, current or voltage E, SI unit of its kind.
    time_constant : float
        T_f > 0, [s].

    Returns
    -------
    array
        E_f, same unit as ``control``.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 0.05, 501); E = np.where(t > 0.01, 3e6, 0.0)
    >>> Ef = lagged_control(t, E, 0.005)
    >>> round(float(Ef[np.searchsorted(t, 0.015)] / 3e6), 2)    # one time constant after the step
    0.63

    References
    ----------
    Butz and von Stryk (2002), eq 16.
    """
    return relaxation_filter(t, control, 1.0 / time_constant)


class FieldLag(Effect):
    name = "field_lag"
    title = "Field lag"
    mechanism = (
        "The particle chains that carry the yield stress take time to form and break (and a coil's "
        "current takes time to rise): the yield stress follows a field change with a time constant T_f."
    )
    signature = (
        "residual right after each change of the field, decaying over a few milliseconds: the model "
        "switches the force at once, the measurement follows late"
    )
    stage = "state"
    neutral = {"field_time_constant": "lower"}
    source = "Butz and von Stryk (2002) eq 16"

    plausible_ratio = {"field_time_constant": (0.2, 10.0)}

    def prior(self, damper):
        law = damper.fluid.field_law
        if law is None or not hasattr(law, "response_time"):  # a CoilLaw: the control is the coil current
            return {}
        return {"field_time_constant": float(law.response_time())}

    def parameters(self, damper):
        start = self.prior(damper).get("field_time_constant", 0.005)
        return (
            Parameter(
                "field_time_constant", "s", start, 1e-5, 10.0, "time constant of the field response", log_scale=True
            ),
        )

    def check(self, record, damper):
        u = np.abs(record.control)
        if u.max() == 0 or np.ptp(u) < 0.1 * u.max():
            return "the field never changes in this record, so a lag in following it cannot be seen"
        dt = np.median(np.diff(record.time))
        if dt > 0.01:
            return f"the record is sampled every {dt * 1e3:.3g} ms, too coarsely to resolve a field response"
        return None

    def fluid_control(self, t, control, values):
        return lagged_control(t, control, values["field_time_constant"])
