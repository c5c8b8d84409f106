r"""Compare the physics damper with a measurement, see where it fails, find the missing effect, add it, refit.

The workflow (docs/diagnosis.md explains how it judges):

1. **Calibrate** the baseline (quasi-steady damper of the file, with a viscosity and a yield-stress factor, plus the
   effects already accepted) to the record by bounded least squares (:func:`erdesign.identification.fit.fit`).
2. **Residual analysis** (:func:`residual_analysis`): where in the cycle the error lives (reversals / pre-yield,
   post-yield, high speed, late in the test, after field changes) and what it looks like, by regressing the
   residual on the signatures of the effects (Vivas-López et al. Table 2: characteristic -> diagram -> model term), said in
   words ("residual is odd in velocity and flat in magnitude: Coulomb-like, about 110 N: seal friction").
3. **Candidates**: every effect not yet in the model is added in turn and the model refitted.  The improvement is
   judged honestly: by the Bayesian information criterion with the number of samples reduced to the effective
   number of independent residuals the candidate leaves (lag-1 autocorrelation), by a minimum relative gain, and for the best
   candidates on held-out cycles (fitted on two thirds of the record, scored on the rest).  When no candidate
   passes, the answer is "no significant missing effect" (``missing_effect`` is None).
4. **Improve** (:func:`improve`): add the missing effect, refit, re-rank, until nothing significant is left; the
   history shows the ESR falling step by step.

Every model is fitted and judged on the samples where the sign of the velocity is known
(:func:`erdesign.data.noise.sign_known`): at a reversal the force of a yield-stress fluid jumps by twice the yield
force, and where the record cannot tell the sign no model can predict it.  There the noise floor is the load cell's
noise alone.  Long records are analysed on an evenly thinned copy of at most ``max_samples`` samples (derivatives are
taken on the full record first); the ESRs reported are those of the full record.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Mapping, Sequence

import numpy as np

from ..damper import Damper
from ..data.measurement import Measurement
from ..data.metrics import esr
from ..data.findings import excluded_mask, find_data_problems
from ..data.noise import velocity_noise
from ..effects import EFFECT_NAMES, EFFECTS, EffectError, parse_effect_names
from ..effects.base import peak_speed, reversal_count
from ..effects.chain import PhysicsDamper, check_control
from ..errors import ErdesignError
from ..identification.fit import FitResult, fit
from ..models.base import Model
from .floor import noise_floor
from .records import MAX_SAMPLES, prepare

__all__ = ["Diagnosis", "Candidate", "ResidualAnalysis", "History", "calibrate", "residual_analysis", "diagnose",
           "improve", "fitted_model", "parameters_at_bounds", "DiagnosisError", "MIN_GAIN", "BIC_THRESHOLD",
           "MAX_SAMPLES", "VERDICTS"]

#: A candidate must lower the residual sum of squares by at least this fraction ...
MIN_GAIN = 0.05
#: ... and the effective BIC by at least this much (Kass and Raftery: > 10 is "very strong" evidence).
BIC_THRESHOLD = 10.0
#: Fraction of the held-out residual sum of squares the candidate must remove.
HELD_OUT_GAIN = 0.02


class DiagnosisError(ErdesignError):
    """The record cannot be diagnosed (too short, wrong control, unknown effect)."""


# ---------------------------------------------------------------------------------------------------- fitting
def _free_parameters(model: PhysicsDamper, record: Measurement) -> list[str]:
    free = list(model.parameter_names)
    if not np.any(np.abs(record.control) > 0) or model.damper.fluid.yield_stress == 0:
        free.remove("yield_stress_factor")        # no field: the yield stress cannot be seen
    return free


def calibrate(damper: Damper, record: Measurement | Sequence[Measurement], effects: Sequence[str] | str = (), *,
              start: Mapping[str, float] | None = None, exclude_clipped: bool | None = None,
              max_samples: int = MAX_SAMPLES) -> FitResult:
    """Fit the baseline (two calibration factors) plus ``effects`` to one record or several records of one damper.

    The fit runs on the samples :func:`diagnose` judges (:mod:`erdesign.diagnosis.records`: transients kept at full
    rate, the sign of the velocity known, clipped samples left out), so the ESR it states is the one
    ``erdesign diagnose`` states for the same model.  ``fitted_model(result)`` gives the model for a whole record.

    Raises a one-line error when a record's control does not match the damper or an effect cannot be seen in
    the records.
    """
    records = _as_records(record)
    model = PhysicsDamper(damper, effects)
    for r in records:
        check_control(damper, r)
        _check_record(r)
    _check_effects_seen(model, records, damper)
    findings = data_findings(records, exclude_clipped=exclude_clipped)
    prep = prepare(records, [excluded_mask([f for f in findings if f.record == _name(r, i)], len(r))
                             for i, r in enumerate(records)], max_samples=max_samples)
    result = _fit(model, prep.work, start, mask=prep.mask())
    result.findings = findings
    result.records = _record_esrs(model, result.values, prep.work, prep)
    return result


def _check_effects_seen(model: PhysicsDamper, records: Sequence[Measurement], damper: Damper) -> None:
    """A one-line error when no record can show one of the model's effects (each record asked on its own)."""
    for e in model.effects:
        whys = [e.check(r, damper) for r in records]
        if all(whys):
            raise EffectError(f"{e.name}: cannot be judged from {records[0].name or 'this record'}"
                              + (f" or the other {len(records) - 1} records" if len(records) > 1 else "")
                              + f": {whys[0]}")


def data_findings(records: Sequence[Measurement], *, exclude_clipped: bool | None = None) -> list:
    """Data-quality findings of every record (:func:`erdesign.data.findings.find_data_problems`), each naming its
    record."""
    out = []
    for i, r in enumerate(records):
        named = r if r.name else replace(r, name=_name(r, i))
        out += find_data_problems(named, exclude_clipped=exclude_clipped)
    return out


def _fit(model: PhysicsDamper, record: Measurement, start=None, mask=None) -> FitResult:
    free = _free_parameters(model, record)
    guess = {**model.initial_guess(record), **{k: v for k, v in (start or {}).items()
                                                if k in model.parameter_names}}
    fixed = {} if "yield_stress_factor" in free else {"yield_stress_factor": guess.get("yield_stress_factor", 1.0)}
    if mask is None:
        return fit(model, record, free=free, fixed=fixed, start=guess, max_nfev=200)
    masked = _Masked(model, record, mask)
    return fit(masked, record.select(mask), free=free, fixed=fixed, start=guess, max_nfev=200)


class _Masked(Model):
    """A model simulated on the whole record but compared on the samples of a mask (held-out validation)."""

    def __init__(self, model: PhysicsDamper, record: Measurement, mask: np.ndarray):
        self.inner, self.full, self.mask = model, record, mask
        self.name, self.title, self.parameters = model.name, model.title, model.parameters

    def initial_guess(self, record):
        return self.inner.initial_guess(self.full)

    @property
    def damper(self):
        return self.inner.damper

    def force(self, record, values):
        return self.inner.force(self.full, values)[self.mask]


