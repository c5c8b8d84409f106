r"""Vectorised evaluation of candidate damper geometries: figures, non-dimensional groups and constraint margins.

Every candidate is a set of SI arrays (gap ``h``, duct length ``L``, mean diameter ``d``, piston ``Dp``, rod
``dr``, ``n`` ducts) evaluated at every design point by the quasi-steady kernel of :mod:`erdesign.damper.quasi_steady`,
vectorised over the candidates, with no Python loop per design and no :class:`~erdesign.damper.Damper` object per
candidate.  :meth:`erdesign.damper.Damper.state` calls the same kernel, so that a design re-checked with
:meth:`~erdesign.damper.Damper.size` gives the same numbers (tests/test_design.py checks it).

Valve damper (Makris et al. 1996, eqs 1, 7 corrected, 14), per duct :math:`Q = v A_p / n`:

.. math::
    F = \Delta p(Q, \tau_y, \eta)\,A_p + F_s, \qquad F_0 = \Delta p(Q, 0, \eta_0)\,A_p + F_s, \qquad
    \mathrm{Re} = \frac{\bar u h \rho}{\eta}, \quad \bar u = \frac{Q}{\pi d h}

(at zero field :math:`\Delta p = 12\eta_0 L Q/(\pi d h^3)`, Makris eq 4).  Mixed damper (Kamath and Wereley 1997,
section II): pressure plus shear drag, with :math:`\bar u = \max(v A_p/(\pi d h), v)`.

Non-dimensional groups reported for each design (why a design behaves as it does): the Bingham number
:math:`\mathrm{Bi} = \tau_y h/(\eta \bar u)` (yield over viscous stress; Bi >> 1: the field dominates, large dynamic
range), the plug fraction :math:`\phi` (0 fully yielded, 1 blocked) and the thin-gap ratio :math:`h/d`.

Constraint margins are relative: :math:`m = x/x_\text{min} - 1` for a lower limit and :math:`m = 1 - x/x_\text{max}`
for an upper one, so that :math:`m \ge 0` is met and :math:`-m` is the shortfall as a fraction of the limit.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from .._util import scalar_or_array
from ..damper.quasi_steady import CRITICAL_REYNOLDS, QuasiSteadyState, mixed_state, valve_state
from ..flow.areas import piston_area
from ..geometry import THIN_GAP_LIMIT, mixed_mean_diameter
from . import envelope
from .figures import FIGURES, OBJECTIVES, Figure

if TYPE_CHECKING:  # pragma: no cover
    from .requirements import Requirements

__all__ = [
    "PointFigures",
    "valve_point_figures",
    "mixed_point_figures",
    "CandidateFigures",
    "Constraint",
    "Figure",
    "constraints_for",
    "evaluate_candidates",
    "FIGURES",
    "OBJECTIVES",
]


class PointFigures(NamedTuple):
    """Quasi-steady figures of candidate designs at one design point, SI arrays."""

    force: np.ndarray
    """Force at the field, seal friction included, [N]."""
    zero_field_force: np.ndarray
    """Force at zero field, [N]."""
    pressure_drop: np.ndarray
    """Pressure drop across the piston at the field, [Pa]."""
    zero_field_pressure_drop: np.ndarray
    """Pressure drop at zero field, [Pa]."""
    plug_fraction: np.ndarray
    """Plug thickness over gap at the field, [-]."""
    reynolds: np.ndarray
    """Reynolds number (Makris eq 1) at the field, [-]."""
    zero_field_reynolds: np.ndarray
    """Reynolds number at zero field (lower viscosity, so usually the larger), [-]."""
    bingham_number: np.ndarray
    """tau_y h / (eta u), [-]."""


def valve_point_figures(v, tau_y, eta, eta0, rho, seal_friction, h, L, d, Ap, n):
    r"""Force, zero-field force and flow groups of valve dampers at one design point (vectorised).

    .. math::
        Q = \frac{v A_p}{n}, \quad F = \Delta p\,A_p + F_s, \quad F_0 = \frac{12\eta_0 L Q}{\pi d h^3}A_p + F_s,
        \quad \mathrm{Re} = \frac{\bar u h\rho}{\eta}, \quad \mathrm{Bi} = \frac{\tau_y h}{\eta\bar u},
        \quad \bar u = \frac{Q}{\pi d h}

    F, Re and F_0 are :func:`erdesign.damper.quasi_steady.valve_state` (thin gap) at the field and at zero field; this
    function adds the Bingham number.

    Parameters
    ----------
    v : float
        Piston velocity, [m/s], > 0.
    tau_y : float
        Yield stress at the field, [Pa].
    eta, eta0 : float
        Plastic viscosity at the field and at zero field, [Pa s].
    rho : float
        Density, [kg/m^3].
    seal_friction : float
        Seal friction F_s, [N].
    h, L, d : float or array
        Gap, duct length, duct mean diameter, [m].
    Ap : float or array
        Piston area, [m^2].
    n : int or array
        Number of ducts in parallel.

    Returns
    -------
    PointFigures

    Notes
    -----
    Thin gap (parallel plates), laminar, quasi-steady; see :mod:`erdesign.flow.bingham`.  The candidate search
    keeps :math:`h/d \le 0.1` (a constraint), where :class:`~erdesign.damper.Damper` also uses the thin gap.

    Examples
    --------
    Makris's damper at 1 in/s and 3 kV/mm (Makris et al. 1996; 6.07 kN as ``erdesign size`` gives):

    >>> from math import pi
    >>> Ap = pi / 4 * (0.0334**2 - 0.01125**2)
    >>> r = valve_point_figures(0.0254, 1800.0, 13.0, 7.0, 1290.0, 112.0, 0.0008, 0.0546, 0.0143, Ap, 1)
    >>> round(r.force / 1e3, 2), round(r.force / r.zero_field_force, 2), round(r.bingham_number, 2)
    (6.07, 1.92, 0.2)

    Bi = 0.2 and a plug of 3 % of the gap: at 1 in/s this duct is viscous-dominated, and most of its dynamic
    range comes from the viscosity rising from 7 to 13 Pa s with the field (Makris et al. 1996, section 3).

    References
    ----------
    Makris et al. (1996), eqs 1, 4, 7 (with h^3) and 14.
    """
    s = valve_state(v, tau_y, eta, rho, seal_friction, h, L, d, Ap, n)
    s0 = valve_state(v, 0.0, eta0, rho, seal_friction, h, L, d, Ap, n)
    return _point_figures(s, s0, h)


def _point_figures(s: QuasiSteadyState, s0: QuasiSteadyState, h) -> PointFigures:
    """The figures of the kernel's states at the field (``s``) and at zero field (``s0``), and Bi."""
    with np.errstate(divide="ignore", invalid="ignore"):
        bingham = s.yield_stress * h / (s.viscosity * s.mean_velocity)
    return PointFigures._make(
        scalar_or_array(a)
        for a in (
            s.force,
            s0.force,
            s.pressure_drop,
            s0.pressure_drop,
            s.plug_fraction,
            s.reynolds,
            s0.reynolds,
            bingham,
        )
    )


