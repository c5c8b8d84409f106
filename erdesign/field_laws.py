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

import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar, NamedTuple

import numpy as np

from ._util import scalar_or_array
from .errors import ErdesignError, UnitError
from .units import Q_, to_si, ureg

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

#: Constants of Carlson's yield-stress law for LORD MR fluids (:func:`carlson_yield_stress`): stress coefficient
#: [Pa], exponent of the iron volume fraction [-], field coefficient [m/A].
CARLSON_STRESS_COEFFICIENT = 271700.0
CARLSON_VOLUME_EXPONENT = 1.5239
CARLSON_FIELD_COEFFICIENT = 6.33e-6

# SI unit of each kind of control (the same table as erdesign.fluid.CONTROL_UNITS, which imports this module).
_CONTROL_SI = ("V/m", "A/m", "T", "A", "V")


def control_unit_of(value: Any, name: str) -> str:
    """SI unit (``"V/m"``, ``"A/m"``, ``"T"``, ``"A"`` or ``"V"``) of a control given as a quantity or string."""
    q = Q_(value) if isinstance(value, str) else value
    dim = getattr(q, "dimensionality", None)
    for unit in _CONTROL_SI:
        if dim == ureg.Unit(unit).dimensionality:
            return unit
    raise UnitError(f"{name}: expected an electric field (V/m), a magnetic field (A/m, T), a current (A) or a "
                    f"voltage (V) with its unit, got {value!r}")


# ---------------------------------------------------------------------------------------------------- kernels
def power_law_yield_stress(E, tau_ref, E_ref, n):
    r"""Yield stress of the power law of the field.

    .. math:: \tau_y = \tau_\text{ref}\left(\frac{|E|}{E_\text{ref}}\right)^n

    Parameters
    ----------
    E : float or array
        Control (field, current or voltage), SI unit of its kind (V/m, A/m, T, A or V).
    tau_ref : float or array
        Yield stress at the reference control, [Pa].
    E_ref : float or array
        Reference control, same unit as ``E``; > 0.
    n : float or array
        Exponent, [-]; > 0.

    Returns
    -------
    float or array
        Yield stress, [Pa].

    Notes
    -----
    Butz and von Stryk (2002, section 2) reports n from 1.2 to 2.5 for ER fluids; Kamath and Wereley (1997,
    section I) call the ER law nominally quadratic.  The law does not saturate: for MR fluids use it only inside the
    range it was fitted on (:func:`fit_power_law`).

    Examples
    --------
    >>> power_law_yield_stress(E=1.5e6, tau_ref=1800.0, E_ref=3e6, n=2.0)   # Makris fluid at half field
    450.0

    References
    ----------
    Butz and von Stryk (2002), section 2: tau_y ~ E^n, n = 1.2 to 2.5.
    """
    return scalar_or_array(tau_ref * (np.abs(E) / E_ref) ** n)


def saturating_yield_stress(E, tau_sat, E_sat):
    r"""Yield stress of the saturating (hyperbolic-tangent) law of the field.

    .. math:: \tau_y = \tau_\text{sat}\tanh\frac{|E|}{E_\text{sat}}

    Parameters
    ----------
    E : float or array
        Control, SI unit of its kind (A/m for a magnetic field).
    tau_sat : float or array
        Saturation yield stress, [Pa].
    E_sat : float or array
        Saturation scale of the control, same unit as ``E``: the slope at zero field is ``tau_sat / E_sat``.

    Returns
    -------
    float or array
        Yield stress, [Pa].

    Notes
    -----
    Linear at small field (:math:`\tau_y \approx \tau_\text{sat}|E|/E_\text{sat}`), within 1 % of saturation
    above :math:`2.65\,E_\text{sat}`.  The linear start is the form of Carlson's law; measured MR curves start
    somewhat more steeply than linearly, so tabulate a datasheet curve (:class:`TabulatedLaw`) when the low-field
    part matters.

    Examples
    --------
    >>> round(saturating_yield_stress(E=158e3, tau_sat=47.9e3, E_sat=158e3))   # tanh(1) of saturation
    36480

    References
    ----------
    Carlson, "MR fluids and devices in the real world", Int. J. Mod. Phys. B 19 (2005) 1463-1470: the tanh form
    of the yield stress of LORD MR fluids.
    """
    return scalar_or_array(tau_sat * np.tanh(np.abs(E) / E_sat))


