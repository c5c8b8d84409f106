"""The equations a report lists: each with its plain-text form, its LaTeX form and its source.

:func:`equations_for` picks those the damper at hand uses (valve or mixed mode, thin gap or exact annulus, the
fluid's field law, a field-dependent viscosity, seal friction).  The text forms are Unicode so that an offline HTML
page shows them without a maths renderer; the Markdown report prints the LaTeX forms.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..damper import Damper
from ..fluid.field_laws import PowerLaw, SaturatingLaw, TabulatedLaw

__all__ = ["Equation", "equations_for"]


@dataclass(frozen=True)
class Equation:
    """One equation of a report."""

    key: str
    title: str
    text: str
    """Unicode form, for HTML."""
    latex: str
    """LaTeX form, for Markdown."""
    source: str
    """Paper and equation number (seed numbers refer to the project's seed papers)."""


_FIELD_LAWS = {
    PowerLaw: Equation(
        "field_law",
        "Yield stress versus control (power law)",
        "τ_y = τ_ref (|E| / E_ref)^n",
        r"\tau_y = \tau_\text{ref}\left(|E|/E_\text{ref}\right)^n",
        "Butz and von Stryk (2002), section 2: n = 1.2 to 2.5 for ER fluids",
    ),
    SaturatingLaw: Equation(
        "field_law",
        "Yield stress versus control (saturating law)",
        "τ_y = τ_sat tanh(|E| / E_sat)",
        r"\tau_y = \tau_\text{sat}\tanh\left(|E|/E_\text{sat}\right)",
        "Carlson, Int. J. Mod. Phys. B 19 (2005) 1463: tau_y = C 271700 phi^1.5239 tanh(6.33e-6 H) [Pa]",
    ),
    TabulatedLaw: Equation(
        "field_law",
        "Yield stress versus control (tabulated curve)",
        "τ_y = PCHIP{(E_i, τ_i)}(|E|)",
        r"\tau_y = \mathrm{PCHIP}\{(E_i, \tau_i)\}(|E|)",
        "material data (materials/); monotone cubic interpolation of Fritsch and Carlson (1980)",
    ),
}


def equations_for(damper: Damper) -> list[Equation]:
    """The equations used for this damper, in the order of the computation."""
    g, fluid = damper.geometry, damper.fluid
    law = fluid.yield_law
    out = [
        _FIELD_LAWS[type(law)]
        if type(law) in _FIELD_LAWS
        else Equation(
            "field_law",
            f"Yield stress versus control ({law.law} law)",
            getattr(law, "equation_text", law.equation),
            law.equation,
            law.reference,
        )
    ]
    if fluid.viscosity_at_reference_field is not None:
        out.append(
            Equation(
                "viscosity",
                "Plastic viscosity versus control",
                "η = η₀ + (η_ref − η₀) τ_y(E) / τ_y(E_ref)",
                r"\eta = \eta_0 + (\eta_\text{ref} - \eta_0)\,\tau_y(E)/\tau_y(E_\text{ref})",
                "Makris et al. (1996), section 3: end points 7 and 13 Pa s; the rise in between is erdesign's "
                "assumption (docs/theory.md, section 1)",
            )
        )
    out += [
        Equation(
            "piston_area",
            "Piston area (double-ended rod)",
            "A_p = π/4 (D_p² − d_r²)",
            r"A_p = \frac{\pi}{4}\left(D_p^2 - d_r^2\right)",
            "geometry",
        ),
        Equation(
            "reynolds",
            "Reynolds number of the gap flow",
            "Re = ū h ρ / η,  ū = Q / (π d h)",
            r"\mathrm{Re} = \frac{\bar u h \rho}{\eta}, \quad \bar u = \frac{Q}{\pi d h}",
            "Makris et al. (1996), eq 1; laminar below Re = 2300",
        ),
        Equation(
            "thin_gap_error",
            "Thin-gap error of the parallel-plate formulas",
            "ε ≈ (h/d)² / 15",
            r"\varepsilon = \frac{Q_\text{exact}}{Q_\text{slit}} - 1 \approx \frac{(h/d)^2}{15}",
            "Bird, Stewart and Lightfoot, Transport Phenomena (2002), eq 2.4-17, expanded in h/d",
        ),
        Equation(
            "yield_pressure_drop",
            "Yield (blocking) pressure drop",
            "Δp_y = 2 τ_y L / h",
            r"\Delta p_y = \frac{2\tau_y L}{h}",
            "Makris et al. (1996), eq 2 with |tau| = tau_y at both walls",
        ),
    ]
    if g.configuration == "valve":
        if damper.uses_exact_annulus:
            out.append(
                Equation(
                    "flow",
                    "Bingham flow through the exact annulus",
                    "Δp(Q) of a Bingham plastic in a concentric annulus",
                    r"\Delta p(Q)\ \text{(concentric annulus, Bingham plastic)}",
                    "Bird, Stewart and Lightfoot (2002) section 2.4 for the annulus; erdesign.flow.annulus_bingham",
                )
            )
        else:
            out.append(
                Equation(
                    "flow",
                    "Bingham flow through the thin annular gap",
                    "Q = π d h³ Δp / (12 η L) · (1 − 3φ/2 + φ³/2),  φ = Δp_y / Δp",
                    r"Q = \frac{\pi d h^3 \Delta p}{12\eta L}\left(1 - \tfrac32\phi + \tfrac12\phi^3\right),"
                    r"\quad \phi = \frac{\Delta p_y}{\Delta p}",
                    "Makris et al. (1996), eqs 5-7, printed with h^2 where h^3 is dimensionally right "
                    "(erdesign.flow.bingham)",
                )
            )
        out += [
            Equation(
                "force",
                "Damper force (valve mode)",
                "F = Δp A_p + F_s sgn(v),  Q = v A_p / n_d",
                r"F = \Delta p\,A_p + F_s\operatorname{sgn}(v), \quad Q = \frac{v A_p}{n_d}",
                "Makris et al. (1996), eq 14",
            ),
            Equation(
                "damping_constant",
                "Small-velocity damping constant (zero field)",
                "C = 12 η₀ L A_p² / (n_d π d h³)",
                r"C = \frac{12\,\eta_0 L A_p^2}{n_d\,\pi d h^3}",
                "Makris et al. (1996), eq 15",
            ),
            Equation(
                "yield_force",
                "Yield (controllable) force",
                "F_y = 2 τ_y L A_p / h",
                r"F_y = \frac{2\tau_y L A_p}{h}",
                "Makris et al. (1996), eqs 2 and 14 as v -> 0+",
            ),
        ]
    else:
        out += [
            Equation(
                "flow",
                "Couette-Poiseuille flow of a Bingham plastic (moving electrode)",
                "τ(y) = τ₀ + g y,  du/dy = D(τ)/η,  D(τ) = sgn(τ) max(|τ| − τ_y, 0)",
                r"\tau(y) = \tau_0 + g y,\quad \frac{du}{dy} = \frac{D(\tau)}{\eta},"
                r"\quad D(\tau) = \operatorname{sgn}(\tau)\max(|\tau| - \tau_y, 0)",
                "Kamath and Wereley (1997), section II (shear plus pressure drag); docs/theory/mixed_mode.md",
            ),
            Equation(
                "force",
                "Damper force (mixed mode)",
                "F = Δp A_p − τ₀ π D_p L + F_s sgn(v)",
                r"F = \Delta p\,A_p - \tau_0\,\pi D_p L + F_s\operatorname{sgn}(v)",
                "Kamath and Wereley (1997), section II; seal friction as Makris et al. (1996), eq 14",
            ),
            Equation(
                "damping_constant",
                "Damping constant (zero field)",
                "C = F/v of the Newtonian fluid",
                r"C = F/v\ \text{(Newtonian Couette-Poiseuille flow)}",
                "docs/theory/mixed_mode.md",
            ),
            Equation(
                "yield_force",
                "Yield (controllable) force",
                "F_y = τ_y (2 L A_p / h + π D_p L)",
                r"F_y = \tau_y\left(\frac{2 L A_p}{h} + \pi D_p L\right)",
                "Kamath and Wereley (1997), section II; erdesign.flow.mixed_mode.mixed_mode_yield_force",
            ),
        ]
    out += [
        Equation(
            "dynamic_range",
            "Dynamic range",
            "D = F(v, E) / F(v, 0)",
            r"D = \frac{F(v, E)}{F(v, 0)}",
            "definition (erdesign size, shared contract)",
        ),
        Equation(
            "energy",
            "Energy per cycle and equivalent damping",
            "U = ∮ F dx,  C_eqv = U / (π Ω X₀²)",
            r"U = \oint F\,dx, \quad C_\text{eqv} = \frac{U}{\pi\Omega X_0^2}",
            "Kamath and Wereley (1997), eqs 1 and 2",
        ),
    ]
    return out
