r"""The noise floor a record supports: the load cell's noise, found where the record shows it, and what the motion
channel adds.

A model that is exactly right still leaves a residual.  This module estimates it once per record, from the record
alone (:func:`estimate_noise_floor`), as a :class:`NoiseFloor`:

.. math::
    \text{ESR}_\text{floor} = \underbrace{\frac{n_k\,\sigma_F^2}{\sum_{i\in k}(F_i-\bar F_k)^2}}_{\texttt{esr}}
    + \underbrace{\frac{\sum_{i\in k}\bigl[(\partial F/\partial v)_i^2\,\sigma_v^2
                                        + (\partial F/\partial a)_i^2\,\sigma_a^2\bigr]}
                       {\sum_{i\in k}(F_i-\bar F_k)^2}}_{\texttt{motion\_esr}}

over the samples :math:`k` of a mask (those a diagnosis judges).  The noise is read on those samples only (a
clipped sample repeats its neighbour's value exactly and would pass for a noise-free one): a cycle pair counts when
both its samples are in the mask, a still segment is made of masked samples, and the spectrum is taken on the
longest unbroken stretch of them (the note says which).  :math:`\sigma_F` is the load cell's noise as it
is in the record (its variance is what an exact model leaves); :math:`\sigma_v`, :math:`\sigma_a` the noise of the
velocity and acceleration derived from the displacement (:func:`motion_noise`), propagated to the force through the
caller's model (the sensitivities; this package imports no model).  The two noises are independent (the load cell
and the displacement transducer), and the velocity and acceleration noise at one sample are uncorrelated (an odd
and an even zero-phase filter of the same white noise), hence the sum of squares.

**Where the force noise is read** (one method per record, the first that applies):

1. ``"given"`` - the user's figure (``--force-noise "5 N"``).
2. ``"still segment"`` - a stretch of at least :data:`MIN_STILL` samples where the displacement and the control
   stay constant within their noise: the force's spread there (a linear trend per stretch removed, 5-sigma
   clipped) is the load cell alone, with no signal to mistake for noise and no assumption on the noise's spectrum.
3. ``"repeated cycles"`` - a periodic programme (the displacement and control repeat after one period, on at
   least half the samples): the difference of adjacent cycles at the same phase cancels the signal and any slow drift
   (heating); its robust spread (median absolute deviation, so that the timing jitter of the force jumps at the
   reversals does not count) over :math:`\sqrt{2}` is the noise.  A period that is not a whole number of samples
   is met by linear interpolation, whose effect on white noise is divided out exactly.
4. ``"spectrum above the excited band"`` - the force's power spectral density (Welch, median averaging) above the
   band the motion and the control excite (from :math:`5\,f_e`, :math:`f_e` the frequency below which 99 % of
   the velocity's and 90 % of the control's variance lie: a yield-stress force holds harmonics of the motion far
   above it).
   Isolated fast events (force jumps at the reversals, a clipped stretch), whose spectrum falls only as
   :math:`1/f^2` and would hide the noise at every frequency, are taken out first (:func:`_dejumped_spectrum`).
   The noise is the lowest flat plateau (a run of log-spaced bands within a factor :data:`FLAT` of each other
   and a log-log slope below :data:`MAX_SLOPE`, over at least :data:`PLATEAU_SPAN` in frequency); the variance
   is the plateau's level times its upper frequency plus the spectrum above it,
   :math:`\sigma_F^2 = N_0 f_p + \int_{f_p}^{f_s/2} P\,df`, which is :math:`N_0 f_s/2` for white noise and
   the variance of the noise as recorded on a low-passed (anti-aliased) channel whose plateau ends before the
   Nyquist frequency.
   Without a plateau the spectrum still bounds the noise: at most white at the lowest level of the pass band
   above the excited band (below the knee of a roll-off).  On a low-passed channel (a roll-off steeper than any
   force, :data:`ROLL_OFF`) that bound is taken, and the note says it is one.
5. ``"fourth differences"`` - the robust spread of the force's fourth differences
   (:func:`erdesign.data.noise.force_noise`) on a channel that is not low-passed and shows no plateau (force
   jumps faster than the sampling hide it), capped by the spectrum's bound.

The order goes from the methods that need no assumption about the noise (nothing moves; the signal repeats) to
those that assume it white (the spectrum extrapolates the plateau's level into the excited band) and those that
also assume the signal smooth over five samples (fourth differences: fast force changes, a record sampled a few
times per force transient or a thinned copy of one, are taken for noise; a low-passed channel hides its noise from
them).  The estimate is made on the full-rate record, before any thinning.

The displacement noise includes its digitisation: a displacement on a grid of step :math:`q` has noise at least
:math:`q/\sqrt{12}` (:func:`quantisation_step`), which at low sample rates sets the floor through the velocity.

Examples
--------
>>> import numpy as np
>>> from erdesign.data.measurement import Measurement
>>> rng = np.random.default_rng(2); t = np.arange(2000) / 500.0
>>> x = 0.01 * np.sin(2 * np.pi * 2 * t); F = 800 * np.tanh(20 * np.cos(2 * np.pi * 2 * t))
>>> floor = estimate_noise_floor(Measurement.from_arrays(t, x, F + 8 * rng.standard_normal(t.size)))
>>> floor.method, bool(0.8 < floor.sigma_force / 8 < 1.2)
('repeated cycles', True)

References
----------
Welch (1967), "The use of fast Fourier transform for the estimation of power spectra", IEEE Transactions on Audio
and Electroacoustics 15(2), 70-73 (the averaged periodogram; :func:`scipy.signal.welch`).  Widrow and Kollar
(2008), *Quantization Noise*, Cambridge University Press, chapter 4 (the digitisation error of step :math:`q`:
uniform, variance :math:`q^2/12`, white while the signal crosses several steps between samples).
"""

