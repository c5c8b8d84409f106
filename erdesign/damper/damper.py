r"""The physics damper: geometry + fluid + seal friction -> quasi-steady force, and the design figures.

Quasi-steady means the gap flow is taken as steady at each instant (no fluid inertia, no compressibility, no
pre-yield elasticity); those and other effects are added on top by the diagnosis work.

The force is that of :mod:`erdesign.damper.quasi_steady`, the one kernel every part of erdesign calls.  Valve damper
(Makris et al., eq 14):

.. math::
    F = \Delta p\,A_p + F_s \operatorname{sgn}(v), \qquad Q_\text{duct} = \frac{v A_p}{n}

with :math:`\Delta p` from the Bingham gap flow (:mod:`erdesign.flow.bingham`; the exact annulus of
:mod:`erdesign.flow.annulus_bingham` when the gap is not thin).

Mixed (moving-electrode) damper (Kamath and Wereley 1997, section II): pressure drag plus shear drag of the
moving head, :math:`F = \Delta p\,A_p + \tau_w \pi D_p L + F_s \operatorname{sgn}(v)`, from the Couette-Poiseuille
Bingham flow of :mod:`erdesign.flow.mixed_mode`.

At ``v = 0`` the force is the break-away force (the limit ``v -> 0+``): the gap is blocked and any force up to it
is held with no motion.

Design figures: small-velocity damping constant (Makris eq 15), Reynolds number (Makris eq 1) and laminar check,
yield (controllable) force, dynamic range F(E)/F(0), energy per cycle and equivalent damping (Kamath and Wereley
1997, eqs 1-2).
"""

from __future__ import annotations

import math
import numbers
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._util import broadcast_named, scalar_or_array, si_array
from ..data.metrics import energy_per_cycle, equivalent_damping
from ..errors import ErdesignError, PlausibilityWarning, ValidityWarning
from ..limits import check_sample_count
from ..flow.bingham import yield_pressure_drop
from ..fluid import Fluid
from ..geometry import THIN_GAP_LIMIT, Geometry
from ..units import Q_, positive_si, to_si
from .accumulator import ROD_KINDS, Accumulator
from .quasi_steady import CRITICAL_REYNOLDS, QuasiSteadyState, damper_state, damping_constant

__all__ = [
    "Damper",
    "exact_annulus_for",
    "QuasiSteadyState",
    "SizingResult",
    "SineResponse",
    "CRITICAL_REYNOLDS",
    "FLOW_MODELS",
    "PLAUSIBLE_PISTON_SPEED",
    "MAX_PISTON_SPEED",
    "SLOWEST_PISTON_SPEED",
    "check_piston_velocity",
]

FLOW_MODELS = ("auto", "thin_gap", "annulus")
#: Fastest piston speed [m/s] taken without a warning (car dampers stay below 2 m/s, landing gear and impact tests
#: reach a few m/s), and the fastest taken at all: beyond them a unit mistake is likely (mm/s given as m/s).
PLAUSIBLE_PISTON_SPEED, MAX_PISTON_SPEED = 10.0, 1000.0
#: Slowest piston speed [m/s] (other than 0) taken without a warning: creep tests run at tenths of a mm/s; below a
#: micrometre per second a unit mistake is likely (mm/s given as km/s, or a value underflowed).
SLOWEST_PISTON_SPEED = 1e-6


def check_piston_velocity(v: Any, name: str = "velocity") -> Any:
    """``v`` (SI, float or array), or an :class:`~erdesign.errors.ErdesignError` naming ``name`` when a speed is
    beyond :data:`MAX_PISTON_SPEED`; a :class:`~erdesign.errors.PlausibilityWarning` beyond
    :data:`PLAUSIBLE_PISTON_SPEED` (``--velocity "500 m/s"`` was sized without a word) or below
    :data:`SLOWEST_PISTON_SPEED` but not 0."""
    speed = float(np.max(np.abs(v))) if np.size(v) else 0.0
    if speed > MAX_PISTON_SPEED:
        raise ErdesignError(
            f"{name}: {speed:.4g} m/s is beyond any piston's speed (at most {MAX_PISTON_SPEED:g} m/s); check the "
            "value and its unit"
        )
    if speed > PLAUSIBLE_PISTON_SPEED:
        warnings.warn(
            f"{name}: {speed:.4g} m/s is beyond the piston speed of any damper ({PLAUSIBLE_PISTON_SPEED:g} m/s); "
            "check the value and its unit (mm/s given as m/s?)",
            PlausibilityWarning,
            stacklevel=3,
        )
    if 0.0 < speed < SLOWEST_PISTON_SPEED:
        warnings.warn(
            f"{name}: {speed:.4g} m/s is below the piston speed of any damper test ({SLOWEST_PISTON_SPEED:g} m/s); "
            "check the value and its unit",
            PlausibilityWarning,
            stacklevel=3,
        )
    return v


