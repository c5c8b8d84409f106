r"""Shear thinning: the post-yield stress grows slower than linearly with shear rate (Herschel-Bulkley).

.. math:: \tau = \tau_y + K\,\dot\gamma^{m}\quad(|\tau| > \tau_y), \qquad K = \eta\,\dot\gamma_\text{ref}^{\,1-m}

The consistency K is tied to the plastic viscosity so that the Herschel-Bulkley and Bingham curves meet at the
reference shear rate :math:`\dot\gamma_\text{ref}` = 1000 1/s (mid-range of damper gaps); ``m = 1`` is Bingham.

Valve ducts: the thin-gap Herschel-Bulkley flow of :mod:`erdesign.flow.herschel_bulkley` (explicit in the
pressure drop, a vectorised root for a given flow).  Mixed (moving-electrode) gaps: erdesign uses the
Bingham Couette-Poiseuille solution with the apparent viscosity :math:`K\dot\gamma_a^{m-1}` at the apparent shear
rate :math:`\dot\gamma_a = 6|Q|/(\pi d h^2) + |v|/h` (an approximation, stated here).
"""

from __future__ import annotations

import numpy as np

from ..flow.herschel_bulkley import herschel_bulkley_pressure_drop, herschel_bulkley_slit_flow_rate
from ..parameters import Parameter
from .base import Effect, peak_speed

__all__ = ["ShearThinning", "herschel_bulkley_slit_flow_rate", "herschel_bulkley_pressure_drop", "REFERENCE_SHEAR_RATE"]

#: Shear rate at which the Herschel-Bulkley consistency matches the plastic viscosity, [1/s].
REFERENCE_SHEAR_RATE = 1000.0


class ShearThinning(Effect):
    name = "shear_thinning"
    title = "Shear thinning (Herschel-Bulkley)"
    mechanism = (
        "After yield the stress grows slower than linearly with the shear rate (flow index m < 1): the "
        "damper is stiffer than Bingham at low speed and softer at high speed."
    )
    signature = (
        "residual even-odd pattern in speed: the model is too low at moderate post-yield speeds and too "
        "high at the highest speeds (the force-velocity curve bends over)"
    )
    stage = "constitutive"
    neutral = {"flow_index": 1.0}
    source = "Herschel-Bulkley law; the MR-model review (c0 falling with speed: shear thinning)"

    def parameters(self, damper):
        return (Parameter("flow_index", "", 1.0, 0.2, 1.5, "Herschel-Bulkley flow index m (1: Bingham)"),)

    def start(self, damper, record):
        return {"flow_index": 0.8}

    def check(self, record, damper):
        v = np.abs(record.velocity)
        if peak_speed(record) == 0 or np.percentile(v, 90) < 2 * np.percentile(v, 30):
            return "the speeds of the record span less than a factor of 2, too narrow to see the curve bend"
        return None

    def gap_law(self, law, values):
        return law._replace(flow_index=values["flow_index"], reference_shear_rate=REFERENCE_SHEAR_RATE)
