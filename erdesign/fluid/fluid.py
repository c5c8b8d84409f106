r"""The controllable fluid: plastic viscosity, yield stress as a function of the control, density.

The control is whatever sets the yield stress and is known to the user: an electric field (ER, V/m), a magnetic
field (MR, A/m or T), or, where only that is measured, the coil current (A) or driver voltage (V).  The dimension
of :attr:`Fluid.reference_field` fixes which; every control value given later must have the same dimension.

Field law (Butz and von Stryk 2002, Butz and von Stryk, section 2: :math:`\tau_y \propto E^n`, n from 1.2 to 2.5):

.. math:: \tau_y(E) = \tau_\text{ref} \left(\frac{|E|}{E_\text{ref}}\right)^n

Optional field-dependent plastic viscosity (Makris et al. measured 7 Pa s at 0 and 13 Pa s at 3 kV/mm):

.. math:: \eta(E) = \eta_0 + (\eta_\text{ref} - \eta_0) \left(\frac{|E|}{E_\text{ref}}\right)^n

Only the two end points are published; between them erdesign assumes the viscosity rises like the yield stress
(the same exponent), which is a modelling choice, stated in docs/theory.md.  Without ``viscosity_at_reference_field``
the viscosity does not depend on the field.

A fluid may instead follow a richer law of the field (:mod:`erdesign.fluid.field_laws`: a saturating law or a tabulated
curve, as the materials database gives for MR fluids), in :attr:`Fluid.field_law`.  Then the yield stress follows
that law and the viscosity rises in proportion to it, :math:`\eta_0 + (\eta_\text{ref} - \eta_0)\,
\tau_y(E)/\tau_y(E_\text{ref})`, which is the formula above for the power law.

A fluid may know the control range it was characterised on (:attr:`Fluid.field_range`, from a material's
``[range]``); a control asked for through :meth:`Fluid.field_si` outside that range issues a
:class:`~erdesign.errors.ValidityWarning`.
"""

from __future__ import annotations

import dataclasses
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._util import scalar_or_array
from ..errors import ErdesignError, PlausibilityWarning, UnitError, ValidityWarning
from ..units import Q_, _parse, dimension_name, to_si, ureg
from .field_laws import FieldLaw, PowerLaw

__all__ = [
    "Fluid",
    "plastic_viscosity",
    "CONTROL_UNITS",
    "control_kind",
    "PLAUSIBLE_CONTROL",
    "FLUID_RANGES",
    "PLAUSIBLE_YIELD_EXPONENT",
]

# SI unit of each kind of control, and what it is called in messages.
CONTROL_UNITS = {
    "electric field": "V/m",
    "magnetic field": "A/m",
    "magnetic flux density": "T",
    "current": "A",
    "voltage": "V",
}


#: Largest control of each kind a controllable fluid plausibly takes (SI): ER fluids break down near 4 to 8 kV/mm
#: (Butz and von Stryk 2002, Table 1 gives ca. 4 kV/mm), MR fluids saturate near 250 kA/m to 1 MA/m (ca. 1 to 2 T);
#: coil currents
#: and driver voltages of damper drives stay within tens of A and hundreds of V.  Beyond it erdesign warns; beyond
#: :data:`IMPOSSIBLE_CONTROL_FACTOR` times it, it refuses the value (a unit mistake, not a control).
PLAUSIBLE_CONTROL = {
    "electric field": 2e7,
    "magnetic field": 2e6,
    "magnetic flux density": 3.0,
    "current": 50.0,
    "voltage": 1e3,
}
IMPOSSIBLE_CONTROL_FACTOR = 1e3
#: A reference control below PLAUSIBLE_CONTROL / this is warned, below PLAUSIBLE_CONTROL / this**2 refused: the yield
#: stress is given at a control no fluid is characterised at (a unit mistake: "3 V/mm" for "3 kV/mm"), and the power
#: law then overflows at any working control ("1e-300 kV/mm": an infinite force, NaN in the results).
SMALL_CONTROL_FACTOR = 1e3
#: Yield exponents (tau_y ~ E^n) a file or Fluid.create may give without a warning: Butz and von Stryk (2002) report 1.2 to 2.5 for
#: ER fluids, MR fluids saturate (fits give 0.7 to 1.5).  An exponent near 0 makes the yield stress a step at zero
#: control.  (The power-law summary fitted to a coil's circuit may lie outside: it is not warned.)
PLAUSIBLE_YIELD_EXPONENT = (0.3, 3.0)

