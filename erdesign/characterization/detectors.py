r"""The characteristics of Vivas-López et al. (n.d.) Table 2, each read from its diagram and mapped to its model term.

A characteristic is found when the feature group that carries it (:mod:`erdesign.characterization.split`) lowers
the ESR (eq 7) of the linear fit of its diagram by more than a threshold when it is added to all the others (a
drop-one test: the others cannot stand in for it).  Passive characteristics are judged on the samples at the
passive control (the passive FV and FD diagrams), the semi-active ones on the semi-active force of eq 1 at the other
samples (the SA FV and FM diagrams).  :data:`CHARACTERISTICS` is the registry; :func:`detect` runs it.

Two rows go beyond the paper's Table 2, each where its own damper showed the opposite ("the average force gain ...
has a linear pattern"; "in the post-yield region the force is almost independent of the piston velocity"):
``nonlinear_gain`` (the FM diagram is a power of the control, as an ER fluid's yield stress goes as E^n with
n = 1.2-2.5, Butz and von Stryk 2002: the customized model's manipulation becomes V = u^n) and
``speed_dependent_force`` (the semi-active force keeps growing with speed, as a plastic valve's does while its plug
thins: carried by the one term of eq 4 that varies with speed, the saturation f_pre-y,ż,V of eq 5d).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize_scalar

from .split import (
    PASSIVE_GROUPS,
    SEMIACTIVE_GROUPS,
    LinearFit,
    Samples,
    fit_groups,
    passive_features,
    robust_peak,
    semiactive_features,
)

__all__ = [
    "CHARACTERISTICS",
    "EXPONENT_RANGE",
    "MIN_SAMPLES",
    "THRESHOLD",
    "Characteristic",
    "Finding",
    "control_exponent",
    "detect",
]

#: Rise of the ESR (a fraction of the force variance) that a characteristic's group must account for to be found.
THRESHOLD = 0.001
#: Fewest samples a diagram needs to be read.
MIN_SAMPLES = 50
#: Range searched for the exponent n of a force gain that grows as the control to the power n (FM diagram): ER
#: yield stress grows as E^n with n = 1.2-2.5 (Butz and von Stryk 2002, Table 1); a saturating MR coil below 1.
EXPONENT_RANGE = (0.25, 4.0)


@dataclass(frozen=True)
class Characteristic:
    """One row of Table 2, or an asymmetry (sections 3.1 and 3.2: the passive FV and the FM diagrams are
    asymmetrical), which section 4 turns into two coefficients per term."""

    name: str
    title: str
    diagram: str
    """Where the paper reads it: ``"passive FV"``, ``"passive FD"``, ``"SA FV"``."""
    model_term: str
    """The term of the general model it calls for, as Table 2 writes it."""
    terms: tuple[str, ...]
    """Keys of :data:`erdesign.models.semiactive.TERMS` it adds to the customized model (empty for asymmetry)."""
    stage: str
    """Which force it is read from: ``"passive"`` (F_P at the passive samples), ``"semiactive"`` (F_SA of eq 1 at the
    others) or ``"damper"`` (F_D at every sample: asymmetry shows in both parts)."""
    group: str
    """The feature group that carries it."""
    value: Callable[[LinearFit, float, float], str]
    """Text of the value that shows it, from the full fit and the peak speed V and stroke Z."""
    without: tuple[str, ...] = ()
    """The groups the fit without it leaves out (default: its own group); the gain leaves out every semi-active group,
    since the pre-yield columns saturate into the gain's own and would stand in for it."""

    asymmetric: bool = False
    """Whether it makes the customized model's coefficients differ in extension and compression."""
    threshold_scale: float = 1.0
    """Its threshold over the common one (:data:`THRESHOLD`, 0.001: a term that carries about 3 % of the RMS force);
    0.5 for asymmetry, whose even part of relative amplitude e adds an ESR of about e^2 (0.0005: about 2 %); 3 for
    the steep pre-yield zone, which is read without the wide speed columns and so also takes the onset of a plastic
    valve's rise with speed (square-root-like at low flow) and the rounding of its step by a velocity derived from
    sampled displacement: on truth-rig records of the Bingham valve without pre-yield elasticity (E2, E5) it reads
    0.0014 with the exact velocity (the same at 1 kHz) and 0.0021 with the derived one at 250 Hz, against
    0.006-0.008 with pre-yield elasticity.  The rise with speed itself is ``speed_dependent_force``, at the common
    threshold; 2 for hysteresis, whose columns live at the reversals, where a spring and a mass act at their largest:
    what their linear columns miss of them leaks into the hysteresis columns (up to 0.001 on closed-form records
    with stiffness, mass and friction and no hysteresis)."""

    ignores: tuple[str, ...] = ()
    """Groups left out of both of its fits: the dictionary it is read on is the others."""
    exponent: bool = False
    """Judged not by leaving out a group but by fixing the exponent of the force gain at 1 (a linear FM diagram)
    in the fit with every group; found, its exponent becomes the customized model's control exponent."""

    @property
    def left_out(self) -> tuple[str, ...]:
        return self.without or (self.group,)


