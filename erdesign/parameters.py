"""A parameter of a model or an effect: name, SI unit, default, physical bounds and how it is fitted.

Shared by the phenomenological models (:mod:`erdesign.models`) and the physics damper's effects
(:mod:`erdesign.effects`), which both hand their parameters to the fitting (:mod:`erdesign.identification.fit`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .errors import ErdesignError
from .units import Q_, format_quantity

__all__ = ["Parameter", "ParameterError"]


class ParameterError(ErdesignError):
    """Unknown parameter name, or a value outside its physical bounds."""


@dataclass(frozen=True)
class Parameter:
    """One parameter of a model.

    Attributes
    ----------
    name : str
        snake_case name, unique within the model (``c0``, ``f_c``, ``viscosity_factor``).
    unit : str
        SI unit of the value (``"N*s/m"``; ``""`` for dimensionless).
    default : float
        Typical value (SI), also the default starting guess.
    lower, upper : float
        Physical bounds (SI); ``-inf`` / ``inf`` allowed.
    description : str
        What it is, in a few words.
    log_scale : bool
        Positive and spanning decades: fitted in log space (needs ``lower > 0``).
    fitted : bool
        Identified by default (False: chosen a priori, like the shape-function widths of Kamath and Wereley, or
        a redundant scale of the Bouc-Wen family; :func:`erdesign.identification.fit.fit` holds it at its start value
        unless it is named in ``free``).
    """

    name: str
    unit: str
    default: float
    lower: float = -math.inf
    upper: float = math.inf
    description: str = ""
    log_scale: bool = False
    fitted: bool = True

    def __post_init__(self) -> None:
        if not self.lower <= self.default <= self.upper:
            raise ParameterError(f"{self.name}: default {self.default} outside its bounds [{self.lower}, {self.upper}]")
        if self.log_scale and not self.lower > 0:
            raise ParameterError(f"{self.name}: a log-scale parameter needs a positive lower bound")

    def quantity(self, value: float):
        """``value`` (SI) as a pint quantity in this parameter's unit."""
        return Q_(value, self.unit)

    def format(self, value: float, digits: int = 4) -> str:
        """``value`` with its unit, as text (``"5000 N·s/m"``)."""
        return format_quantity(self.quantity(value), None, digits).strip()
