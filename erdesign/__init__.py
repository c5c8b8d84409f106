"""erdesign: design, simulation and diagnosis of electro- and magnetorheological dampers with annular ducts.

Three layers (docs/architecture.md):

* kernels - :mod:`erdesign.flow` (steady gap flow) and :mod:`erdesign.constitutive` (stress in time): plain SI
  floats and numpy arrays, vectorised;
* objects - :class:`Fluid`, :class:`Geometry`, :class:`Damper`: built from pint quantities or strings, checked;
* workflows - sizing (:meth:`Damper.size`), design synthesis (:mod:`erdesign.design`), identification
  (:func:`fit`, :mod:`erdesign.models`), diagnosis (:mod:`erdesign.diagnose`), reports (:mod:`erdesign.report`),
  the command line (``erdesign``) and the app (``erdesign app``).

The functions in this namespace take pint quantities or strings and return quantities:

>>> import erdesign
>>> dp = erdesign.bingham_pressure_drop('1 mL/s', '1.8 kPa', '13 Pa*s', '54.6 mm', '14.3 mm', '0.8 mm')
>>> print(f"{dp.to('kPa'):.1f~P}")
724.7 kPa
"""

# Subpackages and workflow modules; functions named like a module (design.design, diagnose.diagnose,
# identify.identify) are deliberately not lifted here, so that the module stays reachable by its name.
from . import constitutive, design, diagnose, effects, field_laws, flow, identify, models, plots, report
from .api import (
    annulus_bingham_flow_rate,
    annulus_bingham_pressure_drop,
    annulus_pressure_drop,
    bingham_flow_rate,
    bingham_number,
    bingham_plug_fraction,
    bingham_pressure_drop,
    couette_poiseuille_bingham,
    makris_stress,
    maxwell_stress,
    mixed_mode_damper_force,
    mixed_mode_yield_force,
    slit_pressure_drop,
    thin_gap_error,
    yield_pressure_drop,
)
from .damper import Damper, QuasiSteadyState, SineResponse, SizingResult
from .damper_file import load_damper, load_example
from .diagnose import calibrate, improve
from .fit import FitResult, fit
from .identify import cross_validation, identify_joint
from .inverse import inverse_control
from .measurement import Measurement, read_measurement, write_measurement
from .models.registry import get_model, model_names
from .physics import PhysicsDamper
from .rig import run_rig
from .errors import DamperFileError, ErdesignError, ErdesignWarning, UnitError, ValidityWarning
from .fluid import Fluid
from .geometry import Geometry
from .metrics import energy_per_cycle, equivalent_damping, esr
from .units import Q_, ureg

__version__ = "0.1.0"

__all__ = [
    "Damper", "QuasiSteadyState", "SineResponse", "SizingResult", "Fluid", "Geometry",
    "load_damper", "load_example",
    "Measurement", "read_measurement", "write_measurement",
    "fit", "FitResult", "get_model", "model_names", "identify_joint", "cross_validation",
    "inverse_control", "PhysicsDamper", "calibrate", "improve", "run_rig",
    "annulus_pressure_drop", "bingham_flow_rate", "bingham_number", "bingham_plug_fraction",
    "bingham_pressure_drop", "slit_pressure_drop", "thin_gap_error", "yield_pressure_drop",
    "makris_stress", "maxwell_stress",
    "couette_poiseuille_bingham", "mixed_mode_damper_force", "mixed_mode_yield_force",
    "annulus_bingham_pressure_drop", "annulus_bingham_flow_rate",
    "energy_per_cycle", "equivalent_damping", "esr",
    "ErdesignError", "UnitError", "DamperFileError", "ErdesignWarning", "ValidityWarning",
    "Q_", "ureg", "flow", "constitutive", "design", "diagnose", "effects", "field_laws", "identify", "models", "plots",
    "report",
]
