r"""The passive / semi-active split of Vivas-López et al. (n.d.) eq 1, :math:`F_{SA}(V) = F_D(V) - F_P`, and the
dictionaries of candidate features the characteristics are read from.

The passive force :math:`F_P` is what the damper gives at its lowest control (the paper's smallest PWM duty
cycle): a linear least-squares fit, on the samples at that control, over a dictionary of features of the motion
(:func:`passive_features`: an offset, viscous, stiffness, friction, hysteresis, inertia and asymmetry groups, each
the columns a term of the paper's Table 2 can produce), evaluated at every sample.  The semi-active force is the
rest (eq 1); its own dictionary (:func:`semiactive_features`) holds the force gain of the control, the pre-yield
zone and the rise of the force with the speed.  Each group is a set of fixed columns (saturations :math:`S(s) = s/(1+|s|)` at a few speed scales, as eqs 5a-5e
use), so every fit is one linear solve and a characteristic is judged by what its group adds (drop-one, in the
spirit of sparse regression over a library of candidate terms).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..models.semiactive import sigmoid_ratio as S

__all__ = [
    "PASSIVE_GROUPS",
    "SEMIACTIVE_GROUPS",
    "LinearFit",
    "Samples",
    "fit_groups",
    "passive_features",
    "robust_peak",
    "semiactive_features",
]

#: Speed scales of the saturating columns, as fractions of the record's peak speed: friction is a step at v = 0
#: smoothed over a few percent of the peak speed at most (a wider saturation would stand in for viscous damping).
SPEED_SCALES = (0.01, 0.03)
#: Speed scales of the wide saturations of the semi-active force (fractions of the peak speed): a force that rises
#: across the whole FV diagram, as the pressure drop of a plastic valve does while its plug thins (Buckingham-Reiner:
#: from 2 to 3 tau_y L / h; at low flow the rise goes as the square root of the flow rate).
WIDE_SPEED_SCALES = (0.1, 0.3, 1.0)


@dataclass(frozen=True)
class Samples:
    """The pooled samples of the records (SI): displacement z [m], velocity v [m/s], acceleration a [m/s^2],
    control u (SI), force F [N], the record index of each sample, and the passive control level ``u_passive`` (the
    lowest control; None when no record has a control column) and the control span."""

    z: np.ndarray
    v: np.ndarray
    a: np.ndarray
    u: np.ndarray
    F: np.ndarray
    record: np.ndarray
    u_passive: float | None
    u_span: float
    band: float = 0.02
    """Samples within this fraction of the control span above the passive level count as passive."""

    @classmethod
    def pool(cls, records, *, passive_band: float = 0.02) -> Samples:
        """Pool ``records``; the passive level is the lowest control, and samples within ``passive_band`` of the
        control span above it count as passive."""

        def cat(name):
            return np.concatenate([np.asarray(getattr(r, name), dtype=float) for r in records])

        u = cat("control")
        controlled = any(r.control_kind is not None for r in records)
        lo, hi = (float(u.min()), float(u.max())) if controlled else (None, 0.0)
        span = (hi - lo) if controlled else 0.0
        return cls(
            cat("displacement"),
            cat("velocity"),
            cat("acceleration"),
            u,
            np.concatenate([r.require_force() for r in records]),
            np.concatenate([np.full(len(r), k) for k, r in enumerate(records)]),
            lo,
            span if span > 0 else 0.0,
            passive_band,
        )

    @property
    def passive(self) -> np.ndarray:
        """Mask of the samples at the passive control (all samples when the control never varies)."""
        if self.u_passive is None or self.u_span == 0:
            return np.ones(self.v.size, dtype=bool)
        return self.u <= self.u_passive + self.band * self.u_span

    @property
    def du(self) -> np.ndarray:
        """Control above the passive level over the control span, [-] (0 to 1)."""
        return self.gain_shape(1.0)

    def gain_shape(self, exponent: float) -> np.ndarray:
        """The force gain of the control over its value at the highest control, [-] (0 to 1), when the gain grows
        as the control to the power ``exponent``: (u^n - u_p^n) / (u_max^n - u_p^n), u_p the passive level; with
        n = 1 it is :attr:`du`.  Zeros when the control never varies."""
        if self.u_passive is None or self.u_span == 0:
            return np.zeros(self.v.size)
        if exponent == 1.0:
            return (self.u - self.u_passive) / self.u_span
        lo, hi = self.u_passive**exponent, (self.u_passive + self.u_span) ** exponent
        return (np.clip(self.u, 0.0, None) ** exponent - lo) / (hi - lo)

    def select(self, mask) -> Samples:
        return Samples(
            self.z[mask],
            self.v[mask],
            self.a[mask],
            self.u[mask],
            self.F[mask],
            self.record[mask],
            self.u_passive,
            self.u_span,
            self.band,
        )


def robust_peak(values: np.ndarray) -> float:
    """A robust peak of |values| (99.5th percentile), never zero."""
    return float(np.percentile(np.abs(values), 99.5)) or 1.0


def passive_features(s: Samples, V: float, Z: float) -> dict[str, np.ndarray]:
    r"""Columns (n x k) of each passive group at the samples ``s``; ``V`` [m/s] and ``Z`` [m] are the peak speed and
    stroke the saturations are scaled by.

    ================  ===========================================================================  ==============
    group             columns                                                                      Table 2 term
    ================  ===========================================================================  ==============
    ``offset``        1                                                                            f_0
    ``viscous``       v                                                                            c_p v
    ``stiffness``     z                                                                            k_p z
    ``friction``      S(v / (s V)), s in :data:`SPEED_SCALES`                                      f_fr (eq 5a)
    ``hysteresis``    S(v / (s V) + sgn z) - S(v / (s V)), s in 0.01, 0.03, 0.1: the force at      f_h,z (eq 5b)
                      small speed depends on the side of the stroke (a transition that lags
                      the reversal), vanishing at high speed (not friction)
    ``inertia``       a, a |v| / V                                                                 m_D, f_h,v
    ``asymmetry``     |v|, |S(v / (s V))|: the even part of the viscous and friction columns       _pos / _neg
                      (a coefficient that differs for v < 0 adds its even part; the odd part
                      is the term itself)
    ================  ===========================================================================  ==============
    """
    z, v, a = s.z, s.v, s.a
    one = np.ones_like(v)
    sat = np.column_stack([S(v / (k * V)) for k in SPEED_SCALES])
    return {
        "offset": one[:, None],
        "viscous": v[:, None],
        "stiffness": z[:, None] / Z * V,  # scaled to the size of the viscous column (conditioning only)
        "friction": sat,
        "hysteresis": _branch(v, z, V),
        "inertia": np.column_stack([a, a * np.abs(v) / V]),
        "asymmetry": np.abs(np.column_stack([v, sat])),
    }


def _branch(v, z, V):
    """The hysteresis columns: S(v / (s V) + sgn z) - S(v / (s V)) (eq 5b less its saturated part)."""
    sz = np.sign(z)
    return np.column_stack([S(v / (k * V) + sz) - S(v / (k * V)) for k in (0.01, 0.03, 0.1)])


def semiactive_features(s: Samples, V: float, Z: float, exponent: float = 1.0) -> dict[str, np.ndarray]:
    r"""Columns of each semi-active group (eq 4 without its coefficients), with w the force gain of the control
    (:meth:`Samples.gain_shape`: the control above the passive level over the control span, to the power
    ``exponent`` when the FM diagram is not linear):

    ================  ===========================================================================  ==============
    group             columns                                                                      Table 2 term
    ================  ===========================================================================  ==============
    ``gain``          w sgn v: the force the control adds, independent of the speed                c_SA
    ``preyield``      w S(v / (s V)), s in :data:`SPEED_SCALES`, and w S(z / (0.3 Z)): a force     eqs 5d, 5e
                      that grows with the speed or the stroke and saturates within a few
                      percent of the peak speed (a steep pre-yield zone)
    ``speed``         w S(v / (s V)), s in :data:`WIDE_SPEED_SCALES`: a force that keeps growing   eq 5d, wide
                      with the speed across the diagram (the post-yield force is not independent
                      of the speed)
    ``asymmetry_sa``  w, w \|S(v / (0.1 V))\|: the gain and pre-yield force differ in extension     c_SA _pos/_neg
                      and compression (a part even in v)
    ``hysteresis_sa`` w times the hysteresis columns of :func:`passive_features`                    f_h,z
    ================  ===========================================================================  ==============
    """
    w, v, z = s.gain_shape(exponent), s.v, s.z
    return {
        "gain": (w * np.sign(v))[:, None],
        "preyield": np.column_stack([w * S(v / (k * V)) for k in SPEED_SCALES] + [w * S(z / (0.3 * Z))]),
        "speed": np.column_stack([w * S(v / (k * V)) for k in WIDE_SPEED_SCALES]),
        "asymmetry_sa": np.column_stack([w, w * np.abs(S(v / (0.1 * V)))]),
        "hysteresis_sa": w[:, None] * _branch(v, z, V),
    }


#: The groups in the order they are listed.
PASSIVE_GROUPS = ("offset", "viscous", "stiffness", "friction", "hysteresis", "inertia", "asymmetry")
SEMIACTIVE_GROUPS = ("gain", "preyield", "speed", "asymmetry_sa", "hysteresis_sa")


@dataclass(frozen=True)
class LinearFit:
    """Least-squares coefficients of the chosen groups, the residual sum of squares [N^2] and the prediction [N]."""

    groups: tuple[str, ...]
    coefficients: Mapping[str, np.ndarray]
    rss: float
    prediction: np.ndarray

    def esr(self, F_D) -> float:
        """The residual over the variation of the damper force ``F_D`` (eq 7); ``F_D`` is the fitted force itself for
        the passive fit and the whole force (passive + semi-active) for a fit of the semi-active part."""
        F_D = np.asarray(F_D, dtype=float)
        return float(self.rss / np.sum((F_D - F_D.mean()) ** 2))


def fit_groups(columns: Mapping[str, np.ndarray], F: np.ndarray, groups) -> LinearFit:
    """Fit ``F`` [N] on the columns of ``groups`` (linear least squares, columns scaled to unit RMS for
    conditioning)."""
    groups = tuple(g for g in groups if g in columns)
    if not groups:
        return LinearFit((), {}, float(np.sum(F**2)), np.zeros_like(F))
    A = np.column_stack([columns[g] for g in groups])
    scale = np.sqrt(np.mean(A**2, axis=0))
    scale[scale == 0] = 1.0
    theta, *_ = np.linalg.lstsq(A / scale, F, rcond=None)
    theta = theta / scale
    pred = A @ theta
    sizes = np.cumsum([0] + [columns[g].shape[1] for g in groups])
    coeffs = {g: theta[sizes[k] : sizes[k + 1]] for k, g in enumerate(groups)}
    return LinearFit(groups, coeffs, float(np.sum((F - pred) ** 2)), pred)