def carlson_yield_stress(H, phi, carrier_factor=1.0):
    r"""Carlson's yield stress of an MR fluid of iron volume fraction ``phi`` in a magnetic field ``H``.

    .. math:: \tau_y = C \cdot 271700\,\phi^{1.5239}\tanh\left(6.33\times 10^{-6}\,|H|\right)

    Parameters
    ----------
    H : float or array
        Magnetic field strength, [A/m].
    phi : float or array
        Volume fraction of iron, [-]; LORD name their hydrocarbon fluids by it (MRF-132DG: 0.32).
    carrier_factor : float or array
        C, [-]: 1.0 for hydrocarbon carriers, 1.16 for water, 0.95 for silicone oil (Carlson 2005).

    Returns
    -------
    float or array
        Yield stress, [Pa].

    Notes
    -----
    The law is quoted in several places with "kPa" beside it; with the constants above the result is in **Pa**
    (for phi = 0.32 it saturates at 47.9 kPa, the level of the MRF-132DG datasheet curve; read in kPa it would be
    48 MPa).  erdesign reads it in Pa.  It is a fit for LORD's fluids up to magnetic saturation of the iron; it is a
    saturating law (:func:`saturating_yield_stress`) with :math:`\tau_\text{sat} = C\,271700\,\phi^{1.5239}` and
    :math:`E_\text{sat} = 1/(6.33\times10^{-6})` = 158 kA/m.

    Examples
    --------
    >>> round(carlson_yield_stress(H=1e9, phi=0.32))   # saturation of an MRF-132DG-like fluid, Pa
    47862

    References
    ----------
    Carlson, "MR fluids and devices in the real world", Int. J. Mod. Phys. B 19 (2005) 1463-1470.
    """
    tau_sat = carrier_factor * CARLSON_STRESS_COEFFICIENT * np.asarray(phi, dtype=float) ** CARLSON_VOLUME_EXPONENT
    return saturating_yield_stress(H, tau_sat, 1.0 / CARLSON_FIELD_COEFFICIENT)


# ---------------------------------------------------------------------------------------------------- fitting
class PowerLawFit(NamedTuple):
    """Result of :func:`fit_power_law`: the power law and where and how well it holds (SI)."""

    yield_stress: float
    """tau_ref, fitted yield stress at the reference control, [Pa]."""
    reference_field: float
    """E_ref, the reference control (the top of the fit range unless given), SI unit of the control."""
    yield_exponent: float
    """n, [-]."""
    exponent_stderr: float
    """Standard error of n from the least-squares fit in log-log coordinates, [-] (0 for an exact fit)."""
    field_min: float
    """Smallest control of the points fitted (> 0), SI unit of the control."""
    field_max: float
    """Largest control of the points fitted, SI unit of the control."""
    max_relative_error: float
    """Largest |tau_fit / tau - 1| over the points fitted, [-]."""
    points: int
    """Number of points fitted."""


