r"""Compare the physics damper with measurements, see where it fails, find the missing effect, add it, refit.

The workflow runs in stages, one module each (docs/diagnosis.md explains how it judges):

1. **Records** (:mod:`erdesign.diagnosis.records`): one or several records of one damper, thinned where that loses
   nothing (every sample after a field change and near reversals kept), joined, with the samples to judge marked:
   where the sign of the velocity is known (:func:`erdesign.data.noise.sign_known`) and no data finding
   (:mod:`erdesign.data.findings`: clipping, saturation, ...) excludes them.
2. **Noise floor** (:mod:`erdesign.diagnosis.floor`): the load cell's noise, once per record, the same in every round.
3. **Calibration** (:mod:`erdesign.diagnosis.calibration`): the baseline (quasi-steady damper of the file, with a
   viscosity and a yield-stress factor, plus the effects already accepted) fitted by bounded least squares.
4. **Residual analysis** (:mod:`erdesign.diagnosis.residuals`): where in the cycle the error lives and what it looks
   like, in words.
5. **Candidates** (:mod:`erdesign.diagnosis.candidates`): every effect not yet in the model added in turn and the
   model refitted, judged by the effective Bayesian information criterion, on held-out cycles (or, with several
   records, on the records it was not fitted on) and against what the record itself bounds.
6. **Verdict** (:mod:`erdesign.diagnosis.verdict`): ``missing_effect`` (one effect, or a pair fitted jointly),
   ``nothing_missing`` (never while a plausible effect removes a fifth of the held-out error) or ``unexplained``.
7. **Improve** (:func:`improve`): add the missing effect(s), refit, re-rank, until nothing significant is left; the
   history shows the ESR falling step by step.

Every ESR stated - the baseline's, each candidate's, each record's - and the noise floor are judged on the same
samples, so ``erdesign fit`` and ``erdesign diagnose`` give one ESR for one model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Sequence

import numpy as np

from ..damper import Damper
from ..data.findings import excluded_mask
from ..data.measurement import Measurement
from ..data.noise import velocity_noise
from ..effects import EFFECT_NAMES, EFFECTS, parse_effect_names
from ..effects.chain import PhysicsDamper, check_control
from ..executor import executor_scope
from ..identification.fit import FitResult
from .calibration import (
    DiagnosisError,
    _as_records,
    _check_effects_seen,
    _check_record,
    _finite_or_none,
    _fit,
    _implausible_record,
    _name,
    _record_esrs,
    calibrate,
    data_findings,
    fitted_model,
)
from .candidates import (
    BIC_THRESHOLD,
    HELD_OUT_GAIN,
    MIN_GAIN,
    Candidate,
    _beyond_record,
    _cannot_judge,
    _held_out,
    evaluate_candidates,
    parameters_at_bounds,
    rank_candidates,
)
from .floor import noise_floor
from .records import MAX_SAMPLES, prepare
from .residuals import ResidualAnalysis, residual_analysis
from .verdict import (
    ABSOLUTE_SLACK,
    AT_FLOOR,
    EXPLAINS,
    PAIR_SEARCH_BELOW,
    PARTIAL_SHARE,
    VERDICTS,
    WELL_ABOVE,
    _held_out_winner,
    _judge_pairs,
    _judge_singles,
    _one_sided,
    _unexplained_reason,
    named_effects,
    why_not_a_step,
)

__all__ = [
    "Diagnosis",
    "Candidate",
    "ResidualAnalysis",
    "History",
    "calibrate",
    "residual_analysis",
    "diagnose",
    "improve",
    "fitted_model",
    "parameters_at_bounds",
    "DiagnosisError",
    "MIN_GAIN",
    "BIC_THRESHOLD",
    "HELD_OUT_GAIN",
    "MAX_SAMPLES",
    "VERDICTS",
    "AT_FLOOR",
    "WELL_ABOVE",
    "ABSOLUTE_SLACK",
    "EXPLAINS",
    "PAIR_SEARCH_BELOW",
    "data_findings",
    "named_effects",
]


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
        out = {
            "baseline_esr": _finite_or_none(self.baseline_esr),
            "ranking": [c.as_json() for c in self.ranking],
            "missing_effect": self.missing_effect,
            "verdict": self.verdict,
            "noise_floor_esr": _finite_or_none(self.noise_floor_esr),
            "noise_floor_method": self.noise_floor_method,
            "missing_effects": self.missing_effects,
            "findings": [f.as_json() for f in self.findings],
            "records": [dict(r) for r in self.records],
        }
        return out

    def report(self, said: Sequence[str] = ()) -> str:
        """A readable report: calibration, where it fails, the ranking with parameters and plausibility, verdict.

        ``said``: kinds of data finding the reader has warned about already (the command line's
        :data:`erdesign.data.measurement.WARNED_AT_READ`), counted but not listed again."""
        model = "baseline" + (f" + {', '.join(self.effects)}" if self.effects else "")
        lines = [
            f"Diagnosis of {self.record_name or 'the record'} ({self.samples[0]} samples"
            + (f", analysed on {self.samples[1]}" if self.samples[1] != self.samples[0] else "")
            + ")"
        ]
        listed = [f for f in self.findings if f.kind not in said]
        if self.findings:
            lines.append("data findings (before any fit):")
            lines.extend(
                f"  - {f.kind}: {f.record}: {f.message}" + (f" ({f.where})" if f.where else "") for f in listed
            )
            if len(listed) < len(self.findings):
                kinds = sorted({f.kind for f in self.findings if f.kind in said})
                lines.append(f"  - {', '.join(kinds)}: warned above as the record was read")
        lines.append(
            f"model: {model}; calibrated ESR {self.baseline_esr:.4g}; noise floor ESR "
            f"{self.noise_floor_esr:.3g} ({self.noise_floor_method or 'estimated'}); both judged on the "
            f"{100 * self.judged_share:.0f} % of the analysed samples where the sign of the velocity is known "
            "and no finding excludes them"
        )
        if len(self.records) > 1:
            lines.append(
                "ESR per record: "
                + ", ".join(
                    f"{r['name']} {r['esr']:.4g}" if r["esr"] is not None else f"{r['name']} -" for r in self.records
                )
            )
        for name in self.baseline.model.parameter_names:
            p = self.baseline.model.parameter(name)
            se = self.baseline.stderr.get(name)
            unc = "" if se is None else (f" ± {p.format(se, 2)}" if math.isfinite(se) else " (not identifiable)")
            lines.append(f"  {name:<22} {p.format(self.baseline.values[name])}{unc}")
        for w in self.warnings:
            lines.append(f"  warning: {w}")
        lines.append("where the model fails:")
        lines.append(self.analysis.report())
        lines.append(
            "candidate effects (best first; ESR after adding it, effective-BIC change, share of the excess "
            "over the noise floor it explains):"
        )
        for i, c in enumerate(self.ranking, 1):
            mark = "*" if c.significant else " "
            if not c.evaluated:
                lines.append(f" {mark}{i}. {c.effect:<20} not evaluated: {c.reason}")
                continue
            held = "" if c.held_out_gain is None else f", held-out gain {100 * c.held_out_gain:.1f} %"
            name = " + ".join(c.effects)
            lines.append(
                f" {mark}{i}. {name:<20} ESR {c.esr:.4g}  dBIC {c.delta_bic:+.1f}  "
                f"explains {100 * c.explained:.0f} %{held}"
            )
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
            lines.append(
                f"verdict: missing effect: {what} ESR {self.baseline_esr:.4g} -> {c.esr:.4g} "
                f"(noise floor {self.noise_floor_esr:.3g})"
            )
        elif self.verdict == "unexplained":
            lines.append("verdict: unexplained: " + self.reason)
        else:
            lines.append("verdict: nothing missing: " + self.reason)
        return "\n".join(lines)


#: Data findings that mimic a mechanism: the effects they make unsafe are never named while they are found
#: (CONTRACTS.md section 6: channel skew is never named field_lag or compressibility).
MIMICS = ("channel_skew", "smoothed", "force_offset_drift")
#: Widths of the expected sign at a reversal tried in the baseline calibration, in units of the velocity noise.
SIGN_WIDTHS = (0.0, 0.5, 1.0, 2.0)


def diagnose(
    damper: Damper,
    record: Measurement | Sequence[Measurement],
    effects: Sequence[str] | str = (),
    *,
    candidates: Sequence[str] | None = None,
    max_samples: int = MAX_SAMPLES,
    pairs: bool = True,
    exclude_clipped: bool | None = None,
    force_noise=None,
    executor=None,
    jobs: int | None = None,
    scheduler=None,
) -> Diagnosis:
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
    executor, jobs, scheduler
        Where the candidates' (and pairs') fits run, each an independent task (:func:`erdesign.executor.
        executor_for`: default in this process).  The diagnosis is the same whatever the executor.

    Returns
    -------
    Diagnosis
        ``verdict`` is ``"missing_effect"`` (``missing_effect`` names it), ``"nothing_missing"`` (the residual is
        at the noise floor, or nothing beyond it can be told from noise) or ``"unexplained"`` (the residual stays
        well above the noise floor and no effect of the library explains it plausibly; ``reason`` says what the
        residual looks like).  Every ESR it states is judged on the same samples (:attr:`Diagnosis.judged_share`).
    """
    with executor_scope(executor, jobs=jobs, scheduler=scheduler) as ex:
        return _diagnose(
            damper,
            record,
            effects,
            candidates=candidates,
            max_samples=max_samples,
            pairs=pairs,
            exclude_clipped=exclude_clipped,
            force_noise=force_noise,
            executor=ex,
        )


