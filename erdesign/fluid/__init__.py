"""The fluid: :class:`Fluid` (plastic viscosity, yield stress as a function of the control, density) and the laws
of the yield stress against the control (:mod:`erdesign.fluid.field_laws`).

* :mod:`~erdesign.fluid.fluid` - :class:`Fluid`, the kinds of control and their SI units (:data:`CONTROL_UNITS`);
* :mod:`~erdesign.fluid.field_laws` - power, saturating and tabulated laws, power-law fits, material-file tables.

The materials database (:mod:`erdesign.materials`) stays a top-level package: it holds the steels of the magnetic
circuit as well as the fluids.
"""

from .fluid import CONTROL_UNITS, FLUID_RANGES, IMPOSSIBLE_CONTROL_FACTOR, PLAUSIBLE_CONTROL, Fluid, control_kind

__all__ = ["Fluid", "CONTROL_UNITS", "control_kind", "PLAUSIBLE_CONTROL", "FLUID_RANGES", "IMPOSSIBLE_CONTROL_FACTOR"]