def fitted_model(result: FitResult) -> PhysicsDamper:
    """The physics model of a fit, for the whole record: diagnosis fits on the samples where the sign of the
    velocity is known, through a wrapper whose ``simulate`` returns those samples only; this unwraps it.

    >>> from erdesign import load_example
    >>> from erdesign.simulation.rig import run_rig, sine
    >>> record = run_rig(load_example("makris"), sine(0.005, 2.0, 3e6, cycles=2, rate=200), seed=1).record
    >>> d = diagnose(load_example("makris"), record, candidates=["seal_friction"])
    >>> model = fitted_model(d.baseline)
    >>> model.simulate(record, d.baseline.values).shape == record.force.shape
    True
    """
    return getattr(result.model, "inner", result.model)


# ---------------------------------------------------------------------------------------------------- residuals
@dataclass
class ResidualAnalysis:
    """Where the residual of a fitted model lives and what it looks like."""

    rms: float
    """RMS residual, [N]."""
    regions: dict[str, tuple[float, float]]
    """region -> (fraction of samples, RMS residual there over the overall RMS)."""
    signatures: dict[str, float]
    """signature -> fitted size (N, kg, N/m ...) of the residual projected on it."""
    shares: dict[str, float]
    """signature -> fraction of the residual variance it explains alone."""
    findings: list[str]
    """The readable conclusions, strongest first."""

    def report(self) -> str:
        lines = [f"  RMS residual {self.rms:.4g} N; where it lives (share of samples, RMS there / overall):"]
        for name, (frac, ratio) in self.regions.items():
            lines.append(f"    {name:<24} {100 * frac:5.1f} %   {ratio:5.2f}")
        if self.findings:
            lines.append("  what it looks like:")
            lines.extend(f"    - {f}" for f in self.findings)
        else:
            lines.append("  what it looks like: no pattern stands out of the noise")
        return "\n".join(lines)


def _regions(record: Measurement, weight: np.ndarray | None = None) -> dict[str, np.ndarray]:
    v = record.velocity
    peak = max(peak_speed(record), 1e-12)
    t = record.time
    T = t[-1] - t[0]
    on = np.abs(record.control) > 0
    regions = {
        "pre-yield (|v| < 5 %)": (np.abs(v) < 0.05 * peak) & on,
        "reversals (|v| < 15 %)": np.abs(v) < 0.15 * peak,
        "post-yield (|v| >= 15 %)": np.abs(v) >= 0.15 * peak,
        "high velocity (> 70 %)": np.abs(v) > 0.7 * peak,
        "first third": t < t[0] + T / 3,
        "late in the test": t > t[0] + 2 * T / 3,
        "moving in + (v > 0)": v > 0.15 * peak,
        "moving in - (v < 0)": v < -0.15 * peak,
    }
    u = np.abs(record.control)
    if u.max() > 0:
        change = np.flatnonzero(np.abs(np.diff(u)) > 0.1 * u.max())
        after = np.zeros(len(record), bool)
        for i in change:
            after[(t > t[i]) & (t < t[i] + 0.03)] = True
        if after.any():
            regions["30 ms after field changes"] = after
    return regions


def residual_analysis(model: PhysicsDamper, result: FitResult, record: Measurement,
                      mask: np.ndarray | None = None) -> ResidualAnalysis:
    """Locate the residual of ``result`` in the cycle and project it on the signatures of the effects (on the
    samples of ``mask`` only, when given: diagnosis leaves out those where the velocity's sign is unknown).

    Signatures (each a regressor, fitted one at a time to say how much of the residual it explains alone):
    ``sgn(v)`` (Coulomb friction), ``a`` (inertia), ``x`` and a constant (gas spring), time x model force (heating),
    the residual near reversals (pre-yield elasticity, compressibility, leakage) and after field changes (lag).
    """
    keep = np.ones(len(record), dtype=bool) if mask is None else np.asarray(mask, dtype=bool)
    comps = model.components(record, result.values)
    r = (record.require_force() - comps["force"])[keep]
    rms = float(np.sqrt(np.mean(r**2))) or 1e-300
    regions = {}
    for name, m in _regions(record).items():
        m = m[keep]
        if m.any():
            regions[name] = (float(m.mean()), float(np.sqrt(np.mean(r[m] ** 2)) / rms))
    t = record.time
    tn = (t - t[0]) / max(t[-1] - t[0], 1e-12)
    peak = max(peak_speed(record), 1e-12)
    basis = {
        "coulomb": np.tanh(record.velocity / (0.01 * peak)),
        "acceleration": record.acceleration,
        "displacement": record.displacement - record.displacement.mean(),
        "offset": np.ones(len(record)),
        "drift": (tn - tn.mean()) * comps["fluid"],
    }
    var = float(np.sum((r - r.mean()) ** 2)) or 1e-300
    sizes, shares = {}, {}
    for name, b in basis.items():
        b = b[keep]
        bb = b if name == "offset" else b - b.mean()
        denom = float(np.dot(bb, bb))
        if denom <= 0:
            continue
        c = float(np.dot(bb, r - (0 if name == "offset" else r.mean())) / denom)
        sizes[name] = c
        shares[name] = float(c**2 * denom / (var if name != "offset" else float(np.sum(r**2)) or 1e-300))
    findings = []
    words = {
        "coulomb": lambda c: (f"residual is odd in velocity and flat in magnitude: Coulomb-like, about {abs(c):.3g} N"
                              f"{'' if c > 0 else ' (negative: less friction than assumed)'}: seal friction"),
        "acceleration": lambda c: (f"residual follows the acceleration: an extra mass of about {c:.3g} kg: fluid "
                                   f"inertia (prior {EFFECTS['fluid_inertia'].prior(model.damper)['slug_mass']:.3g} kg)"
                                   if c > 0 else
                                   "residual follows minus the acceleration: the measured force leads the model's "
                                   "(no mass is negative: a phase error, such as a skewed or filtered channel, or a "
                                   "lag in the model that the record does not have)"),
        "displacement": lambda c: (f"residual grows with the displacement: a spring of about {c:.3g} N/m: gas spring"
                                   if c > 0 else
                                   "residual falls as the displacement grows: not a spring (no stiffness is "
                                   "negative): an offset or drift of the displacement channel, or a one-sided "
                                   "mechanism"),
        "offset": lambda c: f"residual has a constant offset of about {c:.3g} N: gas-spring preload (or load-cell zero)",
        "drift": lambda c: (f"the model force is {'too high' if c < 0 else 'too low'} late in the test "
                            f"(by about {abs(c) * 100:.2g} % of the fluid force over the record): "
                            f"{'viscous heating' if c < 0 else 'a drift (cooling, warm-up of the rig?)'}"),
    }
    for name in sorted(shares, key=shares.get, reverse=True):
        if shares[name] > 0.1:
            findings.append(f"{words[name](sizes[name])} [explains {100 * shares[name]:.0f} % of the residual]")
    rev = regions.get("reversals (|v| < 15 %)")
    if rev and rev[1] > 1.5:
        findings.append(f"the error is concentrated at the reversals ({rev[1]:.2g} x the overall RMS there): "
                        "the force does not jump as the rigid-plastic model does: pre-yield elasticity, "
                        "compressibility (zero field too) or leakage (creep below yield)")
    after = regions.get("30 ms after field changes")
    if after and after[1] > 1.5:
        findings.append(f"the error is concentrated right after field changes ({after[1]:.2g} x the overall RMS): "
                        "the fluid follows the field late: field lag")
    high = regions.get("high velocity (> 70 %)")
    if high and high[1] > 1.5:
        findings.append(f"the error is largest at high speed ({high[1]:.2g} x the overall RMS): the force-velocity "
                        "curve bends (shear thinning) or lags (compressibility)")
    plus, minus = regions.get("moving in + (v > 0)"), regions.get("moving in - (v < 0)")
    if plus and minus and max(plus[1], minus[1]) > 1.5 * max(min(plus[1], minus[1]), 1e-12):
        big = "+" if plus[1] > minus[1] else "-"
        findings.append(f"the residual is asymmetric: {max(plus[1], minus[1]) / max(min(plus[1], minus[1]), 1e-12):.2g} "
                        f"x larger moving in {big} than in the other direction: something acts one way only (a "
                        "blow-off or check valve, the unequal areas of a single-ended rod, cavitation); no effect of "
                        "the library is one-sided")
    late, first = regions.get("late in the test"), regions.get("first third")
    if late and first and late[1] > 1.5 * first[1]:
        findings.append(f"the error grows over the test (late / early RMS {late[1] / max(first[1], 1e-12):.2g}): "
                        "something changes with time: viscous heating")
    return ResidualAnalysis(rms, regions, sizes, shares, findings)


