r"""Inverse models: the control (field, current or voltage) a damper needs to produce a desired force at a motion.

For the models the MR-model review marks invertible the force is affine in the dimensionless control at every sample,
:math:`F = P + Q u` (Kwok, Cheng, magic formula, normalised Bouc-Wen, viscous and asymmetric Dahl, Weng:
:meth:`control_affine`; for Li's viscoelastic-plastic model, the post-yield force), so

.. math:: u = \operatorname{clip}\big((F_d - P)/Q,\ u_{min},\ u_{max}\big);

the modified LuGre model's state depends on the control history, so it is inverted step by step with its state
advanced by the control just chosen.  Any other memoryless model (and the physics damper) is inverted by a
vectorised bracketed root search (:func:`scipy.optimize.elementwise.find_root`).  Forces outside the reachable
range are clipped to it and reported.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Mapping

import numpy as np
from scipy.optimize.elementwise import find_root

from ..data.measurement import Measurement
from ..errors import ErdesignError
from ..models.base import Model
from ..models.friction import LuGreModified, lugre_state

__all__ = ["inverse_control", "InverseResult", "InverseError"]


class InverseError(ErdesignError):
    """The model has no inverse in its control."""


@dataclass
class InverseResult:
    """Control [SI] per sample, the force it produces [N], and where the desired force was out of reach."""

    control: np.ndarray
    force: np.ndarray
    unreachable: np.ndarray
    """True where the desired force lay outside the reachable range and the control was clipped."""

    @property
    def n_clipped(self) -> int:
        return int(np.count_nonzero(self.unreachable))


def inverse_control(
    model: Model,
    record: Measurement,
    force,
    values: Mapping[str, float],
    *,
    control_range=(0.0, 1.0),
    control_kind: str = "current",
) -> InverseResult:
    """Control needed for ``force`` [N] along the motion of ``record``.

    Parameters
    ----------
    model : Model
        A model with a control.
    record : Measurement
        The motion (its control and force columns are ignored).
    force : array
        Desired force, [N], one value per sample.
    values : mapping
        Model parameters (SI).
    control_range : (float, float)
        Reachable control [SI unit of ``control_kind``], e.g. (0, 1) A.
    control_kind : str
        Kind of control of the result.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.models.registry import get_model
    >>> t = np.linspace(0, 1, 201); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> m = get_model("kwok_tanh"); vals = m.check_values({"alpha_u": 800.0})
    >>> r = inverse_control(m, rec, np.full(t.size, 300.0), vals, control_range=(0.0, 2.0))
    >>> r.n_clipped > 0   # 300 N cannot be reached while the damper moves the other way
    True
    """
    if not model.uses_control:
        raise InverseError(f"{model.name}: the force does not depend on the control, so it has no inverse")
    if not (model.invertible or model.name == "physics"):
        raise InverseError(
            f"{model.name}: no inverse (its state depends on the control history in a way that has "
            f"no explicit inverse); the models with one are those `erdesign models --json` marks "
            f"invertible"
        )
    values = model.check_values(values)
    Fd = np.broadcast_to(np.asarray(force, dtype=float), record.time.shape)
    lo, hi = (c / model.control_reference for c in control_range)
    if isinstance(model, LuGreModified):
        u, unreachable = _invert_lugre(model, record, Fd, values, lo, hi)
    elif hasattr(model, "control_affine"):
        P, Q = model.control_affine(record, values)
        if not isinstance(Q, np.ndarray) or Q.dtype == bool:
            return _invert_by_root(model, record, Fd, values, lo, hi, control_kind)
        with np.errstate(divide="ignore", invalid="ignore"):
            u_raw = np.where(Q != 0, (Fd - P) / Q, np.where(Fd >= P, hi, lo))
        u = np.clip(u_raw, lo, hi)
        unreachable = ~np.isclose(u, u_raw, rtol=1e-12, atol=1e-12 * (hi - lo))
    else:  # memoryless (model.invertible) or the physics damper
        return _invert_by_root(model, record, Fd, values, lo, hi, control_kind)
    return _result(model, record, u, unreachable, values, control_kind)


def _result(model, record, u, unreachable, values, kind):
    control = u * model.control_reference
    rec = replace(record, control=control, control_kind=kind)
    return InverseResult(control, model.force(rec, values), unreachable)


def _invert_by_root(model, record, Fd, values, lo, hi, kind):
    def force_at(u):
        rec = replace(
            record, control=np.broadcast_to(u, record.time.shape) * model.control_reference, control_kind=kind
        )
        return model.force(rec, values)

    F_lo, F_hi = force_at(lo), force_at(hi)
    below = (Fd - F_lo) * np.sign(F_hi - F_lo) <= 0
    above = (Fd - F_hi) * np.sign(F_hi - F_lo) >= 0
    inside = ~(below | above)
    u = np.where(below, lo, hi).astype(float)
    if inside.any():
        idx = np.flatnonzero(inside)

        def g(uu, ii):
            # find_root passes only the still-active elements: evaluate the memoryless model on those samples
            ii = np.asarray(ii).astype(int)
            sub = record.select(ii)
            sub = replace(sub, control=np.asarray(uu, float) * model.control_reference, control_kind=kind)
            return model.force(sub, values) - Fd[ii]

        res = find_root(g, (np.full(idx.size, lo), np.full(idx.size, hi)), args=(idx,))
        u[idx] = res.x
    unreachable = ~inside & ~np.isclose(Fd, np.where(below, F_lo, F_hi))
    return _result(model, record, u, unreachable, values, kind)


def _invert_lugre(model, record, Fd, values, lo, hi):
    """Step by step: choose u_n from the state z_n, then advance z with that u_n (exact step)."""
    n = len(record)
    u = np.empty(n)
    unreachable = np.zeros(n, bool)
    z = 0.0
    x = record.displacement
    k0 = values["sigma0"] * values["a0"]
    for i in range(n):
        P, Q = model.control_affine(record.select(slice(i, i + 1)), values, np.array([z]))
        raw = (Fd[i] - P[0]) / Q[0] if Q[0] != 0 else (hi if Fd[i] >= P[0] else lo)
        u[i] = min(max(raw, lo), hi)
        unreachable[i] = u[i] != raw
        if i + 1 < n:
            z = float(lugre_state(x[i : i + 2], max(k0 * (1 + values["a1"] * u[i]), 0.0), z)[-1])
    return u, unreachable
