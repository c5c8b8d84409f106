"""Write docs/models.md from the model registry, so that equations, sources and parameters cannot drift.

Each model's equation and notes are taken from its class docstring, its parameters (units, defaults, bounds) from
its :class:`~erdesign.models.base.Parameter` list; only the integration method and the misprints are written here.
Run from the repository root:  python docs/make_models_doc.py.  tests/test_models.py checks the file is current.
"""

from __future__ import annotations

import inspect
import math
import re
import sys
from pathlib import Path

from erdesign.models.registry import INVERTIBLE, get_model, model_names

DOC = Path(__file__).resolve().parent / "models.md"

#: How each model is advanced in time (the kernels are in erdesign/models/_kernels.py).
INTEGRATION = {
    "bingham": "algebraic in the measured velocity (no state)",
    "bingham_extended": "implicit (backward Euler) sub-steps of the dead-zone form of the Coulomb element, 64 per "
                        "sample by default (a compiled loop): the plastic branch is extremely stiff (Butz and von "
                        "Stryk 2002), the "
                        "implicit step is unconditionally stable and first order; tested against Radau at rtol 1e-10 "
                        "(error 5e-5 of the force spread at 1 ms samples, halving with the step)",
    "powell": "algebraic in the measured velocity and acceleration (no state)",
    "bingmax": "exact discrete-time first-order filter of the Maxwell element (first-order hold: a two-tap IIR filter "
               "by scipy.signal.lfilter on even steps, an affine prefix scan on uneven ones), plus the friction",
    "maxwell": "exact discrete-time first-order filter (as BingMax)",
    "bouc_wen": "exact step of z for the sample's travel (closed-form Riccati solution for n = 2, exponentials for "
                "n = 1, RK4 sub-steps in the travelled distance otherwise), a compiled loop: the stiff saturation of "
                "z does not limit the step",
    "bouc_wen_modified": "RK4 sub-steps of the internal displacement with z exact along each sub-step and the "
                         "control filter exact, a compiled loop; checked against LSODA at rtol 1e-10 (within 1e-4 of "
                         "the force range at 3 kHz with Spencer's 1997 parameters and a random voltage)",
    "bouc_wen_normalized": "exact z steps of the Bouc-Wen kernel with beta = rho (1 - sigma), gamma = rho sigma",
    "kamath_wereley_4": "exact discrete-time filter of the three-parameter (Jeffreys) branch; shape functions "
                        "algebraic",
    "kamath_wereley_6": "as the four-parameter model, plus the inertia and stiction terms (algebraic)",
    "biviscous": "algebraic (no state)",
    "biviscous_hysteretic": "algebraic (no state; the branch is chosen by the sign of the acceleration)",
    "eyring_plastic": "algebraic (no state)",
    "semiactive_general": "algebraic (no state)",
    "dahl": "exact affine recurrence of the Dahl state for a displacement linear between samples (prefix scan)",
    "dahl_viscous": "exact affine recurrence (as Dahl)",
    "lugre": "exact affine recurrence of the bristle state (prefix scan)",
    "lugre_modified": "exact affine recurrence with the control-dependent rate",
    "weng_arctan": "algebraic (no state)",
    "kwok_tanh": "algebraic (no state)",
    "magic_formula": "algebraic (no state)",
    "chebyshev": "algebraic: a tensor Chebyshev series in scaled x, v (and u); identified by linear least squares",
    "maxwell_neural": "Maxwell filter (exact) plus a one-hidden-layer tanh network of (x, v, a, u) trained on the "
                      "Maxwell residual (Levenberg-Marquardt)",
    "bingham_modified": "backward-Euler dead-zone step of the extended Bingham kernel with a rigid Kelvin element "
                        "(64 sub-steps per sample, compiled)",
    "bingham_improved": "algebraic (no state)",
    "bingham_regularized": "algebraic (no state; the branch is chosen by the sign of the acceleration)",
    "bingham_hysteretic": "exact stop operator (elastic-perfectly-plastic spring) for a displacement linear between "
                          "samples, compiled; the damping terms algebraic",
    "bouc_wen_shear": "exact z steps (as Bouc-Wen)",
    "bouc_wen_mass": "exact z steps (as Bouc-Wen); mass and shear-thinning damping algebraic",
    "bouc_wen_modified_mass": "as the modified Bouc-Wen model, plus the inertia term (algebraic)",
    "bouc_wen_amplitude": "exact z steps (as Bouc-Wen); the amplitude laws algebraic",
    "bouc_wen_dominguez": "explicit (the tanh solution of the Bouc-Wen equation on each branch; no state)",
    "bouc_wen_dominguez_cfa": "explicit (as bouc_wen_dominguez)",
    "bouc_wen_asymmetric_sigmoid": "as the modified Bouc-Wen model (zero-current parameters), times the "
                                   "algebraic current gain",
    "bouc_wen_nonsymmetric": "exact z steps of the Bouc-Wen kernel driven by x - mu int sgn(x) dt (the time "
                             "integral exact for x linear between samples)",
    "bouc_wen_modified_normalized": "the modified Bouc-Wen kernel with beta = rho (1 - sigma), gamma = rho sigma, "
                                    "delta = rho",
    "bouc_wen_restructured": "the modified Bouc-Wen kernel with c0 = k0 = 0 in its internal equation",
    "bouc_wen_normalized_dominguez": "exact z steps of the Bouc-Wen kernel (beta = 0, n = 2, A = gamma)",
    "li_viscoelastic_plastic": "exact first-order lag of the Zener element (first-order hold); the switch and the "
                               "post-yield law algebraic",
    "vep_continuous": "implicit-midpoint sub-steps (4 per sample, second order, A-stable) of the internal "
                      "displacement, each sub-step's rate by bisection on the monotone element law (compiled); "
                      "checked against an independent ODE solution (DOP853, rtol 1e-10) to 2e-3 of the force range",
    "vep_nonlinear_stiffness": "as vep_continuous, bisection on the full nonlinear-stiffness equation",
    "sves": "exact stop operator for the elasto-slide element (compiled); spring and dashpot algebraic",
}

