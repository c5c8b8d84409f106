r"""The noise floor of a diagnosis: one number per record(s), fixed across rounds, on the judged samples.

Stage 2 of diagnosis (docs/diagnosis.md).  The load cell's noise :math:`\sigma_{F,r}` of each record :math:`r` is
estimated once from the full record, where no data finding excludes samples (or given by the user), by
:func:`erdesign.data.noise_floor.estimate_noise_floor`, which also says how (``noise_floor_method``).  What the
motion channel adds - the noise of the velocity derived from the displacement, through the damper's force-velocity
slope :math:`\partial F/\partial v` - is added per sample (:func:`erdesign.data.noise_floor.motion_noise`).  The
floor is the ESR that these leave on the judged samples of the analysed record
(:class:`erdesign.diagnosis.records.Prepared`):

.. math::
    \text{ESR}_\text{floor} = \frac{\sum_r \sum_{i \in J_r} \bigl(\sigma_{F,r}^2
        + (\partial F/\partial v)_i^2\,\sigma_{v,r}^2\bigr)}{\sum_{i \in J} (F_i - \bar F)^2}

The slope is that of the damper file's own quasi-steady force at its nominal fluid (no calibration, no effect), so
the floor depends on no fit and is the same in every round of :func:`erdesign.diagnosis.diagnose.improve`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Sequence

import numpy as np

from ..damper import Damper
from ..data.measurement import Measurement
from ..data.noise_floor import estimate_noise_floor, motion_noise

__all__ = ["Floor", "methods_said", "noise_floor", "velocity_slope"]


@dataclass(frozen=True)
class Floor:
    """The noise floor of the judged samples."""

    esr: float
    """ESR the force noise and the motion's noise leave on the judged samples."""
    method: str
    """How the load cell's noise was found (``noise_floor_method``)."""
    sigma_force: tuple[float, ...]
    """The load cell's noise of each record, [N]."""
    motion_esr: float = 0.0
    """The part of :attr:`esr` that the noise of the derived velocity adds."""


def velocity_slope(damper: Damper, record: Measurement, sigma_v: float) -> np.ndarray:
    """:math:`\\partial F/\\partial v` of the damper file's quasi-steady force at its nominal fluid on the record's
    samples, [N s/m]: central differences over :math:`\\pm\\sigma_v` (at least 1e-6 of the peak speed)."""
    from ..effects.chain import PhysicsDamper

    model = PhysicsDamper(damper, ())
    values = model.initial_guess(record)
    v = record.velocity
    dv = max(float(sigma_v), 1e-6 * float(np.max(np.abs(v))), 1e-12)
    sharp = replace(record, velocity_noise=0.0)
    with np.errstate(all="ignore"):
        hi = model.force(replace(sharp, velocity=v + dv), values)
        lo = model.force(replace(sharp, velocity=v - dv), values)
    slope = (hi - lo) / (2 * dv)
    return np.where(np.isfinite(slope), slope, 0.0)


def noise_floor(records: Sequence[Measurement], prep, force_noise=None, damper: Damper | None = None) -> Floor:
    """The floor of ``records`` as prepared by :func:`erdesign.diagnosis.records.prepare` (module notes);
    ``force_noise`` (a string, quantity or float in N) is the user's figure for the load cell; ``damper`` gives the
    force-velocity slope through which the velocity's noise reaches the force (without it the motion adds nothing).
    """
    sigmas, methods = [], []
    force_part = motion_part = 0.0
    kept = prep.kept or [None] * len(records)
    for r, (_, seg), keep in zip(records, prep.segments, kept):
        # the noise is estimated where no finding excludes the samples (a clipped flat top has none)
        est = estimate_noise_floor(r, keep, force_noise=force_noise)
        sigmas.append(float(est.sigma_force))
        methods.append(est.method)
        judged = prep.judged[seg]
        force_part += int(judged.sum()) * float(est.sigma_force) ** 2
        if damper is not None:
            _, sv, _ = motion_noise(r)
            part = replace(prep.work.select(seg), velocity_noise=None)
            slope = velocity_slope(damper, part, sv)[judged]
            motion_part += float(np.sum(slope**2)) * sv**2
    F = prep.work.force[prep.judged]
    ss = float(np.sum((F - F.mean()) ** 2)) if F.size else 0.0
    esr = min((force_part + motion_part) / ss, 1.0) if ss > 0 else 0.0
    motion = min(motion_part / ss, 1.0) if ss > 0 else 0.0
    return Floor(float(esr), methods_said([name for name, _ in prep.segments], methods), tuple(sigmas), float(motion))


#: Record names listed per method in :func:`methods_said` before "and N more".
NAMES_SAID = 3


def methods_said(names: Sequence[str], methods: Sequence[str]) -> str:
    """How the floors of several records were found, in one short line: the method alone when all agree, else each
    method with its number of records and the first :data:`NAMES_SAID` of their names (30 records made a line of
    1,700 characters when every record was named).

    >>> methods_said(["a", "b", "c", "d", "e"], ["repeated cycles"] * 4 + ["fourth differences"])
    'repeated cycles (4 records: a, b, c and 1 more); fourth differences (1 record: e)'
    """
    groups: dict[str, list[str]] = {}
    for name, m in zip(names, methods):
        groups.setdefault(m, []).append(name)
    if len(groups) == 1:
        return methods[0]

    def said(m: str, who: list[str]) -> str:
        listed = ", ".join(who[:NAMES_SAID]) + (f" and {len(who) - NAMES_SAID} more" if len(who) > NAMES_SAID else "")
        return f"{m} ({len(who)} record{'s' if len(who) > 1 else ''}: {listed})"

    return "; ".join(said(m, who) for m, who in groups.items())