#: Possible (error outside) and plausible (warning outside) ranges of the fluid's values, SI.
FLUID_RANGES = {
    "viscosity": ((1e-6, 1e6), (1e-3, 1e3), "Pa*s"),
    "viscosity_at_reference_field": ((1e-6, 1e6), (1e-3, 1e3), "Pa*s"),
    "yield_stress": ((0.0, 1e8), (0.0, 3e5), "Pa"),
    "density": ((1.0, 1e5), (500.0, 8000.0), "kg/m^3"),
    "shear_modulus": ((1e-3, 1e12), (1.0, 1e9), "Pa"),
}


def control_kind(value: Any, name: str = "reference_field") -> str:
    """Kind of control (a key of :data:`CONTROL_UNITS`) of a quantity or string such as ``"3 kV/mm"``."""
    q = _parse(value, name) if isinstance(value, str) else value
    dim = getattr(q, "dimensionality", None)
    for kind, unit in CONTROL_UNITS.items():
        if dim == ureg.Unit(unit).dimensionality:
            return kind
    shown = f"{q:~P}" if hasattr(q, "units") else repr(value)
    raise UnitError(
        f"{name}: expected an electric field (V/m, kV/mm), a magnetic field (A/m, kA/m, T), a coil current (A) or "
        f"a driver voltage (V); got '{shown}'" + (f" ({dimension_name(dim)})" if dim is not None else "")
    )


#: Kinds of control that drive each kind of fluid ("voltage", a driver's command, may drive either).
FLUID_CONTROLS = {
    "ER": ("electric field", "voltage"),
    "MR": ("magnetic field", "magnetic flux density", "current", "voltage"),
}


def _check_material_control(material: str, kind: str, reference_field: Any) -> None:
    """Warn when the control of the reference field cannot drive the material's kind of fluid: an ER fluid given
    a magnetic field or a coil current, an MR fluid given an electric field (a unit slip: kA/m for kV/mm)."""
    if not material:
        return
    from .. import materials  # imported on use: the materials database imports this package

    try:
        fluid_kind = materials.load(material).get("kind")
    except ErdesignError:  # not a material of the database: nothing to compare with
        return
    if fluid_kind in FLUID_CONTROLS and kind not in FLUID_CONTROLS[fluid_kind]:
        shown = reference_field if isinstance(reference_field, str) else f"{reference_field:~P}"
        expected = (
            "an electric field such as '3 kV/mm'"
            if fluid_kind == "ER"
            else "a magnetic field such as '100 kA/m' (or a coil current in A)"
        )
        warnings.warn(
            f"fluid.reference_field: '{shown}' is {'an' if kind[0] in 'aeiou' else 'a'} {kind}, but "
            f"material '{material}' is an {fluid_kind} fluid, driven by {expected}; is the unit right?",
            PlausibilityWarning,
            stacklevel=3,
        )


def _unit_text(value: Any) -> str:
    q = _parse(value, "value") if isinstance(value, str) else value
    return f"{q.units:~}" if hasattr(q, "units") else ""


