r"""Measured (or simulated) damper records: CSV files with units in the header -> SI arrays; derivatives.

File format (docs/file_formats.md): the first line that is not a ``#`` comment names the columns, each
with its unit in square brackets; then one numeric row per sample.  Column order is free.

=====================  ===========================================================================
column                 unit (any pint unit of the right dimension)
=====================  ===========================================================================
``time``               required, a time; strictly increasing
``displacement``       required, a length
``force``              required, a force
``field``              optional control: V/m, kV/mm, A/m, kA/m or T
``current``            optional control: coil current, A (MR)
``voltage``            optional control: command voltage of a current driver, V
``velocity``           optional, a velocity (else derived from the displacement)
``temperature``        optional, a temperature (degC, K, degF)
=====================  ===========================================================================

At most one control column; none means zero field.  Cells are separated by ',' or, when the header line has ';'
between its cells, by ';' (a spreadsheet's "CSV" in a decimal-comma locale), whose numbers may then have decimal
commas.  Every problem is a :class:`MeasurementError` naming the line and the column.

Derivatives (:func:`derivatives`): Fourier filtering of the significant harmonics for records periodic in their
dominant frequency (Kamath and Wereley 1997, section II, differentiated analytically), an adaptive zero-phase
low-pass plus fourth-order central differences for all other records (sweeps, random, earthquake-like motion).
tests/test_measurement.py shows the first does at least as well as the method of Kamath and Wereley (1997) on noisy
sines and the second
stays accurate on noisy non-periodic records.
"""

from __future__ import annotations

import codecs
import csv
import functools
import io
import math
import os
import re
import sys
import unicodedata
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..errors import ErdesignError, ErdesignWarning, did_you_mean
from ..examples import bundled_file
from ..fluid import CONTROL_UNITS
from ..limits import MAX_CELL_CHARS, MAX_RECORD_BYTES, MAX_RECORD_ROWS, decode_text, is_path_like, read_input_bytes
from ..units import Q_, clean_value_text, dimension_name, parse_unit, ureg

__all__ = [
    "Measurement",
    "MeasurementError",
    "read_measurement",
    "write_measurement",
    "derivatives",
    "clipped_samples",
    "check_record",
    "check_against_damper",
    "COLUMNS",
    "CONTROL_COLUMNS",
    "WARNED_AT_READ",
]


class MeasurementError(ErdesignError):
    """A measurement file or record is malformed; the message names the line and column."""


#: Column name -> SI unit (its dimension is the one required).
COLUMNS = {
    "time": "s",
    "displacement": "m",
    "force": "N",
    "velocity": "m/s",
    "temperature": "K",
}
#: Control columns: name -> kinds of control (keys of erdesign.fluid.CONTROL_UNITS) it may hold.
CONTROL_COLUMNS = {
    "field": ("electric field", "magnetic field", "magnetic flux density"),
    "current": ("current",),
    "voltage": ("voltage",),
}
_HEADER = re.compile(r"^\s*([^\[\]]*?)\s*\[(.+)\]\s*$")


@dataclass(frozen=True)
class Measurement:
    """A damper record in SI units: time, displacement, force, control and the derived velocity / acceleration.

    Build it with :func:`read_measurement` or :meth:`Measurement.from_arrays`.  ``force`` may be None for a pure
    motion record (an input to simulate).

    Attributes
    ----------
    time : ndarray
        [s], strictly increasing.
    displacement : ndarray
        x, [m].
    force : ndarray or None
        F, [N].
    velocity : ndarray
        v, [m/s]: the measured column if there was one, else derived (:func:`derivatives`).
    acceleration : ndarray
        a, [m/s^2], derived.
    control : ndarray
        The control in the SI unit of its kind (V/m, A/m, T, A or V); zeros when the record has none.
    control_kind : str or None
        Kind of control (a key of :data:`erdesign.fluid.CONTROL_UNITS`); None when the record has no control column.
    temperature : ndarray or None
        [K].
    name : str
        Where it came from (file name).
    """

    time: np.ndarray
    displacement: np.ndarray
    force: np.ndarray | None
    velocity: np.ndarray
    acceleration: np.ndarray
    control: np.ndarray
    control_kind: str | None = None
    temperature: np.ndarray | None = None
    name: str = ""
    units: dict = field(default_factory=dict)
    """Units the columns were given in (for display and for writing back)."""
    velocity_noise: float | None = None
    """Standard deviation of the noise of :attr:`velocity`, [m/s], when known (a thinned copy of a record keeps the
    value of the full record); None: estimate it from the record (:func:`erdesign.data.noise.velocity_noise`)."""

    @classmethod
    def from_arrays(
        cls,
        time,
        displacement,
        force=None,
        *,
        control=None,
        control_kind=None,
        velocity=None,
        temperature=None,
        name: str = "",
        window: int | None = None,
        units: dict[str, str] | None = None,
    ) -> "Measurement":
        """A record from SI arrays; velocity and acceleration are derived when not given.

        Parameters
        ----------
        time, displacement : array
            [s], [m].
        force : array, optional
            [N].
        control : array or float, optional
            Control in SI units of ``control_kind``.
        control_kind : str, optional
            A key of :data:`erdesign.fluid.CONTROL_UNITS`; required with ``control``.
        velocity : array, optional
            Measured velocity [m/s]; otherwise derived.
        temperature : array, optional
            [K].
        window : int, optional
            Savitzky-Golay window (samples) for the derivatives; default from the dominant period.
        units : dict, optional
            Units the columns were given in (column name -> unit; for display and for writing back).
        """
        t = _as_1d(time, "time", unit="s")
        n = t.size
        x = _as_1d(displacement, "displacement", n, unit="m")
        F = None if force is None else _as_1d(force, "force", n, unit="N")
        if control is not None and control_kind not in CONTROL_UNITS:
            raise MeasurementError(
                f"control_kind: must be one of {', '.join(CONTROL_UNITS)} when a control is given, got {control_kind!r}"
            )
        if control is not None and hasattr(control, "units"):
            from ..units import to_si

            control = to_si(control, CONTROL_UNITS[control_kind], "control")
        u = (
            np.zeros(n)
            if control is None
            else _as_1d(np.broadcast_to(_as_1d_any(control, "control"), (n,)), "control", n)
        )
        T = None if temperature is None else _as_1d(temperature, "temperature", n, unit="K")
        for column, values in (("time", t), ("displacement", x), ("force", F), ("velocity", velocity)):
            if values is not None:
                _check_magnitude(np.asarray(values, dtype=float), column, column)
        _check_time(t, lambda i: f"time: sample {i}")
        v = None if velocity is None else _as_1d(velocity, "velocity", n, unit="m/s")
        kind = control_kind if control is not None else None
        return cls._from_checked(t, x, F, u, kind, v, T, name, window, units)

    @classmethod
    def _from_checked(cls, t, x, F, u, control_kind, velocity, T, name, window, units) -> "Measurement":
        """:meth:`from_arrays` after its checks: float arrays of one length, finite, within
        :data:`POSSIBLE_MAGNITUDE`, time increasing (the reader of files checks them itself, naming lines and
        columns; again here they were passes over every column)."""
        v_derived, a, f0 = _derivatives(t, x, window, 3)
        v = v_derived if velocity is None else velocity
        if velocity is not None:
            _check_velocity(v, v_derived, name)
        record = cls(t, x, F, v, a, u, control_kind, T, name, dict(units or {}))
        if f0 is not None:  # found by the derivatives from the same arrays: kept, not computed again
            record.__dict__["dominant_frequency"] = f0
        return record

    def __len__(self) -> int:
        return self.time.size

    @functools.cached_property
    def dominant_frequency(self) -> float:
        """Frequency of the largest Fourier component of the detrended displacement, [Hz] (0 for no motion)."""
        return _dominant_frequency(self.time, self.displacement)

    @property
    def sample_rate(self) -> float:
        """Mean sampling rate, [Hz]."""
        return (self.time.size - 1) / (self.time[-1] - self.time[0])

    @property
    def duration(self) -> float:
        """[s]"""
        return float(self.time[-1] - self.time[0])

    def select(self, mask_or_slice) -> "Measurement":
        """The samples picked by a boolean mask or slice (derivatives are kept, not recomputed)."""

        def pick(a):
            return None if a is None else a[mask_or_slice]

        return replace(
            self,
            time=self.time[mask_or_slice],
            displacement=self.displacement[mask_or_slice],
            force=pick(self.force),
            velocity=self.velocity[mask_or_slice],
            acceleration=self.acceleration[mask_or_slice],
            control=self.control[mask_or_slice],
            temperature=pick(self.temperature),
        )

    def with_force(self, force) -> "Measurement":
        """The same motion with another force (e.g. a model's prediction)."""
        return replace(self, force=_as_1d(force, "force", len(self)))

    def require_force(self) -> np.ndarray:
        if self.force is None:
            raise MeasurementError(f"{self.name or 'record'}: has no force column")
        return self.force


def _as_1d(values, name: str, n: int | None = None, unit: str | None = None) -> np.ndarray:
    if hasattr(values, "units") and hasattr(values, "magnitude"):  # a pint quantity: converted, never stripped
        if unit is None:
            raise MeasurementError(f"{name}: expected SI numbers, got a quantity in {values.units:~P}")
        from ..units import to_si

        values = to_si(values, unit, name)
    arr = _numbers(values, name)
    if arr.ndim != 1:
        raise MeasurementError(f"{name}: expected a 1-D array, got shape {arr.shape}")
    if n is not None and arr.size != n:
        raise MeasurementError(f"{name}: expected {n} samples (as many as time), got {arr.size}")
    bad = np.empty(0, dtype=int) if _all_finite(arr) else np.flatnonzero(~np.isfinite(arr))
    if bad.size:
        raise MeasurementError(f"{name}: sample {bad[0]} is not finite ({arr[bad[0]]})")
    return arr


def _all_finite(a: np.ndarray) -> bool:
    """True when every element is finite: their sum is finite then, and only then (an infinity or NaN makes it
    infinite or NaN), unless finite values overflow it, which the element-wise test then settles.  One pass over the
    array instead of two (and no array of booleans)."""
    return bool(np.isfinite(np.sum(a))) or bool(np.isfinite(a).all())


def _as_1d_any(values, name: str) -> np.ndarray:
    """A value or array of numbers (a control may be one value for the whole record)."""
    return _numbers(values, name)


def _numbers(values, name: str) -> np.ndarray:
    """``values`` as a float array through the one check of SI arguments (:func:`erdesign._util.si_array`): text,
    booleans, complex numbers, dates and masked values were taken as numbers."""
    from .._util import si_array

    try:
        return si_array(values, name, finite=False)
    except ErdesignError as exc:
        raise MeasurementError(str(exc)) from None


