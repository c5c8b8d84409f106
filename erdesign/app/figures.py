"""Plotly figures of the app that :mod:`erdesign.report.plots` does not have (yet): the geometry trade-off of the sweep
explorer, the loops of one simulated force, the time overlay and the residual plots of a comparison.

Like :mod:`erdesign.report.plots`, each builder takes numbers the library computed (SI arrays) and only draws them, with
units on every axis chosen by :func:`erdesign.formatting.pick_unit`.  Candidates to move into
:mod:`erdesign.report.plots` so that the report can use them too.

>>> import numpy as np
>>> t = np.linspace(0, 1, 101); x = 0.005 * np.sin(2 * np.pi * t); v = 0.01 * np.pi * np.cos(2 * np.pi * t)
>>> fig = loops_figure(x, v, 1e3 * v / v.max(), label="model")
>>> [tr.name for tr in fig.data], fig.layout.yaxis.title.text
(['model', 'model'], 'force F [kN]')
"""

from __future__ import annotations

import numpy as np
import plotly.graph_objects as go
from plotly.subplots import make_subplots

from ..formatting import pick_unit
from ..report.plots import LAYOUT, MEASURED_STYLE, MODEL_STYLE, RESIDUAL_STYLE, spans_decades, value_axis
from ..units import Q_

__all__ = ["tradeoff_figure", "loops_figure", "time_figure", "residual_figure", "BASELINE_STYLE"]

# the one style of the figures (erdesign.report.plots), each figure choosing its own height
_LAYOUT = {k: v for k, v in LAYOUT.items() if k != "height"}
_MEASURED, _MODEL, _OTHER = "#444444", MODEL_STYLE["line"]["color"], "#1f77b4"


def _in(values, si_unit: str, kind: str) -> tuple[np.ndarray, str]:
    """SI values converted to the unit :func:`pick_unit` chooses for them, and that unit as printed."""
    values = np.asarray(values, dtype=float)
    finite = values[np.isfinite(values)]
    unit = pick_unit(Q_(finite if finite.size else np.zeros(1), si_unit), kind)
    return np.asarray(Q_(values, si_unit).to(unit).magnitude), f"{Q_(1.0, unit).units:~P}"


def tradeoff_figure(sweep: dict, label: str, field_label: str, velocity_label: str) -> go.Figure:
    """Force, dynamic range and Reynolds number against one geometry value (the sweep explorer).

    ``sweep`` is the dictionary of :func:`erdesign.app.state.geometry_sweep` (SI arrays).
    """
    x, x_unit = _in(sweep["value"], "m", "length")
    F, f_unit = _in(np.concatenate([sweep["force"], sweep["zero_field_force"]]), "N", "force")
    n = x.size
    fig = make_subplots(
        rows=3,
        cols=1,
        shared_xaxes=True,
        vertical_spacing=0.06,
        subplot_titles=(f"force at {velocity_label}", f"dynamic range F({field_label}) / F(0)", "Reynolds number"),
    )
    fig.add_trace(
        go.Scatter(x=x, y=F[:n], mode="lines+markers", name=field_label, line=dict(color=_MODEL)), row=1, col=1
    )
    fig.add_trace(
        go.Scatter(x=x, y=F[n:], mode="lines+markers", name="zero field", line=dict(color=_OTHER)), row=1, col=1
    )
    fig.add_trace(
        go.Scatter(
            x=x,
            y=sweep["dynamic_range"],
            mode="lines+markers",
            name="dynamic range",
            line=dict(color=_MEASURED),
            showlegend=False,
        ),
        row=2,
        col=1,
    )
    fig.add_trace(
        go.Scatter(
            x=x,
            y=sweep["reynolds"],
            mode="lines+markers",
            name="Reynolds number",
            line=dict(color="#2ca02c"),
            showlegend=False,
        ),
        row=3,
        col=1,
    )
    # log axes only where the values span decades, every tick labelled in full (plots.value_axis)
    fig.update_yaxes(title_text=f"F [{f_unit}]" + (" (log)" if spans_decades(F) else ""), **value_axis(F), row=1, col=1)
    fig.update_yaxes(title_text="F(E)/F(0) [-]", row=2, col=1)
    Re = sweep["reynolds"]
    fig.update_yaxes(title_text="Re [-]" + (" (log)" if spans_decades(Re) else ""), **value_axis(Re), row=3, col=1)
    fig.update_xaxes(title_text=f"{label} [{x_unit}]", row=3, col=1)
    fig.update_layout(title=f"Trade-off: varying the {label}", height=720, **_LAYOUT)
    return fig


