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
    "semiactive_customized": "algebraic (no state; the terms the characterization chose, eq 6 by default)",
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
    "bouc_wen_modified_polynomial": "as the modified Bouc-Wen model (the same compiled loop, cubic coefficient laws)",
    "bouc_wen_normalized_bahar": "exact w steps of the Bouc-Wen kernel with the shape of each step's start (compiled)",
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
    "displacement, each sub-step's rate by a bracketed root (Illinois false position) of the monotone element law (compiled); "
    "checked against an independent ODE solution (DOP853, rtol 1e-10) to 2e-3 of the force range",
    "vep_nonlinear_stiffness": "as vep_continuous, a bracketed root of the full nonlinear-stiffness equation",
    "viscoelastic_plastic_pang": "algebraic (no state)",
    "arctan_hysteretic": "algebraic (no state; the branch is chosen by the sign of the acceleration)",
    "sims_lumped": "implicit-midpoint sub-steps (4 per sample, second order, A-stable) of the fluid mass, each "
    "sub-step's velocity by a bracketed root of the monotone equation of motion (compiled); m1 = 0 "
    "allowed",
    "metered": "algebraic (no state)",
    "balamurugan": "algebraic (no state)",
    "bass": "implicit-midpoint sub-steps of the mass (as sims_lumped); checked against Radau (rtol 1e-9) to 3e-3 of "
    "the force range and against the linear model's complex stiffness",
    "yang_arctan": "algebraic (no state)",
    "yang_exponential": "algebraic (no state)",
    "cheng_tanh": "algebraic (no state)",
    "dahl_asymmetric": "exact affine recurrence of the Dahl state (as Dahl)",
    "zhao_dead_zone": "backward-Euler dead-zone step (the modified Bingham kernel; 64 sub-steps per sample)",
    "zhao_xu_sigmoid": "algebraic (no state)",
    "yuan_tanh": "algebraic (no state)",
    "yu_division": "algebraic (no state)",
    "he_unified": "algebraic (no state)",
    "sves": "exact stop operator for the elasto-slide element (compiled); spring and dashpot algebraic",
}
#: The MR-model review's Table 1, row by row: group | model / number of parameters | Table 1 formula numbers |
#: invertible in the review ("-": not marked) | where it is in the registry or why not; a line that starts with four
#: spaces continues the row above.  The review's text numbers its equations differently from its table (the table is
#: some four to six behind from section 3.4 on); the notes give the text's.
TABLE1_TEXT = """\
Bingham | Bingham standard model / 3 | (2) | - | `bingham`
Bingham | Gamota and Filisko / 6 | (3) | - | `bingham_extended`
Bingham | Bingham plastic / 2 | (5) | - | `bingham` with f0 = 0 (eq 5 is eq 2 without the offset)
Bingham | Modified Bingham / 4 | (6) | - | `bingham_modified`
Bingham | Improved Bingham / 4 | (9) | - | `bingham_improved`
Bingham | Nonlinear Bingham hysteretic / 6 | (10) | - | `bingham_hysteretic`
Bingham | Hysteresis regularized Bingham / 5 | (13) | - | `bingham_regularized` (branch by the sign of the
    acceleration; see the notes)
Bingham | Standard Bouc-Wen / 7 | (15), (16) | - | `bouc_wen`
Bingham | Modified Bouc-Wen (phenomenological) / 9 | (17) | - | `bouc_wen_modified` (Spencer's linear laws, eqs
    18-19; the quadratic law of alpha, eq 21, with alpha_c); the cubic laws of Yang (eq 20) and the quadratic laws
    of c0, c1 (eq 21): `bouc_wen_modified_polynomial`
Bingham | Bouc-Wen in shear mode / 6 | (15), (22) | - | `bouc_wen_shear`
Bingham | Mass included Bouc-Wen / 11, 8, 3 | (23), (25) or (26) | - | `bouc_wen_mass` (eqs 23-24; a2 = 0 is eq 25),
    `bouc_wen_modified_mass` (eq 26)
Bingham | Amplitude-dependent Bouc-Wen / 22 | (16), (27) | - | `bouc_wen_amplitude` (amplitude explicit)
Bingham | Current-dependent Bouc-Wen / 13 | (28), (30) | - | `bouc_wen_dominguez` (eqs 28-31)
Bingham | Current-frequency-amplitude-dependent / 34 | (31) | - | `bouc_wen_dominguez_cfa` (eqs 32-33; frequency and
    amplitude explicit)
Bouc-Wen | Asymmetric sigmoid modified Bouc-Wen / 12 | (17), (33) | - | `bouc_wen_asymmetric_sigmoid` (eqs 34-35)
Bouc-Wen | Nonsymmetrical Bouc-Wen / 8 | (35), (36) | - | `bouc_wen_nonsymmetric` (eqs 36-38)
Bouc-Wen | Normalized Bouc-Wen I / 11 | (40), (41) | - | `bouc_wen_normalized` with k_v = 0 (eqs 41-43: the
    normalised form of eqs 39-40)
Bouc-Wen | Modified normalized Bouc-Wen / 27 | (43)-(45) | yes | `bouc_wen_normalized` (eqs 45-46 with linear
    voltage laws: invertible); Bahar's nonlinear voltage laws (eqs 47-48): `bouc_wen_normalized_bahar`
Bouc-Wen | Normalized Bouc-Wen II / 11 | (49), (48) or (50) | - | `bouc_wen_normalized_dominguez` (eqs 49-53; the
    approximations of eqs 51 and 54 are not separate models)
Bouc-Wen | Normalized phenomenological / 8 | (17), (51) | - | `bouc_wen_modified_normalized` (eq 55)
Bouc-Wen | Bai restructured / 8 | (52) | - | `bouc_wen_restructured` (eq 56)
LuGre | Original LuGre / 4 | (53) | - | `lugre` (eq 57)
LuGre | Modified LuGre / 4 | (54), (55) | yes | `lugre_modified` (eqs 58-59)
Biviscous | Nonlinear biviscous / 3 | (56) | - | `biviscous` (eq 60)
Biviscous | Nonlinear hysteretic biviscous / 3 | (57) | - | `biviscous_hysteretic` (eq 61)
Biviscous | Nonlinear hysteretic arctangent / 4 | (58) | - | `arctan_hysteretic` (eq 62)
Biviscous | Lumped-parameter fluid-flow / 9 | (59) | - | `sims_lumped` (eqs 63-65)
Viscoelastic-plastic | Nonlinear viscoelastic-plastic / 6 | (69) | - | `viscoelastic_plastic_pang` (eqs 66-74);
    Kamath and Wereley's own form: `kamath_wereley_6`
Viscoelastic-plastic | Wereley viscoelastic-plastic / 5 | (70) | - | `viscoelastic_plastic_pang` with F_c = 0 (eq
    75); the four-parameter model: `kamath_wereley_4`
Viscoelastic-plastic | Li viscoelastic-plastic / 6 | (73), (74) | yes | `li_viscoelastic_plastic` (eqs 76-79)
Viscoelastic-plastic | Continuous viscoelastic-plastic (VEP) / 5 | (77) | - | `vep_continuous` (eqs 80-82)
Viscoelastic-plastic | Nonlinear stiffness VEP (nkVEP) / 15 | (78), (79) | - | `vep_nonlinear_stiffness` (eqs 83-85)
Viscoelastic-plastic | Stiffness-viscosity-elasto-slide (SVES) / 6 | (80), (81) | - | `sves` (eqs 86-87)
Algebraic | Weng / 5 | (82) | - | `weng_arctan` with m = 0 (eq 88)
Algebraic | Cesmeci and Engin / 6 | (83) | - | `weng_arctan` (eq 89)
Algebraic | Metered / 9 | (84) | - | `metered` (eq 90; amplitude and frequency explicit)
Algebraic | Balamurgan / 11 | (86) | - | `balamurugan` (eqs 91-92)
Hyperbolic tangent | Bass / 7 | (87), (88) | - | `bass` (eqs 93-94)
Hyperbolic tangent | Kwok / 7 | (89) | yes | `kwok_tanh` (eq 95)
Hyperbolic tangent | Yang / 5, 6 | (90) or (91) | - | `yang_arctan` (eq 96), `yang_exponential` (eq 97)
Hyperbolic tangent | Cheng / 4 | (92) | yes | `cheng_tanh` (eq 98)
Hyperbolic tangent | Magic formula / 8 | (94) | yes | `magic_formula` (eqs 99-100)
Dahl | Dahl / 2 | (97) | - | `dahl` with k0 = c0 = f0 = 0 (eq 103)
Dahl | Modified Dahl / 5 | (98) | - | `dahl` (eq 104)
Dahl | Viscous Dahl / 5 | (99), (41) | - | `dahl_viscous` (eq 105)
Dahl | Asymmetric Dahl / 7 | (99), (100) | - | `dahl_asymmetric` (eqs 105-106)
Dahl | General dynamic models / 5-11 | (101)-(106) | - | `zhao_dead_zone` (eq 107), `zhao_xu_sigmoid` (eq 108),
    `yuan_tanh` (eq 109), `yu_division` (eq 110), `he_unified` (eq 111); not Bui's quasi-static magic-formula model
    (eq 112): the review does not give its quasi-static force F_QS = F_eta + F_tau + F_f
"""
TABLE1 = [tuple(cell.strip() for cell in row.split("|")) for row in re.sub(r"\n {4}", " ", TABLE1_TEXT).splitlines()]


