r"""A virtual test rig: measurements of a damper with hidden effects, perturbed fluid, noise and chosen excitations.

The rig drives the physics damper (:class:`~erdesign.effects.chain.PhysicsDamper`) with an exactly known motion and
control, with the true fluid differing from the nominal one of the damper file (calibration factors), with any
subset of the effect library switched on ("hidden") at chosen values, and adds white noise to the measured force and
displacement.  The record it returns is what a test machine would write: time, noisy displacement, noisy force and
the control; its velocity and acceleration are derived from the noisy displacement
(:func:`erdesign.data.measurement.derivatives`), exactly as for a file read from disk, while the true force was computed
from the exact motion.

Excitations (:class:`Motion`): :func:`sine`, :func:`stepped_sine` (segments over amplitude, frequency and field
with smooth transitions; it was ``sweep``), :func:`field_steps` (a sine with the field switched on and off),
:func:`random_motion` (band-limited Gaussian) and :func:`earthquake_motion` (Kanai-Tajimi filtered noise under a
build-up / decay envelope).  Kinematics are computed on a grid eight times finer than the sampling and differentiated
there, so the true velocity and acceleration are exact to about 1e-5.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping, Sequence

import numpy as np

from .._deprecated import renamed
from .._util import si_array
from ..damper import Damper
from ..data.measurement import Measurement
from ..effects import EFFECTS, parse_effect_names
from ..effects.chain import PhysicsDamper
from ..errors import ErdesignError
from ..limits import MAX_RECORD_ROWS, check_sample_count
from ..units import Q_

__all__ = [
    "Motion",
    "RigRecord",
    "sine",
    "stepped_sine",
    "field_steps",
    "random_motion",
    "earthquake_motion",
    "run_rig",
    "OVERSAMPLING",
]

#: Fine-grid factor for the exact kinematics.
OVERSAMPLING = 8


@dataclass(frozen=True)
class Motion:
    """A prescribed motion and control, SI arrays: time [s], x [m], v [m/s], a [m/s^2], control (SI)."""

    time: np.ndarray
    displacement: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    control: np.ndarray
    description: str = ""

    def record(self, control_kind: str, name: str | None = None, **extra) -> Measurement:
        """The motion as a record without a force (exact velocity and acceleration), to run a model on;
        ``control_kind`` is the fluid's ("electric field" ...), ``name`` defaults to the description, ``extra`` goes
        to :class:`~erdesign.data.measurement.Measurement` (e.g. ``velocity_noise=0.0``)."""
        return Measurement(
            time=self.time,
            displacement=self.displacement,
            force=None,
            velocity=self.velocity,
            acceleration=self.acceleration,
            control=self.control,
            control_kind=control_kind,
            name=self.description if name is None else name,
            **extra,
        )


def _fine(duration: float, rate: float):
    # the fine grid holds OVERSAMPLING x the record's samples
    most = MAX_RECORD_ROWS // OVERSAMPLING
    check_sample_count(duration * rate, "duration, rate", "shorten the record or lower the rate", most)
    n = int(round(duration * rate))
    if n < 8:
        raise ErdesignError(f"rig: {duration:g} s at {rate:g} Hz gives {n} samples; need at least 8")
    t = np.linspace(0.0, n / rate, n * OVERSAMPLING + 1)
    return t, n


def _finish(t_fine, x_fine, control_fine, description) -> Motion:
    v = np.gradient(x_fine, t_fine, edge_order=2)
    a = np.gradient(v, t_fine, edge_order=2)
    s = slice(None, None, OVERSAMPLING)
    return Motion(t_fine[s], x_fine[s], v[s], a[s], control_fine[s], description)


def _control_text(value: float, unit: str | None) -> str:
    """A control (SI) for a description: in ``unit`` (``"kV/mm"``, ``"kA/m"``, ``"A"``) when given, else bare.

    The control of a motion is SI (V/m, A/m, T, A or V): the coherent SI unit of ``unit``'s dimension.

    >>> _control_text(3e6, "kV / mm"), _control_text(2.5e5, "kA/m"), _control_text(1.5, "A"), _control_text(3, None)
    ('3 kV/mm', '250 kA/m', '1.5 A', '3')
    """
    if not unit:
        return f"{value:g}"
    q = Q_(value, Q_(1.0, unit).to_base_units().units).to(unit)
    return f"{q.magnitude:.4g} {q.units:~P}"


def sine(
    amplitude: float,
    frequency: float,
    field: float = 0.0,
    *,
    cycles: float = 3,
    rate: float = 500.0,
    control_unit: str | None = None,
) -> Motion:
    """x = X0 sin(2 pi f t) at a constant control, ``cycles`` cycles sampled at ``rate`` [Hz].

    ``control_unit`` is the unit the description prints the control in (the fluid's ``field_unit``, ``"kV/mm"``);
    the control itself stays SI.

    >>> m = sine(0.005, 2.0, 3e6, cycles=2, rate=200, control_unit="kV/mm")
    >>> len(m.time), round(float(m.velocity[0]), 5)     # 2 cycles of 0.5 s at 200 Hz; v(0) = X0 omega
    (201, 0.06283)
    >>> m.description
    'sine (2 cycles): 5 mm at 2 Hz, control 3 kV/mm'
    """
    return stepped_sine([amplitude], [frequency], [field], cycles=cycles, rate=rate, control_unit=control_unit)


def stepped_sine(
    amplitudes: Sequence[float],
    frequencies: Sequence[float],
    fields: Sequence[float],
    *,
    cycles: float = 2,
    rate: float = 500.0,
    control_unit: str | None = None,
) -> Motion:
    """Segments of ``cycles`` sine cycles, one per (amplitude, frequency, field) triple, joined smoothly.

    The amplitude and frequency blend over the first quarter cycle of each segment (half-cosine), the phase is
    continuous, so velocity and acceleration are continuous; the control steps at each segment start.
    Sequences of length 1 are repeated to the longest length.  ``control_unit``: the unit the description prints
    the controls in (SI numbers without a unit when None).
    """
    n_seg = max(len(amplitudes), len(frequencies), len(fields))
    A, f, E = (np.resize(np.asarray(s, dtype=float), n_seg) for s in (amplitudes, frequencies, fields))
    _check_motion(A, f, rate)
    durations = cycles / f
    starts = np.concatenate([[0.0], np.cumsum(durations)])
    t, _ = _fine(starts[-1], rate)
    seg = np.clip(np.searchsorted(starts, t, side="right") - 1, 0, n_seg - 1)
    into = t - starts[seg]
    blend_time = 0.25 / f[seg]
    w = np.where(into < blend_time, 0.5 - 0.5 * np.cos(np.pi * np.clip(into / blend_time, 0, 1)), 1.0)
    prev = np.maximum(seg - 1, 0)
    amp = A[prev] + (A[seg] - A[prev]) * w
    freq = f[prev] + (f[seg] - f[prev]) * w
    phase = 2 * np.pi * np.concatenate([[0.0], np.cumsum(0.5 * (freq[1:] + freq[:-1]) * np.diff(t))])
    desc = "; ".join(
        f"{a * 1e3:g} mm at {fr:g} Hz, control {_control_text(e, control_unit)}" for a, fr, e in zip(A, f, E)
    )
    # (one segment is a plain sine; several keep the words "sine sweep" of the record files already written)
    what = f"sine ({cycles:g} cycles)" if n_seg == 1 else f"sine sweep ({cycles:g} cycles each)"
    return _finish(t, amp * np.sin(phase), E[seg], f"{what}: {desc}")


#: Deprecated name of :func:`stepped_sine` ("sweep" also named a sample of the design space and the force-velocity
#: curves); the motions it makes still describe themselves as a "sine sweep", the text of existing record files.
sweep = renamed(stepped_sine, "erdesign.rig.sweep")


#: Largest stroke amplitude a damper test can have, [m] (beyond it the value or its unit is wrong).
MAX_AMPLITUDE = 10.0
#: Fewest samples per period of the fastest motion.
MIN_SAMPLES_PER_PERIOD = 8
#: Highest peak piston speed of a damper test, [m/s] (impact tests reach a few m/s).
MAX_SPEED = 100.0


def _check_motion(amplitudes: np.ndarray, frequencies: np.ndarray, rate: float) -> None:
    """One-line errors naming the amplitude or frequency that no test rig can run at ``rate``."""
    for name, values in (("amplitude", amplitudes), ("frequency", frequencies)):
        bad = values[~(np.isfinite(values) & (values > 0))]
        if bad.size:
            raise ErdesignError(f"{name}: must be positive and finite, got {bad[0]:g}")
    if np.max(amplitudes) > MAX_AMPLITUDE:
        raise ErdesignError(
            f"amplitude: {np.max(amplitudes):g} m is beyond any damper's stroke (at most "
            f"{MAX_AMPLITUDE:g} m); check the value and its unit"
        )
    speed = float(np.max(2 * np.pi * amplitudes * frequencies))
    if speed > MAX_SPEED:
        raise ErdesignError(
            f"frequency: {np.max(frequencies):g} Hz at {np.max(amplitudes) * 1e3:g} mm gives a peak "
            f"speed of {speed:.3g} m/s, beyond any damper test (at most {MAX_SPEED:g} m/s); check the "
            "frequency, the amplitude and their units"
        )
    if np.max(frequencies) * MIN_SAMPLES_PER_PERIOD > rate:
        raise ErdesignError(
            f"frequency: {np.max(frequencies):g} Hz cannot be resolved at {rate:g} samples per second "
            f"(at least {MIN_SAMPLES_PER_PERIOD} per period); lower it or raise the sampling rate"
        )


def field_steps(
    amplitude: float,
    frequency: float,
    field: float,
    *,
    cycles: float = 4,
    step_period: float = 0.5,
    rate: float = 1000.0,
    phase: float = 0.3,
    control_unit: str | None = None,
) -> Motion:
    """A sine with the control switched between 0 and ``field`` every ``step_period`` [s]; the steps fall at
    ``phase`` (fraction of a period) into the stroke so that they happen at speed.  ``control_unit``: the unit the
    description prints the control in (as :func:`sine`)."""
    _check_motion(np.array([amplitude], dtype=float), np.array([frequency], dtype=float), rate)
    t, _ = _fine(cycles / frequency, rate)
    x = amplitude * np.sin(2 * np.pi * frequency * t)
    on = np.floor((t - phase / frequency) / step_period) % 2 == 1
    return _finish(
        t,
        x,
        np.where(on, field, 0.0),
        f"sine {amplitude * 1e3:g} mm at {frequency:g} Hz with the "
        f"control switched 0 / {_control_text(field, control_unit)} every {step_period:g} s",
    )


def _shaped_noise(n: int, dt: float, gain, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    spectrum = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, dt)
    return np.fft.irfft(spectrum * gain(f), n)


def random_motion(
    rms: float,
    band: tuple[float, float],
    field: float = 0.0,
    *,
    duration: float = 4.0,
    rate: float = 500.0,
    seed: int = 0,
) -> Motion:
    """Band-limited Gaussian displacement (flat between ``band`` [Hz], smooth roll-off), RMS ``rms`` [m]."""
    t, _ = _fine(duration, rate)
    lo, hi = band
    gain = lambda f: 1.0 / np.sqrt(1 + (lo / np.maximum(f, 1e-9)) ** 8) / np.sqrt(1 + (f / hi) ** 8)  # noqa: E731
    x = _shaped_noise(t.size, t[1] - t[0], gain, seed)
    taper = np.clip(np.minimum(t, t[-1] - t) / (0.1 * duration), 0, 1)  # start and end at rest
    x = x * (0.5 - 0.5 * np.cos(np.pi * taper))
    x *= rms / np.sqrt(np.mean(x**2))
    return _finish(t, x, np.full(t.size, float(field)), f"random motion, RMS {rms * 1e3:g} mm, {lo:g}-{hi:g} Hz")


def earthquake_motion(
    peak: float,
    field: float = 0.0,
    *,
    duration: float = 8.0,
    rate: float = 500.0,
    ground_frequency: float = 2.5,
    ground_damping: float = 0.6,
    seed: int = 0,
) -> Motion:
    """Earthquake-like displacement: Kanai-Tajimi filtered noise (ground frequency and damping, band-limited to
    about 25 Hz) under an envelope that builds up over 15 % of the record and decays exponentially, scaled to the
    peak displacement ``peak``."""
    t, _ = _fine(duration, rate)
    wg, z = 2 * np.pi * ground_frequency, ground_damping

    def gain(f):
        w = 2 * np.pi * f
        kt = np.sqrt((wg**4 + 4 * z**2 * wg**2 * w**2) / ((wg**2 - w**2) ** 2 + 4 * z**2 * wg**2 * w**2))
        # acceleration spectrum -> displacement (divide by w^2), high-passed at 0.3 Hz to keep the stroke bounded
        return kt / np.maximum(w, 1e-9) ** 2 / np.sqrt(1 + (0.3 / np.maximum(f, 1e-9)) ** 8) / (1 + (f / 25.0) ** 4)

    x = _shaped_noise(t.size, t[1] - t[0], gain, seed)
    t1 = 0.15 * duration
    env = np.where(t < t1, (t / t1) ** 2, np.exp(-(t - t1) / (0.3 * duration)))
    env *= np.clip((t[-1] - t) / (0.05 * duration), 0, 1) ** 2  # come to rest
    # the pieces meet with a kink; smoothed over 0.1 s (Hann window) the envelope, and so the piston's velocity,
    # is continuous: a kinked envelope makes the velocity jump, which no actuator does and no derivative filter
    # of a sampled displacement can follow
    w = np.hanning(max(3, int(round(0.1 / (t[1] - t[0])))))
    env = np.convolve(env, w / w.sum(), mode="same")
    x = x * env
    x *= peak / np.max(np.abs(x))
    return _finish(t, x, np.full(t.size, float(field)), f"earthquake-like motion, peak {peak * 1e3:g} mm")


@dataclass
class RigRecord:
    """What the rig measured and what it hid."""

    record: Measurement
    """The measurement (noisy displacement and force; velocity and acceleration derived)."""
    true_force: np.ndarray
    """The noise-free force, [N]."""
    hidden: tuple[str, ...]
    truth: dict[str, float]
    """All parameter values of the true damper (calibration factors and hidden effects), SI."""
    motion: Motion
    comment: str = ""
    extra: dict = field(default_factory=dict)


def run_rig(
    damper: Damper,
    motion: Motion,
    *,
    hidden: Mapping[str, Mapping[str, float]] | Sequence[str] = (),
    viscosity_factor: float = 1.0,
    yield_stress_factor: float = 1.0,
    force_noise: float = 0.005,
    displacement_noise: float = 1e-4,
    seed: int = 0,
    name: str = "rig",
) -> RigRecord:
    """Measure ``damper`` on the virtual rig.

    Parameters
    ----------
    damper : Damper
        The damper of the damper file (nominal fluid).
    motion : Motion
        Excitation.
    hidden : mapping or sequence
        Effects switched on: ``{"seal_friction": {"friction_force": 150.0}, ...}`` (values not given take the
        effect's defaults), or just names.
    viscosity_factor, yield_stress_factor : float
        The true fluid over the nominal one (the calibration the diagnosis must find).
    force_noise : float
        Standard deviation of white force noise as a fraction of the RMS force.
    displacement_noise : float
        Standard deviation of white displacement noise as a fraction of the peak displacement.
    seed : int
        Noise seed.
    name : str
        Record name.

    Returns
    -------
    RigRecord

    Examples
    --------
    >>> from erdesign import load_example
    >>> rig = run_rig(load_example("makris"), sine(0.005, 2.0, 3e6, cycles=2, rate=200),
    ...               hidden={"seal_friction": {"friction_force": 300.0}}, seed=1)
    >>> rig.hidden, len(rig.record), rig.record.control_kind
    (('seal_friction',), 201, 'electric field')
    """
    if not isinstance(motion, Motion):  # a Measurement: "'Measurement' object has no attribute 'record'"
        raise ErdesignError(
            f"motion: expected a Motion (erdesign.programme, sine, stepped_sine), got {type(motion).__name__}"
        )
    for key, value in (
        ("force_noise", force_noise),
        ("displacement_noise", displacement_noise),
        ("viscosity_factor", viscosity_factor),
        ("yield_stress_factor", yield_stress_factor),
    ):  # '0.5 %' and -1 reached numpy ("scale < 0")
        x = si_array(value, key)
        if x.ndim or x < 0 or (key.endswith("factor") and not x > 0):
            raise ErdesignError(
                f"{key}: expected one {'positive' if key.endswith('factor') else 'non-negative'} number, got {value!r}"
            )
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:  # numpy's raw ValueError
        raise ErdesignError(f"seed: must be a whole number >= 0, got {seed!r:.60}")
    if isinstance(hidden, Mapping):
        names = parse_effect_names(list(hidden))
        settings = {k: dict(v) for k, v in hidden.items()}
    else:
        names = parse_effect_names(hidden)
        settings = {}
    model = PhysicsDamper(damper, names)
    exact = motion.record(damper.fluid.control, name)
    values = model.defaults()
    values.update(viscosity_factor=viscosity_factor, yield_stress_factor=yield_stress_factor)
    for e in names:
        values.update(settings.get(e, {}))
    values = model.check_values(values)
    F_true = model.force(exact, values)
    rng = np.random.default_rng(seed)
    F = F_true + force_noise * np.sqrt(np.mean(F_true**2)) * rng.standard_normal(F_true.size)
    x = motion.displacement + displacement_noise * np.max(np.abs(motion.displacement)) * rng.standard_normal(
        F_true.size
    )
    record = Measurement.from_arrays(
        motion.time, x, F, control=motion.control, control_kind=damper.fluid.control, name=name
    )
    parts = []
    for e in names:
        pars = ", ".join(f"{p.name} = {p.format(values[p.name])}" for p in EFFECTS[e].parameters(damper))
        parts.append(f"{e} ({pars})")
    hidden_text = ", ".join(parts) or "nothing"
    comment = (
        f"virtual rig: {damper.name or 'damper'}; {motion.description}; hidden: {hidden_text}; true fluid: "
        f"viscosity x {viscosity_factor:g}, yield stress x {yield_stress_factor:g}; noise: force "
        f"{force_noise:g} of RMS, displacement {displacement_noise:g} of peak; seed {seed}"
    )
    return RigRecord(record, F_true, names, values, motion, comment)