def exact_annulus_for(configuration: str, flow_model: str, gap_ratio):
    """Whether the valve gap flow is computed for the exact annulus (vectorised over ``gap_ratio`` = h/d): always
    with ``flow_model="annulus"``, above :data:`~erdesign.geometry.THIN_GAP_LIMIT` with ``"auto"``, never for a
    mixed damper or ``"thin_gap"``."""
    if configuration != "valve":
        return np.zeros(np.shape(gap_ratio), dtype=bool)
    if flow_model == "annulus":
        return np.ones(np.shape(gap_ratio), dtype=bool)
    return (np.asarray(gap_ratio) > THIN_GAP_LIMIT) & (flow_model == "auto")


@dataclass(frozen=True)
class SizingResult:
    """Design point of a damper (``erdesign size``): every figure as a pint quantity.

    :meth:`as_json` gives the plain-SI dictionary of docs/cli.md.
    """

    velocity: Any
    field: Any
    piston_area: Any
    flow_rate: Any
    flow_per_duct: Any
    pressure_drop: Any
    force: Any
    zero_field_force: Any
    dynamic_range: float | None
    damping_constant: Any
    yield_force: Any
    seal_friction: Any
    reynolds: float
    laminar: bool
    plug_fraction: float
    yield_stress: Any
    viscosity: Any
    gap_ratio: float
    flow_model: str

    def as_json(self) -> dict:
        """The keys of ``erdesign size --json``, plain SI numbers (``dynamic_range`` is null when undefined)."""
        return {
            "piston_area_m2": self.piston_area.to("m^2").magnitude,
            "flow_m3_per_s": self.flow_rate.to("m^3/s").magnitude,
            "pressure_drop_Pa": self.pressure_drop.to("Pa").magnitude,
            "force_N": self.force.to("N").magnitude,
            "zero_field_force_N": self.zero_field_force.to("N").magnitude,
            "dynamic_range": self.dynamic_range,
            "damping_constant_N_s_per_m": self.damping_constant.to("N*s/m").magnitude,
            "reynolds": self.reynolds,
            "laminar": self.laminar,
            "plug_fraction": self.plug_fraction,
        }


@dataclass(frozen=True)
class SineResponse:
    """Quasi-steady response to a sinusoidal displacement x = X0 sin(2 pi f t), SI arrays and cycle figures."""

    time: np.ndarray
    """[s]"""
    displacement: np.ndarray
    """[m]"""
    velocity: np.ndarray
    """[m/s]"""
    force: np.ndarray
    """[N]"""
    energy_per_cycle: float
    """Energy dissipated per cycle, Kamath and Wereley (1997) eq 1, [J]."""
    equivalent_damping: float
    """C_eqv = U / (pi Omega X0^2), Kamath and Wereley (1997) eq 2, [N s/m]."""