# ---------------------------------------------------------------------------------------------------- judging
@dataclass
class Candidate:
    """One effect (or a pair) added to the model and refitted."""

    effect: str
    result: FitResult | None
    esr: float | None
    """ESR after adding it and refitting (full record); None when it could not be evaluated (see :attr:`reason`)."""
    delta_bic: float = math.inf
    """Effective BIC of the candidate minus that of the current model (negative: better)."""
    gain: float = 0.0
    """Fraction of the residual sum of squares removed."""
    held_out_gain: float | None = None
    """Fraction of the held-out residual sum of squares removed (None: not checked)."""
    plausibility: str = ""
    significant: bool = False
    note: str = ""
    explained: float = 0.0
    """Fraction of the baseline's excess over the noise floor that the candidate removes."""
    implausible: list = field(default_factory=list)
    """What is implausible about its fitted size (empty: nothing)."""
    at_bounds: list = field(default_factory=list)
    """Its parameters that ended at a bound of their range."""
    reason: str = ""
    """Why it could not be evaluated (then :attr:`esr` is None) - or why it was not named."""
    effects: tuple = ()
    """The effects it adds: ``(effect,)``, or two for a pair."""

    def __post_init__(self):
        if not self.effects:
            self.effects = (self.effect,)

    @property
    def evaluated(self) -> bool:
        return self.result is not None and self.esr is not None

    def parameters(self, digits: int = 4) -> dict[str, str]:
        """The effects' fitted parameters with units (strings)."""
        if self.result is None:
            return {}
        out = {}
        model = fitted_model(self.result)
        for e in self.effects:
            for p in EFFECTS[e].parameters(model.damper):
                out[p.name] = model.parameter(p.name).format(self.result.values[p.name], digits).strip()
        return out

    def uncertainties(self) -> dict[str, str]:
        if self.result is None:
            return {}
        out = {}
        for e in self.effects:
            for p in EFFECTS[e].parameters(fitted_model(self.result).damper):
                se = self.result.stderr.get(p.name, math.nan)
                out[p.name] = p.format(se, 2) if math.isfinite(se) else "not identifiable"
        return out

    def as_json(self) -> dict:
        out = {"effect": self.effect, "esr": _finite_or_none(self.esr), "parameters": self.parameters()}
        if len(self.effects) > 1:
            out["effects"] = list(self.effects)
        if self.reason:
            out["reason"] = self.reason
        return out


def _finite_or_none(x):
    return float(x) if x is not None and math.isfinite(x) else None


def _effective_n(residual: np.ndarray) -> float:
    """Number of independent residuals: n (1 - rho1)/(1 + rho1) for lag-1 autocorrelation rho1 >= 0."""
    r = residual - residual.mean()
    denom = float(np.dot(r, r))
    rho = float(np.dot(r[1:], r[:-1]) / denom) if denom > 0 else 0.0
    rho = min(max(rho, 0.0), 0.99)
    return max(r.size * (1 - rho) / (1 + rho), 10.0)


def _bic(rss: float, n: int, k: int, n_eff: float) -> float:
    return n_eff * math.log(max(rss / n, 1e-300)) + k * math.log(n_eff)


def _held_out_mask(record: Measurement, blocks: int = 12) -> np.ndarray:
    """True on the held-out samples: every third of ``blocks`` equal time blocks (interleaved, so every part of a
    sweep is in both the training and the held-out set)."""
    t = record.time
    idx = np.minimum(((t - t[0]) / max(t[-1] - t[0], 1e-12) * blocks).astype(int), blocks - 1)
    return idx % 3 == 1


def parameters_at_bounds(result: FitResult, names=None) -> list[str]:
    """Free parameters among ``names`` (default: all free ones) that ended at (within 1e-6 of the range of) a
    bound, as text: ``"slug_mass at its lower bound 0 kg"``.  A value at a bound is not an estimate: the data
    pushed it there (a missing effect, a unit mistake, or a parameter the record cannot tell)."""
    out = []
    for name in (result.free if names is None else names):
        if name not in result.free:
            continue
        p = result.model.parameter(name)
        v = result.values[name]
        lo, hi = p.lower, p.upper
        if p.log_scale:
            v, lo, hi = math.log(v), math.log(lo), (math.log(hi) if math.isfinite(hi) else hi)
        span = (hi - lo) if math.isfinite(hi - lo) else max(abs(v), 1.0)
        if v - lo <= 1e-6 * span:
            out.append(f"{name} at its lower bound {p.format(p.lower)}")
        elif math.isfinite(hi) and hi - v <= 1e-6 * span:
            out.append(f"{name} at its upper bound {p.format(p.upper)}")
    return out


VERDICTS = ("missing_effect", "nothing_missing", "unexplained")


