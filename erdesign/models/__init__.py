"""Damper models behind one interface (:class:`Model`): the phenomenological models of the literature and the
physics damper with effects (registry name ``physics``).

* :mod:`~erdesign.models.base` - :class:`Model` and :class:`Parameter`, the interface every model implements;
* one module per model family (``bingham.py``, ``bouc_wen.py``, ``kamath_wereley.py``, ...);
* :mod:`~erdesign.models.registry` - name -> model, with source and equation numbers (``erdesign models``).

Fitting is :func:`erdesign.identification.fit.fit`; identification workflows are in
:mod:`erdesign.identification.identify`.  Every model's equation and source: docs/models.md.
"""

from .base import ControlAffineModel, Model, ModelInputError, Parameter, ParameterError
from .registry import INVERTIBLE, MODELS, UnknownModelError, describe_models, get_model, model_names

__all__ = [
    "ControlAffineModel",
    "Model",
    "ModelInputError",
    "Parameter",
    "ParameterError",
    "INVERTIBLE",
    "MODELS",
    "UnknownModelError",
    "describe_models",
    "get_model",
    "model_names",
]
