"""Figures of docs/tutorial_diagnosis.md: measured and model loops of each diagnosis round, the error history
against the noise floor, and the record with a mechanism outside the effect library.

Run from the repository root: ``python docs/make_diagnosis_figures.py [OUTDIR]`` (default docs/figures).  Writes
PNG images (plotly's static export, kaleido, which drives the system's Chromium; ``pip install ".[docs]"``) that
the tutorial shows, and, when kaleido is missing, self-contained HTML files instead.
"""

import math
import sys
from pathlib import Path

import plotly.graph_objects as go
from plotly.subplots import make_subplots

from erdesign import load_damper
from erdesign.data.measurement import read_measurement
from erdesign.diagnosis.diagnose import diagnose, fitted_model, improve
from erdesign.report import ErrorHistoryStep
from erdesign.report.plots import error_history_figure
from erdesign.simulation.rig import stepped_sine
from erdesign.simulation.truthrig import TruthDamper, simulate_truth


def _write(fig: go.Figure, path: Path) -> Path:
    try:
        fig.write_image(path.with_suffix(".png"), width=1000, height=420, scale=1)
        return path.with_suffix(".png")
    except Exception:  # no kaleido / no browser: an interactive page instead
        fig.write_html(path.with_suffix(".html"), include_plotlyjs=True)
        return path.with_suffix(".html")


def _loops(record, d, title: str) -> go.Figure:
    """Measured and model force against velocity, and the residual against time, of diagnosis ``d``."""
    F = fitted_model(d.baseline).simulate(record, d.baseline.values)
    fig = make_subplots(rows=1, cols=2, subplot_titles=("force - velocity", "residual - time"))
    fig.add_scatter(
        x=record.velocity * 1e3,
        y=record.force / 1e3,
        mode="lines",
        name="measured",
        row=1,
        col=1,
        line=dict(color="#444"),
    )
    fig.add_scatter(
        x=record.velocity * 1e3,
        y=F / 1e3,
        mode="lines",
        name=f"model, ESR {d.baseline_esr:.3g}",
        row=1,
        col=1,
        line=dict(color="#d62728"),
    )
    fig.add_scatter(
        x=record.time, y=(record.force - F), mode="lines", name="residual", row=1, col=2, line=dict(color="#1f77b4")
    )
    fig.update_xaxes(title_text="velocity v [mm/s]", row=1, col=1)
    fig.update_yaxes(title_text="force F [kN]", row=1, col=1)
    fig.update_xaxes(title_text="time t [s]", row=1, col=2)
    fig.update_yaxes(title_text="F - F_model [N]", row=1, col=2)
    fig.update_layout(
        title=f"{title} (noise floor ESR {d.noise_floor_esr:.2g}): {d.verdict}", margin=dict(l=60, r=20, t=60, b=50)
    )
    return fig


def blowoff_record(damper):
    """The tutorial's record with a mechanism outside the effect library: the truth rig's rebound blow-off valve
    (default cracking force and damping) on a sweep over amplitude, frequency and field."""
    motion = stepped_sine([0.005, 0.01], [2.0, 1.0], [3e6, 1.5e6], cycles=2, rate=200)
    return simulate_truth(TruthDamper(damper, {"blowoff": {}}), motion, seed=1, name="blowoff").measured


def main(outdir: str = "docs/figures") -> list[Path]:
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    damper = load_damper("examples/makris.toml")
    record = read_measurement("examples/measurements/makris_hidden_seal_friction.csv")
    history = improve(damper, record)
    paths = []
    for i, d in enumerate(history.diagnoses):
        label = "baseline" + (" + " + " + ".join(d.effects) if d.effects else "")
        paths.append(_write(_loops(record, d, f"round {i}: {label}"), out / f"diagnosis_round_{i}"))
    steps = [
        ErrorHistoryStep(step=i, effect=(d.effects[-1] if d.effects else "baseline"), esr=d.baseline_esr)
        for i, d in enumerate(history.diagnoses)
    ]
    fig = error_history_figure(steps)
    floor = history.diagnoses[-1].noise_floor_esr
    fig.add_scatter(
        x=list(fig.data[0].x),
        y=[floor] * len(steps),
        mode="lines",
        name=f"noise floor ESR {floor:.2g}",
        line=dict(color="#2ca02c", dash="dash"),
    )
    fig.data[0].showlegend = False
    top = max(s.esr for s in steps)
    fig.update_yaxes(range=[math.log10(floor) - 0.5, math.log10(top) + 0.5])
    paths.append(_write(fig, out / "diagnosis_error_history"))
    blowoff = blowoff_record(damper)
    paths.append(
        _write(_loops(blowoff, diagnose(damper, blowoff), "blow-off valve: baseline"), out / "diagnosis_unexplained")
    )
    return paths


if __name__ == "__main__":
    print("\n".join(str(p) for p in main(*sys.argv[1:])))
