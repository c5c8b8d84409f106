"""Figures of docs/tutorial_diagnosis.md: measured and model loops of each diagnosis round, and the error history.

Run from the repository root: ``python docs/make_diagnosis_figures.py [OUTDIR]`` (default docs/figures).  Writes
PNG images (plotly's static export, kaleido, which drives the system's Chromium; ``pip install ".[docs]"``) that
the tutorial shows, and, when kaleido is missing, self-contained HTML files instead.
"""

import sys
from pathlib import Path

import plotly.graph_objects as go
from plotly.subplots import make_subplots

from erdesign import load_damper
from erdesign.diagnose import improve
from erdesign.measurement import read_measurement
from erdesign.plots import error_history_figure
from erdesign.report import ErrorHistoryStep


def _write(fig: go.Figure, path: Path) -> Path:
    try:
        fig.write_image(path.with_suffix(".png"), width=1000, height=420, scale=1)
        return path.with_suffix(".png")
    except Exception:  # no kaleido / no browser: an interactive page instead
        fig.write_html(path.with_suffix(".html"), include_plotlyjs=True)
        return path.with_suffix(".html")


def main(outdir: str = "docs/figures") -> list[Path]:
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    damper = load_damper("examples/makris.toml")
    record = read_measurement("examples/measurements/makris_two_hidden_effects.csv")
    history = improve(damper, record)
    paths = []
    for i, d in enumerate(history.diagnoses):
        F = d.baseline.model.simulate(record, d.baseline.values)
        label = "baseline" + (" + " + " + ".join(d.effects) if d.effects else "")
        fig = make_subplots(rows=1, cols=2, subplot_titles=("force - velocity", "residual - time"))
        fig.add_scatter(x=record.velocity * 1e3, y=record.force / 1e3, mode="lines", name="measured", row=1, col=1,
                        line=dict(color="#444"))
        fig.add_scatter(x=record.velocity * 1e3, y=F / 1e3, mode="lines", name=f"model, ESR {d.baseline_esr:.3g}",
                        row=1, col=1, line=dict(color="#d62728"))
        fig.add_scatter(x=record.time, y=(record.force - F), mode="lines", name="residual", row=1, col=2,
                        line=dict(color="#1f77b4"))
        fig.update_xaxes(title_text="velocity v [mm/s]", row=1, col=1)
        fig.update_yaxes(title_text="force F [kN]", row=1, col=1)
        fig.update_xaxes(title_text="time t [s]", row=1, col=2)
        fig.update_yaxes(title_text="F - F_model [N]", row=1, col=2)
        fig.update_layout(title=f"round {i}: {label}", margin=dict(l=60, r=20, t=60, b=50))
        paths.append(_write(fig, out / f"diagnosis_round_{i}"))
    steps = [ErrorHistoryStep(step=i, effect=(d.effects[-1] if d.effects else "baseline"), esr=d.baseline_esr)
             for i, d in enumerate(history.diagnoses)]
    paths.append(_write(error_history_figure(steps), out / "diagnosis_error_history"))
    return paths


if __name__ == "__main__":
    print("\n".join(str(p) for p in main(*sys.argv[1:])))
