"""erdesign: design, simulation and diagnosis of electro- and magnetorheological dampers with annular ducts.

Three layers (docs/architecture.md):

* kernels - :mod:`erdesign.flow` (steady gap flow) and :mod:`erdesign.constitutive` (stress in time): plain SI
  floats and numpy arrays, vectorised;
* objects - :class:`Fluid`, :class:`Geometry`, :class:`Damper`: built from pint quantities or strings, checked;
* workflows - sizing (:meth:`Damper.size`), design synthesis (:mod:`erdesign.design`), identification
  (:func:`fit`, :mod:`erdesign.models`, :mod:`erdesign.identification`), diagnosis (:mod:`erdesign.diagnosis`),
  reports (:mod:`erdesign.report`),
  the command line (``erdesign``) and the app (``erdesign app``).

The functions in this namespace take pint quantities or strings and return quantities:

>>> import erdesign
>>> dp = erdesign.bingham_pressure_drop('1 mL/s', '1.8 kPa', '13 Pa*s', '54.6 mm', '14.3 mm', '0.8 mm')
>>> print(f"{dp.to('kPa'):.1f~P}")
724.7 kPa
"""

import importlib as _importlib
import sys as _sys
import types as _types

__version__ = "0.1.0"

# Public name -> module that defines it.  Nothing is imported until a name is first used (PEP 562), so that
# ``import erdesign`` and ``erdesign --help`` do not pay for scipy, pint's registry, numba and plotly.
_LAZY = {
    **dict.fromkeys(
        (
            "annulus_bingham_flow_rate",
            "annulus_bingham_pressure_drop",
            "annulus_pressure_drop",
            "bingham_flow_rate",
            "bingham_number",
            "bingham_plug_fraction",
            "bingham_pressure_drop",
            "couette_poiseuille_bingham",
            "makris_stress",
            "maxwell_stress",
            "mixed_mode_damper_force",
            "mixed_mode_yield_force",
            "slit_pressure_drop",
            "thin_gap_error",
            "yield_pressure_drop",
        ),
        "api",
    ),
    **dict.fromkeys(("Damper", "QuasiSteadyState", "SineResponse", "SizingResult"), "damper"),
    **dict.fromkeys(("load_damper", "load_example"), "damper.files"),
    "save_damper": "damper.writer",
    **dict.fromkeys(("calibrate", "improve"), "diagnosis.diagnose"),
    **dict.fromkeys(("FitResult", "fit"), "identification.fit"),
    **dict.fromkeys(("cross_validation", "identify_joint"), "identification.identify"),
    "inverse_control": "identification.inverse",
    **dict.fromkeys(("Measurement", "read_measurement", "write_measurement"), "data.measurement"),
    **dict.fromkeys(("get_model", "model_names"), "models.registry"),
    "PhysicsDamper": "effects.chain",
    "run_rig": "simulation.rig",
    "programme": "simulation.programmes",
    "characterize": "characterization.method",
    **dict.fromkeys(("DamperFileError", "ErdesignError", "ErdesignWarning", "UnitError", "ValidityWarning"), "errors"),
    "Fluid": "fluid",
    "Geometry": "geometry",
    **dict.fromkeys(("energy_per_cycle", "equivalent_damping", "esr"), "data.metrics"),
    **dict.fromkeys(("Q_", "ureg"), "units"),
}

# Subpackages and workflow modules of the curated namespace: name -> module.  Functions named like a module
# (design.design, diagnose.diagnose, identify.identify) are deliberately not lifted here, so that the module stays
# reachable by its name.  Four names keep the flat layout's module names (docs/architecture.md, moved modules):
# ``erdesign.diagnose`` is :mod:`erdesign.diagnosis.diagnose` and so on, without the deprecation warning that
# ``import erdesign.diagnose`` gives.
_SUBMODULES = {
    "flow": "flow",
    "constitutive": "constitutive",
    "design": "design",
    "diagnose": "diagnosis.diagnose",
    "effects": "effects",
    "field_laws": "fluid.field_laws",
    "identify": "identification.identify",
    "models": "models",
    "plots": "report.plots",
    "report": "report",
}

__all__ = [
    "Damper",
    "QuasiSteadyState",
    "SineResponse",
    "SizingResult",
    "Fluid",
    "Geometry",
    "load_damper",
    "load_example",
    "save_damper",
    "Measurement",
    "read_measurement",
    "write_measurement",
    "fit",
    "FitResult",
    "get_model",
    "model_names",
    "identify_joint",
    "cross_validation",
    "inverse_control",
    "PhysicsDamper",
    "calibrate",
    "improve",
    "run_rig",
    "programme",
    "characterize",
    "annulus_pressure_drop",
    "bingham_flow_rate",
    "bingham_number",
    "bingham_plug_fraction",
    "bingham_pressure_drop",
    "slit_pressure_drop",
    "thin_gap_error",
    "yield_pressure_drop",
    "makris_stress",
    "maxwell_stress",
    "couette_poiseuille_bingham",
    "mixed_mode_damper_force",
    "mixed_mode_yield_force",
    "annulus_bingham_pressure_drop",
    "annulus_bingham_flow_rate",
    "energy_per_cycle",
    "equivalent_damping",
    "esr",
    "ErdesignError",
    "UnitError",
    "DamperFileError",
    "ErdesignWarning",
    "ValidityWarning",
    "Q_",
    "ureg",
    *_SUBMODULES,
]


def __getattr__(name):
    """Import a public name, or any submodule (``erdesign.materials``), on first use."""
    if name in _LAZY:
        value = getattr(_importlib.import_module(f".{_LAZY[name]}", __name__), name)
    elif name in _SUBMODULES:
        value = _importlib.import_module(f".{_SUBMODULES[name]}", __name__)
    elif not name.startswith("__"):
        try:
            value = _importlib.import_module(f".{name}", __name__)
        except ModuleNotFoundError as exc:
            if exc.name != f"{__name__}.{name}":
                raise
            raise AttributeError(f"module {__name__!r} has no attribute {name!r}") from None
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))


class _Package(_types.ModuleType):
    """The package's module type: ``erdesign.fit`` is the function :func:`erdesign.identification.fit.fit`, as it
    was when the package imported everything eagerly, even after the deprecated module ``erdesign.fit`` has been
    imported (the import system then sets the parent's attribute to the module, which this property ignores)."""

    @property
    def fit(self):
        value = self.__dict__.get("_fit_override")
        return value if value is not None else _importlib.import_module(".identification.fit", __name__).fit

    @fit.setter
    def fit(self, value):
        if not isinstance(value, _types.ModuleType):  # a user's monkeypatch is honoured; the submodule is not
            self.__dict__["_fit_override"] = value

    @fit.deleter
    def fit(self):
        self.__dict__.pop("_fit_override", None)


_sys.modules[__name__].__class__ = _Package

# The flat layout's module paths (``erdesign.fit`` ...) stay importable, with a deprecation warning.
from . import _deprecated  # noqa: E402,F401