@dataclass
class Diagnosis:
    """The outcome of :func:`diagnose`."""

    effects: tuple[str, ...]
    """Effects already in the model."""
    baseline: FitResult
    baseline_esr: float
    analysis: ResidualAnalysis
    ranking: list[Candidate]
    missing_effect: str | None
    not_judged: dict[str, str]
    """effect -> why this record cannot show it."""
    record_name: str = ""
    samples: tuple[int, int] = (0, 0)
    """(samples of the record, samples analysed)."""
    verdict: str = "nothing_missing"
    """``"missing_effect"``, ``"nothing_missing"`` or ``"unexplained"`` (docs/cli.md)."""
    noise_floor_esr: float = 0.0
    """ESR that the record's noise alone would leave (:func:`erdesign.data.noise.noise_floor_esr`)."""
    reason: str = ""
    """The verdict in words: why, and for ``"unexplained"`` what the residual looks like and where it lives."""
    pair: tuple[str, ...] = ()
    """When two effects are missing together: both (``missing_effect`` is the first)."""
    warnings: list = field(default_factory=list)
    """Things the user should check (a calibration at its bounds, a baseline worse than the mean ...)."""
    judged_share: float = 1.0
    """Share of the samples the verdict was judged on: those where the sign of the velocity is known
    (:func:`erdesign.data.noise.sign_known`)."""
    judged_esr: float | None = None
    """The calibrated baseline's ESR on the judged samples."""
    judged_floor: float | None = None
    """The force noise's ESR on the judged samples: the floor the verdict compares ``judged_esr`` with (the same
    as :attr:`noise_floor_esr`)."""
    findings: list = field(default_factory=list)
    """Data-quality findings made before any fit (:class:`erdesign.data.findings.Finding`)."""
    records: list = field(default_factory=list)
    """Per record: ``{"name", "samples", "esr"}`` (ESR of the calibrated model on its judged samples)."""
    noise_floor_method: str = ""
    """How the load cell's noise was found (:mod:`erdesign.diagnosis.floor`)."""

    @property
    def missing_effects(self) -> list[str]:
        """The one or two effects to add next (a pair whole), empty unless the verdict is ``missing_effect``."""
        return list(named_effects(self.missing_effect, self.pair)) if self.verdict == "missing_effect" else []

    def as_json(self) -> dict:
        """The keys of ``erdesign diagnose --json`` (docs/cli.md); no value is NaN or infinite."""
        out = {"baseline_esr": _finite_or_none(self.baseline_esr),
               "ranking": [c.as_json() for c in self.ranking],
               "missing_effect": self.missing_effect,
               "verdict": self.verdict,
               "noise_floor_esr": _finite_or_none(self.noise_floor_esr),
               "noise_floor_method": self.noise_floor_method,
               "missing_effects": self.missing_effects,
               "findings": [f.as_json() for f in self.findings],
               "records": [dict(r) for r in self.records]}
        return out

    def report(self) -> str:
        """A readable report: calibration, where it fails, the ranking with parameters and plausibility, verdict."""
        model = "baseline" + (f" + {', '.join(self.effects)}" if self.effects else "")
        lines = [f"Diagnosis of {self.record_name or 'the record'} ({self.samples[0]} samples"
                 + (f", analysed on {self.samples[1]}" if self.samples[1] != self.samples[0] else "") + ")"]
        if self.findings:
            lines.append("data findings (before any fit):")
            lines.extend(f"  - {f.kind}: {f.record}: {f.message}" + (f" ({f.where})" if f.where else "")
                         for f in self.findings)
        lines.append(f"model: {model}; calibrated ESR {self.baseline_esr:.4g}; noise floor ESR "
                     f"{self.noise_floor_esr:.3g} ({self.noise_floor_method or 'estimated'}); both judged on the "
                     f"{100 * self.judged_share:.0f} % of the analysed samples where the sign of the velocity is known "
                     "and no finding excludes them")
        if len(self.records) > 1:
            lines.append("ESR per record: " + ", ".join(
                f"{r['name']} {r['esr']:.4g}" if r["esr"] is not None else f"{r['name']} -" for r in self.records))
        for name in self.baseline.model.parameter_names:
            p = self.baseline.model.parameter(name)
            se = self.baseline.stderr.get(name)
            unc = "" if se is None else (f" ± {p.format(se, 2)}" if math.isfinite(se) else " (not identifiable)")
            lines.append(f"  {name:<22} {p.format(self.baseline.values[name])}{unc}")
        for w in self.warnings:
            lines.append(f"  warning: {w}")
        lines.append("where the model fails:")
        lines.append(self.analysis.report())
        lines.append("candidate effects (best first; ESR after adding it, effective-BIC change, share of the excess "
                     "over the noise floor it explains):")
        for i, c in enumerate(self.ranking, 1):
            mark = "*" if c.significant else " "
            if not c.evaluated:
                lines.append(f" {mark}{i}. {c.effect:<20} not evaluated: {c.reason}")
                continue
            held = "" if c.held_out_gain is None else f", held-out gain {100 * c.held_out_gain:.1f} %"
            name = " + ".join(c.effects)
            lines.append(f" {mark}{i}. {name:<20} ESR {c.esr:.4g}  dBIC {c.delta_bic:+.1f}  "
                         f"explains {100 * c.explained:.0f} %{held}")
            unc = c.uncertainties()
            for n, v in c.parameters().items():
                lines.append(f"      {n} = {v} ± {unc.get(n, '?')}")
            if c.plausibility:
                lines.append(f"      against the prior: {c.plausibility}")
            if c.at_bounds:
                lines.append(f"      at bounds: {'; '.join(c.at_bounds)}")
            if c.note:
                lines.append(f"      {c.note}")
        for e, why in self.not_judged.items():
            lines.append(f"  not judged: {e}: {why}")
        if self.verdict == "missing_effect":
            c = next(c for c in self.ranking if c.significant)
            what = " and ".join(f"{e} ({EFFECTS[e].mechanism})" for e in (self.pair or (self.missing_effect,)))
            lines.append(f"verdict: missing effect: {what} ESR {self.baseline_esr:.4g} -> {c.esr:.4g} "
                         f"(noise floor {self.noise_floor_esr:.3g})")
        elif self.verdict == "unexplained":
            lines.append("verdict: unexplained: " + self.reason)
        else:
            lines.append("verdict: nothing missing: " + self.reason)
        return "\n".join(lines)


def _implausible_record(record: Measurement, damper: Damper) -> list[str]:
    """Possible but implausible records for this damper (a likely unit mistake in a column header)."""
    out = []
    stroke = float(np.ptp(record.displacement))
    speed = float(np.max(np.abs(record.velocity)))
    Dp = damper.geometry.piston_diameter
    unit = lambda col: record.units.get(col, "SI")  # noqa: E731
    if stroke > 50 * Dp:
        out.append(f"the stroke is {stroke:.3g} m, {stroke / Dp:.3g} x the piston diameter: is the displacement "
                   f"column's unit [{unit('displacement')}] right?")
    if speed > 20.0:
        out.append(f"the piston speed reaches {speed:.3g} m/s, beyond any damper test: is the displacement or time "
                   "column's unit right?")
    F = record.force
    if F is not None:
        Fy = float(np.max(np.abs(damper.yield_force_si(record.control)))) + damper.seal_friction
        Fpred = float(np.max(np.abs(damper.force_si(np.clip(record.velocity, -20, 20), record.control))))
        Fmax = float(np.max(np.abs(F)))
        ref = max(Fpred, Fy, 1e-9)
        # (300, not 1000: a force column off by exactly a unit prefix must be caught with the model's own error)
        if Fmax > 300 * ref or Fmax < ref / 300:
            out.append(f"the measured force peaks at {Fmax:.3g} N where the damper file predicts about {ref:.3g} N: "
                       f"is the force column's unit [{unit('force')}] right?")
    return out


