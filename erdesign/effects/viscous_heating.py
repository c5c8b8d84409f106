r"""Viscous heating: the viscosity falls as the fluid warms from the energy it dissipates.

A lumped thermal mass :math:`C_\theta` (fluid and cylinder) heats with the dissipated power :math:`P = F v` and
cools to the surroundings with a time constant :math:`\tau_\theta`; the plastic viscosity falls exponentially with
the temperature rise (Andrade / Reynolds law with coefficient :math:`\alpha`):

.. math::
    \dot{\Delta T} = \frac{P}{C_\theta} - \frac{\Delta T}{\tau_\theta}, \qquad \eta = \eta_0\,e^{-\alpha\,\Delta T}.

The rise is a first-order relaxation solved exactly between samples; the coupling (power depends on viscosity)
is resolved by fixed-point passes over the whole record (:mod:`erdesign.effects.chain`), whose error falls by the factor
:math:`\alpha\Delta T` per pass.  Makris et al. report scatter of their measurements caused by heating of the
fluid over a test.
"""

from __future__ import annotations

import numpy as np

from ..parameters import Parameter
from .base import Effect, relaxation_filter, reversal_count

__all__ = ["ViscousHeating", "temperature_rise", "heated_viscosity_factor", "TEMPERATURE_COEFFICIENT", "SPECIFIC_HEAT"]

#: alpha: fractional fall of viscosity per kelvin, [1/K] (silicone oils: 0.015-0.03 /K).
TEMPERATURE_COEFFICIENT = 0.02
#: Specific heat of the fluid for the prior, [J/(kg K)] (silicone oil about 1500).
SPECIFIC_HEAT = 1500.0


def temperature_rise(t, power, thermal_mass, cooling_time):
    r"""Temperature rise of a lumped thermal mass heated by ``power`` and cooled with a time constant.

    .. math:: \dot{\Delta T} = P/C_\theta - \Delta T/\tau_\theta, \qquad \Delta T(t_0) = 0

    Parameters
    ----------
    t : array
        Time, [s].
    power : array
        Dissipated power, [W].
    thermal_mass : float
        C_theta, [J/K].
    cooling_time : float
        tau_theta, [s].

    Returns
    -------
    array
        Delta T, [K].

    Examples
    --------
    10 W into 100 J/K for 1 s with slow cooling: 0.1 K.

    >>> import numpy as np
    >>> t = np.linspace(0, 1, 101)
    >>> round(float(temperature_rise(t, np.full(101, 10.0), 100.0, 1e9)[-1]), 6)
    0.1
    """
    target = np.asarray(power, dtype=float) * cooling_time / thermal_mass
    return relaxation_filter(t, target, 1.0 / cooling_time, 0.0)


def heated_viscosity_factor(temperature_rise, coefficient=TEMPERATURE_COEFFICIENT):
    r"""Viscosity over its initial value after a temperature rise, :math:`e^{-\alpha\Delta T}`, [-].

    >>> round(heated_viscosity_factor(10.0, 0.02), 4)
    0.8187
    """
    return (
        np.exp(-coefficient * np.asarray(temperature_rise, dtype=float))
        if np.ndim(temperature_rise)
        else float(np.exp(-coefficient * temperature_rise))
    )


class ViscousHeating(Effect):
    name = "viscous_heating"
    title = "Viscous heating"
    mechanism = (
        "The damper turns work into heat; the fluid warms and its viscosity falls (about 2 % per kelvin), "
        "so the force drifts down over the test."
    )
    signature = (
        "residual that grows late in the test: the measured force falls below the model more and more, "
        "most at high speed where the viscous force dominates"
    )
    stage = "thermal"
    neutral = {"thermal_mass": "upper", "cooling_time": 600.0}
    # how much of the cylinder warms with the fluid is not known: a wide window; the cooling time has no prior
    plausible_ratio = {"thermal_mass": (0.05, 20.0), "cooling_time": None}
    source = "Lumped thermal model; Makris et al. (1996) report scatter from heating"

    def parameters(self, damper):
        prior = self.prior(damper)
        return (
            Parameter(
                "thermal_mass",
                "J/K",
                prior["thermal_mass"],
                1e-2,
                1e7,
                "heat capacity of the fluid and cylinder that warm",
                log_scale=True,
            ),
            Parameter(
                "cooling_time",
                "s",
                prior["cooling_time"],
                1.0,
                1e6,
                "time constant of cooling to the surroundings",
                log_scale=True,
            ),
        )

    def prior(self, damper):
        g = damper.geometry
        V = 2 * g.piston_area * g.piston_diameter + np.pi * g.duct_mean_diameter * g.gap * g.duct_length * g.ducts
        return {"thermal_mass": damper.fluid.density * SPECIFIC_HEAT * V, "cooling_time": 600.0}

    def check(self, record, damper):
        if reversal_count(record.velocity) < 6:
            return (
                "the record has fewer than three cycles, so early and late cycles cannot be compared to tell "
                "heating from a lower viscosity"
            )
        return None

    def viscosity_factor(self, t, power, values):
        dT = temperature_rise(t, power, values["thermal_mass"], values["cooling_time"])
        return heated_viscosity_factor(dT, TEMPERATURE_COEFFICIENT)
