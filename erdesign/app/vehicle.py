"""Vehicle page: the quarter vehicle of Butz and von Stryk (2002) with several dampers and control laws side by side.

Dampers: the design of the Size page (its physics damper) and the dampers of the literature
(:data:`erdesign.simulation.vehicle_setup.PRESET_DAMPERS`); control laws:
:data:`erdesign.simulation.control.CONTROLLERS`.
Every run is :func:`erdesign.simulation.vehicle.simulate_vehicle`; the page only chooses the inputs and draws the
results (docs/vehicle.md).
"""

from __future__ import annotations

import itertools

import numpy as np
import plotly.graph_objects as go
import streamlit as st

from erdesign.app import state
from erdesign.errors import ErdesignError
from erdesign.simulation.control import CONTROLLERS
from erdesign.simulation.vehicle_setup import PRESET_DAMPERS
from erdesign.units import to_si

__all__ = ["render", "DESIGN_DAMPER", "FIGURES"]

DESIGN_DAMPER = "the design (Size page)"
#: Ride figure key -> (label, unit of the table and the bar chart, factor from SI).
FIGURES = {
    "body_acceleration_rms_m_per_s2": ("RMS body acceleration", "m/s^2", 1.0),
    "body_acceleration_weighted_rms_m_per_s2": ("ISO 2631 Wk-weighted RMS body acceleration", "m/s^2", 1.0),
    "suspension_travel_rms_m": ("RMS suspension travel", "mm", 1e3),
    "suspension_travel_peak_m": ("peak suspension travel", "mm", 1e3),
    "tyre_load_rms_N": ("RMS dynamic tyre load", "N", 1.0),
    "damper_force_peak_N": ("peak damper force", "N", 1.0),
    "settling_time_s": ("body settling time (10 % band)", "s", 1.0),
}


