r"""Lab artefacts applied to a record: what instruments and exports do to a truth-rig measurement.

Each function takes a :class:`~erdesign.data.measurement.Measurement` (typically ``TruthRecord.measured``) and
returns a new one with the artefact, its velocity and acceleration derived again from the changed displacement, as
a test rig's software would.  They are written apart from the detectors of :mod:`erdesign.data.findings` (which
never import them) so that a test makes an artefact one way and finds it another.

========================  ===========================================================================================
function                  artefact
========================  ===========================================================================================
:func:`clip_force`        the force held at a level (a load cell or amplifier at its limit)
:func:`saturate_displacement`  the displacement held at +-a level while the piston moves on
:func:`moving_average`    a causal moving average over N samples of the force and the displacement before export
:func:`skew_force`        the force lagging the displacement by s seconds (channels sampled at different times)
:func:`cut_time_gap`      samples missing over a span of time
:func:`offset_and_drift`  a constant force offset plus a linear drift
:func:`quantize_displacement`  the displacement rounded to a grid of steps
:func:`shuffle_time`      arrays whose time goes back (rows out of order): returns arrays, not a record
========================  ===========================================================================================

>>> import numpy as np
>>> from erdesign.data.measurement import Measurement
>>> t = np.linspace(0, 2, 1001)
>>> m = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t), 100 * np.cos(2 * np.pi * t))
>>> float(clip_force(m, 80.0).force.max())
80.0
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from scipy.interpolate import CubicSpline

from ...data.measurement import Measurement

__all__ = [
    "clip_force",
    "saturate_displacement",
    "moving_average",
    "skew_force",
    "cut_time_gap",
    "offset_and_drift",
    "quantize_displacement",
    "shuffle_time",
]


def _rebuild(m: Measurement, time=None, displacement=None, force=None, keep=None) -> Measurement:
    """The record with new arrays (``keep``: the samples kept), derivatives derived again from the displacement."""
    pick = (lambda a: a) if keep is None else (lambda a: None if a is None else a[keep])
    t = pick(m.time) if time is None else time
    x = pick(m.displacement) if displacement is None else displacement
    F = pick(m.force) if force is None else force
    out = Measurement.from_arrays(
        t,
        x,
        F,
        control=pick(m.control) if m.control_kind else None,
        control_kind=m.control_kind,
        temperature=pick(m.temperature),
        name=m.name,
    )
    return replace(out, units=dict(m.units))


def _force(m: Measurement) -> np.ndarray:
    if m.force is None:
        raise ValueError(f"record: {m.name or 'the record'} has no force column")
    return m.force


def clip_force(m: Measurement, level: float, *, lower: float | None = None) -> Measurement:
    """The force clipped at ``level`` [N] (and at ``lower`` [N] when given)."""
    F = np.minimum(_force(m), float(level))
    if lower is not None:
        F = np.maximum(F, float(lower))
    return replace(m, force=F)


def saturate_displacement(m: Measurement, level: float) -> Measurement:
    """The displacement channel held within +-``level`` [m]; the force (of the true motion) is unchanged."""
    if level <= 0:
        raise ValueError(f"level: must be > 0 m, got {level}")
    return _rebuild(m, displacement=np.clip(m.displacement, -level, level))


def _causal_average(y: np.ndarray, N: int) -> np.ndarray:
    padded = np.r_[np.full(N - 1, y[0]), y]  # the channel at rest before the record: no start transient
    c = np.cumsum(np.r_[0.0, padded])
    return (c[N:] - c[:-N]) / N


def moving_average(m: Measurement, samples: int) -> Measurement:
    """A causal moving average over ``samples`` samples of the force and the displacement (as the Quiroz (2022)
    preprocessed files were exported: over a tenth of a period)."""
    N = int(samples)
    if N < 2:
        raise ValueError(f"samples: must be an integer >= 2, got {samples}")
    F = None if m.force is None else _causal_average(m.force, N)
    return _rebuild(m, displacement=_causal_average(m.displacement, N), force=F)


def skew_force(m: Measurement, skew: float) -> Measurement:
    """The force lagging the displacement by ``skew`` [s] (negative: leading): the displacement channel is read
    ``skew`` later than the force, x'(t) = x(t + skew) (a cubic spline of the smooth channel; the last samples hold
    the end value)."""
    t = m.time
    x = CubicSpline(t, m.displacement)(np.clip(t + float(skew), t[0], t[-1]))
    return _rebuild(m, displacement=x)


def cut_time_gap(m: Measurement, start: float, length: float) -> Measurement:
    """The samples with ``start <= t < start + length`` [s] removed (a logger that stopped)."""
    keep = ~((m.time >= start) & (m.time < start + length))
    if keep.sum() < 5 or keep.all():
        raise ValueError(
            f"start, length: the span {start:g}-{start + length:g} s must remove some samples and keep at least 5"
        )
    return _rebuild(m, keep=keep)


def offset_and_drift(m: Measurement, offset: float, drift: float) -> Measurement:
    """The force plus ``offset`` [N] plus a linear drift of ``drift`` [N] over the record."""
    tau = (m.time - m.time[0]) / m.duration
    return replace(m, force=_force(m) + float(offset) + float(drift) * tau)


def quantize_displacement(m: Measurement, step: float) -> Measurement:
    """The displacement rounded to whole multiples of ``step`` [m] (an encoder or ADC)."""
    if step <= 0:
        raise ValueError(f"step: must be > 0 m, got {step}")
    return _rebuild(m, displacement=np.round(m.displacement / step) * step)


def shuffle_time(m: Measurement, at: int, rows: int = 2) -> dict[str, np.ndarray]:
    """Arrays ``time``, ``displacement``, ``force`` with ``rows`` rows from sample ``at`` on written in reverse
    order (time goes back): what a caller might hand to the API; no record can hold it."""
    idx = np.arange(len(m))
    idx[at : at + rows] = idx[at : at + rows][::-1]
    return {"time": m.time[idx], "displacement": m.displacement[idx], "force": _force(m)[idx]}
