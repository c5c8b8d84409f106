r"""How much of a record is noise: displacement, velocity and force noise, and the ESR noise alone would leave.

A model that is exactly right still leaves a residual: the force noise of the load cell, and the error of
predicting from a velocity derived from a noisy displacement.  At a reversal a yield-stress damper's force jumps by
twice its yield force; where the measured velocity is within its noise of zero the sign of the true velocity, and
so the force, is not known.  Diagnosis therefore judges models only on the samples where the sign is known
(:func:`sign_known`), where the floor is the force noise alone (:func:`force_noise_esr`):

.. math::
    \text{ESR}_\text{floor, judged} = \frac{n_k\,\sigma_F^2}{\sum_{i \in k} (F_i - \bar F_k)^2}

and reports, for the whole record (``noise_floor_esr`` of ``erdesign diagnose --json``), the floor with what the
unknown sign costs added (:func:`noise_floor_esr`):

.. math::
    \text{ESR}_\text{floor} = \frac{n\,\sigma_F^2 + \sum_i F_{J,i}^2\,\bigl(1 - \operatorname{erf}^2
                                   (|v_i| / \sqrt{2}\sigma_v)\bigr)}{\sum_i (F_i - \bar F)^2}

- :math:`\sigma_F`: white force noise, from the fourth differences of the force (median absolute deviation, robust
  to the force jumps at reversals; the fourth difference of a signal sampled many times per period is negligible);
- :math:`\sigma_v`: noise of the velocity, propagated through the same differentiation the record's velocity came
  from (:func:`velocity_noise`);
- :math:`F_{J,i}`: half the force jump at a reversal (yield force plus seal friction); the second term is the
  variance of :math:`F_J \operatorname{sgn}(v)` given the measured velocity.  It is an expectation: a derived
  velocity is often better than its noise level near a reversal, and on the benchmark records the full-record ESR
  of a correct model lies between 0.2 and 3 times it - which is why verdicts are judged on the known samples.

The estimates are first order (noise small against the signal) and assume white noise; filtered or smoothed
records (a moving average before export) hide their noise from the differences, and their floor is then
underestimated - which errs on the side of saying a residual is *not* noise.  Fourth differences also take force
changes faster than a few samples for noise (a 3 kHz record thinned for analysis).  :mod:`erdesign.data.noise_floor`
estimates the floor from what the record shows to be noise (a still segment, repeated cycles, the spectrum above
the excited band) and adds what the motion channel costs; :func:`force_noise` is its last resort.
"""

from __future__ import annotations

import math
import weakref

import numpy as np
from scipy.special import erf

from .measurement import Measurement, _noise_level, derivatives

__all__ = [
    "displacement_noise",
    "velocity_noise",
    "force_noise",
    "noise_floor_esr",
    "sign_known",
    "force_noise_esr",
    "SIGN_BAND",
    "EDGE_FRACTION",
]

#: Half-width of the reversal band, in units of the velocity noise: inside it the sign of the velocity is unknown.
SIGN_BAND = 3.0
#: Share of the samples at each end of the record whose derived velocity counts as unreliable (filter edges).
EDGE_FRACTION = 0.01

_CACHE: dict[int, tuple[weakref.ref, float]] = {}
#: id of a displacement array -> (weak reference, displacement noise, acceleration noise) from velocity_noise
_ACCELERATION_CACHE: dict[int, tuple[weakref.ref, float, float]] = {}


def displacement_noise(record: Measurement) -> float:
    """Standard deviation of white noise on the displacement, [m] (fourth differences, robust)."""
    return _noise_level(np.asarray(record.displacement, dtype=float))


def force_noise(record: Measurement) -> float:
    """Standard deviation of white noise on the force, [N] (fourth differences, robust); 0 without a force."""
    return 0.0 if record.force is None else _noise_level(np.asarray(record.force, dtype=float))


#: Smallest velocity noise taken, as a fraction of the record's peak speed (:func:`velocity_noise`): far below any
#: transducer's resolution, far above the round-off of a derivative.
VELOCITY_RESOLUTION = 1e-6


