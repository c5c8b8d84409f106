r"""The catalogue of the diagnosis benchmark: records made by the truth rig whose missing effect is known.

Each :class:`Case` says which damper of ``examples/`` is measured, how it is driven (a sine programme, band-limited
random motion or an earthquake-like record), how noisy the force is, which mechanisms of the truth rig
(:data:`erdesign.simulation.truthrig.MECHANISMS`) the true damper has and at what size, and what a correct diagnosis
says:

* no mechanism ("clean": the true damper is exactly Bingham, with perturbed calibration factors) -> the verdict
  ``"nothing_missing"``;
* a mechanism outside the effect library (blow-off valve, single rod, cavitation, free play) -> ``"unexplained"``;
* one or two mechanisms of the library -> ``"missing_effect"`` naming one of them (:attr:`Case.accepted`).

The catalogue is deterministic (every seed is fixed) and is built by :func:`benchmark_cases`.

Design rules (docs/diagnosis_benchmark.md shows the resulting counts):

* every library effect at two sizes, ``moderate`` and ``large``, on five dampers (ER valve, MR valve in kA/m, MR valve
  controlled by the coil current, ER and MR mixed mode), cycling through the three excitations and the two noise
  levels (1 % and 3 % of the RMS force; displacement noise 1e-4 of the peak);
* every pair of library effects once (both at the large size; either name is correct);
* clean cases and out-of-library cases on every damper;
* the control is a staircase 0 / full / half reference field, one step every :data:`STEP_PERIOD`, each step moved
  to the nearest speed peak so that a lagging field is seen while the fluid flows; it is on for two thirds of the
  record (the yield stress and its effects are seen) and off for one third (the viscosity and the seal friction
  are seen apart from it);
* sizes are physical: each is a multiple of the value expected from the damper's own geometry and fluid (the slug
  mass :math:`\rho L A_p^2/(n\pi d h)`, a bulk modulus with entrained air of 0.05-1 GPa, a seal friction of a few
  percent of the damper force, a coil time constant of 10-40 ms, ...) (:func:`mechanism_parameters`);
* effects are placed where they can be seen at physical sizes: no slug inertia on Makris's slow ER damper and no
  heating on the lightly loaded mixed ER head (:data:`NOT_VISIBLE_ON`), heating on sine programmes at twice the
  speed, slug inertia not on earthquake records (:data:`EXCITATIONS_OF`), shear thinning at a quarter of the
  reference field, heating and shear thinning on MR dampers with the quieter load cell (:data:`QUIET_ON_MR`): they
  change only the viscous part of the force, small beside an MR fluid's yield force;
* detectability is measured, not assumed: :func:`effect_size_over_noise` runs the truth rig without noise with and
  without the mechanisms, refits the clean damper's two fluid factors to the run with them (the truth rig's own,
  nothing of the diagnosed model) and compares the energy of what is left with that of the force noise.  Cases
  below :data:`UNDETECTABLE` are reported as undetectable by design (kept in the catalogue, counted apart).

The classes of issue 23 (:data:`ISSUE23_GROUPS`, subset ``"issue23"``; each case carries its class in
:attr:`Case.group` and the benchmark reports each class) are records shaped as independent testers and real
laboratories make them, where the core catalogue's own shapes had hidden failures:

* ``long_field_steps``: 60-80 s at 1 kHz, a DoE-style programme of separate sine runs
  (:func:`~erdesign.simulation.truthrig.motions.sine_programme`) or a logarithmic swept sine, the field stepping every
  2 s at speed; first-order field lags of 10, 20 and 40 ms on an MR valve, a coil-current valve and a mixed head, and
  a two-stage inductive lag (15 + 8 ms, ``coil_lag.second_time_constant``) on the coil-current MR head ``mr_coil``;
  two clean long records;
* ``band_limited_3khz``: 20 s at 3 kHz of band-limited random displacement (Gaussian noise through a causal
  band-pass, +-1 cm, peak speed 1 m/s, as Dyke's NEES tests), the load cell's noise 1 % of the RMS force, white up
  to the Nyquist frequency as in Dyke's record (:data:`ANTI_ALIAS_CORNER`: no anti-alias roll-off shows in it):
  clean, field lag, compressibility, gas spring.  (:attr:`Case.anti_alias` can still put both channels through a
  causal Butterworth low-pass; diagnosis has no model of such a filter, which smears the rigid Bingham jump at each
  reversal - at 500 Hz about 60 x the energy of the noise, and leakage was named for it.);
* ``heating_long``: 60-80 s sine programmes on the three valve dampers at twice their working speed, and 83 s on the
  MR valve at its working speed, the heat capacity (:data:`_HEATING_SHARE` of the fluid's) sized so that the fluid
  warms by 29-31 K (:data:`HEATING_TARGET`);
* ``series_springs_mixed``: an aerated column (bulk modulus 0.1 / 0.4 GPa, and 0.05 GPa on the mixed ER head: 1.7e6
  N/m, the stiffness of the testers' record) on the mixed ER and MR heads, pre-yield elasticity alone on both mixed
  heads (the pair to tell apart), and a gas spring with a compressible column on three valve dampers (either name
  is right);
* ``clean_every_kind``: exact Bingham, perturbed calibration factors, on every example damper (:data:`ALL_DAMPERS`),
  plus two 100 Hz records with a 5 um displacement readout at a constant control (1 % and a quiet 0.2 % load cell,
  where the velocity derived from the steps sets the error floor) and a 3 kHz band-limited record with a 1 % load
  cell;
* ``other_generator``: random motion from other generators than the team's ``random_motion``
  (:mod:`erdesign.simulation.truthrig.motions`: an Ornstein-Uhlenbeck command through a servo, a random-phase
  multi-sine, Gaussian noise through a causal Butterworth band-pass) with leakage, seal friction, shear thinning, a
  gas spring, compressibility, and one clean record.

The records are kept cheap to diagnose: at most 83 000 samples, most far fewer, so that the target of a 60 s,
1 kHz record (under 30 s) can hold for each; the benchmark measures it (docs/diagnosis_benchmark_issue23.md).

Lab artefacts (clipping, smoothing, skew, gaps, drift, quantisation faults) are a class of their own, built on
:mod:`erdesign.simulation.truthrig.artefacts` when it lands: the hook is :meth:`Case.make`, which already applies the
instrument chain of a case (:attr:`Case.anti_alias`, :attr:`Case.displacement_resolution`) after the truth rig.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from itertools import combinations
from typing import Mapping

import numpy as np

from ...damper import Damper
from ...damper.files import load_example
from ..rig import Motion, earthquake_motion, random_motion, stepped_sine
from .motions import (
    filtered_gaussian_motion,
    ornstein_uhlenbeck_motion,
    random_phase_multisine,
    sine_programme,
    swept_sine,
)
from .simulate import MIXED_MECHANISMS, UNSUPPORTED, UNSUPPORTED_MIXED

__all__ = [
    "Case",
    "benchmark_cases",
    "mechanism_parameters",
    "effect_size_over_noise",
    "build_motion",
    "control_staircase",
    "LIBRARY_MECHANISMS",
    "OUT_OF_LIBRARY",
    "DAMPERS",
    "EXCITATIONS",
    "NOISES",
    "SIZES",
    "STEP_PERIOD",
    "UNDETECTABLE",
    "SUBSETS",
    "supported",
    "unsupported_pairs",
    "NOT_VISIBLE_ON",
    "EXCITATIONS_OF",
    "ISSUE23_GROUPS",
    "ISSUE23_EXCITATIONS",
    "ALL_DAMPERS",
    "ANTI_ALIAS_ORDER",
    "ANTI_ALIAS_CORNER",
    "HEATING_TARGET",
    "ARTEFACTS",
]

#: Library effect -> the truth rig's mechanism that produces it.
LIBRARY_MECHANISMS = {
    "seal_friction": "stribeck_friction",
    "fluid_inertia": "slug_inertia",
    "compressibility": "compliance",
    "leakage": "bypass",
    "viscous_heating": "thermal",
    "field_lag": "coil_lag",
    "shear_thinning": "herschel_bulkley",
    "gas_spring": "accumulator",
    "preyield_elasticity": "preyield",
}
#: Mechanisms of the truth rig that no library effect describes.
OUT_OF_LIBRARY = ("blowoff", "single_rod", "cavitation", "free_play")
#: Example dampers (names of examples/*.toml) measured by the benchmark.
DAMPERS = ("makris", "mr_valve", "mr_valve_current", "mr_mixed", "kamath_wereley")
EXCITATIONS = ("sine", "random", "earthquake")
#: Excitations of the issue-23 classes: a DoE-style sine programme, a logarithmic swept sine, and random motion from
#: generators other than the team's ``random_motion`` (:mod:`erdesign.simulation.truthrig.motions`).
ISSUE23_EXCITATIONS = ("doe_sine", "swept_sine", "ou", "multisine", "filtered_gaussian")
#: Every example damper of ``examples/``, the coil-current mixed head ``mr_coil`` included.
ALL_DAMPERS = (*DAMPERS, "mr_coil", "spencer1997", "quiroz2022", "kamath_wereley1997")
#: Force noise, standard deviation as a fraction of the RMS force.
NOISES = (0.01, 0.03)
#: Displacement noise, standard deviation as a fraction of the peak displacement.
DISPLACEMENT_NOISE = 1e-4
SIZES = ("moderate", "large")
#: Time between steps of the control staircase, [s].
STEP_PERIOD = 0.75
#: Levels of the control staircase, fractions of the reference field.
STEP_LEVELS = (0.0, 1.0, 0.5, 0.0, 0.5, 1.0)
#: Effect energy over noise energy below which a case is undetectable by design.
UNDETECTABLE = 3.0
#: ``core``: the catalogue of 2026-11-23 (153 cases); ``issue23``: the classes of issue 23; ``full``: both;
#: ``fast``: seven short cases for the test suite.
SUBSETS = ("full", "core", "issue23", "fast")
#: The classes of issue 23 (:attr:`Case.group`), in the order the benchmark reports them.
ISSUE23_GROUPS = (
    "long_field_steps",
    "band_limited_3khz",
    "heating_long",
    "series_springs_mixed",
    "clean_every_kind",
    "other_generator",
    "artefacts",
)
#: Corner of the anti-alias low-pass of the 3 kHz band-limited records, [Hz]; 0: none.  Dyke's ransim_u record
#: (3004.8 Hz) has a white force spectrum up to the Nyquist frequency (erdesign.data.noise_floor finds its plateau at
#: 1.0-1.5 kHz): no conditioner's roll-off shows in it, so the band-limited records, like it, have none.  (Through a
#: 4th-order Butterworth at 1 kHz the truth rig's rigid Bingham jump at each reversal is smeared over about 1 ms and the
#: calibrated clean baseline leaves ESR 0.017, 166 x its floor; at 1.35 kHz 0.012: diagnosis has no model of an
#: instrument's filter - docs/diagnosis.md, where it is known to fail.)
ANTI_ALIAS_CORNER = 0.0
#: Order of the Butterworth anti-alias low-pass of the band-limited records, [-].
ANTI_ALIAS_ORDER = 4
#: Temperature rise the long heating records are sized for, [K] (a long test warms the fluid by tens of kelvin).
HEATING_TARGET = 30.0


@dataclass(frozen=True)
class _Scale:
    """How a damper is driven: peak piston speed [m/s] and the centre frequency of the excitation [Hz]."""

    speed: float
    frequency: float


# Peak speeds where each damper works: Makris's ER damper at its design point of about 25 mm/s (its zero-field
# damping constant is about 1e5 N s/m), the MR dampers at automotive speeds.
_SCALES = {
    "makris": _Scale(0.03, 1.0),
    "mr_valve": _Scale(0.25, 2.5),
    "mr_valve_current": _Scale(0.25, 2.0),
    "mr_mixed": _Scale(0.25, 2.5),
    "kamath_wereley": _Scale(0.1, 2.0),
    "mr_coil": _Scale(0.25, 2.5),
    "spencer1997": _Scale(0.3, 2.5),  # Dyke's tests: up to 1 m/s; Spencer's sines at 2.5 Hz
    "quiroz2022": _Scale(0.1, 1.0),  # the Quiroz sines: 39-117 mm/s
    "kamath_wereley1997": _Scale(0.06, 10.0),  # the paper's tests: 1 mm at 10 Hz (docs/seeds.md)
}


# ---------------------------------------------------------------------------------------------------- sizes
def _scales(damper: Damper, speed: float) -> dict[str, float]:
    """Physical scales of a damper: piston area, zero-field damping constant, yield force, slug mass, force."""
    g, f = damper.geometry, damper.fluid
    Ap = g.piston_area
    n = g.ducts if g.configuration == "valve" else 1
    # thin-gap Newtonian duct (Makris eq 15) and the yield pressure drop 2 tau_y L / h of a blocked slit
    C0 = 12 * f.viscosity * g.duct_length * Ap**2 / (n * math.pi * g.duct_mean_diameter * g.gap**3)
    Fy = 2 * f.yield_stress * g.duct_length / g.gap * Ap
    slug = f.density * g.duct_length * Ap**2 / (n * math.pi * g.duct_mean_diameter * g.gap)
    return {
        "Ap": Ap,
        "C0": C0,
        "Fy": Fy,
        "slug": slug,
        "force": Fy + C0 * speed,
        "volume": 2 * Ap * 0.08 + n * math.pi * g.duct_mean_diameter * g.gap * g.duct_length,
    }


def mechanism_parameters(
    mechanism: str, size: str, damper: Damper, speed: float, frequency: float = 1.0
) -> dict[str, float]:
    """Parameters (SI) of a truth-rig mechanism at a ``"moderate"`` or ``"large"`` size for ``damper`` driven at
    peak speed ``speed`` [m/s] around ``frequency`` [Hz].

    Each size is a multiple of what the damper's geometry and fluid make physically expected (``F`` the damper
    force F_y + C0 v_peak, ``F_y`` the yield force 2 tau_y L A_p / h at the reference control, ``C0`` the zero-field
    damping constant, ``X`` the amplitude v_peak / (2 pi f)):

    ==================  =========================================================================================
    compliance          bulk modulus 0.4 / 0.1 GPa (oil with a little / more entrained air), chamber volume
                        A_p x 60 mm each
    herschel_bulkley    flow index 0.7 / 0.5 (ER and MR fluids thin by that much between 10 and 1e4 1/s)
    bypass              bypass damping 10 / 3 x max(F_y / v_peak, C0) (a leak past the piston that carries the
                        flow below the yield force up to a tenth / a third of the peak speed)
    accumulator         charge pressure 2 / 4 MPa, gas volume 20 / 10 cm^3, polytropic index 1.2 / 1.4
    stribeck_friction   Coulomb force 7 / 15 % of F, static force 1.5 x, Stribeck speed 2 % of v_peak
    slug_inertia        slug mass 2.5 / 5 x rho L A_p^2 / (n pi d h)
    coil_lag            time constant 15 / 40 ms (coil L/R and eddy currents)
    thermal             heat capacity of a quarter / a tenth of the fluid (A_p x 2 x 80 mm plus the ducts): the
                        fluid in and near the ducts heats first, the record is too short to warm the rest; cooling
                        time 300 s, viscosity coefficient 0.025 / 0.03 1/K
    preyield            shear modulus for a yield strain of 0.15 / 0.4
    blowoff             a rebound relief valve cracking at 0.8 / 0.5 x F, damping 0.2 C0 once open
    single_rod          no parameters (the rod on one side only)
    cavitation          the rebound chamber cavitates at a pressure drop of 0.8 / 0.5 x F / A_p
    free_play           backlash of half-width 3 / 6 % of X
    ==================  =========================================================================================
    """
    if size not in SIZES:
        raise ValueError(f"size: must be one of {', '.join(SIZES)}, got {size!r}")
    big = size == "large"
    s = _scales(damper, speed)
    f = damper.fluid
    if mechanism == "compliance":
        return {"bulk_modulus": 1e8 if big else 4e8, "chamber_volume": s["Ap"] * 0.06}
    if mechanism == "herschel_bulkley":
        return {"flow_index": 0.5 if big else 0.7}
    if mechanism == "bypass":
        return {"bypass_damping": (3.0 if big else 10.0) * max(s["Fy"] / speed, s["C0"])}
    if mechanism == "accumulator":
        return {
            "charge_pressure": 4e6 if big else 2e6,
            "gas_volume": 10e-6 if big else 20e-6,
            "polytropic_index": 1.4 if big else 1.2,
        }
    if mechanism == "stribeck_friction":
        Fc = (0.15 if big else 0.07) * s["force"]
        return {"coulomb_force": Fc, "static_force": 1.5 * Fc, "stribeck_speed": 0.02 * speed}
    if mechanism == "slug_inertia":
        return {"slug_mass": (5.0 if big else 2.5) * s["slug"]}
    if mechanism == "coil_lag":
        return {"time_constant": 0.04 if big else 0.015}
    if mechanism == "thermal":
        C = 1800.0 * s["volume"] * f.density  # J/K: fluid specific heat ~1.5-2 kJ/(kg K)
        return {
            "heat_capacity": C / 10 if big else C / 4,
            "cooling_time": 300.0,
            "temperature_coefficient": 0.03 if big else 0.025,
        }
    if mechanism == "preyield":
        return {"shear_modulus": f.yield_stress / (0.4 if big else 0.15)}
    share = 0.5 if big else 0.8
    if mechanism == "blowoff":
        return {"cracking_force": share * s["force"], "blowoff_damping": 0.2 * s["C0"]}
    if mechanism == "single_rod":
        return {}
    if mechanism == "cavitation":
        return {"charge_pressure": 2e3 + share * s["force"] / s["Ap"], "vapour_pressure": 2e3}
    if mechanism == "free_play":
        return {"half_width": (0.06 if big else 0.03) * speed / (2 * math.pi * frequency)}
    raise ValueError(f"mechanism: unknown {mechanism!r}")


# ---------------------------------------------------------------------------------------------------- motions
def control_staircase(
    time: np.ndarray, velocity: np.ndarray, reference: float, *, step_period: float = STEP_PERIOD, levels=STEP_LEVELS
) -> np.ndarray:
    """The control: ``levels`` x ``reference``, one step every ``step_period`` [s], each step moved to the speed
    peak within a third of a period of its nominal time (a lagging field is then seen at speed)."""
    t = np.asarray(time)
    speed = np.abs(np.asarray(velocity))
    control = np.empty(t.size)
    edges = [0]
    k = 1
    while t[0] + k * step_period < t[-1]:
        nominal = t[0] + k * step_period
        window = np.flatnonzero(np.abs(t - nominal) <= step_period / 3)
        edges.append(int(window[np.argmax(speed[window])]) if window.size else int(np.searchsorted(t, nominal)))
        k += 1
    edges.append(t.size)
    for i, (a, b) in enumerate(zip(edges[:-1], edges[1:])):
        control[a:b] = levels[i % len(levels)] * reference
    return control


def _to_speed(m: Motion, speed: float) -> Motion:
    """The motion scaled so that its peak speed is ``speed``."""
    factor = speed / np.max(np.abs(m.velocity))
    return replace(
        m, displacement=m.displacement * factor, velocity=m.velocity * factor, acceleration=m.acceleration * factor
    )


#: The DoE grid of the ``doe_sine`` programme: (frequency, speed) multiples of the case's frequency and peak speed,
#: in a scrambled run order (a DoE is run in random order so that drifts do not line up with a factor).
_DOE_RUNS = ((1.0, 0.7), (0.5, 1.0), (2.0, 0.4), (1.0, 1.0), (2.0, 0.7), (0.5, 0.4), (2.0, 1.0), (0.5, 0.7), (1.0, 0.4))


# The excitations of build_motion: each makes the motion at peak piston speed ``speed`` [m/s] around ``frequency``
# [Hz] (duration [s], sampling rate [Hz], seed of the random ones).
def _sine(speed, frequency, duration, rate, seed):
    # four segments over frequency and speed (amplitude): the viscous and yield parts apart, and the rate effects
    f = frequency * np.array([1.0, 2.0, 1.5, 3.0])
    v = speed * np.array([0.6, 1.0, 0.4, 0.8])
    return stepped_sine(v / (2 * np.pi * f), f, [0.0], cycles=duration / float(np.sum(1 / f)), rate=rate)


def _random(speed, frequency, duration, rate, seed):
    band = (0.4 * frequency, 4 * frequency)
    return _to_speed(random_motion(1.0, band, duration=duration, rate=rate, seed=seed), speed)


def _earthquake(speed, frequency, duration, rate, seed):
    m = earthquake_motion(1.0, duration=duration, rate=rate, ground_frequency=1.5 * frequency, seed=seed)
    return _to_speed(m, speed)


def _doe_sine(speed, frequency, duration, rate, seed):
    f = frequency * np.array([r[0] for r in _DOE_RUNS])
    v = speed * np.array([r[1] for r in _DOE_RUNS])
    return sine_programme(v / (2 * np.pi * f), f, duration=duration, rate=rate)


def _swept_sine(speed, frequency, duration, rate, seed):
    return swept_sine(speed, 0.4 * frequency, 4 * frequency, duration=duration, rate=rate)


def _ou(speed, frequency, duration, rate, seed):
    m = ornstein_uhlenbeck_motion(
        1.0, 1 / (2 * np.pi * frequency), 4 * frequency, duration=duration, rate=rate, seed=seed
    )
    return _to_speed(m, speed)


def _multisine(speed, frequency, duration, rate, seed):
    band = (0.4 * frequency, 4 * frequency)
    return random_phase_multisine(speed, band, duration / 3, duration=duration, rate=rate, seed=seed)


def _filtered_gaussian(speed, frequency, duration, rate, seed):
    band = (0.4 * frequency, 4 * frequency)
    return _to_speed(filtered_gaussian_motion(1.0, band, duration=duration, rate=rate, seed=seed, order=4), speed)


#: Excitation name -> its motion (the generators above), the order of :data:`EXCITATIONS` then
#: :data:`ISSUE23_EXCITATIONS`.
_MOTIONS = {
    "sine": _sine,
    "random": _random,
    "earthquake": _earthquake,
    "doe_sine": _doe_sine,
    "swept_sine": _swept_sine,
    "ou": _ou,
    "multisine": _multisine,
    "filtered_gaussian": _filtered_gaussian,
}


def build_motion(
    excitation: str,
    damper: Damper,
    *,
    duration: float,
    rate: float,
    seed: int,
    speed: float,
    frequency: float,
    control_scale: float = 1.0,
    step_period: float = STEP_PERIOD,
    levels=STEP_LEVELS,
) -> Motion:
    """The motion of a case: ``excitation`` at peak piston speed ``speed`` [m/s] around ``frequency`` [Hz], with
    the control staircase of :func:`control_staircase` (``levels`` x ``control_scale`` x the reference field, one
    step every ``step_period`` [s]; one level: a constant control).

    Excitations: ``sine`` (four segments over frequency and speed), ``random`` (:func:`~erdesign.simulation.rig.
    random_motion`), ``earthquake``; and those of issue 23: ``doe_sine`` (a 3 x 3 DoE over frequency 0.5-2 x and speed
    0.4-1 x, scrambled run order, equal cycles per run, each run from rest to rest,
    :func:`~erdesign.simulation.truthrig.motions.sine_programme`), ``swept_sine`` (logarithmic, 0.4-4 x ``frequency``),
    ``ou`` (Ornstein-Uhlenbeck command, correlation time 1 / (2 pi f), through a 4 f servo), ``multisine`` (random
    phases, 0.4-4 x ``frequency``, a period of a third of the record) and ``filtered_gaussian`` (causal order-4
    Butterworth band-pass 0.4-4 x ``frequency``), the last three scaled to the peak speed.
    """
    if excitation not in _MOTIONS:
        raise ValueError(f"excitation: must be one of {', '.join(_MOTIONS)}, got {excitation!r}")
    m = _MOTIONS[excitation](speed, frequency, duration, rate, seed)
    levels = tuple(levels)
    control = control_staircase(
        m.time, m.velocity, control_scale * damper.fluid.reference_field, step_period=step_period, levels=levels
    )
    if len(levels) == 1:
        text = f"control constant at {levels[0] * control_scale:g} x reference"
    else:
        text = (
            f"control staircase {' / '.join(f'{x:g}' for x in levels)} x {control_scale:g} x reference every "
            f"{step_period:g} s, steps at speed"
        )
    return replace(m, control=control, description=f"{m.description}; {text}")


# ---------------------------------------------------------------------------------------------------- cases
@dataclass(frozen=True)
class Case:
    """One benchmark record: a damper, an excitation, noise, the true mechanisms and the correct answer."""

    name: str
    damper: str
    """Example damper (``erdesign.load_example`` name)."""
    excitation: str
    """``"sine"``, ``"random"`` or ``"earthquake"``."""
    noise: float
    """Force noise, fraction of the RMS force."""
    mechanisms: Mapping[str, Mapping[str, float]]
    """Truth-rig mechanism -> parameters (SI)."""
    expected: str
    """``"nothing_missing"``, ``"unexplained"`` or a library effect name."""
    accepted: frozenset
    """Effect names that count as a correct ``missing_effect`` (empty for clean and out-of-library cases)."""
    seed: int
    size: str = ""
    """``"moderate"`` or ``"large"`` (empty for clean cases)."""
    duration: float = 6.0
    """[s]"""
    rate: float = 500.0
    """[Hz]"""
    speed: float = 0.1
    """Peak piston speed, [m/s]."""
    frequency: float = 1.0
    """Centre frequency of the excitation, [Hz]."""
    viscosity_factor: float = 1.0
    yield_stress_factor: float = 1.0
    control_scale: float = 1.0
    """Top of the control staircase over the reference field."""
    group: str = ""
    """Benchmark class the case belongs to (one of :data:`ISSUE23_GROUPS`; empty for the core catalogue, which is
    reported by true class)."""
    step_period: float = STEP_PERIOD
    """Time between steps of the control staircase, [s]."""
    step_levels: tuple = STEP_LEVELS
    """Levels of the control staircase, fractions of ``control_scale`` x the reference field (one: constant)."""
    displacement_noise: float = DISPLACEMENT_NOISE
    """Displacement noise, fraction of the peak displacement."""
    anti_alias: float = 0.0
    """Corner [Hz] of the causal Butterworth low-pass (order :data:`ANTI_ALIAS_ORDER`) that both measured channels,
    force and displacement, pass before they are sampled; 0: none.  With it the force noise is drawn white, filtered
    with the force and scaled so that the filtered noise is ``noise`` x the RMS force."""
    displacement_resolution: float = 0.0
    """Step of the displacement readout, [m] (the measured displacement is rounded to it); 0: none."""
    artefacts: tuple = ()
    """Lab artefacts applied to the measured record, in order: ``(name, size)`` pairs of :data:`ARTEFACTS`."""
    finding: str = ""
    """The data finding (:data:`erdesign.data.findings.FINDING_KINDS`) a correct diagnosis reports; empty: none."""
    also_accepted: tuple = ()
    """Verdicts accepted besides :attr:`expected` (a record whose artefact mimics a mechanism: the verdict may be
    ``"unexplained"``, never the mimicked effect)."""

    @property
    def kind(self) -> str:
        """``"clean"``, ``"out_of_library"``, ``"single"`` or ``"pair"``."""
        if self.expected == "nothing_missing":
            return "clean"
        if self.expected == "unexplained":
            return "out_of_library"
        return "pair" if len(self.accepted) > 1 else "single"

    def load_damper(self) -> Damper:
        return load_example(self.damper)

    def motion(self, damper: Damper | None = None) -> Motion:
        return build_motion(
            self.excitation,
            damper or self.load_damper(),
            duration=self.duration,
            rate=self.rate,
            seed=self.seed,
            speed=self.speed,
            frequency=self.frequency,
            control_scale=self.control_scale,
            step_period=self.step_period,
            levels=self.step_levels,
        )

    def truth(self, damper: Damper | None = None, mechanisms: Mapping | None = None):
        """The true damper (:class:`erdesign.simulation.truthrig.TruthDamper`)."""
        from . import TruthDamper

        mech = self.mechanisms if mechanisms is None else mechanisms
        return TruthDamper(
            damper or self.load_damper(),
            mechanisms={k: dict(v) for k, v in mech.items()},
            viscosity_factor=self.viscosity_factor,
            yield_stress_factor=self.yield_stress_factor,
        )

    def make(self, rng_seed: int | None = None):
        """Simulate the case on the truth rig: a :class:`erdesign.simulation.truthrig.TruthRecord` (noise seed
        ``rng_seed``, default :attr:`seed`)."""
        from . import simulate_truth

        damper = self.load_damper()
        seed = self.seed if rng_seed is None else rng_seed
        rec = simulate_truth(
            self.truth(damper),
            self.motion(damper),
            force_noise=0.0 if self.anti_alias else self.noise,
            displacement_noise=self.displacement_noise,
            seed=seed,
            name=self.name,
        )
        if self.anti_alias or self.displacement_resolution:
            rec = self._instrumented(rec, seed)
        for name, size in self.artefacts:
            rec = replace(
                rec,
                measured=ARTEFACTS[name](rec.measured, size),
                description=f"{rec.description}; artefact {name} {size:g}",
            )
        return rec

    def _instrumented(self, rec, seed: int):
        """The record as a band-limited load cell and displacement channel, and a stepped readout, measure it.

        The anti-alias filter is causal (it runs forward in time, as the analogue filter of a signal conditioner
        does) and starts settled at the first sample; force and displacement pass the same filter, so it delays
        both alike and puts no skew between them (the commanded control is logged as issued).
        """
        from scipy import signal

        from ...data.measurement import Measurement

        m = rec.measured
        t, x = np.asarray(m.time), np.array(m.displacement, float)
        F = np.array(rec.true_force if self.anti_alias else m.force, float)
        notes = []
        if self.anti_alias:
            sos = signal.butter(ANTI_ALIAS_ORDER, self.anti_alias, fs=self.rate, output="sos")
            zi = signal.sosfilt_zi(sos)
            low = lambda y: signal.sosfilt(sos, y, zi=zi * y[0])[0]  # noqa: E731
            white = np.random.default_rng(seed + 7919).standard_normal(t.size)
            noise = low(white)
            noise *= self.noise * np.sqrt(np.mean(F**2)) / np.std(noise)
            F = low(F) + noise
            x = low(x)
            notes.append(
                f"force and displacement through a causal order-{ANTI_ALIAS_ORDER} Butterworth low-pass at "
                f"{self.anti_alias:g} Hz, force noise {self.noise:g} of RMS after the filter"
            )
        if self.displacement_resolution:
            q = self.displacement_resolution
            x = np.round(x / q) * q
            notes.append(f"displacement read out in steps of {q * 1e6:g} um")
        measured = Measurement.from_arrays(t, x, F, control=m.control, control_kind=m.control_kind, name=m.name)
        return replace(rec, measured=measured, description=f"{rec.description}; {'; '.join(notes)}")

    def detectability(self) -> dict[str, float | None]:
        """:func:`effect_size_over_noise` of this case."""
        return effect_size_over_noise(self)


def effect_size_over_noise(case: Case, recalibrate: bool = True) -> dict[str, float | None]:
    r"""How visible the case's mechanisms are: noise-free truth runs with and without them.

    .. math::
        D = \frac{\sum (F_\text{with} - F_\text{without})^2}{\sum (F_\text{without} - \bar F_\text{without})^2},
        \qquad \frac{D}{D_\text{noise}}, \quad
        D_\text{noise} = \frac{n\,(\sigma F_\text{rms})^2}{\sum (F_\text{without} - \bar F_\text{without})^2}

    (:math:`\sigma` the force noise as a fraction of the RMS force): the energy of the change the mechanisms make
    over the energy of the noise (``effect_size_over_noise``).  Part of the change is absorbed by recalibrating the
    two fluid factors (a shear-thinning fluid looks much like a Bingham fluid with another viscosity), so with
    ``recalibrate`` the run without the mechanisms is also fitted to the run with them - the truth rig's own
    viscosity and yield-stress factors, bounded least squares, nothing of the diagnosed model - and
    ``visible_over_noise`` is what is left over the noise: what no calibration of the clean damper can remove,
    the size a diagnosis can see.  Samples where the velocity is within 1 % of its peak of zero are left out of
    both sums (there the sign of a measured velocity is not known, :func:`erdesign.data.noise.sign_known`).  All None
    for a clean case.
    """
    keys = ("effect_esr", "noise_esr", "effect_size_over_noise", "visible_esr", "visible_over_noise")
    if not case.mechanisms:
        return dict.fromkeys(keys)
    from scipy.optimize import least_squares

    from . import simulate_truth

    damper = case.load_damper()
    motion = case.motion(damper)

    def run(mech, kv=None, ky=None):
        truth = case.truth(damper, mech)
        if kv is not None:
            truth = replace(truth, viscosity_factor=kv, yield_stress_factor=ky)
        rec = simulate_truth(truth, motion, force_noise=0.0, displacement_noise=0.0, seed=case.seed, name=case.name)
        return np.asarray(rec.true_force, float)

    with_, without = run(case.mechanisms), run({})
    var = float(np.sum((without - without.mean()) ** 2))
    effect = float(np.sum((with_ - without) ** 2)) / var
    noise = with_.size * (case.noise * float(np.sqrt(np.mean(with_**2)))) ** 2 / var
    out = {
        "effect_esr": effect,
        "noise_esr": noise,
        "effect_size_over_noise": effect / noise,
        "visible_esr": None,
        "visible_over_noise": None,
    }
    if recalibrate:
        keep = np.abs(motion.velocity) > 0.01 * np.max(np.abs(motion.velocity))
        k0 = np.array([case.viscosity_factor, case.yield_stress_factor])
        fit = least_squares(
            lambda k: (with_ - run({}, k[0], k[1]))[keep],
            k0,
            bounds=([0.05, 0.05], [20.0, 20.0]),
            x_scale=k0,
            diff_step=1e-4,
            max_nfev=60,
        )
        visible = float(np.sum(fit.fun**2)) / var
        noise_kept = noise * keep.mean()
        out["visible_esr"] = visible
        out["visible_over_noise"] = visible / noise_kept
    return out


# Calibration factors of the true fluid (the nominal file is off by tens of percent), cycled over the cases.
_FACTORS = ((1.15, 0.9), (0.85, 1.1), (1.25, 0.8), (0.9, 1.2), (1.05, 0.95), (0.8, 1.05), (1.2, 1.15))
# Faster excitations for the mechanisms whose force grows with frequency faster than the viscous force.
_FREQUENCY_BOOST = {"slug_inertia": 6.0, "compliance": 1.5}
# Lower control levels where the yield force would hide a small force of another kind.
_CONTROL_SCALE = {"slug_inertia": 0.4, "herschel_bulkley": 0.25}
# Faster strokes for the mechanisms that show in the viscous force only (heating lowers the viscosity, not the yield
# stress): the viscous share of the force and the heating power grow with the speed.
_SPEED_BOOST = {"thermal": 2.0}
# Where a mechanism cannot be seen at physical sizes, its single-effect slots go elsewhere (measured with
# effect_size_over_noise's recalibrated ``visible_over_noise``, docs/diagnosis_benchmark.md):
# - the fluid slug of Makris's ER damper, driven at its design speed of 25 mm/s, weighs too little to be felt;
# - the Kamath-Wereley-like ER head (0.25 Pa s in a 2.5 mm gap) dissipates too little to warm its fluid: what no
#   recalibration absorbs is 0.02 x the noise at either size (benchmark run of 2026-11-23);
NOT_VISIBLE_ON = {"slug_inertia": {"makris"}, "thermal": {"kamath_wereley"}}
# - heating needs sustained power: sine programmes (a decaying earthquake record or random motion heats too little);
#   a fluid slug needs acceleration: not the earthquake records, whose energy lies below 25 Hz;
EXCITATIONS_OF = {"thermal": ("sine",), "slug_inertia": ("sine", "random")}
# - heating and shear thinning change only the viscous part of the force, which is small beside an MR fluid's
#   yield force: on the MR dampers they are measured with the quieter load cell.
QUIET_ON_MR = {"thermal", "herschel_bulkley"}
_MR_DAMPERS = {"mr_valve", "mr_valve_current", "mr_mixed"}
# Sampling rate [Hz] by mechanism: 1 kHz where a few milliseconds matter.
_RATE = {"slug_inertia": 1000.0, "coil_lag": 1000.0, "compliance": 1000.0}
# Record length [s] by mechanism: heating needs time to warm the fluid.
_DURATION = {"thermal": 20.0}


_DAMPER_CACHE: dict[str, Damper] = {}
#: Truth-rig mechanism -> the library effect that describes it.
_EFFECT_OF = {mech: effect for effect, mech in LIBRARY_MECHANISMS.items()}


def _example(name: str) -> Damper:
    if name not in _DAMPER_CACHE:
        _DAMPER_CACHE[name] = load_example(name)
    return _DAMPER_CACHE[name]


def _answer(mechanisms) -> tuple[str, frozenset]:
    """The correct answer for a record with these hidden mechanisms: ``expected`` and the ``accepted`` effects.
    None: ``"nothing_missing"``; one that no library effect describes: ``"unexplained"``; otherwise the library
    effect of the first mechanism, and the effects of all of them are accepted (a pair: either)."""
    if not mechanisms:
        return "nothing_missing", frozenset()
    if any(m not in _EFFECT_OF for m in mechanisms):
        return "unexplained", frozenset()
    effects = [_EFFECT_OF[m] for m in mechanisms]
    return effects[0], frozenset(effects)


def _make_case(
    name: str,
    dname: str,
    excitation: str,
    noise: float,
    mechanisms: Mapping,
    seed: int,
    *,
    size: str | None = None,
    duration: float,
    rate: float,
    speed: float,
    frequency: float,
    control_scale: float,
    **fields,
) -> Case:
    """A case on the example damper ``dname``: mechanisms given as ``{name: size}`` (sized by
    :func:`mechanism_parameters` at the case's speed and frequency) or ``{name: {parameter: value}}`` (sized
    explicitly), the answer from them (:func:`_answer`), the calibration factors from the seed; ``fields`` set the
    other :class:`Case` fields.  ``size`` defaults to the size of the first mechanism when it is given by name."""
    damper = _example(dname)
    if size is None:
        first = next(iter(mechanisms.values()), "")
        size = first if isinstance(first, str) else ""
    params = {
        mech: dict(how) if isinstance(how, Mapping) else mechanism_parameters(mech, how, damper, speed, frequency)
        for mech, how in mechanisms.items()
    }
    if "accumulator" in params:
        # the rod must not fill the gas: at least twice the largest volume it pushes in (long earthquake strokes)
        from .simulate import rod_area

        x = build_motion(
            excitation,
            damper,
            duration=duration,
            rate=rate,
            seed=seed,
            speed=speed,
            frequency=frequency,
            control_scale=control_scale,
        ).displacement
        need = 2.0 * rod_area(damper) * float(np.max(np.abs(x)))
        params["accumulator"]["gas_volume"] = max(params["accumulator"]["gas_volume"], need)
    expected, accepted = _answer(mechanisms)
    kv, ky = _FACTORS[seed % len(_FACTORS)]
    return Case(
        name=name,
        damper=dname,
        excitation=excitation,
        noise=noise,
        mechanisms=params,
        expected=expected,
        accepted=accepted,
        seed=seed,
        size=size,
        duration=duration,
        rate=rate,
        speed=speed,
        frequency=frequency,
        viscosity_factor=kv,
        yield_stress_factor=ky,
        control_scale=control_scale,
        **fields,
    )


def _case(name, damper_name, excitation, noise, mechanisms, seed, duration=None) -> Case:
    """A case of the core catalogue: speed, frequency, duration, rate and control from the damper's scales and the
    mechanisms' needs (:data:`_FREQUENCY_BOOST`, :data:`_SPEED_BOOST`, :data:`_DURATION`, :data:`_RATE`,
    :data:`_CONTROL_SCALE`)."""
    scale = _SCALES[damper_name]
    boost = max([_FREQUENCY_BOOST.get(m, 1.0) for m in mechanisms] or [1.0])
    return _make_case(
        name,
        damper_name,
        excitation,
        noise,
        mechanisms,
        seed,
        duration=duration or max([_DURATION.get(m, 6.0) for m in mechanisms] or [6.0]),
        rate=max([_RATE.get(m, 500.0) for m in mechanisms] or [500.0]),
        speed=scale.speed * max([_SPEED_BOOST.get(m, 1.0) for m in mechanisms] or [1.0]),
        frequency=scale.frequency * boost,
        control_scale=min([_CONTROL_SCALE.get(m, 1.0) for m in mechanisms] or [1.0]),
    )


def supported(mechanisms, damper_name: str) -> bool:
    """Whether the truth rig can simulate ``mechanisms`` together on the example damper ``damper_name`` (the
    mixed-mode damper has no chambers for the out-of-library valves; some sets are not combined,
    :data:`~.simulate.UNSUPPORTED` and :data:`~.simulate.UNSUPPORTED_MIXED`)."""
    names = set(mechanisms)
    if any(group <= names for group in UNSUPPORTED):
        return False
    if _example(damper_name).geometry.configuration != "mixed":
        return True
    return names <= set(MIXED_MECHANISMS) and not any(group <= names for group in UNSUPPORTED_MIXED)


def unsupported_pairs() -> list[tuple[str, str]]:
    """Pairs of library effects the truth rig cannot simulate together on any damper (left out of the catalogue)."""
    return [
        (a, b)
        for a, b in combinations(LIBRARY_MECHANISMS, 2)
        if not any(supported({LIBRARY_MECHANISMS[a], LIBRARY_MECHANISMS[b]}, d) for d in DAMPERS)
    ]


def _conditions(dname: str, excitation: str, noise: float) -> str:
    """The part of a core case's name that says its damper, excitation and noise."""
    return f"{dname}-{excitation}-{round(100 * noise)}pct"