#: The design pinned on the Size page beside the current one: a dashed line in another colour.
BASELINE_STYLE = dict(mode="lines", line=dict(color=_OTHER, width=2, dash="dash"))


def _forces(*forces) -> np.ndarray:
    return np.concatenate([np.ravel(np.asarray(F, dtype=float)) for F in forces if F is not None])


def loops_figure(
    displacement,
    velocity,
    force,
    *,
    label: str = "model",
    measured=None,
    baseline=None,
    baseline_label: str = "pinned design",
) -> go.Figure:
    """Force-displacement and force-velocity loops of one force record (and the measured force, and the force of
    the baseline design on the same motion, when given)."""
    x, x_unit = _in(displacement, "m", "length")
    v, v_unit = _in(velocity, "m/s", "velocity")
    _, f_unit = _in(_forces(force, measured, baseline), "N", "force")
    fig = make_subplots(rows=1, cols=2, subplot_titles=("force - displacement", "force - velocity"))
    # the measured markers first, the model's thin line over them (plots.MEASURED_STYLE, plots.MODEL_STYLE)
    traces = [] if measured is None else [("measured", measured, MEASURED_STYLE)]
    traces.append((label, force, MODEL_STYLE))
    if baseline is not None:
        traces.append((baseline_label, baseline, BASELINE_STYLE))
    for name, F, style in traces:
        y = np.asarray(Q_(np.asarray(F, dtype=float), "N").to(_unit_of(f_unit)).magnitude)
        common = dict(name=name, legendgroup=name, **style)
        fig.add_trace(go.Scatter(x=x, y=y, **common), row=1, col=1)
        fig.add_trace(go.Scatter(x=v, y=y, showlegend=False, **common), row=1, col=2)
    fig.update_xaxes(title_text=f"displacement x [{x_unit}]", row=1, col=1)
    fig.update_xaxes(title_text=f"velocity v [{v_unit}]", row=1, col=2)
    fig.update_yaxes(title_text=f"force F [{f_unit}]", row=1, col=1)
    fig.update_layout(title="Loops", height=420, showlegend=len(traces) > 1, **_LAYOUT)
    return fig


def _unit_of(printed: str) -> str:
    """pint reads its own printed units back (``kN``, ``N·s/m``)."""
    return printed.replace("·", "*")


def time_figure(
    time, force, *, label: str = "model", measured=None, baseline=None, baseline_label: str = "pinned design"
) -> go.Figure:
    """Force against time: the model (and the measurement, and the baseline design's force, when given)."""
    t = np.asarray(time, dtype=float)
    _, f_unit = _in(_forces(force, measured, baseline), "N", "force")
    fig = go.Figure()
    if measured is not None:  # under the model's thin line, so that both stay visible where they agree
        fig.add_trace(
            go.Scatter(
                x=t,
                y=Q_(np.asarray(measured, float), "N").to(_unit_of(f_unit)).magnitude,
                name="measured",
                **MEASURED_STYLE,
            )
        )
    fig.add_trace(
        go.Scatter(x=t, y=Q_(np.asarray(force, float), "N").to(_unit_of(f_unit)).magnitude, name=label, **MODEL_STYLE)
    )
    if baseline is not None:
        fig.add_trace(
            go.Scatter(
                x=t,
                y=Q_(np.asarray(baseline, float), "N").to(_unit_of(f_unit)).magnitude,
                name=baseline_label,
                **BASELINE_STYLE,
            )
        )
    fig.update_layout(
        title="Force against time",
        xaxis_title="time t [s]",
        yaxis_title=f"force F [{f_unit}]",
        height=380,
        showlegend=len(fig.data) > 1,
        **_LAYOUT,
    )
    return fig


def residual_figure(time, velocity, residual) -> go.Figure:
    """Residual (measured minus model force) against time and against velocity."""
    t = np.asarray(time, dtype=float)
    v, v_unit = _in(velocity, "m/s", "velocity")
    r, r_unit = _in(residual, "N", "force")
    fig = make_subplots(rows=1, cols=2, subplot_titles=("residual - time", "residual - velocity"))
    fig.add_trace(go.Scatter(x=t, y=r, name="residual", **RESIDUAL_STYLE), row=1, col=1)
    fig.add_trace(go.Scatter(x=v, y=r, name="residual", **RESIDUAL_STYLE), row=1, col=2)
    fig.update_xaxes(title_text="time t [s]", row=1, col=1)
    fig.update_xaxes(title_text=f"velocity v [{v_unit}]", row=1, col=2)
    fig.update_yaxes(title_text=f"F - F_model [{r_unit}]", row=1, col=1)
    fig.update_layout(title="Residual: measured minus model force", height=380, **_LAYOUT)
    return fig