MISPRINTS = """\
## Misprints and departures from the sources

- **BingMax, Butz and von Stryk (2002) eq 7 vs eq 6 and Makris eq 16.** Butz and von Stryk (2002) writes the model as
  F + lambda dF/dt = C du/dt + F_y sgn(du/dt), which low-passes the friction too; that disagrees with its own
  eq 6 and with Makris et al. (1996) eq 16, where the friction acts in parallel with the Maxwell element,
  unfiltered. `bingmax` implements eq 6 / Makris eq 16.
- **Biviscous, the MR-model review eq 60.** Printed with C_post + F_y (the velocity factor of C_post is missing); the
  continuous law F = C_post v + F_y sgn v above yield is meant and implemented.
- **Hysteretic biviscous, the MR-model review eq 61.** The velocity intervals are printed with mixed signs; the continuous
  clip form with the printed yield velocities (F_y -/+ C_pre v_0)/C_pre is implemented.
- **Magic formula, the MR-model review eq 100.** Printed with the argument dx/dt + A|x| (and a misplaced bracket). With |x|
  the two branches of a sinusoidal cycle have the same |x| at the same velocity, so the term cannot open the
  force-velocity loop that A is said to set; dx/dt + A x opens it by A X0 in velocity, as described. The bracket
  follows the standard magic formula (eq 99).
- **Kamath and Wereley (1997): the definition of alpha.** The shape functions take a velocity "non-dimensionalised
  with respect to the amplitude", alpha = |v| / max |v| (the MR-model review eq 67 uses |v| - v_y in velocity units, the same up
  to scale); the stiction shape function needs the same dimensionless argument, since eps_c is given as a number
  between 0 and 1.
- **Powell, Butz and von Stryk (2002) eqs 4-5.** f_cs (1 + (f_cd / f_cs) e^{-a|v|}) is the printed f_cs + f_cd
e^{-a|v|}, kept.
- **Normalised Bouc-Wen, the MR-model review eq 46.** The source writes -k_w w; the sign is absorbed in k_w (positive k_w
  dissipates).
- **Modified Bouc-Wen.** alpha_c u^2 is not in Butz and von Stryk (2002) (eq 13 is linear in u): it is the quadratic
current law of
  Quiroz (2022) used for the real data (docs/case_studies/quiroz.md); alpha_c = 0 is Spencer's law.
"""


def _docstring_parts(cls) -> tuple[str, str, str]:
    """(summary, equation in LaTeX, notes) from a model class docstring."""
    doc = inspect.getdoc(cls) or ""
    summary = doc.split("\n\n", 1)[0].replace("\n", " ")
    m = re.search(r"\.\. math::(.*?)(?:\n\n(?! )|\Z)", doc, flags=re.S)
    blocks = []
    if m:  # one display block per paragraph of the math directive
        for para in re.split(r"\n\s*\n", m.group(1)):
            body = [ln.strip() for ln in para.splitlines() if ln.strip()]
            if body:
                blocks.append("\n".join(body))
    notes = ""
    n = re.search(r"Notes\n-----\n(.*?)(?:\n\n[A-Z][a-z]+\n-+\n|\Z)", doc, flags=re.S)
    if n:
        notes = _markdown(" ".join(n.group(1).split()))
    return _markdown(summary), blocks, notes


