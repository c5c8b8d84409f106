r"""The truth rig: a damper "as the physics happens" on a displacement-controlled test machine.

:class:`TruthDamper` is a damper file's geometry and nominal fluid, the true fluid (calibration factors) and any
subset of the mechanisms of :data:`~erdesign.simulation.truthrig.mechanisms.MECHANISMS`; :func:`simulate_truth` drives
it with an exactly known :class:`~erdesign.simulation.rig.Motion` and returns a :class:`TruthRecord`: the noise-free
force, the noisy measurement the machine would write, the force split into its parts and the internal states.

The rig shares no code with the model that diagnosis fits (``erdesign.effects.chain``, ``erdesign.effects``,
``erdesign.identification.fit``, ``erdesign.diagnosis.diagnose``): its valve laws are written the other way round (flow
rate from pressure drop, :mod:`erdesign.simulation.truthrig.valve`) and inverted by bracketed roots, and its states are
integrated in the time domain (:mod:`erdesign.simulation.truthrig.kernels`).

The force on the rod, with ``x`` growing in compression (the convention of :mod:`erdesign.simulation.rig`):

.. math::
    F = F_\text{fluid} + F_\text{inertia} + F_\text{friction} + F_\text{gas}

* :math:`F_\text{fluid}`: the valve damper's parallel flow paths (ducts, bypass, blow-off) at the piston speed,
  or the pressure force of the compliant column, or the damper-level Makris eq 8 force, or the column in series
  with the Makris element; for the mixed-mode damper the pressure drag plus the shear drag of its moving-wall gap
  (:func:`erdesign.simulation.truthrig.valve.mixed_gap_flow`), with the same optional states;
* :math:`F_\text{inertia} = m_\text{slug} a` (rigid column; with compliance on a valve damper the slug sits inside
  the fluid state);
* :math:`F_\text{friction}`: the damper file's Coulomb seal friction :math:`F_s \operatorname{sgn} v`, or the
  Stribeck law;
* :math:`F_\text{gas}`: the accumulator.

Time stepping: with compliance, pre-yield or thermal on, the fluid element is integrated on ``substeps`` substeps
per sample; kinematics between samples are cubic Hermite interpolants of the motion (displacement with velocity,
velocity with acceleration), exact at the samples, and the control is held over each sample interval
(zero-order hold, the command at the start of the interval).  Otherwise every force is evaluated at the sample
times with the exact velocity: a rigid Bingham force jumps from :math:`-F_y` to :math:`+F_y` at a reversal with no
smoothing.  Stateful elements start unloaded, at rest, at ambient temperature and with the fluid seeing the first
commanded control.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from ...damper import Damper
from ...data.measurement import CONTROL_COLUMNS, Measurement, read_measurement, write_measurement
from ...errors import ErdesignError, OutputPathError
from ..rig import Motion
from . import kernels as K
from .mechanisms import ATMOSPHERIC_PRESSURE, MECHANISMS, rod_area
from .valve import REFERENCE_SHEAR_RATE

__all__ = [
    "TruthDamper",
    "TruthRecord",
    "simulate_truth",
    "SUBSTEPS",
    "UNSUPPORTED",
    "MIXED_MECHANISMS",
    "UNSUPPORTED_MIXED",
    "FILE_UNITS",
]

#: Default substeps per sample for the time-stepped states.
SUBSTEPS = 10

#: Pairs of mechanisms the rig does not combine, with the reason.
UNSUPPORTED = {
    frozenset({"compliance", "preyield", "slug_inertia"}): "the column in series with the elastic fluid is "
    "integrated without the slug inside it",
    frozenset({"free_play", "compliance"}): "a compliant column stores force across the gap, so the piston no "
    "longer follows the play operator",
    frozenset({"free_play", "preyield"}): "pre-yield elasticity stores force across the gap, so the piston no "
    "longer follows the play operator",
    frozenset({"free_play", "accumulator"}): "the gas force would push the free piston across the gap",
    frozenset({"single_rod", "compliance"}): "the compliance is written for two equal chambers",
}

#: Mechanisms available for the mixed-mode (moving-electrode) damper (no blow-off valve, single rod or cavitation:
#: they are written for the valve's chambers).
MIXED_MECHANISMS = (
    "compliance",
    "herschel_bulkley",
    "bypass",
    "thermal",
    "preyield",
    "stribeck_friction",
    "accumulator",
    "slug_inertia",
    "coil_lag",
    "free_play",
)
#: Sets of mechanisms the rig does not combine on the mixed-mode damper, with the reason.
UNSUPPORTED_MIXED = {
    frozenset({"compliance", "preyield"}): "the column carries the pressure force only, the elastic fluid also the "
    "wall's shear drag",
}

#: Units of the CSV columns :meth:`TruthRecord.write` uses for each kind of control.
FILE_UNITS = {"electric field": "kV/mm", "magnetic field": "kA/m", "current": "A"}

_NON_NEGATIVE = {"viscous_friction", "coulomb_force", "static_force", "vapour_pressure", "second_time_constant"}


def _settings(mechanisms) -> dict[str, dict]:
    if isinstance(mechanisms, Mapping):
        items = list(mechanisms.items())
    elif isinstance(mechanisms, (str, bytes)):
        raise ErdesignError("mechanisms: give a mapping name -> parameters or a sequence of names, not a string")
    else:
        items = [(name, {}) for name in mechanisms]
    out = {}
    for name, values in items:
        if name not in MECHANISMS:
            raise ErdesignError(f"mechanisms: unknown mechanism {name!r}; known: {', '.join(MECHANISMS)}")
        if values is None:
            values = {}
        if not isinstance(values, Mapping):
            raise ErdesignError(f"mechanisms.{name}: parameters must be a mapping name -> value, got {values!r}")
        out[name] = dict(values)
    return out


@dataclass(frozen=True)
class TruthDamper:
    """A damper as the truth rig simulates it: geometry, true fluid and the mechanisms switched on.

    Parameters
    ----------
    damper : Damper
        The damper of the damper file (geometry, nominal fluid, seal friction).
    mechanisms : mapping or sequence
        ``{"compliance": {"bulk_modulus": 2e8}, "coil_lag": {}}`` (values not given take
        :meth:`Mechanism.parameters` defaults) or a sequence of names.  Unknown names or parameters, and pairs the
        rig does not combine (:data:`UNSUPPORTED`), are errors.
    viscosity_factor, yield_stress_factor : float
        The true fluid over the nominal one, [-].

    Attributes
    ----------
    values : dict
        Mechanism name -> complete parameter dict (SI), defaults filled in.

    Examples
    --------
    >>> from erdesign.damper.files import load_example
    >>> truth = TruthDamper(load_example("makris"), {"coil_lag": {"time_constant": 0.05}, "bypass": {}})
    >>> sorted(truth.values), truth.values["coil_lag"]
    (['bypass', 'coil_lag'], {'time_constant': 0.05, 'second_time_constant': 0.0})
    >>> TruthDamper(load_example("makris"), {"coil_lag": {"tau": 1.0}})
    Traceback (most recent call last):
    ...
    erdesign.errors.ErdesignError: mechanisms.coil_lag: unknown parameter 'tau'; known: time_constant, second_time_constant
    """

    damper: Damper
    mechanisms: Any = ()
    viscosity_factor: float = 1.0
    yield_stress_factor: float = 1.0
    values: dict = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        settings = _settings(self.mechanisms)
        for name in ("viscosity_factor", "yield_stress_factor"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                raise ErdesignError(f"{name}: must be a finite number > 0, got {value!r}")
        names = set(settings)
        for group, why in UNSUPPORTED.items():
            if group <= names:
                raise ErdesignError(
                    f"mechanisms: {' and '.join(sorted(group))} cannot be combined in the truth rig: {why}"
                )
        if self.damper.geometry.configuration == "mixed":
            bad = sorted(names - set(MIXED_MECHANISMS))
            if bad:
                raise ErdesignError(
                    f"mechanisms: {', '.join(bad)} need the valve's chambers and are not available "
                    f"for the mixed-mode damper; available: {', '.join(MIXED_MECHANISMS)}"
                )
            for group, why in UNSUPPORTED_MIXED.items():
                if group <= names:
                    raise ErdesignError(
                        f"mechanisms: {' and '.join(sorted(group))} cannot be combined on the "
                        f"mixed-mode damper in the truth rig: {why}"
                    )
        values = {}
        for name, given in settings.items():
            defaults = MECHANISMS[name].parameters(self.damper)
            unknown = sorted(set(given) - set(defaults))
            if unknown:
                raise ErdesignError(
                    f"mechanisms.{name}: unknown parameter {unknown[0]!r}; known: {', '.join(defaults) or 'none'}"
                )
            merged = {**defaults, **{k: float(v) for k, v in given.items()}}
            for key, value in merged.items():
                ok = math.isfinite(value) and (value >= 0 if key in _NON_NEGATIVE else value > 0)
                if not ok:
                    limit = ">= 0" if key in _NON_NEGATIVE else "> 0"
                    raise ErdesignError(f"mechanisms.{name}.{key}: must be finite and {limit}, got {value!r}")
            values[name] = merged
        cav = values.get("cavitation")
        if cav and cav["charge_pressure"] <= cav["vapour_pressure"]:
            raise ErdesignError("mechanisms.cavitation: charge_pressure must exceed vapour_pressure")
        object.__setattr__(self, "mechanisms", tuple(settings))
        object.__setattr__(self, "values", values)

    def has(self, name: str) -> bool:
        """True when mechanism ``name`` is switched on."""
        return name in self.values

    @property
    def piston_areas(self) -> tuple[float, float]:
        """(compression area, rebound area), [m^2]: the full bore and the annulus with a single rod, else Ap."""
        g = self.damper.geometry
        Ap = g.piston_area
        return (math.pi / 4.0 * g.piston_diameter**2 if self.has("single_rod") else Ap), Ap

    @property
    def compliance_stiffness(self) -> float:
        """k_c = 2 beta Ap^2 / V, [N/m] (0 without compliance)."""
        if not self.has("compliance"):
            return 0.0
        c = self.values["compliance"]
        return 2.0 * c["bulk_modulus"] * self.damper.geometry.piston_area**2 / c["chamber_volume"]

    @property
    def mixed(self) -> bool:
        """True for the moving-electrode (mixed-mode) head."""
        return self.damper.geometry.configuration == "mixed"

    @property
    def preyield_stiffness(self) -> float:
        """The damper's elastic stiffness below yield, [N/m]: its Newtonian damping constant with eta replaced by G
        (0 without preyield); K = 12 G L Ap^2 / (n pi d h^3) for the valve.

        A solid of shear modulus G in the gap, loaded by a pressure gradient (and, on the mixed head, by the head's
        wall), deflects in the same profile as the Newtonian fluid flows (the equations are the same with velocity
        -> displacement), so the elastic stiffness is the Newtonian damping constant with eta -> G.
        """
        if not self.has("preyield"):
            return 0.0
        g = self.damper.geometry
        G = self.values["preyield"]["shear_modulus"]
        if not self.mixed:
            return 12.0 * G * g.duct_length * g.piston_area**2 / (g.ducts * math.pi * g.duct_mean_diameter * g.gap**3)
        p = self._geometry_vector()
        p[K.I_M] = 1.0
        return float(K.mixed_steady_force(1.0, 0.0, G, 1.0, p))

    def _geometry_vector(self) -> np.ndarray:
        g = self.damper.geometry
        p = np.zeros(K.N_PARAMETERS)
        p[K.I_L], p[K.I_B], p[K.I_H] = g.duct_length, math.pi * g.duct_mean_diameter, g.gap
        p[K.I_DUCTS] = g.ducts
        p[K.I_GAMMA_REF] = REFERENCE_SHEAR_RATE
        p[K.I_AC] = p[K.I_AR] = g.piston_area
        p[K.I_PC] = p[K.I_CAP] = math.inf
        if self.mixed:
            p[K.I_MIXED] = 1.0
            p[K.I_AWALL] = math.pi * g.piston_diameter * g.duct_length
        return p

    def parameter_vector(self) -> np.ndarray:
        """The SI parameter vector of :mod:`erdesign.simulation.truthrig.kernels`."""
        g, v = self.damper.geometry, self.values
        Ap = g.piston_area
        p = self._geometry_vector()
        p[K.I_M] = v["herschel_bulkley"]["flow_index"] if self.has("herschel_bulkley") else 1.0
        if self.has("bypass"):
            p[K.I_GL] = Ap**2 / v["bypass"]["bypass_damping"]
        p[K.I_PC] = math.inf
        if self.has("blowoff"):
            p[K.I_GB] = Ap**2 / v["blowoff"]["blowoff_damping"]
            p[K.I_PC] = v["blowoff"]["cracking_force"] / Ap
        p[K.I_AC], p[K.I_AR] = self.piston_areas
        if self.has("cavitation"):
            c = v["cavitation"]
            p[K.I_CAP] = (c["charge_pressure"] - c["vapour_pressure"]) * Ap
        p[K.I_KC] = self.compliance_stiffness
        if self.has("compliance") and self.has("slug_inertia") and not self.mixed:
            p[K.I_MSLUG] = v["slug_inertia"]["slug_mass"]
        p[K.I_KPRE] = self.preyield_stiffness
        if self.has("thermal"):
            t = v["thermal"]
            p[K.I_HEAT_CAPACITY], p[K.I_COOLING_TIME] = t["heat_capacity"], t["cooling_time"]
            p[K.I_ALPHA] = t["temperature_coefficient"]
        return p

    def describe(self) -> str:
        """The mechanisms with their values, and the true fluid, as text (a coil lag's second stage only when it is
        on, so that a one-stage lag reads as it did before the second stage existed)."""
        parts = []
        for name, vals in self.values.items():
            units = MECHANISMS[name].units
            text = ", ".join(
                f"{k} = {x:.4g} {units[k]}" for k, x in vals.items() if not (k == "second_time_constant" and x == 0)
            )
            parts.append(f"{name} ({text})" if text else name)
        return (
            f"mechanisms: {'; '.join(parts) or 'none'}; true fluid: viscosity x {self.viscosity_factor:g}, "
            f"yield stress x {self.yield_stress_factor:g}"
        )


@dataclass(frozen=True)
class TruthRecord:
    """What the truth rig measured, and what really happened.

    Attributes
    ----------
    name : str
    true_force : ndarray
        Noise-free force at the samples, [N].
    measured : Measurement
        Noisy displacement and force, commanded control, velocity and acceleration derived from the noisy
        displacement (as for a file read from disk).
    components : dict
        The parts of ``true_force``: ``fluid``, ``inertia``, ``friction``, ``gas_spring``, [N].
    states : dict
        ``piston_displacement`` [m], ``piston_velocity`` [m/s], ``control_seen`` (SI), ``valve_force`` [N]
        (the force the flow paths carry), ``temperature_rise`` [K], ``dissipated`` (energy dissipated in the
        fluid since the previous sample) [J].
    description : str
        Damper, motion, mechanisms with values, noise and seed.
    truth : TruthDamper
    motion : Motion
    """

    name: str
    true_force: np.ndarray
    measured: Measurement
    components: dict
    states: dict
    description: str
    truth: TruthDamper
    motion: Motion

    def file_units(self) -> dict[str, str]:
        """Column units of :meth:`write`: displacement in mm, force in N, control in the damper's field unit."""
        units = {"displacement": "mm", "force": "N"}
        kind = self.measured.control_kind
        if kind is not None:
            column = next(c for c, kinds in CONTROL_COLUMNS.items() if kind in kinds)
            units[column] = FILE_UNITS.get(kind, self.truth.damper.fluid.field_unit)
        return units

    def write(self, path, units: Mapping[str, str] | None = None) -> Path:
        """Write the measurement as a CSV file (:func:`erdesign.data.measurement.write_measurement`), with the
        description as a comment line; ``units`` overrides :meth:`file_units` by column.  Never overwrites."""
        path = Path(path)
        try:  # exclusive: an existing file, even one made while this runs, is never replaced
            write_measurement(
                path, self.measured, units={**self.file_units(), **(units or {})}, comment=self.description
            )
        except OutputPathError:
            if not path.exists():
                raise
            raise ErdesignError(f"{path}: exists; the truth rig does not overwrite files") from None
        return path

    def read_back(self, path) -> Measurement:
        """Read a file written by :meth:`write` with the reader users use (:func:`read_measurement`)."""
        return read_measurement(path)


