"""Plotly figures of a damper's behaviour, shared by the report and the Streamlit app.

Each builder takes the numbers the library computed (a :class:`~erdesign.damper.curves.ForceVelocityCurves`, a
:class:`~erdesign.damper.curves.SineLoops`, an error history) and returns a :class:`plotly.graph_objects.Figure`;
none computes physics.  Axes are labelled with their units, chosen once per axis so that the numbers read between
1 and 1000 (:func:`erdesign.formatting.pick_unit`); conversions go through pint.

>>> from erdesign import load_example
>>> from erdesign.damper.curves import force_velocity_curves
>>> curves = force_velocity_curves(load_example("makris"), np.linspace(0, 0.05, 11), [0.0, 3e6])
>>> fig = force_velocity_figure(curves)
>>> [t.name for t in fig.data], fig.layout.yaxis.title.text
(['E = 0 kV/mm', 'E = 3 kV/mm'], 'force F [kN]')
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import plotly.graph_objects as go
from plotly.subplots import make_subplots

from ..formatting import pick_unit
from ..units import Q_

__all__ = [
    "MEASURED_STYLE",
    "MODEL_STYLE",
    "RESIDUAL_STYLE",
    "LAYOUT",
    "log_ticks",
    "value_axis",
    "spans_decades",
    "pressure_drop_figure",
    "force_velocity_figure",
    "dynamic_range_figure",
    "sine_loops_figure",
    "error_history_figure",
    "measured_loops_figure",
    "IMAGE_FORMATS",
    "export_config",
    "TOLERANCE_OUTPUTS",
    "tolerance_histogram_figure",
    "sensitivity_tornado_figure",
]

# The legend sits to the right of the plot area, outside it and below the title, so that it never covers the
# title or the data.
LAYOUT = dict(
    template="plotly_white",
    height=420,
    margin=dict(l=70, r=20, t=60, b=60),
    legend=dict(x=1.02, xanchor="left", y=1.0, yanchor="top"),
)
_LAYOUT = LAYOUT

#: Measured data: light markers without a line, drawn first, so that the model line over them stays readable and
#: the data show through where both agree.
MEASURED_STYLE = dict(mode="markers", marker=dict(color="rgba(31, 119, 180, 0.35)", size=5, line=dict(width=0)))
#: A model against measured data: a thin dark-red line over the light blue markers (another colour and weight).
MODEL_STYLE = dict(mode="lines", line=dict(color="#b2182b", width=1.6))
#: The residual (measured minus model) beneath a comparison: small grey markers.
RESIDUAL_STYLE = dict(mode="markers", marker=dict(color="rgba(80, 80, 80, 0.55)", size=3), showlegend=False)


def log_ticks(values: Any) -> dict:
    """Axis settings of a log axis over the positive finite ``values`` with every tick labelled in full: the decades
    when the values span more than three decades, else 1, 2 and 5 times each power of ten - never plotly's bare
    mantissas ("5 2 10 5 2 1").

    >>> log_ticks([2e-5, 3e-3])["ticktext"]
    ['1e-05', '2e-05', '5e-05', '0.0001', '0.0002', '0.0005', '0.001', '0.002', '0.005', '0.01']
    >>> log_ticks([1.0, 5e4])["ticktext"]
    ['1', '10', '100', '1000', '1e+04', '1e+05']
    """
    v = np.asarray(values, dtype=float).ravel()
    v = v[np.isfinite(v) & (v > 0)]
    if v.size == 0:
        return {"type": "log"}
    lo, hi = math.floor(math.log10(v.min())), math.ceil(math.log10(v.max()))
    hi = max(hi, lo + 1)
    steps = (1.0,) if hi - lo > 3 else (1.0, 2.0, 5.0)
    ticks = [m * 10.0**k for k in range(lo, hi + 1) for m in steps if m * 10.0**k <= 10.0**hi]
    return {"type": "log", "tickmode": "array", "tickvals": ticks, "ticktext": [f"{t:.4g}" for t in ticks]}


def value_axis(values: Any) -> dict:
    """A log axis (:func:`log_ticks`) when the positive values span more than a decade, else a linear one: a flat
    Reynolds number is not drawn on a log axis spanning decades.  Values equal to a thousandth get a range of
    +-10 % around them, so that rounding noise is not blown up to the whole height of the plot.

    >>> value_axis([0.04289291, 0.04289292])
    {'type': 'linear', 'range': [0.03860362, 0.04718221]}
    """
    if spans_decades(values):
        return log_ticks(values)
    v = np.asarray(values, dtype=float).ravel()
    v = v[np.isfinite(v)]
    if v.size and np.ptp(v) <= 1e-3 * np.max(np.abs(v)):
        pad = 0.1 * float(np.max(np.abs(v))) or 1.0
        return {"type": "linear", "range": [round(float(v.min()) - pad, 8), round(float(v.max()) + pad, 8)]}
    return {"type": "linear"}


#: Formats of plotly's camera button (the browser draws the image: no kaleido, no server-side browser).
IMAGE_FORMATS = ("png", "svg")


def export_config(filename: str, image_format: str = "png") -> dict:
    """The plotly config of a figure shown in the app or the HTML report: the camera button of its toolbar saves
    it as ``<filename>.<image_format>`` (PNG at twice the screen resolution, or SVG), without the plotly logo.

    >>> export_config("makris-1996-force", "svg")["toImageButtonOptions"]
    {'format': 'svg', 'filename': 'makris-1996-force', 'scale': 1}
    """
    if image_format not in IMAGE_FORMATS:
        raise ValueError(f"image format: expected one of {', '.join(IMAGE_FORMATS)}, got {image_format!r}")
    return {
        "displaylogo": False,
        "displayModeBar": True,
        "toImageButtonOptions": {
            "format": image_format,
            "filename": filename,
            "scale": 2 if image_format == "png" else 1,
        },
    }


def spans_decades(values: Any, decades: float = 1.0) -> bool:
    """True when the positive finite values span more than ``decades`` decades (draw them on a log axis).

    >>> spans_decades([100.0, 3000.0]), spans_decades([1.0, 2.0]), spans_decades([0.0, -1.0])
    (True, False, False)
    """
    v = np.asarray(values, dtype=float).ravel()
    v = v[np.isfinite(v) & (v > 0)]
    return bool(v.size >= 2 and np.log10(v.max() / v.min()) > decades)


def _convert(values: Any, si_unit: str, unit: str) -> np.ndarray:
    return np.asarray(Q_(np.asarray(values, dtype=float), si_unit).to(unit).magnitude)


def _unit_label(unit: str) -> str:
    return f"{Q_(1.0, unit).units:~P}" if unit else "-"


#: Line styles of the designs drawn beside the current one (the first is the baseline's).
_DASHES = ("dash", "dot", "dashdot", "longdash")


def _by_field(
    sweep,
    values: np.ndarray,
    si_unit: str,
    kind: str,
    title: str,
    y_label: str,
    skip_zero: bool = False,
    others=(),
) -> go.Figure:
    """One line per control of ``sweep``; ``others``: ``(label, sweep, values)`` of further designs, each in its own
    dash (:data:`_DASHES`), in one unit with the first."""
    both = np.concatenate([np.ravel(values), *(np.ravel(vals) for _, _, vals in others)])
    speeds = np.concatenate([sweep.velocity, *(sw.velocity for _, sw, _ in others)])
    v_unit = pick_unit(Q_(speeds, "m/s"), "velocity")
    y_unit = pick_unit(Q_(both, si_unit), kind) if kind else ""
    fig = go.Figure()
    sets = [("", sweep, values, "solid")] + [
        (f"{label}, ", sw, vals, _DASHES[j % len(_DASHES)]) for j, (label, sw, vals) in enumerate(others)
    ]
    for prefix, sw, vals, dash in sets:
        x = _convert(sw.velocity, "m/s", v_unit)
        for i, (label, E, row) in enumerate(zip(sw.field_labels(), sw.field, vals)):
            if skip_zero and E == 0:
                continue
            y = _convert(row, si_unit, y_unit) if kind else np.asarray(row)
            fig.add_trace(
                go.Scatter(
                    x=x,
                    y=y,
                    mode="lines",
                    name=prefix + label,
                    line=dict(color=_colour(i), dash=dash, width=2.5 if not prefix else 1.5),
                )
            )
    fig.update_layout(
        title=title,
        xaxis_title=f"piston velocity v [{_unit_label(v_unit)}]",
        yaxis_title=f"{y_label} [{_unit_label(y_unit)}]",
        **_LAYOUT,
    )
    return fig


def pressure_drop_figure(sweep) -> go.Figure:
    """Pressure drop across the piston versus velocity, one line per control."""
    return _by_field(sweep, sweep.pressure_drop, "Pa", "pressure", "Pressure drop versus velocity", "pressure drop Δp")


def force_velocity_figure(sweep, baseline=None, pinned=()) -> go.Figure:
    """Quasi-steady damper force versus velocity, one line per control; with ``baseline`` (another sweep), its
    curves dashed beside them (the comparison of two designs); ``pinned``: ``(label, sweep)`` of several designs,
    each in its own dash (dashed, dotted, dash-dotted, long-dashed)."""
    others = [("baseline", baseline)] if baseline is not None else []
    others += list(pinned)
    if not others:
        title = "Force versus velocity"
    elif len(others) == 1:
        title = f"Force versus velocity: this design (solid) and the {others[0][0]} (dashed)"
    else:
        title = "Force versus velocity: this design (solid) and the pinned designs (dashed, dotted, ...)"
    return _by_field(
        sweep, sweep.force, "N", "force", title, "force F", others=[(label, sw, sw.force) for label, sw in others]
    )


def dynamic_range_figure(sweep) -> go.Figure:
    """Dynamic range F(v, E) / F(v, 0) versus velocity, one line per nonzero control."""
    return _by_field(
        sweep, sweep.dynamic_range, "", "", "Dynamic range versus velocity", "dynamic range F(E)/F(0)", skip_zero=True
    )


def sine_loops_figure(loops) -> go.Figure:
    """Force-displacement and force-velocity loops of a sine, side by side, one loop per control."""
    x_unit = pick_unit(Q_(loops.amplitude, "m"), "length")
    v_unit = pick_unit(Q_(np.concatenate([r.velocity for r in loops.responses]), "m/s"), "velocity")
    f_unit = pick_unit(Q_(np.concatenate([r.force for r in loops.responses]), "N"), "force")
    fig = make_subplots(rows=1, cols=2, subplot_titles=("force - displacement", "force - velocity"))
    for i, (label, r) in enumerate(zip(loops.field_labels(), loops.responses)):
        F = _convert(r.force, "N", f_unit)
        common = dict(mode="lines", name=label, legendgroup=label, line=dict(color=_colour(i)))
        fig.add_trace(go.Scatter(x=_convert(r.displacement, "m", x_unit), y=F, **common), row=1, col=1)
        fig.add_trace(go.Scatter(x=_convert(r.velocity, "m/s", v_unit), y=F, showlegend=False, **common), row=1, col=2)
    amp = Q_(loops.amplitude, "m").to(x_unit).magnitude
    fig.update_layout(
        title=f"Sine loops: X0 = {amp:.4g} {_unit_label(x_unit)}, f = {loops.frequency:.4g} Hz", **_LAYOUT
    )
    fig.update_xaxes(title_text=f"displacement x [{_unit_label(x_unit)}]", row=1, col=1)
    fig.update_xaxes(title_text=f"velocity v [{_unit_label(v_unit)}]", row=1, col=2)
    fig.update_yaxes(title_text=f"force F [{_unit_label(f_unit)}]", row=1, col=1)
    return fig


def error_history_figure(history: Sequence[Any], noise_floor: float | None = None) -> go.Figure:
    """ESR after each step of a diagnosis (bars labelled with the effect added), and the noise floor when given.

    The ESR axis is logarithmic: each added effect typically divides the error by a factor, and a linear axis would
    hide every step after the first.
    """
    fig = go.Figure(
        go.Bar(
            x=[f"{h.step}: {h.effect}" for h in history],
            y=[h.esr for h in history],
            text=[f"{h.esr:.3g}" for h in history],
            textposition="outside",
            name="ESR",
            marker_color="#1f77b4",
            cliponaxis=False,
        )
    )
    esr = [h.esr for h in history if h.esr > 0]
    lows = esr + ([noise_floor] if noise_floor is not None and noise_floor > 0 else [])
    if noise_floor is not None and noise_floor > 0:
        fig.add_hline(y=noise_floor, line=dict(color="#2ca02c", dash="dash"))
        # plotly places a line's own annotation wrongly on a log axis: annotate at log10(y) instead, in the right
        # margin at the line's end (inside the plot it sat over the last bar, which always reaches above the floor)
        fig.add_annotation(
            x=1.01,
            xref="paper",
            xanchor="left",
            y=float(np.log10(noise_floor)),
            yref="y",
            yanchor="middle",
            align="left",
            text=f"noise floor<br>{noise_floor:.3g}",
            showarrow=False,
            font=dict(color="#1e7b1e"),
            bgcolor="rgba(255, 255, 255, 0.85)",
        )
    fig.update_layout(
        title="Error history",
        xaxis_title="step: effect added",
        yaxis_title="ESR [-]",
        **{**_LAYOUT, "showlegend": False, "margin": {**_LAYOUT["margin"], "r": 100}},
    )
    if lows:  # the range holds the bars, their labels and the noise floor
        lo, hi = float(np.log10(min(lows))) - 0.5, float(np.log10(max(esr or lows))) + 0.6
        fig.update_yaxes(range=[lo, hi], **log_ticks([10**lo, 10**hi]))
    else:
        fig.update_yaxes(type="log")
    return fig


def measured_loops_figure(displacement, velocity, force_measured, force_model) -> go.Figure:
    """Measured (light markers) and model force (thin line over them) against displacement and velocity, and the
    residual (measured minus model) beneath each, in the same force unit (SI arrays)."""
    x_unit = pick_unit(Q_(displacement, "m"), "length")
    v_unit = pick_unit(Q_(velocity, "m/s"), "velocity")
    f_unit = pick_unit(Q_(np.concatenate([np.ravel(force_measured), np.ravel(force_model)]), "N"), "force")
    fig = make_subplots(
        rows=2,
        cols=2,
        shared_xaxes=True,
        row_heights=[0.72, 0.28],
        vertical_spacing=0.06,
        horizontal_spacing=0.1,
        subplot_titles=("force - displacement", "force - velocity", "", ""),
    )
    x, v = _convert(displacement, "m", x_unit), _convert(velocity, "m/s", v_unit)
    for name, F, style in (("measured", force_measured, MEASURED_STYLE), ("model", force_model, MODEL_STYLE)):
        y = _convert(F, "N", f_unit)
        common = dict(name=name, legendgroup=name, **style)
        fig.add_trace(go.Scatter(x=x, y=y, **common), row=1, col=1)
        fig.add_trace(go.Scatter(x=v, y=y, showlegend=False, **common), row=1, col=2)
    r = _convert(np.asarray(force_measured, dtype=float) - np.asarray(force_model, dtype=float), "N", f_unit)
    fig.add_trace(go.Scatter(x=x, y=r, name="residual", **RESIDUAL_STYLE), row=2, col=1)
    fig.add_trace(go.Scatter(x=v, y=r, name="residual", **RESIDUAL_STYLE), row=2, col=2)
    fig.update_layout(title="Measurement and model", **{**_LAYOUT, "height": 560})
    fig.update_xaxes(title_text=f"displacement x [{_unit_label(x_unit)}]", row=2, col=1)
    fig.update_xaxes(title_text=f"velocity v [{_unit_label(v_unit)}]", row=2, col=2)
    fig.update_yaxes(title_text=f"force F [{_unit_label(f_unit)}]", row=1, col=1)
    fig.update_yaxes(title_text=f"residual [{_unit_label(f_unit)}]", row=2, col=1)
    return fig


#: Outputs of a tolerance study (:mod:`erdesign.campaign.tolerance`): label, SI unit and unit kind for the axes.
TOLERANCE_OUTPUTS = {
    "force_N": ("force", "force F", "N", "force"),
    "zero_field_force_N": ("zero-field force", "zero-field force F(0)", "N", "force"),
    "dynamic_range": ("dynamic range", "dynamic range F(E)/F(0)", "", ""),
    "damping_constant_N_s_per_m": ("damping constant", "damping constant C", "N*s/m", "damping"),
}


def tolerance_histogram_figure(result, output: str = "force_N") -> go.Figure:
    """Histogram of one output of a tolerance study (its kept histogram), with the 5, 50 and 95 % quantiles and the
    nominal value marked.

    >>> from erdesign import load_example
    >>> from erdesign.campaign.tolerance import tolerance_study
    >>> r = tolerance_study(load_example("makris"), ["geometry.gap=+-2.5 %"], velocity=0.0254, samples=2000,
    ...                     sensitivity=False)
    >>> fig = tolerance_histogram_figure(r)
    >>> fig.layout.xaxis.title.text, fig.layout.title.text
    ('force F [kN]', 'Spread of the force (2000 samples)')
    """
    name, label, si_unit, kind = TOLERANCE_OUTPUTS[output]
    edges, counts = result.histograms[output]
    unit = pick_unit(Q_(edges, si_unit), kind) if kind else ""
    x = _convert(edges, si_unit, unit) if kind else np.asarray(edges)
    centres, widths = (x[1:] + x[:-1]) / 2, np.diff(x)
    fig = go.Figure(
        go.Bar(
            x=centres,
            y=counts / max(1, result.count),
            width=widths,
            name="samples",
            marker=dict(color="rgba(31, 119, 180, 0.6)"),
        )
    )
    marks = [(f"{q} %", result.quantiles[output][q], "dash") for q in ("5", "50", "95")]
    marks.append(("nominal", result.nominal[output], "solid"))
    for i, (mark, value, dash) in enumerate(marks):
        if value is None or not np.isfinite(value):
            continue
        xv = float(_convert(value, si_unit, unit)) if kind else float(value)
        fig.add_trace(
            go.Scatter(
                x=[xv, xv],
                y=[0, float(counts.max()) / max(1, result.count)],
                mode="lines",
                name=mark,
                line=dict(color=_colour(i + 1), dash=dash, width=2),
            )
        )
    fig.update_layout(
        title=f"Spread of the {name} ({result.count} samples)",
        xaxis_title=f"{label} [{_unit_label(unit)}]",
        yaxis_title="fraction of samples per bin",
        bargap=0.02,
        **_LAYOUT,
    )
    return fig


def sensitivity_tornado_figure(result, output: str = "force_N") -> go.Figure:
    """Tornado chart of one output of a tolerance study: the first-order and total Sobol index of each input,
    largest at the top, with the bootstrap 95 % intervals."""
    name = TOLERANCE_OUTPUTS[output][0]
    rows = [(key, s) for key, s in result.sensitivity.get(output, {}).items() if s["total"] is not None]
    rows.sort(key=lambda r: r[1]["total"])
    inputs = [key for key, _ in rows]
    fig = go.Figure()
    for key, legend, colour in (("total", "total", _colour(0)), ("first", "first-order", _colour(1))):
        fig.add_trace(
            go.Bar(
                y=inputs,
                x=[s[key] for _, s in rows],
                orientation="h",
                name=legend,
                marker=dict(color=colour),
                error_x=dict(type="data", array=[s[key + "_conf"] or 0.0 for _, s in rows]),
            )
        )
    fig.update_layout(
        title=f"What drives the spread of the {name}",
        xaxis_title="Sobol index (share of the variance)",
        barmode="group",
        xaxis=dict(range=[0, 1.05]),
        **_LAYOUT,
    )
    if not rows:
        fig.add_annotation(text="this output does not vary", showarrow=False, x=0.5, y=0.5, xref="paper", yref="paper")
    return fig


def _colour(i: int) -> str:
    palette = ("#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf")
    return palette[i % len(palette)]
