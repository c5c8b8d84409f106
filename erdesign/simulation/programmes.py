r"""The test programmes of the characterization method of Vivas-López et al. (n.d.), Table 1: displacement signals
and actuation (control) signals, and the experiments E1-E5 that pair them.

Displacement signals (:data:`DISPLACEMENTS`):

* ``rp`` - road profile (:func:`road_profile`): the suspension stroke of a car on a random road, band-limited to
  0-3 Hz (the paper's band) with the falling spectrum of ISO 8608 road profiles, at one or several peak
  amplitudes in turn (E2: ±8 mm; E3: ±1 to ±8 mm);
* ``dsfs`` - decreasing-amplitude stepped-frequency sine (:func:`dsfs`): sine steps from 0.5 to 14.5 Hz whose
  amplitude falls from ±8 to ±1 mm as the frequency rises.

Actuation signals (:data:`ACTUATIONS`), between a low and a high control (the paper's PWM duty cycle 10 % to 80 %):

* ``sc`` - stepped increments (:func:`stepped_control`): a staircase from low to high, repeated;
* ``icps`` - increasing clock period signal (:func:`icps`): a random level between low and high held for a clock
  period that grows along the record;
* ``prbs`` - pseudo-random binary signal (:func:`prbs`): a maximal-length shift-register sequence between low and
  high.

:data:`EXPERIMENTS` names the paper's pairs (E1 = DSFS + SC, ..., E5 = DSFS + PRBS) and :func:`programme` makes any
``displacement+actuation`` pair as a :class:`~erdesign.simulation.rig.Motion` (``erdesign doe`` writes it as a
measurement file without force).

Notes
-----
The paper gives the amplitude and frequency ranges (Table 1) but neither step sizes, durations nor clock periods;
the defaults here (1 Hz frequency steps with 4 cycles each, a 20 s road profile, eight control levels held 1 s,
ICPS clock periods from 0.05 s to 2 s, an order-8 PRBS clocked at 0.1 s) are this project's choices, each a
keyword.

References
----------
Vivas-López et al. (n.d.), section 2 and Table 1 (design of experiments); ISO 8608 (road profile spectra,
displacement PSD falling as the inverse square of the spatial frequency).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace

import numpy as np

from .._util import si_array
from ..errors import ErdesignError
from ..units import to_si
from .rig import Motion, _check_motion, _fine, _finish, stepped_sine

__all__ = [
    "ACTUATIONS",
    "DISPLACEMENTS",
    "EXPERIMENTS",
    "PRBS_TAPS",
    "ProgrammeError",
    "dsfs",
    "icps",
    "prbs",
    "prbs_bits",
    "programme",
    "road_profile",
    "stepped_control",
]


class ProgrammeError(ErdesignError):
    """A test programme that cannot be made: unknown name, or a parameter out of range (the message names it)."""


# ------------------------------------------------------------------------------------------ displacement signals
def dsfs(
    amplitude_range: tuple[float, float] = (0.008, 0.001),
    frequency_range: tuple[float, float] = (0.5, 14.5),
    *,
    frequency_step: float = 1.0,
    cycles: float = 4,
    rate: float = 500.0,
) -> Motion:
    r"""Decreasing-amplitude stepped-frequency sine (DSFS) of Vivas-López et al. (n.d.), Table 1.

    Step k runs ``cycles`` cycles at :math:`f_k = f_0 + k\,\Delta f` up to ``frequency_range[1]``, with amplitude
    falling linearly from ``amplitude_range[0]`` at the first step to ``amplitude_range[1]`` at the last, joined
    smoothly (:func:`~erdesign.simulation.rig.stepped_sine`: continuous phase, amplitude and frequency blended over
    a quarter cycle).

    Parameters
    ----------
    amplitude_range : (float, float)
        Amplitude at the first (lowest-frequency) and at the last step, [m]; the paper's ±8 to ±1 mm.
    frequency_range : (float, float)
        First and last frequency, [Hz]; the paper's 0.5 to 14.5 Hz.
    frequency_step : float
        [Hz].
    cycles : float
        Cycles per step.
    rate : float
        Sampling rate, [Hz].

    Examples
    --------
    >>> m = dsfs(rate=500)
    >>> round(float(m.time[-1]), 1), round(float(abs(m.displacement).max()) * 1e3, 2)
    (18.7, 8.0)
    """
    f0, f1 = (float(f) for f in frequency_range)
    if not (0 < f0 <= f1 and frequency_step > 0 and cycles > 0):
        raise ProgrammeError(
            f"frequency_range: need 0 < first <= last and a positive step and cycles, got "
            f"{f0:g}-{f1:g} Hz step {frequency_step:g} Hz, {cycles:g} cycles"
        )
    f = np.arange(f0, f1 + 1e-9 * f1, frequency_step)
    A = np.linspace(float(amplitude_range[0]), float(amplitude_range[1]), f.size)
    _check(A, f, rate)
    m = stepped_sine(A, f, [0.0], cycles=cycles, rate=rate)
    return replace(
        m,
        description=f"DSFS: {f.size} steps {f0:g}-{f[-1]:g} Hz, amplitude {A[0] * 1e3:g} to "
        f"{A[-1] * 1e3:g} mm, {cycles:g} cycles each",
    )


def road_profile(
    amplitudes: Sequence[float] = (0.008,),
    band: tuple[float, float] = (0.1, 3.0),
    *,
    duration: float = 20.0,
    rate: float = 500.0,
    seed: int = 0,
    ramp: float = 0.5,
) -> Motion:
    r"""Road-profile (RP) stroke of Vivas-López et al. (n.d.), Table 1: band-limited random displacement.

    White Gaussian noise shaped in frequency to the spectrum of an ISO 8608 road seen at constant speed
    (displacement amplitude spectrum :math:`\propto 1/f`) inside ``band`` and zero outside (half-cosine tapers over
    the lowest and highest 10 % of the band), then cut into ``len(amplitudes)`` equal segments, segment k scaled so
    that its largest excursion is ``amplitudes[k]`` (smooth half-cosine blends between segments) and faded in and
    out over ``ramp`` seconds so the actuator starts and ends at rest.

    Parameters
    ----------
    amplitudes : sequence of float
        Peak displacement of each segment, [m]; the paper's E2 is (8 mm,), E3 steps from 1 to 8 mm.
    band : (float, float)
        [Hz]; the paper's 0-3 Hz (0.1 Hz low edge: a rig cannot hold a drifting mean stroke).
    duration, rate, seed, ramp : float, float, int, float
        [s], [Hz], seed of the noise, fade [s].

    Examples
    --------
    >>> m = road_profile((0.008,), duration=10.0, rate=200)
    >>> round(float(abs(m.displacement).max()) * 1e3, 3), abs(float(m.displacement[0])), abs(float(m.displacement[-1]))
    (8.0, 0.0, 0.0)
    """
    A = np.asarray(amplitudes, dtype=float)
    lo, hi = (float(b) for b in band)
    if A.size == 0:
        raise ProgrammeError("amplitudes: need at least one peak amplitude")
    if not (0 < lo < hi):
        raise ProgrammeError(f"band: need 0 < low < high, got {lo:g}-{hi:g} Hz")
    _check(A, np.array([hi]), rate)
    if not (math.isfinite(duration) and duration >= 4 * ramp and duration * lo >= 1.0):
        raise ProgrammeError(
            f"duration: {duration:g} s is too short for a road profile down to {lo:g} Hz (need at "
            f"least one period of the lowest frequency and the {ramp:g} s fades)"
        )
    t, _ = _fine(duration, rate)
    dt = t[1] - t[0]
    rng = np.random.default_rng(seed)
    spectrum = np.fft.rfft(rng.standard_normal(t.size))
    f = np.fft.rfftfreq(t.size, dt)
    width = 0.1 * (hi - lo)
    taper = np.clip(np.minimum(f - lo, hi - f) / width, 0.0, 1.0)
    gain = np.where((f >= lo) & (f <= hi), (0.5 - 0.5 * np.cos(np.pi * taper)) / np.maximum(f, lo), 0.0)
    x = np.fft.irfft(spectrum * gain, t.size)
    # segments at their peak amplitudes: a smooth envelope (blends over 10 % of a segment, fades at the ends)
    # whose levels are corrected until each segment's largest excursion is its amplitude
    edges = np.linspace(0.0, t[-1], A.size + 1)
    seg = np.clip(np.searchsorted(edges, t, side="right") - 1, 0, A.size - 1)
    blend = 0.1 * (edges[1] - edges[0])
    into = t - edges[seg]
    w = np.where(into < blend, 0.5 - 0.5 * np.cos(np.pi * np.clip(into / blend, 0, 1)), 1.0)
    fade = np.clip(np.minimum(t - t[0], t[-1] - t) / ramp, 0.0, 1.0)
    fade = 0.5 - 0.5 * np.cos(np.pi * fade)
    level = np.ones(A.size)
    for _ in range(20):
        shaped = x * fade * (level[np.maximum(seg - 1, 0)] + (level[seg] - level[np.maximum(seg - 1, 0)]) * w)
        peak = np.array([np.max(np.abs(shaped[seg == k])) for k in range(A.size)])
        if np.allclose(peak, A, rtol=1e-6, atol=0.0):
            break
        level *= A / peak
    x = shaped
    shown = ", ".join(f"{a * 1e3:g}" for a in A)
    return _finish(
        t, x, np.zeros(t.size), f"RP: road profile {lo:g}-{hi:g} Hz over {duration:g} s, peaks {shown} mm (seed {seed})"
    )


def _check(A: np.ndarray, f: np.ndarray, rate: float) -> None:
    try:
        _check_motion(A, f, rate)
    except ErdesignError as exc:
        raise ProgrammeError(str(exc)) from None


# ------------------------------------------------------------------------------------------- actuation signals
def stepped_control(t, low: float, high: float, *, steps: int = 8, hold: float = 1.0) -> np.ndarray:
    """Stepped increments (SC): a staircase of ``steps`` equal increments from ``low`` to ``high``, each held ``hold``
    seconds, repeated from ``low`` until the end of ``t`` (Vivas-López et al., Table 1, E1).

    >>> stepped_control(np.arange(0, 6.0, 1.0), 0.0, 2.0, steps=3).tolist()
    [0.0, 1.0, 2.0, 0.0, 1.0, 2.0]
    """
    if int(steps) != steps or steps < 2 or not hold > 0:
        raise ProgrammeError(f"steps, hold: need at least 2 steps and a positive hold, got {steps!r}, {hold!r} s")
    t = np.asarray(t, dtype=float)
    k = np.floor((t - t[0]) / hold + 1e-9).astype(int) % int(steps)
    return low + (high - low) * k / (steps - 1)


def icps(t, low: float, high: float, *, period_range: tuple[float, float] = (0.05, 2.0), seed: int = 0) -> np.ndarray:
    """Increasing clock period signal (ICPS): a level drawn uniformly from [low, high] at each clock tick, the clock
    period growing geometrically from ``period_range[0]`` at the start to ``period_range[1]`` at the end of ``t``
    (Vivas-López et al., Table 1, E3 and E4: "covers the whole force range").

    >>> u = icps(np.linspace(0, 10, 1001), 0.0, 1.0)
    >>> bool(u.min() >= 0.0 and u.max() <= 1.0)
    True
    """
    p0, p1 = (float(p) for p in period_range)
    t = np.asarray(t, dtype=float)
    T = float(t[-1] - t[0])
    if not (0 < p0 <= p1 <= T):
        raise ProgrammeError(f"period_range: need 0 < first <= last <= the record's {T:g} s, got {p0:g}-{p1:g} s")
    # the period at time s is p0 (p1/p0)^(s/T); ticks follow by stepping it
    ticks = [0.0]
    while ticks[-1] < T:
        ticks.append(ticks[-1] + p0 * (p1 / p0) ** (ticks[-1] / T))
    ticks = np.asarray(ticks)
    levels = np.random.default_rng(seed).uniform(low, high, ticks.size)
    return levels[np.searchsorted(ticks, t - t[0], side="right") - 1]


#: Feedback taps (1-based, Fibonacci form) of a maximal-length shift register of each order (period 2^n - 1).
PRBS_TAPS = {
    2: (2, 1),
    3: (3, 2),
    4: (4, 3),
    5: (5, 3),
    6: (6, 5),
    7: (7, 6),
    8: (8, 6, 5, 4),
    9: (9, 5),
    10: (10, 7),
    11: (11, 9),
    12: (12, 11, 10, 4),
    13: (13, 12, 11, 8),
    14: (14, 13, 12, 2),
    15: (15, 14),
    16: (16, 15, 13, 4),
}


def prbs_bits(order: int, count: int | None = None, *, seed: int = 1) -> np.ndarray:
    """``count`` bits (default one period, 2^order - 1) of the maximal-length linear feedback shift register of
    ``order`` (:data:`PRBS_TAPS`), started from the nonzero state ``seed``.

    >>> prbs_bits(3).tolist()
    [1, 0, 0, 1, 0, 1, 1]
    """
    if order not in PRBS_TAPS:
        raise ProgrammeError(f"order: a PRBS order from {min(PRBS_TAPS)} to {max(PRBS_TAPS)}, got {order!r}")
    period = 2**order - 1
    state = int(seed) % (period + 1)
    if state == 0:
        raise ProgrammeError(f"seed: the shift register needs a nonzero start state modulo 2^{order}, got {seed!r}")
    count = period if count is None else int(count)
    out = np.empty(count, dtype=np.int8)
    for i in range(count):
        out[i] = state & 1
        feedback = 0
        for tap in PRBS_TAPS[order]:
            feedback ^= (state >> (order - tap)) & 1
        state = (state >> 1) | (feedback << (order - 1))
    return out


def prbs(t, low: float, high: float, *, clock: float = 0.1, order: int = 8, seed: int = 1) -> np.ndarray:
    """Pseudo-random binary signal (PRBS): ``high`` for a one bit and ``low`` for a zero bit of :func:`prbs_bits`,
    one bit each ``clock`` seconds (Vivas-López et al., Table 1, E2 and E5: "only captures the limits of the force
    range").

    >>> prbs(np.arange(0, 0.7, 0.1), 0.0, 1.0, clock=0.1, order=3).tolist()
    [1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0]
    """
    if not clock > 0:
        raise ProgrammeError(f"clock: must be positive, got {clock!r} s")
    t = np.asarray(t, dtype=float)
    k = np.floor((t - t[0]) / clock + 1e-9).astype(int)
    bits = prbs_bits(order, int(k[-1]) + 1, seed=seed)
    return np.where(bits[k] == 1, high, low).astype(float)


# ------------------------------------------------------------------------------------------- the registries
#: Displacement signals by name: a function of keyword options returning a Motion.
DISPLACEMENTS: Mapping[str, Callable[..., Motion]] = {"rp": road_profile, "dsfs": dsfs}
#: Actuation signals by name: a function ``(t, low, high, **options)`` returning the control.
ACTUATIONS: Mapping[str, Callable[..., np.ndarray]] = {"sc": stepped_control, "icps": icps, "prbs": prbs}


@dataclass(frozen=True)
class Experiment:
    """One row of Vivas-López et al. Table 1: the displacement and actuation signals and their options."""

    displacement: str
    actuation: str
    displacement_options: Mapping[str, object]
    purpose: str


#: The paper's experiments (Table 1): E1 characterizes, E2-E5 identify.
EXPERIMENTS: Mapping[str, Experiment] = {
    "e1": Experiment("dsfs", "sc", {}, "characterization"),
    "e2": Experiment("rp", "prbs", {"amplitudes": (0.008,)}, "identification"),
    "e3": Experiment("rp", "icps", {"amplitudes": tuple(np.arange(1, 9) * 1e-3)}, "identification"),
    "e4": Experiment("dsfs", "icps", {}, "identification"),
    "e5": Experiment("dsfs", "prbs", {}, "identification"),
}


def programme(
    name: str,
    *,
    control_range: tuple[float, float] | None = None,
    rate: float = 500.0,
    seed: int = 0,
    displacement_options: Mapping[str, object] | None = None,
    actuation_options: Mapping[str, object] | None = None,
) -> Motion:
    """The test programme ``name``: an experiment of Table 1 (``"E1"`` ... ``"E5"``), a displacement signal alone
    (``"rp"``, ``"dsfs"``: control zero) or a pair ``"DISPLACEMENT+ACTUATION"`` (``"dsfs+prbs"``).

    Parameters
    ----------
    name : str
        Case-insensitive.
    control_range : (float, float), optional
        Low and high control (SI: V/m, A/m, T, A or V); required with an actuation signal.
    rate : float or quantity
        Sampling rate, [Hz] (a number) or a quantity or text with its unit (``"1 kHz"``).
    seed : int
        Seed of the random signals (road profile, ICPS; the PRBS start state is ``seed + 1``).
    displacement_options, actuation_options : mapping, optional
        Keywords of the displacement function (:data:`DISPLACEMENTS`) and of the actuation function
        (:data:`ACTUATIONS`); they override an experiment's own.

    Examples
    --------
    >>> m = programme("E5", control_range=(0.5e6, 4e6))
    >>> sorted(set(m.control.tolist())) == [0.5e6, 4e6], m.description.split(":")[0]
    (True, 'E5')
    """
    key = str(name).strip().lower()
    if key in EXPERIMENTS:
        e = EXPERIMENTS[key]
        disp, act, own = e.displacement, e.actuation, dict(e.displacement_options)
    else:
        disp, _, act = key.partition("+")
        own = {}
        if disp in ACTUATIONS and not act:
            raise ProgrammeError(
                f"programme: {name!r} is an actuation signal; pair it with a displacement signal, "
                f"e.g. 'dsfs+{disp}' (or one of E1-E5)"
            )
        if disp not in DISPLACEMENTS or (act and act not in ACTUATIONS):
            raise ProgrammeError(
                f"programme: unknown {name!r}; one of {', '.join(k.upper() for k in EXPERIMENTS)}, "
                f"{', '.join(DISPLACEMENTS)} or DISPLACEMENT+ACTUATION with the actuation one of "
                f"{', '.join(ACTUATIONS)}"
            )
    # a rate as text or a quantity ("500 Hz") was a raw numpy message naming displacement_options
    if isinstance(rate, str) or hasattr(rate, "units"):
        rate = to_si(rate, "Hz", "rate")
    if isinstance(rate, bool) or not isinstance(rate, (int, float, np.number)) or not 0 < rate < math.inf:
        raise ProgrammeError(f"rate: must be one positive, finite sampling rate [Hz], got {rate!r:.60}")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:  # numpy's raw ValueError
        raise ProgrammeError(f"seed: must be a whole number >= 0, got {seed!r:.60}")
    options = {**own, **dict(displacement_options or {})}
    if disp == "rp":
        options.setdefault("seed", seed)
    try:
        motion = DISPLACEMENTS[disp](rate=rate, **options)
    except TypeError as exc:
        raise ProgrammeError(f"displacement_options: {exc}") from None
    label = key.upper()
    if not act:
        for given, what in ((control_range, "control_range"), (actuation_options, "actuation_options")):
            if given is not None:
                raise ProgrammeError(
                    f"{what}: {name!r} has no actuation signal (the control is zero); pair it, e.g. '{disp}+prbs'"
                )
        return replace(motion, description=f"{label}: {motion.description}")
    if control_range is None:
        raise ProgrammeError(f"control_range: the actuation signal {act.upper()} needs a low and a high control")
    if isinstance(control_range, (str, bytes)) or not hasattr(control_range, "__len__") or len(control_range) != 2:
        # '0.5 A, 2 A' was "could not convert string to float: '.'"; three items "too many values to unpack"
        raise ProgrammeError(f"control_range: expected (low, high) in SI units, got {control_range!r:.60}")
    # a quantity (Q_(0.5, 'A')) was "Cannot convert from 'ampere' to 'dimensionless'": si_array names it
    low, high = (si_array(c, "control_range") for c in control_range)
    if low.ndim or high.ndim:
        raise ProgrammeError(f"control_range: expected two numbers (low, high), got {control_range!r:.60}")
    low, high = float(low), float(high)
    if not (math.isfinite(low) and math.isfinite(high) and low < high):
        raise ProgrammeError(f"control_range: need a finite low below the high, got {low:g}, {high:g}")
    act_options = {
        **({"seed": seed + 1} if act == "prbs" else {"seed": seed} if act == "icps" else {}),
        **dict(actuation_options or {}),
    }
    try:
        u = ACTUATIONS[act](motion.time, low, high, **act_options)
    except TypeError as exc:
        raise ProgrammeError(f"actuation_options: {exc}") from None
    return replace(
        motion,
        control=u,
        description=f"{label}: {motion.description}; {act.upper()} control between the low and the high level",
    )