def _piston_kinematics(truth: TruthDamper, motion: Motion):
    x, v, a = (np.asarray(arr, dtype=float) for arr in (motion.displacement, motion.velocity, motion.acceleration))
    if not truth.has("free_play"):
        return x, v, a
    delta = truth.values["free_play"]["half_width"]
    xp = K.play_operator(x, delta, float(x[0]))
    engaged = ((xp == x - delta) & (v > 0)) | ((xp == x + delta) & (v < 0))
    return xp, np.where(engaged, v, 0.0), np.where(engaged, a, 0.0)


def _fine_grid(t, x, v, a, substeps):
    """Cubic Hermite kinematics on ``substeps`` substeps per sample interval (exact at the samples)."""
    S = substeps
    s = np.arange(1, S + 1) / S
    h00, h10, h01, h11 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s, -2 * s**3 + 3 * s**2, s**3 - s**2
    dt = np.diff(t)[:, None]
    xf = h00 * x[:-1, None] + h10 * dt * v[:-1, None] + h01 * x[1:, None] + h11 * dt * v[1:, None]
    vf = h00 * v[:-1, None] + h10 * dt * a[:-1, None] + h01 * v[1:, None] + h11 * dt * a[1:, None]
    xf = np.concatenate([[x[0]], xf.ravel()])
    vf = np.concatenate([[v[0]], vf.ravel()])
    xf[::S], vf[::S] = x, v
    h = np.concatenate([[0.0], np.repeat(np.diff(t) / S, S)])
    return xf, vf, h