def _check_record(record: Measurement) -> None:
    if record.force is None:
        raise DiagnosisError(f"{record.name or 'record'}: has no force column")
    if len(record) < 50:
        raise DiagnosisError(f"{record.name or 'record'}: {len(record)} samples are too few to judge any effect "
                             "(need at least 50, over at least one cycle)")
    if reversal_count(record.velocity) < 2:
        raise DiagnosisError(f"{record.name or 'record'}: the piston reverses fewer than twice; at least one full "
                             "cycle is needed to judge any effect")
    for name, a in (("force", record.force), ("displacement", record.displacement), ("velocity", record.velocity)):
        if not np.all(np.isfinite(a)):
            raise DiagnosisError(f"{record.name or 'record'}: the {name} has non-finite values")


#: Widths of the expected sign at a reversal tried in the baseline calibration, in units of the velocity noise.
SIGN_WIDTHS = (0.0, 0.5, 1.0, 2.0)
#: The baseline's ESR counts as "at the noise floor" up to this multiple of the floor (plus ABSOLUTE_SLACK) ...
AT_FLOOR = 1.25
#: ... and as "well above" it (something is missing) beyond this multiple.
WELL_ABOVE = 3.0
#: ESR slack for records with almost no noise (model and derivative round-off).
ABSOLUTE_SLACK = 2e-5
#: A named effect must remove at least this share of the baseline's excess over the noise floor.
EXPLAINS = 0.6
#: Below this share explained by the best single effect, pairs are searched jointly.
PAIR_SEARCH_BELOW = 0.85
#: With the baseline within AT_FLOOR x the estimated floor, a candidate is named only on overwhelming evidence:
#: an effective-BIC fall beyond STRICT_BIC and a held-out gain beyond STRICT_HELD_OUT.
STRICT_BIC = 100.0
STRICT_HELD_OUT = 0.3
#: How many of the best single candidates enter the pair search.
PAIR_POOL = 4


def _evaluate(base_model: PhysicsDamper, base: FitResult, work: Measurement, effects: tuple, added: tuple,
              damper: Damper, start=None, mask=None) -> Candidate:
    """Fit the model with ``added`` effects; a candidate that cannot be evaluated says why (never raises)."""
    name = added[0] if len(added) == 1 else " + ".join(added)
    model = base_model.with_effects(effects + added)
    starts = [{**base.values, **(start or {})}]
    starts.append({**base.values, **{k: v for e in added for k, v in EFFECTS[e].neutral_values(damper).items()}})
    res, errors = None, []
    for s in starts:
        try:
            r = _fit(model, work, start=s, mask=mask)
        except (ErdesignError, FloatingPointError, ValueError, ZeroDivisionError) as exc:
            errors.append(str(exc))
            continue
        if not math.isfinite(r.rss):
            errors.append("the fit ended at non-finite forces")
            continue
        if res is None or r.rss < res.rss:
            res = r
        if res.rss <= base.rss:
            break
    if res is None:
        return Candidate(name, None, None, reason="could not be evaluated: " + (errors[0] if errors else "no fit"),
                         effects=added)
    n_eff = _effective_n(res.residual)
    delta_bic = _bic(res.rss, base.n, res.k, n_eff) - _bic(base.rss, base.n, base.k, n_eff)
    cand = Candidate(name, res, res.esr, delta_bic, 1 - res.rss / base.rss if base.rss > 0 else 0.0, effects=added)
    names = [p.name for e in added for p in EFFECTS[e].parameters(damper)]
    cand.at_bounds = parameters_at_bounds(res, names)
    cand.implausible = [f"{e}: {note}" for e in added for note in EFFECTS[e].implausible(damper, res.values)]
    cand.plausibility = "; ".join(EFFECTS[e].plausibility(damper, res.values) for e in added)
    return cand


