r"""The excitation amplitude and frequency some catalogue models take as parameters.

Several models of the MR-model review scale their coefficients with the stroke amplitude or the excitation
frequency of a harmonic test (Ali and Ramaswamy, eq 27; Dominguez et al., eq 32; Metered et al., eq 90; Cheng et
al., eq 98; and the velocity scale of Kamath and Wereley 1997, eq 9).  Here such quantities are explicit parameters
held a priori (``fitted=False``): a simulation uses the value given, never a value read silently from the rest of
the record, and identification starts from the record's own value (:func:`record_amplitude`,
:func:`record_frequency`) and reports it.  :func:`warn_if_multi_amplitude` says when a record is not one harmonic
test, where one amplitude cannot describe it.
"""

from __future__ import annotations

import warnings

import numpy as np

__all__ = ["cycle_peaks", "record_amplitude", "record_frequency", "warn_if_multi_amplitude"]


def record_amplitude(record) -> float:
    """Half the peak-to-peak displacement of the record [m] (the stroke amplitude of a harmonic test)."""
    x = np.asarray(record.displacement, dtype=float)
    return 0.5 * float(np.ptp(x)) if x.size else 0.0


def record_frequency(record) -> float:
    """Excitation frequency [Hz] from the velocity reversals: (number of sign changes) / (2 x duration); 0 when the
    velocity never reverses.

    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 2001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * 3 * t))
    >>> round(record_frequency(rec), 1)
    3.0
    """
    v = np.asarray(record.velocity, dtype=float)
    s = np.sign(v[np.abs(v) > 1e-9 * (np.max(np.abs(v)) if v.size else 0.0)])
    reversals = int(np.count_nonzero(s[1:] != s[:-1])) if s.size > 1 else 0
    duration = float(record.time[-1] - record.time[0]) if len(record) > 1 else 0.0
    return reversals / (2.0 * duration) if duration > 0 else 0.0


def cycle_peaks(values: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """Peak |values| between successive sign changes of ``reference`` (one per half cycle)."""
    values = np.abs(np.asarray(values, dtype=float))
    s = np.sign(reference)
    cuts = np.flatnonzero(s[1:] * s[:-1] < 0) + 1
    parts = np.split(values, cuts)
    return np.array([p.max() for p in parts if p.size])


def warn_if_multi_amplitude(record, what: str, quantity: str = "velocity", tolerance: float = 0.1) -> None:
    """Warn when the half-cycle peaks of the record's displacement (or velocity) differ by more than ``tolerance``
    (relative): a model that takes one amplitude for the whole record then depends on the rest of the record."""
    y = record.velocity if quantity == "velocity" else record.displacement
    ref = record.displacement if quantity == "velocity" else record.velocity
    peaks = cycle_peaks(y, ref)
    inner = peaks[1:-1] if peaks.size > 3 else peaks  # the first and last half cycles are usually partial
    if inner.size >= 2 and inner.max() > 0 and (inner.max() - inner.min()) / inner.max() > tolerance:
        warnings.warn(
            f"{what}: the record's {quantity} peaks range from {inner.min():.3g} to {inner.max():.3g} "
            f"(SI) - it is not one harmonic test, so the single {quantity} scale this model takes "
            f"describes only part of it; give the scale explicitly or split the record",
            stacklevel=3,
        )
