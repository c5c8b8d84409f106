"""Figures of docs/tutorial_diagnosis.md: measured and model force-velocity loops before and after each round.

Run from the repository root: ``python docs/make_diagnosis_figures.py [OUTDIR]`` (default docs/figures); writes one
self-contained plotly HTML file per round (about 3 s).
"""

import sys
from pathlib import Path

import plotly.graph_objects as go

from erdesign import load_damper
from erdesign.diagnose import improve
from erdesign.measurement import read_measurement


def main(outdir: str = "docs/figures") -> list[Path]:
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    damper = load_damper("examples/makris.toml")
    record = read_measurement("examples/measurements/makris_two_hidden_effects.csv")
    history = improve(damper, record)
    paths = []
    for i, d in enumerate(history.diagnoses):
        model = d.baseline.model
        F = model.simulate(record, d.baseline.values)
        fig = go.Figure()
        fig.add_scatter(x=record.velocity * 1e3, y=record.force / 1e3, mode="lines", name="measured")
        fig.add_scatter(x=record.velocity * 1e3, y=F / 1e3, mode="lines", name=f"model (ESR {d.baseline_esr:.3g})")
        fig.update_layout(title=f"round {i}: baseline{' + ' + ', '.join(d.effects) if d.effects else ''}",
                          xaxis_title="velocity [mm/s]", yaxis_title="force [kN]")
        path = out / f"diagnosis_round_{i}.html"
        fig.write_html(path, include_plotlyjs="cdn")
        paths.append(path)
    return paths


if __name__ == "__main__":
    print("\n".join(str(p) for p in main(*sys.argv[1:])))
