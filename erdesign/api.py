"""Unit-aware public versions of the SI kernels: pint quantities or strings in, quantities out.

Each function here is the kernel of the same name in :mod:`erdesign.flow` (or :mod:`erdesign.constitutive`)
wrapped by :func:`erdesign.units.unit_aware`, which checks every argument's dimension (the error names the
argument) and converts to SI before calling the kernel.  The kernel itself is reachable as ``func.kernel``.
"""

from __future__ import annotations

from .constitutive import makris as _makris
from .flow import annulus_bingham as _annulus_bingham
from .flow import bingham as _bingham
from .flow import mixed_mode as _mixed
from .flow import newtonian as _newtonian
from .units import unit_aware

__all__ = [
    "slit_pressure_drop",
    "annulus_pressure_drop",
    "thin_gap_error",
    "yield_pressure_drop",
    "bingham_number",
    "bingham_flow_rate",
    "bingham_pressure_drop",
    "bingham_plug_fraction",
    "makris_stress",
    "maxwell_stress",
    "couette_poiseuille_bingham",
    "mixed_mode_damper_force",
    "mixed_mode_yield_force",
    "annulus_bingham_pressure_drop",
    "annulus_bingham_flow_rate",
]

_DUCT = dict(L="m", d="m", h="m")

slit_pressure_drop = unit_aware("Pa", Q="m^3/s", eta="Pa*s", **_DUCT)(_newtonian.slit_pressure_drop)
annulus_pressure_drop = unit_aware("Pa", Q="m^3/s", eta="Pa*s", **_DUCT)(_newtonian.annulus_pressure_drop)
thin_gap_error = unit_aware("", h_over_d="")(_newtonian.thin_gap_error)

yield_pressure_drop = unit_aware("Pa", tau_y="Pa", L="m", h="m")(_bingham.yield_pressure_drop)
bingham_number = unit_aware("", Q="m^3/s", tau_y="Pa", eta="Pa*s", d="m", h="m")(_bingham.bingham_number)
bingham_flow_rate = unit_aware("m^3/s", dp="Pa", tau_y="Pa", eta="Pa*s", **_DUCT)(_bingham.bingham_flow_rate)
bingham_pressure_drop = unit_aware("Pa", Q="m^3/s", tau_y="Pa", eta="Pa*s", **_DUCT)(_bingham.bingham_pressure_drop)
bingham_plug_fraction = unit_aware("", Q="m^3/s", tau_y="Pa", eta="Pa*s", **_DUCT)(_bingham.bingham_plug_fraction)

makris_stress = unit_aware("Pa", t="s", gamma="", tau_y="Pa", eta="Pa*s", G="Pa", tau0="Pa")(_makris.makris_stress)
maxwell_stress = unit_aware("Pa", t="s", gamma="", eta="Pa*s", G="Pa", tau0="Pa")(_makris.maxwell_stress)

couette_poiseuille_bingham = unit_aware(
    dict(
        pressure_gradient="Pa/m",
        wall_stress_moving="Pa",
        wall_stress_fixed="Pa",
        plug_y1="m",
        plug_y2="m",
        plug_fraction="",
    ),
    U="m/s",
    q="m^2/s",
    tau_y="Pa",
    eta="Pa*s",
    h="m",
)(_mixed.couette_poiseuille_bingham)
mixed_mode_damper_force = unit_aware(
    dict(force="N", pressure_drop="Pa", pressure_force="N", shear_force="N", flow_rate="m^3/s", plug_fraction=""),
    v="m/s",
    tau_y="Pa",
    eta="Pa*s",
    L="m",
    Dp="m",
    dr="m",
    h="m",
)(_mixed.mixed_mode_damper_force)
mixed_mode_yield_force = unit_aware("N", tau_y="Pa", L="m", Dp="m", dr="m", h="m")(_mixed.mixed_mode_yield_force)

annulus_bingham_pressure_drop = unit_aware("Pa", Q="m^3/s", tau_y="Pa", eta="Pa*s", **_DUCT)(
    _annulus_bingham.annulus_bingham_pressure_drop
)
annulus_bingham_flow_rate = unit_aware("m^3/s", dp="Pa", tau_y="Pa", eta="Pa*s", **_DUCT)(
    _annulus_bingham.annulus_bingham_flow_rate
)
