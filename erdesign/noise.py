r"""How much of a record is noise: displacement, velocity and force noise, and the ESR noise alone would leave.

A model that is exactly right still leaves a residual: the force noise of the load cell, and the error of
predicting from a velocity derived from a noisy displacement.  Diagnosis compares every residual with this floor
(``noise_floor_esr`` of ``erdesign diagnose --json``) instead of with zero:

.. math::
    \text{ESR}_\text{floor} = \frac{n\,\sigma_F^2 + \sum_{|v_i| < 3 w \sigma_v} (r_i^2 - \sigma_F^2)_+}
                                   {\sum_i (F_i - \bar F)^2}

- :math:`\sigma_F`: white force noise, from the fourth differences of the force (median absolute deviation, robust
  to the force jumps at reversals; the fourth difference of a signal sampled many times per period is negligible);
- :math:`\sigma_v`: noise of the velocity, propagated through the same differentiation the record's velocity came
  from (:func:`velocity_noise`);
- the second sum is the residual :math:`r_i` of the calibrated model on the samples whose velocity is within three
  sign widths :math:`w\sigma_v` of zero: there the sign of the true velocity is not known, and a yield-stress
  fluid's force jumps by twice its yield force.  (An expectation such as :math:`F_y^2(1 - \operatorname{erf}^2)`
  over-counts this several times on records of the virtual rig, because few samples fall in so narrow a band;
  the band's own residual is what the record actually lost there.)

The estimate is first order (noise small against the signal) and assumes white noise; filtered or smoothed
records (a moving average before export) hide their noise from the differences, and their floor is then
underestimated - which errs on the side of saying a residual is *not* noise.
"""

from __future__ import annotations

import math
import weakref
from dataclasses import replace

import numpy as np

from .measurement import Measurement, _noise_level, derivatives

__all__ = ["displacement_noise", "velocity_noise", "force_noise", "noise_floor_esr"]

_CACHE: dict[int, tuple[weakref.ref, float]] = {}


def displacement_noise(record: Measurement) -> float:
    """Standard deviation of white noise on the displacement, [m] (fourth differences, robust)."""
    return _noise_level(np.asarray(record.displacement, dtype=float))


def force_noise(record: Measurement) -> float:
    """Standard deviation of white noise on the force, [N] (fourth differences, robust); 0 without a force."""
    return 0.0 if record.force is None else _noise_level(np.asarray(record.force, dtype=float))


def velocity_noise(record: Measurement) -> float:
    r"""Standard deviation of the noise of the record's velocity, [m/s].

    A measured velocity column: from its own fourth differences.  A derived velocity: the displacement noise
    :math:`\sigma_x` is propagated through :func:`erdesign.measurement.derivatives` by differentiating the record
    again with fresh noise of the same level added (fixed seed) and taking the RMS of the change; this follows
    whatever rule (Fourier filtering or adaptive low-pass) the record's velocity came from.  The value is cached per
    record and kept by thinned copies (:attr:`Measurement.velocity_noise`).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 2, 2001); x = 0.01 * np.sin(2 * np.pi * t)
    >>> velocity_noise(Measurement.from_arrays(t, x)) < 1e-9        # no noise but round-off
    True
    """
    if record.velocity_noise is not None:
        return float(record.velocity_noise)
    key = id(record.velocity)
    hit = _CACHE.get(key)
    if hit is not None and hit[0]() is record.velocity:
        return hit[1]
    if "velocity" in record.units:
        sigma = _noise_level(np.asarray(record.velocity, dtype=float))
    else:
        sx = displacement_noise(record)
        if sx == 0 or len(record) < 16:
            sigma = 0.0
        else:
            t, x = record.time, np.asarray(record.displacement, dtype=float)
            rng = np.random.default_rng(12345)
            v1 = derivatives(t, x)[0]
            v2 = derivatives(t, x + sx * rng.standard_normal(x.size))[0]
            sigma = float(np.sqrt(np.mean((v2 - v1) ** 2)))
    try:
        _CACHE[key] = (weakref.ref(record.velocity), sigma)
    except TypeError:       # an array type without weak references: no cache
        pass
    if len(_CACHE) > 256:
        for k in [k for k, (ref, _) in _CACHE.items() if ref() is None]:
            del _CACHE[k]
    return sigma


def noise_floor_esr(record: Measurement, residual, *, band: float = 3.0, sigma_v: float | None = None) -> float:
    """ESR that noise alone would leave on ``record`` for a model that leaves ``residual`` (module notes).

    Parameters
    ----------
    record : Measurement
        With a force.
    residual : array
        Measured minus model force of the calibrated model, [N].
    band : float
        Half-width of the reversal band in units of the velocity noise: samples with |v| < band sigma_v count
        as noise whatever their residual (the sign of the velocity is not known there).
    sigma_v : float, optional
        The velocity noise, [m/s]; default :func:`velocity_noise` of the record.

    Returns
    -------
    float
        In [0, 1] (0 when the force does not vary).

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0); t = np.linspace(0, 2, 2001)
    >>> F = 1000 * np.cos(2 * np.pi * t) + 10 * rng.standard_normal(2001)
    >>> rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t), F)
    >>> ratio = noise_floor_esr(rec, F - 1000 * np.cos(2 * np.pi * t)) / (10**2 / (1000**2 / 2))  # floor / noise
    >>> bool(0.8 < ratio < 1.2)           # the 4th-difference estimate of 2001 samples is good to about 10 %
    True
    """
    F = record.require_force()
    ss = float(np.sum((F - F.mean()) ** 2))
    if not ss > 0:
        return 0.0
    sF = force_noise(record)
    sv = velocity_noise(record) if sigma_v is None else float(sigma_v)
    r = np.asarray(residual, dtype=float)
    in_band = np.abs(record.velocity) < band * sv
    extra = float(np.sum(np.maximum(r[in_band] ** 2 - sF**2, 0.0))) if sv > 0 else 0.0
    out = (F.size * sF**2 + extra) / ss
    return float(min(out, 1.0)) if math.isfinite(out) else 1.0