def diagnose(damper: Damper, record: Measurement | Sequence[Measurement], effects: Sequence[str] | str = (), *,
             candidates: Sequence[str] | None = None, max_samples: int = MAX_SAMPLES, pairs: bool = True,
             exclude_clipped: bool | None = None, force_noise=None) -> Diagnosis:
    """Calibrate the baseline (+ ``effects``), analyse the residual, rank every other effect, give a verdict.

    Parameters
    ----------
    damper : Damper
    record : Measurement or sequence of Measurement
        One record, or several records of the same damper: they are calibrated together (one parameter set) and
        candidates are judged by how they predict the records they were not fitted on.
    effects : sequence of str or "a,b"
        Effects already in the model.
    candidates : sequence of str, optional
        Effects to judge (default: all others in the library).
    max_samples : int
        Longer records are thinned for the analysis, keeping the transients (:mod:`erdesign.diagnosis.records`).
    pairs : bool
        Search pairs of effects jointly when the best single one leaves much of the excess unexplained.
    exclude_clipped : bool, optional
        True: leave out the samples at a flat top or bottom of the force even where the detector is unsure; False:
        keep them; None (default): leave them out when found.
    force_noise : str, pint quantity or float [N], optional
        The load cell's noise when it is known; otherwise it is estimated from the record.

    Returns
    -------
    Diagnosis
        ``verdict`` is ``"missing_effect"`` (``missing_effect`` names it), ``"nothing_missing"`` (the residual is
        at the noise floor, or nothing beyond it can be told from noise) or ``"unexplained"`` (the residual stays
        well above the noise floor and no effect of the library explains it plausibly; ``reason`` says what the
        residual looks like).  Every ESR it states is judged on the same samples (:attr:`Diagnosis.judged_share`).
    """
    effects = parse_effect_names(effects)
    records = _as_records(record)
    for r in records:
        check_control(damper, r)
        _check_record(r)
    base_model = PhysicsDamper(damper, effects)
    _check_effects_seen(base_model, records, damper)
    findings = data_findings(records, exclude_clipped=exclude_clipped)
    prep = prepare(records, [excluded_mask([f for f in findings if f.record == _name(r, i)], len(r))
                             for i, r in enumerate(records)], max_samples=max_samples)
    work, mask = prep.work, prep.mask()
    known = prep.judged
    # Models are fitted and judged on the samples where the sign of the velocity is known (noise.sign_known) and
    # that no data finding excludes: at a reversal a yield-stress force jumps by twice the yield force, and where the
    # record cannot tell the sign no model can predict the force.
    sigma_v = velocity_noise(work)
    base = _fit(base_model, work, mask=mask)
    # the force at the reversals: the expected sign over the width that fits the record best (a derived velocity is
    # often better than its noise level near a reversal, where the filter's error is small)
    F = work.force
    best = None
    for f in SIGN_WIDTHS if sigma_v > 0 else (0.0,):
        trial = replace(work, velocity_noise=f * sigma_v)
        with np.errstate(all="ignore"):
            rss = float(np.sum((F - base_model.force(trial, base.values)) ** 2))
        if best is None or rss < best[0]:
            best = (rss, f, trial)
    _, width, work = best
    analysis = residual_analysis(base_model, base, work, mask)
    floor_info = noise_floor(records, prep, force_noise)
    floor = floor_info.esr
    warnings_ = [f"the calibration ends at a bound: {b}" for b in parameters_at_bounds(base, base.free)]
    suspicious = [s for r in records for s in _implausible_record(r, damper)]
    warnings_ += suspicious
    warnings_ += [f"{f.record}: {f.message}" for f in findings if f.unsafe_for]
    names = [c for c in (parse_effect_names(candidates) if candidates is not None else EFFECT_NAMES)
             if c not in effects]
    ranking: list[Candidate] = []
    not_judged: dict[str, str] = {}
    for name in names:
        why = _cannot_judge(name, records, work, damper)
        if why:
            not_judged[name] = why
            continue
        ranking.append(_evaluate(base_model, base, work, effects, (name,), damper, mask=mask))
    excess = base.esr - floor
    for c in ranking:
        if c.evaluated:
            c.explained = (base.esr - c.esr) / excess if excess > 0 else 0.0
            c.implausible += _beyond_record(c, work, mask)
    ranking.sort(key=lambda c: (not c.evaluated, c.delta_bic))
    at_floor = base.esr <= AT_FLOOR * floor + ABSOLUTE_SLACK
    well_above = base.esr > WELL_ABOVE * floor + ABSOLUTE_SLACK
    if not base.esr < 1.0:
        warnings_.append(f"the calibrated baseline leaves {100 * base.esr:.0f} % of the force variance: the damper "
                         "file does not describe this record (a unit in the header, the wrong damper, or a mechanism "
                         "far outside the model)")
    held = _held_out(prep)
    missing, pair, verdict, reason, one_sided = None, (), "nothing_missing", "", None
    if suspicious:
        verdict = "unexplained"
        reason = ("the record is implausible for this damper, so no effect is named: " + "; ".join(suspicious))
    else:
        # at the (estimated) noise floor an effect must be overwhelming - or clearly better on held-out data
        named = _judge_singles(base_model, base, work, ranking, strict=at_floor, mask=mask, held=held)
        if named is None and pairs and well_above:
            best_share = max((c.explained for c in ranking if c.evaluated), default=0.0)
            if best_share < PAIR_SEARCH_BELOW:
                named = _judge_pairs(base_model, base, work, effects, ranking, damper, excess, mask=mask, held=held)
        if named is None and not well_above:
            # never "nothing missing" while a plausible effect clearly improves the held-out data
            named = _held_out_winner(base_model, work, ranking, mask, held)
        one_sided = None if named is None else _one_sided(named, work, mask, floor)
        if one_sided is not None:
            named.significant = False
            named.note = "not named: " + one_sided
            verdict = "unexplained"
            reason = (f"{named.effect} lowers the ESR from {base.esr:.3g} to {named.esr:.3g} (noise floor "
                      f"{floor:.3g}), but what it leaves is one-sided: {one_sided}. No effect of the library acts in "
                      "one direction only: a blow-off or check valve, the unequal areas of a single-ended rod or "
                      "cavitation may be at work.")
            named = None
        if named is not None:
            missing, pair = named.effects[0], (named.effects if len(named.effects) > 1 else ())
            verdict = "missing_effect"
            held_txt = ("" if named.held_out_gain is None else
                        f", {100 * named.held_out_gain:.0f} % less error on held-out "
                        f"{'records' if len(records) > 1 else 'cycles'}")
            reason = (f"adding {' and '.join(named.effects)} lowers the ESR from {base.esr:.3g} to {named.esr:.3g} "
                      f"(noise floor {floor:.3g}), {100 * max(named.explained, 0):.0f} % of the excess, with "
                      f"plausible values{held_txt}")
    if verdict == "missing_effect" or suspicious or one_sided:
        pass
    elif at_floor:
        reason = (f"the calibrated baseline's ESR {base.esr:.3g} is at the noise floor {floor:.3g}: what is left "
                  "is noise")
    else:
        if not well_above:
            reason = (f"the calibrated baseline's ESR {base.esr:.3g} is within {WELL_ABOVE:g} x the noise floor "
                      f"{floor:.3g} and no effect removes a significant part of the rest")
        else:
            verdict = "unexplained"
            reason = _unexplained_reason(base.esr, floor, ranking, analysis)
            if warnings_:
                reason += " Check first: " + "; ".join(warnings_) + "."
    unsafe = sorted({f.kind for f in findings if f.unsafe_for and (
        verdict != "missing_effect" or set(f.unsafe_for) & set(named_effects(missing, pair)))})
    if unsafe:
        reason += (f" Unsafe: the data finding(s) {', '.join(unsafe)} (see findings) can mimic or hide a "
                   "mechanism; judge this verdict with them in mind.")
    if reason and not suspicious:
        reason += (f" (judged on {100 * known.mean():.0f} % of the analysed samples: where the sign of the velocity "
                   "is known" + (" and no data finding excludes them" if any(prep.excluded) else "") + ")")
    ranking.sort(key=lambda c: (not c.significant, not c.evaluated, c.delta_bic))
    per_record = _record_esrs(base_model, base.values, work, prep)
    return Diagnosis(effects, base, base.esr, analysis, ranking, missing, not_judged, work.name,
                     (sum(prep.full_samples), len(work)), verdict, floor, reason, pair, warnings_,
                     float(known.mean()), base.esr, floor, findings=findings, records=per_record,
                     noise_floor_method=floor_info.method)


def named_effects(missing: str | None, pair: tuple[str, ...]) -> tuple[str, ...]:
    """The effect(s) a verdict names: the pair whole, the single effect, or none."""
    return tuple(pair) or ((missing,) if missing else ())


def _name(record: Measurement, i: int) -> str:
    return record.name or f"record {i + 1}"


def _as_records(record) -> list[Measurement]:
    if isinstance(record, Measurement):
        return [record]
    records = list(record)
    if not records:
        raise DiagnosisError("no record given")
    for i, r in enumerate(records):
        if not isinstance(r, Measurement):
            raise DiagnosisError(f"record {i + 1}: expected a Measurement, got {type(r).__name__}")
    names = [_name(r, i) for i, r in enumerate(records)]
    if len(set(names)) < len(names):
        records = [replace(r, name=f"{_name(r, i)} ({i + 1})") for i, r in enumerate(records)]
    return records


def _cannot_judge(name: str, records, work: Measurement, damper: Damper) -> str | None:
    """Why the records cannot show effect ``name`` (None: they can): each full record is asked (its own sampling
    step), the candidate is judged when any record can show it."""
    whys = [EFFECTS[name].check(r, damper) for r in records]
    if any(w is None for w in whys):
        return None
    return whys[0]


