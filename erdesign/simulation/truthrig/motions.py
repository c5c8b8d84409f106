r"""Motions for the truth rig made apart from the team's own generators of :mod:`erdesign.simulation.rig`.

The diagnosis benchmark must not only see motions of one random generator
(:func:`erdesign.simulation.rig.random_motion`: Gaussian noise shaped in the frequency domain, flat between two
corners, zero phase).  The generators here make random and swept motion by other means, the way other labs command
their actuators:

* :func:`swept_sine`: a logarithmic sine sweep at a constant peak speed (a swept-sine test programme);
* :func:`sine_programme`: a DoE-style test plan of separate sine runs, each faded in and out, with rests between;
* :func:`ornstein_uhlenbeck_motion`: an Ornstein-Uhlenbeck (mean-reverting) random command, integrated exactly in the
  time domain, followed by a servo actuator (a causal critically damped second-order low-pass);
* :func:`random_phase_multisine`: a periodic multi-sine, lines at multiples of 1 / period with random phases and
  amplitudes falling as 1/f (flat velocity spectrum), several periods repeated;
* :func:`filtered_gaussian_motion`: white Gaussian noise through a causal Butterworth band-pass (time-domain
  recursion, so its phase is not zero), as a random displacement command (the Dyke NEES "ransim" kind of test).

All are computed on a grid :data:`~erdesign.simulation.rig.OVERSAMPLING` times finer than the sampling and
differentiated there (as the rig's own generators), start and end at rest, and carry no control (the benchmark adds
it, :func:`erdesign.simulation.truthrig.cases.control_staircase`).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import signal

from ...errors import ErdesignError
from ..rig import OVERSAMPLING, Motion

__all__ = [
    "swept_sine",
    "sine_programme",
    "ornstein_uhlenbeck_motion",
    "random_phase_multisine",
    "filtered_gaussian_motion",
]


def _grid(duration: float, rate: float) -> np.ndarray:
    n = int(round(duration * rate))
    if not (math.isfinite(duration) and duration > 0 and n >= 8):
        raise ErdesignError(f"duration: {duration!r} s at {rate!r} Hz gives fewer than 8 samples")
    return np.linspace(0.0, n / rate, n * OVERSAMPLING + 1)


def _sampled(t: np.ndarray, x: np.ndarray, description: str) -> Motion:
    v = np.gradient(x, t, edge_order=2)
    a = np.gradient(v, t, edge_order=2)
    s = slice(None, None, OVERSAMPLING)
    return Motion(t[s], x[s], v[s], a[s], np.zeros(t[s].size), description)


def _at_rest_ends(t: np.ndarray, x: np.ndarray, ramp: float) -> np.ndarray:
    """Half-cosine fade-in and fade-out over ``ramp`` seconds (the actuator starts and stops at rest)."""
    w = np.clip(np.minimum(t - t[0], t[-1] - t) / ramp, 0.0, 1.0)
    return x * (0.5 - 0.5 * np.cos(np.pi * w))


def swept_sine(speed: float, f_start: float, f_end: float, *, duration: float, rate: float) -> Motion:
    r"""Logarithmic sine sweep from ``f_start`` to ``f_end`` [Hz] over ``duration`` [s] at peak speed ``speed`` [m/s].

    .. math::
        f(t) = f_0 (f_1/f_0)^{t/T}, \quad \phi(t) = 2\pi \int_0^t f\,dt, \quad
        x(t) = \frac{v_\text{peak}}{2\pi f(t)} \sin\phi(t)

    faded in and out over 0.5 s and scaled to the peak speed ``speed`` exactly.  The amplitude falls as the
    frequency rises, so the speed peaks stay near ``speed`` over the whole sweep (within the few percent that the
    sliding amplitude adds).

    >>> m = swept_sine(0.2, 0.5, 5.0, duration=20.0, rate=500)
    >>> len(m.time), round(float(abs(m.velocity).max()), 2)
    (10001, 0.2)
    """
    if not (0 < f_start and 0 < f_end and 8 * max(f_start, f_end) <= rate):
        raise ErdesignError(f"f_start, f_end: need 0 < f and 8 f <= rate, got {f_start!r}, {f_end!r} at {rate!r} Hz")
    t = _grid(duration, rate)
    T = t[-1]
    k = math.log(f_end / f_start) / T
    f = f_start * np.exp(k * t)
    phase = 2 * np.pi * f_start * np.expm1(k * t) / k if k != 0 else 2 * np.pi * f_start * t
    x = _at_rest_ends(t, speed / (2 * np.pi * f) * np.sin(phase), 0.5)
    x *= speed / np.max(np.abs(np.gradient(x, t)))
    return _sampled(
        t, x, f"swept sine {f_start:g}-{f_end:g} Hz (logarithmic) over {duration:g} s at {speed:g} m/s peak"
    )


def sine_programme(amplitudes, frequencies, *, duration: float, rate: float, rest: float = 0.25) -> Motion:
    r"""A DoE-style programme of sine tests: run k is a sine of amplitude ``amplitudes[k]`` [m] at
    ``frequencies[k]`` [Hz], faded in over its first cycle and out over its last, followed by ``rest`` [s] at rest.

    Every run has the same number of cycles, chosen so that the programme lasts about ``duration`` [s] (at least
    three cycles a run).  Each run starts and ends at rest, as a test machine runs the points of a test plan one by
    one (unlike :func:`erdesign.simulation.rig.stepped_sine`, which blends one segment into the next).

    >>> m = sine_programme([0.01, 0.005], [1.0, 2.0], duration=12.0, rate=500)
    >>> round(float(m.time[-1]), 1), round(float(abs(m.displacement).max()), 4), abs(float(m.velocity[0])) < 1e-6
    (11.0, 0.01, True)
    """
    A = np.asarray(amplitudes, dtype=float)
    f = np.asarray(frequencies, dtype=float)
    if A.shape != f.shape or A.size == 0 or np.any(A <= 0) or np.any(f <= 0) or 8 * f.max() > rate:
        raise ErdesignError(
            "amplitudes, frequencies: need as many positive amplitudes as frequencies, each "
            "resolved by 8 samples a period at the rate"
        )
    cycles = max(3, int((duration - rest * A.size) / float(np.sum(1 / f))))
    t = _grid(rest * A.size + cycles * float(np.sum(1 / f)), rate)
    x = np.zeros(t.size)
    start = 0.0
    for Ak, fk in zip(A, f):
        length = cycles / fk
        into = t - start
        inside = (into >= 0) & (into <= length)
        ramp = np.clip(np.minimum(into, length - into) * fk, 0.0, 1.0)
        x[inside] = (Ak * (0.5 - 0.5 * np.cos(np.pi * ramp)) * np.sin(2 * np.pi * fk * into))[inside]
        start += length + rest
    runs = ", ".join(f"{a * 1e3:.3g} mm at {fr:g} Hz" for a, fr in zip(A, f))
    return _sampled(t, x, f"sine programme of {A.size} runs, {cycles} cycles each ({runs}), {rest:g} s rest between")


def ornstein_uhlenbeck_motion(
    rms: float, correlation_time: float, actuator_bandwidth: float, *, duration: float, rate: float, seed: int
) -> Motion:
    r"""An Ornstein-Uhlenbeck displacement command of RMS ``rms`` [m] followed by a servo actuator.

    The command is the stationary Ornstein-Uhlenbeck process :math:`dc = -c/\tau\,dt + \sigma\sqrt{2/\tau}\,dW`,
    integrated exactly on the fine grid (:math:`c_{k+1} = c_k e^{-\Delta t/\tau} + \sigma\sqrt{1 - e^{-2\Delta
    t/\tau}}\,\xi_k`, Gillespie 1996); the actuator follows it as a critically damped second-order system of
    bandwidth ``actuator_bandwidth`` [Hz] (bilinear transform, causal), which makes the displacement smooth enough
    to have a velocity and an acceleration.  Faded in and out over 10 % of the record, scaled to RMS ``rms``.

    References
    ----------
    Gillespie, D. T. (1996). Exact numerical simulation of the Ornstein-Uhlenbeck process and its integral.
    Physical Review E 54, 2084-2091, eq 1.3.

    >>> m = ornstein_uhlenbeck_motion(0.005, 0.2, 8.0, duration=10.0, rate=500, seed=1)
    >>> len(m.time), round(float(np.sqrt(np.mean(m.displacement**2))), 4)
    (5001, 0.005)
    """
    t = _grid(duration, rate)
    dt = t[1] - t[0]
    rng = np.random.default_rng(seed)
    e = math.exp(-dt / correlation_time)
    xi = rng.standard_normal(t.size) * math.sqrt(1 - e * e)
    c = signal.lfilter([1.0], [1.0, -e], xi, zi=[e * rng.standard_normal()])[0]  # c_k = e c_{k-1} + xi_k
    w = 2 * np.pi * actuator_bandwidth
    b, a = signal.bilinear([w * w], [1.0, 2 * w, w * w], fs=1.0 / dt)
    x = signal.lfilter(b, a, c - c[0])
    x = _at_rest_ends(t, x, 0.1 * duration)
    x *= rms / np.sqrt(np.mean(x**2))
    return _sampled(
        t,
        x,
        f"Ornstein-Uhlenbeck command (correlation time {correlation_time:g} s) through a "
        f"{actuator_bandwidth:g} Hz servo, RMS {rms * 1e3:g} mm",
    )


def random_phase_multisine(
    speed: float, band: tuple[float, float], period: float, *, duration: float, rate: float, seed: int
) -> Motion:
    r"""A periodic multi-sine: every multiple of 1 / ``period`` within ``band`` [Hz] at a random phase, amplitude
    :math:`\propto 1/f` (every line the same velocity amplitude), scaled to peak speed ``speed`` [m/s].

    .. math::
        x(t) = \sum_k \frac{A}{2\pi f_k} \sin(2\pi f_k t + \varphi_k), \quad f_k = k / T_p, \quad
        \varphi_k \sim U(0, 2\pi)

    The motion repeats every ``period`` [s] (a test programme that repeats its cycles, e.g. to average the noise);
    faded in and out over half a period (the first and last periods are then not exact repeats).

    >>> m = random_phase_multisine(0.1, (0.5, 5.0), 4.0, duration=16.0, rate=500, seed=3)
    >>> round(float(abs(m.velocity).max()), 3), bool(np.allclose(m.displacement[2000:4000], m.displacement[4000:6000]))
    (0.1, True)
    """
    t = _grid(duration, rate)
    rng = np.random.default_rng(seed)
    k = np.arange(max(1, math.ceil(band[0] * period)), math.floor(band[1] * period) + 1)
    if k.size == 0 or 8 * k[-1] / period > rate:
        raise ErdesignError(f"band: no line of a {period:g} s period within {band} Hz that {rate:g} Hz resolves")
    f = k / period
    phases = rng.uniform(0, 2 * np.pi, f.size)
    x = np.zeros(t.size)
    for fk, pk in zip(f, phases):
        x += np.sin(2 * np.pi * fk * t + pk) / (2 * np.pi * fk)
    x = _at_rest_ends(t, x, 0.5 * period)
    x *= speed / np.max(np.abs(np.gradient(x, t)))
    return _sampled(
        t, x, f"random-phase multi-sine, {f.size} lines {f[0]:g}-{f[-1]:g} Hz, period {period:g} s, {speed:g} m/s peak"
    )


def filtered_gaussian_motion(
    peak: float, band: tuple[float, float], *, duration: float, rate: float, seed: int, order: int = 2
) -> Motion:
    r"""White Gaussian noise through a causal Butterworth band-pass of ``order`` [-] between ``band`` [Hz],
    scaled to the peak displacement ``peak`` [m]: a band-limited random displacement command.

    The filter runs forward in time (second-order sections, no zero-phase pass), after a settling stretch of
    twice the longest period that is cut off; the record is faded in and out over 5 % of its length.

    >>> m = filtered_gaussian_motion(0.01, (0.2, 8.0), duration=10.0, rate=1000, seed=2)
    >>> round(float(abs(m.displacement).max()), 4), len(m.time)
    (0.01, 10001)
    """
    t = _grid(duration, rate)
    dt = t[1] - t[0]
    rng = np.random.default_rng(seed)
    settle = int(round(2.0 / band[0] / dt))
    sos = signal.butter(order, band, btype="bandpass", fs=1.0 / dt, output="sos")
    x = signal.sosfilt(sos, rng.standard_normal(t.size + settle))[settle:]
    x = _at_rest_ends(t, x, 0.05 * duration)
    x *= peak / np.max(np.abs(x))
    return _sampled(
        t,
        x,
        f"Gaussian noise through a causal order-{order} Butterworth band-pass {band[0]:g}-"
        f"{band[1]:g} Hz, peak {peak * 1e3:g} mm",
    )