def mixed_point_figures(v, tau_y, eta, eta0, rho, seal_friction, h, L, Dp, dr):
    r"""Force, zero-field force and flow groups of mixed-mode (moving-electrode) dampers at one point (vectorised).

    .. math::
        F = \Delta p\,A_p - \tau_0\,\pi D_p L + F_s, \quad
        \bar u = \max\!\left(\frac{v A_p}{\pi d h}, v\right), \quad d = D_p + h

    F, Re and F_0 are :func:`erdesign.damper.quasi_steady.mixed_state` at the field and at zero field (:math:`\Delta p,
    \tau_0` from :func:`erdesign.flow.mixed_mode.mixed_mode_damper_force`); Re and Bi as in
    :func:`valve_point_figures` with this :math:`\bar u`.

    Parameters
    ----------
    v, tau_y, eta, eta0, rho, seal_friction
        As in :func:`valve_point_figures`.
    h : float or array
        Gap between head and cylinder, [m].
    L : float or array
        Length of the piston head (electrode), [m].
    Dp, dr : float or array
        Head and rod diameters, [m].

    Returns
    -------
    PointFigures

    Notes
    -----
    Each element is a bracketed root (about 5 us per element on one core), two orders slower than the closed
    form of the valve damper; the zero-field figures are closed form.

    Examples
    --------
    >>> r = mixed_point_figures(0.05, 2000.0, 0.1, 0.1, 1200.0, 0.0, 1e-3, 0.02, 0.03, 0.01)
    >>> round(r.force, 1), round(r.plug_fraction, 2)
    (71.1, 0.76)

    References
    ----------
    Kamath and Wereley (1997), section II; docs/theory/mixed_mode.md.
    """
    d = mixed_mean_diameter(Dp, h)
    s = mixed_state(v, tau_y, eta, rho, seal_friction, h, L, d, Dp, dr)
    s0 = mixed_state(v, 0.0, eta0, rho, seal_friction, h, L, d, Dp, dr)
    return _point_figures(s, s0, h)


