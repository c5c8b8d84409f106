"""The validity checks of a damper design: where the quasi-steady model of erdesign holds, and where it does not.

Each check has a status ``pass``, ``warn`` or ``info`` (nothing to check against):

* laminar flow: the largest Reynolds number of the curves below 2300 (Makris eq 1);
* thin gap: h/d at most :data:`~erdesign.geometry.THIN_GAP_LIMIT` (the thin-gap error is shown);
* field range: every control asked for inside the fluid's characterised range (materials ``[range]``);
* plug: plug fraction at the design velocity and the largest control at most :data:`PLUG_FRACTION_LIMIT`;
* seal friction: its share of the zero-field force at the design velocity at most :data:`SEAL_SHARE_LIMIT`.

The report (section 4, :func:`erdesign.report.build_report`) and the app's Size page show them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..formatting import Shown, show
from ..geometry import THIN_GAP_LIMIT
from ..units import Q_
from .curves import ForceVelocityCurves
from .damper import Damper
from .quasi_steady import CRITICAL_REYNOLDS

__all__ = ["Check", "validity_checks", "PLUG_FRACTION_LIMIT", "SEAL_SHARE_LIMIT"]


#: Plug fraction above which the report warns: each sheared layer is then thinner than 5 % of the gap, the force
#: is set almost wholly by the yield stress, and pre-yield elasticity (Makris eq 8), which the quasi-steady
#: Bingham flow leaves out, shapes the response.  A modelling judgement, not a published limit.
PLUG_FRACTION_LIMIT = 0.9
#: Share of the zero-field force taken by seal friction above which the report warns: the off-state force, and so
#: the dynamic range, then depends mostly on the seals, which the model treats as a constant Coulomb force.
SEAL_SHARE_LIMIT = 0.2


@dataclass(frozen=True)
class Check:
    """A validity check."""

    key: str
    name: str
    status: str
    """``"pass"``, ``"warn"`` or ``"info"`` (nothing to check against)."""
    value: Shown | None
    limit: Shown | None
    detail: str
    source: str


def validity_checks(
    damper: Damper, sweep: ForceVelocityCurves, fields: np.ndarray, v_design: float, field_design: float | None = None
) -> tuple[Check, ...]:
    """The validity checks of a design (module notes): the report's section 4 and the app's Size page.

    ``sweep`` holds the force-velocity curves on the grid of :func:`erdesign.report.builder.report_grid`; ``fields``
    every control asked for (SI); ``v_design`` the design velocity [m/s] and ``field_design`` the design control (SI;
    default the largest).
    """
    g, fluid = damper.geometry, damper.fluid
    out = []
    re_max = float(np.nanmax(sweep.reynolds))
    out.append(
        Check(
            "laminar",
            "Laminar flow (Reynolds number)",
            "pass" if re_max < CRITICAL_REYNOLDS else "warn",
            show(re_max, "", name="largest Reynolds number"),
            show(CRITICAL_REYNOLDS, "", name="critical Reynolds"),
            "largest Re of the velocity and control sweep"
            + ("" if re_max < CRITICAL_REYNOLDS else ": the laminar gap-flow model does not hold"),
            "Makris et al. (1996), eq 1",
        )
    )
    ratio = g.gap_ratio
    thin_ok = ratio <= THIN_GAP_LIMIT
    detail = f"thin-gap error {g.thin_gap_error * 100:.3g} % of the Newtonian pressure drop"
    if not thin_ok:
        detail += (
            "; the valve flow uses the exact annulus"
            if damper.uses_exact_annulus
            else "; the mixed-mode model keeps the thin-gap form and carries this error"
        )
    out.append(
        Check(
            "thin_gap",
            "Thin gap (h/d)",
            "pass" if thin_ok or damper.uses_exact_annulus else "warn",
            show(ratio, "", name="h/d"),
            show(THIN_GAP_LIMIT, "", name="h/d limit"),
            detail,
            "Bird, Stewart and Lightfoot (2002), eq 2.4-17 (erdesign.flow.newtonian.thin_gap_error)",
        )
    )
    unit = fluid.field_unit
    if fluid.field_range is None:
        out.append(
            Check(
                "field_range",
                "Control within the fluid's range",
                "info",
                None,
                None,
                "the fluid states no characterised range (name a material to check it)",
                "materials/",
            )
        )
    else:
        lo, hi = fluid.field_range
        E = np.abs(fields)
        outside = E[(E != 0) & ((E > hi * (1 + 1e-9)) | (E < lo * (1 - 1e-9)))]
        worst = float(E.max())
        out.append(
            Check(
                "field_range",
                "Control within the fluid's range",
                "warn" if outside.size else "pass",
                show(Q_(worst, fluid.control_unit), unit, name="largest control"),
                show(Q_(hi, fluid.control_unit), unit, name="top of the range"),
                (
                    f"{outside.size} control(s) outside {show(Q_(lo, fluid.control_unit), unit, name='range low')} to "
                    f"{show(Q_(hi, fluid.control_unit), unit, name='range high')}: the yield stress is extrapolated"
                )
                if outside.size
                else "every control asked for is inside the characterised range",
                f"materials/{fluid.material}.toml [range]" if fluid.material else "fluid.field_range",
            )
        )
    i_design = int(np.argmin(np.abs(sweep.velocity - v_design)))
    i_field = (
        int(np.argmax(np.abs(sweep.field)))
        if field_design is None
        else int(np.argmin(np.abs(np.abs(sweep.field) - abs(field_design))))
    )
    phi = float(sweep.plug_fraction[i_field, i_design])
    out.append(
        Check(
            "plug",
            "Plug does not block the gap",
            "pass" if phi <= PLUG_FRACTION_LIMIT else "warn",
            show(phi, "", name="plug fraction"),
            show(PLUG_FRACTION_LIMIT, "", name="plug fraction limit"),
            "plug thickness over gap at the design velocity and control"
            + (
                ""
                if phi <= PLUG_FRACTION_LIMIT
                else ": the gap is nearly blocked, the force is set by the yield stress "
                "and pre-yield elasticity (Makris eq 8), not modelled here, matters"
            ),
            "Makris et al. (1996), eqs 2 and 5 (plug of thickness 2 tau_y L / dp)",
        )
    )
    if damper.seal_friction == 0:
        out.append(
            Check(
                "seal_friction",
                "Seal friction share of the force",
                "info",
                None,
                None,
                "no seal friction given (fluid.seal_friction)",
                "Makris et al. (1996), eq 14",
            )
        )
    else:
        F0 = float(sweep.zero_field_force[i_design])
        share = damper.seal_friction / abs(F0)
        out.append(
            Check(
                "seal_friction",
                "Seal friction share of the force",
                "pass" if share <= SEAL_SHARE_LIMIT else "warn",
                show(Q_(share, ""), "percent", name="seal friction share"),
                show(Q_(SEAL_SHARE_LIMIT, ""), "percent", name="seal friction share limit"),
                "seal friction over the zero-field force at the design velocity"
                + (
                    ""
                    if share <= SEAL_SHARE_LIMIT
                    else ": the off-state force and the dynamic range depend mostly on the seals"
                ),
                "Makris et al. (1996), eq 14",
            )
        )
    return tuple(out)
