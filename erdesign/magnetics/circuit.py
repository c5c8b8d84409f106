r"""Nonlinear reluctance network of the common MR piston head: coil current -> gap flux density -> yield stress.

The head (docs/file_formats.md, [coil]) is axisymmetric: a coil of N turns on a steel core of radius
:math:`r_c`, between two steel poles of axial length :math:`L_p` and radius :math:`R_p`; the annular fluid gap
:math:`h` separates the poles from the steel housing (inner radius :math:`R_i = R_p + h`, outer :math:`R_o`), which
is the return path.  The flux goes up the core, out radially through one pole, across the gap, along the housing
wall and back in through the gap and the other pole.  Ampere's law around that loop,

.. math::
    N I = \underbrace{H_s(B_\text{core})(L_c + L_p)}_\text{core}
        + 2\underbrace{\int_0^{R_p} H_s(B_\text{pole}(r))\,dr}_\text{pole}
        + 2\underbrace{\int_{R_p}^{R_i} H_f(B_\text{gap}(r))\,dr}_\text{gap}
        + 2\underbrace{\int_{R_i}^{R_o} H_s(B_\text{wall,r}(r))\,dr}_\text{housing at pole}
        + \underbrace{H_s(B_\text{wall})(L_c + L_p)}_\text{housing}

with :math:`H_s(B)` and :math:`H_f(B)` the B-H curves of the steel and the fluid (:mod:`erdesign.magnetics.bh`), is
the reluctance-network balance of Gavin, Hoagg and Dobossy (2001), who solve it with the nonlinear B-H curves of the
steel and the fluid to size MR dampers for minimum power and time constant.  The flux density of each element is
the flux over the area it crosses: :math:`B_\text{core} = \Phi_c/\pi r_c^2`; radially through the pole and the gap
:math:`\Phi/2\pi r L_p` (in the pole inside the core radius, :math:`\Phi r / 2\pi r_c^2 L_p`, the core's flux being
collected uniformly); in the housing wall at the pole the radial flux falls as it turns axial; axially along the wall
:math:`\Phi/\pi(R_o^2 - R_i^2)`.  Radial integrals use 24-point Gauss-Legendre quadrature.

Leakage, where it matters (the flux that does not cross the gap under the poles):

* fringing at the outer end of each pole, through the fluid from the pole's end face to the housing, by the method
  of probable flux paths (Roters 1941, ch. 5): a path leaving the end face at depth s below the pole's rim is a
  quarter circle of radius s plus the gap, of length :math:`h + \pi s/2`, and carries
  :math:`2\pi r_m B_f(F_g/(h + \pi s/2))\,ds` at the gap's MMF :math:`F_g` (the fluid in the fringe is less
  saturated than in the gap); integrated over the whole end face, :math:`0 < s < R_p` (the chamber beyond the head
  is full of fluid);
* fringing on the coil side of each pole: the same quarter circles, now through the winding (:math:`\mu_0`) in
  series with the gap at the fluid's chord permeability, over :math:`0 < s < \min(L_c/2, R_p - r_c)`;
  for a linear fluid both are an extra pole length :func:`fringe_length`;
* axially through the fluid annulus over the coil, from pole to pole, at the field :math:`F_e/L_c` of the
  MMF :math:`F_e` across the external path;
* axially through the coil window (copper, :math:`\mu_0`): a path at radius r encloses the fraction
  :math:`f = (r - r_c)/(R_p - r_c)` of the ampere-turns, so it carries :math:`\mu_0 F_e f\,2\pi r\,dr/L_c` and
  links :math:`N f` turns (the classical 1/3 factor of a uniformly distributed winding).

The unknown is the gap field :math:`H_g` at the gap's mean radius; every flux and MMF is explicit in it and
:math:`NI(H_g)` increases monotonically, so the operating point at any array of currents is one bracketed scalar
root per current (:func:`scipy.optimize.elementwise.find_root`, Chandrupatla's method).  The flux linkage
:math:`\lambda` gives the (secant) inductance :math:`L = \lambda/I` and the time constant :math:`L/R`.

Assumptions: DC (no eddy currents: a solid-steel head responds more slowly than L/R), no hysteresis, thin gap
compared with the radii, the flux enters the housing over the pole length only; the finite-element check
(:mod:`erdesign.magnetics.fem`) measures what these cost (docs/magnetics.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.optimize import elementwise

from ..errors import DamperFileError, ErdesignError, ValidityWarning
from ..fluid.field_laws import FieldLaw
from .bh import MU0, BHCurve
from .coil import MAX_FILL_FACTOR, Coil, coil_resistance

__all__ = ["PistonHead", "HeadBatch", "piston_head", "MagneticCircuit", "CircuitState", "PARTS", "fringe_length"]

#: Parts of the circuit whose saturation is checked, in the order of :attr:`CircuitState.part_flux_density`.
PARTS = ("core", "pole", "gap", "housing_at_pole", "housing_wall")

_GL_X, _GL_W = np.polynomial.legendre.leggauss(24)


def fringe_length(gap: float, extent: float) -> float:
    r"""Equivalent extra pole length of the fringing flux at one pole end, [m].

    .. math:: \delta = \frac{2h}{\pi}\ln\left(1 + \frac{\pi x}{2h}\right)

    from paths of length :math:`h + \pi s/2` (quarter circles of radius s from the end face to the housing, plus
    the gap) over an end face of extent x: :math:`\int_0^x ds/(h + \pi s/2)`, times h.

    >>> round(fringe_length(1e-3, 11e-3) * 1e3, 3)   # mm, 1 mm gap, 11 mm end face
    1.85
    """
    return 2.0 * gap / math.pi * math.log1p(math.pi * extent / (2.0 * gap))


@dataclass(frozen=True)
class PistonHead:
    """Geometry and winding of the head in SI units (m); see the module docstring for the symbols."""

    core_radius: float  # r_c
    pole_radius: float  # R_p
    gap: float  # h
    housing_outer_radius: float  # R_o
    pole_length: float  # L_p
    coil_length: float  # L_c
    turns: int  # N
    wire_diameter: float  # d_w

    def __post_init__(self) -> None:
        if not (
            0 < self.core_radius < self.pole_radius
            and self.gap > 0
            and self.pole_length > 0
            and self.coil_length > 0
            and self.housing_outer_radius > self.pole_radius + self.gap
            and self.turns >= 1
            and self.wire_diameter > 0
        ):
            raise ErdesignError(f"piston head: inconsistent geometry {self!r}")

    @property
    def housing_inner_radius(self) -> float:
        """R_i = R_p + h, [m]."""
        return self.pole_radius + self.gap

    @property
    def mean_gap_radius(self) -> float:
        """r_m = R_p + h/2, [m]: where the gap flux density is reported."""
        return self.pole_radius + 0.5 * self.gap

    @property
    def window_area(self) -> float:
        """Cross-section of the winding window (R_p - r_c) L_c, [m^2]."""
        return (self.pole_radius - self.core_radius) * self.coil_length

    @property
    def fill_factor(self) -> float:
        """Copper fill factor N pi d_w^2/4 / window area, [-]."""
        return self.turns * math.pi * self.wire_diameter**2 / 4.0 / self.window_area

    @property
    def head_length(self) -> float:
        """L_c + 2 L_p, [m]."""
        return self.coil_length + 2.0 * self.pole_length


@dataclass(frozen=True)
class HeadBatch(PistonHead):
    """Many heads at once: every attribute an array of the same shape (N,), unchecked (design candidates; the
    caller masks impossible ones).  A :class:`MagneticCircuit` of a batch solves each head at its own current."""

    def __post_init__(self) -> None:
        pass


def _col(x):
    """x as a column against the quadrature nodes (a batch of heads: (N, 1); a scalar stays a scalar)."""
    return x if np.ndim(x) == 0 else np.asarray(x)[..., None]


def piston_head(geometry: Any, coil: Coil, *, where: str = "coil") -> PistonHead:
    """The :class:`PistonHead` of a damper geometry (:class:`erdesign.geometry.Geometry`) and its ``[coil]``.

    The head's outer radius is :math:`R_p = (d - h)/2` (d the mean diameter of the annular duct, h the gap; for a
    "mixed" damper that is half the piston diameter), its length the duct length L, the coil length
    :math:`L_c = L - 2L_p`.  Impossible combinations are a :class:`DamperFileError` naming the key; implausible
    ones warn.
    """
    import warnings

    if getattr(geometry, "ducts", 1) != 1:
        raise DamperFileError(
            f"{where}: a coil needs one annular duct around the head, got geometry.ducts = {geometry.ducts}"
        )
    h = geometry.gap
    R_p = 0.5 * (geometry.duct_mean_diameter - h)
    r_c = 0.5 * coil.core_diameter
    R_o = 0.5 * coil.housing_outer_diameter
    L_c = geometry.duct_length - 2.0 * coil.pole_length
    if not r_c < R_p:
        raise DamperFileError(
            f"{where}.core_diameter: {coil.core_diameter * 1e3:.4g} mm leaves no room for the "
            f"winding inside the head of diameter {2e3 * R_p:.4g} mm"
        )
    if not L_c > 0:
        raise DamperFileError(
            f"{where}.pole_length: two poles of {coil.pole_length * 1e3:.4g} mm fill the head "
            f"length {geometry.duct_length * 1e3:.4g} mm (geometry.duct_length); no room for the coil"
        )
    if not R_o > R_p + h:
        raise DamperFileError(
            f"{where}.housing_outer_diameter: {coil.housing_outer_diameter * 1e3:.4g} mm is not "
            f"larger than the bore {2e3 * (R_p + h):.4g} mm"
        )
    head = PistonHead(
        core_radius=r_c,
        pole_radius=R_p,
        gap=h,
        housing_outer_radius=R_o,
        pole_length=coil.pole_length,
        coil_length=L_c,
        turns=coil.turns,
        wire_diameter=coil.wire_diameter,
    )
    if head.fill_factor > MAX_FILL_FACTOR:
        raise DamperFileError(
            f"{where}.turns: {coil.turns} turns of {coil.wire_diameter * 1e3:.4g} mm wire need a "
            f"copper fill factor of {head.fill_factor:.2f}, above the {MAX_FILL_FACTOR:.3f} of "
            f"hexagonally packed bare wire; the window is {1e6 * head.window_area:.4g} mm^2"
        )
    if head.fill_factor > 0.7:
        warnings.warn(
            f"{where}.turns: copper fill factor {head.fill_factor:.2f} is above the 0.5-0.7 a round-wire "
            "coil with enamel reaches in practice",
            ValidityWarning,
            stacklevel=2,
        )
    if R_o - (R_p + h) < 1e-3:
        warnings.warn(
            f"{where}.housing_outer_diameter: housing wall {1e3 * (R_o - R_p - h):.3g} mm thick is implausibly thin",
            ValidityWarning,
            stacklevel=2,
        )
    if h > 0.25 * R_p:
        warnings.warn(
            f"{where}: the gap ({h * 1e3:.3g} mm) is not thin compared with the head radius; the "
            "reluctance network assumes a thin gap",
            ValidityWarning,
            stacklevel=2,
        )
    return head


@dataclass(frozen=True)
class CircuitState:
    """The solved circuit at an array of currents (SI floats / arrays; one entry per current)."""

    current: np.ndarray  #: I, [A]
    gap_field: np.ndarray  #: H_g at the mean gap radius, [A/m]
    gap_flux_density: np.ndarray  #: B_g at the mean gap radius, [T]
    yield_stress: np.ndarray  #: tau_y(H_g), [Pa]
    flux_linkage: np.ndarray  #: lambda, [Wb]
    core_flux: np.ndarray  #: Phi_c, [Wb]
    gap_flux: np.ndarray  #: flux crossing one gap under the pole face, [Wb]
    leakage_fraction: np.ndarray  #: 1 - gap flux / core flux, [-]
    part_flux_density: dict  #: part -> |B| [T] (the largest in the part)
    part_field: dict  #: part -> |H| [A/m]
    saturated: np.ndarray  #: bool: some part past the knee of its curve
    mmf_drops: dict = field(default_factory=dict)  #: element -> MMF [A] (core, poles, gaps, housing)


class MagneticCircuit:
    """The reluctance network of a head with its steel and fluid (SI kernel; pint at :mod:`erdesign.magnetics.api`).

    Parameters
    ----------
    head : PistonHead
    steel : BHCurve
        Core, poles and housing (one steel).
    fluid : BHCurve
        The MR fluid's B-H curve.
    yield_law : FieldLaw
        The fluid's yield stress against field strength (control in A/m).
    temperature : float
        Copper temperature for the resistance, [degC].
    """

    def __init__(
        self,
        head: PistonHead,
        steel: BHCurve,
        fluid: BHCurve,
        yield_law: FieldLaw,
        *,
        temperature: float = 20.0,
        name: str = "",
    ) -> None:
        if yield_law.control_unit != "A/m":
            raise ErdesignError(
                f"magnetic circuit: the fluid's yield curve must be against field strength (A/m), "
                f"got a control in {yield_law.control_unit}"
            )
        self.head = head
        self.steel = steel
        self.fluid = fluid
        self.yield_law = yield_law
        self.temperature = float(temperature)
        self.name = name
        r = head
        self._A_core = math.pi * r.core_radius**2
        self._A_wall = math.pi * (r.housing_outer_radius**2 - r.housing_inner_radius**2)
        self._A_annulus = math.pi * (r.housing_inner_radius**2 - r.pole_radius**2)
        a, b = r.core_radius, r.pole_radius
        # integrals of 2 pi r f and 2 pi r f^2 over the window, f = (r - a)/(b - a)
        self._W1 = 2 * math.pi * (b - a) * (a / 2 + (b - a) / 3)
        self._W2 = 2 * math.pi * (b - a) * (a / 3 + (b - a) / 4)

    # ------------------------------------------------------------------ kernel
    @staticmethod
    def _quad(a: float, b: float, g, Phi):
        """int_a^b g(r, Phi) dr for an array Phi (Gauss-Legendre)."""
        r = _col(0.5 * (a + b)) + _col(0.5 * (b - a)) * _GL_X
        vals = g(r, np.asarray(Phi, dtype=float)[..., None])
        return 0.5 * (b - a) * np.sum(vals * _GL_W, axis=-1)

    def _network(self, Hg) -> dict:
        """Every flux and MMF of the network at gap fields Hg [A/m] (array)."""
        r = self.head
        Hg = np.asarray(Hg, dtype=float)
        Lp, Lc, h = r.pole_length, r.coil_length, r.gap
        Ri, Ro, Rp, rc, rm = (
            r.housing_inner_radius,
            r.housing_outer_radius,
            r.pole_radius,
            r.core_radius,
            r.mean_gap_radius,
        )
        Hs, Hf = self.steel.H_of_B, self.fluid.H_of_B
        # columns of the geometry for the integrands (a batch of heads: one row per head)
        Lp_, h_, Ro_, Ri_, rc_ = _col(Lp), _col(h), _col(Ro), _col(Ri), _col(rc)
        Bg = self.fluid.B_of_H(Hg)
        Phi_g = 2 * math.pi * rm * Lp * Bg
        F_gap = self._quad(Rp, Ri, lambda rr, P: Hf(P / (2 * math.pi * rr * Lp_)), Phi_g)
        # fringing at the outer end: fluid paths h + pi s / 2 from the end face (depth s <= R_p) to the housing
        Phi_fo = (
            2
            * math.pi
            * rm
            * self._quad(0.0, Rp, lambda ss, F: self.fluid.B_of_H(F / (h_ + 0.5 * math.pi * ss)), F_gap)
        )
        # fringing on the coil side: a quarter circle through the winding (mu0) and the gap (fluid, chord mu)
        mu_g = np.where(Hg > 0, Bg / np.where(Hg > 0, Hg, 1.0), MU0 * self.fluid.initial_relative_permeability())
        x_c = np.minimum(0.5 * Lc, Rp - rc)
        Phi_fc = 2 * math.pi * rm * F_gap * (2 * MU0 / math.pi) * np.log1p(math.pi * x_c / (2 * MU0 * h / mu_g))
        Phi_e = Phi_g + Phi_fo + Phi_fc
        F_hp = self._quad(
            Ri, Ro, lambda rr, P: Hs(P * (Ro_**2 - rr**2) / (Ro_**2 - Ri_**2) / (2 * math.pi * rr * Lp_)), Phi_e
        )
        B_wall = Phi_e / self._A_wall
        F_wall = Hs(B_wall) * (Lc + Lp)
        F_e = 2 * (F_gap + F_hp) + F_wall
        Phi_ax = self.fluid.B_of_H(F_e / Lc) * self._A_annulus
        Phi_w = MU0 * F_e / Lc * self._W1
        Phi_c = Phi_e + Phi_ax + Phi_w
        B_core = Phi_c / self._A_core
        F_core = Hs(B_core) * (Lc + Lp)
        F_pole = self._quad(0.0, rc, lambda rr, P: Hs(P * rr / (2 * math.pi * rc_**2 * Lp_)), Phi_c) + self._quad(
            rc, Rp, lambda rr, P: Hs(P / (2 * math.pi * rr * Lp_)), Phi_c
        )
        NI = F_core + 2 * F_pole + F_e
        linkage = r.turns * (Phi_e + Phi_ax + MU0 * F_e / Lc * self._W2)
        parts_B = {
            "core": np.abs(B_core),
            "pole": np.abs(Phi_c / (2 * math.pi * rc * Lp)),
            "gap": np.abs(Bg),
            "housing_at_pole": np.abs(Phi_e / (2 * math.pi * Ri * Lp)),
            "housing_wall": np.abs(B_wall),
        }
        return dict(
            NI=NI,
            Bg=Bg,
            Phi_g=Phi_g,
            Phi_e=Phi_e,
            Phi_c=Phi_c,
            linkage=linkage,
            parts_B=parts_B,
            mmf={"core": F_core, "poles": 2 * F_pole, "gaps": 2 * F_gap, "housing": 2 * F_hp + F_wall},
        )

    def _part_fields(self, parts_B: dict) -> dict:
        return {k: np.abs(self.fluid.H_of_B(B) if k == "gap" else self.steel.H_of_B(B)) for k, B in parts_B.items()}

    def _knee_fields(self) -> dict:
        Hs_knee = self.steel.knee()[1]
        Hf_knee = self.fluid.knee()[1]
        return {k: (Hf_knee if k == "gap" else Hs_knee) for k in PARTS}

    def solve_gap_field(self, current) -> np.ndarray:
        """Gap field H_g [A/m] at coil currents I [A] (array; |I| is used, the circuit being odd)."""
        NI = self.head.turns * np.abs(np.asarray(current, dtype=float))
        if isinstance(self.head, HeadBatch):
            return self._solve_batch(NI)
        out = np.zeros_like(NI)
        on = NI > 0
        if np.any(on):
            target = NI[on]
            hi = target / (2 * self.head.gap)  # all the MMF across the two gaps: NI(hi) >= target

            def f(Hg, t):  # relative residual: one tolerance fits every current of the batch
                return self._network(Hg)["NI"] / t - 1.0

            res = elementwise.find_root(
                f, (np.zeros_like(target), hi), args=(target,), tolerances={"xrtol": 1e-12, "fatol": 1e-11}
            )
            if not np.all(res.success):  # pragma: no cover - the bracket is valid by construction
                raise ErdesignError("magnetic circuit: the operating point did not converge")
            out[on] = res.x
        return out

    def _solve_batch(self, NI) -> np.ndarray:
        """Gap fields of a batch of heads, each at its own ampere-turns NI (full arrays, no compression of the
        converged elements, so that every head keeps its row): Illinois regula falsi on [0, NI/2h]."""
        NI = np.broadcast_to(np.asarray(NI, dtype=float), np.shape(self.head.gap)).copy()
        on = NI > 0
        target = np.where(on, NI, 1.0)
        lo = np.zeros_like(target)
        hi = target / (2 * self.head.gap)
        f_lo = -np.ones_like(target)
        f_hi = self._network(hi)["NI"] / target - 1.0
        x = hi.copy()
        side = np.zeros(target.shape, dtype=int)
        for _ in range(200):
            x = np.where(f_hi != f_lo, hi - f_hi * (hi - lo) / (f_hi - f_lo), 0.5 * (lo + hi))
            x = np.clip(x, lo, hi)
            fx = self._network(x)["NI"] / target - 1.0
            if np.max(np.abs(fx)) < 1e-11:
                break
            left = fx < 0  # the root lies above x
            lo, f_lo, hi, f_hi = (
                np.where(left, x, lo),
                np.where(left, fx, f_lo),
                np.where(left, hi, x),
                np.where(left, f_hi, fx),
            )
            # Illinois: halve the value kept at the end that stays twice running
            f_hi = np.where(left & (side == 1), 0.5 * f_hi, f_hi)
            f_lo = np.where(~left & (side == -1), 0.5 * f_lo, f_lo)
            side = np.where(left, 1, -1)
        return np.where(on, x, 0.0)

    def state(self, current) -> CircuitState:
        """The solved circuit at coil currents I [A] (float or array)."""
        I = np.atleast_1d(np.asarray(current, dtype=float))
        Hg = self.solve_gap_field(I)
        net = self._network(Hg)
        parts_H = self._part_fields(net["parts_B"])
        knee = self._knee_fields()
        saturated = np.zeros(I.shape, dtype=bool)
        for k in PARTS:
            saturated |= parts_H[k] > knee[k]
        tau = np.asarray(self.yield_law.yield_stress(Hg), dtype=float)
        flux_linkage = np.sign(I) * net["linkage"]
        return CircuitState(
            current=I,
            gap_field=np.sign(I) * Hg,
            gap_flux_density=np.sign(I) * net["Bg"],
            yield_stress=tau,
            flux_linkage=flux_linkage,
            core_flux=np.sign(I) * net["Phi_c"],
            gap_flux=np.sign(I) * net["Phi_g"],
            leakage_fraction=np.where(
                net["Phi_c"] > 0, 1.0 - net["Phi_g"] / np.where(net["Phi_c"] > 0, net["Phi_c"], 1.0), 0.0
            ),
            part_flux_density=net["parts_B"],
            part_field=parts_H,
            saturated=saturated,
            mmf_drops=net["mmf"],
        )

    # ------------------------------------------------------------------ coil
    @property
    def resistance(self) -> float:
        """DC resistance of the coil at :attr:`temperature`, [ohm]."""
        r = self.head
        return coil_resistance(r.turns, r.wire_diameter, r.core_radius, r.pole_radius, self.temperature)

    def inductance(self, current) -> np.ndarray:
        """Secant inductance lambda(I)/I [H] (its small-current limit at I = 0)."""
        I = np.abs(np.atleast_1d(np.asarray(current, dtype=float)))
        small = 1e-6 / self.head.turns
        Ie = np.where(I > small, I, small)
        lam = self._network(self.solve_gap_field(Ie))["linkage"]
        return lam / Ie

    def incremental_inductance(self, current) -> np.ndarray:
        """d lambda / d I [H] (central difference, 0.1 % of the current)."""
        I = np.abs(np.atleast_1d(np.asarray(current, dtype=float)))
        dI = np.maximum(1e-3 * I, 1e-6)
        lo = np.maximum(I - dI, 0.0)
        hi = I + dI
        lam = self._network(self.solve_gap_field(np.concatenate([lo, hi])))["linkage"]
        n = I.size
        return (lam[n:] - lam[:n]) / (hi - lo)

    def time_constant(self, current) -> np.ndarray:
        """L(I)/R [s] with the secant inductance."""
        return self.inductance(current) / self.resistance

    # ------------------------------------------------------------------ saturation
    def _sweep(self, H_max: float = 2e6, n: int = 800) -> dict:
        Hg = np.concatenate([[0.0], np.geomspace(10.0, H_max, n)])
        net = self._network(Hg)
        return dict(Hg=Hg, I=net["NI"] / self.head.turns, Bg=net["Bg"], parts_H=self._part_fields(net["parts_B"]))

    def part_knee_currents(self) -> dict:
        """part -> coil current [A] at which the part reaches the knee of its B-H curve (inf if beyond 2 MA/m gap
        field)."""
        sw = self._sweep()
        knee = self._knee_fields()
        out = {}
        for k in PARTS:
            ratio = sw["parts_H"][k] / knee[k]
            above = np.nonzero(ratio >= 1.0)[0]
            if above.size == 0:
                out[k] = math.inf
                continue
            j = int(above[0])
            t = (1.0 - ratio[j - 1]) / (ratio[j] - ratio[j - 1])
            out[k] = float(sw["I"][j - 1] + t * (sw["I"][j] - sw["I"][j - 1]))
        return out

    def limiting_part(self) -> str | None:
        """The part that reaches its knee at the lowest current (where the flux saturates first), or None."""
        knees = self.part_knee_currents()
        k = min(knees, key=knees.get)
        return None if math.isinf(knees[k]) else k

    def knee_current(self) -> float:
        """Current [A] where dB_gap/dI has fallen to half its small-current value: the knee of B_gap(I)."""
        sw = self._sweep()
        return _curve_knee(sw["I"], sw["Bg"])


def _curve_knee(I: np.ndarray, B: np.ndarray) -> float:
    """First current where the slope dB/dI of a monotone curve falls to half its initial slope (linear interp)."""
    I = np.asarray(I, dtype=float)
    B = np.asarray(B, dtype=float)
    slope = np.diff(B) / np.diff(I)
    mid = 0.5 * (I[1:] + I[:-1])
    s0 = slope[0]
    below = np.nonzero(slope <= 0.5 * s0)[0]
    if below.size == 0:
        return math.inf
    j = int(below[0])
    if j == 0:
        return float(mid[0])
    t = (slope[j - 1] - 0.5 * s0) / (slope[j - 1] - slope[j])
    return float(mid[j - 1] + t * (mid[j] - mid[j - 1]))