def _control_seen(truth: TruthDamper, command: np.ndarray, h: np.ndarray, substeps: int) -> np.ndarray:
    # command held over each sample interval; index i of the grid belongs to interval (i - 1) // substeps
    held = np.repeat(command, substeps)[: h.size]
    if not truth.has("coil_lag"):
        return held
    lag = truth.values["coil_lag"]
    if lag["second_time_constant"] > 0:  # two stages in cascade (coil L/R, then eddy currents)
        return K.two_stage_lag(held, h, lag["time_constant"], lag["second_time_constant"], float(command[0]))
    return K.first_order_lag(held, h, lag["time_constant"], float(command[0]))


def _friction(truth: TruthDamper, v):
    if truth.has("stribeck_friction"):
        s = truth.values["stribeck_friction"]
        level = s["coulomb_force"] + (s["static_force"] - s["coulomb_force"]) * np.exp(
            -((v / s["stribeck_speed"]) ** 2)
        )
        return np.sign(v) * level + s["viscous_friction"] * v
    return np.sign(v) * truth.damper.seal_friction


def _gas(truth: TruthDamper, x):
    if not truth.has("accumulator"):
        return np.zeros_like(x)
    acc, A_rod = truth.values["accumulator"], rod_area(truth.damper)
    volume = acc["gas_volume"] - A_rod * x
    if np.any(volume <= 0):
        raise ErdesignError(
            "mechanisms.accumulator: the rod would fill the whole gas volume; give a larger "
            "gas_volume or a smaller stroke"
        )
    return (
        acc["charge_pressure"] * (acc["gas_volume"] / volume) ** acc["polytropic_index"] - ATMOSPHERIC_PRESSURE
    ) * A_rod