def _diagnose(
    damper, record, effects, *, candidates, max_samples, pairs, exclude_clipped, force_noise, executor
) -> Diagnosis:
    """:func:`diagnose` on a given executor."""
    effects = parse_effect_names(effects)
    records = _as_records(record)
    for r in records:
        check_control(damper, r)
        _check_record(r)
    base_model = PhysicsDamper(damper, effects)
    _check_effects_seen(base_model, records, damper)
    findings = data_findings(records, exclude_clipped=exclude_clipped)
    prep = prepare(
        records,
        [excluded_mask([f for f in findings if f.record == _name(r, i)], len(r)) for i, r in enumerate(records)],
        max_samples=max_samples,
    )
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
    floor_info = noise_floor(records, prep, force_noise, damper)
    floor = floor_info.esr
    warnings_ = [f"the calibration ends at a bound: {b}" for b in parameters_at_bounds(base, base.free)]
    suspicious = [s for r in records for s in _implausible_record(r, damper)]
    warnings_ += suspicious
    warnings_ += [f"{f.record}: {f.message}" for f in findings if f.unsafe_for]
    names = [
        c for c in (parse_effect_names(candidates) if candidates is not None else EFFECT_NAMES) if c not in effects
    ]
    not_judged: dict[str, str] = {}
    for name in names:
        why = _cannot_judge(name, records, work, damper)
        if why:
            not_judged[name] = why
    ranking: list[Candidate] = evaluate_candidates(
        base_model,
        base,
        work,
        effects,
        [((n,), None) for n in names if n not in not_judged],
        damper,
        mask=mask,
        executor=executor,
    )
    excess = base.esr - floor
    _score(ranking, base, floor, work, mask, findings)
    at_floor = base.esr <= AT_FLOOR * floor + ABSOLUTE_SLACK
    well_above = base.esr > WELL_ABOVE * floor + ABSOLUTE_SLACK
    if not base.esr < 1.0:
        warnings_.append(
            f"the calibrated baseline leaves {100 * base.esr:.0f} % of the force variance: the damper "
            "file does not describe this record (a unit in the header, the wrong damper, or a mechanism "
            "far outside the model)"
        )
    held = _held_out(prep)
    missing, pair, verdict, reason, one_sided = None, (), "nothing_missing", "", None
    reversals = looked = None
    if suspicious:
        verdict = "unexplained"
        reason = "the record is implausible for this damper, so no effect is named: " + "; ".join(suspicious)
    else:
        # at the (estimated) noise floor an effect must be overwhelming - or clearly better on held-out data
        named = _judge_singles(base_model, base, work, ranking, strict=at_floor, mask=mask, held=held)
        if named is None and pairs and well_above:
            best_share = max((c.explained for c in ranking if c.evaluated), default=0.0)
            if best_share < PAIR_SEARCH_BELOW:
                named = _judge_pairs(
                    base_model, base, work, effects, ranking, damper, excess, mask=mask, held=held, executor=executor
                )
        if named is None:
            # never "nothing missing" while a plausible effect clearly improves the held-out data; far above the
            # floor, an effect that clearly improves the held-out data is a step of the loop even when more is
            # missing (the residual of the model with it is judged again, one-sidedness included)
            named = _held_out_winner(base_model, work, ranking, mask, held, partial=well_above)
        if named is None and well_above:
            # far above the floor with nothing named: the effects that act where the judged samples do not reach
            # (only those the judged samples cannot see: one that explains a share there was judged already)
            unseen = {c.effect for c in ranking if c.evaluated and len(c.effects) == 1 and c.explained < PARTIAL_SHARE}
            named, reversals, looked = _judge_at_reversals(
                base_model,
                work,
                effects,
                [n for n in names if n in unseen],
                damper,
                prep,
                floor,
                findings,
                held,
                executor,
            )
        one_sided = None if named is None else _one_sided(named, work, mask, floor)
        if one_sided is not None:
            named.significant = False
            named.note = "not named: " + one_sided
            verdict = "unexplained"
            reason = (
                f"{named.effect} lowers the ESR from {base.esr:.3g} to {named.esr:.3g} (noise floor "
                f"{floor:.3g}), but what it leaves is one-sided: {one_sided}. No effect of the library acts in "
                "one direction only: a blow-off or check valve, the unequal areas of a single-ended rod or "
                "cavitation may be at work."
            )
            named = None
        if named is not None:
            missing, pair = named.effects[0], (named.effects if len(named.effects) > 1 else ())
            verdict = "missing_effect"
            held_txt = (
                ""
                if named.held_out_gain is None
                else f", {100 * named.held_out_gain:.0f} % less error on held-out "
                f"{'records' if len(records) > 1 else 'cycles'}"
            )
            reason = (
                f"adding {' and '.join(named.effects)} lowers the ESR from "
                f"{(base if reversals is None else reversals).esr:.3g} to {named.esr:.3g} "
                f"(noise floor {floor:.3g}), {100 * max(named.explained, 0):.0f} % of the excess, with "
                f"plausible values{held_txt}"
                + ("; more is missing: diagnose again with it" if named.explained < EXPLAINS else "")
            )
            if reversals is not None:
                # the ranking stays judged on the verdict's samples (one set for every ESR it lists); its entry for
                # the effect says where it was named
                for c in ranking:
                    if c.effects == named.effects:
                        c.significant = True
                        c.note = (
                            f"named where it acts, on the samples near reversals too: ESR {reversals.esr:.3g} -> "
                            f"{named.esr:.3g} there, {100 * named.held_out_gain:.0f} % less error on held-out cycles"
                        )
                reason = (
                    f"on the {100 * known.mean():.0f} % of the analysed samples where the sign of the velocity is "
                    f"known, no effect explains enough of the excess (ESR {base.esr:.3g}); judged where it acts, with "
                    f"the samples near reversals ({100 * prep.analysed.mean():.0f} %: all where the piston moves and "
                    f"no data finding excludes them), {reason}"
                )
    if verdict == "missing_effect" or suspicious or one_sided:
        pass
    elif at_floor:
        reason = (
            f"the calibrated baseline's ESR {base.esr:.3g} is at the noise floor {floor:.3g}: what is left is noise"
        )
    else:
        if not well_above:
            reason = (
                f"the calibrated baseline's ESR {base.esr:.3g} is within {WELL_ABOVE:g} x the noise floor "
                f"{floor:.3g} and no effect removes a significant part of the rest"
            )
        else:
            verdict = "unexplained"
            reason = _unexplained_reason(base.esr, floor, ranking, analysis)
            if looked is not None:
                c, why = looked
                reason += (
                    f" Judged with the samples near reversals too (the other {100 * (1 - known.sum() / prep.analysed.sum()):.0f} "
                    f"% of the analysed samples), where a compliance or a bypass acts, the best such effect, "
                    f"{c.effect}, explains {100 * max(c.explained, 0):.0f} % of the excess there but is not named: "
                    f"{why}."
                )
            if warnings_:
                reason += " Check first: " + "; ".join(warnings_) + "."
    unsafe = sorted(
        {
            f.kind
            for f in findings
            if f.unsafe_for and (verdict != "missing_effect" or set(f.unsafe_for) & set(named_effects(missing, pair)))
        }
    )
    if unsafe:
        reason += (
            f" Unsafe: the data finding(s) {', '.join(unsafe)} (see findings) can mimic or hide a "
            "mechanism; judge this verdict with them in mind."
        )
    if reason and not suspicious and reversals is None:
        reason += (
            f" (judged on {100 * known.mean():.0f} % of the analysed samples: where the sign of the velocity "
            "is known" + (" and no data finding excludes them" if any(prep.excluded) else "") + ")"
        )
    ranking.sort(key=lambda c: (not c.significant, not c.evaluated, c.delta_bic))
    per_record = _record_esrs(base_model, base.values, work, prep)
    return Diagnosis(
        effects,
        base,
        base.esr,
        analysis,
        ranking,
        missing,
        not_judged,
        work.name,
        (sum(prep.full_samples), len(work)),
        verdict,
        floor,
        reason,
        pair,
        warnings_,
        float(known.mean()),
        base.esr,
        floor,
        findings=findings,
        records=per_record,
        noise_floor_method=floor_info.method,
    )


