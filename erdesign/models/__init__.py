"""Damper models behind one interface (:class:`Model`): phenomenological models of the literature and, through the
diagnosis work, the physics damper with effects.  The registry of named models lives in
:mod:`erdesign.models.registry` once the model library exists."""

from .base import Model, Parameter, ParameterError

__all__ = ["Model", "Parameter", "ParameterError"]
