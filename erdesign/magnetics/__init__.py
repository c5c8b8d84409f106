"""Magnetic circuit of MR dampers: from coil current to gap flux density, yield stress and coil figures.

Three layers (docs/magnetics.md):

* :mod:`~erdesign.magnetics.bh` - B-H curves of steels and MR fluids (SI);
* :mod:`~erdesign.magnetics.circuit` and :mod:`~erdesign.magnetics.coil` - the nonlinear reluctance network of the
  piston head and the copper of its coil (SI kernels, vectorised over currents);
* :mod:`~erdesign.magnetics.law` - :class:`CoilLaw`, the fluid's yield stress against coil current through the
  circuit, the field law of every damper file with a ``[coil]``;
* :mod:`~erdesign.magnetics.api` - built from a damper file with a ``[coil]``, evaluated at currents given with
  units (:meth:`MagneticCircuit.at` returns pint quantities);

and the independent check :mod:`~erdesign.magnetics.fem` (axisymmetric nonlinear finite elements, scikit-fem).
"""

from .api import CircuitReport, build_circuit, circuit_from_damper_dict, load_magnetic_circuit
from .bh import MU0, BHCurve, carlson_curve, carlson_flux_density
from .circuit import PARTS, MagneticCircuit, PistonHead, piston_head
from .coil import COIL_KEYS, Coil, coil_from_table, coil_resistance, current_rise_time
from .law import CoilLaw, coil_law

__all__ = [
    "CircuitReport",
    "build_circuit",
    "circuit_from_damper_dict",
    "CoilLaw",
    "coil_law",
    "current_rise_time",
    "load_magnetic_circuit",
    "MU0",
    "BHCurve",
    "carlson_curve",
    "carlson_flux_density",
    "PARTS",
    "MagneticCircuit",
    "PistonHead",
    "piston_head",
    "COIL_KEYS",
    "Coil",
    "coil_from_table",
    "coil_resistance",
]