def _score(ranking: list[Candidate], base: FitResult, floor: float, work: Measurement, mask, findings) -> None:
    """Each evaluated candidate's share of the baseline's excess over the noise floor, sizes the record rules out,
    candidates a data finding mimics blocked, and the ranking (:func:`rank_candidates`), in place."""
    excess = base.esr - floor
    mimicked = {e: f for f in findings if f.kind in MIMICS for e in f.unsafe_for}
    for c in ranking:
        if c.evaluated:
            c.explained = (base.esr - c.esr) / excess if excess > 0 else 0.0
            c.implausible += _beyond_record(c, work, mask)
        hit = [mimicked[e] for e in c.effects if e in mimicked]
        if hit:
            c.blocked = (
                f"the data finding '{hit[0].kind}' ({hit[0].record}) makes the force lag the motion as "
                f"{c.effect} would; it is an artefact of the record, not a mechanism"
            )
    # ranked by the BIC with one effective sample count for all (the smallest any candidate leaves): each
    # candidate's own count (its significance against the baseline) would rank a worse fit first when the better one
    # leaves a smoother residual
    rank_candidates(ranking, base)


#: The samples near reversals must add at least this share to the judged ones for a second look
#: (:func:`_judge_at_reversals`) to be worth its fits.
REVERSAL_SHARE = 0.05


