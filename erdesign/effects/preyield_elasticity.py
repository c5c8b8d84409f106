r"""Pre-yield elasticity: the fluid is an elastic solid below yield (Makris eq 8, shear modulus G).

Makris's elastic-viscoplastic law (Makris et al. 1996, eq 8, :mod:`erdesign.constitutive.makris`) relaxes the stress
towards the Bingham stress at the rate :math:`R = G|\dot\gamma|/(\eta|\dot\gamma| + \tau_y)`.  At the damper
level the wall stress maps to the force by :math:`F = (2 L A_p/h)\,\tau` and the strain to the displacement by
:math:`\gamma = 6 A_p x/(n\pi d h^2)` (the Newtonian wall shear rate), so that the force relaxes towards the
quasi-steady fluid force :math:`F_{qs}(v)`:

.. math::
    \dot F = \frac{k_G |v|}{|F_{qs}(v)|}\,\big(F_{qs}(v) - F\big), \qquad k_G = \frac{12\,G\,L\,A_p^2}{n\pi d h^3}
    = G\,\frac{C}{\eta}.

For the linear Bingham force :math:`F_{qs} = C v + F_y\operatorname{sgn} v` this is Makris eq 8 exactly; erdesign
uses the exact quasi-steady force of the configuration instead (the departure is stated here).  At rest the rate
vanishes and the damper is a spring :math:`k_G`; in steady flow it is the quasi-steady damper.
"""

from __future__ import annotations

import numpy as np

from ..parameters import Parameter
from .base import Effect, geometric_damping, relaxation_filter

__all__ = ["PreyieldElasticity", "elastic_viscoplastic_force", "elastic_stiffness"]

#: Substeps per sample of the elastic-viscoplastic relaxation.
SUBSTEPS = 8


def elastic_stiffness(G, damper) -> float:
    """Damper-level pre-yield stiffness k_G = G C / eta_0 = 12 G L Ap^2 / (n pi d h^3) (valve), [N/m]."""
    return G * geometric_damping(damper)


def elastic_viscoplastic_force(t, v, quasi_steady_force, stiffness, initial=0.0, held_force=None):
    r"""Fluid force of the damper-level Makris law (eq 8 with the exact quasi-steady force as its target).

    .. math:: \dot F = \frac{k_G |v|}{|F_{qs}(v)|}\,(F_{qs}(v) - F)

    Parameters
    ----------
    t : array
        Time, [s].
    v : array
        Piston velocity, [m/s].
    quasi_steady_force : array
        F_qs(v), the quasi-steady fluid force (pressure plus shear drag, no friction), [N].
    stiffness : float
        k_G, [N/m].
    initial : float
        Force at t[0], [N]; default 0 (fluid at rest and unstressed, as Makris).
    held_force : array, optional
        The quasi-steady force at each sample's speed with the control of the sample before, [N]: the end of each
        interval's target when the control is held over the interval (a zero-order hold: a command that steps at
        a sample acts from that sample on).  Default ``quasi_steady_force`` (the target linear between samples).

    Returns
    -------
    array
        [N].

    Notes
    -----
    Solved exactly between samples with the rate held over each step at its mean speed (the update of
    :func:`erdesign.constitutive.makris.makris_stress`, which is the special case of a linear Bingham target).
    Where both the speed and the quasi-steady force vanish the rate is taken as zero (the stress is held).

    Examples
    --------
    Far below yield the damper is a spring: a small ramp x = 1e-6 t against a 100 N yield force:

    >>> import numpy as np
    >>> t = np.linspace(0, 1, 101); v = np.full(101, 1e-6)
    >>> F = elastic_viscoplastic_force(t, v, 100.0 + 0 * t, 1e6)
    >>> round(float(F[-1]), 3)        # k x = 1e6 * 1e-6 = 1 N, less 0.5 % of relaxation towards 100 N
    0.995

    References
    ----------
    Makris et al. (1996), eqs 8-10.
    """
    t = np.asarray(t, dtype=float)
    v = np.asarray(v, dtype=float)
    Fq = np.asarray(quasi_steady_force, dtype=float)
    # On SUBSTEPS substeps per sample (speed and |F_qs| linear between samples, the sign of the target that of the
    # interpolated speed): at a reversal the speed grows from zero within a step and a stiff fluid yields again
    # before the step ends, which a rate held over the whole step (zero at the reversal) would miss by a sample.
    S = SUBSTEPS
    n = v.size
    frac = np.arange(S) / S
    idx = np.repeat(np.arange(n - 1), S)
    w = np.tile(frac, n - 1)
    tf = np.append(t[idx] + w * (t[idx + 1] - t[idx]), t[-1])
    vf = np.append(v[idx] + w * (v[idx + 1] - v[idx]), v[-1])
    af = np.abs(Fq)
    end = af if held_force is None else np.abs(np.asarray(held_force, dtype=float))
    Ff = np.append(af[idx] + w * (end[idx + 1] - af[idx]), af[-1])
    target = np.where(vf != 0, np.sign(vf), np.append(np.sign(Fq[idx]), np.sign(Fq[-1]))) * Ff
    with np.errstate(divide="ignore", invalid="ignore"):
        rate = np.where(Ff > 0, stiffness * np.abs(vf) / Ff, 0.0)
    return relaxation_filter(tf, target, rate, initial)[::S]


class PreyieldElasticity(Effect):
    name = "preyield_elasticity"
    title = "Pre-yield elasticity (Makris eq 8)"
    mechanism = (
        "Below yield the field-structured fluid deforms elastically (shear modulus G) instead of being "
        "rigid: the damper is a spring of stiffness k_G = G C / eta until the fluid yields."
    )
    signature = (
        "residual at the reversals (pre-yield): the measured force changes gradually with displacement "
        "where the model jumps by twice the yield force; grows with the field, absent at zero field"
    )
    stage = "constitutive-in-time"
    continuous_at_reversal = True
    neutral = {"shear_modulus": "upper"}
    # pre-yield moduli of ER / MR fluids scatter over a decade with particle loading and field
    plausible_ratio = {"shear_modulus": (0.1, 10.0)}
    source = "Makris et al. (1996) eq 8"

    def parameters(self, damper):
        G = self.prior(damper).get("shear_modulus", 1e4)
        return (Parameter("shear_modulus", "Pa", G, 1e-2, 1e9, "pre-yield shear modulus of the fluid", log_scale=True),)

    def prior(self, damper):
        G = damper.fluid.shear_modulus
        return {"shear_modulus": G} if G else {}

    def start(self, damper, record):
        # start where the elastic deflection at yield is a tenth of the stroke: visible but not dominant
        Fy = float(np.max(np.abs(damper.yield_force_si(record.control)))) if len(record) else 0.0
        stroke = max(np.ptp(record.displacement), 1e-9)
        G = 10 * Fy / stroke / geometric_damping(damper) if Fy > 0 else 1e4
        p = self.parameters(damper)[0]
        return {"shear_modulus": float(np.clip(G, p.lower, p.upper))}

    def check(self, record, damper):
        if not np.any(np.abs(record.control) > 0):
            return (
                "the record has no field: without a yield stress the fluid has no pre-yield regime "
                "(measure with the field on)"
            )
        return None

    def filter_fluid_force(self, t, v, fluid_force, damper, values, held_force=None):
        # relaxes onto the quasi-steady force from its value at the first sample (settled)
        return elastic_viscoplastic_force(
            t,
            v,
            fluid_force,
            elastic_stiffness(values["shear_modulus"], damper),
            initial=fluid_force[0],
            held_force=held_force,
        )