@dataclass(frozen=True)
class Damper:
    """A physics damper: geometry, fluid and seal friction.

    Build it from a damper file with :func:`erdesign.load_damper` or directly:

    >>> from erdesign import Damper, Fluid, Geometry
    >>> g = Geometry.create(configuration="valve", duct_length="54.6 mm", duct_mean_diameter="14.3 mm",
    ...                     gap="0.8 mm", piston_diameter="33.4 mm", rod_diameter="11.25 mm")
    >>> f = Fluid.create(viscosity="7 Pa*s", yield_stress="1.8 kPa", reference_field="3 kV/mm",
    ...                  yield_exponent=2.0, density="1100 kg/m^3")
    >>> d = Damper(geometry=g, fluid=f, seal_friction=112.0)
    >>> round(d.damping_constant().to("kN*s/m").magnitude, 1)     # Makris eq 15: 120 kN s/m
    120.3

    Attributes
    ----------
    geometry : Geometry
    fluid : Fluid
    seal_friction : float
        Coulomb friction of seals and bearings, F_s (Makris eq 14), [N].
    name : str
    flow_model : str
        ``"thin_gap"`` (parallel plates, Makris's equations), ``"annulus"`` (exact concentric annulus, valve only)
        or ``"auto"`` (thin gap up to h/d = :data:`~erdesign.geometry.THIN_GAP_LIMIT`, exact annulus above).
    rod : str
        ``"double"`` (a rod on both sides of the piston, the default) or ``"single"`` (one rod; the rod volume goes
        into a gas accumulator on the head side).  The quasi-steady force is the same (the gap passes
        :math:`v A_p` either way); a single rod adds the accumulator's force on the rod.
    accumulator : Accumulator or None
        The gas accumulator of a single-ended damper (:mod:`erdesign.damper.accumulator`), which sets the prior of
        the gas spring effect; None when the file does not describe one.
    """

    geometry: Geometry
    fluid: Fluid
    seal_friction: float = 0.0
    name: str = ""
    flow_model: str = "auto"
    rod: str = "double"
    accumulator: Accumulator | None = None

    def __post_init__(self) -> None:
        if self.flow_model not in FLOW_MODELS:
            raise ErdesignError(f"flow_model: must be one of {', '.join(FLOW_MODELS)}, got {self.flow_model!r}")
        if self.flow_model == "annulus" and self.geometry.configuration == "mixed":
            raise ErdesignError("flow_model: the exact annulus is available for the valve configuration only")
        if not (np.isfinite(self.seal_friction) and self.seal_friction >= 0):
            raise ErdesignError(f"seal_friction: must be a finite force >= 0, got {self.seal_friction!r} N")
        if self.rod not in ROD_KINDS:
            raise ErdesignError(f"geometry.rod: must be one of {', '.join(map(repr, ROD_KINDS))}, got {self.rod!r}")
        if self.accumulator is not None:
            if not isinstance(self.accumulator, Accumulator):
                raise ErdesignError(f"accumulator: expected an Accumulator, got {self.accumulator!r}")
            if self.rod != "single":
                raise ErdesignError(
                    "accumulator: a gas accumulator pushes on the rod only when the rod is "
                    'single-ended; set geometry.rod = "single"'
                )
            if self.geometry.rod_diameter <= 0:
                raise ErdesignError(
                    "geometry.rod_diameter: a single-ended damper with an accumulator needs the "
                    "rod's diameter (the gas pushes on its cross-section), got 0"
                )

    # ------------------------------------------------------------------ accumulator (single-ended rod)
    def gas_preload_si(self) -> float | None:
        """Preload of the accumulator on the rod, f_0 = p_0 A_r [N]; None without an accumulator."""
        return None if self.accumulator is None else self.accumulator.preload(self.geometry.rod_diameter)

    def gas_stiffness_si(self) -> float | None:
        """Stiffness of the accumulator on the rod, k = n p_0 A_r^2 / V_0 [N/m]; None without an accumulator."""
        return None if self.accumulator is None else self.accumulator.stiffness(self.geometry.rod_diameter)

    # ------------------------------------------------------------------ SI layer (floats / arrays)
    @property
    def uses_exact_annulus(self) -> bool:
        """True when the valve gap flow is computed for the exact annulus rather than parallel plates."""
        return bool(exact_annulus_for(self.geometry.configuration, self.flow_model, self.geometry.gap_ratio))

    def state(self, v, field=0.0) -> QuasiSteadyState:
        """Quasi-steady state at piston velocity ``v`` [m/s] and control ``field`` (SI magnitude), vectorised.

        ``v`` and ``field`` broadcast against each other.  The kernel is
        :func:`erdesign.damper.quasi_steady.quasi_steady_state`; see the module notes for the equations.
        """
        v, field = si_array(v, "v"), si_array(field, "field")
        broadcast_named(v=v, field=field)
        tau_y = np.asarray(self.fluid.yield_stress_at(field), dtype=float)
        eta = np.asarray(self.fluid.viscosity_at(field), dtype=float)
        return damper_state(self, v, tau_y, eta)

    def force_si(self, v, field=0.0):
        """Quasi-steady force [N] at velocity ``v`` [m/s] and control ``field`` (SI), vectorised."""
        return self.state(v, field).force

    def damping_constant_si(self) -> float:
        r"""Small-velocity damping constant of the zero-field fluid, [N s/m].

        Valve (Makris eq 15, n ducts in parallel; the exact annulus divides it by the conductance ratio of
        :func:`erdesign.flow.newtonian.annulus_conductance_ratio`):

        .. math:: C = \frac{12\,\eta_0\,L\,A_p^2}{n\,\pi\,d\,h^3}

        Mixed: the slope F/v of the Newtonian Couette-Poiseuille solution (pressure + shear drag).  Both are the
        quasi-steady fluid force of the zero-field fluid at 1 m/s (:func:`erdesign.damper.quasi_steady.damper_state`),
        which is linear in the velocity, so exact at any velocity.  Seal friction is not part of C.
        """
        g = self.geometry
        return float(
            damping_constant(
                g.configuration,
                self.fluid.viscosity,
                self.fluid.density,
                g.gap,
                g.duct_length,
                g.duct_mean_diameter,
                g.piston_diameter,
                g.rod_diameter,
                g.ducts,
                self.uses_exact_annulus,
            )
        )

    def yield_force_si(self, field) -> Any:
        """Controllable (yield) force of the fluid at control ``field`` (SI): the fluid force as v -> 0+, [N].

        Valve: :math:`2\\tau_y L A_p / h`; mixed: :math:`\\tau_y (2 L A_p / h + \\pi D_p L)`.  Seal friction is
        not included.
        """
        g = self.geometry
        tau_y = np.asarray(self.fluid.yield_stress_at(np.asarray(field, dtype=float)))
        f = yield_pressure_drop(tau_y, g.duct_length, g.gap) * g.piston_area + tau_y * g.shear_area
        return scalar_or_array(f)

    # ------------------------------------------------------------------ unit-aware layer
    def _velocity(self, velocity, name="velocity"):
        return check_piston_velocity(to_si(velocity, "m/s", name), name)

    def force(self, velocity: Any, field: Any = None):
        """Quasi-steady force at a velocity (quantity or string, may be an array) and a control, as a quantity."""
        return Q_(self.force_si(self._velocity(velocity), self.fluid.field_si(field)), "N")

    def damping_constant(self):
        """Small-velocity damping constant of the zero-field fluid (Makris eq 15), quantity [N s/m]."""
        return Q_(self.damping_constant_si(), "N*s/m")

    def yield_force(self, field: Any = None):
        """Controllable (yield) force of the fluid at a control, quantity [N]."""
        return Q_(self.yield_force_si(self.fluid.field_si(field)), "N")

    def dynamic_range(self, velocity: Any, field: Any):
        """F(v, E) / F(v, 0), [-]: how much the control multiplies the force at each velocity (array or float)."""
        v = self._velocity(velocity)
        E = self.fluid.field_si(field)
        with np.errstate(divide="ignore", invalid="ignore"):
            return scalar_or_array(np.asarray(self.force_si(v, E)) / np.asarray(self.force_si(v, 0.0)))

    def size(self, velocity: Any, field: Any = None) -> SizingResult:
        """Quasi-steady design point at one piston velocity and control (``erdesign size``).

        Warns (:class:`~erdesign.errors.ValidityWarning`) when the flow is not laminar.

        Examples
        --------
        >>> from erdesign import load_example
        >>> r = load_example("makris").size(velocity="1 in/s", field="3 kV/mm")
        >>> print(f"{r.force.to('kN'):.3~P}  range {r.dynamic_range:.2f}  Re {r.reynolds:.3f}")
        6.07 kN  range 1.92  Re 0.044
        """
        v = self._velocity(velocity)
        if np.ndim(v) != 0:
            raise ErdesignError("velocity: size takes one velocity; use Damper.state or Damper.force for sweeps")
        E = self.fluid.field_si(field)
        if np.ndim(E) != 0:
            raise ErdesignError("field: size takes one value of the control")
        s = self.state(v, E)
        s0 = self.state(v, 0.0)
        dyn = s.force / s0.force if s0.force != 0 else None
        laminar = bool(s.reynolds < CRITICAL_REYNOLDS)
        if not laminar:
            warnings.warn(
                f"velocity: Reynolds number {s.reynolds:.4g} exceeds {CRITICAL_REYNOLDS:g}; the laminar gap-flow "
                "model does not hold (Makris eq 1)",
                ValidityWarning,
                stacklevel=2,
            )
        unit = self.fluid.control_unit
        return SizingResult(
            velocity=Q_(v, "m/s"),
            field=Q_(E, unit),
            piston_area=Q_(self.geometry.piston_area, "m^2"),
            flow_rate=Q_(s.flow_rate, "m^3/s"),
            flow_per_duct=Q_(s.flow_per_duct, "m^3/s"),
            pressure_drop=Q_(s.pressure_drop, "Pa"),
            force=Q_(s.force, "N"),
            zero_field_force=Q_(s0.force, "N"),
            dynamic_range=None if dyn is None else float(dyn),
            damping_constant=self.damping_constant(),
            yield_force=Q_(self.yield_force_si(E), "N"),
            seal_friction=Q_(self.seal_friction, "N"),
            reynolds=float(s.reynolds),
            laminar=laminar,
            plug_fraction=float(s.plug_fraction),
            yield_stress=Q_(s.yield_stress, "Pa"),
            viscosity=Q_(s.viscosity, "Pa*s"),
            gap_ratio=self.geometry.gap_ratio,
            flow_model="exact annulus" if self.uses_exact_annulus else "thin gap",
        )

    def sine_response(
        self, amplitude: Any, frequency: Any, field: Any = None, *, cycles: int = 1, samples_per_cycle: int = 2000
    ) -> SineResponse:
        """Quasi-steady force for x = X0 sin(2 pi f t), with energy per cycle and C_eqv (Kamath and Wereley 1997, eqs
        1-2).

        Parameters
        ----------
        amplitude : quantity or str
            Displacement amplitude X0 (a length).
        frequency : quantity or str
            Frequency f (Hz).
        field : quantity or str, optional
            Control (default zero).
        cycles : int
            Whole cycles to simulate.
        samples_per_cycle : int
            Samples per cycle.
        """
        from ..simulation.rig import MAX_AMPLITUDE  # the one bound of a test motion's amplitude

        X0 = positive_si(amplitude, "m", "amplitude")
        f = positive_si(frequency, "Hz", "frequency")
        if X0 > MAX_AMPLITUDE:  # report --amplitude "1 km" drew loops of a kilometre without a word
            raise ErdesignError(
                f"amplitude: {X0:g} m is beyond any damper's stroke (at most {MAX_AMPLITUDE:g} m); check the value "
                "and its unit"
            )
        # the peak piston speed, through the damper's one check of speeds (1e-300 Hz gave a period of 1e300 s)
        check_piston_velocity(2 * math.pi * f * X0, "amplitude, frequency: the peak speed")
        for key, value, low in (("cycles", cycles, 1), ("samples_per_cycle", samples_per_cycle, 16)):
            # numbers.Integral: numpy's integers too; a bool is not a count (True was taken as one cycle)
            if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < low:
                raise ErdesignError(f"{key}: must be a whole number >= {low}, got {value!r}")
        cycles, samples_per_cycle = int(cycles), int(samples_per_cycle)
        check_sample_count(cycles * samples_per_cycle + 1, "cycles, samples_per_cycle", "take fewer")
        E = self.fluid.field_si(field)
        omega = 2 * math.pi * f
        t = np.linspace(0.0, cycles / f, cycles * samples_per_cycle + 1)
        x = X0 * np.sin(omega * t)
        v = X0 * omega * np.cos(omega * t)
        F = np.asarray(self.force_si(v, E), dtype=float)
        U = energy_per_cycle(t, x, F, frequency=f)
        return SineResponse(t, x, v, F, U, equivalent_damping(U, omega, X0))