def _record_esrs(model: PhysicsDamper, values, work: Measurement, prep) -> list[dict]:
    """ESR of the model on each record's judged samples."""
    with np.errstate(all="ignore"):
        Fm = model.force(work, values)
    out = []
    for (name, seg), n_full in zip(prep.segments, prep.full_samples):
        keep = prep.judged[seg]
        e = esr(work.force[seg][keep], Fm[seg][keep]) if keep.sum() > 2 else math.nan
        out.append({"name": name, "samples": int(n_full), "esr": _finite_or_none(e)})
    return out


def _held_out(prep) -> np.ndarray:
    """True on the held-out samples: with several records every second record (record-wise cross-validation),
    with one every third of twelve time blocks (:func:`_held_out_mask`)."""
    if len(prep.segments) > 1:
        held = np.zeros(len(prep.work), dtype=bool)
        for i, (_, seg) in enumerate(prep.segments):
            held[seg] = i % 2 == 1
        return held
    return _held_out_mask(prep.work)


#: A plausible candidate that removes at least this share of the held-out error is never left unnamed.
HELD_OUT_CLEAR = 0.2


def _held_out_winner(base_model, work, ranking, mask, held) -> Candidate | None:
    """The plausible candidate that most lowers the error on held-out data, when it removes at least
    :data:`HELD_OUT_CLEAR` of it (else None): a verdict ``nothing_missing`` would hide it."""
    best = None
    for c in [c for c in ranking if c.evaluated][:PAIR_POOL]:
        if c.implausible or c.at_bounds or not (c.delta_bic < -BIC_THRESHOLD and c.gain > MIN_GAIN):
            continue
        if c.held_out_gain is None:
            c.held_out_gain = _held_out_gain(base_model, c, work, mask, held)
        if c.held_out_gain >= HELD_OUT_CLEAR and (best is None or c.held_out_gain > best.held_out_gain):
            best = c
    if best is not None:
        best.significant = True
        best.note = (f"named on held-out data: it removes {100 * best.held_out_gain:.0f} % of the error there "
                     "although the calibrated model looked close to the noise floor")
    return best


def _beyond_record(cand: Candidate, work: Measurement, mask) -> list[str]:
    """Fitted sizes that the record itself rules out: a part of the model that alone would exceed the largest
    measured force (:data:`RECORD_BOUNDS`)."""
    keep = np.ones(len(work), dtype=bool) if mask is None else mask
    F_max = float(np.max(np.abs(work.force[keep]))) if keep.any() else 0.0
    if not F_max > 0:
        return []
    out = []
    for name, (size, what) in RECORD_BOUNDS.items():
        if name not in cand.result.values:
            continue
        value = cand.result.values[name]
        force = abs(value) * size(work)
        if force > 2.0 * F_max:
            unit = fitted_model(cand.result).parameter(name).format(value).strip()
            out.append(f"{name} = {unit} {what} about {force:.3g} N, more than twice the largest measured force "
                       f"{F_max:.3g} N")
    return out


#: Parameter -> (the record's quantity it multiplies into a force, what that force is): the bound the record sets.
RECORD_BOUNDS = {
    "bypass_damping": (lambda r: float(np.max(np.abs(r.velocity))),
                       "would alone carry the flow at the peak speed with"),
    "slug_mass": (lambda r: float(np.max(np.abs(r.acceleration))), "would need at the peak acceleration"),
    "gas_stiffness": (lambda r: 0.5 * float(np.ptp(r.displacement)), "would push over half the stroke with"),
    "friction_force": (lambda r: 1.0, "is a friction force of"),
}


def _least_noise(ranking) -> float:
    """The largest noise ESR the candidates allow: noise cannot exceed what a model leaves, its ESR times
    n / (n - k) for k parameters fitted to n samples (inf when none was evaluated)."""
    return min((c.esr * c.result.n / (c.result.n - c.result.k) for c in ranking
                if c.evaluated and c.result.n > c.result.k), default=math.inf)


def _judge_singles(base_model, base, work, ranking, strict: bool = False, mask=None, held=None) -> Candidate | None:
    """The best single candidate that is significant (effective BIC, gain, held-out cycles), plausible and explains
    enough of the excess over the noise floor; notes on the others say why they were not named."""
    blocked_by = None
    for c in [c for c in ranking if c.evaluated][:4]:
        if not (c.delta_bic < -(STRICT_BIC if strict else BIC_THRESHOLD) and c.gain > MIN_GAIN):
            continue
        if c.implausible:
            c.note = "not named: its fitted size is implausible (" + "; ".join(c.implausible) + ")"
            blocked_by = blocked_by or c
            continue
        if blocked_by is not None and c.explained < blocked_by.explained - 0.1:
            c.note = (f"not named: {blocked_by.effect} fits much better ({100 * blocked_by.explained:.0f} % of the "
                      f"excess against {100 * c.explained:.0f} %) but with an implausible size, so neither is the "
                      "answer")
            continue
        if not c.esr < 0.5:
            c.note = "not named: the model with it still leaves half the force variance unexplained"
            continue
        if c.explained < EXPLAINS:
            c.note = (f"not named alone: it explains only {100 * c.explained:.0f} % of the excess over the noise "
                      "floor")
            continue
        c.held_out_gain = _held_out_gain(base_model, c, work, mask, held)
        if c.held_out_gain > (STRICT_HELD_OUT if strict else HELD_OUT_GAIN):
            c.significant = True
            return c
        c.note = "does not improve the held-out cycles: fits noise or the calibration, not a mechanism"
    return None


def _judge_pairs(base_model, base, work, effects, ranking, damper, excess, mask=None, held=None) -> Candidate | None:
    """Pairs of the best single candidates fitted jointly (not greedily); the best significant, plausible pair
    that explains enough of the excess, or None."""
    pool = [c for c in ranking if c.evaluated and c.gain > 0][:PAIR_POOL]
    found = []
    for i in range(len(pool)):
        for j in range(i + 1, len(pool)):
            a, b = pool[i], pool[j]
            # each effect starts from its own single fit, the calibration from the first
            start = {**b.result.values, **a.result.values,
                     **{p.name: b.result.values[p.name] for p in EFFECTS[b.effect].parameters(damper)}}
            c = _evaluate(base_model, base, work, effects, (a.effect, b.effect), damper, start=start, mask=mask)
            if not c.evaluated:
                continue
            c.explained = (base.esr - c.esr) / excess if excess > 0 else 0.0
            best_single = min(a.result.rss, b.result.rss)
            n_eff = _effective_n(c.result.residual)
            better = _bic(c.result.rss, base.n, c.result.k, n_eff) < _bic(best_single, base.n, c.result.k - 1,
                                                                           n_eff) - BIC_THRESHOLD
            if better and not c.implausible and c.explained >= EXPLAINS and c.delta_bic < -BIC_THRESHOLD:
                found.append(c)
    if not found:
        return None
    best = min(found, key=lambda c: c.delta_bic)
    best.held_out_gain = _held_out_gain(base_model, best, work, mask, held)
    if best.held_out_gain <= HELD_OUT_GAIN:
        return None
    best.significant = True
    # name first the effect that does more alone
    singles = {c.effect: c for c in pool}
    best.effects = tuple(sorted(best.effects, key=lambda e: singles[e].delta_bic))
    best.effect = " + ".join(best.effects)
    ranking.insert(0, best)
    return best