def _judge_at_reversals(base_model, work, effects, names, damper, prep, floor, findings, held, executor):
    """``(candidate, baseline, None)``: the effect among ``names`` that makes the force continuous through a
    reversal (:attr:`erdesign.effects.base.Effect.continuous_at_reversal`: a compliance below yield, a compliant
    column, a bypass), judged on the samples where it acts; ``(None, None, (looked, why))`` when none is named
    (``looked``: the one that explains most there, ``why``: why it is not a step, for the verdict's reason; None when
    no second look ran).

    The verdict is judged where the sign of the velocity is known, because a rigid yield-stress force jumps at a
    reversal and no model can place the jump inside the velocity's noise.  An effect of this kind acts mostly on
    the samples left out: on Dyke's ``ransim_u`` (docs/case_studies/dyke.md) pre-yield elasticity removes 6 % of
    the round-2 model's excess on the judged samples and 35 % with the samples near reversals.  So when the
    baseline is far above its floor and no effect explains enough on the judged samples, these effects - those of
    them that explain less than :data:`~erdesign.diagnosis.verdict.PARTIAL_SHARE` there (one that explains more was
    seen and judged: on a truth-rig record with free play, pre-yield elasticity and compressibility explain 40 % each,
    a tie that names neither) - are judged once more on :attr:`~erdesign.diagnosis.records.Prepared.analysed` (judged plus reversal samples), the
    baseline refitted there, by the rule of a partial step (:func:`_held_out_winner`: a fifth of the excess, strong
    evidence, a clear gain on held-out cycles, no rival within 5 %).  It runs only where the first look found
    nothing, so a record that the judged samples explain is judged as before."""
    wide = prep.analysed
    names = [n for n in names if EFFECTS[n].continuous_at_reversal]
    if wide is None or not names or wide.sum() < (1.0 + REVERSAL_SHARE) * prep.judged.sum():
        return None, None, None
    base = _fit(base_model, work, mask=wide)
    ranking = evaluate_candidates(
        base_model, base, work, effects, [((n,), None) for n in names], damper, mask=wide, executor=executor
    )
    _score(ranking, base, floor, work, wide, findings)
    named = _held_out_winner(base_model, work, ranking, wide, held, partial=True)
    if named is not None:
        return named, base, None
    looked = max((c for c in ranking if c.evaluated), key=lambda c: c.explained, default=None)
    if looked is None:
        return None, None, None
    return None, None, (looked, why_not_a_step(looked, ranking, base_model, work, wide, held))


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


def improve(
    damper: Damper,
    record: Measurement | Sequence[Measurement],
    effects: Sequence[str] | str = (),
    *,
    max_rounds: int = 3,
    max_samples: int = MAX_SAMPLES,
    exclude_clipped: bool | None = None,
    force_noise=None,
) -> History:
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
        d = diagnose(
            damper, record, effects, max_samples=max_samples, exclude_clipped=exclude_clipped, force_noise=force_noise
        )
        history.diagnoses.append(d)
        history.steps.append((effects, d.baseline_esr))
        if d.verdict != "missing_effect":
            break
        effects = effects + tuple(d.missing_effects)
    return history