@dataclass(frozen=True)
class CandidateFigures:
    """Figures of N candidate designs at P design points, SI arrays (shape (N,) or (P, N)).

    ``margins`` has one row per constraint of :func:`constraints_for` (shape (C, N)); ``feasible`` is True where
    the geometry is valid and every margin is >= 0.
    """

    gap: np.ndarray
    duct_length: np.ndarray
    duct_mean_diameter: np.ndarray
    piston_diameter: np.ndarray
    rod_diameter: np.ndarray
    ducts: np.ndarray
    valid: np.ndarray
    """Geometry is buildable: rod thinner than piston, gap smaller than the mean diameter, all positive."""
    piston_area: np.ndarray
    gap_ratio: np.ndarray
    fluid_volume: np.ndarray
    total_fluid_volume: np.ndarray
    outer_diameter: np.ndarray
    length: np.ndarray
    force: np.ndarray
    zero_field_force: np.ndarray
    controllable_force: np.ndarray
    dynamic_range: np.ndarray
    pressure_drop: np.ndarray
    zero_field_pressure_drop: np.ndarray
    plug_fraction: np.ndarray
    reynolds: np.ndarray
    zero_field_reynolds: np.ndarray
    bingham_number: np.ndarray
    voltage: np.ndarray
    """Electrode voltage E h (ER; the control times the gap for other controls; with a coil, the coil's I R), [V]."""
    margins: np.ndarray
    # with [design.coil] (erdesign.design.coil), else None
    turns: np.ndarray | None = None
    wire_diameter: np.ndarray | None = None
    core_diameter: np.ndarray | None = None
    pole_length: np.ndarray | None = None
    housing_outer_diameter: np.ndarray | None = None
    yield_stress: np.ndarray | None = None
    """(P, N) [Pa]."""
    gap_flux_density: np.ndarray | None = None
    """(P, N) [T]."""
    current_density: np.ndarray | None = None
    """(P, N) [A/m^2]."""
    saturation: np.ndarray | None = None
    """(P, N): largest H_part / H_knee."""
    fill_factor: np.ndarray | None = None
    coil_resistance: np.ndarray | None = None
    coil_power: np.ndarray | None = None
    time_constant: np.ndarray | None = None

    @property
    def feasible(self) -> np.ndarray:
        return self.valid & np.all(self.margins >= 0.0, axis=0)

    def __len__(self) -> int:
        return self.gap.shape[0]

    def figure(self, name: str) -> np.ndarray:
        """Figure ``name`` of :data:`FIGURES` for every candidate (at the first design point), shape (N,)."""
        fig = FIGURES[name]
        value = getattr(self, fig.attribute)
        return value[0] if fig.per_point else value

    def take(self, index) -> "CandidateFigures":
        """The candidates selected by ``index`` (integer or boolean array)."""
        out = {}
        for key, value in self.__dict__.items():
            if value is None:
                out[key] = None
                continue
            out[key] = value[..., index] if value.ndim == 2 else value[index]
        return CandidateFigures(**out)


