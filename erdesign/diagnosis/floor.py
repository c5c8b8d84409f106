r"""The noise floor of a diagnosis: one number per record(s), fixed across rounds, on the judged samples.

Stage 2 of diagnosis (docs/diagnosis.md).  The load cell's noise :math:`\sigma_{F,r}` of each record :math:`r` is
estimated once from the full record (or given by the user) by :func:`erdesign.data.noise.estimate_noise_floor`, which
also says how (``noise_floor_method``).  The floor is the ESR that this noise alone leaves on the judged samples of
the analysed record (:class:`erdesign.diagnosis.records.Prepared`):

.. math::
    \text{ESR}_\text{floor} = \frac{\sum_r n_r\,\sigma_{F,r}^2}{\sum_{i\,\text{judged}} (F_i - \bar F)^2}

It depends on no model, so it is the same in every round of :func:`erdesign.diagnosis.diagnose.improve`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ..data.measurement import Measurement
from ..data.noise import estimate_noise_floor

__all__ = ["Floor", "noise_floor"]


@dataclass(frozen=True)
class Floor:
    """The noise floor of the judged samples."""

    esr: float
    """ESR the force noise alone leaves on the judged samples."""
    method: str
    """How the load cell's noise was found (``noise_floor_method``)."""
    sigma_force: tuple[float, ...]
    """The load cell's noise of each record, [N]."""


def noise_floor(records: Sequence[Measurement], prep, force_noise=None) -> Floor:
    """The floor of ``records`` as prepared by :func:`erdesign.diagnosis.records.prepare` (module notes);
    ``force_noise`` (a string, quantity or float in N) is the user's figure for the load cell."""
    sigmas, methods = [], []
    num = 0.0
    kept = prep.kept or [None] * len(records)
    for r, (_, seg), keep in zip(records, prep.segments, kept):
        # the noise is estimated where no finding excludes the samples (a clipped flat top has none)
        est = estimate_noise_floor(r, keep, force_noise=force_noise)
        sigmas.append(float(est.sigma_force))
        methods.append(est.method)
        num += int(prep.judged[seg].sum()) * float(est.sigma_force) ** 2
    F = prep.work.force[prep.judged]
    ss = float(np.sum((F - F.mean()) ** 2)) if F.size else 0.0
    esr = min(num / ss, 1.0) if ss > 0 else 0.0
    method = methods[0] if len(set(methods)) == 1 else "; ".join(
        f"{name}: {m}" for (name, _), m in zip(prep.segments, methods))
    return Floor(float(esr), method, tuple(sigmas))
