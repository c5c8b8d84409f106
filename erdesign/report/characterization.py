"""The page of a characterization (``erdesign characterize --out``, the Characterize page of the app): the FD, FV and
FM diagrams and their 2D densities, measured against the models, as Vivas-López et al. (n.d.) Fig 5, and the tables.

Figures are plotly; they show what :mod:`erdesign.characterization` computed and compute nothing of their own but
the drawing.
"""

from __future__ import annotations

import html
from pathlib import Path

import numpy as np

__all__ = ["density_figure", "diagram_figure", "render_characterization", "write_characterization"]

_AXIS = {"FD": ("displacement [mm]", 1e3), "FV": ("velocity [m/s]", 1.0), "FM": ("control (SI)", 1.0)}


def _forces(result, k: int) -> dict[str, np.ndarray]:
    rec = result.records[k]
    return {
        "measured": rec.force,
        "customized": result.model_force("customized", k),
        "Eyring-plastic": result.model_force("eyring_plastic", k),
    }


def diagram_figure(result, k: int = 0):
    """FD, FV and FM diagrams of record ``k``: the measured force and the two models' (identified on the record
    with the best average), and the semi-active force of eq 1 in the FV panel's hover."""
    import plotly.graph_objects as go
    from plotly.subplots import make_subplots

    from ..characterization.diagrams import diagram_axes

    rec = result.records[k]
    forces = _forces(result, k)
    fig = make_subplots(rows=1, cols=3, subplot_titles=("FD", "FV", "FM"))
    colours = {"measured": "black", "customized": "#2ca02c", "Eyring-plastic": "#d62728"}
    for col, d in enumerate(("FD", "FV", "FM"), start=1):
        for name, F in forces.items():
            x, y = diagram_axes(rec, d, F)
            fig.add_trace(
                go.Scattergl(
                    x=x * _AXIS[d][1],
                    y=y,
                    mode="markers",
                    name=name,
                    legendgroup=name,
                    showlegend=col == 1,
                    marker={"size": 2, "color": colours[name]},
                    opacity=0.5,
                ),
                row=1,
                col=col,
            )
        fig.update_xaxes(title_text=_axis(rec, d), row=1, col=col)
    fig.update_yaxes(title_text="force [N]", row=1, col=1)
    fig.update_layout(height=380, title=f"Characteristic diagrams of {rec.name}", margin={"t": 60})
    return fig


def density_figure(result, k: int = 0, bins: int = 40):
    """The 2D densities of Vivas-López et al. Fig 5: FV, FD and FM (rows) of the measured record ``k``, the
    Eyring-plastic and the customized model (columns), each on the measured ranges (share of samples per cell)."""
    import plotly.graph_objects as go
    from plotly.subplots import make_subplots

    from ..characterization.diagrams import density, diagram_axes

    rec = result.records[k]
    forces = _forces(result, k)
    order = ("measured", "Eyring-plastic", "customized")
    fig = make_subplots(
        rows=3,
        cols=3,
        column_titles=list(order),
        row_titles=["FV", "FD", "FM"],
        horizontal_spacing=0.05,
        vertical_spacing=0.08,
    )
    for row, d in enumerate(("FV", "FD", "FM"), start=1):
        x, F = diagram_axes(rec, d)
        x_range = (float(x.min()), float(x.max()))
        F_range = (float(F.min()), float(F.max()))
        for col, name in enumerate(order, start=1):
            xs, ys = diagram_axes(rec, d, forces[name])
            dens = density(xs, ys, bins=bins, x_range=x_range, F_range=F_range)
            xc = 0.5 * (dens.x_edges[1:] + dens.x_edges[:-1]) * _AXIS[d][1]
            Fc = 0.5 * (dens.F_edges[1:] + dens.F_edges[:-1])
            z = np.where(dens.counts > 0, dens.fraction, np.nan).T
            fig.add_trace(
                go.Heatmap(
                    x=xc, y=Fc, z=z, colorscale="Jet", showscale=(row == 1 and col == 3), colorbar={"title": "share"}
                ),
                row=row,
                col=col,
            )
            fig.update_xaxes(title_text=_axis(rec, d) if col == 2 else None, row=row, col=col)
        fig.update_yaxes(title_text="force [N]", row=row, col=1)
    fig.update_layout(
        height=900,
        title=f"2D densities of {rec.name}: measured against the models (Vivas-López et al. Fig 5)",
        margin={"t": 80},
    )
    return fig


