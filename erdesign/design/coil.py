r"""Figures of candidate MR piston heads with their coils: the magnetic circuit of every candidate at once.

With ``[design.coil]`` in a requirements file the design also sizes the poles and the coil (turns, wire, core,
housing), as Gavin, Hoagg and Dobossy (2001) do: the yield stress at each design point is no longer a property of
the fluid at a given field but follows each candidate's magnetic circuit at the point's coil current,

.. math:: \tau_y = \tau_y^\text{fluid}\big(H_g(N I;\ \text{head})\big),

with :math:`H_g` the gap field of the nonlinear reluctance network (:mod:`erdesign.magnetics.circuit`) solved for a
batch of heads (:class:`~erdesign.magnetics.circuit.HeadBatch`), one operating point per candidate.  The head of a
candidate is that of a damper file with this geometry and ``[coil]`` (:func:`erdesign.magnetics.circuit.piston_head`):
head radius :math:`R_p = (d - h)/2`, coil length :math:`L_c = L - 2L_p`, and the housing (the damper's cylinder,
the return path) of outer diameter ``housing_outer_diameter``, which is then the damper's outer diameter.

Figures of the coil at each point's current I: the voltage :math:`IR`, the current density :math:`I/(\pi d_w^2/4)`,
the saturation ratio (largest ratio of a part's field to the field at the knee of its B-H curve; above 1 the part
is saturated), and, at the largest current of the design points (the design current), the power :math:`I^2R` and
the time constant :math:`L/R` with the secant inductance :math:`\lambda/I` (the figures Gavin et al. minimise).
The copper fill factor :math:`N\pi d_w^2/4/((R_p - r_c)L_c)` is a figure of the geometry.
"""

from __future__ import annotations

import functools
import math
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    from .requirements import Requirements

__all__ = ["CoilFigures", "coil_figures", "design_current"]


class CoilFigures(NamedTuple):
    """Coil figures of N candidates at P design points, SI arrays ((N,) or (P, N))."""

    valid: np.ndarray
    """The head can be built: core inside the head, room for the coil between the poles, housing outside the bore."""
    yield_stress: np.ndarray
    """tau_y at each point's current, [Pa], (P, N)."""
    gap_flux_density: np.ndarray
    """B_g at each point's current, [T], (P, N)."""
    voltage: np.ndarray
    """I R at each point, [V], (P, N)."""
    current_density: np.ndarray
    """I / wire cross-section at each point, [A/m^2], (P, N)."""
    saturation: np.ndarray
    """Largest H_part / H_knee at each point's current, [-], (P, N)."""
    fill_factor: np.ndarray
    """Copper fill factor, [-], (N,)."""
    resistance: np.ndarray
    """Coil resistance at 20 degC, [ohm], (N,)."""
    power: np.ndarray
    """I^2 R at the design current, [W], (N,)."""
    time_constant: np.ndarray
    """L/R at the design current, [s], (N,)."""


def design_current(req: "Requirements") -> float:
    """The design current: the largest coil current of the design points, [A]."""
    return max(p.field for p in req.points)


@functools.lru_cache(maxsize=8)
def _materials(material: str, steel: str):
    from .. import materials

    return (
        materials.steel_curve(steel),
        materials.magnetization_curve(material),
        materials.material_fluid(material).yield_curve,
    )


#: Placeholder head (m, turns) evaluated in place of impossible ones, so that no kernel sees them.
_PLACEHOLDER = dict(
    core_radius=0.012,
    pole_radius=0.02,
    gap=1e-3,
    housing_outer_radius=0.026,
    pole_length=0.008,
    coil_length=0.02,
    turns=300.0,
    wire_diameter=5e-4,
)


def coil_figures(
    req: "Requirements", h, L, d, turns, wire_diameter, core_diameter, pole_length, housing_outer_diameter
) -> CoilFigures:
    """Coil figures of N candidates (SI arrays of shape (N,)) at every design point of ``req`` (module notes)."""
    from ..magnetics.circuit import HeadBatch, MagneticCircuit

    steel, fluid_bh, yield_law = _materials(req.coil.material, req.coil.steel)
    head = dict(
        core_radius=0.5 * np.asarray(core_diameter, dtype=float),
        pole_radius=0.5 * (np.asarray(d, dtype=float) - h),
        gap=np.asarray(h, dtype=float),
        housing_outer_radius=0.5 * np.asarray(housing_outer_diameter, dtype=float),
        pole_length=np.asarray(pole_length, dtype=float),
        coil_length=np.asarray(L, dtype=float) - 2.0 * np.asarray(pole_length, dtype=float),
        turns=np.asarray(turns, dtype=float),
        wire_diameter=np.asarray(wire_diameter, dtype=float),
    )
    n = np.broadcast_shapes(*(np.shape(v) for v in head.values()))
    head = {k: np.broadcast_to(v, n).astype(float) for k, v in head.items()}
    valid = (
        (head["core_radius"] > 0)
        & (head["core_radius"] < head["pole_radius"])
        & (head["coil_length"] > 0)
        & (head["housing_outer_radius"] > head["pole_radius"] + head["gap"])
        & (head["gap"] > 0)
        & (head["turns"] >= 1)
        & (head["wire_diameter"] > 0)
    )
    if not np.all(valid):
        head = {k: np.where(valid, v, _PLACEHOLDER[k]) for k, v in head.items()}
    batch = HeadBatch(**head)
    circuit = MagneticCircuit(batch, steel, fluid_bh, yield_law)
    R = np.asarray(circuit.resistance, dtype=float) * np.ones(n)
    wire_area = math.pi * head["wire_diameter"] ** 2 / 4.0
    knee = circuit._knee_fields()
    solved: dict[float, tuple] = {}
    rows = []
    for p in req.points:
        I = float(abs(p.field))
        if I not in solved:
            if I == 0.0:
                zero = np.zeros(n)
                solved[I] = (zero, zero, zero, zero)
            else:
                st = circuit.state(np.full(n, I))
                sat = np.max([st.part_field[k] / knee[k] for k in knee], axis=0)
                solved[I] = (
                    np.asarray(st.yield_stress, dtype=float),
                    np.abs(st.gap_flux_density),
                    sat,
                    np.abs(st.flux_linkage),
                )
        tau, B, sat, linkage = solved[I]
        rows.append((tau, B, I * R, I / wire_area, sat))
    I_d = design_current(req)
    linkage = solved[float(abs(I_d))][3]
    L_over_R = linkage / I_d / R if I_d > 0 else np.full(n, np.nan)
    stack = [np.stack([r[j] for r in rows]) for j in range(5)]
    return CoilFigures(
        valid=valid,
        yield_stress=stack[0],
        gap_flux_density=stack[1],
        voltage=stack[2],
        current_density=stack[3],
        saturation=stack[4],
        fill_factor=batch.fill_factor * np.ones(n),
        resistance=R,
        power=I_d**2 * R,
        time_constant=L_over_R,
    )