@dataclass(frozen=True)
class Fluid:
    """A Bingham-plastic controllable fluid in SI units.

    Build it with :meth:`Fluid.create` from quantities or strings; the fields hold SI floats.

    Attributes
    ----------
    viscosity : float
        Plastic viscosity at zero field, eta_0, [Pa s].
    yield_stress : float
        Yield stress at the reference control, tau_ref, [Pa].
    reference_field : float
        Control at which ``yield_stress`` holds, E_ref, in the SI unit of its kind (V/m, A/m, T, A or V).
    control : str
        Kind of control, a key of :data:`CONTROL_UNITS`.
    yield_exponent : float
        Exponent n of the field law, [-].
    density : float
        Density, rho, [kg/m^3].
    viscosity_at_reference_field : float or None
        Plastic viscosity at the reference control, [Pa s]; None: viscosity independent of the field.
    shear_modulus : float or None
        Pre-yield shear modulus G (Makris eq 8), [Pa].
    name : str
        Free text.
    field_law : FieldLaw or None
        Law of the yield stress in the control (:mod:`erdesign.fluid.field_laws`); None: the power law of
        ``yield_stress``, ``reference_field`` and ``yield_exponent``.  With a law, ``yield_stress`` and
        ``yield_exponent`` are the power-law summary (exact at the reference field) that the damper file shows.
    field_range : (float, float) or None
        Control range the fluid was characterised on, SI; None: unknown (no check).
    material : str
        Name of the material (materials database) the values came from, or empty.
    """

    viscosity: float
    yield_stress: float
    reference_field: float
    control: str
    yield_exponent: float
    density: float
    viscosity_at_reference_field: float | None = None
    shear_modulus: float | None = None
    name: str = ""
    display_unit: str = ""
    """Unit the reference field was given in (``"kV/mm"``), for display; SI when empty."""
    field_law: FieldLaw | None = None
    field_range: tuple[float, float] | None = None
    material: str = ""

    def __post_init__(self) -> None:
        checks = [
            ("viscosity", self.viscosity > 0, "must be positive"),
            ("yield_stress", self.yield_stress >= 0, "must not be negative"),
            ("reference_field", self.reference_field > 0, "must be positive"),
            (
                "yield_exponent",
                0 < self.yield_exponent <= 5,
                "must lie in (0, 5] (Butz and von Stryk 2002 report 1.2 to 2.5)",
            ),
            ("density", self.density > 0, "must be positive"),
        ]
        if self.viscosity_at_reference_field is not None:
            checks.append(("viscosity_at_reference_field", self.viscosity_at_reference_field > 0, "must be positive"))
        if self.shear_modulus is not None:
            checks.append(("shear_modulus", self.shear_modulus > 0, "must be positive"))
        for key, ok, why in checks:
            if not ok:
                raise UnitError(f"fluid.{key}: {why}, got {getattr(self, key)!r} (SI)")
        for key, ((lo, hi), _, unit) in FLUID_RANGES.items():
            value = getattr(self, key)
            if value is not None and not lo <= value <= hi:
                raise UnitError(
                    f"fluid.{key}: {value:.4g} {unit} is outside the possible range {lo:g} to {hi:g} "
                    f"{unit} (a unit mistake?)"
                )
        if (
            self.control in PLAUSIBLE_CONTROL
            and self.reference_field > IMPOSSIBLE_CONTROL_FACTOR * PLAUSIBLE_CONTROL[self.control]
        ):
            raise UnitError(
                f"fluid.reference_field: {self.reference_field:.4g} {CONTROL_UNITS[self.control]} is "
                f"beyond any {self.control} a fluid takes (a unit mistake?)"
            )
        if (
            self.control in PLAUSIBLE_CONTROL
            and self.reference_field < PLAUSIBLE_CONTROL[self.control] / SMALL_CONTROL_FACTOR**2
        ):
            raise UnitError(
                f"fluid.reference_field: {self._shown(self.reference_field)} is below any {self.control} a fluid "
                f"is characterised at (a unit mistake?)"
            )
        if self.control not in CONTROL_UNITS:
            raise UnitError(f"fluid.control: unknown kind of control {self.control!r}")
        if self.field_law is not None:
            if not isinstance(self.field_law, FieldLaw):
                raise UnitError(
                    f"fluid.field_law: expected a FieldLaw (erdesign.fluid.field_laws), got {self.field_law!r}"
                )
            if self.field_law.control_unit != self.control_unit:
                raise UnitError(
                    f"fluid.field_law: its control is in {self.field_law.control_unit}, the reference "
                    f"field in {self.control_unit}; both must be of the same kind"
                )
            if not float(self.field_law.yield_stress(self.reference_field)) > 0:
                raise UnitError("fluid.field_law: the yield stress at the reference field must be positive")
        law = (
            self.field_law
            if self.field_law is not None
            else PowerLaw(
                self.control_unit,
                yield_stress_ref=self.yield_stress,
                reference_field=self.reference_field,
                exponent=self.yield_exponent,
            )
        )
        object.__setattr__(self, "_law", law)
        if self.field_range is not None:
            lo, hi = self.field_range
            if not (0 <= lo < hi and np.isfinite(hi)):
                raise UnitError(
                    f"fluid.field_range: need 0 <= low < high, got {self.field_range!r} ({self.control_unit})"
                )

    @classmethod
    def create(
        cls,
        *,
        viscosity: Any,
        yield_stress: Any,
        reference_field: Any,
        yield_exponent: float,
        density: Any,
        viscosity_at_reference_field: Any = None,
        shear_modulus: Any = None,
        name: str = "",
        field_law: FieldLaw | None = None,
        field_range: Any = None,
        material: str = "",
    ) -> "Fluid":
        """Fluid from pint quantities or strings (``viscosity="7 Pa*s"``, ``reference_field="3 kV/mm"``).

        ``field_law`` (a :class:`~erdesign.fluid.field_laws.FieldLaw`) replaces the power law; ``field_range`` is a
        pair ``(low, high)`` of controls (``("0 kV/mm", "3 kV/mm")``) outside which :meth:`field_si` warns.

        Examples
        --------
        >>> f = Fluid.create(viscosity="7 Pa*s", yield_stress="1.8 kPa", reference_field="3 kV/mm",
        ...                  yield_exponent=2.0, density="1100 kg/m^3", viscosity_at_reference_field="13 Pa*s")
        >>> f.control, f.reference_field
        ('electric field', 3000000.0)
        >>> round(f.yield_stress_at(1.5e6), 1), round(f.viscosity_at(1.5e6), 2)   # half the field
        (450.0, 8.5)
        """
        kind = control_kind(reference_field, "fluid.reference_field")
        exponent = to_si(yield_exponent, "", "fluid.yield_exponent", scalar=True)
        if not isinstance(exponent, float):
            raise UnitError(f"fluid.yield_exponent: expected one number, got {yield_exponent!r}")
        fluid = cls(
            viscosity=to_si(viscosity, "Pa*s", "fluid.viscosity", scalar=True),
            yield_stress=to_si(yield_stress, "Pa", "fluid.yield_stress", scalar=True),
            reference_field=to_si(reference_field, CONTROL_UNITS[kind], "fluid.reference_field", scalar=True),
            control=kind,
            yield_exponent=float(exponent),
            density=to_si(density, "kg/m^3", "fluid.density", scalar=True),
            viscosity_at_reference_field=(
                None
                if viscosity_at_reference_field is None
                else to_si(viscosity_at_reference_field, "Pa*s", "fluid.viscosity_at_reference_field", scalar=True)
            ),
            shear_modulus=None
            if shear_modulus is None
            else to_si(shear_modulus, "Pa", "fluid.shear_modulus", scalar=True),
            name=name,
            display_unit=_unit_text(reference_field),
            field_law=field_law,
            field_range=None if field_range is None else _field_range(field_range, CONTROL_UNITS[kind]),
            material=material,
        )
        fluid.warn_implausible()
        _check_material_control(material, kind, reference_field)
        return fluid

    def warn_implausible(self) -> list[str]:
        """Warn (:class:`~erdesign.errors.PlausibilityWarning`) for each value outside the range real fluids take;
        returns the messages."""
        messages = []
        for key, (_, (lo, hi), unit) in FLUID_RANGES.items():
            value = getattr(self, key)
            if value is not None and not lo <= value <= hi:
                messages.append(
                    f"fluid.{key}: {value:.4g} {unit} is outside the plausible range {lo:g} to {hi:g} "
                    f"{unit}; check the value and its unit"
                )
        limit = PLAUSIBLE_CONTROL.get(self.control)
        if limit is not None and self.reference_field > limit:
            messages.append(
                f"fluid.reference_field: {self._shown(self.reference_field)} is beyond the largest "
                f"{self.control} a fluid plausibly takes ({self._shown(limit)}); check the unit"
            )
        lo, hi = PLAUSIBLE_YIELD_EXPONENT
        if self.field_law is None and not lo <= self.yield_exponent <= hi:
            messages.append(
                f"fluid.yield_exponent: {self.yield_exponent:.4g} is outside the plausible range {lo:g} to {hi:g} "
                "(Butz and von Stryk 2002 report 1.2 to 2.5); check the value"
            )
        if limit is not None and self.reference_field < limit / SMALL_CONTROL_FACTOR:
            messages.append(
                f"fluid.reference_field: {self._shown(self.reference_field)} is below the {self.control} fluids "
                f"are characterised at (at least {self._shown(limit / SMALL_CONTROL_FACTOR)}); check the unit"
            )

        for m in messages:
            warnings.warn(m, PlausibilityWarning, stacklevel=3)
        return messages

    def _shown(self, value: float) -> str:
        unit = self.field_unit
        try:
            return f"{Q_(value, self.control_unit).to(unit).magnitude:.4g} {Q_(1.0, unit).units:~P}"
        except Exception:  # noqa: BLE001 - display only
            return f"{value:.4g} {self.control_unit}"

    @property
    def control_unit(self) -> str:
        """SI unit of the control (``"V/m"``, ``"A/m"``, ``"T"``, ``"A"`` or ``"V"``)."""
        return CONTROL_UNITS[self.control]

    @property
    def field_unit(self) -> str:
        """Unit to show control values in: the one the reference field was given in, else SI."""
        return self.display_unit or self.control_unit

    @property
    def yield_law(self) -> FieldLaw:
        """The one law of the yield stress in the control: :attr:`field_law`, or the power law of the attributes
        (built once, in ``__post_init__``).  :meth:`yield_stress_at` and :meth:`viscosity_at` go through it."""
        return self._law

    def field_si(self, field: Any, name: str = "field") -> float | np.ndarray:
        """SI magnitude of a control value, checked against the kind of this fluid's reference field.

        Warns (:class:`~erdesign.errors.ValidityWarning`) when the value lies outside :attr:`field_range`.
        """
        if field is None:
            return 0.0
        value = to_si(field, self.control_unit, name)
        self.check_plausible_field(value, name)
        self.check_field(value, name)
        return value

    def check_plausible_field(self, field, name: str = "field") -> None:
        """Refuse a control beyond :data:`IMPOSSIBLE_CONTROL_FACTOR` times the plausible largest of its kind, warn
        beyond the plausible largest (:data:`PLAUSIBLE_CONTROL`)."""
        limit = PLAUSIBLE_CONTROL.get(self.control)
        if limit is None:
            return
        worst = float(np.max(np.abs(np.asarray(field, dtype=float)), initial=0.0))
        if worst > IMPOSSIBLE_CONTROL_FACTOR * limit:
            raise UnitError(
                f"{name}: {self._shown(worst)} is beyond any {self.control} a fluid takes (the "
                f"plausible largest is {self._shown(limit)}); check the value and its unit"
            )
        if worst > limit:
            warnings.warn(
                f"{name}: {self._shown(worst)} is beyond the largest {self.control} a fluid plausibly "
                f"takes ({self._shown(limit)}); check the value and its unit",
                PlausibilityWarning,
                stacklevel=3,
            )

    def check_field(self, field, name: str = "field") -> bool:
        """True when every |control| (SI) lies in :attr:`field_range` (or no range is known); warns otherwise.

        The zero control (the off state) is always inside.
        """
        if self.field_range is None:
            return True
        lo, hi = self.field_range
        E = np.abs(np.asarray(field, dtype=float))
        outside = (E != 0) & ((E > hi * (1 + 1e-9)) | (E < lo * (1 - 1e-9)))
        if not np.any(outside):
            return True
        unit = self.field_unit
        worst = float(E[outside].max() if E.ndim else E)
        shown = Q_(worst, self.control_unit).to(unit).magnitude
        lo_u, hi_u = (Q_(x, self.control_unit).to(unit).magnitude for x in (lo, hi))
        unit = f"{Q_(1.0, unit).units:~P}"
        owner = f"material '{self.material}'" if self.material else "this fluid"
        warnings.warn(
            f"{name}: {shown:.4g} {unit} is outside the range {lo_u:.4g} to {hi_u:.4g} {unit} on which {owner} is "
            "characterised; the yield stress there is extrapolated",
            ValidityWarning,
            stacklevel=3,
        )
        return False

    def _yield_ratio(self, field):
        """tau_y(E) / tau_y(E_ref), [-]: (|E|/E_ref)^n for the power law."""
        return self._law.ratio(field, self.reference_field)

    def yield_stress_at(self, field):
        r"""Yield stress at the control ``field`` (SI magnitude), [Pa]: the fluid's :attr:`yield_law`,
        :math:`\tau_\text{ref}(|E|/E_\text{ref})^n` unless the fluid was given a richer :attr:`field_law`.
        """
        return scalar_or_array(self._law.yield_stress(field))

    def viscosity_at(self, field):
        r"""Plastic viscosity at the control ``field`` (SI magnitude), [Pa s].

        :math:`\eta_0 + (\eta_\text{ref} - \eta_0)\,\tau_y(E)/\tau_y(E_\text{ref})` (for the power law
        :math:`(|E|/E_\text{ref})^n`), or :math:`\eta_0` when no ``viscosity_at_reference_field`` is given.
        """
        if self.viscosity_at_reference_field is None:
            return scalar_or_array(self.viscosity + 0.0 * np.asarray(field, dtype=float))
        return scalar_or_array(
            plastic_viscosity(self.viscosity, self.viscosity_at_reference_field, self._yield_ratio(field))
        )

    def with_changes(self, **changes: Any) -> "Fluid":
        """Copy with some SI fields replaced (``fluid.with_changes(viscosity=9.0)``)."""
        return dataclasses.replace(self, **changes)


def plastic_viscosity(eta0, eta_ref, yield_ratio):
    r"""Plastic viscosity at a control, [Pa s]: :math:`\eta_0 + (\eta_\text{ref} - \eta_0)\,r` with
    :math:`r = \tau_y(E)/\tau_y(E_\text{ref})` (vectorised; :meth:`Fluid.viscosity_at` is this for one fluid)."""
    return eta0 + (np.asarray(eta_ref, dtype=float) - eta0) * yield_ratio


def _field_range(value: Any, si_unit: str) -> tuple[float, float]:
    """``(low, high)`` controls (quantities or strings) in SI, checked."""
    if isinstance(value, (str, bytes)) or len(value) != 2:
        raise UnitError(f"fluid.field_range: expected a pair (low, high) of controls, got {value!r}")
    lo, hi = (to_si(v, si_unit, f"fluid.field_range[{i}]") for i, v in enumerate(value))
    return float(lo), float(hi)
