r"""Damper geometry: the annular duct(s), the piston and the rod, in SI units, with checks.

Two configurations (docs/file_formats.md, ``[geometry]``):

``valve``
    Makris's damper: a double-ended piston pushes the fluid through ``ducts`` stationary annular ducts in parallel,
    each of length L, mean diameter d and gap h.  The electrodes do not move relative to each other.
``mixed``
    Kamath and Wereley's moving-electrode damper: the piston head (diameter Dp, length L) is the inner electrode.
    The fluid it displaces flows back through the gap h between head and cylinder while the head shears it (flow +
    shear, "mixed mode").  The mean diameter of that gap is ``Dp + h``.

Piston (head) area with a double-ended rod of diameter dr, the same on both sides:

.. math:: A_p = \frac{\pi}{4}\left(D_p^2 - d_r^2\right)

The thin-gap (parallel-plate) flow formulas need ``h << d``; :attr:`Geometry.thin_gap_error` is the error they make
for a Newtonian fluid (:func:`erdesign.flow.newtonian.thin_gap_error`).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np

from .errors import DamperFileError, PlausibilityWarning, ValidityWarning
from .flow.areas import piston_area
from .flow.newtonian import thin_gap_error
from .units import to_si

__all__ = [
    "Geometry",
    "mixed_mean_diameter",
    "CONFIGURATIONS",
    "THIN_GAP_LIMIT",
    "POSSIBLE_LENGTHS",
    "PLAUSIBLE_LENGTHS",
]

CONFIGURATIONS = ("valve", "mixed")

#: Largest h/d for which erdesign uses the thin-gap formulas without comment.  At h/d = 0.1 the thin-gap
#: Newtonian pressure drop is 0.07 % high; above it the valve damper uses the exact annulus and warns.
THIN_GAP_LIMIT = 0.1

#: Possible range of each length [m]: outside it the value is an error (no damper, or a unit mistake so large that
#: the arithmetic of the kernels breaks down: a gap of 1e-300 m cubed is zero).
POSSIBLE_LENGTHS = {
    "gap": (1e-7, 1.0),
    "duct_length": (1e-6, 100.0),
    "duct_mean_diameter": (1e-6, 100.0),
    "piston_diameter": (1e-6, 100.0),
    "rod_diameter": (0.0, 100.0),
}
#: Plausible range of each length [m]: outside it erdesign warns (a unit mistake is likely).  ER/MR particles are
#: 1 to 50 um across, so a gap below 50 um jams; gaps above 10 mm take fields no supply gives (Butz and von Stryk
#: 2002, Table 1).
PLAUSIBLE_LENGTHS = {
    "gap": (5e-5, 1e-2),
    "duct_length": (1e-3, 2.0),
    "duct_mean_diameter": (1e-3, 1.0),
    "piston_diameter": (3e-3, 1.0),
    "rod_diameter": (0.0, 0.5),
}
#: Most parallel ducts possible, and the most erdesign takes without a warning.
MAX_DUCTS, PLAUSIBLE_DUCTS = 10_000, 64


@dataclass(frozen=True)
class Geometry:
    """Geometry of a valve or mixed-mode damper, SI floats.  Build it with :meth:`Geometry.create`.

    Attributes
    ----------
    configuration : str
        ``"valve"`` or ``"mixed"``.
    duct_length : float
        L, duct length (mixed: length of the piston head), [m].
    duct_mean_diameter : float
        d, mean diameter of the annular gap, [m].
    gap : float
        h, radial gap, [m].
    piston_diameter : float
        Dp, piston (head) diameter, [m].
    rod_diameter : float
        dr, rod diameter (double-ended rod), [m].
    ducts : int
        Number of parallel ducts (valve), [-].
    """

    configuration: str
    duct_length: float
    duct_mean_diameter: float
    gap: float
    piston_diameter: float
    rod_diameter: float
    ducts: int = 1

    def __post_init__(self) -> None:
        def bad(key: str, why: str) -> DamperFileError:
            return DamperFileError(f"geometry.{key}: {why}")

        if self.configuration not in CONFIGURATIONS:
            raise bad(
                "configuration", f"must be one of {', '.join(map(repr, CONFIGURATIONS))}, got {self.configuration!r}"
            )
        # The constructor takes SI floats, and also quantities or strings ("0.8 mm"), as Geometry.create does.
        for key in ("duct_length", "duct_mean_diameter", "gap", "piston_diameter", "rod_diameter"):
            value = getattr(self, key)
            if not isinstance(value, float):
                object.__setattr__(self, key, _length_si(key, value))
            if not math.isfinite(getattr(self, key)):
                raise bad(key, f"must be finite, got {getattr(self, key)!r}")
        ducts = self.ducts
        if isinstance(ducts, (int, np.integer)) and not isinstance(ducts, bool):
            object.__setattr__(self, "ducts", int(ducts))
        for key in ("duct_length", "duct_mean_diameter", "gap", "piston_diameter"):
            value = getattr(self, key)
            if not value > 0:
                raise bad(key, f"must be positive, got {value:g} m")
        if self.rod_diameter < 0:
            raise bad("rod_diameter", f"must not be negative, got {self.rod_diameter:g} m")
        for key, (lo, hi) in POSSIBLE_LENGTHS.items():
            value = getattr(self, key)
            if not lo <= value <= hi:
                raise bad(
                    key,
                    f"{_mm(value)} is outside the possible range {_mm(lo)} to {_mm(hi)} of a damper (a unit mistake?)",
                )
        if self.rod_diameter >= self.piston_diameter:
            raise bad(
                "rod_diameter",
                f"must be smaller than the piston diameter ({self.rod_diameter * 1e3:g} mm "
                f">= {self.piston_diameter * 1e3:g} mm)",
            )
        if self.gap >= self.duct_mean_diameter:
            raise bad(
                "gap",
                f"must be smaller than the mean diameter of the annulus ({self.gap * 1e3:g} mm >= "
                f"{self.duct_mean_diameter * 1e3:g} mm): the inner wall would have no diameter left",
            )
        if not (isinstance(self.ducts, int) and not isinstance(self.ducts, bool) and self.ducts >= 1):
            raise bad("ducts", f"must be a whole number >= 1, got {self.ducts!r}")
        if self.ducts > MAX_DUCTS:
            raise bad("ducts", f"{self.ducts} parallel ducts is beyond the possible range (at most {MAX_DUCTS})")
        if self.configuration == "mixed":
            if self.ducts != 1:
                raise bad("ducts", "applies to the valve configuration only (a mixed damper has one gap)")
            expected = mixed_mean_diameter(self.piston_diameter, self.gap)
            if not math.isclose(self.duct_mean_diameter, expected, rel_tol=1e-3):
                raise bad(
                    "duct_mean_diameter",
                    f"for a mixed damper it is piston_diameter + gap = "
                    f"{expected * 1e3:.4g} mm, got {self.duct_mean_diameter * 1e3:.4g} mm",
                )
        self._warn_implausible()
        if self.gap_ratio > THIN_GAP_LIMIT:
            warnings.warn(
                f"geometry.gap: h/d = {self.gap_ratio:.3g} is not small; the thin-gap formulas are off by "
                f"{100 * self.thin_gap_error:.2g} % for a Newtonian fluid"
                + (
                    "; the exact annulus is used"
                    if self.configuration == "valve"
                    else "; the mixed-mode model keeps the thin-gap form (compare erdesign.flow.numerical in annular "
                    "coordinates)"
                ),
                ValidityWarning,
                stacklevel=3,
            )

    def _warn_implausible(self) -> None:
        """A :class:`~erdesign.errors.PlausibilityWarning` per value outside the range real dampers take."""
        for key, (lo, hi) in PLAUSIBLE_LENGTHS.items():
            value = getattr(self, key)
            if not lo <= value <= hi:
                warnings.warn(
                    f"geometry.{key}: {_mm(value)} is outside the plausible range {_mm(lo)} to {_mm(hi)}; "
                    "check the value and its unit",
                    PlausibilityWarning,
                    stacklevel=4,
                )
        if self.ducts > PLAUSIBLE_DUCTS:
            warnings.warn(
                f"geometry.ducts: {self.ducts} parallel ducts is implausibly many (more than "
                f"{PLAUSIBLE_DUCTS}); check the value",
                PlausibilityWarning,
                stacklevel=4,
            )

    @classmethod
    def create(
        cls,
        *,
        configuration: str,
        duct_length: Any,
        gap: Any,
        piston_diameter: Any,
        rod_diameter: Any,
        duct_mean_diameter: Any = None,
        ducts: int = 1,
    ) -> "Geometry":
        """Geometry from pint quantities or strings, checked.

        ``duct_mean_diameter`` may be omitted for a mixed damper (it is ``piston_diameter + gap``).

        Examples
        --------
        >>> g = Geometry.create(configuration="valve", duct_length="54.6 mm", duct_mean_diameter="14.3 mm",
        ...                     gap="0.8 mm", piston_diameter="33.4 mm", rod_diameter="11.25 mm")
        >>> round(g.piston_area * 1e4, 4)   # cm^2
        7.7676
        """
        if configuration not in CONFIGURATIONS:
            raise DamperFileError(
                f"geometry.configuration: must be one of {', '.join(map(repr, CONFIGURATIONS))}, got {configuration!r}"
            )
        L = to_si(duct_length, "m", "geometry.duct_length", scalar=True)
        h = to_si(gap, "m", "geometry.gap", scalar=True)
        Dp = to_si(piston_diameter, "m", "geometry.piston_diameter", scalar=True)
        dr = to_si(rod_diameter, "m", "geometry.rod_diameter", scalar=True)
        if duct_mean_diameter is None:
            if configuration == "valve":
                raise DamperFileError("geometry.duct_mean_diameter: missing (required for a valve damper)")
            d = mixed_mean_diameter(Dp, h)
        else:
            d = to_si(duct_mean_diameter, "m", "geometry.duct_mean_diameter", scalar=True)
        if isinstance(ducts, bool) or not isinstance(ducts, (int, np.integer)):
            raise DamperFileError(f"geometry.ducts: must be a whole number >= 1, got {ducts!r}")
        return cls(configuration, L, d, h, Dp, dr, ducts)

    def with_(self, **changes: Any) -> "Geometry":
        """This geometry with some values changed (SI floats [m], quantities or strings), checked as on construction.

        A mixed damper's ``duct_mean_diameter`` follows the head and the gap (:func:`mixed_mean_diameter`) unless
        it is among the changes.  An unknown name is an error.

        Examples
        --------
        >>> g = Geometry.create(configuration="mixed", duct_length="50 mm", gap="1 mm", piston_diameter="38 mm",
        ...                     rod_diameter="12.7 mm")
        >>> round(g.with_(gap="2 mm").duct_mean_diameter * 1e3, 6)     # mm: Dp + h
        40.0
        """
        names = [f.name for f in dataclasses.fields(self)]
        unknown = sorted(set(changes) - set(names))
        if unknown:
            raise TypeError(f"Geometry.with_: unknown value(s) {', '.join(unknown)}; known: {', '.join(names)}")
        values = {key: getattr(self, key) for key in names} | changes
        if values["configuration"] == "mixed" and "duct_mean_diameter" not in changes:
            values["duct_mean_diameter"] = mixed_mean_diameter(
                _length_si("piston_diameter", values["piston_diameter"]), _length_si("gap", values["gap"])
            )
        return Geometry(**values)

    @property
    def piston_area(self) -> float:
        """A_p = pi/4 (Dp^2 - dr^2), the area that displaces fluid, [m^2] (:func:`erdesign.flow.areas.piston_area`)."""
        return piston_area(self.piston_diameter, self.rod_diameter)

    @property
    def gap_ratio(self) -> float:
        """h/d, [-]."""
        return self.gap / self.duct_mean_diameter

    @property
    def thin_gap_error(self) -> float:
        """Relative error of the thin-gap Newtonian pressure drop against the exact annulus, [-]."""
        return float(thin_gap_error(self.gap_ratio))

    @property
    def shear_area(self) -> float:
        """Area of the moving electrode that shears the fluid (mixed: pi Dp L; valve: 0), [m^2]."""
        return math.pi * self.piston_diameter * self.duct_length if self.configuration == "mixed" else 0.0

    @property
    def active_fluid_volume(self) -> float:
        """Volume of fluid between the electrodes, pi d h L per duct times the number of ducts, [m^3].

        The volume Kamath and Wereley (1997) (Kamath and Wereley, section III.C) divides the dissipated energy by.
        """
        return math.pi * self.duct_mean_diameter * self.gap * self.duct_length * self.ducts


def mixed_mean_diameter(piston_diameter, gap):
    """Mean diameter of a mixed damper's gap, d = Dp + h, [m] (the gap lies between the head and the cylinder).

    Parameters
    ----------
    piston_diameter : float or array
        Dp, head diameter, [m].
    gap : float or array
        h, radial gap between head and cylinder, [m].

    Examples
    --------
    >>> round(mixed_mean_diameter(0.038, 0.00254), 5)
    0.04054
    """
    return piston_diameter + gap


def _length_si(key: str, value: Any) -> float:
    """One length [m] from an SI number, a quantity or a string; a :class:`DamperFileError` naming ``key`` else."""
    if isinstance(value, float):
        return value
    if isinstance(value, (int, np.integer, np.floating)) and not isinstance(value, bool):
        return float(value)
    if value is None or isinstance(value, bool):
        raise DamperFileError(f"geometry.{key}: expected a length such as '0.8 mm', got {value!r}")
    si = to_si(value, "m", f"geometry.{key}")
    if not isinstance(si, float):
        raise DamperFileError(f"geometry.{key}: expected one length, got {value!r}")
    return si


def _mm(value: float) -> str:
    """A length [m] as text in mm (``0.0008`` -> ``'0.8 mm'``), in m beyond 1 km."""
    return f"{value * 1e3:.4g} mm" if abs(value) < 1e3 else f"{value:.4g} m"