from __future__ import annotations

import math
import warnings
import weakref
from dataclasses import dataclass

import numpy as np

from ..errors import ErdesignError, PlausibilityWarning
from .measurement import Measurement, _noise_level, derivatives
from .noise import _ACCELERATION_CACHE, EDGE_FRACTION, velocity_noise

__all__ = [
    "still_samples",
    "NoiseFloor",
    "estimate_noise_floor",
    "motion_noise",
    "quantisation_step",
    "displacement_noise_level",
    "force_noise_from_spectrum",
    "force_noise_from_cycles",
    "force_noise_from_still_segment",
    "METHODS",
    "MIN_STILL",
    "FLAT",
    "PLATEAU_SPAN",
    "MAX_SLOPE",
    "ROLL_OFF",
    "HARMONIC_MARGIN",
]

#: The methods, in order of preference (module notes).
METHODS = ("given", "still segment", "repeated cycles", "spectrum above the excited band", "fourth differences")
#: Fewest samples at rest for a still segment (the spread of 300 samples is known to about 4 %).
MIN_STILL = 300
#: Largest ratio between the band levels of a flat plateau of the force spectrum.
FLAT = 2.0
#: Smallest ratio of upper to lower frequency of a plateau.
PLATEAU_SPAN = 1.4
#: Largest log-log slope of a plateau (white noise: 0; the harmonics of force jumps: -2).
MAX_SLOPE = 0.5
#: Log-log slope of the spectrum below which it is a filter's roll-off (a Butterworth filter of order 4: -8, run
#: forwards and backwards: -16), steeper than a force: a jump's harmonics fall as -2, a kink's as -4.
ROLL_OFF = -8.0
#: The search for a plateau starts at this multiple of the excited band's upper frequency.
HARMONIC_MARGIN = 5.0


@dataclass(frozen=True)
class NoiseFloor:
    """The noise floor of one record: the force noise, how it was found, and the ESR it and the motion leave.

    Attributes
    ----------
    sigma_force : float
        White-equivalent load-cell noise, [N]: its variance is that of the force noise as recorded.
    method : str
        How :attr:`sigma_force` was found, one of :data:`METHODS`.
    esr : float
        ESR the force noise alone leaves on the samples of the mask, [-].
    motion_esr : float
        ESR the velocity and acceleration noise add through the model's sensitivities, [-] (0 without them).
    sigma_velocity, sigma_acceleration : float
        Noise of the derived velocity [m/s] and acceleration [m/s^2] (0 when not computed).
    sigma_displacement : float
        Displacement noise taken, [m]: fourth differences, or the digitisation step over sqrt(12) where it dominates.
    note : str
        What the estimate rests on (the plateau's band, the segment, the period; a missing plateau).
    """

    sigma_force: float
    method: str
    esr: float
    motion_esr: float = 0.0
    sigma_velocity: float = 0.0
    sigma_acceleration: float = 0.0
    sigma_displacement: float = 0.0
    note: str = ""

    def total(self) -> float:
        """The whole floor, :attr:`esr` + :attr:`motion_esr`, [-]."""
        return float(self.esr + self.motion_esr)

    def on(self, record: Measurement, mask=None, *, sensitivity=None) -> NoiseFloor:
        """The same noise levels judged on other samples: a thinned copy of the record, another mask.

        The noise is estimated once, on the full-rate record (:func:`estimate_noise_floor`); a diagnosis that
        analyses a thinned copy takes the ESRs there with this, so that one record has one floor.  Without
        ``sensitivity`` the motion's share is 0.

        Examples
        --------
        >>> t = np.arange(4000) / 1000.0; F = 1000 * np.sin(2 * np.pi * t)
        >>> rec = Measurement.from_arrays(t, 0.01 * np.cos(2 * np.pi * t), F)
        >>> floor = estimate_noise_floor(rec, force_noise="10 N")
        >>> thinned = floor.on(rec.select(slice(None, None, 8)))
        >>> thinned.sigma_force, round(thinned.esr / floor.esr, 2)
        (10.0, 1.0)
        """
        F = record.require_force()
        k = _mask(mask, F.size)
        esr, motion = _esrs(F, k, self.sigma_force, self.sigma_velocity, self.sigma_acceleration, sensitivity)
        return NoiseFloor(
            self.sigma_force,
            self.method,
            esr,
            motion,
            self.sigma_velocity,
            self.sigma_acceleration,
            self.sigma_displacement,
            self.note,
        )


# ----------------------------------------------------------------------------------------------------- helpers


def _uniform(t: np.ndarray) -> bool:
    """Regular sampling: every time within 0.3 steps of a uniform grid (a time column printed with few digits,
    0.3 ms +- 0.05 ms at 3 kHz, is regular; a gap or a drifting clock is not)."""
    if t.size < 2:
        return False
    dt = (t[-1] - t[0]) / (t.size - 1)
    return dt > 0 and bool(np.max(np.abs(t - t[0] - dt * np.arange(t.size))) <= 0.3 * dt)


