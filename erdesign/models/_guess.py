"""The scales of a record that the models' starting guesses are read from, written once for every model.

A model's guess (:meth:`erdesign.models.base.Model.guess_from_force`) starts from the least-squares fit of the
simplest damper law, :math:`F \\approx f_y\\operatorname{sgn}\\dot x + c\\dot x + f_0`, and from the record's stroke
and peak speed; each model maps these to its own parameters.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

__all__ = ["ForceScales", "force_scales", "peak_speed", "sign_viscous_fit", "stroke", "viscous_slope"]


def sign_viscous_fit(record) -> tuple[float, float, float]:
    """(f_y [N], c [N s/m], f_0 [N]): the least-squares fit F = f_y sgn v + c v + f_0 of the record, unclamped."""
    v = record.velocity
    A = np.column_stack([np.sign(v), v, np.ones_like(v)])
    (fy, c, f0), *_ = np.linalg.lstsq(A, record.force, rcond=None)
    return float(fy), float(c), float(f0)


def viscous_slope(record) -> float:
    """c [N s/m] of the least-squares fit F - mean F = c v of the record (the force's viscous part)."""
    v = record.velocity
    return float(np.dot(v, record.force - record.force.mean()) / max(np.dot(v, v), 1e-300))


def stroke(record) -> float:
    """Largest excursion of the displacement from its mean [m] (1 for a record that does not move)."""
    x = record.displacement
    return float(np.max(np.abs(x - np.mean(x)))) or 1.0


def peak_speed(record) -> float:
    """Largest speed of the record [m/s] (1 for a record that does not move)."""
    return float(np.max(np.abs(record.velocity))) or 1.0


class ForceScales(NamedTuple):
    """The scales most guesses use: the fit's friction (at least 1 N) and damping (not negative), its offset, the
    stroke and the peak speed."""

    friction: float
    """f_y of :func:`sign_viscous_fit`, at least 1 N [N]."""
    damping: float
    """c of :func:`sign_viscous_fit`, not negative (or at least the ``min_damping`` asked for) [N s/m]."""
    offset: float
    """f_0 of :func:`sign_viscous_fit` [N]."""
    stroke: float
    """:func:`stroke` [m]."""
    speed: float
    """:func:`peak_speed` [m/s]."""


def force_scales(record, min_damping: float = 0.0) -> ForceScales:
    """The :class:`ForceScales` of a record with a force; the damping at least ``min_damping`` [N s/m]."""
    fy, c, f0 = sign_viscous_fit(record)
    return ForceScales(max(fy, 1.0), max(c, min_damping), f0, stroke(record), peak_speed(record))
