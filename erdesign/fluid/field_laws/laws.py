r"""The field-law objects: a law's parameters with its control unit, and the registry of laws by name."""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..._util import scalar_or_array
from ...errors import ErdesignError, UnitError
from ...units import Q_
from .fitting import PowerLawFit, fit_power_law
from .kernels import CONTROL_SI, power_law_yield_stress, saturating_yield_stress

__all__ = ["FieldLaw", "PowerLaw", "SaturatingLaw", "TabulatedLaw", "FIELD_LAWS"]


@dataclass(frozen=True)
class FieldLaw:
    """Base of the field laws: a yield stress [Pa] as a function of the control, in SI units.

    Subclasses set :attr:`law` (the name used in material files), implement :meth:`yield_stress`,
    :attr:`equation` (LaTeX) and :meth:`describe`.
    """

    control_unit: str
    """SI unit of the control: ``"V/m"``, ``"A/m"``, ``"T"``, ``"A"`` or ``"V"``."""

    law: ClassVar[str] = ""
    equation: ClassVar[str] = ""
    reference: ClassVar[str] = ""

    def __post_init__(self) -> None:
        if self.control_unit not in CONTROL_SI:
            raise UnitError(
                f"field law: unknown control unit {self.control_unit!r}; expected one of {', '.join(CONTROL_SI)}"
            )

    def yield_stress(self, E):  # pragma: no cover - abstract
        """Yield stress [Pa] at the control ``E`` (SI magnitude, float or array)."""
        raise NotImplementedError

    def describe(self, field_unit: str | None = None) -> str:  # pragma: no cover - abstract
        """One line with the law and its parameters, the control shown in ``field_unit``."""
        raise NotImplementedError

    def ratio(self, E, reference_field: float):
        """tau_y(E) / tau_y(E_ref), [-]: how the yield stress scales with the control (the plastic viscosity of a
        :class:`~erdesign.fluid.Fluid` rises with it)."""
        at_ref = float(self.yield_stress(reference_field))
        return np.asarray(self.yield_stress(E), dtype=float) / at_ref

    def fit(
        self, field_max: float, field_min: float = 0.0, samples: int = 25, *, reference_field: float | None = None
    ) -> PowerLawFit:
        """Power-law summary of this law over a control range (SI), with its error.

        The law is sampled at ``samples`` controls spaced evenly over ``(field_min, field_max]`` (the zero field is
        left out; a curve read from a datasheet graph weighs the range the same way) and fitted with
        :func:`fit_power_law`, anchored at ``reference_field`` (default ``field_max``) so that the power law is
        exact there.
        """
        if not (field_max > field_min >= 0):
            raise ErdesignError(f"fit range: need 0 <= field_min < field_max, got {field_min!r}, {field_max!r}")
        start = field_min if field_min > 0 else field_max / samples
        E = np.linspace(start, field_max, samples)
        E_ref = field_max if reference_field is None else float(reference_field)
        return fit_power_law(E, self.yield_stress(E), anchor=(E_ref, float(self.yield_stress(E_ref))))

    def _show(self, value: float, field_unit: str | None) -> str:
        q = Q_(value, self.control_unit).to(field_unit or self.control_unit)
        return f"{q.magnitude:.4g} {q.units:~P}"


@dataclass(frozen=True)
class PowerLaw(FieldLaw):
    """:math:`\\tau_y = \\tau_\\text{ref}(|E|/E_\\text{ref})^n` (:func:`power_law_yield_stress`), SI.

    >>> law = PowerLaw("V/m", yield_stress_ref=1800.0, reference_field=3e6, exponent=2.0)
    >>> law.yield_stress(1.5e6), law.describe("kV/mm")
    (450.0, 'power law: tau_y = 1800 Pa (|E| / 3 kV/mm)^2')
    """

    yield_stress_ref: float = 0.0
    """tau_ref, [Pa]."""
    reference_field: float = 1.0
    """E_ref, SI unit of the control."""
    exponent: float = 1.0
    """n, [-]."""

    law: ClassVar[str] = "power"
    equation: ClassVar[str] = r"\tau_y = \tau_\text{ref}\left(|E|/E_\text{ref}\right)^n"
    reference: ClassVar[str] = "Butz and von Stryk (2002), section 2: tau_y ~ E^n, n = 1.2 to 2.5"

    def __post_init__(self) -> None:
        super().__post_init__()
        if not (self.yield_stress_ref >= 0 and self.reference_field > 0 and 0 < self.exponent <= 5):
            raise ErdesignError(
                f"power law: need tau_ref >= 0, E_ref > 0 and 0 < n <= 5, got {self.yield_stress_ref!r} Pa, "
                f"{self.reference_field!r} {self.control_unit}, {self.exponent!r}"
            )

    def yield_stress(self, E):
        return power_law_yield_stress(E, self.yield_stress_ref, self.reference_field, self.exponent)

    def ratio(self, E, reference_field: float):
        # (|E|/E_ref)^n at the law's own reference: defined for tau_ref = 0 too
        if reference_field == self.reference_field:
            return (np.abs(E) / self.reference_field) ** self.exponent
        return super().ratio(E, reference_field)

    def describe(self, field_unit: str | None = None) -> str:
        return (
            f"power law: tau_y = {self.yield_stress_ref:.4g} Pa (|E| / "
            f"{self._show(self.reference_field, field_unit)})^{self.exponent:.4g}"
        )


