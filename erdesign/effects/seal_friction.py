r"""Seal friction: Coulomb-like friction of the rod seals and bearings (Makris eq 14; stiction, Kamath and Wereley
(1997) eq 7).

.. math:: F_f = F_c \tanh\!\left(\frac{v}{v_s}\right)

Makris writes the seal force as :math:`P_y\operatorname{sgn}\dot u` (eq 14, :math:`P_y` = 112 N for his damper);
Kamath and Wereley smooth the sign with a hyperbolic tangent of the velocity (Kamath and Wereley 1997, eq 7,
smoothing factor
:math:`\epsilon_c` chosen a priori).  The physics damper (:mod:`erdesign.effects.chain`) takes instead the expected sign
over the record's own velocity noise (:func:`erdesign.effects.base.sign_expectation`), the same that resolves the
yield jump; :func:`coulomb_friction` is the tanh form of Kamath and Wereley (1997) for a chosen smoothing speed.
"""

from __future__ import annotations

import numpy as np

from ..parameters import Parameter
from .base import Effect, reversal_count

__all__ = ["SealFriction", "coulomb_friction"]


def coulomb_friction(v, friction_force, smoothing_speed):
    r"""Smoothed Coulomb friction force of seals and bearings.

    .. math:: F_f = F_c \tanh(v / v_s)

    Parameters
    ----------
    v : float or array
        Piston velocity, [m/s].
    friction_force : float or array
        Coulomb (sliding) friction F_c, [N], >= 0.
    smoothing_speed : float
        v_s > 0, [m/s]; the sign of v is resolved for |v| >> v_s (0 gives the sharp sign of Makris eq 14).

    Returns
    -------
    float or array
        Friction force with the sign of v, [N].

    Notes
    -----
    Rate independent above a few v_s.  Kamath and Wereley (1997) eq 7 prints the shape function as
    :math:`\tfrac12\tanh(\dot X/4\epsilon_c)`, whose half makes :math:`F_c` the peak-to-peak rather than the
    amplitude of the friction; here :math:`F_c` is the amplitude, as :math:`P_y` in Makris eq 14.

    Examples
    --------
    >>> round(float(coulomb_friction(0.1, 112.0, 0.001)), 6)
    112.0

    References
    ----------
    Makris et al. (1996), eq 14; Kamath and Wereley (1997), eq 7.
    """
    if smoothing_speed <= 0:
        return friction_force * np.sign(v)
    return friction_force * np.tanh(np.asarray(v, dtype=float) / smoothing_speed)


class SealFriction(Effect):
    name = "seal_friction"
    title = "Seal friction"
    mechanism = (
        "Coulomb friction of the rod seals and bearings: a force of constant size opposing the motion, "
        "independent of the field and of the speed."
    )
    signature = (
        "residual odd in velocity and flat in magnitude (a step at each reversal), the same at every "
        "field: Coulomb-like"
    )
    stage = "additive"
    neutral = {"friction_force": "lower"}
    # the file's value is the seals alone, new; bearings, rig fixtures and worn or dry seals add several times it
    plausible_ratio = {"friction_force": (0.1, 20.0)}
    source = "Makris et al. (1996) eq 14; Kamath and Wereley (1997) eq 7"

    def parameters(self, damper):
        prior = self.prior(damper).get(
            "friction_force", 0.02 * max(damper.yield_force_si(damper.fluid.reference_field), 1.0)
        )
        return (
            Parameter("friction_force", "N", float(prior), 0.0, 1e6, "Coulomb friction of seals and bearings, F_c"),
        )

    def prior(self, damper):
        # the damper file's seal_friction (Makris: 112 N) is the only prior there is
        return {"friction_force": damper.seal_friction} if damper.seal_friction > 0 else {}

    def check(self, record, damper):
        if reversal_count(record.velocity) < 2:
            return "the piston reverses fewer than twice, so a force that flips with the motion cannot be seen"
        u = np.abs(record.control)
        if damper.fluid.yield_stress > 0 and u.min() > 0 and np.ptp(u) < 0.1 * u.max():
            return (
                "the field is on and the same throughout, so a friction that flips with the motion cannot be "
                "told from the yield stress (measure at two fields, e.g. zero and on)"
            )
        return None

    def additive_forces(self, record, sign, damper, values):
        # fitted, it replaces the damper file's seal friction (the baseline's "friction" component)
        return {"friction": values["friction_force"] * sign}
