"""Residual analysis (stage 4 of diagnosis): where in the cycle the error of a calibrated model lives and what it
looks like, in words (Vivas-López et al. Table 2: characteristic -> diagram -> model term).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..data.measurement import Measurement
from ..effects import EFFECTS
from ..effects.base import peak_speed
from ..effects.chain import PhysicsDamper
from ..identification.fit import FitResult

__all__ = ["ResidualAnalysis", "residual_analysis"]


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


def residual_analysis(
    model: PhysicsDamper, result: FitResult, record: Measurement, mask: np.ndarray | None = None
) -> ResidualAnalysis:
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
        "coulomb": lambda c: (
            f"residual is odd in velocity and flat in magnitude: Coulomb-like, about {abs(c):.3g} N"
            f"{'' if c > 0 else ' (negative: less friction than assumed)'}: seal friction"
        ),
        "acceleration": lambda c: (
            f"residual follows the acceleration: an extra mass of about {c:.3g} kg: fluid "
            f"inertia (prior {EFFECTS['fluid_inertia'].prior(model.damper)['slug_mass']:.3g} kg)"
            if c > 0
            else "residual follows minus the acceleration: the measured force leads the model's "
            "(no mass is negative: a phase error, such as a skewed or filtered channel, or a "
            "lag in the model that the record does not have)"
        ),
        "displacement": lambda c: (
            f"residual grows with the displacement: a spring of about {c:.3g} N/m: gas spring"
            if c > 0
            else "residual falls as the displacement grows: not a spring (no stiffness is "
            "negative): an offset or drift of the displacement channel, or a one-sided "
            "mechanism"
        ),
        "offset": lambda c: (
            f"residual has a constant offset of about {c:.3g} N: gas-spring preload (or load-cell zero)"
        ),
        "drift": lambda c: (
            f"the model force is {'too high' if c < 0 else 'too low'} late in the test "
            f"(by about {abs(c) * 100:.2g} % of the fluid force over the record): "
            f"{'viscous heating' if c < 0 else 'a drift (cooling, warm-up of the rig?)'}"
        ),
    }
    for name in sorted(shares, key=shares.get, reverse=True):
        if shares[name] > 0.1:
            findings.append(f"{words[name](sizes[name])} [explains {100 * shares[name]:.0f} % of the residual]")
    rev = regions.get("reversals (|v| < 15 %)")
    if rev and rev[1] > 1.5:
        findings.append(
            f"the error is concentrated at the reversals ({rev[1]:.2g} x the overall RMS there): "
            "the force does not jump as the rigid-plastic model does: pre-yield elasticity, "
            "compressibility (zero field too) or leakage (creep below yield)"
        )
    after = regions.get("30 ms after field changes")
    if after and after[1] > 1.5:
        findings.append(
            f"the error is concentrated right after field changes ({after[1]:.2g} x the overall RMS): "
            "the fluid follows the field late: field lag"
        )
    high = regions.get("high velocity (> 70 %)")
    if high and high[1] > 1.5:
        findings.append(
            f"the error is largest at high speed ({high[1]:.2g} x the overall RMS): the force-velocity "
            "curve bends (shear thinning) or lags (compressibility)"
        )
    plus, minus = regions.get("moving in + (v > 0)"), regions.get("moving in - (v < 0)")
    if plus and minus and max(plus[1], minus[1]) > 1.5 * max(min(plus[1], minus[1]), 1e-12):
        big = "+" if plus[1] > minus[1] else "-"
        findings.append(
            f"the residual is asymmetric: {max(plus[1], minus[1]) / max(min(plus[1], minus[1]), 1e-12):.2g} "
            f"x larger moving in {big} than in the other direction: something acts one way only (a "
            "blow-off or check valve, the unequal areas of a single-ended rod, cavitation); no effect of "
            "the library is one-sided"
        )
    late, first = regions.get("late in the test"), regions.get("first third")
    if late and first and late[1] > 1.5 * first[1]:
        findings.append(
            f"the error grows over the test (late / early RMS {late[1] / max(first[1], 1e-12):.2g}): "
            "something changes with time: viscous heating"
        )
    return ResidualAnalysis(rms, regions, sizes, shares, findings)