@dataclass(frozen=True)
class SaturatingLaw(FieldLaw):
    """:math:`\\tau_y = \\tau_\\text{sat}\\tanh(|E|/E_\\text{sat})` (:func:`saturating_yield_stress`), SI.

    >>> law = SaturatingLaw("A/m", saturation_stress=47.86e3, saturation_field=158.0e3)
    >>> round(law.yield_stress(1e9)), law.describe("kA/m")
    (47860, 'saturating law: tau_y = 4.786e+04 Pa tanh(|E| / 158 kA/m)')
    """

    saturation_stress: float = 0.0
    """tau_sat, [Pa]."""
    saturation_field: float = 1.0
    """E_sat, SI unit of the control."""

    law: ClassVar[str] = "saturating"
    equation: ClassVar[str] = r"\tau_y = \tau_\text{sat}\tanh\left(|E|/E_\text{sat}\right)"
    reference: ClassVar[str] = (
        "Carlson, MR fluids and devices in the real world, Int. J. Mod. Phys. B 19 (2005) "
        "1463-1470 (tanh law of LORD MR fluids)"
    )

    def __post_init__(self) -> None:
        super().__post_init__()
        if not (self.saturation_stress >= 0 and self.saturation_field > 0):
            raise ErdesignError(
                f"saturating law: need tau_sat >= 0 and E_sat > 0, got {self.saturation_stress!r} "
                f"Pa and {self.saturation_field!r} {self.control_unit}"
            )

    def yield_stress(self, E):
        return saturating_yield_stress(E, self.saturation_stress, self.saturation_field)

    def describe(self, field_unit: str | None = None) -> str:
        return (
            f"saturating law: tau_y = {self.saturation_stress:.4g} Pa tanh(|E| / "
            f"{self._show(self.saturation_field, field_unit)})"
        )


@dataclass(frozen=True)
class TabulatedLaw(FieldLaw):
    """A tabulated yield-stress curve, interpolated by a monotone cubic (PCHIP); the last value held beyond it.

    ``fields`` start at zero and increase strictly; ``stresses`` [Pa] do not decrease.

    >>> law = TabulatedLaw("A/m", fields=(0.0, 50e3, 100e3), stresses=(0.0, 15e3, 25e3))
    >>> law.yield_stress(np.array([50e3, 1e6])).tolist()     # a table point; held beyond the table
    [15000.0, 25000.0]
    """

    fields: tuple[float, ...] = ()
    """Controls of the points, SI unit of the control, first 0, strictly increasing."""
    stresses: tuple[float, ...] = ()
    """Yield stress at each point, [Pa], non-decreasing."""

    law: ClassVar[str] = "table"
    equation: ClassVar[str] = r"\tau_y = \mathrm{PCHIP}\{(E_i, \tau_i)\}(|E|)"
    reference: ClassVar[str] = (
        "Fritsch and Carlson, Monotone piecewise cubic interpolation, SIAM J. Numer. Anal. "
        "17 (1980) 238-246 (scipy.interpolate.PchipInterpolator)"
    )

    def __post_init__(self) -> None:
        super().__post_init__()
        E = np.asarray(self.fields, dtype=float)
        tau = np.asarray(self.stresses, dtype=float)
        problems = [
            (
                E.ndim == 1 and E.size >= 2 and E.shape == tau.shape,
                "needs at least two points, as many stresses as fields",
            ),
            (np.all(np.isfinite(E)) and np.all(np.isfinite(tau)), "values must be finite"),
            (E.size == 0 or E[0] == 0.0, "the first point must be at zero field (the off-state yield stress, often 0)"),
            (np.all(np.diff(E) > 0), "fields must increase strictly"),
            (np.all(tau >= 0) and np.all(np.diff(tau) >= 0), "yield stresses must be >= 0 and must not decrease"),
        ]
        for ok, why in problems:
            if not ok:
                raise ErdesignError(f"tabulated law: {why}")

    @functools.cached_property
    def _interpolant(self) -> "PchipInterpolator":  # noqa: F821
        from scipy.interpolate import PchipInterpolator  # imported here: costs ~1 s at start-up

        return PchipInterpolator(np.asarray(self.fields), np.asarray(self.stresses), extrapolate=False)

    def yield_stress(self, E):
        E = np.minimum(np.abs(np.asarray(E, dtype=float)), self.fields[-1])
        return scalar_or_array(self._interpolant(E))

    def describe(self, field_unit: str | None = None) -> str:
        return (
            f"tabulated curve, {len(self.fields)} points up to {self._show(self.fields[-1], field_unit)} "
            f"({self.stresses[-1]:.4g} Pa), monotone cubic interpolation"
        )


FIELD_LAWS: dict[str, type[FieldLaw]] = {cls.law: cls for cls in (PowerLaw, SaturatingLaw, TabulatedLaw)}
"""The field laws by the name a material file's ``[yield_curve] law`` uses (``"carlson"`` builds a saturating law)."""