def esr_change_text(reduction: float | None) -> str:
    """``"28.4 % less ESR"`` or ``"19.7 % more ESR"``."""
    if reduction is None:
        return "no comparable ESR"
    return f"{100 * abs(reduction):.1f} % {'less' if reduction >= 0 else 'more'} ESR"


def _axis(record, diagram: str) -> str:
    """The x-axis title of a diagram, the control in its SI unit."""
    if diagram != "FM":
        return _AXIS[diagram][0]
    from ..fluid import CONTROL_UNITS

    return f"{record.control_kind or 'control'} [{CONTROL_UNITS.get(record.control_kind, '-')}]"


def _table(head, rows) -> str:
    e = html.escape
    return (
        "<table><tr>"
        + "".join(f"<th>{e(str(h))}</th>" for h in head)
        + "</tr>"
        + "".join("<tr>" + "".join(f"<td>{e(str(c))}</td>" for c in row) + "</tr>" for row in rows)
        + "</table>"
    )


def render_characterization(result) -> str:
    """The page as one self-contained HTML document (plotly's JavaScript embedded once)."""
    doc = result.to_dict()
    e = html.escape
    parts = [
        "<h2>Characteristics (Table 2)</h2>",
        _table(
            ["characteristic", "diagram", "model term", "found", "evidence"],
            [
                [c["title"], c["diagram"], c["model_term"], "yes" if c["found"] else "no", c["evidence"]]
                for c in doc["characteristics"]
            ],
        ),
    ]
    m = doc["model"]
    parts += [
        (
            f"<h2>Customized model</h2><p>Terms: {e(', '.join(m['terms']))}; "
            f"{'asymmetric' if m['asymmetric'] else 'symmetric'} coefficients; manipulation V = u^"
            f"{m['control_exponent']:.3g}; {m['parameter_count']} parameters, "
            f"identified on {e(m['identified_on'])} (ESR {m['esr']:.4f}).</p>"
        ),
        _table(["parameter", "value"], list(m["parameters"].items())),
    ]
    cv = doc["cross_validation"]
    for key, title in (("customized", "customized model"), ("eyring_plastic", "Eyring-plastic model (eq 8)")):

        def cell(x):
            return "-" if x is None else f"{x:.4f}"

        rows = [[n, *map(cell, row)] for n, row in zip(cv["records"], cv[key]["table"])]
        rows.append(["average", *map(cell, cv[key]["average"])])
        parts += [
            f"<h2>Cross-validation, {title} (Table 4)</h2><p>Column: identified on; row: validated on.</p>",
            _table(["validation \\ identification", *cv["records"]], rows),
        ]
    c = doc["comparison"]
    ident, cvc = c["identification"], c["cross_validation"]
    parts += [
        "<h2>Customized against Eyring-plastic (Table 6)</h2>",
        _table(
            ["record", "customized ESR", "Eyring-plastic ESR"],
            [[n, *map(cell, (a, b))] for n, a, b in zip(cv["records"], ident["customized"], ident["eyring_plastic"])],
        ),
        (
            f"<p>On average {esr_change_text(ident['esr_reduction'])} on the identification records; "
            f"cross-validation mean ESR {cvc['customized_mean_esr']:.4f} against "
            f"{cvc['eyring_plastic_mean_esr']:.4f}.</p>"
        ),
    ]
    k = result.identified_on
    for i, fig in enumerate((diagram_figure(result, k), density_figure(result, k))):
        parts.append(fig.to_html(full_html=False, include_plotlyjs=(i == 0), include_mathjax=False))
    style = (
        "body{font-family:sans-serif;max-width:1200px;margin:auto}table{border-collapse:collapse;margin:1em 0}"
        "td,th{border:1px solid #ccc;padding:3px 6px;font-size:90%}"
    )
    return (
        f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>Characterization</title><style>{style}"
        f"</style></head><body><h1>Characterization and customized model (Vivas-López et al.)</h1>"
        + "".join(parts)
        + "</body></html>"
    )


def write_characterization(result, path, *, overwrite: bool = False, option: str = "path") -> Path:
    """Write :func:`render_characterization` to ``path``, whole or not at all, over an existing file only with
    ``overwrite`` (:mod:`erdesign.output`)."""
    from ..output import write_output

    return write_output(path, render_characterization(result), overwrite=overwrite, option=option)