def _c(fit: LinearFit, V: float, Z: float) -> str:
    return f"c_p = {fit.coefficients['viscous'][0]:.4g} N s/m"


def _k(fit: LinearFit, V: float, Z: float) -> str:
    return f"k_p = {fit.coefficients['stiffness'][0] * V / Z:.4g} N/m"


def _f(fit: LinearFit, V: float, Z: float) -> str:
    return f"a friction force of {float(np.sum(fit.coefficients['friction'])):.4g} N at high speed"


def _h(fit: LinearFit, V: float, Z: float) -> str:
    lag = float(np.sum(fit.coefficients["hysteresis"])) + float(np.sum(fit.coefficients.get("hysteresis_sa", 0.0)))
    return f"the force near a reversal lags it by up to {lag:.4g} N (at the highest control)"


def _m(fit: LinearFit, V: float, Z: float) -> str:
    return f"m_D = {fit.coefficients['inertia'][0]:.4g} kg"


def _a(fit: LinearFit, V: float, Z: float) -> str:
    cf = fit.coefficients["asymmetry"]
    return (
        f"extension and compression differ by {2 * cf[0]:.4g} N s/m of damping and "
        f"{2 * float(np.sum(cf[1:])):.4g} N of friction"
    )


def _asa(fit: LinearFit, V: float, Z: float) -> str:
    return f"extension and compression differ by {2 * fit.coefficients['asymmetry_sa'][0]:.4g} N of control force gain"


def _g(fit: LinearFit, V: float, Z: float) -> str:
    return f"c_SA = {fit.coefficients['gain'][0]:.4g} N over the control span (post-yield, FM diagram)"


def _p(fit: LinearFit, V: float, Z: float) -> str:
    cf = fit.coefficients["preyield"]
    return f"a force that grows with speed before it saturates: {float(np.sum(cf[:-1])):.4g} N over the control span"


def _s(fit: LinearFit, V: float, Z: float) -> str:
    return "the force the control adds changes with the speed across the diagram, not only at its sign"


def _n(fit: LinearFit, V: float, Z: float) -> str:
    return "the mean force gain fitted as a power of the control"


#: The registry: name -> characteristic (Vivas-López et al. Table 2).
CHARACTERISTICS: dict[str, Characteristic] = {
    c.name: c
    for c in (
        Characteristic(
            "viscous_damping", "Viscous damping", "passive FV", "c_p ż", ("viscous",), "passive", "viscous", _c
        ),
        Characteristic("stiffness", "Stiffness", "passive FD", "k_p z", ("stiffness",), "passive", "stiffness", _k),
        Characteristic("friction", "Friction", "passive FV", "f_fr", ("friction",), "passive", "friction", _f),
        Characteristic(
            "hysteresis",
            "Hysteresis loop",
            "FV",
            "f_h,z",
            ("hysteresis_z",),
            "damper",
            "hysteresis",
            _h,
            ("hysteresis", "hysteresis_sa"),
            False,
            2.0,
        ),
        Characteristic(
            "frequency_dependent_loop",
            "Frequency dependent hysteresis loop",
            "passive FV",
            "f_h,ż, m_D",
            ("inertia",),
            "passive",
            "inertia",
            _m,
        ),
        Characteristic(
            "asymmetry",
            "Asymmetry of the passive force",
            "passive FV",
            "coefficients for ż ≥ 0 and ż < 0",
            (),
            "passive",
            "asymmetry",
            _a,
            (),
            True,
            0.5,
        ),
        Characteristic(
            "gain",
            "Gain in force due to manipulation",
            "SA FV",
            "c_SA",
            ("gain",),
            "semiactive",
            "gain",
            _g,
            SEMIACTIVE_GROUPS,
        ),
        Characteristic(
            "nonlinear_gain",
            "Force gain not linear in the control",
            "SA FM",
            "c_SA V with V = u^n",
            (),
            "semiactive",
            "gain",
            _n,
            (),
            exponent=True,
        ),
        Characteristic(
            "preyield",
            "Pre-yield zone",
            "SA FV",
            "f_pre-y,ż,V",
            ("preyield",),
            "semiactive",
            "preyield",
            _p,
            (),
            False,
            3.0,
            ignores=("speed",),
        ),
        Characteristic(
            "speed_dependent_force",
            "Semi-active force growing with speed",
            "SA FV",
            "f_pre-y,ż,V (a wide saturation)",
            ("preyield",),
            "semiactive",
            "speed",
            _s,
            ("preyield", "speed"),
        ),
        Characteristic(
            "asymmetry_semiactive",
            "Asymmetry of the force gain",
            "SA FM",
            "c_SA for ż ≥ 0 and ż < 0",
            (),
            "semiactive",
            "asymmetry_sa",
            _asa,
            (),
            True,
            0.5,
        ),
    )
}