def _markdown(text: str) -> str:
    """Sphinx roles to Markdown: :math:`x` -> $x$, :func:`~a.b` -> `b`, ``x`` -> `x`."""
    text = re.sub(r":math:`([^`]*)`", r"$\1$", text)
    text = re.sub(r":(?:func|class|meth|mod|data|attr):`~?([^`]*)`", lambda m: f"`{m.group(1).split('.')[-1]}`"
                  if m.group(0).count("~") else f"`{m.group(1)}`", text)
    return text.replace("``", "`")


def _number(v: float) -> str:
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    return f"{v:.6g}"


def _invertibility(model) -> str:
    if not model.uses_control:
        return "no control input (passive model): no inverse"
    if hasattr(model, "control_affine"):
        how = "closed form: the force is affine in the control at each sample"
        if model.name == "lugre_modified":
            how = "step by step: affine in the control at each step, with the state advanced by the control chosen"
    elif getattr(model, "memoryless", False):
        how = "vectorised bracketed root in the control (scipy.optimize.elementwise.find_root)"
    else:
        return ("not provided by `erdesign.identification.inverse` (the control acts through a state, a filter or a "
                "fitted series that no closed form or root bracket is written for)")
    marked = " (the MR-model review Table 1: invertible)" if model.name in INVERTIBLE else ""
    return f"{how}{marked}; `erdesign.identification.inverse.inverse_control`"


def render() -> str:
    lines = [
        "# The damper model library",
        "",
        "<!-- Written by docs/make_models_doc.py from the model registry; do not edit by hand. -->",
        "",
        "Every model implements `erdesign.models.base.Model`: `force(record, values)` maps a motion record (time,",
        "displacement, derived velocity and acceleration, and the control column: field, current or voltage) and SI",
        "parameter values to a force [N]. Internal states start at rest at the first sample. `u` is the dimensionless",
        "control, control / `control_reference` (chosen by `erdesign.identification.identify` as the power of ten",
        "near the largest control of the records). Where a record has no control column, the parameters listed as",
        "control parameters are held at their defaults (zero slopes): field-dependent coefficients are then",
        "identified as constants. `erdesign models --json` lists the same registry. Sources: Kamath and Wereley (1997),",
        "Butz and von Stryk (2002), Vivas-López et al. (n.d.), the MR-model review, Makris et al. (1996) and the others",
        "of [references.md](references.md).",
        "",
        "Fitting: bounded least squares (`erdesign.identification.fit.fit`, trust-region reflective; log-scale",
        "parameters searched in log space; multi-start and a differential-evolution stage on request); parameters",
        "marked *a priori* are held unless named in `free`. Identification across records:",
        "`erdesign.identification.identify.identify_joint`; cross-validation tables (in the style of Vivas-López et",
        "al., Table 4): `erdesign.identification.identify.cross_validation`.",
        "",
    ]
    for name in model_names():
        if name == "physics":
            lines += [
                "## `physics`: the physics damper of a damper file",
                "",
                "Source: Makris et al. (1996) eqs 5-7 and 14, the mixed mode of Kamath and Wereley (1997), and the",
                "effect library (`erdesign.effects`). Built as `get_model(\"physics\", damper=\"damper.toml\", effects=(...))`, or",
                "`erdesign identify X.csv --model physics --damper D.toml [--effects a,b]`. Parameters: the calibration",
                "factors `viscosity_factor`, `yield_stress_factor` [-] plus those of the chosen effects (see",
                "erdesign/effects/chain.py); without a field in the record the yield-stress factor is held at 1.",
                "Invertibility: vectorised bracketed root in the field",
                "(`erdesign.identification.inverse.inverse_control`).",
                "",
            ]
            continue
        model = get_model(name)
        summary, eq, notes = _docstring_parts(type(model))
        lines += [f"## `{name}`: {model.title}", "", summary, "", f"Source: {model.source}.", ""]
        for block in eq:
            lines += ["$$", block, "$$", ""]
        lines += ["| parameter | unit | default | bounds | |", "|---|---|---|---|---|"]
        for p in model.parameters:
            tags = [t for t, on in (("a priori", not p.fitted), ("control", p.name in model.control_parameters),
                                    ("log scale", p.log_scale)) if on]
            desc = p.description + (f" ({', '.join(tags)})" if tags else "")
            lines.append(f"| `{p.name}` | {p.unit or '-'} | {_number(p.default)} | "
                         f"[{_number(p.lower)}, {_number(p.upper)}] | {desc} |")
        lines += ["", f"Integration: {INTEGRATION[name]}.", "", f"Invertibility: {_invertibility(model)}.", ""]
        if model.requires_control:
            lines += ["Needs a control column (a record without one is an error).", ""]
        if notes:
            lines += [f"Notes: {notes}", ""]
    lines.append(MISPRINTS)
    return "\n".join(lines)


def main() -> int:
    DOC.write_text(render())
    print(f"wrote {DOC}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