def velocity_noise(record: Measurement) -> float:
    r"""Standard deviation of the noise of the record's velocity, [m/s].

    A measured velocity column: from its own fourth differences.  A derived velocity: the displacement noise
    :math:`\sigma_x` is propagated through :func:`erdesign.data.measurement.derivatives` by differentiating the record
    again with fresh noise of the same level added (fixed seed) and taking the RMS of the change; this follows
    whatever rule (Fourier filtering or adaptive low-pass) the record's velocity came from.  The value is cached per
    record and kept by thinned copies (:attr:`Measurement.velocity_noise`).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 2, 2001); x = 0.01 * np.sin(2 * np.pi * t)
    >>> round(velocity_noise(Measurement.from_arrays(t, x)) / (2 * np.pi * 0.01), 9)  # no noise: the floor, 1e-6
    1e-06
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
            v1, a1 = derivatives(t, x)
            v2, a2 = derivatives(t, x + sx * rng.standard_normal(x.size))
            sigma = float(np.sqrt(np.mean((v2 - v1) ** 2)))
            # the acceleration's noise comes out of the same two differentiations: kept for
            # erdesign.data.noise_floor.motion_noise (the filters' ends left out, as there)
            edge = min(max(3, int(EDGE_FRACTION * x.size)), x.size // 4)
            try:
                _ACCELERATION_CACHE[id(record.displacement)] = (
                    weakref.ref(record.displacement),
                    sx,
                    float(np.sqrt(np.mean((a2 - a1)[edge : x.size - edge] ** 2))),
                )
            except TypeError:
                pass
    # A velocity is never known better than VELOCITY_RESOLUTION of its peak: on a record without noise the
    # derivative's own error (about 1e-10 of the peak for the Fourier rule) would otherwise decide the sign of a
    # sample that falls exactly on a reversal, where the force of a rigid-plastic gap is anywhere within +-F_y
    peak = float(np.max(np.abs(record.velocity))) if len(record) else 0.0
    sigma = max(sigma, VELOCITY_RESOLUTION * peak)
    try:
        _CACHE[key] = (weakref.ref(record.velocity), sigma)
    except TypeError:  # an array type without weak references: no cache
        pass
    if len(_CACHE) > 256:
        for k in [k for k, (ref, _) in _CACHE.items() if ref() is None]:
            del _CACHE[k]
        for k in [k for k, (ref, *_) in _ACCELERATION_CACHE.items() if ref() is None]:
            del _ACCELERATION_CACHE[k]
    return sigma


def sign_known(record: Measurement, sigma_v: float | None = None) -> np.ndarray:
    r"""True on the samples where the sign of the piston velocity is known from the record.

    A yield-stress damper's force jumps by twice its yield force when the velocity changes sign; where the record
    cannot tell that sign the force cannot be predicted by any model, whatever mechanisms it holds.  Unknown are:
    the samples with :math:`|v| < 3\sigma_v` (:data:`SIGN_BAND`, :math:`\sigma_v` the velocity noise) and the first
    and last :data:`EDGE_FRACTION` of the record (at least 3 samples each), where a derivative filter has no
    samples on one side.  (A motion whose velocity jumps - a kinked displacement - defeats any derivative filter:
    the sign is then wrong for a sample or two beyond the band; the truth rig's motions are smooth.)  Diagnosis judges models on the other samples, where the only noise is
    the load cell's.  If that would leave fewer than half the samples (a very noisy velocity), the band shrinks to
    the median speed.

    Examples
    --------
    >>> t = np.linspace(0, 1, 1001); x = 0.01 * np.sin(2 * np.pi * t)
    >>> known = sign_known(Measurement.from_arrays(t, x), sigma_v=1e-3)
    >>> bool(known[500]), bool(known[250]), bool(known[0]), round(float(known.mean()), 2)   # crest, reversal, edge
    (True, False, False, 0.95)
    """
    v = np.asarray(record.velocity, dtype=float)
    n = v.size
    sv = velocity_noise(record) if sigma_v is None else float(sigma_v)
    speed = np.abs(v)
    band = min(SIGN_BAND * sv, float(np.median(speed)))
    known = speed >= band if band > 0 else np.ones(n, dtype=bool)
    edge = min(max(3, int(EDGE_FRACTION * n)), n // 4)
    known[:edge] = False
    known[n - edge :] = False
    return known


def force_noise_esr(record: Measurement, mask: np.ndarray | None = None) -> float:
    r"""ESR that the force noise alone leaves on the samples of ``mask`` (default all):
    :math:`n\,\sigma_F^2 / \sum (F_i - \bar F)^2` over them, with :math:`\sigma_F` from :func:`force_noise`.

    On the samples where the sign of the velocity is known (:func:`sign_known`) this is the whole noise floor of a
    correct model (the velocity noise's share, :math:`(\partial F/\partial v)^2\sigma_v^2`, is below 10 % of it on
    the benchmark records).

    Examples
    --------
    >>> rng = np.random.default_rng(1); t = np.linspace(0, 2, 4001)
    >>> F = 1000 * np.sin(2 * np.pi * t) + 10 * rng.standard_normal(t.size)
    >>> rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t), F)
    >>> bool(0.8 < force_noise_esr(rec) / (10**2 / (1000**2 / 2)) < 1.2)
    True
    """
    F = record.require_force()
    Fm = F if mask is None else F[mask]
    ss = float(np.sum((Fm - Fm.mean()) ** 2)) if Fm.size else 0.0
    if not ss > 0:
        return 0.0
    out = Fm.size * force_noise(record) ** 2 / ss
    return float(min(out, 1.0)) if math.isfinite(out) else 1.0


def noise_floor_esr(record: Measurement, jump=0.0, *, sigma_v: float | None = None) -> float:
    """ESR that noise alone would leave on the whole of ``record`` for a correct model (module notes).

    Parameters
    ----------
    record : Measurement
        With a force.
    jump : float or array
        Half the force jump at a reversal, [N]: the yield force plus the seal friction (per sample, or one value).
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
    >>> ratio = noise_floor_esr(rec) / (10**2 / (1000**2 / 2))     # no jump: the force noise alone
    >>> bool(0.8 < ratio < 1.2)           # the 4th-difference estimate of 2001 samples is good to about 10 %
    True
    >>> bool(noise_floor_esr(rec, 500.0, sigma_v=1e-3) > 3 * noise_floor_esr(rec))   # a yield force of 500 N
    True
    """
    F = record.require_force()
    ss = float(np.sum((F - F.mean()) ** 2))
    if not ss > 0:
        return 0.0
    sF = force_noise(record)
    sv = velocity_noise(record) if sigma_v is None else float(sigma_v)
    J = np.broadcast_to(np.abs(np.asarray(jump, dtype=float)), F.shape)
    sign = 0.0
    if sv > 0:
        p = erf(np.abs(np.asarray(record.velocity, dtype=float)) / (math.sqrt(2) * sv))
        sign = float(np.sum(J**2 * (1 - p**2)))
    out = (F.size * sF**2 + sign) / ss
    return float(min(out, 1.0)) if math.isfinite(out) else 1.0