@dataclass(frozen=True)
class Finding:
    """Whether a characteristic was found and the evidence: the ESR of its diagram's fit with all groups
    (``esr_with``) and without its group (``esr_without``), the rise over :attr:`threshold`, and the value of the
    term."""

    characteristic: Characteristic
    found: bool
    evidence: str
    esr_with: float | None
    esr_without: float | None
    threshold: float
    value: float | None = None
    """The number the customized model takes from it (the control exponent n of ``nonlinear_gain``), else None."""

    @property
    def delta_esr(self) -> float | None:
        return None if self.esr_with is None else self.esr_without - self.esr_with

    def to_dict(self) -> dict:
        c = self.characteristic
        return {
            "name": c.name,
            "title": c.title,
            "diagram": c.diagram,
            "model_term": c.model_term,
            "found": self.found,
            "evidence": self.evidence,
            "esr_with": self.esr_with,
            "esr_without": self.esr_without,
            "delta_esr": self.delta_esr,
            "threshold": self.threshold,
            "value": self.value,
        }


def _judge(c: Characteristic, columns, F, F_D, groups, V, Z, threshold, diagram_text, linear=None, n=1.0) -> Finding:
    """The drop-one test of ``c``: the fit of ``F`` on ``groups`` against the fit without ``c``'s groups (or, for the
    exponent of the force gain, against the fit on the ``linear`` columns: exponent 1); ESRs over ``F_D``."""
    threshold = threshold * c.threshold_scale
    groups = [g for g in groups if g not in c.ignores]
    full = fit_groups(columns, F, groups)
    if c.exponent:
        without = fit_groups(linear, F, groups)
    else:
        without = fit_groups(columns, F, [g for g in groups if g not in c.left_out])
    e_with, e_without = full.esr(F_D), without.esr(F_D)
    delta = e_without - e_with
    found = bool(delta > threshold)
    value = c.value(full, V, Z) + (f", n = {n:.3g} (a straight line: n = 1)" if c.exponent else "")
    evidence = (
        f"{'found' if found else 'not found'} in the {diagram_text}: {value}; without the "
        f"term the ESR of the fit rises from {e_with:.4f} to {e_without:.4f} (+{delta:.4f}, threshold "
        f"+{threshold:g})"
    )
    return Finding(c, found, evidence, e_with, e_without, threshold, n if c.exponent else None)


def _best_exponent(sa: Samples, F, V, Z) -> float:
    """The exponent n of the force gain w = (u^n - u_p^n) / (u_max^n - u_p^n) that fits the semi-active force ``F``
    best with every semi-active group (a one-dimensional least squares over :data:`EXPONENT_RANGE`); 1 when the
    control is negative or takes fewer than three levels (two levels, as PRBS, cannot tell a curve from a line)."""
    if sa.u_passive is None or sa.u_passive < 0 or np.unique(np.round(sa.du, 6)).size < 3:
        return 1.0

    def rss(n):
        return fit_groups(semiactive_features(sa, V, Z, n), F, SEMIACTIVE_GROUPS).rss

    lo, hi = np.log(EXPONENT_RANGE[0]), np.log(EXPONENT_RANGE[1])
    best = minimize_scalar(lambda q: rss(np.exp(q)), bounds=(lo, hi), method="bounded", options={"xatol": 1e-3})
    return float(np.exp(best.x))