def _table1() -> list[str]:
    """The Table 1 section; every registry name it cites must exist (checked here, so the doc cannot drift)."""
    names = set(model_names())
    lines = [
        "## The MR-model review's Table 1, row by row",
        "",
        'Every row of the review\'s Table 1 (47 rows), with the registry model that implements it. "Invertible" '
        "is the review's mark; `erdesign models --json` gives each model an `invertible` key for what "
        "`erdesign.identification.inverse.inverse_control` inverts (every memoryless model with a control, by a "
        "bracketed root, besides the review's six).",
        "",
    ]
    rows = []
    for i, (group, model, eqs, inv, where) in enumerate(TABLE1, 1):
        for cited in re.findall(r"`([a-z0-9_]+)`", where):
            if cited not in names:
                raise SystemExit(f"docs/make_models_doc.py: Table 1 row {i} cites {cited!r}, not in the registry")
        rows.append((str(i), group, model, eqs, inv or "-", where))
    columns = ("#", "group", "model / parameters", "Table 1 eqs", "review: invertible", "in erdesign")
    return lines + _table(columns, rows) + [""]


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
- **The MR-model review, the rest of its catalogue** (each model's notes above give the detail):
  eq 13 (hysteresis-regularised Bingham) chooses the branch by the sign of the velocity, which gives no loop: the
  sign of the acceleration is used; eqs 29-30 (Dominguez) print +gamma, the velocity inside the tanh and the branch
  by the sign of x: -gamma (eq 15), the displacement, and the direction of motion are used; eq 31 writes
  gamma = -gamma1 + gamma2 I: the sign is absorbed; eq 33's low-current laws c4 + (c4 - c1) I / I_c are not continuous
  at I_c: c4 + (c1 - c4) I / I_c is used; eq 37 (Kwok) misplaces its brackets (it is eq 15 with the shifted
  velocity); eq 56 (Bai) drops sigma from the z equation (eq 55 has it); eq 64 (Sims) switches at F_y / C_pre,
  where the law jumps: the continuous switch of eq 60 is used; eq 72's S_c = (1 + tanh) / 2 is one-sided: tanh is
  used; eqs 80 and 82 print kx - y for k(x - y); eq 87 (SVES) prints -N + k2 (x - x_bar) on the decreasing branch
  for N + k2 (x - x_bar); eq 93 (Bass) adds the friction along the mass's velocity: it opposes it here; eq 108
  (Zhao-Xu) has a constant velocity shift, which makes no loop: it follows the sign of the acceleration; eq 110
  (Yu) prints growing exponentials in its backbone: the saturating (negative) exponents are used.
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
    text = re.sub(
        r":(?:func|class|meth|mod|data|attr):`~?([^`]*)`",
        lambda m: f"`{m.group(1).split('.')[-1]}`" if m.group(0).count("~") else f"`{m.group(1)}`",
        text,
    )
    return text.replace("``", "`")


def _number(v: float) -> str:
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    return f"{v:.6g}"


def _table(columns, rows) -> list[str]:
    """A Markdown table: the header of ``columns``, the rule, a line per row of cells."""

    def line(cells):
        return "|" + "|".join(f" {c} " if c else " " for c in cells) + "|"

    return [line(columns), "|" + "---|" * len(columns), *(line(r) for r in rows)]


def _parameter_row(model, p) -> tuple[str, ...]:
    """A parameter's cells: name, unit, default, bounds, description with its tags."""
    tags = [
        t
        for t, on in (
            ("a priori", not p.fitted),
            ("control", p.name in model.control_parameters),
            ("log scale", p.log_scale),
        )
        if on
    ]
    desc = p.description + (f" ({', '.join(tags)})" if tags else "")
    return f"`{p.name}`", p.unit or "-", _number(p.default), f"[{_number(p.lower)}, {_number(p.upper)}]", desc


def _invertibility(model) -> str:
    if not model.uses_control:
        return "no control input (passive model): no inverse"
    if hasattr(model, "control_affine"):
        how = "closed form: the force is affine in the control at each sample"
        if model.name == "lugre_modified":
            how = "step by step: affine in the control at each step, with the state advanced by the control chosen"
        elif model.name == "li_viscoelastic_plastic":
            how = (
                "closed form in the post-yield regime, where the force is affine in the control (the pre-yield "
                "force does not depend on it)"
            )
    elif getattr(model, "memoryless", False):
        how = "vectorised bracketed root in the control (scipy.optimize.elementwise.find_root)"
    else:
        return (
            "not provided by `erdesign.identification.inverse` (the control acts through a state, a filter or a "
            "fitted series that no closed form or root bracket is written for)"
        )
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
                'effect library (`erdesign.effects`). Built as `get_model("physics", damper="damper.toml", effects=(...))`, or',
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
        lines += _table(
            ("parameter", "unit", "default", "bounds", ""), [_parameter_row(model, p) for p in model.parameters]
        )
        lines += ["", f"Integration: {INTEGRATION[name]}.", "", f"Invertibility: {_invertibility(model)}.", ""]
        if model.requires_control:
            lines += ["Needs a control column (a record without one is an error).", ""]
        if notes:
            lines += [f"Notes: {notes}", ""]
    lines += _table1()
    lines.append(MISPRINTS)
    return "\n".join(lines)


def main() -> int:
    DOC.write_text(render())
    print(f"wrote {DOC}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
