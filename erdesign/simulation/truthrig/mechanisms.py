"""The registry of mechanisms the truth rig can switch on: names, physics in a sentence, parameters and defaults.

Each :class:`Mechanism` says which effect of the erdesign effect library it corresponds to (``library_effect``),
or None for the mechanisms outside that library (``blowoff``, ``single_rod``, ``cavitation``, ``free_play``), which
a diagnosis with the library cannot express.  Parameters are SI; defaults follow from the damper's geometry and
nominal fluid where a physical value exists (the slug mass, the chamber volume) and are plain typical values
otherwise.  The simulation itself lives in :mod:`erdesign.simulation.truthrig.simulate`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

__all__ = ["Mechanism", "MECHANISMS", "mechanism_names", "SPECIFIC_HEAT", "VAPOUR_PRESSURE", "ATMOSPHERIC_PRESSURE"]

#: Specific heat of the fluid used for the default heat capacity, [J/(kg K)] (silicone and mineral oils 1.4-2 kJ).
SPECIFIC_HEAT = 1500.0
#: Default vapour (cavitation) pressure of the fluid, [Pa] (absolute; dissolved air comes out near a few kPa).
VAPOUR_PRESSURE = 2.0e3
#: Atmospheric pressure on the outer end of the rod, [Pa].
ATMOSPHERIC_PRESSURE = 101325.0


def newtonian_damping(damper) -> float:
    """Zero-field thin-gap damping constant C0 = 12 eta0 L Ap^2 / (n pi d h^3), [N s/m] (Makris eq 15)."""
    g = damper.geometry
    return (
        12.0
        * damper.fluid.viscosity
        * g.duct_length
        * g.piston_area**2
        / (g.ducts * math.pi * g.duct_mean_diameter * g.gap**3)
    )


def reference_yield_force(damper) -> float:
    """Valve yield force at the reference control, 2 tau_ref L Ap / h, [N] (0 for a fluid without yield)."""
    g = damper.geometry
    return 2.0 * damper.fluid.yield_stress * g.duct_length * g.piston_area / g.gap


def rod_area(damper) -> float:
    """Cross-section of the piston rod, pi dr^2 / 4, [m^2]."""
    return math.pi / 4.0 * damper.geometry.rod_diameter**2


def _chamber_volume(damper) -> float:
    g = damper.geometry
    return g.piston_area * g.piston_diameter


def _heat_capacity(damper) -> float:
    # the fluid of both chambers plus a steel body of ten chamber volumes (7850 kg/m^3, 460 J/(kg K))
    V = _chamber_volume(damper)
    return damper.fluid.density * SPECIFIC_HEAT * 2.0 * V + 7850.0 * 460.0 * 10.0 * V


def _slug_mass(damper) -> float:
    g = damper.geometry
    return damper.fluid.density * g.duct_length * g.piston_area**2 / (g.ducts * math.pi * g.duct_mean_diameter * g.gap)


@dataclass(frozen=True)
class Mechanism:
    """One mechanism of the truth rig.

    Attributes
    ----------
    name : str
        Registry key.
    title : str
        Short human name.
    description : str
        The physics in one or two sentences.
    library_effect : str or None
        The erdesign effect-library name it corresponds to; None when outside the library.
    units : dict
        Parameter name -> unit string.
    """

    name: str
    title: str
    description: str
    library_effect: str | None
    units: dict = field(default_factory=dict)
    _defaults: Callable = field(default=lambda damper: {}, repr=False)

    def parameters(self, damper) -> dict:
        """Parameter name -> default value (SI) for ``damper``."""
        return dict(self._defaults(damper))


MECHANISMS: dict[str, Mechanism] = {
    m.name: m
    for m in (
        Mechanism(
            "compliance",
            "Fluid compliance",
            "The fluid column of the two chambers is compressible (effective bulk modulus beta, volume V each), so the "
            "pressure force is a spring k_c = 2 beta Ap^2 / V in series with the valve: after a reversal the force ramps "
            "over 2 F_y / k_c of stroke before the valve yields again.",
            "compressibility",
            {"bulk_modulus": "Pa", "chamber_volume": "m^3"},
            lambda d: {"bulk_modulus": 1.0e9, "chamber_volume": _chamber_volume(d)},
        ),
        Mechanism(
            "herschel_bulkley",
            "Herschel-Bulkley fluid",
            "The fluid shear-thins after yield, tau = tau_y + K gamma_dot^m with K = eta gamma_ref^(1-m) "
            "(gamma_ref = 1000 1/s): the exact Herschel-Bulkley slit law replaces the Bingham one.",
            "shear_thinning",
            {"flow_index": "-"},
            lambda d: {"flow_index": 0.7},
        ),
        Mechanism(
            "bypass",
            "Leakage bypass",
            "A laminar Newtonian path (piston-seal clearance) in parallel with the ducts, damping constant C_l alone: "
            "below the yield force the piston creeps through it at v = F / C_l.",
            "leakage",
            {"bypass_damping": "N*s/m"},
            lambda d: {"bypass_damping": 5.0 * newtonian_damping(d)},
        ),
        Mechanism(
            "accumulator",
            "Gas accumulator",
            "A gas charge (pressure p0, volume Vg) compressed polytropically by the rod as it enters: "
            "F = (p0 (Vg / (Vg - A_rod x))^n - p_atm) A_rod.",
            "gas_spring",
            {"charge_pressure": "Pa", "gas_volume": "m^3", "polytropic_index": "-"},
            lambda d: {"charge_pressure": 2.0e6, "gas_volume": _chamber_volume(d), "polytropic_index": 1.4},
        ),
        Mechanism(
            "stribeck_friction",
            "Seal friction with stiction",
            "Seal friction with a Stribeck dip: F = sgn(v) (F_c + (F_s - F_c) exp(-(|v|/v_s)^2)) + c_v v, in place of "
            "the damper file's Coulomb seal friction.",
            "seal_friction",
            {"coulomb_force": "N", "static_force": "N", "stribeck_speed": "m/s", "viscous_friction": "N*s/m"},
            lambda d: {
                "coulomb_force": d.seal_friction or 100.0,
                "static_force": 1.5 * (d.seal_friction or 100.0),
                "stribeck_speed": 0.005,
                "viscous_friction": 0.0,
            },
        ),
        Mechanism(
            "slug_inertia",
            "Fluid slug inertia",
            "The fluid in the ducts is accelerated with the flow: dp = rho L / A_duct dQ/dt per duct, a mass "
            "m = rho L Ap^2 / (n pi d h) on the piston (in series with the compliance when both are on).",
            "fluid_inertia",
            {"slug_mass": "kg"},
            lambda d: {"slug_mass": _slug_mass(d)},
        ),
        Mechanism(
            "coil_lag",
            "Coil / driver lag",
            "The control the fluid sees lags the commanded control as a first-order system, u' = (c - u) / T; with "
            "a second time constant T2 > 0 as two first-order stages in cascade (the coil's L/R, then the eddy "
            "currents of the steel), u2' = (u - u2) / T2.",
            "field_lag",
            {"time_constant": "s", "second_time_constant": "s"},
            lambda d: {"time_constant": 0.02, "second_time_constant": 0.0},
        ),
        Mechanism(
            "thermal",
            "Viscous heating",
            "A lumped thermal mass (default: the fluid of both chambers and a steel body of ten chamber volumes) heated by the power the fluid dissipates and cooled to ambient, "
            "C dT/dt = P - C (T - T0) / tau; the plastic viscosity falls as eta0 exp(-alpha (T - T0)).",
            "viscous_heating",
            {"heat_capacity": "J/K", "cooling_time": "s", "temperature_coefficient": "1/K"},
            lambda d: {"heat_capacity": _heat_capacity(d), "cooling_time": 300.0, "temperature_coefficient": 0.02},
        ),
        Mechanism(
            "preyield",
            "Pre-yield elasticity",
            "The fluid is elastic-viscoplastic (Makris et al. eq 8) at the damper level: a spring of stiffness "
            "K = 12 G L Ap^2 / (n pi d h^3) below yield that relaxes onto the rigid steady force above it.",
            "preyield_elasticity",
            {"shear_modulus": "Pa"},
            lambda d: {"shear_modulus": d.fluid.shear_modulus or 10.0 * d.fluid.yield_stress},
        ),
        Mechanism(
            "blowoff",
            "Rebound blow-off valve",
            "A spring-loaded relief valve in parallel with the ducts opens in rebound only, above its cracking force, "
            "and lets the piston through at (F - F_c) / C_b more speed: the rebound force saturates near F_c.",
            None,
            {"cracking_force": "N", "blowoff_damping": "N*s/m"},
            lambda d: {
                "cracking_force": max(1.5 * reference_yield_force(d), 1000.0),
                "blowoff_damping": 0.2 * newtonian_damping(d),
            },
        ),
        Mechanism(
            "single_rod",
            "Single-ended rod",
            "The rod comes out of one chamber only: compression pressurises the full bore pi Dp^2 / 4 and pushes that "
            "volume through the valve, rebound the annulus Ap, so the force is asymmetric.",
            None,
            {},
            lambda d: {},
        ),
        Mechanism(
            "cavitation",
            "Cavitation",
            "The expanding chamber cannot fall below the vapour pressure, so the rebound force is capped at "
            "(p_charge - p_vapour) Ap.",
            None,
            {"charge_pressure": "Pa", "vapour_pressure": "Pa"},
            lambda d: {
                "charge_pressure": VAPOUR_PRESSURE
                + max(1.2 * reference_yield_force(d), 1000.0) / d.geometry.piston_area,
                "vapour_pressure": VAPOUR_PRESSURE,
            },
        ),
        Mechanism(
            "free_play",
            "Free play in the mounts",
            "Backlash of total width 2 delta in the mounts: the piston follows the actuator through the play operator "
            "and no force is transmitted while the actuator crosses the gap.",
            None,
            {"half_width": "m"},
            lambda d: {"half_width": 0.5e-3},
        ),
    )
}


def mechanism_names() -> list[str]:
    """The names of the truth-rig mechanisms, in registry order.

    >>> mechanism_names()[:3]
    ['compliance', 'herschel_bulkley', 'bypass']
    """
    return list(MECHANISMS)
