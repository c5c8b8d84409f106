"""The verdict (stage 6 of diagnosis): which candidate, or pair, is named; when nothing is missing; when the residual
is unexplained.  The thresholds are module constants, each with the reason for its value.
"""

from __future__ import annotations

import numpy as np

from ..data.measurement import Measurement
from ..effects import EFFECTS
from .calibration import fitted_model
from .candidates import (
    BIC_THRESHOLD,
    HELD_OUT_GAIN,
    MIN_GAIN,
    Candidate,
    _bic,
    _effective_n,
    _held_out_gain,
    evaluate_candidates,
)

__all__ = [
    "VERDICTS",
    "AT_FLOOR",
    "WELL_ABOVE",
    "ABSOLUTE_SLACK",
    "EXPLAINS",
    "PAIR_SEARCH_BELOW",
    "STRICT_BIC",
    "STRICT_HELD_OUT",
    "PAIR_POOL",
    "HELD_OUT_CLEAR",
    "PARTIAL_SHARE",
    "PARTIAL_TIE",
    "ONE_SIDED",
    "ONE_SIDED_SHARE",
    "named_effects",
    "why_not_a_step",
]


VERDICTS = ("missing_effect", "nothing_missing", "unexplained")


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


#: Far above the floor, a candidate named as one step of the loop must remove at least this share of the excess.
PARTIAL_SHARE = 0.2
#: ... and no other plausible candidate may explain within this share of the excess as much as it does.
PARTIAL_TIE = 0.05
#: A plausible candidate that removes at least this share of the held-out error is never left unnamed.
HELD_OUT_CLEAR = 0.2


def named_effects(missing: str | None, pair: tuple[str, ...]) -> tuple[str, ...]:
    """The effect(s) a verdict names: the pair whole, the single effect, or none."""
    return tuple(pair) or ((missing,) if missing else ())


def _held_out_winner(base_model, work, ranking, mask, held, partial: bool = False) -> Candidate | None:
    """The plausible candidate that most lowers the error on held-out data, when it removes at least
    :data:`HELD_OUT_CLEAR` of it (else None): a verdict ``nothing_missing`` would hide it.  With ``partial`` (the
    baseline far above its floor, no effect explaining most of the excess) it must also remove
    :data:`PARTIAL_SHARE` of the excess with strong evidence (:data:`STRICT_BIC`) and no plausible rival within
    :data:`PARTIAL_TIE`: a step of the loop, with more still missing."""
    best = None
    pool = [c for c in ranking if c.evaluated and not c.blocked][:PAIR_POOL]
    plausible = [c for c in pool if not c.implausible and not c.at_bounds]
    for c in pool:
        if c.implausible or c.at_bounds or not (c.delta_bic < -BIC_THRESHOLD and c.gain > MIN_GAIN):
            continue
        if partial:
            # a step of the loop only when the evidence singles it out: strong, and no other plausible effect
            # explains about as much (two mechanisms that fit the same error equally point at neither)
            rival = any(o is not c and abs(o.explained - c.explained) < PARTIAL_TIE for o in plausible)
            if c.explained < PARTIAL_SHARE or c.delta_bic >= -STRICT_BIC or rival:
                continue
        if c.held_out_gain is None:
            c.held_out_gain = _held_out_gain(base_model, c, work, mask, held)
        if c.held_out_gain >= HELD_OUT_CLEAR and (best is None or c.held_out_gain > best.held_out_gain):
            best = c
    if best is not None:
        best.significant = True
        best.note = f"named on held-out data: it removes {100 * best.held_out_gain:.0f} % of the error there" + (
            f" and {100 * best.explained:.0f} % of the excess over the floor; more is missing: diagnose again with it"
            if partial
            else " although the calibrated model looked close to the noise floor"
        )
    return best


def why_not_a_step(c: Candidate, ranking, base_model=None, work=None, mask=None, held=None) -> str:
    """Why :func:`_held_out_winner` (``partial``) did not name candidate ``c``: the first rule it fails, in the
    order they are checked (for a verdict's reason)."""
    if c.implausible:
        return "its fitted size is implausible (" + "; ".join(c.implausible) + ")"
    if c.at_bounds:
        return "its fit ends at a bound"
    if not (c.delta_bic < -BIC_THRESHOLD and c.gain > MIN_GAIN) or c.explained < PARTIAL_SHARE:
        return f"a step needs {100 * PARTIAL_SHARE:.0f} % of the excess"
    if c.delta_bic >= -STRICT_BIC:
        return f"the evidence is weak (effective-BIC change {c.delta_bic:+.0f}; a step needs below {-STRICT_BIC:+.0f})"
    plausible = [o for o in ranking if o.evaluated and not o.blocked and not o.implausible and not o.at_bounds]
    rival = [o for o in plausible if o is not c and abs(o.explained - c.explained) < PARTIAL_TIE]
    if rival:
        return (
            f"{rival[0].effect} explains about as much ({100 * rival[0].explained:.0f} %), so the record points at "
            "neither"
        )
    if c.held_out_gain is None and base_model is not None:
        c.held_out_gain = _held_out_gain(base_model, c, work, mask, held)
    if c.held_out_gain is not None and c.held_out_gain < HELD_OUT_CLEAR:
        return (
            f"it removes only {100 * c.held_out_gain:.0f} % of the error on held-out cycles (a step needs "
            f"{100 * HELD_OUT_CLEAR:.0f} %)"
        )
    return "another effect is a clearer step"