def fit_power_law(E, tau_y, *, anchor=None) -> PowerLawFit:
    r"""Fit :math:`\tau_y = \tau_\text{ref}(E/E_\text{ref})^n` to a yield-stress curve by least squares in logs.

    .. math:: \ln\tau_y = \ln\tau_\text{ref} + n \ln\frac{E}{E_\text{ref}}

    Parameters
    ----------
    E : array
        Control at each point, SI unit of its kind.  Points with ``E <= 0`` or ``tau_y <= 0`` are left out (the
        logarithm is undefined there; the power law passes through the origin anyway).
    tau_y : array
        Yield stress at each point, [Pa].
    anchor : (float, float), optional
        ``(E_ref, tau_ref)``: make the law pass exactly through this point and fit the exponent alone,
        :math:`n = \sum x y / \sum x^2` with :math:`x = \ln(E/E_\text{ref})`, :math:`y = \ln(\tau_y/\tau_\text{ref})`.
        Without it both :math:`\tau_\text{ref}` and n are fitted (:func:`scipy.stats.linregress`) and
        :math:`E_\text{ref}` is the largest control fitted.

    Returns
    -------
    PowerLawFit
        The law, the standard error of n, the fit range and the largest relative error over it.

    Notes
    -----
    Least squares on logarithms weighs relative errors equally along the curve.  For a saturating curve no power
    law fits well over a wide range: the returned ``max_relative_error`` says how badly, and ``field_min`` /
    ``field_max`` say where the summary may be used at all.

    Examples
    --------
    >>> E = np.array([1e6, 2e6, 3e6]); fit = fit_power_law(E, 1800.0 * (E / 3e6) ** 2)
    >>> round(fit.yield_exponent, 6), round(fit.yield_stress, 3), fit.reference_field
    (2.0, 1800.0, 3000000.0)

    References
    ----------
    Butz and von Stryk (2002), section 2, for the law; the fit is ordinary least squares.
    """
    E = np.asarray(E, dtype=float).ravel()
    tau = np.asarray(tau_y, dtype=float).ravel()
    if E.shape != tau.shape:
        raise ErdesignError(f"fit_power_law: E and tau_y must have the same length, got {E.size} and {tau.size}")
    keep = (E > 0) & (tau > 0) & np.isfinite(E) & np.isfinite(tau)
    E, tau = E[keep], tau[keep]
    if anchor is None:
        if E.size < 2 or np.ptp(E) == 0:
            raise ErdesignError("fit_power_law: need at least two points of positive, distinct control and stress")
        E_ref = float(E.max())
        x, y = np.log(E / E_ref), np.log(tau)
        if E.size == 2:
            n = float((y[1] - y[0]) / (x[1] - x[0]))
            log_tau_ref, stderr = float(y[0] - n * x[0]), 0.0
        else:
            from scipy.stats import linregress  # imported here: scipy.stats costs ~0.5 s at start-up

            r = linregress(x, y)
            n, log_tau_ref, stderr = float(r.slope), float(r.intercept), float(r.stderr)
        tau_ref = math.exp(log_tau_ref)
    else:
        E_ref, tau_ref = (float(a) for a in anchor)
        if not (E_ref > 0 and tau_ref > 0):
            raise ErdesignError(f"fit_power_law: anchor must be a positive (E_ref, tau_ref), got {anchor!r}")
        x, y = np.log(E / E_ref), np.log(tau / tau_ref)
        if not np.any(x != 0):
            raise ErdesignError("fit_power_law: need a point away from the anchor to fit the exponent")
        n = float(np.sum(x * y) / np.sum(x * x))
        dof = max(E.size - 1, 1)
        stderr = float(math.sqrt(np.sum((y - n * x) ** 2) / dof / np.sum(x * x)))
    fitted = tau_ref * (E / E_ref) ** n
    return PowerLawFit(
        yield_stress=float(tau_ref), reference_field=float(E_ref), yield_exponent=n, exponent_stderr=stderr,
        field_min=float(E.min()), field_max=float(E.max()),
        max_relative_error=float(np.max(np.abs(fitted / tau - 1.0))), points=int(E.size))


