r"""The samples a diagnosis works on: one or several records of one damper, thinned where that loses nothing, with
the samples to judge marked.

Stage 1 of diagnosis (docs/diagnosis.md).  Every later stage - calibration, residual analysis, candidates, verdict -
runs models on one :class:`Prepared` record and compares them with the measured force on its ``judged`` samples
only, so that ``erdesign fit`` and ``erdesign diagnose`` state one ESR for one model.

* **Several records** are joined end to end (:func:`join_records`) with a pause of :data:`JOIN_PAUSE` between
  them: the states that effects carry in time (the lagged field, the pressure of a compressible column) settle
  during the pause, so each record starts from its own state; :attr:`Prepared.segments` says which samples belong to
  which record, for the ESR of each and for record-wise cross-validation.
* **Long records** are thinned for the analysis (:func:`analysis_samples`), but never where an effect lives in a
  transient: every sample within :data:`AFTER_FIELD_CHANGE` of a change of the field, and samples near reversals at
  up to :data:`REVERSAL_RATE_FACTOR` times the thinned rate, are kept - so a field lag of a few milliseconds on a
  long 1 kHz record is still judged.  Velocities and accelerations are derived on the full record first.
* **Judged samples** are those where the sign of the velocity is known (:func:`erdesign.data.noise.sign_known`;
  not while the piston rests, :func:`erdesign.data.noise_floor.still_samples`) and that no data finding excludes (a clipped force, a saturated displacement:
  :mod:`erdesign.data.findings`).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field, replace
from typing import Sequence

import numpy as np

from ..data.measurement import Measurement
from ..errors import ErdesignError
from ..data.noise import displacement_noise, sign_known, velocity_noise
from ..data.noise_floor import still_samples

__all__ = [
    "Prepared",
    "prepare",
    "join_records",
    "analysis_samples",
    "velocity_bias",
    "sign_known_widened",
    "MAX_SAMPLES",
    "AFTER_FIELD_CHANGE",
    "JOIN_PAUSE",
    "REVERSAL_RATE_FACTOR",
    "FIELD_CHANGE",
]

#: Records longer than this are thinned for the analysis (the kept transients come on top, up to twice as many).
MAX_SAMPLES = 4000
#: Fewest samples an analysis may be thinned to (max_samples): fewer cannot show a hysteresis loop.
MIN_MAX_SAMPLES = 100
#: After a change of the field every sample is kept this long, [s]: coil and driver lags are 5-40 ms.
AFTER_FIELD_CHANGE = 0.06
#: A change of the control between two samples larger than this share of its range counts as a field change.
FIELD_CHANGE = 0.1
#: Near reversals (|v| below 10 % of the peak speed) samples are kept this many times more densely than elsewhere.
REVERSAL_RATE_FACTOR = 4
#: Pause between joined records, [s]: long beside any time constant an effect carries (lags, column pressure).
JOIN_PAUSE = 10.0


@dataclass
class Prepared:
    """The record(s) a diagnosis works on, thinned, with the samples to judge."""

    work: Measurement
    """The joined, thinned record the models run on (velocity noise of the full records kept)."""
    judged: np.ndarray
    """True on the samples that scores and verdicts are judged on."""
    segments: list[tuple[str, slice]]
    """(record name, its samples in :attr:`work`) per record."""
    full_samples: list[int]
    """Samples of each full record."""
    excluded: list[int] = field(default_factory=list)
    """Samples of each full record left out by a data finding (clipped, saturated)."""
    kept: list = field(default_factory=list)
    """Per full record: True on the samples no data finding leaves out (None: all)."""
    analysed: np.ndarray | None = None
    """True on the samples no data finding leaves out and where the piston moves: :attr:`judged` plus the samples
    near reversals, where only an effect that makes the force continuous there can be judged (None: as judged)."""

    @property
    def names(self) -> list[str]:
        return [n for n, _ in self.segments]

    def mask(self) -> np.ndarray | None:
        """:attr:`judged`, or None when every sample is judged."""
        return None if self.judged.all() else self.judged


def _field_changes(record: Measurement) -> np.ndarray:
    u = np.abs(np.asarray(record.control, dtype=float))
    span = float(u.max() - u.min()) if u.size else 0.0
    if not span > 0:
        return np.zeros(0, dtype=int)
    return np.flatnonzero(np.abs(np.diff(record.control)) > FIELD_CHANGE * span)


def analysis_samples(record: Measurement, max_samples: int = MAX_SAMPLES) -> np.ndarray:
    """Indices of the samples the analysis keeps: an even thinning to about ``max_samples``, every sample within
    :data:`AFTER_FIELD_CHANGE` after a field change, and denser samples near reversals (module notes).

    Examples
    --------
    >>> t = np.arange(0, 60, 1e-3); x = 0.01 * np.sin(2 * np.pi * 0.5 * t)
    >>> E = np.where((t % 10) < 5, 1.0, 0.0)                          # the field switched every 5 s
    >>> from erdesign.data.measurement import Measurement
    >>> keep = analysis_samples(Measurement.from_arrays(t, x, control=E, control_kind="current"))
    >>> int(np.median(np.diff(t[keep])) * 1e3), bool(np.all(np.diff(t[keep])[(t[keep] > 5.0) [:-1]
    ...                                                        & (t[keep] < 5.05)[:-1]] < 1.5e-3))
    (15, True)
    """
    n = len(record)
    if n <= max_samples:
        return np.arange(n)
    step = int(math.ceil(n / max_samples))
    keep = np.zeros(n, dtype=bool)
    keep[::step] = True
    keep[-1] = True
    t = record.time
    changes = _field_changes(record)
    if changes.size:
        starts = t[changes]
        # every sample in [t_change, t_change + AFTER_FIELD_CHANGE]
        j = np.searchsorted(starts, t, side="right") - 1
        near = (j >= 0) & (t - starts[np.maximum(j, 0)] <= AFTER_FIELD_CHANGE + 1e-9)
        near[changes] = True
        keep |= near
    fine = max(step // REVERSAL_RATE_FACTOR, 1)
    if fine < step:
        v = np.abs(record.velocity)
        slow = v < 0.1 * max(float(v.max()), 1e-300)
        grid = np.zeros(n, dtype=bool)
        grid[::fine] = True
        keep |= slow & grid
    idx = np.flatnonzero(keep)
    if idx.size > 3 * max_samples:
        # a control that changes everywhere (a random command): even thinning at the transient rate instead
        fine_step = int(math.ceil(n / (3 * max_samples)))
        idx = np.unique(np.r_[np.arange(0, n, fine_step), n - 1])
    return idx


def velocity_bias(record: Measurement) -> float:
    r"""RMS error of the record's derived velocity that is not noise, [m/s]: what a derivative filter leaves out of a
    rough motion (a servo actuator following a random command), estimated against plain central differences,
    whose own error is noise alone, :math:`\sigma_x/(\sqrt 2\,\Delta t)`:
    :math:`b^2 = \overline{(v - v_{cd})^2} - \sigma_x^2/(2\Delta t^2)` (0 for a measured velocity column)."""
    if "velocity" in record.units or len(record) < 8:
        return 0.0
    t, x = record.time, np.asarray(record.displacement, dtype=float)
    dt = float(np.median(np.diff(t)))
    e = np.asarray(record.velocity, dtype=float) - np.gradient(x, t)
    inner = e[len(e) // 100 + 1 : len(e) - len(e) // 100 - 1]  # the filter's edges are sign-unknown anyway
    cd_noise = displacement_noise(record) / (math.sqrt(2.0) * dt)
    return math.sqrt(max(float(np.mean(inner**2)) - cd_noise**2, 0.0))


def sign_known_widened(record: Measurement, sigma_v: float) -> np.ndarray:
    """:func:`erdesign.data.noise.sign_known` with the band widened by the derived velocity's bias
    (:func:`velocity_bias`): where the bias exceeds the noise (a rough motion), the band is
    ``3 sqrt(sigma_v^2 + b^2)`` and two samples more on each side.  On the benchmark's Ornstein-Uhlenbeck record
    (a servo following a random command) the derived velocity was 4 x its noise off, and eleven samples of the
    wrong sign beyond the band cost a clean record 244 x its floor."""
    b = velocity_bias(record)
    if not b > sigma_v:
        return sign_known(record, sigma_v)
    known = sign_known(record, math.hypot(sigma_v, b))
    from scipy.ndimage import binary_erosion

    return binary_erosion(known, iterations=2, border_value=0)


def join_records(records: Sequence[Measurement], pause: float = JOIN_PAUSE) -> tuple[Measurement, list[slice]]:
    """Several records end to end, each shifted in time to start ``pause`` after the previous one ends; the
    velocity noise is the largest of theirs.  Returns the joined record and each one's samples.

    Examples
    --------
    >>> t = np.linspace(0, 1, 101); x = 0.01 * np.sin(2 * np.pi * t)
    >>> a = Measurement.from_arrays(t, x, 100 * x); b = Measurement.from_arrays(t, 2 * x, 200 * x)
    >>> j, seg = join_records([a, b])
    >>> len(j), seg[1], float(j.time[101] - j.time[100])
    (202, slice(101, 202, None), 10.0)
    """
    if len(records) == 1:
        return records[0], [slice(0, len(records[0]))]
    parts, segs, t0, i0 = [], [], 0.0, 0
    for r in records:
        shift = t0 - float(r.time[0])
        parts.append(replace(r, time=r.time + shift))
        segs.append(slice(i0, i0 + len(r)))
        t0 = float(r.time[-1]) + shift + pause
        i0 += len(r)
    cat = lambda name: np.concatenate([getattr(p, name) for p in parts])  # noqa: E731
    temperature = (
        np.concatenate([p.temperature for p in parts]) if all(p.temperature is not None for p in parts) else None
    )
    first = records[0]
    joined = replace(
        first,
        time=cat("time"),
        displacement=cat("displacement"),
        force=cat("force"),
        velocity=cat("velocity"),
        acceleration=cat("acceleration"),
        control=cat("control"),
        temperature=temperature,
        name=" + ".join(r.name or f"record {i + 1}" for i, r in enumerate(records)),
        velocity_noise=max(velocity_noise(r) for r in records),
    )
    return joined, segs


def prepare(
    records: Sequence[Measurement],
    excluded: Sequence[np.ndarray | None] | None = None,
    *,
    max_samples: int = MAX_SAMPLES,
) -> Prepared:
    """Thin each record (:func:`analysis_samples`), mark its judged samples (sign of the velocity known, not
    excluded) and join them (:func:`join_records`).  ``excluded``: per record, True where a data finding leaves
    the sample out (or None)."""
    if (
        isinstance(max_samples, bool)
        or not isinstance(max_samples, numbers.Real)
        or not float(max_samples).is_integer()
        or max_samples < MIN_MAX_SAMPLES
    ):  # 0 was a ZeroDivisionError
        raise ErdesignError(f"max_samples: must be a whole number >= {MIN_MAX_SAMPLES}, got {max_samples!r}")
    max_samples = int(max_samples)
    excluded = list(excluded) if excluded is not None else [None] * len(records)
    per_record = max(max_samples // len(records), 400) if len(records) > 1 else max_samples
    thinned, judged, analysed, counts, n_full, kept = [], [], [], [], [], []
    for r, ex in zip(records, excluded):
        sigma_v = velocity_noise(r)
        # the sign of the velocity is unknown near reversals and wherever the piston rests (a derivative filter rings
        # after the motion stops)
        moving = ~still_samples(r)
        if ex is not None:
            moving = moving & ~ex
        known = sign_known_widened(r, sigma_v) & moving
        keep = analysis_samples(r, per_record)
        if len(keep) == len(r):
            thinned.append(replace(r, velocity_noise=sigma_v))
        else:
            thinned.append(replace(r.select(keep), velocity_noise=sigma_v))
        judged.append(known[keep])
        analysed.append(moving[keep])
        counts.append(0 if ex is None else int(ex.sum()))
        kept.append(None if ex is None or not ex.any() else ~ex)
        n_full.append(len(r))
    work, segs = join_records(thinned)
    names = [r.name or f"record {i + 1}" for i, r in enumerate(records)]
    return Prepared(
        work, np.concatenate(judged), list(zip(names, segs)), n_full, counts, kept, np.concatenate(analysed)
    )