class Constraint(NamedTuple):
    """One requirement as a constraint on candidate designs."""

    name: str
    """Shown in ``active_constraints`` and ``conflicts``: the requirement's key, with its point if any."""
    value: Callable[[CandidateFigures], np.ndarray]
    """The constrained quantity of every candidate, SI, shape (N,)."""
    limit: float
    upper: bool
    """True: value <= limit; False: value >= limit."""
    unit: str
    """Unit to show value and limit in (pint), e.g. ``"kN"``."""
    scale: float
    """SI value of one ``unit`` (1000 for kN), for messages."""

    def margin(self, figures: CandidateFigures) -> np.ndarray:
        """Relative margin, >= 0 when met: 1 - value/limit (upper) or value/limit - 1 (lower)."""
        ratio = self.value(figures) / self.limit
        return 1.0 - ratio if self.upper else ratio - 1.0


def _per_point(attribute: str, i: int):
    return lambda f: getattr(f, attribute)[i]


def _peak(a: str, b: str, i: int, absolute: bool = True):
    if absolute:
        return lambda f: np.maximum(np.abs(getattr(f, a)[i]), np.abs(getattr(f, b)[i]))
    return lambda f: np.maximum(getattr(f, a)[i], getattr(f, b)[i])


def constraints_for(req: "Requirements") -> tuple[Constraint, ...]:
    """The constraints a requirements set puts on candidate designs, in a fixed order."""
    out: list[Constraint] = []
    unit = req.fluid.field_unit
    from ..units import Q_

    field_scale = float(Q_(1.0, unit).to(req.fluid.control_unit).magnitude)
    for i, p in enumerate(req.points):
        tag = f" (point {i + 1})"
        if p.min_force is not None:
            out.append(Constraint("min_force" + tag, _per_point("force", i), p.min_force, False, "kN", 1e3))
        if p.min_dynamic_range is not None:
            out.append(
                Constraint(
                    "min_dynamic_range" + tag, _per_point("dynamic_range", i), p.min_dynamic_range, False, "", 1.0
                )
            )
        if p.max_zero_field_force is not None:
            out.append(
                Constraint(
                    "max_zero_field_force" + tag,
                    _per_point("zero_field_force", i),
                    p.max_zero_field_force,
                    True,
                    "kN",
                    1e3,
                )
            )
        if req.limits.max_pressure is not None:
            out.append(
                Constraint(
                    "max_pressure" + tag,
                    _peak("pressure_drop", "zero_field_pressure_drop", i),
                    req.limits.max_pressure,
                    True,
                    "MPa",
                    1e6,
                )
            )
        if req.limits.laminar:
            out.append(
                Constraint(
                    "laminar" + tag,
                    _peak("reynolds", "zero_field_reynolds", i, absolute=False),
                    CRITICAL_REYNOLDS,
                    True,
                    "",
                    1.0,
                )
            )
        if req.limits.max_field is not None:
            out.append(
                Constraint(
                    "max_field" + tag,
                    (lambda f, E=p.field: np.full(len(f), E)),
                    req.limits.max_field,
                    True,
                    unit,
                    field_scale,
                )
            )
        if req.limits.max_voltage is not None:
            out.append(
                Constraint("max_voltage" + tag, _per_point("voltage", i), req.limits.max_voltage, True, "kV", 1e3)
            )
    if req.coil is not None:
        out += _coil_constraints(req)
    lim = req.limits
    if lim.max_outer_diameter is not None:
        out.append(
            Constraint("max_outer_diameter", lambda f: f.outer_diameter, lim.max_outer_diameter, True, "mm", 1e-3)
        )
    if lim.max_length is not None:
        out.append(Constraint("max_length", lambda f: f.length, lim.max_length, True, "mm", 1e-3))
    if lim.min_gap is not None:
        out.append(Constraint("min_gap", lambda f: f.gap, lim.min_gap, False, "mm", 1e-3))
    out.append(Constraint("thin_gap", lambda f: f.gap_ratio, THIN_GAP_LIMIT, True, "", 1.0))
    if req.configuration == "valve" and req.envelope.duct_placement == "around":
        wall = req.envelope.wall
        out.append(
            Constraint(
                "duct_around_cylinder",
                lambda f: envelope.duct_clearance_ratio(f.piston_diameter, f.gap, f.duct_mean_diameter, wall),
                1.0,
                False,
                "",
                1.0,
            )
        )
    return tuple(out)