# ---------------------------------------------------------------------------------------------------- objects
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
        if self.control_unit not in _CONTROL_SI:
            raise UnitError(f"field law: unknown control unit {self.control_unit!r}; expected one of "
                            f"{', '.join(_CONTROL_SI)}")

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

    def fit(self, field_max: float, field_min: float = 0.0, samples: int = 25, *,
            reference_field: float | None = None) -> PowerLawFit:
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
                f"{self.reference_field!r} {self.control_unit}, {self.exponent!r}")

    def yield_stress(self, E):
        return power_law_yield_stress(E, self.yield_stress_ref, self.reference_field, self.exponent)

    def ratio(self, E, reference_field: float):
        # (|E|/E_ref)^n at the law's own reference: defined for tau_ref = 0 too
        if reference_field == self.reference_field:
            return (np.abs(E) / self.reference_field) ** self.exponent
        return super().ratio(E, reference_field)

    def describe(self, field_unit: str | None = None) -> str:
        return (f"power law: tau_y = {self.yield_stress_ref:.4g} Pa (|E| / "
                f"{self._show(self.reference_field, field_unit)})^{self.exponent:.4g}")


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
    reference: ClassVar[str] = ("Carlson, MR fluids and devices in the real world, Int. J. Mod. Phys. B 19 (2005) "
                                "1463-1470 (tanh law of LORD MR fluids)")

    def __post_init__(self) -> None:
        super().__post_init__()
        if not (self.saturation_stress >= 0 and self.saturation_field > 0):
            raise ErdesignError(f"saturating law: need tau_sat >= 0 and E_sat > 0, got {self.saturation_stress!r} "
                                f"Pa and {self.saturation_field!r} {self.control_unit}")

    def yield_stress(self, E):
        return saturating_yield_stress(E, self.saturation_stress, self.saturation_field)

    def describe(self, field_unit: str | None = None) -> str:
        return (f"saturating law: tau_y = {self.saturation_stress:.4g} Pa tanh(|E| / "
                f"{self._show(self.saturation_field, field_unit)})")


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
    reference: ClassVar[str] = ("Fritsch and Carlson, Monotone piecewise cubic interpolation, SIAM J. Numer. Anal. "
                                "17 (1980) 238-246 (scipy.interpolate.PchipInterpolator)")

    def __post_init__(self) -> None:
        super().__post_init__()
        E = np.asarray(self.fields, dtype=float)
        tau = np.asarray(self.stresses, dtype=float)
        problems = [
            (E.ndim == 1 and E.size >= 2 and E.shape == tau.shape, "needs at least two points, as many stresses as fields"),
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
        return (f"tabulated curve, {len(self.fields)} points up to {self._show(self.fields[-1], field_unit)} "
                f"({self.stresses[-1]:.4g} Pa), monotone cubic interpolation")


FIELD_LAWS: dict[str, type[FieldLaw]] = {cls.law: cls for cls in (PowerLaw, SaturatingLaw, TabulatedLaw)}
"""The field laws by the name a material file's ``[yield_curve] law`` uses (``"carlson"`` builds a saturating law)."""


# ---------------------------------------------------------------------------------------------------- from files
_LAW_KEYS = {
    "power": ("yield_stress", "reference_field", "yield_exponent"),
    "saturating": ("saturation_stress", "saturation_field"),
    "carlson": ("volume_fraction", "carrier_factor"),
    "table": ("field", "yield_stress", "field_unit", "yield_stress_unit"),
}
_COMMON_KEYS = ("law", "fit_range", "control")


def _number(value: Any, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ErdesignError(f"{name}: expected a number, got {value!r}")
    return float(value)


def _column(values: Any, unit: str | None, si_unit: str, name: str) -> np.ndarray:
    """A list of strings with units (``["0 kA/m", ...]``), or of numbers with ``unit`` given, in SI."""
    if not isinstance(values, list) or not values:
        raise ErdesignError(f"{name}: expected a list of values")
    if unit is not None:
        return np.array([to_si(Q_(_number(v, f"{name}[{i}]"), unit), si_unit, f"{name}[{i}]")
                         for i, v in enumerate(values)])
    return np.array([to_si(v, si_unit, f"{name}[{i}]") for i, v in enumerate(values)])


def field_law_from_dict(table: Mapping[str, Any], *, where: str = "yield_curve",
                        control_unit: str | None = None) -> FieldLaw:
    """A :class:`FieldLaw` from the ``[yield_curve]`` table of a material file (docs/materials.md).

    ``law`` selects the form; each form has its keys (values are strings with units, pint-parsed):

    * ``law = "power"``: ``yield_stress``, ``reference_field``, ``yield_exponent``;
    * ``law = "saturating"``: ``saturation_stress``, ``saturation_field``;
    * ``law = "carlson"``: ``volume_fraction`` and ``carrier_factor`` of :func:`carlson_yield_stress` (magnetic
      field in A/m);
    * ``law = "table"``: ``field`` and ``yield_stress`` lists, of strings with units, or of numbers with
      ``field_unit`` / ``yield_stress_unit``.

    ``fit_range`` (``["0 kA/m", "250 kA/m"]``) is the range of the material's power-law summary; it is read by
    :mod:`erdesign.materials`, not here.  Unknown keys are errors naming the key.  ``control_unit``, when given, is
    the SI unit the control must have (the material's reference field).

    >>> law = field_law_from_dict({"law": "carlson", "volume_fraction": 0.32, "carrier_factor": 1.0})
    >>> type(law).__name__, round(law.saturation_stress), round(law.saturation_field)
    ('SaturatingLaw', 47862, 157978)
    """
    if not isinstance(table, Mapping):
        raise ErdesignError(f"{where}: expected a table, got {table!r}")
    law = table.get("law")
    if law not in _LAW_KEYS:
        raise ErdesignError(f"{where}.law: expected one of {', '.join(map(repr, _LAW_KEYS))}, got {law!r}")
    allowed = _LAW_KEYS[law] + _COMMON_KEYS
    for key in table:
        if key not in allowed:
            raise ErdesignError(f"{where}.{key}: unknown key for law = {law!r}; allowed keys: {', '.join(allowed)}")
    missing = [k for k in _LAW_KEYS[law] if k not in table and not k.endswith("_unit") and k != "carrier_factor"]
    if missing:
        raise ErdesignError(f"{where}.{missing[0]}: missing (law = {law!r} needs {', '.join(_LAW_KEYS[law])})")

    def unit_of(key: str) -> str:
        return _control_unit_checked(table[key], f"{where}.{key}", control_unit)

    try:
        if law == "power":
            unit = unit_of("reference_field")
            return PowerLaw(unit, yield_stress_ref=to_si(table["yield_stress"], "Pa", f"{where}.yield_stress"),
                            reference_field=to_si(table["reference_field"], unit, f"{where}.reference_field"),
                            exponent=_number(table["yield_exponent"], f"{where}.yield_exponent"))
        if law == "saturating":
            unit = unit_of("saturation_field")
            return SaturatingLaw(unit,
                                 saturation_stress=to_si(table["saturation_stress"], "Pa", f"{where}.saturation_stress"),
                                 saturation_field=to_si(table["saturation_field"], unit, f"{where}.saturation_field"))
        if law == "carlson":
            if control_unit not in (None, "A/m"):
                raise UnitError(f"{where}.law: Carlson's law takes a magnetic field in A/m, but the fluid's reference "
                                f"field is in {control_unit}")
            phi = _number(table["volume_fraction"], f"{where}.volume_fraction")
            factor = _number(table.get("carrier_factor", 1.0), f"{where}.carrier_factor")
            if not (0 < phi < 1 and factor > 0):
                raise ErdesignError(f"{where}: need 0 < volume_fraction < 1 and carrier_factor > 0")
            return SaturatingLaw("A/m",
                                 saturation_stress=factor * CARLSON_STRESS_COEFFICIENT * phi ** CARLSON_VOLUME_EXPONENT,
                                 saturation_field=1.0 / CARLSON_FIELD_COEFFICIENT)
        # table
        field_unit, stress_unit = table.get("field_unit"), table.get("yield_stress_unit")
        fields = table["field"]
        if not isinstance(fields, list) or not fields:
            raise ErdesignError(f"{where}.field: expected a list of values")
        first = Q_(_number(fields[0], f"{where}.field[0]"), field_unit) if field_unit else fields[0]
        unit = _control_unit_checked(first, f"{where}.field", control_unit)
        E = _column(fields, field_unit, unit, f"{where}.field")
        tau = _column(table["yield_stress"], stress_unit, "Pa", f"{where}.yield_stress")
        return TabulatedLaw(unit, fields=tuple(E.tolist()), stresses=tuple(tau.tolist()))
    except ErdesignError as exc:
        if str(exc).startswith(where):
            raise
        raise type(exc)(f"{where}: {exc}") from None


def _control_unit_checked(value: Any, name: str, control_unit: str | None) -> str:
    """SI control unit of ``value``, checked against the fluid's ``control_unit`` when given."""
    unit = control_unit_of(value, name)
    if control_unit is not None and unit != control_unit:
        raise UnitError(f"{name}: the control of the yield curve ({unit}) is not of the kind of the fluid's "
                        f"reference field ({control_unit})")
    return unit
