"""Steady flow through the gap of an annular duct: SI kernels (plain floats or numpy arrays, vectorised).

One module per flow situation:

* :mod:`~erdesign.flow.newtonian` - Hagen-Poiseuille flow, thin-gap (Makris eq 4) and exact annulus.
* :mod:`~erdesign.flow.bingham` - Bingham plastic through a stationary gap (valve mode, Makris eqs 5-7, corrected).
* :mod:`~erdesign.flow.mixed_mode` - Couette-Poiseuille Bingham flow with a moving wall (moving-electrode damper).
* :mod:`~erdesign.flow.annulus_bingham` - exact Bingham flow through a concentric annulus (Fredrickson and Bird).
* :mod:`~erdesign.flow.herschel_bulkley` - Herschel-Bulkley (shear-thinning) fluid through a thin stationary gap.
* :mod:`~erdesign.flow.areas` - the piston area of an annular head.
* :mod:`~erdesign.flow.numerical` - independent regularised (Papanastasiou) finite-difference solver, slit and
  annulus, with a moving wall: the check on all the closed forms.

The unit-aware versions of these functions (pint quantities in and out) are in the top-level ``erdesign``
namespace.
"""

from .annulus_bingham import (
    AnnulusBinghamFlow,
    annulus_bingham_flow,
    annulus_bingham_flow_rate,
    annulus_bingham_plug_fraction,
    annulus_bingham_pressure_drop,
    annulus_bingham_shape,
    annulus_bingham_velocity,
    thin_gap_error_bingham,
)
from .areas import piston_area
from .bingham import (
    BinghamSlitFlow,
    bingham_flow_rate,
    bingham_number,
    bingham_plug_fraction,
    bingham_pressure_drop,
    bingham_slit_flow,
    yield_pressure_drop,
)
from .herschel_bulkley import herschel_bulkley_pressure_drop, herschel_bulkley_slit_flow_rate
from .mixed_mode import (
    CouettePoiseuilleBingham,
    GapFlowRegime,
    MixedModeDamperForce,
    couette_poiseuille_bingham,
    couette_poiseuille_bingham_velocity,
    mixed_mode_damper_force,
    mixed_mode_yield_force,
)
from .numerical import ConvergenceError, GapFlow, gap_grid, solve_gap_flow
from .newtonian import (
    annulus_conductance_ratio,
    annulus_flow_rate,
    annulus_pressure_drop,
    slit_flow_rate,
    slit_pressure_drop,
    thin_gap_error,
)

__all__ = [
    "herschel_bulkley_pressure_drop",
    "herschel_bulkley_slit_flow_rate",
    "piston_area",
    "AnnulusBinghamFlow",
    "annulus_bingham_flow",
    "annulus_bingham_flow_rate",
    "annulus_bingham_plug_fraction",
    "annulus_bingham_pressure_drop",
    "annulus_bingham_shape",
    "annulus_bingham_velocity",
    "thin_gap_error_bingham",
    "ConvergenceError",
    "GapFlow",
    "gap_grid",
    "solve_gap_flow",
    "CouettePoiseuilleBingham",
    "GapFlowRegime",
    "MixedModeDamperForce",
    "couette_poiseuille_bingham",
    "couette_poiseuille_bingham_velocity",
    "mixed_mode_damper_force",
    "mixed_mode_yield_force",
    "BinghamSlitFlow",
    "bingham_flow_rate",
    "bingham_number",
    "bingham_plug_fraction",
    "bingham_pressure_drop",
    "bingham_slit_flow",
    "yield_pressure_drop",
    "annulus_conductance_ratio",
    "annulus_flow_rate",
    "annulus_pressure_drop",
    "slit_flow_rate",
    "slit_pressure_drop",
    "thin_gap_error",
]