def _full() -> list[Case]:
    cases: list[Case] = []
    seed = 1000
    effects = list(LIBRARY_MECHANISMS)
    # single effects: 9 effects x 2 sizes x 5 slots, one per damper where the truth rig can simulate the effect on
    # it (otherwise the slot goes to another damper with another excitation); excitation and noise cycle so that
    # each effect meets all
    for ie, effect in enumerate(effects):
        mech = LIBRARY_MECHANISMS[effect]
        dampers = [d for d in DAMPERS if supported({mech}, d) and d not in NOT_VISIBLE_ON.get(mech, ())]
        for isz, size in enumerate(SIZES):
            for k in range(len(DAMPERS)):
                dname = dampers[k % len(dampers)]
                choices = EXCITATIONS_OF.get(mech, EXCITATIONS)
                exc = choices[(k + ie + isz + k // len(dampers)) % len(choices)]
                noise = NOISES[0] if mech in QUIET_ON_MR and dname in _MR_DAMPERS else NOISES[(k + isz) % 2]
                seed += 1
                name = f"{effect}-{size}-{_conditions(dname, exc, noise)}"
                if any(c.name == name for c in cases):  # the same conditions again (another noise seed)
                    name += f"-{k}"
                cases.append(_case(name, dname, exc, noise, {mech: size}, seed))
    # every pair of library effects once, both large, that the truth rig can simulate together
    impossible = set(unsupported_pairs())
    for ip, (a, b) in enumerate(combinations(effects, 2)):
        if (a, b) in impossible:
            continue
        pair = {LIBRARY_MECHANISMS[a], LIBRARY_MECHANISMS[b]}
        dname = next(
            DAMPERS[(ip + j) % len(DAMPERS)]
            for j in range(len(DAMPERS))
            if supported(pair, DAMPERS[(ip + j) % len(DAMPERS)])
        )
        exc = EXCITATIONS[ip % 3]
        noise = NOISES[(ip // 3) % 2]
        seed += 1
        mechanisms = {LIBRARY_MECHANISMS[a]: "large", LIBRARY_MECHANISMS[b]: "large"}
        cases.append(_case(f"pair-{a}+{b}-{_conditions(dname, exc, noise)}", dname, exc, noise, mechanisms, seed))
    # clean: exactly Bingham with perturbed calibration factors
    for ic in range(15):
        dname = DAMPERS[ic % len(DAMPERS)]
        exc = EXCITATIONS[ic % 3]
        noise = NOISES[(ic // 5) % 2]
        seed += 1
        cases.append(_case(f"clean-{_conditions(dname, exc, noise)}-{ic}", dname, exc, noise, {}, seed))
    # outside the library
    for io, (mech, dname) in enumerate((m, d) for m in OUT_OF_LIBRARY for d in DAMPERS[:3]):
        exc = EXCITATIONS[io % 3]
        noise = NOISES[io % 2]
        seed += 1
        cases.append(
            _case(f"outside-{mech}-{_conditions(dname, exc, noise)}", dname, exc, noise, {mech: "large"}, seed)
        )
    return cases


def _fast() -> list[Case]:
    """Seven short records: one clean, one out of the library, five single effects on different dampers."""
    specs = [
        ("clean", "mr_valve", "sine", {}),
        ("outside-blowoff", "mr_valve_current", "sine", {"blowoff": "large"}),
        ("seal_friction", "makris", "sine", {"stribeck_friction": "large"}),
        ("compressibility", "mr_valve", "random", {"compliance": "large"}),
        ("field_lag", "mr_valve_current", "sine", {"coil_lag": "large"}),
        ("fluid_inertia", "mr_mixed", "sine", {"slug_inertia": "large"}),
        ("gas_spring", "kamath_wereley", "earthquake", {"accumulator": "large"}),
    ]
    return [
        _case(f"fast-{label}-{dname}-{exc}", dname, exc, 0.01, mech, 100 + i, duration=4.0)
        for i, (label, dname, exc, mech) in enumerate(specs)
    ]


# ---------------------------------------------------------------------------------------------------- issue 23
# Heat capacity of the long heating records over the fluid's own (mechanism_parameters' "volume" x density x
# 1800 J/(kg K)), by damper and speed over its working speed: sized so that the record warms the fluid by about
# HEATING_TARGET (measured on the truth rig; tests/test_diagnosis_benchmark.py holds each record to 25-35 K).  The
# factor is the share of the fluid and its steel that heats with the fluid in the ducts within a minute or so.
_HEATING_SHARE = {
    ("makris", 2.0): 0.8,
    ("mr_valve", 2.0): 0.88,
    ("mr_valve_current", 2.0): 0.7,
    ("mr_valve", 1.0): 0.47,
}


def _artefact(name: str):
    from . import artefacts

    return getattr(artefacts, name)


#: Lab artefacts of the ``artefacts`` class (:mod:`erdesign.simulation.truthrig.artefacts`), each sized relative to
#: the record: name -> function of (measured record, size).
ARTEFACTS = {
    # the load cell at its limit: the force clipped at ``size`` x its peak
    "clip": lambda m, f: _artefact("clip_force")(m, f * float(np.max(m.force))),
    # the displacement transducer at its limit: held within ``size`` x its peak
    "saturate": lambda m, f: _artefact("saturate_displacement")(m, f * float(np.max(np.abs(m.displacement)))),
    # a causal moving average over ``size`` samples of both channels before export
    "average": lambda m, n: _artefact("moving_average")(m, int(n)),
    # the force channel ``size`` seconds behind the displacement channel
    "skew": lambda m, s: _artefact("skew_force")(m, s),
    # a hole of ``size`` seconds in the middle of the record
    "gap": lambda m, s: _artefact("cut_time_gap")(m, float(m.time[len(m) // 2]), s),
    # a load-cell offset and drift, each ``size`` x the RMS force
    "drift": lambda m, f: _artefact("offset_and_drift")(
        m, f * float(np.sqrt(np.mean(m.force**2))), f * float(np.sqrt(np.mean(m.force**2)))
    ),
    # a displacement readout in steps of ``size`` metres
    "quantize": lambda m, q: _artefact("quantize_displacement")(m, q),
}


def _issue_case(
    group: str,
    label: str,
    dname: str,
    excitation: str,
    mechanisms: Mapping,
    seed: int,
    *,
    duration: float,
    rate: float,
    noise: float = NOISES[0],
    speed: float | None = None,
    frequency: float | None = None,
    control_scale: float = 1.0,
    size: str | None = None,
    **fields,
) -> Case:
    """A case of an issue-23 class (:func:`_make_case`), at the damper's working speed and frequency unless given."""
    scale = _SCALES[dname]
    return _make_case(
        f"{group}-{label}-{dname}-{excitation}-{100 * noise:g}pct",
        dname,
        excitation,
        noise,
        mechanisms,
        seed,
        size=size,
        duration=duration,
        rate=rate,
        speed=scale.speed if speed is None else speed,
        frequency=scale.frequency if frequency is None else frequency,
        control_scale=control_scale,
        group=group,
        **fields,
    )


def _heating(dname: str, boost: float) -> dict[str, float]:
    """The thermal mechanism of a long heating record at ``boost`` x the damper's working speed:
    :func:`mechanism_parameters` ``large`` with the heat capacity of :data:`_HEATING_SHARE`."""
    damper = _example(dname)
    speed = boost * _SCALES[dname].speed
    out = mechanism_parameters("thermal", "large", damper, speed)
    out["heat_capacity"] = (
        _HEATING_SHARE[dname, boost] * 1800.0 * _scales(damper, speed)["volume"] * damper.fluid.density
    )
    return out


def _issue23() -> list[Case]:
    """The classes of issue 23 (:data:`ISSUE23_GROUPS`), 50 cases; seeds from 5000."""
    cases: list[Case] = []
    seed = 5000

    def add(*args, **kw):
        nonlocal seed
        seed += 1
        cases.append(_issue_case(*args, seed=seed, **kw))

    # conditions several classes share: short 1 kHz records, plain 500 Hz records, and a shaking table's 100 Hz
    # records with a 5 um displacement readout
    short = dict(duration=6.0, rate=1000.0)
    plain = dict(duration=8.0, rate=500.0)
    shaking = dict(duration=30.0, rate=100.0, frequency=1.0, displacement_resolution=5e-6)

    # 1. long records at 1 kHz with field steps during motion: the diagnosis thinned them and lost the field lag
    g = "long_field_steps"
    lag = lambda T, T2=0.0: {"coil_lag": {"time_constant": T, "second_time_constant": T2}}  # noqa: E731
    long_ = dict(rate=1000.0, step_period=2.0)
    add(g, "lag20ms", "mr_valve", "doe_sine", lag(0.02), duration=70.0, **long_)
    add(g, "lag15+8ms", "mr_coil", "swept_sine", lag(0.015, 0.008), duration=63.0, **long_)
    add(g, "lag10ms", "mr_valve_current", "doe_sine", lag(0.01), duration=60.0, **long_)
    add(g, "lag40ms", "mr_mixed", "swept_sine", lag(0.04), duration=80.0, noise=0.03, **long_)
    add(g, "clean", "mr_valve", "doe_sine", {}, duration=60.0, **long_)
    add(g, "clean", "mr_valve_current", "swept_sine", {}, duration=66.0, noise=0.03, **long_)

    # 2. 3 kHz band-limited random records (a Dyke NEES-like test: +-1 cm, 1 m/s, anti-alias filter, 1 % load cell)
    g = "band_limited_3khz"
    dyke = dict(duration=20.0, rate=3000.0, speed=1.0, frequency=6.0, anti_alias=ANTI_ALIAS_CORNER)
    add(g, "clean", "mr_valve", "filtered_gaussian", {}, **dyke)
    add(g, "lag15ms", "mr_valve_current", "filtered_gaussian", {"coil_lag": "moderate"}, **dyke)
    add(g, "compressibility", "mr_valve", "filtered_gaussian", {"compliance": "large"}, **dyke)
    add(g, "gas_spring", "mr_valve_current", "filtered_gaussian", {"accumulator": "large"}, **dyke)

    # 3. long tests that warm the fluid by about 30 K (valve dampers: their viscous force is seen)
    g = "heating_long"
    for dname, duration, rate in (
        ("makris", 75.0, 500.0),
        ("mr_valve", 80.0, 1000.0),
        ("mr_valve_current", 60.0, 1000.0),
    ):
        add(
            g,
            "30K",
            dname,
            "sine",
            {"thermal": _heating(dname, 2.0)},
            duration=duration,
            rate=rate,
            speed=2.0 * _SCALES[dname].speed,
            size="large",
        )

    # 4. springs in series on mixed heads: an aerated column, pre-yield elasticity alone, and gas + column
    g = "series_springs_mixed"
    fast = {d: 1.5 * _SCALES[d].frequency for d in ("kamath_wereley", "mr_mixed", "makris", "mr_valve")}
    add(g, "aerated", "kamath_wereley", "random", {"compliance": "large"}, frequency=fast["kamath_wereley"], **short)
    add(g, "aerated", "mr_mixed", "sine", {"compliance": "moderate"}, frequency=fast["mr_mixed"], **short)
    add(g, "preyield", "kamath_wereley", "sine", {"preyield": "large"}, **short)
    add(g, "preyield", "mr_mixed", "random", {"preyield": "large"}, **short)
    add(
        g,
        "gas+column",
        "makris",
        "sine",
        {"accumulator": "large", "compliance": "large"},
        frequency=fast["makris"],
        **short,
    )
    add(
        g,
        "gas+column",
        "mr_valve",
        "random",
        {"accumulator": "large", "compliance": "moderate"},
        frequency=fast["mr_valve"],
        noise=0.03,
        **short,
    )

    # 5. clean records (exact Bingham, perturbed calibration factors) of every example damper, a 100 Hz record with
    #    a 5 um displacement readout and a 3 kHz band-limited record
    g = "clean_every_kind"
    for i, dname in enumerate(ALL_DAMPERS[:6]):
        add(g, "clean", dname, EXCITATIONS[i % 3], {}, noise=NOISES[i % 2], **plain)
    add(g, "100Hz-5um", "mr_mixed", "sine", {}, speed=0.1, step_levels=(0.6,), **shaking)
    add(g, "3kHz-band-limited", "mr_coil", "filtered_gaussian", {}, **dyke)

    # 6. random motion from other generators than the team's random_motion
    g = "other_generator"
    add(g, "leakage", "mr_valve", "ou", {"bypass": "large"}, **plain)
    add(g, "clean", "kamath_wereley", "ou", {}, **plain)
    add(g, "seal_friction", "makris", "multisine", {"stribeck_friction": "large"}, duration=9.0, rate=500.0, noise=0.03)
    add(
        g,
        "shear_thinning",
        "mr_valve_current",
        "multisine",
        {"herschel_bulkley": "large"},
        duration=9.0,
        rate=500.0,
        control_scale=0.25,
    )
    add(g, "gas_spring", "mr_mixed", "filtered_gaussian", {"accumulator": "moderate"}, **plain)
    add(
        g,
        "compressibility",
        "mr_valve",
        "filtered_gaussian",
        {"compliance": "large"},
        frequency=fast["mr_valve"],
        noise=0.03,
        **short,
    )

    # 5 (continued; last, so that the seeds above stay those of the first run): a shaking-table record, strokes of
    # 2.5-6 mm and a quiet load cell (0.2 %), so that the error the 5 um steps put into the derived velocity, not
    # the load cell, sets the floor
    g = "clean_every_kind"
    add(g, "100Hz-5um-quiet", "mr_coil", "sine", {}, speed=0.06, step_levels=(0.5,), noise=0.002, **shaking)

    # harder variants, shaped as the independent testers' records that failed (issue 23): a heavily aerated column
    # on the mixed ER head (0.05 GPa: 1.7e6 N/m, the testers' 1.6e6), a gas spring with a column at moderate sizes
    # on a sine programme, and heating at the damper's working speed over 83 s
    g = "series_springs_mixed"
    column = {"bulk_modulus": 5e7, "chamber_volume": 0.06 * _example("kamath_wereley").geometry.piston_area}
    add(
        g,
        "aerated-soft",
        "kamath_wereley",
        "sine",
        {"compliance": column},
        frequency=fast["kamath_wereley"],
        size="large",
        **short,
    )
    add(
        g,
        "gas+column-moderate",
        "mr_valve_current",
        "sine",
        {"accumulator": "moderate", "compliance": "moderate"},
        frequency=1.5 * _SCALES["mr_valve_current"].frequency,
        **short,
    )
    g = "heating_long"
    add(
        g,
        "30K-working-speed",
        "mr_valve",
        "sine",
        {"thermal": _heating("mr_valve", 1.0)},
        duration=83.0,
        rate=1000.0,
        size="large",
    )

    # 7. lab artefacts (erdesign/simulation/truthrig/artefacts.py) on records with and without a hidden mechanism: the
    #    finding must be reported, the artefact never named as a mechanism, and a hidden mechanism still found
    g = "artefacts"
    art = dict(duration=8.0, rate=1000.0)
    either = ("unexplained",)
    # label, damper, excitation, hidden mechanisms, artefact, the finding, verdicts accepted besides the expected
    for label, dname, exc, mechanisms, artefact, finding, also in (
        ("clipped", "mr_valve", "sine", {"stribeck_friction": "large"}, ("clip", 0.85), "clipped", ()),
        ("clipped", "mr_mixed", "random", {}, ("clip", 0.8), "clipped", ()),
        ("saturated", "mr_valve_current", "sine", {}, ("saturate", 0.9), "saturated_displacement", ()),
        ("smoothed", "mr_valve", "sine", {}, ("average", 8), "smoothed", either),
        ("skew0.8ms", "mr_valve_current", "sine", {}, ("skew", 8e-4), "channel_skew", either),
        # (a skew shows where the force jumps at reversals: on Makris's viscous ER damper 0.8 ms moves the force by
        #  less than its noise, so the skew case of the random motion is on the mixed MR head)
        ("skew0.8ms", "mr_mixed", "random", {}, ("skew", 8e-4), "channel_skew", either),
        ("gap", "mr_valve_current", "sine", {"coil_lag": "large"}, ("gap", 1.0), "time_gap", ()),
        ("drift", "mr_valve", "random", {}, ("drift", 0.08), "force_offset_drift", either),
        ("quantized5um", "mr_valve", "sine", {}, ("quantize", 5e-6), "quantized_displacement", ()),
        ("quantized5um", "mr_mixed", "sine", {"compliance": "large"}, ("quantize", 5e-6), "quantized_displacement", ()),
    ):
        add(g, label, dname, exc, mechanisms, artefacts=(artefact,), finding=finding, also_accepted=also, **art)

    # 5 (continued, last so that the seeds above stay): the example dampers added with issue 23, clean
    g = "clean_every_kind"
    for i, dname in enumerate(ALL_DAMPERS[6:], start=6):
        add(g, "clean", dname, EXCITATIONS[i % 3], {}, noise=NOISES[i % 2], **plain)
    return cases


def benchmark_cases(subset: str = "full") -> list[Case]:
    """The benchmark's cases: ``"full"`` (the core catalogue and the classes of issue 23, 203 cases), ``"core"``
    (the catalogue of 2026-11-23, 153 cases), ``"issue23"`` (:data:`ISSUE23_GROUPS`, 50 cases) or ``"fast"`` (seven
    short ones for the test suite).

    >>> core, new = benchmark_cases("core"), benchmark_cases("issue23")
    >>> len(core), sum(c.kind == "clean" for c in core), sum(c.kind == "pair" for c in core)
    (153, 15, 36)
    >>> len(new), sum(c.kind == "clean" for c in new), [c.name for c in benchmark_cases()] == [
    ...     c.name for c in core + new]
    (50, 23, True)
    """
    if subset == "full":
        return _full() + _issue23()
    if subset == "core":
        return _full()
    if subset == "issue23":
        return _issue23()
    if subset == "fast":
        return _fast()
    raise ValueError(f"subset: must be one of {', '.join(SUBSETS)}, got {subset!r}")