def _coil_constraints(req: "Requirements") -> list[Constraint]:
    c = req.coil
    out: list[Constraint] = []
    for i, p in enumerate(req.points):
        if p.field == 0:
            continue
        tag = f" (point {i + 1})"
        if c.supply_voltage is not None:
            out.append(
                Constraint("coil.supply_voltage" + tag, _per_point("voltage", i), c.supply_voltage, True, "V", 1.0)
            )
        out.append(
            Constraint(
                "coil.max_current_density" + tag,
                _per_point("current_density", i),
                c.max_current_density,
                True,
                "A/mm^2",
                1e6,
            )
        )
        if not c.allow_saturation:
            out.append(Constraint("coil.saturation" + tag, _per_point("saturation", i), 1.0, True, "x knee", 1.0))
    out.append(Constraint("coil.max_fill_factor", lambda f: f.fill_factor, c.max_fill_factor, True, "", 1.0))
    if c.max_power is not None:
        out.append(Constraint("coil.max_power", lambda f: f.coil_power, c.max_power, True, "W", 1.0))
    if c.max_time_constant is not None:
        out.append(
            Constraint("coil.max_time_constant", lambda f: f.time_constant, c.max_time_constant, True, "ms", 1e-3)
        )
    return out


def evaluate_candidates(
    req: "Requirements",
    gap,
    duct_length,
    duct_mean_diameter,
    piston_diameter,
    rod_diameter,
    ducts,
    constraints: tuple[Constraint, ...] | None = None,
    coil=None,
) -> CandidateFigures:
    r"""Figures and constraint margins of N candidate geometries at every design point of ``req`` (vectorised).

    Parameters
    ----------
    req : Requirements
        Fluid, configuration, design points, limits and envelope.
    gap, duct_length, piston_diameter, rod_diameter : array
        Candidate geometry, [m], shape (N,).
    duct_mean_diameter : array or None
        [m]; ignored for a mixed damper (it is ``piston_diameter + gap``).
    ducts : array
        Number of ducts, whole numbers (1 for mixed).
    constraints : tuple of Constraint, optional
        :func:`constraints_for(req) <constraints_for>` (pass it when calling repeatedly).
    coil : dict of str -> array, optional
        With ``[design.coil]``: ``turns``, ``wire_diameter``, ``core_diameter``, ``pole_length``,
        ``housing_outer_diameter`` of each candidate (:mod:`erdesign.design.coil`); the yield stress at each point
        then follows each candidate's magnetic circuit.

    Returns
    -------
    CandidateFigures
        Shape (N,) geometric figures, (P, N) point figures, (C, N) margins.

    Notes
    -----
    Invalid geometries (rod not thinner than the piston, gap not smaller than the mean diameter, a non-positive
    length) are evaluated with a placeholder geometry so that the kernels never see them; their margins are NaN
    and ``valid`` is False.  Memory is about 40 (P + C) bytes per candidate: pass chunks (the search in
    :mod:`erdesign.design.search` uses 65536 by default).
    """
    if constraints is None:
        constraints = constraints_for(req)
    h = np.asarray(gap, dtype=float)
    L = np.asarray(duct_length, dtype=float)
    Dp = np.asarray(piston_diameter, dtype=float)
    dr = np.asarray(rod_diameter, dtype=float)
    mixed = req.configuration == "mixed"
    d = mixed_mean_diameter(Dp, h) if mixed else np.asarray(duct_mean_diameter, dtype=float)
    n = np.ones_like(h) if mixed else np.asarray(ducts, dtype=float)
    h, L, d, Dp, dr, n = np.broadcast_arrays(*(np.atleast_1d(a) for a in (h, L, d, Dp, dr, n)))
    valid = (h > 0) & (L > 0) & (dr >= 0) & (dr < Dp) & (h < d) & (n >= 1)
    all_valid = bool(np.all(valid))
    if not all_valid:  # placeholder geometry, so that no kernel sees an impossible duct
        h, L, d, Dp, dr, n = (
            np.where(valid, a, s) for a, s in zip((h, L, d, Dp, dr, n), (1e-3, 0.05, 0.02, 0.04, 0.01, 1.0))
        )
    Ap = piston_area(Dp, dr)
    fl, env = req.fluid, req.envelope
    cf = None
    if req.coil is not None:
        from .coil import coil_figures

        if coil is None:
            raise ValueError("evaluate_candidates: requirements with [design.coil] need the coil variables")
        cv = {k: np.broadcast_to(np.asarray(coil[k], dtype=float), h.shape) for k in coil}
        cf = coil_figures(
            req,
            h,
            L,
            d,
            cv["turns"],
            cv["wire_diameter"],
            cv["core_diameter"],
            cv["pole_length"],
            cv["housing_outer_diameter"],
        )
        valid = valid & cf.valid
        all_valid = bool(np.all(valid))
    rows = []
    for i, p in enumerate(req.points):
        tau_y = float(fl.yield_stress_at(p.field)) if cf is None else cf.yield_stress[i]
        eta = float(fl.viscosity_at(p.field)) if cf is None else fl.viscosity
        if mixed:
            rows.append(
                mixed_point_figures(p.velocity, tau_y, eta, fl.viscosity, fl.density, req.seal_friction, h, L, Dp, dr)
            )
        else:
            rows.append(
                valve_point_figures(p.velocity, tau_y, eta, fl.viscosity, fl.density, req.seal_friction, h, L, d, Ap, n)
            )
    if len(rows) == 1:  # a view, no copy (the common case of one design point)
        stacked = {key: np.broadcast_to(getattr(rows[0], key), h.shape)[None, :] for key in PointFigures._fields}
    else:
        stacked = {
            key: np.stack([np.broadcast_to(getattr(r, key), h.shape) for r in rows]) for key in PointFigures._fields
        }
    fields = np.array([p.field for p in req.points])[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        dynamic_range = stacked["force"] / stacked["zero_field_force"]
    figures = CandidateFigures(
        gap=h,
        duct_length=L,
        duct_mean_diameter=d,
        piston_diameter=Dp,
        rod_diameter=dr,
        ducts=n,
        valid=valid,
        piston_area=Ap,
        gap_ratio=h / d,
        fluid_volume=envelope.active_fluid_volume(h, L, d, n),
        total_fluid_volume=envelope.total_fluid_volume(Ap, h, L, d, n, env.stroke, req.configuration),
        outer_diameter=envelope.outer_diameter(Dp, h, d, env.wall, req.configuration, env.duct_placement),
        length=np.broadcast_to(
            envelope.body_length(L, env.stroke, env.head_length, env.end_allowance, req.configuration), h.shape
        ),
        controllable_force=stacked["force"] - stacked["zero_field_force"],
        dynamic_range=dynamic_range,
        voltage=fields * h if cf is None else cf.voltage,
        margins=np.empty((0, h.shape[0])),
        **stacked,
    )
    if cf is not None:
        for key in coil:
            object.__setattr__(figures, key, cv[key])
        for key, value in (
            ("yield_stress", cf.yield_stress),
            ("gap_flux_density", cf.gap_flux_density),
            ("current_density", cf.current_density),
            ("saturation", cf.saturation),
            ("fill_factor", cf.fill_factor),
            ("coil_resistance", cf.resistance),
            ("coil_power", cf.power),
            ("time_constant", cf.time_constant),
            ("outer_diameter", cv["housing_outer_diameter"]),
        ):
            object.__setattr__(figures, key, value)
    margins = np.empty((len(constraints), h.shape[0]))
    for j, c in enumerate(constraints):
        margins[j] = c.margin(figures)
    if not all_valid:
        margins[:, ~valid] = np.nan
    object.__setattr__(figures, "margins", margins)
    return figures
