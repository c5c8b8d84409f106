r"""Yield stress as a function of the control (field laws), and power-law fits of measured curves.

Three laws, each a plain SI kernel plus a small frozen object that carries its parameters and its control unit:

``power``
    :math:`\tau_y = \tau_\text{ref}(|E|/E_\text{ref})^n`, the law of the damper file (Butz and von Stryk 2002,
    section 2, gives
    n from 1.2 to 2.5 for ER fluids).  It does not saturate.
``saturating``
    :math:`\tau_y = \tau_\text{sat}\tanh(|E|/E_\text{sat})`: linear at small field, saturating at
    :math:`\tau_\text{sat}` as the particles saturate magnetically, the shape of MR fluids.  Carlson's published
    law for LORD hydrocarbon MR fluids (:func:`carlson_yield_stress`) is of this form.
``table``
    A tabulated curve (a datasheet graph read point by point) interpolated by the monotone piecewise-cubic Hermite
    interpolant of Fritsch and Carlson (:class:`scipy.interpolate.PchipInterpolator`), which never overshoots
    between points, so a monotone table gives a monotone law.  Above the last point the last value is held.

:func:`fit_power_law` fits the power law to a curve (a table or a law sampled on a field range) and reports the
fit range with the error of the fit, so that the power-law summary a material file gives for a saturating fluid is
never used without knowing where it holds.  :func:`field_law_from_dict` builds a law from the ``[yield_curve]``
table of a material file (docs/materials.md).

All laws are even in the control (the yield stress depends on :math:`|E|`) and take SI magnitudes: V/m, A/m, T,
A or V, as the fluid's reference field (:data:`erdesign.fluid.CONTROL_UNITS`).
"""

from __future__ import annotations

from .fitting import PowerLawFit, fit_power_law
from .kernels import (
    CARLSON_FIELD_COEFFICIENT,
    CARLSON_STRESS_COEFFICIENT,
    CARLSON_VOLUME_EXPONENT,
    carlson_yield_stress,
    control_unit_of,
    power_law_yield_stress,
    saturating_yield_stress,
)
from .laws import FIELD_LAWS, FieldLaw, PowerLaw, SaturatingLaw, TabulatedLaw
from .tables import field_law_from_dict

__all__ = [
    "power_law_yield_stress",
    "saturating_yield_stress",
    "carlson_yield_stress",
    "CARLSON_STRESS_COEFFICIENT",
    "CARLSON_VOLUME_EXPONENT",
    "CARLSON_FIELD_COEFFICIENT",
    "fit_power_law",
    "PowerLawFit",
    "FieldLaw",
    "PowerLaw",
    "SaturatingLaw",
    "TabulatedLaw",
    "FIELD_LAWS",
    "field_law_from_dict",
    "control_unit_of",
]