def _check_velocity(v: np.ndarray, v_derived: np.ndarray, name: str) -> None:
    """Warn when a measured velocity column disagrees with the derivative of the displacement (a unit or sign
    mistake, or a column of something else): more than 10 % of the derivative's power left over after the best
    scale, or a best scale off by more than 20 %."""
    power = float(np.dot(v_derived, v_derived))
    if power == 0.0:
        return
    scale = float(np.dot(v, v_derived)) / power
    rest = float(np.sum((v - scale * v_derived) ** 2)) / power
    if rest > 0.1 or abs(scale - 1.0) > 0.2:
        warnings.warn(
            f"{name or 'record'}: the velocity column is {scale:.3g} x the derivative of the displacement "
            f"(with {100 * rest:.2g} % of its power left over): check its unit and sign; the models use the "
            "velocity column as given",
            ErdesignWarning,
            stacklevel=3,
        )


def clipped_samples(force, *, min_count: int = 3) -> np.ndarray:
    """Samples at a flat top or bottom of the force: a load cell or amplifier at its limit.

    A record's largest (smallest) value, repeated at least ``min_count`` times and at least twice in a row, is
    taken as a clipping level; every sample at that level (to 1e-9 of the force range) is flagged.  A measured
    force that merely peaks reaches its extreme once.

    Examples
    --------
    >>> F = np.r_[np.sin(np.linspace(0, 6, 50)) * 10, 0.0]
    >>> int(clipped_samples(np.minimum(F, 8.0)).sum()), int(clipped_samples(F).sum())
    (11, 0)

    Returns
    -------
    ndarray of bool
        True at the clipped samples.
    """
    F = np.asarray(force, dtype=float)
    mask = np.zeros(F.shape, dtype=bool)
    if F.size < 3:
        return mask
    tol = 1e-9 * float(np.ptp(F))
    for level in (float(F.max()), float(F.min())):
        at = np.abs(F - level) <= tol
        if at.sum() >= min_count and np.any(at[1:] & at[:-1]):
            mask |= at
    return mask


def _check_time(t: np.ndarray, where) -> None:
    if t.size < 5:
        raise MeasurementError(f"time: a record needs at least 5 samples, got {t.size}")
    steps = np.diff(t)
    if steps.min() > 0:  # (NaN is refused before)
        return
    bad = np.flatnonzero(steps <= 0)
    if bad.size:
        raise MeasurementError(
            f"{where(bad[0] + 1)}: time must increase strictly ({t[bad[0]]:g} s then {t[bad[0] + 1]:g} s)"
        )


def _detrend(t: np.ndarray, x: np.ndarray) -> np.ndarray:
    """x minus its least-squares line in t, in closed form (numpy.polyfit's least squares cost ten times as much
    on a long record; the two agree to rounding).  Sums, not BLAS dot products: a multithreaded BLAS spends more
    CPU time starting its threads than these take."""
    tc = t - t.mean()
    xc = x - x.mean()
    product = tc * xc
    slope = np.sum(product) / np.sum(np.multiply(tc, tc, out=product))
    xc -= np.multiply(slope, tc, out=tc)  # in place (each new array of a long record is a pass over cold memory)
    return xc


@functools.lru_cache(maxsize=8)
def _hann(n: int) -> np.ndarray:
    """numpy.hanning(n), read-only and kept: a record's spectra (the dominant frequency, the periodicity test, the
    low-pass cut-off, the record's checks) all use the window of its length."""
    w = np.hanning(n)
    w.flags.writeable = False
    return w


def _step_spread(t: np.ndarray) -> float:
    """Largest difference of a time step from the mean step, as a fraction of the mean step."""
    dt = (t[-1] - t[0]) / (t.size - 1)
    deviation = np.diff(t)
    deviation -= dt
    return float(np.abs(deviation, out=deviation).max()) / dt


#: Largest :func:`_step_spread` of an evenly sampled record (written with rounded times): the steps' differences
#: then move no computed phase or resampled value by more than rounding.
EVEN_STEPS = 1e-9


def _evenly_sampled(t: np.ndarray) -> bool:
    """True when every time step is the mean step to within :data:`EVEN_STEPS` of it."""
    return t.size >= 2 and _step_spread(t) <= EVEN_STEPS


def _spectrum(t: np.ndarray, x: np.ndarray, even: bool | None = None):
    """(frequencies [Hz], magnitudes, detrended signal) of the Hann-windowed spectrum of the signal detrended by a
    least-squares line, resampled onto a uniform grid unless the record is one already (:func:`_evenly_sampled`,
    unless ``even`` says)."""
    n = t.size
    if _evenly_sampled(t) if even is None else even:
        tu, xu = t, x
    else:
        tu = np.linspace(t[0], t[-1], n)
        xu = np.interp(tu, t, x)
    xu = _detrend(tu, xu)
    spectrum = np.abs(np.fft.rfft(xu * _hann(n)))
    freqs = np.fft.rfftfreq(n, d=(tu[-1] - tu[0]) / (n - 1))
    return freqs, spectrum, xu


def _dominant_frequency(t: np.ndarray, x: np.ndarray, spectrum=None) -> float:
    """Frequency [Hz] of the largest Fourier component of the detrended signal (resampled if uneven); ``spectrum``:
    the result of :func:`_spectrum` if already computed."""
    freqs, spectrum, _ = _spectrum(t, x) if spectrum is None else spectrum
    spectrum = spectrum[1:]  # not the mean (what is left of it after the detrending)
    return float(freqs[1 + int(np.argmax(spectrum))]) if spectrum.size and spectrum.max() > 0 else 0.0


#: Largest fraction of the windowed power n sum(x^2) of a sinusoid (or of a line) that the Hann window leaks more
#: than 4 bins from its frequency: 2.3e-5 measured over frequencies 3-40 bins and phases; 1e-4 keeps a margin.
_HANN_LEAKAGE = 1e-4


def _clearly_aperiodic(spectrum, f0: float, T: float, fs: float, limit: float) -> bool:
    """True when no trend line plus harmonics of a frequency within 0.5/T of f0 can leave a residual of rms <=
    ``limit``: the spectral test that :func:`_periodic_derivatives` runs before any least-squares fit.

    With x = line + H + r (H the fitted harmonics, sum(r^2) <= n limit^2 when the fit is accepted), the detrended,
    Hann-windowed spectrum outside the bins of the harmonics (4 bins plus the k/2 bins by which harmonic k may move
    with the fundamental) holds at most the leakage of H, (K + 2) * 2 * _HANN_LEAKAGE * n * sum(H'^2) with
    sum(H'^2) <= 2 sum(x_d^2) + 2 n limit^2 (the K + 2 terms may leak into the same bins, hence the factor), plus
    twice the power of r, 2 n^2 limit^2 (Parseval, the window <= 1).  Power beyond that bound means the fit
    would be rejected whatever it found, so it is not run: the answer is the one the fits would give, at the cost
    of one sum over the spectrum already computed for the dominant frequency."""
    freqs, magnitude, xd = spectrum
    n = xd.size
    df = freqs[1]
    K = int(max(1, min(15, np.floor(0.4 * fs / max(f0 - 0.5 / T, 1e-300)))))
    power = magnitude**2
    keep = freqs > 4.5 * df  # the trend line's residue at the lowest bins
    for k in range(1, K + 1):
        width = 5.0 * df + 0.5 * k / T
        # the test on the bins near harmonic k only (the others are more than a bin beyond its band)
        lo, hi = max(0, int((k * f0 - width) / df) - 1), min(freqs.size, int((k * f0 + width) / df) + 2)
        keep[lo:hi] &= np.abs(freqs[lo:hi] - k * f0) > width
    off = float(np.sum(power[keep]))
    residual = n * n * limit**2
    leakage = (K + 2) * 2.0 * _HANN_LEAKAGE * n * (2.0 * float(np.sum(xd**2)) + 2.0 * n * limit**2)
    return off > 2.0 * leakage + 2.0 * residual


def _noise_level(x: np.ndarray) -> float:
    """Standard deviation of white noise on a smooth sampled signal, from its fourth differences.

    The fourth difference of white noise has variance 70 sigma^2, while that of a signal sampled many times per
    period is negligible (X0 (omega dt)^4); the median absolute deviation makes the estimate robust to steps."""
    x = np.asarray(x, dtype=float)
    if x.size < 9:
        return 0.0
    # numpy.diff(x, 4) in two arrays instead of four (each new array of a long record is a pass over cold memory)
    a = np.subtract(x[1:], x[:-1])
    b = np.subtract(a[1:], a[:-1])
    np.subtract(b[1:], b[:-1], out=a[:-2])
    d4 = np.subtract(a[1:-2], a[:-3], out=b[:-2])
    d4 -= _median(d4)
    return float(_median(np.abs(d4, out=d4)) / 0.6745 / math.sqrt(70.0))