def _judge_singles(base_model, base, work, ranking, strict: bool = False, mask=None, held=None) -> Candidate | None:
    """The best single candidate that is significant (effective BIC, gain, held-out cycles), plausible and explains
    enough of the excess over the noise floor; notes on the others say why they were not named."""
    blocked_by = None
    for c in [c for c in ranking if c.evaluated][:4]:
        if c.blocked:
            c.note = "not named: " + c.blocked
            continue
        if not (c.delta_bic < -(STRICT_BIC if strict else BIC_THRESHOLD) and c.gain > MIN_GAIN):
            continue
        if c.implausible:
            c.note = "not named: its fitted size is implausible (" + "; ".join(c.implausible) + ")"
            blocked_by = blocked_by or c
            continue
        if blocked_by is not None and c.explained < blocked_by.explained - 0.1:
            c.note = (
                f"not named: {blocked_by.effect} fits much better ({100 * blocked_by.explained:.0f} % of the "
                f"excess against {100 * c.explained:.0f} %) but with an implausible size, so neither is the "
                "answer"
            )
            continue
        if not c.esr < 0.5:
            c.note = "not named: the model with it still leaves half the force variance unexplained"
            continue
        if c.explained < EXPLAINS:
            c.note = f"not named alone: it explains only {100 * c.explained:.0f} % of the excess over the noise floor"
            continue
        c.held_out_gain = _held_out_gain(base_model, c, work, mask, held)
        if c.held_out_gain > (STRICT_HELD_OUT if strict else HELD_OUT_GAIN):
            c.significant = True
            return c
        c.note = "does not improve the held-out cycles: fits noise or the calibration, not a mechanism"
    return None


def _judge_pairs(
    base_model, base, work, effects, ranking, damper, excess, mask=None, held=None, executor=None
) -> Candidate | None:
    """Pairs of the best single candidates fitted jointly (not greedily); the best significant, plausible pair
    that explains enough of the excess, or None.  The pairs' fits are independent tasks on ``executor``."""
    pool = [c for c in ranking if c.evaluated and c.gain > 0 and not c.blocked][:PAIR_POOL]
    couples = [(pool[i], pool[j]) for i in range(len(pool)) for j in range(i + 1, len(pool))]
    # each effect starts from its own single fit, the calibration from the first
    tasks = [
        (
            (a.effect, b.effect),
            {
                **b.result.values,
                **a.result.values,
                **{p.name: b.result.values[p.name] for p in EFFECTS[b.effect].parameters(damper)},
            },
        )
        for a, b in couples
    ]
    found = []
    for (a, b), c in zip(
        couples, evaluate_candidates(base_model, base, work, effects, tasks, damper, mask=mask, executor=executor)
    ):
        if not c.evaluated:
            continue
        c.explained = (base.esr - c.esr) / excess if excess > 0 else 0.0
        best_single = min(a.result.rss, b.result.rss)
        n_eff = _effective_n(c.result.residual)
        better = (
            _bic(c.result.rss, base.n, c.result.k, n_eff)
            < _bic(best_single, base.n, c.result.k - 1, n_eff) - BIC_THRESHOLD
        )
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
    drop = c * c * hh / ss  # ESR the one-sided term removes
    left = float(np.sum(r**2)) / ss - floor  # what the named model leaves above the floor
    if drop * F.size > ONE_SIDED * floor and drop > ONE_SIDED_SHARE * left:
        side = "+" if c > 0 else "-"
        return (
            f"the force is {100 * abs(c):.2g} % of the fluid force larger moving in {side} than the model "
            f"allows (this removes {drop / max(left, 1e-300) * 100:.0f} % of what it leaves above the floor)"
        )
    return None


def _unexplained_reason(base_esr, floor, ranking, analysis) -> str:
    """What the residual looks like and where it lives, and why no effect of the library explains it."""
    parts = [
        f"the calibrated baseline's ESR {base_esr:.3g} is {base_esr / max(floor, 1e-12):.3g} x the noise floor "
        f"{floor:.3g}"
    ]
    ev = [c for c in ranking if c.evaluated]
    if ev:
        c = max(ev, key=lambda c: c.explained)
        if c.blocked:
            why = c.blocked
        elif c.implausible:
            why = f"its fitted size is implausible ({'; '.join(c.implausible)})"
        elif c.note and c.explained >= EXPLAINS:
            why = c.note.removeprefix("not named: ")
        else:
            why = f"it explains only {100 * max(c.explained, 0):.0f} % of the excess"
        parts.append(f"the best effect of the library, {c.effect}, is not named: {why}")
    looks = analysis.findings[:3]
    if looks:
        parts.append("the residual: " + "; ".join(looks))
    where = sorted(analysis.regions.items(), key=lambda kv: -kv[1][1])
    if where:
        name, (frac, ratio) = where[0]
        parts.append(f"it is largest {name} ({ratio:.2g} x the overall RMS on {100 * frac:.0f} % of the samples)")
    return (
        "; ".join(parts) + ". A mechanism outside the effect library (a blow-off valve, asymmetric areas, "
        "cavitation, free play, a clipped or filtered signal) or a wrong damper file may be at work."
    )