@st.cache_data(show_spinner=False, max_entries=32)
def _run(spec_text: str, damper_name: str, control: str, road: tuple, duration: float) -> dict:
    """One run as plain data (cached on plain arguments)."""
    from erdesign.simulation.roads import make_road
    from erdesign.simulation.vehicle import simulate_vehicle
    from erdesign.simulation.vehicle_setup import vehicle_damper

    if damper_name == DESIGN_DAMPER:
        damper, _ = state.build_damper(spec_text)
        d = vehicle_damper(damper=damper)
    else:
        d = vehicle_damper(**PRESET_DAMPERS[damper_name])
    r = simulate_vehicle(d, make_road(road[0], **dict(road[1:])), control, duration=duration)
    step = max(1, r.time.size // 2000)  # at most 2000 points per curve in the browser
    return {
        "time": r.time[::step],
        "u0": r.u0[::step],
        "u2": r.u2[::step],
        "a2": r.a2[::step],
        "ride": r.ride(),
        "control_kind": r.control_kind,
    }


def _road() -> tuple | None:
    kind = state.widget(
        st.selectbox,
        "road",
        "veh.road",
        "bump",
        options=["step", "bump", "random"],
        format_func={
            "step": "step (Butz and von Stryk 4.4)",
            "bump": "(1 - cos) bump (4.5)",
            "random": "ISO 8608 random road",
        }.get,
    )
    try:
        if kind == "random":
            c = st.columns(2)
            road_class = state.widget(c[0].selectbox, "ISO 8608 class", "veh.class", "C", options=list("ABCDEFGH"))
            speed = to_si(state.widget(c[1].text_input, "speed", "veh.speed", "20 m/s"), "m/s", "speed")
            return ("random", ("road_class", road_class), ("speed", float(speed)))
        height = to_si(state.widget(st.text_input, "height", "veh.height", "0.1 m"), "m", "height")
        if kind == "bump":
            length = to_si(state.widget(st.text_input, "bump duration", "veh.bump", "0.5 s"), "s", "bump duration")
            return ("bump", ("height", float(height)), ("duration", float(length)))
        return ("step", ("height", float(height)))
    except ErdesignError as exc:
        st.error(state.clean_message(str(exc)))
        return None


#: Short names of the dampers on the page (choices, run labels, legends), so that they fit a chip and a legend; the
#: sources are in the help of the choice.
SHORT_NAMES = {
    "conventional (Butz and von Stryk eq 33)": "conventional (Butz)",
    "MR, Bingham (Butz and von Stryk 4.2)": "MR Bingham (Butz)",
    "MR, modified Bouc-Wen (Butz and von Stryk 4.3)": "MR Bouc-Wen (Butz)",
    "MR, Spencer et al. 1997, 0-2.25 V": "MR Spencer 1997",
}


def short(name: str) -> str:
    """The damper's name on the page."""
    return SHORT_NAMES.get(name, name)


#: Legend under the plot area, so that it takes no width from the curves.
_LEGEND_BELOW = dict(orientation="h", x=0.0, xanchor="left", y=-0.22, yanchor="top")


def time_figure(runs: dict, key: str, label: str, unit: str, factor: float, road: dict | None = None) -> go.Figure:
    """One curve per run of ``key`` against time (the road under it when given)."""
    fig = go.Figure()
    if road is not None:
        fig.add_scatter(x=road["time"], y=factor * road["u0"], name="road u0", line=dict(color="#999999", dash="dot"))
    for name, run in runs.items():
        fig.add_scatter(x=run["time"], y=factor * run[key], name=name)
    fig.update_layout(
        template="plotly_white",
        title=label,
        xaxis_title="time t [s]",
        yaxis_title=f"{label} [{unit}]",
        margin=dict(l=70, r=20, t=60, b=60),
        legend=_LEGEND_BELOW,
    )
    return fig


def bar_figure(runs: dict, key: str) -> go.Figure:
    """A ride figure of every run as bars."""
    label, unit, factor = FIGURES[key]
    names = list(runs)
    values = [np.nan if runs[n]["ride"][key] is None else factor * runs[n]["ride"][key] for n in names]
    fig = go.Figure(go.Bar(x=names, y=values, text=[f"{v:.3g}" for v in values], textposition="auto"))
    fig.update_layout(
        template="plotly_white",
        yaxis_title=f"{label} [{unit}]",  # the axis names it: no title
        margin=dict(l=70, r=20, t=30, b=120),
    )
    return fig


def render() -> None:
    """Draw the Vehicle page."""
    st.title("Vehicle")
    st.caption(
        "The quarter vehicle of Butz and von Stryk (2002), section 4: axle 250 kg, body 1300 kg, tyre 650 kN/m "
        "and 800 N s/m, suspension spring 110 kN/m, with the dampers and control laws chosen below "
        "(docs/vehicle.md)."
    )
    design = state.current_design()
    text = state.spec_text(design["spec"])
    left, right = st.columns([1, 2], gap="large")
    with left:
        dampers = state.widget(
            st.multiselect,
            "dampers",
            "veh.dampers",
            list(PRESET_DAMPERS)[:2],
            options=[DESIGN_DAMPER, *PRESET_DAMPERS],
            format_func=short,
            help="The design of the Size page runs as its physics damper (control range 0 to "
            "its reference field). The others: " + "; ".join(PRESET_DAMPERS) + ".",
        )
        controls = state.widget(
            st.multiselect,
            "control laws",
            "veh.controls",
            ["passive"],
            options=list(CONTROLLERS),
            help="Semi-active laws need a damper whose force the control changes.",
        )
        road = _road()
        duration = state.widget(
            st.number_input, "simulated time [s]", "veh.duration", 2.0, min_value=0.5, max_value=20.0, step=0.5
        )
    with right:
        if road is None or not dampers or not controls:
            st.info("Choose at least one damper and one control law.")
            return
        runs, skipped = {}, []
        with st.spinner("Simulating ..."):
            for damper_name, control in itertools.product(dampers, controls):
                label = f"{short(damper_name)}, {control}"
                try:
                    runs[label] = _run(text, damper_name, control, road, float(duration))
                except ErdesignError as exc:
                    skipped.append(f"{label}: {state.clean_message(str(exc))}")
        for message in skipped:
            st.warning(message)
        if not runs:
            return
        rows = [
            {
                "run": name,
                **{
                    FIGURES[k][0] + f" [{FIGURES[k][1]}]": (
                        None if run["ride"][k] is None else round(FIGURES[k][2] * run["ride"][k], 4)
                    )
                    for k in FIGURES
                },
            }
            for name, run in runs.items()
        ]
        st.dataframe(rows, hide_index=True, key="veh.table")
        first = next(iter(runs.values()))
        st.plotly_chart(
            time_figure(runs, "u2", "body displacement u2", "mm", 1e3, road=first),
            key="veh.fig.body",
            config=state.chart_config("veh.fig.body"),
        )
        st.plotly_chart(
            time_figure(runs, "a2", "body acceleration a2", "m/s^2", 1.0),
            key="veh.fig.acceleration",
            config=state.chart_config("veh.fig.acceleration"),
        )
        st.plotly_chart(
            bar_figure(runs, "body_acceleration_weighted_rms_m_per_s2"),
            key="veh.fig.comfort",
            config=state.chart_config("veh.fig.comfort"),
        )


if __name__ == "__main__":
    render()