def control_exponent(findings) -> float:
    """The control exponent of the customized model: that of a found ``nonlinear_gain``, else 1 (linear)."""
    return next((f.value for f in findings if f.found and f.characteristic.exponent), 1.0)


def _unobservable(c: Characteristic, why: str, threshold: float) -> Finding:
    return Finding(c, False, f"not observable: {why}", None, None, threshold * c.threshold_scale)


def detect(samples: Samples, *, threshold: float = THRESHOLD) -> tuple[list[Finding], np.ndarray]:
    """Every characteristic of :data:`CHARACTERISTICS` judged on the pooled ``samples``, and the passive force
    :math:`F_P` [N] at every sample (eq 1: the semi-active force is ``samples.F - F_P``).

    The exponent of the force gain is read first (``nonlinear_gain``, FM diagram); the other semi-active
    characteristics are judged with the gain it finds (exponent 1 when it is not found)."""
    V, Z = robust_peak(samples.v), robust_peak(samples.z)
    passive = samples.passive
    ps = samples.select(passive)
    columns_all = passive_features(samples, V, Z)
    findings = []
    if passive.sum() < MIN_SAMPLES:
        F_P = np.zeros_like(samples.F)
        passive_ok = False
    else:
        columns = {g: col[passive] for g, col in columns_all.items()}
        theta = fit_groups(columns, ps.F, PASSIVE_GROUPS).coefficients
        F_P = sum(columns_all[g] @ theta[g] for g in PASSIVE_GROUPS)
        passive_ok = True
    controlled = ~passive
    sa = samples.select(controlled)
    observable = samples.u_passive is not None and samples.u_span > 0
    readable = controlled.sum() >= MIN_SAMPLES and passive_ok
    n = _best_exponent(sa, sa.F - F_P[controlled], V, Z) if observable and readable else 1.0
    sa_linear = semiactive_features(sa, V, Z)
    exponent_row = next((c for c in CHARACTERISTICS.values() if c.exponent), None)
    if exponent_row is not None and observable and readable:
        nonlinear = _judge(
            exponent_row,
            semiactive_features(sa, V, Z, n),
            sa.F - F_P[controlled],
            sa.F,
            SEMIACTIVE_GROUPS,
            V,
            Z,
            threshold,
            "semi-active FM diagram",
            sa_linear,
            n,
        )
        n = n if nonlinear.found else 1.0
    sa_columns = semiactive_features(sa, V, Z, n)
    columns_damper = {**columns_all, **semiactive_features(samples, V, Z, n)}
    for c in CHARACTERISTICS.values():
        if c.stage == "damper":
            findings.append(
                _judge(
                    c,
                    columns_damper,
                    samples.F,
                    samples.F,
                    PASSIVE_GROUPS + SEMIACTIVE_GROUPS,
                    V,
                    Z,
                    threshold,
                    "FV and FM diagrams",
                )
            )
        elif c.stage == "passive":
            if not passive_ok:
                findings.append(
                    _unobservable(
                        c, f"{int(passive.sum())} samples at the passive control (need {MIN_SAMPLES})", threshold
                    )
                )
                continue
            findings.append(
                _judge(
                    c, columns, ps.F, ps.F, PASSIVE_GROUPS, V, Z, threshold, f"passive {c.diagram.split()[-1]} diagram"
                )
            )
        else:
            if not observable:
                findings.append(_unobservable(c, "the control never varies (no semi-active force to read)", threshold))
                continue
            if not readable:
                findings.append(
                    _unobservable(
                        c,
                        f"{int(controlled.sum())} samples above the passive control and "
                        f"{int(passive.sum())} at it (need {MIN_SAMPLES} of each)",
                        threshold,
                    )
                )
                continue
            if c.exponent:
                findings.append(nonlinear)
                continue
            # the semi-active fit explains F_SA (eq 1); its ESR is over the damper force F_D (eq 7)
            findings.append(
                _judge(
                    c,
                    sa_columns,
                    sa.F - F_P[controlled],
                    sa.F,
                    SEMIACTIVE_GROUPS,
                    V,
                    Z,
                    threshold,
                    f"semi-active {c.diagram.split()[-1]} diagram",
                )
            )
    return findings, F_P
