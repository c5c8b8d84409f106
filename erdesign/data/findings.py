r"""Data-quality findings made before any fit: what a record's channels say about how it was measured.

A fit or a diagnosis explains the force by physics; a record can also carry the marks of its instruments and its
export - a load cell at its limit, a displacement channel at the end of its range, a moving average applied before
export, a constant time offset between the channels, a hole in the time column, a load-cell offset or drift, a
displacement on a coarse grid.  :func:`find_data_problems` looks for each (a registry of small detectors,
:data:`DETECTORS`) and returns :class:`Finding` objects: a message a user reads, where in the record it is, the
samples a fit must leave out (:func:`excluded_mask`) and the effects whose verdict the finding makes unsafe.

================================  ====================================================================================
kind                              signature in the record
================================  ====================================================================================
``clipped``                       the force's largest (smallest) value repeated in a flat run
                                  (:func:`erdesign.data.measurement.clipped_samples`), more often than the
                                  quantisation of a peak explains
``saturated_displacement``        the same flat run at an extreme of the displacement, while the force keeps changing
``smoothed``                      a moving average over N samples: the channel's spectrum is zero at every multiple of
                                  ``fs / N`` (the nulls of a boxcar), far below the spectrum between them
``channel_skew``                  the force jumps at a reversal (yield force, seal friction) as sharply as a sample,
                                  but a constant time after (or before) the velocity's zero: a delay between channels,
                                  not a physical lag (a compressible column or an elastic fluid rounds the jump over
                                  a time that grows with the force and shrinks with the acceleration)
``time_gap``                      a time step more than :data:`GAP_FACTOR` times the median step
``non_monotonic_time``            time that repeats or goes back (arrays only: :func:`find_time_problems`; a
                                  :class:`~erdesign.data.measurement.Measurement` refuses such time)
``force_offset_drift``            a trend of the force over the record that no odd function of the velocity, no
                                  spring and no inertia explains (a load cell warming or creeping); with
                                  ``expected_mean_force``, an offset from it
``quantized_displacement``        every displacement step a whole multiple of one step, coarse against the
                                  displacement's other noise
================================  ====================================================================================

Every detector errs on the side of silence: a finding on a clean record is a false alarm that a user learns to
ignore.  tests/test_findings.py makes each artefact on truth-rig records
(:mod:`erdesign.simulation.truthrig.artefacts`) and checks that it is found, with its size, and that clean records of
every example damper and motion, and a compressible column, raise nothing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..errors import ErdesignError
from .measurement import Measurement, _noise_level, clipped_samples

__all__ = [
    "FINDING_KINDS",
    "Finding",
    "find_data_problems",
    "find_time_problems",
    "excluded_mask",
    "DETECTORS",
    "LAG_EFFECTS",
    "SMOOTHING_MIMICS",
    "GAP_FACTOR",
]

FINDING_KINDS = (
    "clipped",
    "saturated_displacement",
    "smoothed",
    "channel_skew",
    "time_gap",
    "non_monotonic_time",
    "force_offset_drift",
    "quantized_displacement",
)

#: Effects whose signature is a lag of the force behind the motion: a smoothed record or a skewed channel makes a
#: verdict on them unsafe.
LAG_EFFECTS = ("compressibility", "preyield_elasticity", "field_lag", "fluid_inertia")
#: Effects a moving average mimics: the lag-type effects, and leakage (the average rounds the force's jump at each
#: reversal, as creep through a bypass below yield does).
SMOOTHING_MIMICS = (*LAG_EFFECTS, "leakage")

#: A time step more than this many times the median step is a gap.
GAP_FACTOR = 3.0


@dataclass(frozen=True, eq=False)  # compared by identity: it may hold a mask
class Finding:
    """One data-quality finding about one record.

    Attributes
    ----------
    kind : str
        One of :data:`FINDING_KINDS`.
    message : str
        What was found and what it means for a fit, in a sentence or two.
    record : str
        The record's name.
    where : str
        Where in the record, human-readable (``"t = 3.21-3.40 s, 217 samples"``).
    skew_s : float or None
        ``channel_skew`` only: the force lags the displacement by this time, [s] (negative: it leads).
    excluded : ndarray of bool or None
        Samples a fit must leave out (``clipped``, ``saturated_displacement``); None when the finding excludes
        nothing.
    unsafe_for : tuple of str
        Effect names (the effect library) whose verdict this finding makes unsafe.
    """

    kind: str
    message: str
    record: str
    where: str
    skew_s: float | None = None
    excluded: np.ndarray | None = None
    unsafe_for: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.kind not in FINDING_KINDS:
            raise ValueError(f"kind: must be one of {', '.join(FINDING_KINDS)}, got {self.kind!r}")

    def __str__(self) -> str:
        """One line for a report: ``"clipped (t = 19.59-19.89 s, 217 samples): the force sits at ..."``."""
        return f"{self.kind} ({self.where}): {self.message}"

    def as_json(self) -> dict:
        """``{"kind", "message", "record", "where"}``, plus ``"skew_s"`` for ``channel_skew`` (never NaN)."""
        out = {"kind": self.kind, "message": self.message, "record": self.record, "where": self.where}
        if self.kind == "channel_skew" and self.skew_s is not None and math.isfinite(self.skew_s):
            out["skew_s"] = float(self.skew_s)
        return out


def excluded_mask(findings, n: int) -> np.ndarray:
    """True where a fit must leave the sample out: the union of the ``excluded`` masks of ``findings`` that have one
    of ``n`` samples.

    >>> f = Finding("clipped", "flat top", "r", "3 samples", excluded=np.array([0, 1, 1, 0], bool))
    >>> excluded_mask([f], 4).tolist()
    [False, True, True, False]
    """
    if int(n) < 0:
        raise ValueError(f"n: must be a number of samples >= 0, got {n}")
    mask = np.zeros(int(n), dtype=bool)
    for f in findings:
        if f.excluded is not None:
            if f.excluded.shape != mask.shape:
                raise ValueError(
                    f"findings: the {f.kind} finding of {f.record!r} has a mask of {f.excluded.size} samples, not {n}"
                )
            mask |= f.excluded
    return mask


# ---------------------------------------------------------------------------------------------------- helpers
def _span(t: np.ndarray, mask: np.ndarray) -> str:
    """``"t = a-b s, N samples"`` of the samples in ``mask``."""
    idx = np.flatnonzero(mask)
    return f"t = {t[idx[0]]:.4g}-{t[idx[-1]]:.4g} s, {idx.size} samples"


def _runs(mask: np.ndarray) -> int:
    """Number of runs of True."""
    return int(np.count_nonzero(np.diff(np.r_[0, mask.astype(np.int8)]) == 1))


def _grid_step(y: np.ndarray) -> float | None:
    """The step of the grid every value of ``y`` lies on, when there is one coarser than round-off; else None.

    The smallest non-zero change between samples is the candidate; it is the step when at least 98 % of all changes
    are whole multiples of it (to 2 %).  An unquantised noisy channel has no such step."""
    d = np.abs(np.diff(y))
    scale = float(np.ptp(y))
    if scale == 0 or d.size < 10:
        return None
    nz = d[d > 1e-9 * scale]
    if nz.size < 5:
        return None
    q = float(nz.min())
    k = d / q
    on_grid = np.abs(k - np.round(k)) <= 0.02
    return q if on_grid.mean() >= 0.98 else None


def _pile_up(y: np.ndarray, at: np.ndarray, level: float, q: float | None) -> bool:
    """Whether the samples at an extreme ``level`` pile up there (a limit) rather than a quantised peak touching it:
    at least 5 and more than three times as many as at the next level in, one quantisation step away."""
    if q is None:
        return True  # exact repeats of an unquantised extreme happen only at a limit
    inside = np.sign(np.mean(y) - level)
    nxt = np.abs(y - (level + inside * q)) <= 0.02 * q
    return at.sum() >= 5 and at.sum() > 3 * nxt.sum()


def _beyond_level(x: np.ndarray, at: np.ndarray, level: float, q: float | None) -> bool:
    """Whether the motion around the flat runs ``at`` of ``x`` at ``level`` would have gone beyond it: a parabola
    through the samples on either side of the longest run (as many as the run is long, 4 to 12 each) peaks more
    than a grid step (``q``, or 1e-3 of the range without a grid) past the level.  A smooth peak that merely rounds
    to the level peaks within a step of it."""
    starts = np.flatnonzero(np.diff(np.r_[0, at.astype(np.int8)]) == 1)
    ends = np.flatnonzero(np.diff(np.r_[at.astype(np.int8), 0]) == -1) + 1
    k = int(np.argmax(ends - starts))
    a, b = int(starts[k]), int(ends[k])
    w = int(np.clip(b - a, 4, 12))
    if a - w < 0 or b + w > x.size:
        return b - a >= 3 and q is None
    idx = np.r_[a - w : a, b : b + w]
    c2, c1, c0 = np.polyfit(idx - 0.5 * (a + b), x[idx], 2)
    if c2 == 0:
        return False
    vertex = c0 - c1**2 / (4 * c2)
    step = q if q is not None else 1e-3 * float(np.ptp(x))
    return bool(np.sign(level - np.mean(x)) * (vertex - level) > step)


def _correlation_length(r: np.ndarray) -> float:
    """Samples per independent sample of a residual: 1 + 2 x its autocorrelation summed up to the first zero."""
    n = r.size
    z = r - r.mean()
    spec = np.abs(np.fft.rfft(z, 2 * n)) ** 2
    ac = np.fft.irfft(spec)[:n]
    if ac[0] <= 0:
        return 1.0
    rho = ac / ac[0]
    first = np.flatnonzero(rho <= 0)
    stop = int(first[0]) if first.size else n
    return float(max(1.0, 1.0 + 2.0 * np.sum(rho[1:stop])))


def _dominant_period(record: Measurement) -> float:
    """Period of the displacement's largest Fourier component, [s] (the record's length if none)."""
    f = record.dominant_frequency
    return 1.0 / f if f > 0 else record.duration


# ---------------------------------------------------------------------------------------------------- detectors
@dataclass(frozen=True)
class _Options:
    exclude_clipped: bool | None
    expected_mean_force: float | None


def _clipped(record: Measurement, opt: _Options) -> list[Finding]:
    """``clipped``: a flat top or bottom of the force (:func:`~erdesign.data.measurement.clipped_samples`)."""
    if record.force is None:
        return []
    F = record.force
    mask = clipped_samples(F)
    if not mask.any() or mask.mean() > 0.5:
        return []  # none, or a constant or two-level force: a dead channel or a noise-free synthetic one
    q = _grid_step(F)
    tol = 1e-9 * float(np.ptp(F))
    sure = True
    for lvl in (F.max(), F.min()):
        at = mask & (np.abs(F - lvl) <= tol)
        if at.any():
            # a limit holds the force flat where it would have gone on: many samples piled up at the level, or a
            # run the force on either side would have overshot
            sure &= _pile_up(F, at, lvl, q) and (at.sum() >= CLIPPED_SURE or _beyond_level(F, at, lvl, q))
    if not sure and opt.exclude_clipped is not True and mask.sum() < 5:
        return []  # a flat peak of a few samples (a smoothed or quantised force): not worth a word
    exclude = sure if opt.exclude_clipped is None else opt.exclude_clipped
    levels = sorted({float(v) for v in F[mask]})
    level_text = " and ".join(f"{v:.6g} N" for v in levels)
    if sure:
        msg = (
            f"the force sits at {level_text} on {int(mask.sum())} samples in {_runs(mask)} flat runs: a load cell "
            "or amplifier at its limit; the true force there is unknown"
        )
    else:
        msg = (
            f"the force repeats its extreme {level_text} on {int(mask.sum())} samples; that may be a limit or "
            "a flat peak (quantised or smoothed)"
        )
    msg += (
        ": those samples are left out of the fit"
        if exclude
        else ": those samples are kept (--exclude-clipped leaves them out)"
    )
    return [Finding("clipped", msg, record.name, _span(record.time, mask), excluded=mask if exclude else None)]


def _saturated_displacement(record: Measurement, opt: _Options) -> list[Finding]:
    """``saturated_displacement``: a flat extreme of the displacement while the force changes."""
    x = record.displacement
    if record.force is None:
        return []
    mask = clipped_samples(x)
    if mask.mean() > 0.5:
        mask[:] = False
    q = _grid_step(x)
    tol = 1e-9 * np.ptp(x)
    F = record.force
    sigma = _noise_level(F)
    keep = np.zeros_like(mask)
    for lvl in (x.max(), x.min()):
        at = mask & (np.abs(x - lvl) <= tol)
        if not at.any():
            continue
        # the force keeps changing while the displacement stands still: the channel, not the piston, stopped
        if (
            np.ptp(F[at]) > max(10 * sigma, 0.05 * np.ptp(F))
            and _pile_up(x, at, lvl, q)
            and _beyond_level(x, at, lvl, q)
        ):
            keep |= at
    out = []
    if keep.any():
        levels = " and ".join(f"{v * 1e3:.6g} mm" for v in sorted({float(v) for v in x[keep]}))
        msg = (
            f"the displacement stands at {levels} on {int(keep.sum())} samples in {_runs(keep)} flat runs while "
            "the force keeps changing: a displacement channel at the end of its range; the motion there is "
            "unknown and those samples are left out of the fit"
        )
        out.append(Finding("saturated_displacement", msg, record.name, _span(record.time, keep), excluded=keep))
    held = np.zeros_like(keep) if keep.any() else _held_beyond(record)
    if held.any():
        lo, hi = (float(v) for v in np.percentile(x[held], [10, 90]))
        rest = x[~held]
        msg = (
            f"the displacement is held at {lo * 1e3:.3g} to {hi * 1e3:.3g} mm (10-90 %), beyond anything the rest of the "
            f"record reaches ({rest.min() * 1e3:.3g} to {rest.max() * 1e3:.3g} mm), while the force swings by "
            f"{np.ptp(F[held]):.3g} N: an actuator or transducer excursion, not the damper's motion; those "
            "samples are left out of the fit"
        )
        out.append(Finding("saturated_displacement", msg, record.name, _span(record.time, held), excluded=held))
    return out


#: A held excursion of the displacement (:func:`_held_beyond`): the top (or bottom) share of the stroke ...
HELD_TOP = 0.15
#: ... visited once, for at least this long, [s] ...
HELD_MIN_DURATION = 0.1
#: ... at a median speed below this share of the record's peak speed ...
HELD_SLOW = 0.05
#: ... while the force swings by this share of its range.
HELD_FORCE_SWING = 0.5


def _held_beyond(record: Measurement) -> np.ndarray:
    """Samples of a held excursion: the displacement's top (or bottom) :data:`HELD_TOP` of the stroke is reached
    once, in one stretch of at least :data:`HELD_MIN_DURATION` (gaps under 50 ms bridged), where its median speed is below
    :data:`HELD_SLOW` of the record's peak speed while the force swings by :data:`HELD_FORCE_SWING` of its range
    (Dyke's ransim_u: 10.5-11.0 mm for 0.38 s where the rest stays below 8.4 mm, the force swinging by 7 kN).  A
    damper's force follows its motion; a force that swings while the displacement is held at an extreme it never
    reaches again is the actuator or the transducer, not the damper.  A sine passes through the same share of its
    stroke at about 40 % of its peak speed, and random motion at a similar share."""
    x, t, F = np.asarray(record.displacement, float), np.asarray(record.time, float), record.force
    n = x.size
    out = np.zeros(n, dtype=bool)
    span = float(np.ptp(x))
    if F is None or n < 20 or not span > 0:
        return out
    dt = float(np.median(np.diff(t)))
    bridge = max(int(round(0.05 / dt)), 1)
    speed = np.abs(np.asarray(record.velocity, float))
    for y in (x, -x):
        near = y >= y.max() - HELD_TOP * span
        idx = np.flatnonzero(near)
        if np.any(np.diff(idx) > bridge):
            continue  # the extreme is visited more than once
        a, b = idx[0], idx[-1]
        if t[b] - t[a] < HELD_MIN_DURATION:
            continue
        # the typical speed there (a median: the transducer's own jumps and dips do not count)
        if np.median(speed[near]) >= HELD_SLOW * float(speed.max()):
            continue
        if np.ptp(F[a : b + 1]) < HELD_FORCE_SWING * float(np.ptp(F)):
            continue
        out[a : b + 1] = True
    return out


#: Samples at a flat extreme of the force from which it is surely clipped (fewer: only if the force on either side
#: would have gone beyond it).
CLIPPED_SURE = 10

#: Depth of the nulls of a moving average that makes a channel ``smoothed``: the spectrum at the nulls below this
#: fraction of the spectrum between them (mean over the nulls, log10).
SMOOTHING_DEPTH = -1.5
#: Longest moving average looked for, [samples].
MAX_WINDOW = 4000


def _null_depths(y: np.ndarray, N: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For each window length in ``N`` [samples]: the mean depth of the nulls a moving average over it would carve in
    the spectrum of ``y`` (log10 of the power at the nulls over the power between them; each null clipped to -4..1),
    and whether it can be judged (at least two nulls and four bins, over a floor above round-off); see
    :func:`_boxcar_window`."""
    n = y.size
    z = y - np.polyval(np.polyfit(np.arange(n), y, 1), np.arange(n))
    P = np.abs(np.fft.rfft(z * np.hanning(n))) ** 2
    m = P.size
    if not np.any(P > 0):
        return np.full(N.size, np.inf), np.zeros(N.size, dtype=bool)
    from scipy.ndimage import median_filter

    local = median_filter(P, size=41, mode="nearest")
    ok = P <= 30 * local + 1e-300
    ok[:3] = False  # the trend and the lowest bins carry the motion itself
    cs = np.r_[0.0, np.cumsum(np.where(ok, P, 0.0))]
    cc = np.r_[0, np.cumsum(ok)]

    def band(lo, hi):
        lo = np.clip(lo, 0, m)
        hi = np.clip(hi, 0, m)
        cnt = cc[hi] - cc[lo]
        return np.where(cnt > 0, (cs[hi] - cs[lo]) / np.maximum(cnt, 1), np.nan), cnt

    kmax = np.minimum(N // 2, 40)
    rows = np.repeat(np.arange(N.size), kmax)
    j = np.arange(rows.size) - np.repeat(np.cumsum(kmax) - kmax, kmax)  # 0 .. kmax - 1
    # 40 nulls spread from the first to the last below the Nyquist frequency: a filter zeroes them all, the noise
    # included, where the valleys between a signal's harmonics fill with noise at high frequencies
    last = N[rows] // 2
    k = np.where(last <= 40, j + 1, 1 + np.round(j * (last - 1) / 39.0).astype(int))
    spacing = n / N[rows]  # bins between nulls
    centre = k * spacing
    half = np.maximum(0.5, 0.02 * spacing)
    null, ncount = band(np.floor(centre - half + 0.5).astype(int), np.floor(centre + half + 0.5).astype(int) + 1)
    s1, _ = band(np.floor(centre - 0.35 * spacing).astype(int), np.ceil(centre - 0.15 * spacing).astype(int))
    s2, _ = band(np.floor(centre + 0.15 * spacing).astype(int), np.ceil(centre + 0.35 * spacing).astype(int))
    shoulder = np.where(np.isfinite(s1) & np.isfinite(s2), 0.5 * (s1 + s2), np.where(np.isfinite(s1), s1, s2))
    good = np.isfinite(null) & np.isfinite(shoulder) & (shoulder > 0)
    ratio = np.clip(np.log10(np.maximum(np.where(good, null, 1.0), 1e-300) / np.where(good, shoulder, 1.0)), -4, 1)
    used = np.bincount(rows, weights=good, minlength=N.size)
    bins = np.bincount(rows, weights=np.where(good, ncount, 0), minlength=N.size)
    depth = np.bincount(rows, weights=np.where(good, ratio, 0.0), minlength=N.size) / np.maximum(used, 1)
    # with few nulls every one must be empty: a digital low-pass (an anti-alias Butterworth through the bilinear
    # transform) zeroes the Nyquist frequency, the last null of every even window, and would make a mean deep
    shallowest = np.full(N.size, -np.inf)
    np.maximum.at(shallowest, rows[good], ratio[good])
    depth = np.where(used < 4, shallowest, depth)
    # at least two nulls (a window of 4 samples or more), over a floor above round-off (a noise-free synthetic
    # channel has no continuum to carve nulls in)
    floor = 1e-20 * float(P.max())
    loud = np.bincount(rows, weights=np.where(good, shoulder, 0.0), minlength=N.size) / np.maximum(used, 1)
    judged = (used >= 2) & (bins >= 4) & (loud > floor)
    return np.where(judged, depth, np.inf), judged


#: The stretches of a record (start and end, fractions of its length) besides the whole in which a moving average's
#: nulls must appear too: overlapping, of unequal length and ending at no simple fraction of the record, so that no
#: programme of whole cycles fits all of them.
SMOOTHING_PIECES = ((0.0, 0.63), (0.29, 1.0))


def _boxcar_window(y: np.ndarray) -> tuple[int, float] | None:
    """The length N [samples] of a moving average ``y`` was smoothed by, and the depth of its nulls (log10 of the
    power at the nulls over the power half-way between them), or None.

    A moving average over N samples (N >= 4: at least two nulls) multiplies the spectrum by
    :math:`|\\sin(\\pi f N/f_s) / (N \\sin(\\pi f/f_s))|^2`, zero at every :math:`k f_s / N`.  For each N up
    to a twelfth of the shortest stretch judged (and :data:`MAX_WINDOW`) the power in narrow bands at 40 of its
    nulls (all when there are fewer, else spread evenly from the first to the Nyquist frequency) is compared with the power a quarter of the spacing away on each side; bins of lines of the signal (more
    than 30 times the local median) are left out of both, so that a periodic signal whose harmonics fall between
    candidate nulls cannot mimic a comb.

    A filter carves its nulls into every stretch of the record, but a signal can have spectral zeros of its own:
    a programme whose segments are whole numbers of cycles of a force with odd harmonics only (a stepped sine of 3
    cycles at 1 Hz and 3 at 2 Hz) has none of its power at the multiples of 4 Hz over the whole record, a comb as
    deep as a moving average's over 1/4 s, and deep valleys there in any stretch where its harmonics stand far
    above the noise.  The depth is therefore taken as the shallowest over the whole record and the stretches
    :data:`SMOOTHING_PIECES`, which cut those segments at arbitrary points, and over nulls up to the Nyquist
    frequency, where a filter's nulls stay empty and the noise fills a signal's valleys (issue 23: a clean stepped
    sine was called smoothed over 125 samples).  The window with the
    deepest mean null wins, or the longest multiple of it about as deep (a window has the nulls of its divisors
    too)."""
    n = y.size
    if n < 64:
        return None
    pieces = [(0, n)] + [(int(a * n), int(b * n)) for a, b in SMOOTHING_PIECES]
    shortest = min(b - a for a, b in pieces)
    N = np.arange(2, min(shortest // 12, MAX_WINDOW) + 1)
    if N.size == 0:
        return None
    depth = np.full(N.size, -np.inf)
    for a, b in pieces:
        depth = np.maximum(depth, _null_depths(y[a:b], N)[0])
    i = int(np.argmin(depth))
    if not np.isfinite(depth[i]):
        return None
    # a window N has the nulls of every divisor of N too: take the longest window about as deep as the deepest
    close = np.flatnonzero(depth <= depth[i] + 0.3)
    j = int(close[-1]) if N[close[-1]] % N[i] == 0 else i
    return int(N[j]), float(depth[j])


def _smoothed(record: Measurement, opt: _Options) -> list[Finding]:
    """``smoothed``: the comb of nulls of a moving average in the force or displacement (:func:`_boxcar_window`)."""
    channels = [("force", record.force), ("displacement", record.displacement)]
    found = []
    for name, y in channels:
        if y is None:
            continue
        hit = _boxcar_window(np.asarray(y, float))
        if hit is not None and hit[1] < SMOOTHING_DEPTH:
            found.append((name, hit))
    if not found:
        return []
    dt = record.duration / (len(record) - 1)
    N = found[0][1][0]
    names = " and ".join(name for name, _ in found)
    period = _dominant_period(record)
    msg = (
        f"the {names} {'was' if len(found) == 1 else 'were'} smoothed by a moving average over about {N} samples "
        f"({N * dt:.3g} s, {N * dt / period:.2g} of the motion's period): its spectrum is zero at every multiple "
        f"of {1 / (N * dt):.4g} Hz. A causal average delays a channel by {(N - 1) * dt / 2:.3g} s and rounds the "
        "force at reversals: a lag no physics made, so verdicts on lag-type effects and leakage "
        f"({', '.join(SMOOTHING_MIMICS)}) are unsafe"
    )
    return [
        Finding(
            "smoothed",
            msg,
            record.name,
            f"whole record, {N} samples ({N * dt:.3g} s) window",
            unsafe_for=SMOOTHING_MIMICS,
        )
    ]


def _reversal_jumps(record: Measurement):
    """Each clear force jump at a velocity reversal: (delay of the jump after the velocity's zero [s], jump [N],
    sharp: bool, whether the two samples the force jumps between both lie on one side of the zero, strictly).

    Around each reversal the force is fitted by a line plus a step, ``a + b (t - t0) + J/2 sgn(t - t0 - d)``, the
    step between any two samples within the window; ``d`` is the mid-time of the best pair.  The jump is sharp when
    what the step leaves within three samples of it is at the force noise (a physical lag rounds it over many)."""
    F, v, t = record.force, record.velocity, record.time
    sigma = _noise_level(F)
    dt = record.duration / (len(record) - 1)
    peak = float(np.max(np.abs(v)))
    if peak == 0 or sigma == 0:
        return []
    s = np.sign(v)
    cross = np.flatnonzero((s[:-1] * s[1:]) < 0)
    if cross.size < 2:
        return []
    # keep crossings between half-cycles that reach 10 % of the peak speed (not dithering about zero)
    bounds = np.r_[0, cross + 1]
    amp = np.maximum.reduceat(np.abs(v), bounds)
    out = []
    for j, i in enumerate(cross):
        if amp[j] < 0.1 * peak or amp[j + 1] < 0.1 * peak:
            continue
        t0 = t[i] - v[i] * (t[i + 1] - t[i]) / (v[i + 1] - v[i])
        end = bounds[j + 2] - 1 if j + 2 < bounds.size else v.size - 1
        half_cycle = min(t[i] - t[bounds[j]], t[end] - t[i + 1])
        W = int(max(8, min(0.15 * half_cycle / dt, 60)))
        lo, hi = i - W + 1, i + W + 1
        if lo < 0 or hi > F.size:
            continue
        tt = (t[lo:hi] - t0) / dt
        ff = F[lo:hi]
        split, coef, cost = _best_step(tt, ff)
        J = float(coef[2])
        if J * np.sign(v[i + 1]) < 8 * sigma:
            continue
        r = ff - coef[0] - coef[1] * tt - coef[2] * np.where(np.arange(tt.size) >= split, 0.5, -0.5)
        near = r[max(0, split - 3) : split + 3]
        sharp = float(np.sqrt(np.mean(near**2))) < 3 * sigma
        d = 0.5 * (tt[split - 1] + tt[split]) * dt
        # a jump between samples that bracket the zero (or touch it) is no evidence of a delay
        apart = bool(tt[split - 1] > SKEW_TOUCH or tt[split] < -SKEW_TOUCH)
        out.append((d, J, sharp, apart))
    return out


def _best_step(tt: np.ndarray, ff: np.ndarray):
    """Least squares of ``a + b tt + c s`` with ``s = -1/2`` before and ``+1/2`` from a split sample on, over every
    split in the middle half of the window: (best split, (a, b, c), cost)."""
    n = tt.size
    splits = np.arange(n // 4, n - n // 4)
    ct, cf, ctf = (np.r_[0.0, np.cumsum(y)] for y in (tt, ff, tt * ff))
    St, Sf, Stt, Stf = tt.sum(), ff.sum(), tt @ tt, tt @ ff
    after = lambda c, total: total - c[splits]  # noqa: E731
    Ss = 0.5 * ((n - splits) - splits)
    Sts = 0.5 * (after(ct, St) - ct[splits])
    Ssf = 0.5 * (after(cf, Sf) - cf[splits])
    G = np.empty((splits.size, 3, 3))
    G[:, 0, 0], G[:, 0, 1], G[:, 0, 2] = n, St, Ss
    G[:, 1, 0], G[:, 1, 1], G[:, 1, 2] = St, Stt, Sts
    G[:, 2, 0], G[:, 2, 1], G[:, 2, 2] = Ss, Sts, 0.25 * n
    rhs = np.stack([np.full(splits.size, Sf), np.full(splits.size, Stf), Ssf], axis=1)
    coef = np.linalg.solve(G, rhs[..., None])[..., 0]
    cost = ff @ ff - np.einsum("ij,ij->i", coef, rhs)
    best = int(np.argmin(cost))
    return int(splits[best]), coef[best], float(cost[best])


#: Force jumps at reversals, in force-noise levels, from which their sharpness is judged for a skew.
SKEW_JUMP = 20.0
#: A velocity zero within this many samples of a sample counts as on it (for :data:`SKEW_APART`).
SKEW_TOUCH = 0.05
#: Share of the sharp jumps that must fall between two samples both after (or both before) the velocity's zero:
#: where a rig's frequency divides the sampling rate every reversal falls on a sample and the force jumps just
#: after it, half a sample "late" with no delay at all (a clean stepped sine at 5 Hz and 500 Hz).
SKEW_APART = 0.4


def _channel_skew(record: Measurement, opt: _Options) -> list[Finding]:
    """``channel_skew``: sharp force jumps a constant time from the velocity's zeros (:func:`_reversal_jumps`)."""
    if record.force is None or len(record) < 50:
        return []
    # only jumps far above the noise tell sharp from rounded (a rounded rise leaves a quarter of the jump)
    sigma = _noise_level(record.force)
    jumps = [j for j in _reversal_jumps(record) if abs(j[1]) >= SKEW_JUMP * sigma]
    if len(jumps) < 4:
        return []
    sharp = np.array([j[2] for j in jumps])
    if sharp.sum() < 4 or sharp.mean() < 0.6:
        return []  # the force turns over gradually at reversals: a physical lag, not judged here
    d = np.array([j[0] for j in jumps])[sharp]
    apart = np.array([j[3] for j in jumps])[sharp]
    dt = record.duration / (len(record) - 1)
    mean, spread = float(np.mean(d)), float(np.std(d))
    se = spread / math.sqrt(d.size)
    # a constant delay seen through samples spreads by the sampling alone (uniform over a step: 0.29 dt)
    if abs(mean) < 0.4 * dt or abs(mean) < 4 * se or spread > 0.5 * dt:
        return []
    if np.mean(apart & (np.sign(d) == np.sign(mean))) < SKEW_APART:
        return []  # the jumps touch the velocity's zero: reversals on samples, not a delay
    lag = "lags" if mean > 0 else "leads"
    msg = (
        f"the force {lag} the displacement by {abs(mean) * 1e3:.3g} ms ({abs(mean) / dt:.2g} samples): at "
        f"{d.size} reversals it jumps as sharply as a sample but the same time after the velocity's zero "
        f"(spread {spread * 1e3:.2g} ms), a constant delay between the channels (sampling skew), not a physical "
        f"lag; shift the force by {-mean * 1e3:.3g} ms before fitting. Verdicts on lag-type effects "
        f"({', '.join(LAG_EFFECTS)}) are unsafe"
    )
    return [
        Finding(
            "channel_skew",
            msg,
            record.name,
            f"{d.size} reversals over the whole record",
            skew_s=mean,
            unsafe_for=LAG_EFFECTS,
        )
    ]


def _time_gap(record: Measurement, opt: _Options) -> list[Finding]:
    """``time_gap``: :func:`find_time_problems` on the record's time."""
    return [f for f in find_time_problems(record.time, record=record.name) if f.kind == "time_gap"]


#: A trend of the force over the record larger than this fraction of its RMS is a drift.
DRIFT_FRACTION = 0.03
#: Fewest samples for judging a drift: twenty per coefficient of the regression (30).
DRIFT_MIN_SAMPLES = 600


def _force_offset_drift(record: Measurement, opt: _Options) -> list[Finding]:
    r"""A trend of the force the motion does not explain.

    The force is regressed on what a damper's force can depend on - odd functions of the velocity
    (its sign, two ``tanh``, ``v``, ``v |v|``, ``sgn(v) sqrt|v|``) times 1, the control and its square, and growing
    or falling over the record (heating),
    the displacement and its square (springs), the acceleration (inertia) - plus a constant and a line in time.
    The line's change over the record is the drift; it is reported when it exceeds :data:`DRIFT_FRACTION` of the
    force's RMS, four standard errors (with the residual's correlation length) and ten times the scatter of the
    residual's means over twelve blocks (a drift is smooth; an effect the regression lacks leaves steps)."""
    F = record.force
    if F is None or len(record) < DRIFT_MIN_SAMPLES:
        return []
    t, x, v, a = record.time, record.displacement, record.velocity, record.acceleration
    tau = (t - t[0]) / max(record.duration, 1e-300) - 0.5
    vmax = float(np.max(np.abs(v))) or 1.0
    u = record.control
    un = u / float(np.max(np.abs(u))) if np.any(u != 0) else np.zeros_like(u)
    vn = v / vmax
    xs = (x - x.mean()) / (float(np.ptp(x)) or 1.0)
    amax = float(np.max(np.abs(a))) or 1.0
    cols = [np.ones_like(t), tau]
    odd = [np.sign(v), np.tanh(vn / 0.003), np.tanh(vn / 0.03), vn, vn * np.abs(vn), np.sign(v) * np.sqrt(np.abs(vn))]
    for g in odd:
        cols += [g, g * un, g * un**2, g * tau]
    cols += [xs, xs**2, a / amax]
    A = np.column_stack(cols)
    coef = np.linalg.lstsq(A.T @ A, A.T @ F, rcond=None)[0]  # normal equations: 30 columns, fast
    r = F - A @ coef
    rms = float(np.sqrt(np.mean((F - F.mean()) ** 2)))
    if rms == 0:
        return []
    drift = float(coef[1])  # change over the whole record, [N]
    # standard error with the residual's correlation: n / (1 + 2 sum of its autocorrelation up to its first zero)
    n_eff = len(record) / _correlation_length(r)
    se = float(np.std(r)) / (np.std(tau) * math.sqrt(n_eff))
    # a drift is smooth: what the fit leaves in twelve consecutive blocks scatters little about it, where a physical
    # effect the regression lacks (a compressible column after a field step) leaves steps of either sign
    blocks = np.array([b.mean() for b in np.array_split(r, 12)])
    se_blocks = float(np.std(blocks)) / (np.std(np.linspace(-0.5, 0.5, 12)) * math.sqrt(12))
    found = abs(drift) > DRIFT_FRACTION * rms and abs(drift) > 4 * se and abs(drift) > 10 * se_blocks
    drifting = found
    parts = []
    if drifting:
        parts.append(
            f"the force drifts by {drift:+.3g} N over the record ({100 * abs(drift) / rms:.2g} % of its RMS), "
            "a trend no velocity, displacement or acceleration term explains: a load cell warming or "
            "creeping"
        )
    offset = None
    if opt.expected_mean_force is not None:
        offset = float(coef[0]) - float(opt.expected_mean_force)
        offset_se = float(np.std(r)) / math.sqrt(n_eff)
        if abs(offset) > DRIFT_FRACTION * rms and abs(offset) > 4 * offset_se:
            parts.append(
                f"the force is offset by {offset:+.3g} N from the {opt.expected_mean_force:.3g} N the damper "
                "should show at mid-stroke and rest"
            )
            found = True
    if not found:
        return []
    msg = "; ".join(parts) + ": remove it (or fit an offset) before judging gas_spring or viscous_heating"
    return [
        Finding(
            "force_offset_drift",
            msg,
            record.name,
            f"t = {t[0]:.4g}-{t[-1]:.4g} s, the whole record",
            unsafe_for=("gas_spring", "viscous_heating"),
        )
    ]


#: A displacement grid coarser than this fraction of the stroke is always reported.
QUANTIZATION_FRACTION = 1e-4


def _quantized_displacement(record: Measurement, opt: _Options) -> list[Finding]:
    """``quantized_displacement``: the displacement on a grid (:func:`_grid_step`) that matters."""
    x = record.displacement
    q = _grid_step(x)
    if q is None:
        return []
    # report a grid that matters: coarser than 1e-4 of the stroke (a 13-bit converter over the stroke), or its
    # rounding (q / sqrt 12) at least half of the displacement's noise
    noise = _noise_level(x)
    stroke = float(np.ptp(x))
    if q < QUANTIZATION_FRACTION * stroke and (q / math.sqrt(12) < 0.5 * noise or q < 1e-6 * stroke):
        return []
    dt = record.duration / (len(record) - 1)
    msg = (
        f"the displacement lies on a grid of {q * 1e6:.3g} um steps ({q / float(np.ptp(x)):.2g} of the stroke): "
        f"the velocity derived from it carries a rounding noise of about {q / dt / math.sqrt(6):.3g} m/s per "
        "two-point difference, which sets the error floor at low sample rates"
    )
    return [Finding("quantized_displacement", msg, record.name, f"whole record, step {q * 1e6:.3g} um")]


Detector = Callable[[Measurement, _Options], list[Finding]]
#: kind -> detector (``record, options -> findings``); ``non_monotonic_time`` is found on arrays only
#: (:func:`find_time_problems`).
DETECTORS: dict[str, Detector] = {
    "clipped": _clipped,
    "saturated_displacement": _saturated_displacement,
    "smoothed": _smoothed,
    "channel_skew": _channel_skew,
    "time_gap": _time_gap,
    "force_offset_drift": _force_offset_drift,
    "quantized_displacement": _quantized_displacement,
}


def find_time_problems(time, *, record: str = "") -> list[Finding]:
    """``non_monotonic_time`` and ``time_gap`` findings of a time column given as an array (seconds).

    A :class:`~erdesign.data.measurement.Measurement` (and the measurement CSV reader) refuses time that does not
    increase strictly, so that finding is made here, on the arrays a caller is about to hand to
    :meth:`~erdesign.data.measurement.Measurement.from_arrays`; gaps are found on both.

    >>> [f.kind for f in find_time_problems([0.0, 0.1, 0.2, 0.2, 0.3, 1.3, 1.4])]
    ['non_monotonic_time', 'time_gap']
    """
    t = np.asarray(time, dtype=float)
    if t.ndim != 1:
        raise ValueError(f"time: expected a 1-D array, got shape {t.shape}")
    out: list[Finding] = []
    if t.size < 3:
        return out
    steps = np.diff(t)
    bad = np.flatnonzero(steps <= 0)
    if bad.size:
        first = int(bad[0]) + 1
        back = int(np.count_nonzero(steps < 0))
        same = int(np.count_nonzero(steps == 0))
        msg = (
            f"time does not increase at {bad.size} samples ({back} going back, {same} repeated), first at sample "
            f"{first} ({t[first - 1]:g} s then {t[first]:g} s): rows out of order, a restarted clock or joined "
            "files; sort or split the record before any fit"
        )
        out.append(
            Finding("non_monotonic_time", msg, record, f"sample {first} (t = {t[first]:.4g} s), {bad.size} samples")
        )
    positive = steps[steps > 0] if bad.size else steps
    if positive.size == 0:
        return out
    if float(positive.max()) <= GAP_FACTOR * float(positive.min()):
        return out  # no step beyond GAP_FACTOR x the least, so none beyond it x the median (found without sorting)
    dt = float(np.median(positive))
    gaps = np.flatnonzero(steps > GAP_FACTOR * dt)
    if gaps.size:
        missing = float(np.sum(steps[gaps] - dt))
        listed = ", ".join(f"{t[g]:.4g}-{t[g + 1]:.4g} s" for g in gaps[:3]) + (" ..." if gaps.size > 3 else "")
        msg = (
            f"the time column has {gaps.size} hole{'s' if gaps.size > 1 else ''} ({missing:.3g} s missing, "
            f"about {int(round(missing / dt))} samples at the {dt:.3g} s step): derivatives and time-stepped "
            "effects are not continuous across a hole; fit the pieces as separate records"
        )
        out.append(Finding("time_gap", msg, record, listed))
    return out


def find_data_problems(
    record: Measurement, *, exclude_clipped: bool | None = None, expected_mean_force: float | None = None
) -> list[Finding]:
    """The data-quality findings of a record, in the order of :data:`FINDING_KINDS`.

    Parameters
    ----------
    record : Measurement
        The record as read (not thinned: the detectors need every sample).
    exclude_clipped : bool or None
        None: clipped force samples are excluded when the detector is sure (an unquantised extreme repeated, or a
        quantised one piled up far beyond its neighbour level); True: also where it is unsure (``--exclude-clipped``);
        False: never (the finding is still reported).
    expected_mean_force : float, optional
        The force the damper should show at mid-stroke and rest, [N] (0 for a double-ended damper without preload,
        the gas preload for one with an accumulator); when given, an offset from it is a ``force_offset_drift``
        finding.  Without it only a drift is (a constant offset cannot be told from a gas preload by the record).

    Returns
    -------
    list of Finding
    """
    if not isinstance(record, Measurement):
        raise ErdesignError(f"record: expected a Measurement, got {type(record).__name__}")
    if not (exclude_clipped is None or isinstance(exclude_clipped, (bool, np.bool_))):  # 'yes', 1: a ValueError
        raise ErdesignError(
            f"exclude_clipped: must be None, True or False, got {' '.join(repr(exclude_clipped).split())[:60]}"
        )
    opt = _Options(exclude_clipped, None if expected_mean_force is None else float(expected_mean_force))
    out: list[Finding] = []
    for kind in FINDING_KINDS:
        detector = DETECTORS.get(kind)
        if detector is not None:
            out += detector(record, opt)
    return out
