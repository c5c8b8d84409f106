r"""Compressibility: fluid and accumulator compliance in series with the flow.

The chambers hold a volume :math:`V` of fluid of effective bulk modulus :math:`\beta` (oil, trapped air, hose and
seal compliance).  The pressure force :math:`P = \Delta p\,A_p` is then a state: the piston compresses the fluid
at rate :math:`A_p v` while the ducts pass the flow that the current pressure drives,

.. math:: \dot P = k_h\,\big(v - v_d(P)\big), \qquad k_h = \frac{2\beta A_p^2}{V},

where :math:`v_d(P)` is the piston speed whose quasi-steady pressure force is :math:`P` (two chambers of volume
:math:`V` each, in series).  erdesign linearises the duct about the imposed motion with the plastic damping
constant :math:`C` (the slope of the Bingham force-velocity line), :math:`v_d(P) \approx v + (P - P_{qs}(v))/C`,
which turns the law into a first-order lag of the quasi-steady pressure force,

.. math:: \dot P = \frac{k_h}{C}\,\big(P_{qs}(v) - P\big),

solved exactly between samples (:func:`~erdesign.effects.base.relaxation_filter`).  For a Newtonian fluid (zero
field) the lag is exact (a Maxwell element); with a yield stress it is first order in the compliance, i.e. right
when the lag time :math:`C/k_h` is small against the time the velocity takes to change.
"""

from __future__ import annotations

import numpy as np

from ..models.base import Parameter
from .base import Effect, relaxation_filter

__all__ = ["Compressibility", "hydraulic_stiffness", "compliant_pressure_force", "BULK_MODULUS"]

#: Effective bulk modulus used for the prior, [Pa]: silicone oil is 1-1.5 GPa, less with entrained air.
BULK_MODULUS = 1.0e9


def hydraulic_stiffness(bulk_modulus, Ap, chamber_volume):
    r"""Stiffness of the fluid column seen by the piston, two chambers in series.

    .. math:: k_h = \frac{2\beta A_p^2}{V}

    Parameters
    ----------
    bulk_modulus : float
        Effective bulk modulus beta, [Pa].
    Ap : float
        Piston area, [m^2].
    chamber_volume : float
        Fluid volume of one chamber, V, [m^3].

    Returns
    -------
    float
        k_h, [N/m].

    Examples
    --------
    >>> round(hydraulic_stiffness(1e9, 7.7676e-4, 7.7676e-4 * 0.0334) / 1e6, 2)   # MN/m, Makris chambers
    46.51
    """
    return 2.0 * bulk_modulus * Ap**2 / chamber_volume


def compliant_pressure_force(t, quasi_steady_force, damping, stiffness, initial=None):
    r"""Pressure force of a damper with a compliant fluid column: first-order lag of the quasi-steady force.

    .. math:: \dot P = \frac{k_h}{C(t)}\,\big(P_{qs}(t) - P\big)

    Parameters
    ----------
    t : array
        Time, [s].
    quasi_steady_force : array
        P_qs, the pressure force of the incompressible damper at each sample, [N].
    damping : float or array
        Plastic damping constant C at each sample (field dependent), [N s/m].
    stiffness : float
        Hydraulic stiffness k_h, [N/m].
    initial : float, optional
        P at t[0], [N]; default the quasi-steady value.

    Returns
    -------
    array
        P, [N].

    Notes
    -----
    Exact for a Newtonian fluid; first order in C/k_h otherwise (module notes).  The lag time C/k_h is a few
    milliseconds for Makris's damper (C = 120 kN s/m, k_h of about 50 MN/m).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 1, 1001); P = compliant_pressure_force(t, np.ones(1001), 100.0, 1000.0, initial=0.0)
    >>> bool(abs(P[100] - (1 - np.exp(-1.0))) < 1e-12)      # time constant C/k = 0.1 s
    True

    References
    ----------
    Lumped hydraulic capacitance (Merritt, Hydraulic Control Systems, 1967, ch. 3); the Maxwell model of Makris
    et al. (seed 004, eq 13) is the same law at zero field.
    """
    rate = stiffness / np.asarray(damping, dtype=float)
    return relaxation_filter(t, quasi_steady_force, rate, initial)


class Compressibility(Effect):
    name = "compressibility"
    title = "Compressibility (fluid and accumulator compliance)"
    mechanism = ("The fluid in the chambers is compressed before it flows: a spring k_h = 2 beta A_p^2 / V in series "
                 "with the ducts, so the pressure force lags the motion by C/k_h.")
    signature = ("residual in phase with the displacement at high speed (the loop leans and rounds off at the ends "
                 "of the stroke, force lags velocity), present at zero field too")
    composition = "series"
    neutral = {"hydraulic_stiffness": "upper"}
    source = "Lumped hydraulic capacitance; seed 004 eq 13 (Maxwell) at zero field"

    def parameters(self, damper):
        k = self.prior(damper)["hydraulic_stiffness"]
        return (Parameter("hydraulic_stiffness", "N/m", k, 1e2, 1e12,
                          "stiffness of the fluid column, 2 beta A_p^2 / V", log_scale=True),)

    def prior(self, damper):
        g = damper.geometry
        V = g.piston_area * g.piston_diameter + np.pi * g.duct_mean_diameter * g.gap * g.duct_length * g.ducts
        return {"hydraulic_stiffness": hydraulic_stiffness(BULK_MODULUS, g.piston_area, V)}
