r"""Leakage: a laminar bypass (piston-head clearance, worn seal) in parallel with the ducts.

The displaced flow splits between the ducts and a bypass of damping constant :math:`C_l` (the force the bypass
alone would give per unit piston speed, Newtonian: no field acts on it):

.. math:: A_p v = Q_\text{gap}(\Delta p) + \frac{A_p\,\Delta p\,A_p}{C_l}
          \quad\Longleftrightarrow\quad \Delta p = \Delta p_\text{gap}\!\left(v - \frac{\Delta p A_p}{C_l}\right),

solved for :math:`\Delta p` per sample with a vectorised bracketed root (:func:`leaky_pressure_drop`).  Below the
yield pressure the ducts are blocked and the piston creeps through the bypass at :math:`v = \Delta p A_p/C_l`:
the force no longer jumps at a reversal but rises with the creep speed.
"""

from __future__ import annotations

import numpy as np

from ..numerics import find_root
from ..parameters import Parameter
from .base import Effect

__all__ = ["Leakage", "leaky_pressure_drop"]


def leaky_pressure_drop(v, Ap, bypass_damping, gap_pressure_drop, args=(), quasi_steady_drop=None):
    r"""Pressure drop of a damper whose flow splits between the ducts and a laminar bypass.

    .. math:: \Delta p = \Delta p_\text{gap}\big(v - \Delta p\,A_p / C_l\big)

    Parameters
    ----------
    v : array
        Piston velocity, [m/s].
    Ap : float
        Piston area, [m^2].
    bypass_damping : float
        C_l, damping constant of the bypass alone, [N s/m].
    gap_pressure_drop : callable
        ``gap_pressure_drop(u, *args)``: pressure drop [Pa] of the ducts when they pass the flow of a piston moving
        at ``u`` [m/s], increasing in u, with the break-away value at u = 0; elementwise in ``u`` and ``args``
        (the root finder calls it with the unconverged elements only).
    args : tuple of arrays
        Per-sample arguments of ``gap_pressure_drop`` (yield stress, viscosity, wall speed ...), the shape of v.
    quasi_steady_drop : array, optional
        ``gap_pressure_drop(v)`` if already known (the no-leak value, one end of the bracket).

    A ``gap_pressure_drop`` with a method ``with_bypass(v, k, args, dp0, xatol, xrtol)`` (k = A_p / C_l) that
    returns the root (or None) is solved by it: the gap laws of the physics damper do so in compiled code
    (:class:`erdesign.effects.chain._GapDrop`), with the same iteration and tolerances per element.

    Returns
    -------
    array
        Pressure drop, [Pa], with the sign of v.

    Notes
    -----
    The residual :math:`\Delta p - \Delta p_\text{gap}(v - \Delta p A_p/C_l)` increases with :math:`\Delta p`, is
    of the sign opposite to v at 0 and of the sign of v at the no-leak value, so that bracket always holds the
    root (Chandrupatla's method, :func:`erdesign.numerics.find_root`: scipy's, without its framework).  Below
    yield the root sits on the break-away jump of the gap law, where the duct flow is zero: there it converges to
    the creep solution :math:`\Delta p = C_l v / A_p`.

    Examples
    --------
    A duct blocked below 1 MPa, viscous above (damping 1e9 Pa s/m x Ap = 1 MN s/m), and a bypass of the same
    damping: at 0.1 mm/s the piston creeps through the bypass; at 0.1 m/s the two share the flow.

    >>> import numpy as np
    >>> Ap = 1e-3
    >>> gap = lambda u: np.copysign(1e6, u) + 1e9 * u          # yield 1 MPa, then viscous
    >>> dp = leaky_pressure_drop(np.array([1e-4, 0.1]), Ap, 1e6, gap)
    >>> np.round(dp / 1e6, 4).tolist()    # MPa: creep C_l v / Ap = 0.1; fast (1 + 100)/2 = 50.5
    [0.1, 50.5]
    """
    v = np.asarray(v, dtype=float)
    args = tuple(np.broadcast_to(np.asarray(a, dtype=float), v.shape) for a in args)
    dp0 = gap_pressure_drop(v, *args) if quasi_steady_drop is None else np.asarray(quasi_steady_drop, dtype=float)
    lo = np.minimum(0.0, dp0)
    hi = np.maximum(0.0, dp0)
    k = Ap / bypass_damping

    def residual(dp, v, *args):
        return dp - gap_pressure_drop(v - dp * k, *args)

    scale = float(np.max(np.abs(dp0))) + 1.0 if dp0.size else 1.0
    compiled = getattr(gap_pressure_drop, "with_bypass", None)
    if compiled is not None:
        dp = compiled(v, k, args, dp0, 1e-10 * scale, 1e-12)
        if dp is not None:
            return dp
    same = hi == lo
    res = find_root(
        residual,
        np.where(same, lo - 1.0, lo),
        np.where(same, hi + 1.0, hi),
        args=(v, *args),
        xatol=1e-10 * scale,
        xrtol=1e-12,
        maxiter=200,
    )
    return np.where(same, dp0, res)


class Leakage(Effect):
    name = "leakage"
    title = "Leakage (laminar bypass)"
    mechanism = (
        "Part of the flow bypasses the ducts through a laminar clearance (piston head, worn seal) that "
        "no field controls: below yield the piston creeps through the bypass instead of stopping."
    )
    signature = (
        "residual at low speed with the field on: the measured force near a reversal is smaller than "
        "the yield force and grows with speed (creep below yield); the loss of force is largest where "
        "the model is blocked"
    )
    stage = "parallel"
    continuous_at_reversal = True
    neutral = {"bypass_damping": "upper"}
    source = "Laminar bypass in parallel with the ducts (erdesign); Makris eq 4 for its damping constant"

    def parameters(self, damper):
        C = damper.damping_constant_si()
        return (
            Parameter(
                "bypass_damping",
                "N*s/m",
                10.0 * C,
                1e-3 * C,
                1e6 * C,
                "damping constant of the bypass alone",
                log_scale=True,
            ),
        )

    def check(self, record, damper):
        if not np.any(np.abs(record.control) > 0):
            return (
                "the record has no field: without a yield stress a bypass only lowers the damping, which the "
                "viscosity factor already does"
            )
        return None

    def split_flow(self, v, gap_pressure_drop, args, quasi_steady_drop, damper, values):
        Ap, C_l = damper.geometry.piston_area, values["bypass_damping"]
        dp = leaky_pressure_drop(v, Ap, C_l, gap_pressure_drop, args=args, quasi_steady_drop=quasi_steady_drop)
        u = v - dp * Ap / C_l
        # creeping (the root on the break-away jump, dp = C_l v / Ap): the duct flow is zero up to rounding, whose
        # sign would pick the side of the jump for what is read at it (a moving head's shear drag); take the side
        # of the piston's motion, the limit of the flowing branch
        creep = np.abs(u) <= 1e-9 * np.abs(v)
        return dp, np.where(creep, np.copysign(0.0, v), u)

    def bypass_conductance(self, values):
        return 1.0 / values["bypass_damping"]
