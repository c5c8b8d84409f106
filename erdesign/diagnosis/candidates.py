"""Candidates (stage 5 of diagnosis): every effect not yet in the model added in turn and refitted, scored by the
effective Bayesian information criterion, on held-out data and against what the record itself bounds.
"""

from __future__ import annotations

import math
from functools import partial
from dataclasses import dataclass, field

import numpy as np

from ..damper import Damper
from ..data.measurement import Measurement
from ..effects import EFFECTS
from ..effects.chain import PhysicsDamper
from ..errors import ErdesignError
from ..identification.engine import at_bound
from ..identification.fit import FitResult
from .calibration import _finite_or_none, _fit, fitted_model, unseen_reason

__all__ = [
    "Candidate",
    "rank_candidates",
    "parameters_at_bounds",
    "MIN_GAIN",
    "BIC_THRESHOLD",
    "HELD_OUT_GAIN",
    "RECORD_BOUNDS",
    "CLOSE_RIVALS",
    "CLEARLY_WHITER",
]


#: A candidate must lower the residual sum of squares by at least this fraction ...
MIN_GAIN = 0.05


#: ... and the effective BIC by at least this much (Kass and Raftery: > 10 is "very strong" evidence).
BIC_THRESHOLD = 10.0


#: Fraction of the held-out residual sum of squares the candidate must remove.
HELD_OUT_GAIN = 0.02


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
    rank_bic: float = math.inf
    """BIC change with the effective sample count shared by all candidates: the order of the ranking."""
    blocked: str = ""
    """Why it may not be named whatever its fit (a data finding that mimics it), or empty."""

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


def _effective_n(residual: np.ndarray) -> float:
    """Number of independent residuals: n (1 - rho1)/(1 + rho1) for lag-1 autocorrelation rho1 >= 0."""
    r = residual - residual.mean()
    denom = float(np.dot(r, r))
    rho = float(np.dot(r[1:], r[:-1]) / denom) if denom > 0 else 0.0
    rho = min(max(rho, 0.0), 0.99)
    return max(r.size * (1 - rho) / (1 + rho), 10.0)


def _bic(rss: float, n: int, k: int, n_eff: float) -> float:
    return n_eff * math.log(max(rss / n, 1e-300)) + k * math.log(n_eff)


#: Candidates whose residual sums of squares lie within this factor of the best are close rivals: among them the
#: whiteness of what each leaves decides (see :func:`rank_candidates`).
CLOSE_RIVALS = 2.0


#: ... when the effective sample counts they leave differ by at least this factor (else their residuals are about
#: equally structured - by another effect still missing, say - and whiteness tells little).  Set between measured
#: cases, not derived: 1.64 and 2.27 on truth-rig records of pre-yield elasticity that compressibility fits within 2x
#: (the whiter fit is the true one), 1.13 on one where both leave a residual structured by a missing shear thinning,
#: and 1.43 on the 30 Quiroz records (real data, truth unknown; pre-yield elasticity has the smaller sum of squares
#: and keeps the lead).
CLEARLY_WHITER = 1.5


def rank_candidates(ranking: list, base: FitResult) -> None:
    """Sort ``ranking`` in place, best first.

    Evaluated candidates are ranked by the BIC change with one effective sample count for all (the smallest any of
    them leaves), so that candidates with as many parameters are ranked by their residual sum of squares.  Close
    rivals, whose residual sums of squares lie within :data:`CLOSE_RIVALS` of the best, are ordered among
    themselves by the BIC change with each one's own effective count (:attr:`Candidate.delta_bic`): a fit that
    leaves correlated residual has missed structure, and when two fits are this close that structure is the better
    evidence - when it is clear, the effective counts differing by :data:`CLEARLY_WHITER` at least.  (Two springs in
    series - pre-yield elasticity and compressibility - fit one record almost equally well; the true one leaves a
    white residual, the other one that follows the reversals.)
    """
    evaluated = [c for c in ranking if c.evaluated]
    if evaluated:
        n_common = min(_effective_n(c.result.residual) for c in evaluated)
        for c in evaluated:
            c.rank_bic = _bic(c.result.rss, base.n, c.result.k, n_common) - _bic(base.rss, base.n, base.k, n_common)
    ranking.sort(key=lambda c: (not c.evaluated, c.rank_bic if c.evaluated else math.inf))
    if len(evaluated) > 1 and ranking[0].rank_bic < 0:
        best_rss = ranking[0].result.rss
        close = [c for c in ranking if c.evaluated and c.rank_bic < 0 and c.result.rss <= CLOSE_RIVALS * best_rss]
        whiteness = [_effective_n(c.result.residual) for c in close]
        if len(close) > 1 and max(whiteness) >= CLEARLY_WHITER * min(whiteness):
            rest = [c for c in ranking if c not in close]
            ranking[:] = sorted(close, key=lambda c: c.delta_bic) + rest


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
    for name in result.free if names is None else names:
        if name not in result.free:
            continue
        p = result.model.parameter(name)
        side = at_bound(p, result.values[name])
        if side:
            out.append(f"{name} at its {side} bound {p.format(p.lower if side == 'lower' else p.upper)}")
    return out