def simulate_truth(
    truth: TruthDamper,
    motion: Motion,
    *,
    force_noise: float = 0.01,
    displacement_noise: float = 1e-4,
    seed: int = 0,
    name: str = "truth",
    substeps: int = SUBSTEPS,
) -> TruthRecord:
    """Measure a :class:`TruthDamper` on the truth rig under an imposed motion.

    Parameters
    ----------
    truth : TruthDamper
    motion : Motion
        The actuator's motion and commanded control (:mod:`erdesign.simulation.rig` generators), SI.
    force_noise : float
        Standard deviation of white force noise as a fraction of the RMS of the true force, [-].
    displacement_noise : float
        Standard deviation of white displacement noise as a fraction of the peak displacement, [-].
    seed : int
        Noise seed; the record is deterministic for a given seed.
    name : str
        Record name.
    substeps : int
        Substeps per sample for the time-stepped states (compliance, pre-yield, thermal).

    Returns
    -------
    TruthRecord

    Examples
    --------
    >>> from erdesign.damper.files import load_example
    >>> from erdesign.simulation.rig import sine
    >>> truth = TruthDamper(load_example("makris"), {"compliance": {}, "coil_lag": {}}, viscosity_factor=1.1)
    >>> rec = simulate_truth(truth, sine(0.005, 2.0, 3e6, cycles=2, rate=500), seed=1, name="case-001")
    >>> len(rec.measured), rec.measured.control_kind, round(float(abs(rec.true_force).max()), -2)
    (501, 'electric field', 15800.0)

    References
    ----------
    Makris, Burton, Hill and Jordan (1996), eqs 6, 8, 13 and 14; Kamath and Wereley, section II
    (Kamath and Wereley 1997) for the mixed-mode damper.
    """
    if not isinstance(truth, TruthDamper):
        raise ErdesignError("truth: must be a TruthDamper")
    if not (isinstance(substeps, int) and substeps >= 1):
        raise ErdesignError(f"substeps: must be a whole number >= 1, got {substeps!r}")
    for label, value in (("force_noise", force_noise), ("displacement_noise", displacement_noise)):
        if not (math.isfinite(value) and value >= 0):
            raise ErdesignError(f"{label}: must be finite and >= 0, got {value!r}")
    damper, fl = truth.damper, truth.damper.fluid
    t = np.asarray(motion.time, dtype=float)
    command = np.asarray(motion.control, dtype=float)
    xp, vp, ap = _piston_kinematics(truth, motion)

    stateful = any(truth.has(n) for n in ("compliance", "preyield", "thermal"))
    S = substeps if stateful else 1
    if S > 1:
        xf, vf, h = _fine_grid(t, xp, vp, ap, S)
    else:
        xf, vf, h = xp, vp, np.concatenate([[0.0], np.diff(t)])
    seen = _control_seen(truth, command, h, S)
    tau_y = truth.yield_stress_factor * np.asarray(fl.yield_stress_at(seen), dtype=float) * np.ones_like(seen)
    eta = truth.viscosity_factor * np.asarray(fl.viscosity_at(seen), dtype=float) * np.ones_like(seen)

    states: dict[str, np.ndarray] = {"piston_displacement": xp, "piston_velocity": vp, "control_seen": seen[::S]}
    inertia = np.zeros_like(t)
    if truth.has("slug_inertia") and (truth.mixed or not truth.has("compliance")):
        inertia = truth.values["slug_inertia"]["slug_mass"] * ap
    dx = np.concatenate([[0.0], np.diff(xf)])
    force, valve, theta, dissipated = K.run(vf, dx, h, tau_y, eta, truth.parameter_vector())
    fluid = force[::S]
    per_sample = np.concatenate([[0.0], np.add.reduceat(dissipated[1:], np.arange(0, dissipated.size - 1, S))])
    states.update(valve_force=valve[::S], temperature_rise=theta[::S], dissipated=per_sample)
    components = {"fluid": fluid, "inertia": inertia, "friction": _friction(truth, vp), "gas_spring": _gas(truth, xp)}
    true_force = sum(components.values())

    rng = np.random.default_rng(seed)
    F = true_force + force_noise * np.sqrt(np.mean(true_force**2)) * rng.standard_normal(t.size)
    x = motion.displacement + displacement_noise * np.max(np.abs(motion.displacement)) * rng.standard_normal(t.size)
    measured = Measurement.from_arrays(t, x, F, control=command, control_kind=fl.control, name=name)
    description = (
        f"truth rig: {damper.name or 'damper'} ({damper.geometry.configuration}); {motion.description}; "
        f"{truth.describe()}; noise: force {force_noise:g} of RMS, displacement {displacement_noise:g} "
        f"of peak; seed {seed}"
    )
    return TruthRecord(name, true_force, measured, components, states, description, truth, motion)