def quantisation_step(x) -> float:
    """The digitisation step of a channel, [its unit]: the smallest gap between its values when every gap is a whole
    multiple of it (within 2 %, for 90 % of the gaps), else 0.

    Examples
    --------
    >>> quantisation_step(np.round(np.sin(np.linspace(0, 6, 500)) / 5e-3) * 5e-3)
    0.005
    >>> quantisation_step(np.sin(np.linspace(0, 6, 500)))
    0.0
    """
    x = np.asarray(x, dtype=float)
    levels = np.unique(x[np.isfinite(x)])
    if levels.size < 3:
        return 0.0
    gaps = np.diff(levels)
    gaps = gaps[gaps > 1e-9 * (levels[-1] - levels[0])]  # below: round-off of a unit conversion
    if gaps.size < 2:
        return 0.0
    q = float(gaps.min())
    ratio = gaps / q
    if np.mean(np.abs(ratio - np.round(ratio)) <= 0.02) < 0.9:
        return 0.0
    # the smallest gap is one step; refine over all the single-step gaps
    return float(round(float(np.median(gaps[np.round(ratio) == 1])), 15))


def displacement_noise_level(x) -> float:
    r"""Noise of a displacement channel, [its unit]: the fourth-difference estimate, or :math:`q/\sqrt{12}` when
    the channel is digitised in steps :math:`q` (:func:`quantisation_step`) and that is within 1.5 times it.

    The fourth differences of a digitisation error (uniform, lighter-tailed than a Gaussian) read its median
    absolute deviation as about 1.25 times its standard deviation, and a slow staircase as no noise at all: where
    the digitisation dominates, its known variance :math:`q^2/12` is taken instead.

    Examples
    --------
    >>> t = np.arange(2000) / 100.0; x = np.round(5e-3 * np.sin(2 * np.pi * 0.7 * t) / 5e-6) * 5e-6
    >>> round(float(displacement_noise_level(x) / (5e-6 / np.sqrt(12))), 6)
    1.0
    """
    x = np.asarray(x, dtype=float)
    s4 = _noise_level(x)
    sq = quantisation_step(x) / math.sqrt(12.0)
    return float(sq if s4 <= 1.5 * sq else s4)


_MOTION_CACHE: dict[int, tuple[weakref.ref, tuple[float, float, float]]] = {}