#: What a named model leaves is one-sided (the force larger in one direction than the model's odd law allows) when
#: the one-sided term lowers the residual sum of squares by more than ONE_SIDED noise variances (a chi-square of one
#: degree of freedom: far beyond chance) ...
ONE_SIDED = 50.0
#: ... and removes at least this share of what the model leaves above the floor.
ONE_SIDED_SHARE = 0.5


def _one_sided(cand: Candidate, work: Measurement, mask, floor: float) -> str | None:
    """Whether the residual of the named model is one-sided, and how (None: it is not).

    Every effect of the library keeps the fluid force odd in the velocity; a single-ended rod (unequal areas), a
    blow-off or check valve and cavitation make it larger in one direction than in the other.  Their signature is
    an even term proportional to the size of the fluid force: the residual is regressed on :math:`|F_\text{fluid}|`
    (centred) over the judged samples.
    """
    model = fitted_model(cand.result)
    with np.errstate(all="ignore"):
        comps = model.components(work, cand.result.values)
    keep = np.ones(len(work), dtype=bool) if mask is None else mask
    F = work.force[keep]
    r = (work.force - comps["force"])[keep]
    h = np.abs(comps["fluid"])[keep]
    if not (np.all(np.isfinite(r)) and np.all(np.isfinite(h))):
        return None
    h, r0 = h - h.mean(), r - r.mean()
    hh = float(np.dot(h, h))
    ss = float(np.sum((F - F.mean()) ** 2))
    if not (hh > 0 and ss > 0):
        return None
    c = float(np.dot(h, r0)) / hh
    drop = c * c * hh / ss                         # ESR the one-sided term removes
    left = float(np.sum(r**2)) / ss - floor        # what the named model leaves above the floor
    if drop * F.size > ONE_SIDED * floor and drop > ONE_SIDED_SHARE * left:
        side = "+" if c > 0 else "-"
        return (f"the force is {100 * abs(c):.2g} % of the fluid force larger moving in {side} than the model "
                f"allows (this removes {drop / max(left, 1e-300) * 100:.0f} % of what it leaves above the floor)")
    return None


def _unexplained_reason(base_esr, floor, ranking, analysis) -> str:
    """What the residual looks like and where it lives, and why no effect of the library explains it."""
    parts = [f"the calibrated baseline's ESR {base_esr:.3g} is {base_esr / max(floor, 1e-12):.3g} x the noise floor "
             f"{floor:.3g}"]
    ev = [c for c in ranking if c.evaluated]
    if ev:
        c = max(ev, key=lambda c: c.explained)
        why = (f"its fitted size is implausible ({'; '.join(c.implausible)})" if c.implausible else
               f"it explains only {100 * max(c.explained, 0):.0f} % of the excess")
        parts.append(f"the best effect of the library, {c.effect}, does not explain it: {why}")
    looks = analysis.findings[:3]
    if looks:
        parts.append("the residual: " + "; ".join(looks))
    where = sorted(analysis.regions.items(), key=lambda kv: -kv[1][1])
    if where:
        name, (frac, ratio) = where[0]
        parts.append(f"it is largest {name} ({ratio:.2g} x the overall RMS on {100 * frac:.0f} % of the samples)")
    return "; ".join(parts) + ". A mechanism outside the effect library (a blow-off valve, asymmetric areas, " \
        "cavitation, free play, a clipped or filtered signal) or a wrong damper file may be at work."


def _held_out_gain(base_model: PhysicsDamper, cand: Candidate, record: Measurement, mask=None,
                   held: np.ndarray | None = None) -> float:
    """Fraction of the held-out RSS the candidate removes, both models fitted on the training samples only (both
    sets restricted to ``mask``, the samples judged).  ``held``: the held-out samples (default: every third of
    twelve time blocks, :func:`_held_out_mask`)."""
    held = _held_out_mask(record) if held is None else held
    train = ~held
    if mask is not None:
        held, train = held & mask, train & mask
    F = record.force
    model = fitted_model(cand.result)
    try:
        b = _fit(base_model, record, start=cand.result.values, mask=train)
        c = _fit(model, record, start=cand.result.values, mask=train)
    except ErdesignError:
        return 0.0
    with np.errstate(all="ignore"):
        rb = np.sum((F[held] - base_model.force(record, b.values)[held]) ** 2)
        rc = np.sum((F[held] - model.force(record, c.values)[held]) ** 2)
    if not (math.isfinite(rb) and math.isfinite(rc)):
        return 0.0
    return float(1 - rc / rb) if rb > 0 else 0.0


@dataclass
class History:
    """Rounds of :func:`improve`: the effects and ESR after each, and each round's diagnosis."""

    steps: list[tuple[tuple[str, ...], float]] = field(default_factory=list)
    diagnoses: list[Diagnosis] = field(default_factory=list)

    @property
    def effects(self) -> tuple[str, ...]:
        return self.steps[-1][0] if self.steps else ()

    def report(self) -> str:
        lines = ["history of the error:"]
        for effects, e in self.steps:
            lines.append(f"  ESR {e:.4g}   baseline{' + ' + ' + '.join(effects) if effects else ''}")
        return "\n".join(lines)


def improve(damper: Damper, record: Measurement | Sequence[Measurement], effects: Sequence[str] | str = (), *,
            max_rounds: int = 3, max_samples: int = MAX_SAMPLES, exclude_clipped: bool | None = None,
            force_noise=None) -> History:
    """Diagnose, add the missing effect(s), refit, re-rank - until no significant effect is missing.

    The noise floor is the same in every round (:mod:`erdesign.diagnosis.floor`: it depends on no model).

    Examples
    --------
    >>> from erdesign import load_example
    >>> from erdesign.simulation.rig import run_rig, stepped_sine
    >>> motion = stepped_sine([0.005], [2.0], [0.0, 3e6], cycles=2, rate=200)     # friction and yield stress apart
    >>> rig = run_rig(load_example("makris"), motion, hidden={"seal_friction": {"friction_force": 400.0}},
    ...               viscosity_factor=1.2, seed=2)
    >>> h = improve(load_example("makris"), rig.record, max_rounds=2)
    >>> h.effects, h.steps[-1][1] < h.steps[0][1] / 3
    (('seal_friction',), True)
    """
    effects = parse_effect_names(effects)
    history = History()
    for _ in range(max_rounds + 1):
        d = diagnose(damper, record, effects, max_samples=max_samples, exclude_clipped=exclude_clipped,
                     force_noise=force_noise)
        history.diagnoses.append(d)
        history.steps.append((effects, d.baseline_esr))
        if d.verdict != "missing_effect":
            break
        effects = effects + tuple(d.missing_effects)
    return history
