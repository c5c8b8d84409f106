r"""Magnetisation (B-H) curves of the steels and MR fluids of a damper's magnetic circuit, in SI units.

A :class:`BHCurve` is one monotone curve :math:`H(B)` through tabulated points (a steel's DC magnetisation curve
from a materials library) interpolated by the monotone piecewise-cubic Hermite interpolant of Fritsch and Carlson
(:class:`scipy.interpolate.PchipInterpolator`), so that the interpolated curve never overshoots and stays
invertible.  Above the last point the material is taken as fully saturated: the differential permeability is that
of free space, :math:`H = H_n + (B - B_n)/\mu_0`.  The curve is odd (:math:`H(-B) = -H(B)`); hysteresis is not
modelled (the DC anhysteretic / normal magnetisation curve is used, as in Gavin, Hoagg and Dobossy 2001).

MR fluids: :func:`carlson_flux_density` is Carlson's empirical law for LORD's hydrocarbon MR fluids,

.. math:: B = 1.91\,\phi^{1.133}\left[1 - e^{-10.97\,\mu_0 H}\right] + \mu_0 H,

sampled densely into a :class:`BHCurve` by :func:`carlson_curve`.

The *knee* of a curve (:meth:`BHCurve.knee`) is where its chord permeability :math:`B/H` has fallen to half of its
largest value on the way to saturation.  This is erdesign's definition (there is no single standard one); it
places the knee of AISI 1018 (FEMM library curve) at about 1.36 T and 2.2 kA/m, and that of an MRF-132DG-like
fluid (Carlson's law, phi = 0.32) at about 0.66 T and 155 kA/m.

Example
-------
>>> c = BHCurve("test", B=(0.0, 1.0, 1.5), H=(0.0, 1000.0, 5000.0))
>>> float(c.H_of_B(1.0)), float(c.B_of_H(5000.0 + 1.0 / MU0))    # a table point; one tesla above the table
(1000.0, 2.5)
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np
from scipy.interpolate import PchipInterpolator

from ..errors import ErdesignError

__all__ = [
    "MU0",
    "BHCurve",
    "carlson_flux_density",
    "carlson_curve",
    "bh_curve_from_dict",
    "CARLSON_B_COEFFICIENT",
    "CARLSON_B_EXPONENT",
    "CARLSON_B_FIELD_COEFFICIENT",
]

#: Magnetic constant [H/m] (CODATA 2018 value, as scipy.constants.mu_0; 4 pi 1e-7 to 1e-9 relative).
MU0 = 1.25663706212e-6

#: Constants of Carlson's B-H law of LORD MR fluids (:func:`carlson_flux_density`): [T], [-], [1/T].
CARLSON_B_COEFFICIENT = 1.91
CARLSON_B_EXPONENT = 1.133
CARLSON_B_FIELD_COEFFICIENT = 10.97


def carlson_flux_density(H, phi):
    r"""Flux density of a LORD hydrocarbon MR fluid of iron volume fraction ``phi`` in the field ``H``.

    .. math:: B = 1.91\,\phi^{1.133}\left[1 - e^{-10.97\,\mu_0 |H|}\right]\operatorname{sgn}H + \mu_0 H

    Parameters
    ----------
    H : float or array
        Magnetic field strength, [A/m].
    phi : float
        Volume fraction of iron, [-] (MRF-132DG: 0.32).

    Returns
    -------
    float or array
        Flux density, [T].

    Notes
    -----
    The saturation polarisation :math:`1.91\phi^{1.133}` is 0.525 T for phi = 0.32 and the initial relative
    permeability is :math:`1 + 10.97\cdot 1.91\phi^{1.133}` = 6.8.  The law is quoted from Carlson (2005) in the
    form above by secondary sources; erdesign could not read the original paper and states it as not verified
    (docs/magnetics.md, "Sources").

    Examples
    --------
    >>> round(float(carlson_flux_density(250e3, 0.32)), 3)     # T at 250 kA/m
    0.823

    References
    ----------
    J. D. Carlson, MR fluids and devices in the real world, Int. J. Mod. Phys. B 19 (2005) 1463-1470.
    """
    H = np.asarray(H, dtype=float)
    J_sat = CARLSON_B_COEFFICIENT * float(phi) ** CARLSON_B_EXPONENT
    return np.sign(H) * J_sat * -np.expm1(-CARLSON_B_FIELD_COEFFICIENT * MU0 * np.abs(H)) + MU0 * H


@dataclass(frozen=True)
class BHCurve:
    """A monotone magnetisation curve H(B) through points (B_i, H_i), SI; see the module docstring.

    ``B`` [T] and ``H`` [A/m] start at (0, 0) and increase strictly.  ``name`` and ``source`` say what it is.
    """

    name: str
    B: tuple[float, ...]
    H: tuple[float, ...]
    source: str = ""
    _cache: dict = field(default_factory=dict, repr=False, compare=False)

    def __post_init__(self) -> None:
        B = np.asarray(self.B, dtype=float)
        H = np.asarray(self.H, dtype=float)
        if not (B.ndim == 1 and B.shape == H.shape and B.size >= 2):
            raise ErdesignError(f"B-H curve {self.name!r}: needs at least two points and as many B as H values")
        if not (np.all(np.isfinite(B)) and np.all(np.isfinite(H))):
            raise ErdesignError(f"B-H curve {self.name!r}: values must be finite")
        if B[0] != 0.0 or H[0] != 0.0:
            raise ErdesignError(f"B-H curve {self.name!r}: must start at B = 0 T, H = 0 A/m, got ({B[0]!r}, {H[0]!r})")
        if not (np.all(np.diff(B) > 0) and np.all(np.diff(H) > 0)):
            raise ErdesignError(f"B-H curve {self.name!r}: B and H must both increase strictly")
        if np.any(B[1:] - MU0 * H[1:] < -1e-9):
            raise ErdesignError(f"B-H curve {self.name!r}: B < mu0 H somewhere (a relative permeability below 1)")

    # ------------------------------------------------------------------ interpolation
    def _interp(self) -> tuple[PchipInterpolator, np.ndarray]:
        if "pchip" not in self._cache:
            B = np.asarray(self.B, dtype=float)
            H = np.asarray(self.H, dtype=float)
            spline = PchipInterpolator(B, H, extrapolate=False)
            # a dense table of the spline for the inverse B(H): monotone, so np.interp inverts it
            Bd = np.unique(np.concatenate([np.linspace(0.0, B[-1], 4001), B]))
            Hd = spline(Bd)
            Hd[0] = 0.0
            self._cache["pchip"] = (spline, np.vstack([Bd, Hd]))
        return self._cache["pchip"]

    @property
    def B_max(self) -> float:
        """Last tabulated flux density [T]; above it the differential permeability is mu0."""
        return float(self.B[-1])

    def H_of_B(self, B):
        """Field strength [A/m] at flux density ``B`` [T] (odd; mu0 slope above the table)."""
        spline, _ = self._interp()
        B = np.asarray(B, dtype=float)
        a = np.abs(B)
        inside = a <= self.B_max
        H = np.where(inside, spline(np.where(inside, a, 0.0)), self.H[-1] + (a - self.B_max) / MU0)
        return np.sign(B) * H

    def dH_dB(self, B):
        """Differential reluctivity dH/dB [m/H] at ``B`` [T] (even in B)."""
        spline, _ = self._interp()
        a = np.abs(np.asarray(B, dtype=float))
        inside = a <= self.B_max
        return np.where(inside, spline.derivative()(np.where(inside, a, 0.0)), 1.0 / MU0)

    def B_of_H(self, H):
        """Flux density [T] at field strength ``H`` [A/m] (the inverse of :meth:`H_of_B`)."""
        _, table = self._interp()
        H = np.asarray(H, dtype=float)
        a = np.abs(H)
        H_end = float(table[1, -1])
        B = np.where(a <= H_end, np.interp(a, table[1], table[0]), self.B_max + MU0 * (a - H_end))
        return np.sign(H) * B

    def reluctivity(self, B):
        """nu = H/B [m/H] at ``B`` [T]; the initial differential value at B = 0."""
        B = np.abs(np.asarray(B, dtype=float))
        tiny = B < 1e-9
        safe = np.where(tiny, 1.0, B)
        return np.where(tiny, self.dH_dB(0.0), self.H_of_B(safe) / safe)

    def reluctivity_derivative(self, B):
        """d nu / d(B^2) [m/(H T^2)] at ``B`` [T] (for Newton's method in the finite-element check)."""
        B = np.abs(np.asarray(B, dtype=float))
        tiny = B < 1e-6
        safe = np.where(tiny, 1e-6, B)
        d = (self.dH_dB(safe) * safe - self.H_of_B(safe)) / safe**2 / (2.0 * safe)
        return np.where(tiny, 0.0, d)

    # ------------------------------------------------------------------ characteristics
    def initial_relative_permeability(self) -> float:
        """mu_r at B -> 0, [-]."""
        return float(1.0 / (MU0 * self.dH_dB(0.0)))

    @functools.cached_property
    def _knee(self) -> tuple[float, float]:
        Hs = np.geomspace(1e-3, 1e8, 20001)
        Bs = self.B_of_H(Hs)
        mu = Bs / Hs
        i_max = int(np.argmax(mu))
        after = np.nonzero(mu[i_max:] <= 0.5 * mu[i_max])[0]
        if after.size == 0:  # pragma: no cover - every curve ends at mu0 slope
            return float("inf"), float("inf")
        j = i_max + int(after[0])
        # interpolate the crossing in log H
        m0, m1 = mu[j - 1], mu[j]
        t = (m0 - 0.5 * mu[i_max]) / (m0 - m1)
        H = float(np.exp(np.log(Hs[j - 1]) + t * (np.log(Hs[j]) - np.log(Hs[j - 1]))))
        return float(self.B_of_H(H)), H

    def knee(self) -> tuple[float, float]:
        """(B, H) [T, A/m] of the knee: where the chord permeability B/H has fallen to half its largest value."""
        return self._knee


def carlson_curve(phi: float, name: str = "", source: str = "") -> BHCurve:
    """:class:`BHCurve` of Carlson's MR-fluid law (:func:`carlson_flux_density`) sampled on 0 to 10 MA/m.

    >>> c = carlson_curve(0.32)
    >>> round(c.initial_relative_permeability(), 2)
    6.76
    """
    if not 0 < phi < 1:
        raise ErdesignError(f"carlson B-H law: need 0 < volume_fraction < 1, got {phi!r}")
    H = np.concatenate([[0.0], np.geomspace(1.0, 1e7, 1200)])
    B = carlson_flux_density(H, phi)
    return BHCurve(
        name or f"carlson phi={phi:g}", tuple(B.tolist()), tuple(H.tolist()), source or "Carlson 2005 B-H law"
    )


def _column(values: Any, unit: str, si: str, where: str) -> np.ndarray:
    from ..units import Q_, to_si

    if not isinstance(values, list) or not values:
        raise ErdesignError(f"{where}: expected a list of numbers")
    out = []
    for i, v in enumerate(values):
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise ErdesignError(f"{where}[{i}]: expected a number, got {v!r}")
        out.append(to_si(Q_(float(v), unit), si, f"{where}[{i}]"))
    return np.asarray(out, dtype=float)


def bh_curve_from_dict(
    table: Mapping[str, Any], *, name: str, where: str = "magnetization", source: str = ""
) -> BHCurve:
    """A :class:`BHCurve` from the ``[magnetization]`` table of a material file (docs/materials.md).

    * ``law = "carlson"``: ``volume_fraction`` (Carlson's MR-fluid law);
    * ``law = "table"``: ``flux_density`` and ``field`` lists of numbers with ``flux_density_unit`` and
      ``field_unit`` (e.g. ``"T"``, ``"A/m"``), starting at 0 and increasing.

    >>> bh_curve_from_dict({"law": "table", "flux_density": [0, 1], "field": [0, 500],
    ...                     "flux_density_unit": "T", "field_unit": "A/m"}, name="x").H
    (0.0, 500.0)
    """
    if not isinstance(table, Mapping):
        raise ErdesignError(f"{where}: expected a table, got {table!r}")
    keys = {
        "carlson": ("law", "volume_fraction"),
        "table": ("law", "flux_density", "field", "flux_density_unit", "field_unit"),
    }
    law = table.get("law")
    if law not in keys:
        raise ErdesignError(f'{where}.law: expected "carlson" or "table", got {law!r}')
    for key in table:
        if key not in keys[law]:
            raise ErdesignError(f"{where}.{key}: unknown key for law = {law!r}; allowed keys: {', '.join(keys[law])}")
    for key in keys[law]:
        if key not in table:
            raise ErdesignError(f"{where}.{key}: missing (law = {law!r} needs {', '.join(keys[law][1:])})")
    if law == "carlson":
        phi = table["volume_fraction"]
        if isinstance(phi, bool) or not isinstance(phi, (int, float)) or not 0 < phi < 1:
            raise ErdesignError(f"{where}.volume_fraction: expected a number in (0, 1), got {phi!r}")
        return carlson_curve(float(phi), name=name, source=source)
    B = _column(table["flux_density"], table["flux_density_unit"], "T", f"{where}.flux_density")
    H = _column(table["field"], table["field_unit"], "A/m", f"{where}.field")
    if B.size != H.size:
        raise ErdesignError(f"{where}: flux_density and field must have the same length, got {B.size} and {H.size}")
    try:
        return BHCurve(name, tuple(B.tolist()), tuple(H.tolist()), source)
    except ErdesignError as exc:
        raise ErdesignError(f"{where}: {exc}") from None