def _median(a: np.ndarray) -> float:
    """numpy.median of a 1-D array, the same value, ~3 x faster on a long array: the middle values are selected
    among those between two quantiles of every 16th value (which hold them with overwhelming odds; checked, with
    numpy.median itself when they do not: NaN, or an unlucky spread)."""
    n = a.size
    m = n // 2
    if n < 8192:
        return float(np.median(a))
    sample = a[::16]
    half = 3 * math.isqrt(sample.size) + 1  # 6 standard deviations of the sample's rank of the median
    lo_rank, hi_rank = max(0, sample.size // 2 - half), min(sample.size - 1, sample.size // 2 + half)
    lo, hi = np.partition(sample, (lo_rank, hi_rank))[[lo_rank, hi_rank]]
    below = int(np.count_nonzero(a < lo))
    band = a[(a >= lo) & (a <= hi)]
    above = int(np.count_nonzero(a > hi))
    first = m - 1 - below if n % 2 == 0 else m - below
    if below + band.size + above != n or first < 0 or m - below >= band.size:
        return float(np.median(a))
    band = np.partition(band, (first, m - below))
    return float((band[first] + band[m - below]) / 2 if n % 2 == 0 else band[m - below])


def _harmonic_columns(
    t: np.ndarray,
    f: float,
    harmonics: int,
    out: np.ndarray | None = None,
    origin: float | None = None,
    even: bool | None = None,
) -> np.ndarray:
    """cos(k w), sin(k w) for k = 1..``harmonics`` with w = 2 pi f (t - origin) (default origin t[0]), as the columns
    2k - 2 and 2k - 1 of an (n, 2 harmonics) array (``out`` if given), from cos(w), sin(w) by angle addition (an error
    of k ulp instead
    of 2K transcendental passes).  On an evenly sampled record (:func:`_evenly_sampled`) cos(w) and sin(w) come from
    those at the starts of blocks of sqrt(n) samples times those at the offsets within a block (2 sqrt(n)
    transcendental evaluations instead of 2n, and an error of 2 ulp; ``even``: whether it is, if known)."""
    n = t.size
    out = np.empty((n, 2 * harmonics)) if out is None else out
    if harmonics == 1:
        out[:, 0], out[:, 1] = _fundamental(t, f, origin, even)
        return out
    # by rows of their transpose, each contiguous (by the columns of ``out`` the additions took 4 x longer)
    rows = np.empty((2 * harmonics, n))
    rows[0], rows[1] = _fundamental(t, f, origin, even)
    c1, s1 = rows[0], rows[1]
    for k in range(2, harmonics + 1):
        ck, sk, ck1, sk1 = rows[2 * k - 4 : 2 * k]
        np.multiply(c1, ck, out=ck1)
        ck1 -= s1 * sk
        np.multiply(s1, ck, out=sk1)
        sk1 += c1 * sk
    out[...] = rows.T
    return out


def _fundamental(t: np.ndarray, f: float, origin: float | None = None, even: bool | None = None):
    """(cos w, sin w), w = 2 pi f (t - origin), as :func:`_harmonic_columns` computes them (its first two
    columns)."""
    n = t.size
    origin = t[0] if origin is None else origin
    if n >= 1024 and (_evenly_sampled(t) if even is None else even):
        starts, offsets = _phasors(t, f, origin)
        z = np.multiply.outer(starts, offsets).ravel()[:n]
        return z.real, z.imag
    w = 2 * np.pi * f * (t - origin)
    return np.cos(w), np.sin(w)


def _phasors(t: np.ndarray, f: float, origin: float):
    """exp(i w) of an evenly sampled record at the starts of its blocks of isqrt(n) + 1 samples and at the offsets
    within a block: their outer product, raveled, is exp(i w) at every sample (:func:`_fundamental`)."""
    block = math.isqrt(t.size) + 1
    return np.exp(2j * np.pi * f * (t[::block] - origin)), np.exp(2j * np.pi * f * (t[:block] - t[0]))


def _harmonic_fit(t: np.ndarray, x: np.ndarray, f: float, harmonics: int, even: bool | None = None):
    """Least-squares fit of a trend line plus ``harmonics`` harmonics of f; returns (coefficients of 1,
    t - t[0], cos(k w), sin(k w) for k = 1..harmonics; the design matrix, whose columns 2k and 2k + 1 are
    cos(k w) and sin(k w) with w = 2 pi f (t - t[0]); the residual).

    The trend column is centred and scaled to [-1, 1], orthogonal to the constant, and the harmonics of a record
    of at least 1.5 periods are nearly orthogonal, so the normal equations are well conditioned; one step of
    iterative refinement brings the coefficients to the accuracy of an SVD (numpy.linalg.lstsq, used before, and
    measured within 1e-15 of it) at a tenth of its cost.  The harmonics come from :func:`_harmonic_columns`
    (``even``: whether t is evenly sampled, if known)."""
    T = t[-1] - t[0]
    A = np.empty((t.size, 2 + 2 * harmonics))
    A[:, 0] = 1.0
    A[:, 1] = (2.0 / T) * (t - t[0]) - 1.0
    _harmonic_columns(t, f, harmonics, out=A[:, 2:], even=even)
    gram = A.T @ A
    coef = np.linalg.solve(gram, A.T @ x)
    r = x - A @ coef
    coef += np.linalg.solve(gram, A.T @ r)
    r = x - A @ coef
    coef[0] -= coef[1]  # back to the columns 1 and t - t[0]
    coef[1] *= 2.0 / T
    return coef, A, r


def _periodic_derivatives(t, x, f0, sigma, spectrum=None, even: bool | None = None):
    """Fourier filtering (Kamath and Wereley 1997): velocity and acceleration of the significant harmonics of the
    refined fundamental, or None when the record is not periodic in f0 (the harmonics leave more than noise).
    ``spectrum`` (:func:`_spectrum` of the record, evenly sampled) lets :func:`_clearly_aperiodic` reject a record
    before any fit; ``even``: whether the record is evenly sampled (:func:`_evenly_sampled`), if known."""
    T = t[-1] - t[0]
    if f0 <= 0 or f0 * T < 1.5:
        return None
    limit = 1.5 * sigma + 1e-7 * np.ptp(x)
    fs = (t.size - 1) / T
    if spectrum is not None and _clearly_aperiodic(spectrum, f0, T, fs, limit):
        return None
    # No BLAS thread limit (threadpoolctl): the fits are at most FIT_SAMPLES x 32, which OpenBLAS runs on one thread
    # anyway (measured: the same CPU and wall time with and without), and setting the limit cost 3.7 ms a call, more
    # than the fits.
    return _harmonic_derivatives(t, x, f0, sigma, T, fs, limit, _evenly_sampled(t) if even is None else even)


#: Most samples the harmonic fits of :func:`_periodic_derivatives` take: a longer evenly sampled record is fitted by
#: the means of blocks of s samples, s the least that brings it to this many (and at most what keeps 2.5 means a
#: period of the 15th harmonic).  On 60,000 samples the fits took 36 ms, seven times the parsing of the file; on
#: 2048 means they take 1.5.
FIT_SAMPLES = 2048


def _harmonic_derivatives(t, x, f0, sigma, T, fs, limit, even):
    """The fits of :func:`_periodic_derivatives`: the fundamental refined by least squares, then up to 15
    harmonics; None when they leave more than noise.

    An evenly sampled record longer than :data:`FIT_SAMPLES` is fitted by the means of blocks of s samples.  The mean
    of a block of an even record is the trend line at the block's mean time plus each harmonic there times the
    Dirichlet gain D_k = sin(s theta) / (s sin theta), theta = pi k f dt, so the fit of the means gives the
    coefficients times D_k (divided out below), with the noise's variance divided by s: the same information on the
    harmonics as a fit of every sample (tests/test_derivatives_fast_paths.py: the same accuracy), at 1/s of the cost
    a fit.  The sum of squares of the means' residual, times s, is at most that of every sample's (the deviations
    within the blocks are left out), so it rejects only records the full fit would; the model must then leave no more
    than noise at every sample.
    """
    from scipy.optimize import minimize_scalar

    n = t.size
    stride = max(1, min(-(-n // FIT_SAMPLES), int(0.4 * fs / (15 * (f0 + 0.5 / T)))))
    if not even:
        stride = 1  # block means of an uneven record are no harmonic series: fit every sample
    nb = n // stride
    ts = t[: nb * stride].reshape(nb, stride).mean(axis=1) if stride > 1 else t
    xs = x[: nb * stride].reshape(nb, stride).mean(axis=1) if stride > 1 else x
    res = minimize_scalar(
        lambda f: float(np.sum(_harmonic_fit(ts, xs, f, 1, even)[2] ** 2)),
        bounds=(f0 - 0.5 / T, f0 + 0.5 / T),
        method="bounded",
        options={"xatol": 1e-10 * f0},
    )
    f = float(res.x)
    K = int(max(1, min(15, np.floor(0.4 * fs / f))))
    if ts.size >= 64 * (2 * K + 2):
        # The least-squares residual over every 8th sample is a lower bound of the one over all samples (a subset of
        # the terms of the sum, each minimised on its own): when it already exceeds the limit the full fit would be
        # rejected too, and the large fit (most of the cost on long random records) is skipped.
        *_, r_sub = _harmonic_fit(ts[::8], xs[::8], f, K, even)
        if stride * np.sum(r_sub**2) > n * limit**2:
            return None
    coef, A, r = _harmonic_fit(ts, xs, f, K, even)
    if stride * np.sum(r**2) > n * limit**2:
        return None
    # keep only harmonics that stand above the noise (amplitude > 4 standard errors; the means' noise is sigma /
    # sqrt(stride), their standard error that of every sample's fit)
    se = 4 * sigma * math.sqrt(2.0 / (ts.size * stride))
    c = coef.copy()
    kept = []
    for k in range(1, K + 1):
        if math.hypot(c[2 * k], c[2 * k + 1]) < se:
            c[2 * k] = c[2 * k + 1] = 0.0
        elif stride > 1:
            theta = math.pi * k * f * T / (n - 1)
            c[2 * k : 2 * k + 2] /= math.sin(stride * theta) / (stride * math.sin(theta))
            kept.append(k)
        else:
            kept.append(k)
    return _harmonic_series(t, x, f, c, kept, A if stride == 1 else None, ts[0], limit)


#: Samples a block of :func:`_harmonic_series`: its arrays then stay in the processor's cache.
SERIES_BLOCK = 16384


def _harmonic_series(t, x, f, c, kept, A, origin, limit):
    """Velocity and acceleration of the trend line and harmonics ``kept`` of f (coefficients ``c`` as
    :func:`_harmonic_fit` gives them), differentiated analytically; None when the model leaves more than ``limit``
    (rms) at the samples.  ``A``: the design matrix of a fit of every sample (whose residual was checked before),
    else None: the harmonics are computed from ``origin`` (the first block mean's time) and the model checked.

    Block by block of :data:`SERIES_BLOCK` samples, the cosines and sines of each block by angle addition as
    :func:`_harmonic_columns` (the same values): arrays of the record's length only for the fundamental and the
    results (the whole model in one piece took 4.6 MB, which the allocator gave back to the system after each read
    and took again, page by page, in the next)."""
    n = t.size
    w = 2 * np.pi * f
    v = np.full_like(t, c[1])
    a = np.zeros_like(t)
    K = max(kept, default=0)
    if A is None:  # blocks of whole rows of the phasors' outer product (a record fitted by means is even and long)
        starts, offsets = _phasors(t, f, origin)
        size = offsets.size * max(1, SERIES_BLOCK // offsets.size)
    else:
        size = SERIES_BLOCK
    squares = 0.0  # of the model's residual
    for lo in range(0, n, size):
        block = slice(lo, min(n, lo + size))
        vb, ab = v[block], a[block]
        if A is None and K:
            rows = slice(lo // offsets.size, -(-block.stop // offsets.size))
            z = np.multiply.outer(starts[rows], offsets).ravel()[: block.stop - lo]
            c1, s1 = np.ascontiguousarray(z.real), np.ascontiguousarray(z.imag)
        model = None  # c[0] + c[1] (t - origin) + the harmonics
        if A is None:
            model = np.subtract(t[block], origin)
            model *= c[1]
            model += c[0]
        cos = sin = None
        for k in range(1, K + 1):
            if A is not None:
                cos, sin = A[block, 2 * k], A[block, 2 * k + 1]
            elif k == 1:
                cos, sin = c1, s1
            else:
                cos, sin = c1 * cos - s1 * sin, s1 * cos + c1 * sin
            if k not in kept:
                continue
            ck, sk = c[2 * k], c[2 * k + 1]
            h = ck * cos + sk * sin  # the harmonic; its derivative is k w (sk cos - ck sin)
            vb += (k * w) * (sk * cos - ck * sin)
            ab -= (k * w) ** 2 * h
            if model is not None:
                model += h
        if model is not None:
            r = np.subtract(x[block], model, out=model)
            squares += float(np.sum(r * r))  # not np.dot: BLAS threads cost more than it
    if A is None and math.sqrt(squares / n) > limit:
        return None
    return v, a


def _central4(y: np.ndarray, dt: float) -> np.ndarray:
    """Fourth-order central difference (second order at the two end samples of each side)."""
    if y.size < 5:
        return np.gradient(y, dt, edge_order=2)
    d = np.empty(y.shape)
    inner = d[2:-2]  # (-y[4:] + 8 y[3:-1] - 8 y[1:-3] + y[:-4]) / (12 dt), in place, in that order
    np.negative(y[4:], out=inner)
    inner += 8 * y[3:-1]
    inner -= 8 * y[1:-3]
    inner += y[:-4]
    inner /= 12 * dt
    d[:2] = np.gradient(y[:3], dt, edge_order=2)[:2]  # numpy.gradient's values there, from the samples they use
    d[-2:] = np.gradient(y[-3:], dt, edge_order=2)[-2:]
    return d


def _moving_mean(P: np.ndarray, k: int, lo: int = 0, hi: int | None = None) -> np.ndarray:
    """numpy.convolve(P, ones(2k + 1) / (2k + 1), "same")[lo:hi] of non-negative P in O(n): the window of 2k + 1
    samples always spans two consecutive blocks of that length, so each mean is the sum of a block's suffix and of
    the next block's prefix (cumulative sums within blocks: each term is summed with its window's own, so the mean
    keeps the relative accuracy of the convolution, ~1e-15, however widely P ranges).  The blocks are those of the
    whole of P whatever ``lo`` and ``hi``, so a part has the values of the whole (only its blocks are summed)."""
    B = 2 * k + 1
    n = P.size
    hi = n if hi is None else hi
    first, last = lo // B, (hi - 1) // B + 1  # the blocks of the means lo..hi - 1 and the blocks after them
    Q = np.zeros((last - first + 1, B))  # block r holds P[r B - k : (r + 1) B - k], zero beyond P
    start = first * B - k
    Q.ravel()[max(0, -start) : max(0, min(n, start + Q.size) - start)] = P[max(0, start) : start + Q.size]
    suffix = np.ascontiguousarray(Q[:, ::-1])
    np.cumsum(suffix, axis=1, out=suffix)
    prefix = np.empty(Q.shape)
    prefix[:, 0] = 0.0
    np.cumsum(Q[:, :-1], axis=1, out=prefix[:, 1:])
    offset = lo - first * B
    return (suffix[:, ::-1].ravel()[offset : offset + hi - lo] + prefix.ravel()[B + offset : B + offset + hi - lo]) / B


#: Means a step of :func:`_last_mean_above` computes.
MEANS_A_STEP = 2048


def _last_mean_above(P: np.ndarray, k: int, level: float) -> int:
    """The last index at which :func:`_moving_mean` (P, k) exceeds ``level`` (-1 if none), with the same means,
    computed only where one can exceed it: within k of a term above ``level`` (a mean is at most its window's
    largest term), from the last such term down, :data:`MEANS_A_STEP` at a time.  The periodogram of a long
    record stands above the level at a few hundred bins out of tens of thousands: the smoothing of all of them
    cost a tenth of the low-pass."""
    big = np.flatnonzero(P > level)
    n = P.size
    hi = min(n, int(big[-1]) + k + 1) if big.size else 0
    while hi > 0:
        lo = max(0, hi - MEANS_A_STEP)
        above = np.flatnonzero(_moving_mean(P, k, lo, hi) > level)
        if above.size:
            return lo + int(above[-1])
        below = big[: np.searchsorted(big, lo + k)]  # the terms whose windows reach below lo
        hi = min(lo, int(below[-1]) + k + 1) if below.size else 0
    return -1


@functools.lru_cache(maxsize=64)
def _butterworth(order: int, cutoff: float) -> np.ndarray:
    """Second-order sections of the digital Butterworth low-pass of even ``order`` and ``cutoff`` (a fraction of the
    Nyquist frequency): the array of ``scipy.signal.butter(order, cutoff, output="sos")`` (and of ``butter(order,
    fc, fs=fs, ...)`` with cutoff = 2 fc / fs), read-only, kept for the next record of that cut-off.

    Built from butter's poles as ``scipy.signal.zpk2sos`` builds it, with the same operations (its zeros all at -1:
    each section's numerator 1, 2, 1; its denominator the polynomial of a pole and its conjugate, by numpy.convolve
    as scipy's ``poly``; the pole nearest the unit circle in the last section; the gain in the first): 60 us
    instead of 260, zpk2sos's general pairing being most of butter's time (tests/test_reading_fast_paths.py
    checks the arrays are equal, bit for bit, over orders 2-8 and cut-offs 1e-6-0.99: a last ulp moves the gain of
    a low cut-off's sections by far more)."""
    from scipy.signal import butter

    _, p, k = butter(order, cutoff, output="zpk")
    upper = p[p.imag > 0]  # one pole of each conjugate pair (an even order has no real pole)
    upper = upper[np.argsort(-np.abs(1 - np.abs(upper)), kind="stable")]
    sos = np.zeros((upper.size, 6))
    sos[:, :3] = (1.0, 2.0, 1.0)
    for i, pole in enumerate(upper):
        sos[i, 3:] = np.convolve(np.convolve(np.ones(1, complex), [1, -pole]), [1, -np.conj(pole)]).real
    sos[0, :3] *= k
    sos.flags.writeable = False
    return sos


def _lowpass_derivatives(x, dt, f0, sigma, spectrum):
    """Adaptive zero-phase low-pass, then fourth-order central differences.

    Cut-off: the frequency below which the signal power stands out of the white-noise floor (1.5 x the last frequency
    whose smoothed periodogram exceeds 10 x the noise power per bin), at least 3 x the dominant frequency and at
    most a fifth of the sampling rate.  ``spectrum``: :func:`_spectrum` of the (evenly sampled) record."""
    from scipy.signal import sosfiltfilt

    n = x.size
    fs = 1.0 / dt
    f, magnitude, _ = spectrum
    P = magnitude**2
    floor = sigma**2 * np.sum(_hann(n) ** 2)
    k = max(1, n // 400)
    last = _last_mean_above(P, k, 10 * floor)
    fc = 1.5 * f[last] if last >= 0 else 3 * f0
    fc = float(np.clip(max(fc, 3 * f0), 2 * fs / n, 0.2 * fs))
    if fc >= 0.2 * fs * 0.999 and sigma == 0:
        xs = x
    else:
        sos = _butterworth(4, 2 * fc / fs).copy()  # (scipy's sosfilt takes a writable array only)
        xs = np.ascontiguousarray(sosfiltfilt(sos, x))  # (a reversed view: slower to difference)
    v = _central4(xs, dt)
    return v, _central4(v, dt)


def derivatives(t, x, *, window: int | None = None, polyorder: int = 3):
    r"""Velocity and acceleration of a sampled displacement, robust to measurement noise.

    The rule, in order:

    1. **Periodic records** (the displacement is a trend line plus harmonics of its dominant frequency to within
       the noise): Fourier filtering as Kamath and Wereley (1997, section II).  The fundamental is refined by
       least squares, up to 15 harmonics are fitted, those below four standard errors are dropped, and the
       series is differentiated analytically (which beats their fourth-order difference of the filtered signal).
    2. **Other records** (sweeps, random, earthquake-like motion): an adaptive zero-phase low-pass (4th-order
       Butterworth, :func:`scipy.signal.sosfiltfilt`) whose cut-off is where the displacement spectrum meets the
       noise floor, then fourth-order central differences.
    3. With an explicit ``window``: Savitzky-Golay differentiation over that many samples.

    Parameters
    ----------
    t : array
        Time, [s]; rule 1 takes any sampling; for rules 2 and 3, steps varying by more than 1 % are resampled onto
        a uniform grid and interpolated back.
    x : array
        Displacement, [m].
    window : int, optional
        Savitzky-Golay window length in samples (odd); forces rule 3.
    polyorder : int
        Degree of the Savitzky-Golay polynomial (rule 3).

    Returns
    -------
    (v, a) : tuple of arrays
        [m/s], [m/s^2].

    Notes
    -----
    The noise level is estimated from the fourth differences of the displacement (:func:`_noise_level`), which a
    signal sampled many times per period does not contribute to.  tests/test_measurement.py measures the error on
    noisy sines (rule 1, against the method of Kamath and Wereley (1997)) and on noisy random and earthquake-like
    records (rule 2).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 2, 2001); x = 0.01 * np.sin(2 * np.pi * t)
    >>> v, a = derivatives(t, x)
    >>> bool(np.max(np.abs(v - 0.01 * 2 * np.pi * np.cos(2 * np.pi * t))) / (0.02 * np.pi) < 1e-6)
    True

    References
    ----------
    Kamath and Wereley (1997), section II (Fourier filtering and fourth-order central differences).
    """
    v, a, _ = _derivatives(t, x, window, polyorder)
    return v, a


def _derivatives(t, x, window: int | None, polyorder: int):
    """:func:`derivatives`, and the dominant frequency [Hz] of the displacement that rules 1 and 2 find on the way
    (None with a ``window``)."""
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    f0 = None
    n = t.size
    dt = (t[-1] - t[0]) / (n - 1)
    spread = _step_spread(t)
    uneven = spread > 0.01
    tu = np.linspace(t[0], t[-1], n) if uneven else t
    xu = np.interp(tu, t, x) if uneven else x
    if window is not None:
        window = max(polyorder + 2, min(int(window), max(polyorder + 2, n // 3)))
        window += 1 - window % 2  # odd
        if window > n:
            raise MeasurementError(f"derivatives: the record ({n} samples) is too short for a window of {window}")
        from scipy.signal import savgol_filter  # imported on use: scipy.signal costs start-up time

        v = savgol_filter(xu, window, polyorder, deriv=1, delta=dt, mode="interp")
        a = savgol_filter(xu, window, polyorder, deriv=2, delta=dt, mode="interp")
    else:
        spectrum = _spectrum(tu, xu, even=uneven or spread <= EVEN_STEPS)
        f0 = _dominant_frequency(tu, xu, spectrum)
        sigma = _noise_level(xu)
        # the harmonic fit needs no uniform grid: fit the samples where they were taken (the spectral test does,
        # so an uneven record goes to the fits)
        out = (
            _periodic_derivatives(t, x, f0, sigma, None if uneven else spectrum, even=spread <= EVEN_STEPS)
            if n >= 16
            else None
        )
        if out is not None:
            return (*out, f0)
        if n < 16:
            v = np.gradient(xu, dt, edge_order=2) if n >= 3 else np.zeros(n)
            a = np.gradient(v, dt, edge_order=2) if n >= 3 else np.zeros(n)
        else:
            v, a = _lowpass_derivatives(xu, dt, f0, sigma, spectrum)
    if uneven:
        v, a = np.interp(t, tu, v), np.interp(t, tu, a)
    return v, a, f0


def _parse_header(cells: list[str], lineno: int, path: str, require_force: bool = True) -> list[tuple[str, str, Any]]:
    columns = []
    seen: dict[str, int] = {}
    if len(cells) == 1 and "\t" in cells[0]:  # (a ';'-separated file is made comma-separated before)
        raise MeasurementError(
            f"{path}: line {lineno}: the columns are separated by tabs; erdesign reads files with ',' or ';' "
            "between the columns (save as CSV)"
        )
    if len(cells) == 1 and re.search(r"\]\s+\S", cells[0]):  # 'time [s] displacement [mm] force [N]'
        raise MeasurementError(
            f"{path}: line {lineno}: the columns are separated by spaces; erdesign reads files with ',' or ';' "
            "between the columns (save as CSV)"
        )
    if len(cells) == 1 and re.search(r"\]\s*[|:]\s*\S", cells[0]):  # 'time [s]|displacement [mm]|force [N]'
        sep = re.search(r"\]\s*([|:])", cells[0])[1]
        raise MeasurementError(
            f"{path}: line {lineno}: the columns are separated by {sep!r}; erdesign reads files with ',' or ';' "
            "between the columns (save as CSV)"
        )
    for col, cell in enumerate(cells, start=1):
        if len(cell) > MAX_CELL_CHARS:
            raise MeasurementError(
                f"{path}: line {lineno}, column {col}: a header cell of {len(cell):,} characters "
                f"(at most {MAX_CELL_CHARS:,}); a header cell is a name and its unit, e.g. "
                "'time [s]'"
            )
        m = _HEADER.match(cell)
        # invisible characters (a BOM or a zero-width space pasted mid-line) dropped from the name
        name = "".join(ch for ch in m[1] if unicodedata.category(ch) != "Cf").strip().lower() if m else ""
        if not cell.strip() and col == 1 and len(cells) > 1:  # df.to_csv('rec.csv') writes the index first
            raise MeasurementError(
                f"{path}: line {lineno}, column 1: no name; an index column, as pandas' to_csv writes by default? "
                "write the file with to_csv(..., index=False)"
            )
        if not cell.strip() and col == len(cells):
            raise MeasurementError(
                f"{path}: line {lineno}, column {col}: no name; the header ends in a ',' (remove it, and any at the "
                "ends of the rows)"
            )
        if col == 1 and re.fullmatch(r"\s*sep=.?\s*", cell, re.IGNORECASE):
            raise MeasurementError(
                f"{path}: line {lineno}: {cell.strip()!r} is Excel's separator line, not a header; remove the line"
            )
        if not name:
            raise MeasurementError(
                f"{path}: line {lineno}, column {col} ({cell.strip()!r}): expected a name with "
                f"its unit in square brackets, e.g. 'time [s]'"
            )
        unit = m[2].strip()
        where = f"{path}: line {lineno}, column {col} ({name})"
        if "\t" in unit:
            raise MeasurementError(
                f"{where}: a tab inside the header: erdesign reads files with ',' or ';' between the columns"
            )
        if name not in COLUMNS and name not in CONTROL_COLUMNS:
            known = [*COLUMNS, *CONTROL_COLUMNS]
            raise MeasurementError(f"{where}: unknown column{did_you_mean(name, known)}; known: {', '.join(known)}")
        if name in seen:
            raise MeasurementError(f"{where}: column '{name}' appears twice (also column {seen[name]})")
        seen[name] = col
        try:
            q = parse_unit(unit, "unit")
            unit = clean_value_text(unit, "unit", number=False).strip()  # as parsed ('\uff4bN' is 'kN')
        except ErdesignError as exc:
            raise MeasurementError(f"{where}: {str(exc).removeprefix('unit: ')}") from None
        if name in COLUMNS:
            if q.dimensionality != ureg.Unit(COLUMNS[name]).dimensionality:
                raise MeasurementError(
                    f"{where}: unit {unit!r} is {dimension_name(q.dimensionality)}; expected "
                    f"{dimension_name(ureg.Unit(COLUMNS[name]).dimensionality)}"
                )
            kind = None
        else:
            kind = next(
                (k for k in CONTROL_COLUMNS[name] if q.dimensionality == ureg.Unit(CONTROL_UNITS[k]).dimensionality),
                None,
            )
            if kind is None:
                allowed = " or ".join(CONTROL_UNITS[k] for k in CONTROL_COLUMNS[name])
                raise MeasurementError(
                    f"{where}: unit {unit!r} is {dimension_name(q.dimensionality)}; a '{name}' column takes {allowed}"
                )
        columns.append((name, unit, kind))
    required = ("time", "displacement", "force") if require_force else ("time", "displacement")
    missing = [c for c in required if c not in seen]
    if missing:
        raise MeasurementError(f"{path}: line {lineno}: missing required column '{missing[0]} [...]'")
    controls = [c for c in seen if c in CONTROL_COLUMNS]
    if len(controls) > 1:
        raise MeasurementError(
            f"{path}: line {lineno}: more than one control column ({', '.join(controls)}); "
            "give one of field, current or voltage"
        )
    return columns


def read_measurement(path: str | Path, *, window: int | None = None, require_force: bool = True) -> Measurement:
    """Read a measurement CSV file (docs/file_formats.md) into SI arrays.

    With ``require_force=False`` a file without a force column is read as a motion record (``force`` is None), e.g.
    a displacement history to simulate a model on.

    Raises :class:`MeasurementError` naming the line and column of the first problem: no units in the header,
    unknown unit or column, wrong dimension, non-numeric or empty cell, NaN or infinity, wrong number of cells,
    non-increasing time, fewer than 5 samples.
    """
    if not is_path_like(path):
        hint = (
            "; for data in memory use Measurement.from_arrays(time, displacement, force)"
            if hasattr(path, "shape")
            else ""
        )
        raise MeasurementError(
            f"path: expected the name of a measurement file (a str or Path), got {type(path).__name__} "
            f"{' '.join(repr(path).split())[:60]}{hint}"
        )
    if not os.fspath(path).strip():  # Path("") is the current folder: ".: is a folder"
        raise MeasurementError(f"path: an empty file name {os.fspath(path)!r}; give the name of a measurement file")
    path = Path(path)
    label = str(path)
    path = bundled_file(path) or path  # the documented examples/measurements/... from any folder
    try:
        raw = read_input_bytes(path, MAX_RECORD_BYTES, "a measurement CSV file")
        text = None if raw.isascii() else decode_text(raw, label, "a measurement CSV file")  # decoded when needed
    except ErdesignError as exc:
        raise MeasurementError(str(exc)) from None
    except FileNotFoundError:
        pattern = (
            "; a pattern ('*', '?') that matched no file? it is not expanded here"
            if any(c in label for c in "*?")
            else ""
        )
        raise MeasurementError(f"{label}: no such file{pattern}") from None
    except IsADirectoryError:
        raise MeasurementError(f"{label}: is a folder, expected a measurement CSV file") from None
    except UnicodeDecodeError:
        raise MeasurementError(f"{label}: not a text (UTF-8) file") from None
    except OSError as exc:
        raise MeasurementError(f"{label}: cannot be read ({exc.strerror or exc})") from None
    # a line takes at least one byte: a file of fewer bytes cannot hold too many (the count is a pass over the text)
    rows_given = raw.count(b"\n") if len(raw) > MAX_RECORD_ROWS else 0
    if rows_given > MAX_RECORD_ROWS:
        raise MeasurementError(
            f"{label}: {rows_given:,} lines, more than the {MAX_RECORD_ROWS:,} rows erdesign reads "
            "in one record; thin or split the file"
        )
    if (converted := _as_comma_separated(raw, label)) is not raw:
        text = None  # a ';' file made ',': the text decoded before is not the one to read line by line
    raw = converted
    del converted  # one reference to the bytes, freed before the derivatives (below)
    fast = _read_fast(raw, label, require_force)
    if fast is not None:
        # the file's bytes freed before the derivatives: their memory then holds the derivatives' arrays (kept, they
        # would add the file's size to the peak, and the allocator would give the memory back to the system after
        # every read and take it again, cleared, page by page, in the next: 2-3 ms of a 60k-row read)
        del raw, text
        columns, data = fast
        return _measurement_from_table(path, label, columns, data, None, window, require_force)
    lines = _csv_lines(raw.decode("utf-8-sig") if text is None else text, label)
    rows = [
        (i, r)
        for i, r in enumerate(lines, start=1)
        if r and not r[0].lstrip().startswith("#") and any(c.strip() for c in r)
    ]
    if not rows:
        raise MeasurementError(
            f"{label}: empty file (expected a header line such as 'time [s],displacement [mm],force [N]')"
        )
    header_line, header = rows[0]
    columns = _parse_header(header, header_line, label, require_force)
    data = np.empty((len(rows) - 1, len(columns)))
    for r, (lineno, cells) in enumerate(rows[1:]):
        if len(cells) != len(columns):
            hint = (
                "; a decimal comma? with ',' between columns the decimal mark is '.' (a file with ';' between columns "
                "may use decimal commas)"
                if len(cells) > len(columns) and any(re.fullmatch(r"\s*-?\d+", c) for c in cells[1:])
                else ""
            )
            raise MeasurementError(
                f"{label}: line {lineno}: {len(cells)} cells, expected {len(columns)} (one per header column){hint}"
            )
        for c, cell in enumerate(cells):
            value = _cell_number(cell, lambda: f"{label}: line {lineno}, column {c + 1} ({columns[c][0]})")
            if not math.isfinite(value):
                raise MeasurementError(
                    f"{label}: line {lineno}, column {c + 1} ({columns[c][0]}): {cell.strip()!r} is not a finite number"
                )
            data[r, c] = value
    lines = [lineno for lineno, _ in rows[1:]]
    return _measurement_from_table(path, label, columns, list(data.T), lines, window, require_force)


def _csv_lines(text: str, label: str) -> list[list[str]]:
    """The cells of every line (Python's csv reader), with a cell longer than :data:`~erdesign.limits.MAX_CELL_CHARS`
    refused naming its line (csv's own 'field larger than field limit' names nothing)."""
    reader = csv.reader(io.StringIO(text, newline=""))
    lines = []
    try:
        for cells in reader:
            for col, cell in enumerate(cells, start=1):
                if len(cell) > MAX_CELL_CHARS:
                    raise MeasurementError(
                        f"{label}: line {reader.line_num}, column {col}: a cell of {len(cell):,} "
                        f"characters (at most {MAX_CELL_CHARS:,}); a cell is a number or a "
                        "header such as 'time [s]'"
                    )
            lines.append(cells)
    except csv.Error as exc:
        detail = "a cell longer than the CSV reader takes" if "field limit" in str(exc) else str(exc)
        raise MeasurementError(
            f"{label}: line {max(reader.line_num, 1)}: {detail} (at most {MAX_CELL_CHARS:,} characters a cell)"
        ) from None
    return lines


_NUMBER = re.compile(r"\s*[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?\s*", re.ASCII)


def _cell_number(cell: str, where) -> float:
    """The number of a data cell: ASCII digits with an optional sign, point and exponent; a typeset minus sign
    (U+2212) is a minus.  Python's float() also reads digit separators ('4_446.6') and other scripts' digits, which
    a measurement never holds on purpose: they are refused with the rest, naming the line and column."""
    text = cell.replace("\u2212", "-")
    if _NUMBER.fullmatch(text):
        value = float(text)
        if value == 0.0 and re.search("[1-9]", re.split("[eE]", text)[0]):  # '1e-400': read as 0 without a word
            raise MeasurementError(
                f"{where()}: {cell.strip()!r} is too small to compute with (below {sys.float_info.min:.3g}; it would "
                "be read as 0); check the value and the column's unit"
            )
        return value
    stripped = cell.strip()
    if stripped.lower().lstrip("+-") in ("nan", "inf", "infinity"):
        raise MeasurementError(f"{where()}: {stripped!r} is not a finite number")
    if re.fullmatch(r"[-+]?\d+,\d+", stripped):
        hint = f"; a decimal comma? write {stripped.replace(',', '.')}"
    elif re.search(r"\d[_']\d", stripped):
        hint = "; a digit separator? write the number without it"
    else:
        hint = ""
    raise MeasurementError(f"{where()}: {stripped[:40]!r} is not a number{hint}")


def _header_line(raw: bytes) -> tuple[int, int, int] | None:
    """(start, end, start of the next line) of the header, the first line that is neither blank nor a comment;
    None if there is none."""
    pos = 0
    while pos < len(raw):
        start = pos
        end = raw.find(b"\n", pos)
        end = len(raw) if end == -1 else end
        k = raw.find(b"\r", pos, end)  # within the line only: a search of the whole file costs a pass over it
        end = end if k == -1 else k
        pos = end + (2 if raw[end : end + 2] == b"\r\n" else 1)
        stripped = raw[start:end].strip()
        if stripped and not stripped.startswith(b"#") and stripped.replace(b",", b"").replace(b";", b"").strip():
            return start, end, pos
    return None


def _line_number(raw: bytes, offset: int) -> int:
    """The line (from 1) that byte ``offset`` is on (lines end with LF, CRLF or CR, as the csv module counts)."""
    return len(raw[:offset].splitlines()) + (1 if offset == 0 or raw[offset - 1 : offset] in (b"\n", b"\r") else 0)


def _as_comma_separated(raw: bytes, label: str) -> bytes:
    """The file with ',' between cells and '.' as the decimal mark, as the readers take it.

    A header with ';' between its cells is a ';'-separated file: what a spreadsheet in a locale whose decimal mark is
    ',' saves as "CSV" (European Excel).  Its ';' become ',' and, when its numbers have decimal commas, those become
    '.'.  Refused as ambiguous, naming the line: a header with both ';' and ',' (which separates the columns?), and a
    ';'-separated file whose numbers hold both ',' and '.' (a '.' there is a thousands separator or a number written
    the other way: '1.234,5').  Every other file is returned as it is; lines keep their numbers."""
    span = _header_line(raw)
    if span is None or b";" not in raw[span[0] : span[1]]:
        return raw
    start, end, _ = span
    if b"," in raw[start:end]:
        raise MeasurementError(
            f"{label}: line {_line_number(raw, start)}: both ';' and ',' between the header's cells: which one "
            "separates the columns? use one ('time [s];displacement [mm];force [N]')"
        )
    body = raw[end:]
    rows = body  # the data rows, without comment lines
    if b"#" in body:
        rows = b"\n".join(line for _, line in _lines_with_offsets(body) if not line.lstrip().startswith(b"#"))
    if b"," in rows:  # decimal commas
        if b"." in rows:
            for offset, line in _lines_with_offsets(body):
                if b"." in line and not line.lstrip().startswith(b"#"):
                    cell = next(c for c in line.split(b";") if b"." in c).strip().decode("utf-8", "replace")
                    raise MeasurementError(
                        f"{label}: line {_line_number(raw, end + offset)}: {cell[:40]!r} in a ';'-separated file "
                        "whose numbers have decimal commas: is the '.' a thousands separator? save the numbers "
                        "with one decimal mark and no digit grouping"
                    )
        body = body.replace(b",", b".")
    return raw[:end].replace(b";", b",") + body.replace(b";", b",")


def _lines_with_offsets(text: bytes):
    """(offset, line) of each line of ``text`` (LF, CRLF or CR ends)."""
    offset = 0
    for line in text.splitlines(keepends=True):
        yield offset, line.rstrip(b"\r\n")
        offset += len(line)


def _read_fast(raw: bytes, label: str, require_force: bool):
    """(columns, data) of a well-formed file (its bytes, UTF-8 already checked) by pandas' C parser when pandas is
    loaded, else numpy's, or None to let the line-by-line reader find and name the problem (any irregular cell, row
    or value).  Same result as the line-by-line reader, ~20 x faster.  The parsers read the bytes: pandas parses
    a text stream ~1.7 x slower (it encodes it back to UTF-8 first)."""
    if raw.startswith(codecs.BOM_UTF8):
        raw = raw[len(codecs.BOM_UTF8) :]
    if b'"' in raw:
        return None
    span = _header_line(raw)
    if span is None:
        return None
    start, end, pos = span
    header = raw[start:end].decode("utf-8")
    if raw.find(b"\r", pos) != -1 or raw.find(b"#", pos) != -1:
        body = raw[pos:].replace(b"\r\n", b"\n").replace(b"\r", b"\n")
        # comment lines among the data: keep the others
        raw, pos = b"\n".join(line for line in body.split(b"\n") if not line.lstrip().startswith(b"#")), 0
    try:
        columns = _parse_header(header.split(","), 0, label, require_force)
    except MeasurementError:
        return None
    try:
        data = _parse_table(raw, pos, len(columns))
    except (ValueError, TypeError):
        return None
    if len(data) != len(columns) or data[0].size < 5 or not all(_all_finite(values) for values in data):
        return None
    # a zero that may be a number too small for a float ('1e-400'): the line-by-line reader names it.  A zero in the
    # first row only (a time column from 0) needs a look at that row alone, not a scan of the file
    if any(np.count_nonzero(values[1:]) < values.size - 1 for values in data):
        if _may_underflow(raw, pos):
            return None
    elif any(values[0] == 0.0 for values in data):
        first_end = raw.find(b"\n", pos)
        if _may_underflow(raw[pos : len(raw) if first_end < 0 else first_end], 0):
            return None
    t = data[[c[0] for c in columns].index("time")]
    if np.any(np.diff(t) <= 0):
        return None
    return columns, data


def _may_underflow(raw: bytes, pos: int, block: int = 1 << 18) -> bool:
    """True when the table (``raw`` from ``pos`` on) has a number with a negative exponent of 100 or more in size
    ('1e-400', '2E-0325', '5e-150'), which a float may not hold: the parsers read such a number as 0 without a word,
    so the line-by-line reader, which names it, reads the file instead.  An exponent below 100 written with three
    digits ('3.3e-005', as the C runtime of Windows and MATLAB write them) is not such a number: a file of them with
    a zero (a command at 0 V) stays on the fast path (the line-by-line reader takes ten times as long).
    Vectorised over blocks of ``block`` bytes, so that its scratch arrays stay small beside the file: the pairs 'e-'
    or 'E-' are found by two comparisons a byte, the few exponents then looked at (about 1 ms for 2 MB, in blocks
    of 256 kB)."""
    a = np.frombuffer(raw, dtype=np.uint8, offset=pos)
    zero = ord("0")
    for start in range(0, a.size, block):
        chunk = a[start : start + block + 16]  # 16 bytes more: an exponent across the block's end is seen whole
        head = chunk[: block + 1]
        j = np.flatnonzero((head[1:] == ord("-")) & ((head[:-1] | 0x20) == ord("e"))) + 2  # first exponent digits
        if not j.size:
            continue
        for _ in range(8):  # past leading zeros ('E-0325')
            lead = chunk[np.minimum(j, chunk.size - 1)] == zero
            if not lead.any():
                break
            j = j + lead
        j = j[j + 2 < chunk.size]
        if j.size and np.any((chunk[j] - zero < 10) & (chunk[j + 1] - zero < 10) & (chunk[j + 2] - zero < 10)):
            return True
    return False


#: Size of a table [bytes] from which pyarrow's parser is imported to read it when no faster parser than numpy's is
#: loaded: numpy's takes 16 ms a MB (60k rows of 3 columns: 2.1 MB, 34 ms), importing pyarrow.csv 30-36 ms once,
#: pyarrow's parse a fifth of numpy's.  From 1 MB (30k rows) on, the import costs at most twice numpy's parse of that
#: one file (tens of ms in a command that takes seconds), breaks even at 2.5 MB, and every later file is parsed five
#: times faster (the app, a batch).
IMPORT_PARSER_BYTES = 2**20


def _parse_table(raw: bytes, pos: int, columns: int) -> list[np.ndarray]:
    """The columns of numbers of a comma-separated table (``raw`` from ``pos`` on) by the fastest parser at hand:
    pandas' C parser when pandas is loaded and converts by fast_float (:func:`_pandas_rounds_correctly`: 0.85 x the
    time of pyarrow's parse); else pyarrow's when it is loaded (pandas loads it) or the table is
    :data:`IMPORT_PARSER_BYTES` or more and it is installed (one thread: 0.8 x the time of an older pandas' C parser);
    else an older pandas' C parser when loaded (importing pandas costs ten times what it saves on a 60k-row file);
    else numpy's, five times slower.  Each is correctly rounded, as Python's float (tests/test_derivatives_fast_paths.py
    compares every parser with the line-by-line reader to the bit).  Any irregular cell or row raises a ValueError
    (pyarrow's ArrowInvalid and pandas' ParserError are ones)."""
    end = raw.find(b"\n", pos)
    if raw.count(b",", pos, len(raw) if end < 0 else end) != columns - 1:
        # the parsers take their column count from the first row: a row of 300,000 cells made pandas build a frame
        # of 300,000 columns (15 s for a 600 kB file) before the line-by-line reader named the line
        raise ValueError("the first row's cells are not the header's")
    pandas = sys.modules.get("pandas")
    if pandas is not None and _pandas_rounds_correctly(pandas.__version__):
        return _parse_table_pandas(pandas, raw, pos)
    pyarrow = sys.modules.get("pyarrow")
    if pyarrow is None and len(raw) - pos >= IMPORT_PARSER_BYTES:
        try:
            import pyarrow
        except ImportError:  # not installed: numpy's parser (or pandas')
            pyarrow = None
    if pyarrow is not None:
        return _parse_table_arrow(pyarrow, raw, pos, columns)
    if pandas is not None:
        return _parse_table_pandas(pandas, raw, pos)
    text = raw[pos:].decode("utf-8")
    with warnings.catch_warnings():  # no rows: "input contained no data: <_io.StringIO ...>"; the caller says it
        warnings.simplefilter("ignore", UserWarning)
        return list(np.loadtxt(io.StringIO(text), delimiter=",", comments=None, ndmin=2, dtype=float).T)


@functools.lru_cache(maxsize=4)
def _pandas_rounds_correctly(version: str) -> bool:
    """True when the pandas of ``version`` converts text to float by fast_float (pandas 3.1 on: pandas-dev/pandas
    #64432), correctly rounded; the converters before it ("high", the default, and "legacy") could miss by an ulp
    (pandas-dev/pandas #17154)."""
    parts = re.match(r"(\d+)\.(\d+)", version)
    return parts is not None and (int(parts[1]), int(parts[2])) >= (3, 1)


def _parse_table_pandas(pandas, raw: bytes, pos: int) -> list[np.ndarray]:
    """:func:`_parse_table` by pandas' C parser, on the bytes (no copy), every column as float, no NA strings."""
    stream = io.BytesIO(raw)  # no copy of the bytes
    stream.seek(pos)
    table = pandas.read_csv(stream, header=None, dtype=float, engine="c", skip_blank_lines=True, na_filter=False)
    return list(table.to_numpy().T)


def _parse_table_arrow(pyarrow, raw: bytes, pos: int, columns: int) -> list[np.ndarray]:
    """:func:`_parse_table` by pyarrow's parser: the bytes from ``pos`` on, read in place (a zero-copy buffer; a
    file object made pyarrow copy them into blocks of 1 MB), as one block (one chunk a column), by the streaming
    reader (``read_csv`` starts a thread for every call, even with ``use_threads=False``), with no quoting and no
    null strings (both rule out nothing the fast path reads: a quote sends a file to the line-by-line reader
    before, and an empty or 'NA' cell fails the conversion to float and goes there after).  0.9 x the time of the
    default options."""
    import pyarrow.csv

    csv_ = pyarrow.csv
    body = len(raw) - pos
    reader = csv_.open_csv(
        pyarrow.BufferReader(pyarrow.py_buffer(raw)[pos:]),
        read_options=csv_.ReadOptions(
            autogenerate_column_names=True, use_threads=False, block_size=max(1, min(body + 1, 2**31 - 1))
        ),
        parse_options=csv_.ParseOptions(quote_char=False, double_quote=False),
        convert_options=csv_.ConvertOptions(
            column_types={f"f{i}": pyarrow.float64() for i in range(columns)},
            null_values=[],
            strings_can_be_null=False,
        ),
    )
    table = reader.read_all()
    data = []
    for column in table.columns:
        if column.null_count:
            raise ValueError("an empty cell")  # the line-by-line reader names it
        # the values buffer of each chunk (Arrow's layout of a float64 array: validity bitmap, values), copied into
        # an array of its own (one array of the table took fresh pages from the system at every read when its
        # size was above the allocator's threshold for them); not to_numpy(), which imports pandas (300 ms)
        values = np.empty(table.num_rows)
        row = 0
        for chunk in column.chunks:
            values[row : row + len(chunk)] = np.frombuffer(
                chunk.buffers()[1], dtype=np.float64, count=len(chunk), offset=8 * chunk.offset
            )
            row += len(chunk)
        data.append(values)
    return data


def _measurement_from_table(
    path: Path, label: str, columns, data: list[np.ndarray], line_of, window, require_force: bool = False
) -> Measurement:
    """The record of a parsed table (``data``: its columns; ``line_of``: file line of each row, for messages; None on
    the fast path, whose tables have already passed the checks that need it)."""
    if data[0].size < 5:
        raise MeasurementError(f"{label}: {data[0].size} data rows; a record needs at least 5")
    si: dict[str, np.ndarray] = {}
    kind = None
    units = {}
    for c, (name, unit, col_kind) in enumerate(columns):
        target = COLUMNS.get(name) or CONTROL_UNITS[col_kind]
        with np.errstate(all="ignore"):
            si[name] = np.asarray(Q_(data[c], unit).to(target).magnitude, dtype=float)
        units[name] = unit
        if col_kind:
            kind = col_kind
        # the parsed numbers are finite (checked as they were read): in SI units too unless converted
        _check_possible(si[name], name, unit, label, c + 1, finite=si[name] is data[c])
    t = si["time"]
    col = [c[0] for c in columns].index("time")
    if line_of is not None:
        _check_time(t, lambda i: f"{label}: line {line_of[i]}, column {col + 1} (time)")
    elif t is not data[col]:  # converted: steps of a few ulp may have rounded to nothing
        _check_time(t, lambda i: f"{label}: column {col + 1} (time), data row {i + 1}")
    control_name = next((c for c in si if c in CONTROL_COLUMNS), None)
    m = Measurement._from_checked(
        t,
        si["displacement"],
        si.get("force"),
        si[control_name] if control_name else np.zeros(t.size),
        kind,
        si.get("velocity"),
        si.get("temperature"),
        path.name,
        window,
        units,
    )
    check_record(m)
    if require_force and float(np.ptp(m.force)) == 0.0:  # an unplugged load cell: esr() failed, naming no file
        raise MeasurementError(
            f"{m.name}: force: constant ({m.force[0]:g} N): the force never changes, so there is nothing to fit or "
            "judge (is the load cell connected, is it the right column?)"
        )
    return m


#: Largest magnitude each column can possibly take, SI (beyond it the file is refused: a unit mistake so large
#: that sums of squares overflow, or no damper ever built).  The largest seismic dampers make about 10 MN.
POSSIBLE_MAGNITUDE = {"displacement": 100.0, "force": 1e9, "velocity": 1e3, "time": 1e9}
#: Shortest mean time step of a record, [s] (an attosecond: no data logger comes near; below it the steps lose
#: their digits and the derivatives fail).
SHORTEST_TIME_STEP = 1e-18


def _check_possible(values: np.ndarray, name: str, unit: str, label: str, col: int, finite: bool = False) -> None:
    """Refuse a column of a file whose SI values cannot be (``finite``: they are known to be finite)."""
    where = f"{label}: column {col} ({name} [{unit}])"
    if not finite and not _all_finite(values):
        raise MeasurementError(f"{where}: a value is not finite in SI units")
    if name == "temperature" and values.size and float(values.min()) < 0.0:
        raise MeasurementError(
            f"{where}: {float(values.min()):.4g} K is below absolute zero; is the unit right (degC, not K)?"
        )
    _check_magnitude(values, name, where)


def _check_magnitude(values: np.ndarray, name: str, where: str) -> None:
    """Refuse values beyond :data:`POSSIBLE_MAGNITUDE` (a unit mistake so large that sums of squares overflow) and
    time steps below :data:`SHORTEST_TIME_STEP` (so small that differences lose every digit)."""
    limit = POSSIBLE_MAGNITUDE.get(name)
    if limit is not None and values.size:
        peak = max(float(values.max()), -float(values.min()))  # max |values|, without an array of them
        if peak > limit:
            si = COLUMNS[name]
            span = float(values.max() - values.min())
            if name == "time" and span <= limit:  # a clock time (Unix time: 1.7e9 s), not a unit mistake
                raise MeasurementError(
                    f"{where}: starts at {float(values[0]):.4g} s, a clock time (Unix time?) rather than the time "
                    f"since the record's start; subtract the first time (the record spans {span:.4g} s)"
                )
            raise MeasurementError(
                f"{where}: {peak:.3g} {si} is beyond any damper record (at most {limit:g} {si}); "
                "check the column's unit"
            )
    if name == "time" and values.size > 1:
        step = float(values[-1] - values[0]) / (values.size - 1)
        if 0 < step < SHORTEST_TIME_STEP:
            raise MeasurementError(
                f"{where}: a mean time step of {step:.3g} s is beyond any clock (at least "
                f"{SHORTEST_TIME_STEP:g} s); check the unit of the time"
            )


#: Kinds of data finding (:data:`erdesign.data.findings.FINDING_KINDS`) that :func:`check_record` warns about when a
#: record is read: a command that reads records and then lists their findings leaves these out (said once).
WARNED_AT_READ = ("time_gap",)

#: Temperatures [K] of any damper test (-73 to 227 degC): outside them a warning names the likely unit mistake.
PLAUSIBLE_TEMPERATURE = (200.0, 500.0)

#: Fewest samples, and fewest samples per cycle of the motion, below which a record is flagged.
FEW_SAMPLES, SAMPLES_PER_CYCLE = 100, 10


#: Smallest stroke [m] and force span [N] a record may have: below them no sensor resolves the motion or the force.
TINY_STROKE, TINY_FORCE = 1e-12, 1e-6


def check_record(record: "Measurement", damper=None, *, warn: bool = True) -> list[str]:  # noqa: C901
    """What looks wrong in a record, alone and (with ``damper``) against the damper it is said to come from.

    Errors (:class:`MeasurementError`): no motion at all (a constant displacement); with a damper, a control beyond
    any the fluid takes.  Warnings (:class:`~erdesign.errors.PlausibilityWarning`, each naming the column and the
    likely unit mistake): fewer than :data:`FEW_SAMPLES` samples or less than one cycle of the motion, fewer than
    :data:`SAMPLES_PER_CYCLE` samples per cycle (the time step cannot resolve the motion), a sampling rate beyond
    any data logger, a piston speed beyond any damper test; with a damper, a stroke beyond its size and a force
    far from what the damper file predicts at the record's motion and control (a factor near 1000 is named as the
    likely unit mistake: force in mN or kN, displacement in mm or m).

    Returns the warning messages (issued as warnings too unless ``warn`` is False).
    """
    from ..errors import PlausibilityWarning

    name = record.name or "record"
    unit = lambda col, si: record.units.get(col, si)  # noqa: E731
    x, t, v = record.displacement, record.time, record.velocity
    out: list[str] = []
    stroke = float(np.ptp(x))
    if stroke == 0.0:
        raise MeasurementError(
            f"{name}: displacement: constant ({x[0]:g} m): the record has no motion, so there "
            "is nothing to fit or judge"
        )
    # spans no sensor resolves (8e-300 mm, 8e-317 N: values scaled by a unit mistake or underflowed) reached the
    # fits, which divided by them (an internal error of erdesign identify)
    if stroke < TINY_STROKE:
        raise MeasurementError(
            f"{name}: displacement: the piston moves {stroke:.3g} m, less than any displacement sensor resolves "
            f"({TINY_STROKE:g} m); is the column's unit [{unit('displacement', 'm')}] right?"
        )
    F = record.force
    force_span = float(np.ptp(F)) if F is not None else 0.0
    if 0.0 < force_span < TINY_FORCE:
        raise MeasurementError(
            f"{name}: force: the force spans {force_span:.3g} N, less than any load cell resolves "
            f"({TINY_FORCE:g} N); is the column's unit [{unit('force', 'N')}] right?"
        )
    n = len(record)
    f0 = record.dominant_frequency
    cycles = _reversals(v) / 2.0  # the FFT's lowest bin is one cycle per record: count reversals instead
    if n < FEW_SAMPLES:
        out.append(f"{name}: time: only {n} samples; a fit or a diagnosis needs a few hundred over at least one cycle")
    if cycles < 1.0:
        out.append(
            f"{name}: displacement: the piston reverses {int(2 * cycles)} times; at least one full cycle "
            "(two reversals) is needed to tell viscous from yield forces"
        )
    elif f0 > 0 and record.sample_rate / f0 < SAMPLES_PER_CYCLE:
        out.append(
            f"{name}: time: {record.sample_rate / f0:.3g} samples per cycle of the motion "
            f"({f0:.3g} Hz sampled at {record.sample_rate:.3g} Hz) cannot resolve it; need at least "
            f"{SAMPLES_PER_CYCLE} (is the time column's unit [{unit('time', 's')}] right?)"
        )
    if record.sample_rate > 1e7:
        out.append(
            f"{name}: time: a sampling rate of {record.sample_rate:.3g} Hz is beyond any damper test rig; "
            f"is the time column's unit [{unit('time', 's')}] right?"
        )
    if max(float(v.max()), -float(v.min())) > 20.0:
        speed = max(float(v.max()), -float(v.min()))
        out.append(
            f"{name}: velocity: the piston speed reaches {speed:.3g} m/s, beyond any damper test; is the unit "
            f"of the displacement [{unit('displacement', 'm')}] or time [{unit('time', 's')}] column right?"
        )
    from .findings import find_time_problems  # the one detector of holes in the time column

    out += [f"{name}: time: {f.message} (at {f.where})" for f in find_time_problems(t) if f.kind in WARNED_AT_READ]
    T = record.temperature
    if T is not None and (float(T.min()) < PLAUSIBLE_TEMPERATURE[0] or float(T.max()) > PLAUSIBLE_TEMPERATURE[1]):
        lo, hi = PLAUSIBLE_TEMPERATURE
        as_celsius = (
            f"; read as degC they would be {float(T.min()):.4g} to {float(T.max()):.4g} degC, plausible: a "
            "likely unit mistake"
            if lo - 273.15 <= T.min() and T.max() <= hi - 273.15
            else ""
        )
        out.append(
            f"{name}: temperature: {float(T.min()):.4g} to {float(T.max()):.4g} K, outside the {lo:g} to "
            f"{hi:g} K any damper test runs at{as_celsius}; is the column's unit [{unit('temperature', 'K')}] "
            "right?"
        )
    if damper is not None:
        out += _check_against_damper(record, damper)
    if warn:
        for message in out:
            warnings.warn(message, PlausibilityWarning, stacklevel=2)
    return out


def read_for_damper(paths, damper) -> list["Measurement"]:
    """The measurement files, each checked against the damper (:func:`check_against_damper`: a unit mistake is
    named before a fit absorbs it) - as ``erdesign fit``, ``diagnose`` and ``batch`` read them."""
    records = []
    for path in paths:
        record = read_measurement(path)
        check_against_damper(record, damper)
        records.append(record)
    return records


def check_against_damper(record: "Measurement", damper, *, warn: bool = True) -> list[str]:
    """The checks of :func:`check_record` that need the damper only (:func:`read_measurement` has done the others):
    a control beyond any the fluid takes (error), a stroke beyond the damper's size, a force far from what the
    damper file predicts at the record's motion and control.  Returns the warning messages."""
    from ..errors import PlausibilityWarning

    out = _check_against_damper(record, damper)
    if warn:
        for message in out:
            warnings.warn(message, PlausibilityWarning, stacklevel=2)
    return out


def _reversals(v: np.ndarray) -> int:
    """Sign changes of the velocity outside the noise band below 5 % of the peak speed (two per cycle)."""
    peak = max(float(v.max()), -float(v.min())) if v.size else 0.0
    if peak == 0.0:
        return 0
    s = np.sign(v[np.abs(v) > 0.05 * peak])
    return int(np.count_nonzero(s[1:] != s[:-1]))


def _factor_hint(ratio: float) -> str:
    """' (a factor near 1000: ...)' when ``ratio`` (measured / expected) is within a factor 5 of 1e3 or 1e-3."""
    for k, text in (
        (1e3, "1000 too large"),
        (1e-3, "1000 too small"),
        (1e6, "a million too large"),
        (1e-6, "a million too small"),
    ):
        if k / 5 < ratio < k * 5:
            return f"; it is about {text}: a likely unit mistake"
    return ""


def _check_against_damper(record: "Measurement", damper) -> list[str]:
    name = record.name or "record"
    stroke = float(np.ptp(record.displacement))
    unit = lambda col, si: record.units.get(col, si)  # noqa: E731
    out = []
    if record.control_kind is not None and record.control_kind == damper.fluid.control:
        damper.fluid.check_plausible_field(record.control, f"{name}: {_control_column(record)} column")
    Dp = damper.geometry.piston_diameter
    if stroke > max(1.0, 30 * Dp):
        hint = (
            f"; in a unit 1000 x smaller it would be {stroke:.3g} mm, a plausible stroke: a likely unit mistake "
            "(values in mm given as m?)"
            if stroke / 1e3 <= 30 * Dp
            else ""
        )
        out.append(
            f"{name}: displacement: the stroke is {stroke:.3g} m, {stroke / Dp:.3g} x the piston diameter of "
            f"the damper{hint}; is the column's unit [{unit('displacement', 'm')}] right?"
        )
    elif stroke < 1e-3 * Dp:
        hint = (
            f"; in a unit 1000 x larger it would be {stroke * 1e6:.3g} mm, a plausible stroke: a likely unit "
            "mistake (values in mm given as um?)"
            if stroke * 1e3 >= 1e-3 * Dp  # the stroke in a unit 1000 x larger is plausible (8e-297 mm was not)
            else ""
        )
        out.append(
            f"{name}: displacement: the stroke is {stroke * 1e6:.3g} um, {stroke / Dp:.2g} x the piston "
            f"diameter, too small for a damper test{hint}; is the column's unit "
            f"[{unit('displacement', 'm')}] right?"
        )
    F = record.force
    if F is None or record.control_kind not in (None, damper.fluid.control):
        return out
    try:
        with np.errstate(all="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            v = np.clip(record.velocity, -20.0, 20.0)
            predicted = np.asarray(damper.force_si(v, record.control), dtype=float)
    except ErdesignError:
        return out
    if not np.all(np.isfinite(predicted)):
        return out
    spread = lambda a: float(np.percentile(a, 99) - np.percentile(a, 1))  # noqa: E731
    measured, expected = spread(F), spread(predicted)
    if expected <= 0 or measured <= 0:
        return out
    ratio = measured / expected
    if ratio > 30 or ratio < 1 / 30:
        out.append(
            f"{name}: force: the measured force spans {measured:.3g} N, {ratio:.3g} x the {expected:.3g} N the "
            f"damper file predicts at the record's motion and control{_factor_hint(ratio)}; is the unit of "
            f"the force [{unit('force', 'N')}] or displacement [{unit('displacement', 'm')}] column right, and "
            "is it the right damper file?"
        )
    return out


def _control_column(record: "Measurement") -> str:
    return next((c for c, kinds in CONTROL_COLUMNS.items() if record.control_kind in kinds), "control")


def write_measurement(
    path: str | Path,
    m: Measurement,
    *,
    units: dict[str, str] | None = None,
    comment: str = "",
    overwrite: bool = False,
    option: str = "path",
) -> None:
    """Write a record as a measurement CSV file (SI units unless ``units`` maps column -> unit).

    Written whole or not at all (an interrupt leaves no half-written file), and an existing ``path`` only with
    ``overwrite`` (:mod:`erdesign.output`; ``option`` names the output in messages, e.g. ``--out``)."""
    from ..output import open_output

    if not isinstance(m, Measurement):  # a DataFrame, or the arguments swapped: "'str' object has no attribute 'units'"
        hint = " (the arguments are path, then record)" if isinstance(m, (str, Path)) else ""
        raise MeasurementError(f"m: expected a Measurement, got {type(m).__name__}{hint}")
    if units is not None and not isinstance(units, Mapping):
        raise MeasurementError(f"units: expected a mapping of column -> unit, got {type(units).__name__} {units!r:.60}")
    units = {**m.units, **(units or {})}
    cols: list[tuple[str, np.ndarray, str]] = [("time", m.time, "s"), ("displacement", m.displacement, "m")]
    if m.force is not None:
        cols.append(("force", m.force, "N"))
    if m.control_kind is not None:
        name = next(c for c, kinds in CONTROL_COLUMNS.items() if m.control_kind in kinds)
        cols.append((name, m.control, CONTROL_UNITS[m.control_kind]))
    if m.temperature is not None:
        cols.append(("temperature", m.temperature, "K"))
    unknown = sorted(set(units) - {c[0] for c in cols} - set(m.units))
    if unknown:  # a unit for a column the record has not was dropped without a word
        raise MeasurementError(
            f"units: no column {unknown[0]!r} in this record{did_you_mean(unknown[0], [c[0] for c in cols])}; "
            f"its columns: {', '.join(c[0] for c in cols)}"
        )
    header, table = [], []
    for name, values, si_unit in cols:
        unit = units.get(name, si_unit)
        if (
            not isinstance(unit, str)
            or parse_unit(unit, f"units[{name!r}]").dimensionality != Q_(1, si_unit).dimensionality
        ):
            raise MeasurementError(
                f"units[{name!r}]: expected a unit of {dimension_name(Q_(1, si_unit).dimensionality)}, got {unit!r}"
            )
        header.append(f"{name} [{unit}]")
        table.append(Q_(values, si_unit).to(unit).magnitude)
    with open_output(path, newline="", overwrite=overwrite, option=option) as fh:
        for line in comment.splitlines():
            fh.write(f"# {line}\n")
        w = csv.writer(fh)
        w.writerow(header)
        for row in np.column_stack(table):
            w.writerow([f"{v:.10g}" for v in row])