def _evaluate(
    base_model: PhysicsDamper,
    base: FitResult,
    work: Measurement,
    effects: tuple,
    added: tuple,
    damper: Damper,
    start=None,
    mask=None,
) -> Candidate:
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
        return Candidate(
            name, None, None, reason="could not be evaluated: " + (errors[0] if errors else "no fit"), effects=added
        )
    n_eff = _effective_n(res.residual)
    delta_bic = _bic(res.rss, base.n, res.k, n_eff) - _bic(base.rss, base.n, base.k, n_eff)
    cand = Candidate(name, res, res.esr, delta_bic, 1 - res.rss / base.rss if base.rss > 0 else 0.0, effects=added)
    names = [p.name for e in added for p in EFFECTS[e].parameters(damper)]
    cand.at_bounds = parameters_at_bounds(res, names)
    cand.implausible = [f"{e}: {note}" for e in added for note in EFFECTS[e].implausible(damper, res.values)]
    cand.plausibility = "; ".join(EFFECTS[e].plausibility(damper, res.values) for e in added)
    return cand


def _evaluate_task(fixed: tuple, task: tuple) -> Candidate:
    """One candidate fit as an executor task: ``fixed`` = (base model, base fit, record, effects, damper, mask),
    ``task`` = (added effects, start)."""
    base_model, base, work, effects, damper, mask = fixed
    added, start = task
    return _evaluate(base_model, base, work, effects, added, damper, start=start, mask=mask)


def evaluate_candidates(
    base_model: PhysicsDamper,
    base: FitResult,
    work: Measurement,
    effects: tuple,
    tasks: list[tuple[tuple, dict | None]],
    damper: Damper,
    mask=None,
    executor=None,
) -> list:
    """:func:`_evaluate` for each ``(added effects, start)`` of ``tasks``, each an independent fit on the executor
    (:mod:`erdesign.executor`; default in this process), in the order of ``tasks``."""
    from ..executor import SerialExecutor

    ex = executor if executor is not None else SerialExecutor()
    return ex.map(partial(_evaluate_task, (base_model, base, work, effects, damper, mask)), tasks)


def _cannot_judge(name: str, records, work: Measurement, damper: Damper) -> str | None:
    """Why the records cannot show effect ``name`` (None: they can; :func:`erdesign.diagnosis.calibration.
    unseen_reason`)."""
    return unseen_reason(EFFECTS[name], records, damper)


def _beyond_record(cand: Candidate, work: Measurement, mask) -> list[str]:
    """Fitted sizes that the record itself rules out (:data:`RECORD_BOUNDS`): a mass, spring or friction that alone
    would exceed the largest measured force, or a bypass so open that it could not hold the measured force."""
    keep = np.ones(len(work), dtype=bool) if mask is None else mask
    F_max = float(np.max(np.abs(work.force[keep]))) if keep.any() else 0.0
    if not F_max > 0:
        return []
    out = []
    for name, (size, what, low) in RECORD_BOUNDS.items():
        if name not in cand.result.values:
            continue
        value = cand.result.values[name]
        force = abs(value) * size(work)
        text = fitted_model(cand.result).parameter(name).format(value).strip()
        if not low and force > 2.0 * F_max:
            out.append(
                f"{name} = {text} {what} about {force:.3g} N, more than twice the largest measured force {F_max:.3g} N"
            )
        elif low and force < 0.5 * F_max:
            out.append(
                f"{name} = {text} {what} about {force:.3g} N, less than half the largest measured force "
                f"{F_max:.3g} N: the bypass would relieve the pressure the record shows"
            )
    return out


#: Parameter -> (the record's quantity it multiplies into a force, what that force is, whether the bound is a lower
#: one): the bound the record sets.  A bypass in parallel with the ducts carries at most the whole flow, so the force
#: can never exceed the bypass damping times the speed: a bypass whose whole-flow force at the peak speed lies well
#: below the measured force is impossible; one far above it only leaks a little (creep below yield), as a bypass does.
RECORD_BOUNDS = {
    "bypass_damping": (
        lambda r: float(np.max(np.abs(r.velocity))),
        "would carry the whole flow at the peak speed with",
        True,
    ),
    "slug_mass": (lambda r: float(np.max(np.abs(r.acceleration))), "would need at the peak acceleration", False),
    "gas_stiffness": (lambda r: 0.5 * float(np.ptp(r.displacement)), "would push over half the stroke with", False),
    "friction_force": (lambda r: 1.0, "is a friction force of", False),
}


def _held_out(prep) -> np.ndarray:
    """True on the held-out samples: with several records every second record (record-wise cross-validation),
    with one every third of twelve time blocks (:func:`_held_out_mask`)."""
    if len(prep.segments) > 1:
        held = np.zeros(len(prep.work), dtype=bool)
        for i, (_, seg) in enumerate(prep.segments):
            held[seg] = i % 2 == 1
        return held
    return _held_out_mask(prep.work)


def _held_out_gain(
    base_model: PhysicsDamper, cand: Candidate, record: Measurement, mask=None, held: np.ndarray | None = None
) -> float:
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