def motion_noise(record: Measurement) -> tuple[float, float, float]:
    r"""Noise of the displacement [m], the derived velocity [m/s] and the derived acceleration [m/s^2].

    :math:`\sigma_x` from :func:`displacement_noise_level` (the digitisation step counts).  It is propagated through
    :func:`erdesign.data.measurement.derivatives` as :func:`erdesign.data.noise.velocity_noise` does: the record
    is differentiated again with fresh white noise of that level added (fixed seed) and the RMS change of the
    velocity and acceleration is taken away from the ends (:data:`erdesign.data.noise.EDGE_FRACTION`).  A measured
    velocity column keeps its own noise (fourth differences).  Cached per record.

    Examples
    --------
    >>> t = np.arange(2000) / 100.0; x = np.round(5e-3 * np.sin(2 * np.pi * 0.7 * t) / 5e-6) * 5e-6
    >>> sx, sv, sa = motion_noise(Measurement.from_arrays(t, x))
    >>> round(sx * 1e6, 2), bool(0 < sv < 1e-3)
    (1.44, True)
    """
    key = id(record.displacement)
    hit = _MOTION_CACHE.get(key)
    if hit is not None and hit[0]() is record.displacement:
        return hit[1]
    t, x = np.asarray(record.time, dtype=float), np.asarray(record.displacement, dtype=float)
    sx = displacement_noise_level(x)
    sv = sa = 0.0
    shared = None
    if "velocity" not in record.units and record.velocity_noise is None and sx == _noise_level(x):
        # the same differentiations as velocity_noise's (its noise level and seed): share them, and their cost
        sv = velocity_noise(record)
        hit = _ACCELERATION_CACHE.get(id(record.displacement))
        if hit is not None and hit[0]() is record.displacement and hit[1] == sx:
            shared = hit[2]
    if shared is not None:
        sa = shared
    elif sx > 0 and x.size >= 16:
        rng = np.random.default_rng(12345)
        v1, a1 = derivatives(t, x)
        v2, a2 = derivatives(t, x + sx * rng.standard_normal(x.size))
        edge = min(max(3, int(EDGE_FRACTION * x.size)), x.size // 4)
        inner = slice(edge, x.size - edge)
        sv = float(np.sqrt(np.mean((v2 - v1)[inner] ** 2)))
        sa = float(np.sqrt(np.mean((a2 - a1)[inner] ** 2)))
    if "velocity" in record.units:
        sv = _noise_level(np.asarray(record.velocity, dtype=float))
    out = (float(sx), sv, sa)
    try:
        _MOTION_CACHE[key] = (weakref.ref(record.displacement), out)
    except TypeError:
        pass
    if len(_MOTION_CACHE) > 256:
        for k in [k for k, (ref, _) in _MOTION_CACHE.items() if ref() is None]:
            del _MOTION_CACHE[k]
    return out


def _robust_sigma(d: np.ndarray) -> float:
    """Standard deviation of the Gaussian bulk of ``d`` (median absolute deviation)."""
    return float(np.median(np.abs(d - np.median(d))) / 0.6744897501960817)


# ----------------------------------------------------------------------------------------------- still segment


def _still(record: Measurement, one_sided: bool = False) -> tuple[np.ndarray, float] | None:
    """(True where the piston is at rest, the displacement tolerance [m]) or None for a record too short to tell.
    The window is centred on the sample, or with ``one_sided`` starts or ends at it."""
    from scipy.ndimage import maximum_filter1d, minimum_filter1d

    x = np.asarray(record.displacement, dtype=float)
    n = x.size
    fs = record.sample_rate
    w = int(min(max(64, round(0.2 * fs)), n // 4))
    if w < 16:
        return None
    span = float(np.ptp(x))
    sx = displacement_noise_level(x)
    tol = max(8.0 * sx, 2.0 * quantisation_step(x), 1e-6 * span)

    def steady(y, limit):
        # the window of w samples that starts at i, and the one that ends at i: a sample right after the motion
        # stops (or right before it starts) is at rest on one side
        c = (maximum_filter1d(y, w) - minimum_filter1d(y, w)) <= limit  # centred on i
        h = w // 2
        ahead, behind = np.zeros(n, dtype=bool), np.zeros(n, dtype=bool)
        ahead[: n - h] = c[h:]
        behind[w - 1 - h :] = c[: n - (w - 1 - h)]
        return ahead, behind

    if not one_sided:
        still = (maximum_filter1d(x, w) - minimum_filter1d(x, w)) <= tol
        u = np.asarray(record.control, dtype=float)
        if np.ptp(u) > 0:
            still &= (maximum_filter1d(u, w) - minimum_filter1d(u, w)) <= 1e-6 * float(np.max(np.abs(u)))
        return still, tol
    ahead, behind = steady(x, tol)
    u = np.asarray(record.control, dtype=float)
    if np.ptp(u) > 0:
        ua, ub = steady(u, 1e-6 * float(np.max(np.abs(u))))
        ahead, behind = ahead & ua, behind & ub
    return ahead | behind, tol


def still_samples(record: Measurement) -> np.ndarray:
    """True on the samples where the piston is at rest: over a window of ``max(64, 0.2 s)`` samples that starts or
    ends at the sample, the displacement stays within eight times its noise (or two digitisation steps) and the
    control does not change.

    There the sign of the velocity is unknown whatever the derived velocity says (a derivative filter rings after the
    motion stops), so a yield-stress damper's force is anywhere within its break-away range: diagnosis does not judge
    models there (:mod:`erdesign.diagnosis.records`).

    Examples
    --------
    >>> t = np.arange(3000) / 1000.0; x = np.where(t < 1, 0.0, 0.005 * np.sin(2 * np.pi * (t - 1)))
    >>> still = still_samples(Measurement.from_arrays(t, x))
    >>> bool(still[:850].all()), bool(still[1200:].any())
    (True, False)
    """
    found = _still(record, one_sided=True)
    return np.zeros(len(record), dtype=bool) if found is None else found[0]


def force_noise_from_still_segment(
    record: Measurement, mask=None, *, min_samples: int = MIN_STILL
) -> tuple[float, str] | None:
    """The force's spread where the piston is at rest, [N], and a note; None without such a stretch.

    A sample is at rest when, over a centred window of ``max(64, 0.2 s)`` samples, the displacement stays within
    eight times its noise (or two digitisation steps) and the control does not change; a stretch held at the
    record's largest or smallest displacement is left out (a saturated transducer looks still).  Stretches of at least 64
    samples are pooled when they hold ``min_samples`` together; each has its linear trend removed (a force
    relaxing after the motion stopped), then the RMS is taken with 5-sigma outliers clipped.  The spread of a
    channel that flickers between two digitisation levels is its RMS, not a median deviation (which may be 0).
    Only samples in ``mask`` (default all) count: a clipped sample is not at rest.

    Examples
    --------
    >>> rng = np.random.default_rng(0); t = np.arange(3000) / 1000.0
    >>> x = np.where(t < 1, 0.0, 0.005 * np.sin(2 * np.pi * (t - 1)))
    >>> F = 2000 * np.tanh(1e3 * np.gradient(x, t)) + 3.0 * rng.standard_normal(t.size)
    >>> s, note = force_noise_from_still_segment(Measurement.from_arrays(t, x, F, velocity=np.gradient(x, t)))
    >>> bool(2.7 < s < 3.3)
    True
    """
    F = record.require_force()
    x = np.asarray(record.displacement, dtype=float)
    n = x.size
    if n < min_samples:
        return None
    found = _still(record)
    if found is None:
        return None
    still, tol = found
    span = float(np.ptp(x))
    still = still & _mask(mask, n)
    edges = np.flatnonzero(np.diff(np.concatenate([[0], still.astype(np.int8), [0]])))
    # a stretch held at the record's largest or smallest displacement may be a saturated transducer while the
    # piston moves on: not taken
    top, bottom = float(np.max(x)), float(np.min(x))
    runs = [
        (a, b)
        for a, b in zip(edges[::2], edges[1::2])
        if b - a >= 64 and (span <= 4 * tol or min(top - np.max(x[a:b]), np.min(x[a:b]) - bottom) > tol)
    ]
    if sum(b - a for a, b in runs) < min_samples:
        return None
    residuals = []
    for a, b in runs:
        i = np.arange(b - a, dtype=float)
        seg = F[a:b]
        residuals.append(seg - np.polyval(np.polyfit(i, seg, 1), i))
    r = np.concatenate(residuals)
    keep = np.ones(r.size, dtype=bool)
    for _ in range(3):
        s = float(np.sqrt(np.mean(r[keep] ** 2)))
        new = np.abs(r) <= 5 * s if s > 0 else keep
        if np.array_equal(new, keep):
            break
        keep = new
    s = float(np.sqrt(np.mean(r[keep] ** 2)))
    return s, f"{r.size} samples at rest in {len(runs)} stretch(es) (first at {record.time[runs[0][0]]:.3g} s)"


# ---------------------------------------------------------------------------------------------- repeated cycles


def _lagged_difference(y: np.ndarray, lag: float) -> tuple[np.ndarray, float]:
    """y(i + lag) - y(i) with linear interpolation for a fractional lag, and the variance factor of white noise."""
    m = int(math.floor(lag))
    alpha = lag - m
    if alpha < 1e-6:
        return y[m:] - y[: y.size - m], 2.0
    shifted = (1 - alpha) * y[m:-1] + alpha * y[m + 1 :]
    return shifted - y[: shifted.size], 1.0 + (1 - alpha) ** 2 + alpha**2


def _lagged_inside(k: np.ndarray, lag: float) -> np.ndarray:
    """Whether every sample a lagged difference (:func:`_lagged_difference`) takes is in ``k``: i and i + lag (both
    neighbours of i + lag when it falls between samples)."""
    m = int(math.floor(lag))
    if lag - m < 1e-6:
        return k[m:] & k[: k.size - m]
    return k[m:-1] & k[m + 1 :] & k[: k.size - m - 1]


def force_noise_from_cycles(record: Measurement, mask=None) -> tuple[float, str] | None:
    r"""Force noise from the differences between adjacent cycles of a periodic programme, [N], and a note; None
    when the record is not periodic.

    The period is the dominant one of the displacement, refined by least squares on the lag of the adjacent-cycle
    difference.  Compared are the samples where the displacement repeats within its noise (or a digitisation step)
    and the control repeats; at least 150 such pairs are needed, and half of all pairs one period apart.  A pair
    counts only when every sample it takes (two, three with a fractional period) is in ``mask`` (default all): two
    clipped samples at the same level would otherwise pass for a noise-free pair.  Needs a uniform sampling.

    Examples
    --------
    >>> rng = np.random.default_rng(1); t = np.arange(2500) / 500.0
    >>> x = 0.01 * np.sin(2 * np.pi * 1.3 * t); F = 900 * np.sign(np.cos(2 * np.pi * 1.3 * t))
    >>> s, note = force_noise_from_cycles(Measurement.from_arrays(t, x, F + 5 * rng.standard_normal(t.size)))
    >>> bool(4.5 < s < 5.5)
    True
    """
    from scipy.optimize import minimize_scalar

    from .measurement import _dominant_frequency

    F = record.require_force()
    t = np.asarray(record.time, dtype=float)
    x = np.asarray(record.displacement, dtype=float)
    n = t.size
    if n < 200 or not _uniform(t):
        return None
    dt = (t[-1] - t[0]) / (n - 1)
    f0 = _dominant_frequency(t, x)
    if not f0 > 0:
        return None
    period = 1.0 / (f0 * dt)  # samples
    if n < period + 150 or period < 8:
        return None
    # the dominant frequency is known to about half a Fourier bin: a grid of whole lags over a bin each side,
    # then a fractional refinement around the best
    stride = max(1, n // 4000)

    def cost(L: float) -> float:
        # the smaller 80 % of the squared differences (a start-up transient or a stretch at another amplitude does
        # not pull the period), on at most 4000 pairs
        m, alpha = int(math.floor(L)), L - math.floor(L)
        i = np.arange(0, n - m - 1, stride)
        d2 = ((1 - alpha) * x[i + m] + alpha * x[i + m + 1] - x[i]) ** 2
        keep = int(0.8 * d2.size)
        return float(np.mean(np.partition(d2, keep)[:keep])) if keep > 0 else float(np.mean(d2))

    T = t[-1] - t[0]
    lo, hi = 1.0 / ((f0 + 1.0 / T) * dt), 1.0 / (max(f0 - 1.0 / T, 0.5 * f0) * dt)
    hi = min(hi, n - 150.0)
    if hi <= lo:
        return None
    grid = np.unique(np.round(np.linspace(lo, hi, int(min(400, hi - lo + 2)))))
    L0 = float(grid[int(np.argmin([cost(L) for L in grid]))])
    step = float(grid[1] - grid[0]) if grid.size > 1 else 1.0
    res = minimize_scalar(cost, bounds=(max(L0 - step, 2.0), L0 + step), method="bounded", options={"xatol": 1e-4})
    lag = float(res.x)
    dx, _ = _lagged_difference(x, lag)
    sx = displacement_noise_level(x)
    amp = float(np.sqrt(2.0) * np.std(x))
    tol = max(6.0 * sx, 2.0 * quantisation_step(x), 2e-3 * amp)
    same = np.abs(dx) <= tol
    u = np.asarray(record.control, dtype=float)
    if np.ptp(u) > 0:
        du, _ = _lagged_difference(u, lag)
        same &= np.abs(du) <= 1e-3 * float(np.max(np.abs(u)))
    kept = _lagged_inside(_mask(mask, n), lag)
    same &= kept
    if same.sum() < max(150, 0.5 * kept.sum()):
        return None
    dF, factor = _lagged_difference(F, lag)
    s = _robust_sigma(dF[same]) / math.sqrt(factor)
    return s, (
        f"{int(same.sum())} pairs of samples one period ({lag * dt:.5g} s, {1 / (lag * dt):.4g} Hz) apart "
        "where the motion repeats"
    )


# ------------------------------------------------------------------------------------------------------ spectrum


def _band_top(f: np.ndarray, P: np.ndarray, share: float = 0.99) -> float:
    """Frequency below which ``share`` of the power of a one-sided spectrum lies."""
    c = np.cumsum(P)
    if not c[-1] > 0:
        return 0.0
    return float(f[min(int(np.searchsorted(c, share * c[-1])), f.size - 1)])


def _plateau_level(P: np.ndarray) -> float:
    """Mean level of the bins of a plateau, lines (bins above five times the median) left out: the median alone
    of a spectral estimate's skewed distribution lies about 5 % below its mean."""
    med = float(np.median(P))
    return float(np.mean(P[P <= 5 * med])) if med > 0 else 0.0


def _dejumped_spectrum(F: np.ndarray, fs: float, nper: int) -> tuple[np.ndarray, np.ndarray]:
    r"""One-sided PSD of the force [N^2/Hz] with its isolated fast events (force jumps at reversals, clipped
    stretches) taken out.

    A step of the force is a broadband event (its spectrum falls only as :math:`1/f^2`) that would hide the noise
    at every frequency; in the fourth difference :math:`e = \Delta^4 F` it is a five-sample burst.  The samples of
    :math:`e` beyond six robust standard deviations, with four neighbours each side, are set to zero, the Welch
    spectrum of :math:`e` (median averaging) is scaled by the share of samples kept and divided by the fourth
    difference's gain :math:`(2\sin(\pi f/f_s))^8`.
    """
    from scipy.ndimage import maximum_filter1d
    from scipy.signal import welch

    e = np.diff(F, 4)
    s = _robust_sigma(e)
    bad = (
        maximum_filter1d((np.abs(e - np.median(e)) > 6 * s).astype(np.int8), 9).astype(bool)
        if s > 0
        else np.zeros(e.size, dtype=bool)
    )
    kept = 1.0 - float(bad.mean())
    e = np.where(bad, 0.0, e)
    f, Pe = welch(e, fs=fs, nperseg=nper, detrend="constant", average="median")
    gain = (2 * np.sin(np.pi * f / fs)) ** 8
    P = np.where(gain > 1e-12, Pe / max(kept, 0.5) / np.maximum(gain, 1e-300), np.inf)
    return f, P


def force_noise_from_spectrum(record: Measurement) -> tuple[float | None, float, str, bool]:
    r"""Force noise from the spectrum above the excited band: (sigma or None, upper bound, note, low-passed), [N].

    ``sigma`` is the white-equivalent noise of the lowest flat plateau (module notes); None when the spectrum
    has no plateau (it keeps falling: force transients faster than the
    sampling, or a signal above the noise up to the roll-off).  ``upper bound`` is then what the noise can be at
    most: white at the lowest level of the pass band above the excited band, and as recorded above it (``inf``
    when there is no band above the excited one).  ``low-passed`` says whether the spectrum ends in a roll-off
    steeper than any force (a log-log slope below :data:`ROLL_OFF`: an anti-aliasing or smoothing filter), where
    fourth differences see only what the filter left of the noise.

    Examples
    --------
    >>> rng = np.random.default_rng(3); t = np.arange(20000) / 2000.0
    >>> x = 0.01 * np.sin(2 * np.pi * 1.1 * t) + 0.004 * np.sin(2 * np.pi * 2.9 * t)
    >>> F = 1e4 * np.gradient(x, t) + 2.0 * rng.standard_normal(t.size)
    >>> s, bound, note, lowpassed = force_noise_from_spectrum(Measurement.from_arrays(t, x, F))
    >>> bool(1.8 < s < 2.2), lowpassed
    (True, False)
    """
    from scipy.signal import welch

    F = record.require_force()
    t = np.asarray(record.time, dtype=float)
    n = t.size
    if n < 512 or not _uniform(t):
        return None, math.inf, "too short or unevenly sampled for a spectrum", False
    fs = record.sample_rate
    nyq = fs / 2
    nper = int(min(4096, max(256, 2 ** int(math.floor(math.log2(n / 8))))))
    f, P = _dejumped_spectrum(F, fs, nper)
    df = float(f[1] - f[0])
    _, Pv = welch(np.asarray(record.velocity, dtype=float), fs=fs, nperseg=nper, detrend="linear")
    fe = _band_top(f, Pv)
    u = np.asarray(record.control, dtype=float)
    if np.ptp(u) > 0:
        # a command signal is often a held random sequence whose steps spread a little power to the Nyquist
        # frequency: its band is where 90 % of its variance lies
        fe = max(fe, _band_top(f, welch(u, fs=fs, nperseg=nper, detrend="linear")[1], 0.90))
    f_lo = max(HARMONIC_MARGIN * fe, 4 * fs / nper)
    if f_lo >= 0.8 * nyq:
        return None, math.inf, f"no band above the excited one (up to {fe:.3g} Hz) below {nyq:.4g} Hz", False
    # log-spaced bands, 16 a decade, each of at least 3 bins
    edges = np.geomspace(f_lo, nyq, max(2, int(math.ceil(16 * math.log10(nyq / f_lo)))) + 1)
    bands: list[tuple[float, float, float, int]] = []
    for lo_edge, hi_edge in zip(edges[:-1], edges[1:]):
        k = (f >= lo_edge) & (f < hi_edge) if hi_edge < nyq else (f >= lo_edge)
        if bands and (k.sum() < 3 or bands[-1][3] < 3):
            a0 = bands[-1][0]
            k = k | ((f >= a0) & (f < lo_edge))
            bands[-1] = (a0, hi_edge, float(np.median(P[k])), int(k.sum()))
        elif k.any():
            bands.append((lo_edge, hi_edge, float(np.median(P[k])), int(k.sum())))
    levels = np.array([bd[2] for bd in bands])
    centres = np.log10([math.sqrt(bd[0] * bd[1]) for bd in bands])
    # the pass band ends where the spectrum first falls faster than any force does
    slopes = np.diff(np.log10(np.maximum(levels, 1e-300))) / np.diff(centres) if len(bands) > 1 else np.zeros(0)
    steep = np.flatnonzero(slopes < ROLL_OFF)
    end = int(steep[0]) + 1 if steep.size else len(bands)  # bands[:end] are the pass band
    lowpassed = bool(steep.size) and levels[-1] < 1e-2 * levels[max(end - 1, 0)]
    if not lowpassed:
        end = len(bands)
    best = None
    for i in range(len(bands)):
        lo = hi = levels[i]
        for j in range(i + 1, len(bands)):
            lo, hi = min(lo, levels[j]), max(hi, levels[j])
            if hi > FLAT * lo:
                break
            if bands[j][1] / bands[i][0] >= PLATEAU_SPAN:
                if abs(np.polyfit(centres[i : j + 1], np.log10(levels[i : j + 1]), 1)[0]) > MAX_SLOPE:
                    continue  # still falling: the harmonics of the motion, or a filter's knee
                level = _plateau_level(P[(f >= bands[i][0]) & (f <= bands[j][1])])
                if best is None or level < best[0]:
                    best = (level, bands[i][0], bands[j][1])

    def above(fp: float) -> float:
        return float(np.sum(P[f > fp]) * df)

    # the bound from the pass band below the filter's knee (at 0.75 of the roll-off's start a Butterworth filter of
    # order 4 run both ways keeps 80 % of the power)
    knee = (
        max(1, int(np.searchsorted([bd[1] for bd in bands], 0.75 * bands[end - 1][1], side="right")))
        if lowpassed
        else end
    )
    jmin = int(np.argmin(levels[:knee]))
    bound = math.sqrt(levels[jmin] * bands[jmin][1] + above(bands[jmin][1]))
    band = f"excited band up to {fe:.3g} Hz"
    if best is None:
        where = (
            f"the pass band, up to {bands[end - 1][1]:.4g} Hz where a roll-off begins" if lowpassed else f"{nyq:.4g} Hz"
        )
        return (
            None,
            bound,
            (
                f"no flat plateau above the {band}: the spectrum falls to {where}, at least to "
                f"{levels[jmin]:.3g} N^2/Hz near {bands[jmin][0]:.4g} Hz"
            ),
            lowpassed,
        )
    level, a, b = best
    top = min(b, nyq)
    sigma = math.sqrt(level * top + above(top))
    if top >= 0.95 * nyq:
        where = "to the Nyquist frequency"
    elif lowpassed:
        where = f"to {top:.4g} Hz, where the channel's roll-off begins"
    else:
        where = f"to {top:.4g} Hz"
    return sigma, bound, f"plateau {level:.3g} N^2/Hz from {a:.4g} Hz {where}; {band}", lowpassed


# ------------------------------------------------------------------------------------------------------- the floor


def _given_force_noise(value) -> float:
    if isinstance(value, np.ndarray) and value.ndim == 0 and value.dtype.kind in "iuf":  # np.array(5.0): 5 N
        value = value.item()
    if isinstance(value, (bool, np.bool_)):
        raise ErdesignError(f"force_noise: must be a force (e.g. '5 N') or a number of newtons, got {value!r}")
    if isinstance(value, (int, float, np.integer, np.floating)):
        s = float(value)
    else:
        from ..units import to_si

        s = float(to_si(value, "N", "force_noise"))
    if not (math.isfinite(s) and s >= 0):
        raise ErdesignError(f"force_noise: must be finite and >= 0 N, got {value!r}")
    return s


def _sensitivity(sensitivity, n: int) -> tuple[np.ndarray, np.ndarray]:
    if isinstance(sensitivity, np.ndarray) and sensitivity.ndim == 1:
        sensitivity = (sensitivity, None)
    try:
        dv, da = sensitivity
    except (TypeError, ValueError):
        raise ErdesignError(
            "sensitivity: must be a pair (dF/dv [N s/m], dF/da [N s^2/m]) of arrays of the "
            f"record's length {n} (or None for either), got {type(sensitivity).__name__}"
        ) from None
    out = []
    for name, s in (("dF/dv", dv), ("dF/da", da)):
        arr = (
            np.zeros(n)
            if s is None
            else np.broadcast_to(np.asarray(s, dtype=float), (n,))
            if np.ndim(s) == 0
            else np.asarray(s, dtype=float)
        )
        if arr.shape != (n,) or not np.all(np.isfinite(arr)):
            raise ErdesignError(
                f"sensitivity: {name} must be finite with one value per sample ({n}), got shape {np.shape(s)}"
            )
        out.append(arr)
    return out[0], out[1]


def estimate_noise_floor(record: Measurement, mask=None, *, force_noise=None, sensitivity=None) -> NoiseFloor:
    r"""The noise floor the record supports (module notes): the load cell's noise and what the motion adds.

    Parameters
    ----------
    record : Measurement
        The full-rate record, with a force (thinning before this hides the noise under the signal).
    mask : bool array, optional
        The samples the ESRs are taken on (those a diagnosis judges) and the only ones the noise is read on (clipped
        samples left out); default all.
    force_noise : pint.Quantity, str or float, optional
        The load cell's noise when known (``"5 N"``; a plain number is in newtons): method ``"given"``.
    sensitivity : pair of arrays, optional
        :math:`\partial F/\partial v` [N s/m] and :math:`\partial F/\partial a` [N s^2/m] of the caller's model on
        the record's samples (either may be None); gives :attr:`NoiseFloor.motion_esr`.

    Returns
    -------
    NoiseFloor

    Notes
    -----
    One number per record: it depends on the record and, through the sensitivity only, on a model.  Cost: a few
    Welch spectra and lagged differences; with a sensitivity also two differentiations of the displacement
    (:func:`motion_noise`, cached per record).

    Examples
    --------
    >>> rng = np.random.default_rng(0); t = np.arange(4000) / 1000.0
    >>> x = 0.005 * np.sin(2 * np.pi * 1.5 * t); F = 3e4 * np.gradient(x, t) + 4 * rng.standard_normal(t.size)
    >>> rec = Measurement.from_arrays(t, x, F)
    >>> estimate_noise_floor(rec, force_noise="4 N").method
    'given'
    >>> nf = estimate_noise_floor(rec, sensitivity=(np.full(t.size, 3e4), None))
    >>> nf.method, bool(nf.total() > nf.esr > 0)
    ('repeated cycles', True)
    """
    if not isinstance(record, Measurement):
        raise ErdesignError(f"record: must be a Measurement, got {type(record).__name__}")
    F = record.require_force()
    n = F.size
    k = _mask(mask, n)
    note = ""
    if force_noise is not None:
        sigma, method = _given_force_noise(force_noise), "given"
        spread = float(np.std(F[k])) if k.any() else 0.0
        if sigma > spread:  # '5 kN' for '5 N': a floor above every residual, so nothing is ever missing
            warnings.warn(
                f"force_noise: {sigma:.4g} N is more than the spread of the force itself ({spread:.4g} N standard "
                f"deviation) in {record.name or 'the record'}: no residual can rise above such a floor; is the unit "
                "right?",
                PlausibilityWarning,
                stacklevel=2,
            )
    else:
        found = force_noise_from_still_segment(record, k)
        method = "still segment"
        if found is None:
            found, method = force_noise_from_cycles(record, k), "repeated cycles"
        if found is None:
            # the spectrum needs an unbroken stretch: the longest run of samples in the mask
            stretch, part = record, ""
            if not k.all():
                a, b = _longest_run(k)
                stretch = record.select(slice(a, b))
                part = (
                    f"on the longest stretch of samples kept, {record.time[a]:.4g}-{record.time[b - 1]:.4g} s "
                    f"({b - a} of {n} samples): "
                )
            s_spec, bound, note, lowpassed = force_noise_from_spectrum(stretch)
            note = part + note
            F4 = np.asarray(stretch.force, dtype=float)
            if s_spec is not None:
                found, method = (s_spec, note), "spectrum above the excited band"
            else:
                s4 = _noise_level(F4)
                if lowpassed:  # fourth differences see what the filter left of the noise: use the bound
                    found, method = (
                        (
                            bound,
                            note + "; a low-passed channel: the noise taken at that level, an "
                            f"upper bound (fourth differences {s4:.3g} N)",
                        ),
                        "spectrum above the excited band",
                    )
                elif bound < s4:
                    found, method = (
                        (
                            bound,
                            note + "; taken as white at that level: an upper bound, below the "
                            f"fourth differences' {s4:.3g} N",
                        ),
                        "spectrum above the excited band",
                    )
                else:
                    found, method = (
                        (s4, note + f"; fourth differences {s4:.3g} N, below the spectrum's bound {bound:.3g} N"),
                        "fourth differences",
                    )
        sigma, note = found
    sx = sv = sa = 0.0
    if sensitivity is not None:
        _sensitivity(sensitivity, n)  # checked before the differentiations
        sx, sv, sa = motion_noise(record)
    esr, motion = _esrs(F, k, float(sigma), sv, sa, sensitivity)
    return NoiseFloor(float(sigma), method, esr, motion, float(sv), float(sa), float(sx), note)


def _longest_run(k: np.ndarray) -> tuple[int, int]:
    """Start and end (exclusive) of the longest run of True in ``k`` ((0, 0) when there is none)."""
    edges = np.flatnonzero(np.diff(np.concatenate([[0], k.astype(np.int8), [0]])))
    if edges.size == 0:
        return 0, 0
    starts, ends = edges[::2], edges[1::2]
    i = int(np.argmax(ends - starts))
    return int(starts[i]), int(ends[i])


def _mask(mask, n: int) -> np.ndarray:
    if mask is None:
        return np.ones(n, dtype=bool)
    k = np.asarray(mask)
    if k.dtype != bool or k.shape != (n,):
        raise ErdesignError(
            f"mask: must be a boolean array of the record's length {n}, got {k.dtype} of shape {k.shape}"
        )
    return k


def _esrs(F: np.ndarray, k: np.ndarray, sigma: float, sv: float, sa: float, sensitivity) -> tuple[float, float]:
    """(ESR of the force noise, ESR the motion adds) on the samples ``k``."""
    Fk = F[k]
    ss = float(np.sum((Fk - Fk.mean()) ** 2)) if Fk.size else 0.0
    if not ss > 0:
        return 0.0, 0.0
    esr = min(Fk.size * sigma**2 / ss, 1.0)
    motion = 0.0
    if sensitivity is not None:
        dv, da = _sensitivity(sensitivity, F.size)
        motion = min(float(np.sum(dv[k] ** 2 * sv**2 + da[k] ** 2 * sa**2)) / ss, 1.0)
    return float(esr), float(motion)
