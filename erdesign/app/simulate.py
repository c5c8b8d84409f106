"""Simulate page: a model (the physics damper with effects, or any model of the library) driven by an excitation.

Excitations come from the virtual rig (:mod:`erdesign.simulation.rig`: sine, sine sweep, earthquake-like record) or from
the displacement of an uploaded measurement CSV; forces from :meth:`erdesign.models.base.Model.simulate`
(:func:`erdesign.app.state.simulate`).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import streamlit as st

from erdesign.app import figures, state
from erdesign.effects import EFFECT_NAMES, EFFECTS
from erdesign.errors import ErdesignError
from erdesign.models.registry import get_model, model_names
from erdesign.report.export import csv_text
from erdesign.report.fit import EXPORT_UNITS
from erdesign.report.formatting import control_label, kind_of, pick_unit, round_significant, show, unit_system
from erdesign.units import Q_, to_si, ureg

__all__ = ["render", "EXCITATIONS", "model_label"]

EXCITATIONS = {
    "sine": "sine",
    "sweep": "sine sweep (two amplitudes and frequencies)",
    "earthquake": "earthquake-like record",
    "upload": "uploaded displacement (measurement CSV)",
    "programme": "test programme E1-E5 (Vivas-López et al.)",
}


def _excitation(fluid, design_field: str):
    """Draw the excitation inputs; return the excitation as plain data (SI) for :func:`state.simulate` and the
    uploaded file (or None), or None when the inputs are not complete.

    The control input follows the damper: its label names the fluid's kind of control (field E, coil current I)
    and it takes the design control of the Size page whenever that changes (another damper, another control);
    a value typed here holds until then."""
    control_unit = fluid.control_unit
    kind = state.widget(
        st.selectbox, "excitation", "sim.kind", "sine", options=list(EXCITATIONS), format_func=EXCITATIONS.get
    )
    if st.session_state.get("sim.field.source") != design_field:
        state.set_widget("sim.field", design_field)
        st.session_state["sim.field.source"] = design_field
    field_text = state.widget(
        st.text_input,
        control_label(fluid.control),
        "sim.field",
        design_field,
        help="The control during the test, with its unit (the design control of the Size page to start with).",
    )
    try:
        E = float(to_si(field_text, control_unit, "field"))
        if kind == "sine":
            c = st.columns(3)
            X0 = to_si(state.widget(c[0].text_input, "amplitude X0", "sim.amplitude", "10 mm"), "m", "amplitude")
            f = to_si(state.widget(c[1].text_input, "frequency f", "sim.frequency", "1 Hz"), "Hz", "frequency")
            cycles = state.widget(c[2].number_input, "cycles", "sim.cycles", 2, min_value=1, max_value=20)
            return (
                ("kind", "sine"),
                ("amplitude", float(X0)),
                ("frequency", float(f)),
                ("field", E),
                ("cycles", float(cycles)),
                ("rate", _rate(float(f))),
            ), None
        if kind == "sweep":
            c = st.columns(2)
            A = [
                to_si(state.widget(c[0].text_input, f"amplitude {i + 1}", f"sim.sweep.a{i}", a), "m", "amplitude")
                for i, a in enumerate(("5 mm", "15 mm"))
            ]
            f = [
                to_si(state.widget(c[1].text_input, f"frequency {i + 1}", f"sim.sweep.f{i}", q), "Hz", "frequency")
                for i, q in enumerate(("2 Hz", "0.5 Hz"))
            ]
            return (
                ("kind", "sweep"),
                ("amplitudes", tuple(map(float, A))),
                ("frequencies", tuple(map(float, f))),
                ("fields", (E, E)),
                ("cycles", 2.0),
                ("rate", _rate(max(f))),
            ), None
        if kind == "earthquake":
            c = st.columns(3)
            peak = to_si(state.widget(c[0].text_input, "peak displacement", "sim.peak", "10 mm"), "m", "peak")
            duration = to_si(state.widget(c[1].text_input, "duration", "sim.duration", "8 s"), "s", "duration")
            seed = state.widget(c[2].number_input, "random seed", "sim.seed", 0, min_value=0, max_value=10_000)
            return (
                ("kind", "earthquake"),
                ("peak", float(peak)),
                ("field", E),
                ("duration", float(duration)),
                ("rate", 500.0),
                ("seed", int(seed)),
            ), None
        if kind == "programme":
            from erdesign.simulation.programmes import EXPERIMENTS

            name = state.widget(
                st.selectbox,
                "experiment",
                "sim.programme",
                "E5",
                options=[k.upper() for k in EXPERIMENTS],
                help="Table 1 of Vivas-López et al.: the control steps between E/8 and E (their PWM "
                "duty cycle 10 % to 80 %); docs/characterize.md.",
            )
            return (("kind", "programme"), ("name", name), ("control_range", (E / 8, E)), ("rate", 250.0)), None
    except ErdesignError as exc:
        st.error(state.clean_message(str(exc)))
        return None
    upload = st.file_uploader(
        "displacement CSV (time and displacement columns with units; force optional)", type=["csv"], key="sim.upload"
    )
    if upload is None:
        st.info(
            "Upload a CSV with time and displacement columns: the displacement drives the model; a force column, "
            "if there is one, is shown for comparison. Without a field column the field above is applied."
        )
        return None
    return (("kind", "upload"), ("field", E)), upload


def _rate(frequency: float) -> float:
    """Sampling rate of a rig excitation: 400 samples per cycle of the fastest frequency, at least 200 Hz."""
    return max(200.0, 400.0 * frequency)


def _model(damper) -> tuple[str, tuple[str, ...], tuple[tuple[str, float], ...]] | None:
    names = model_names()
    name = state.widget(
        st.selectbox,
        "model",
        "sim.model",
        "physics",
        options=names,
        help="physics: the damper of the Size page with effects; the others are the "
        "phenomenological models of the library (erdesign models).",
    )
    effects: tuple[str, ...] = ()
    if name == "physics":
        effects = tuple(
            state.widget(
                st.multiselect,
                "effects",
                "sim.effects",
                [],
                options=list(EFFECT_NAMES),
                help="Physical effects added to the quasi-steady damper (erdesign.effects).",
            )
        )
        for e in effects:
            st.caption(f"**{e}**: {EFFECTS[e].mechanism}")
        model = get_model("physics", damper=damper, effects=effects)
    else:
        model = get_model(name)
        st.caption(model.source)
    system = unit_system()
    # The table of one model and unit system is a widget of its own (its key); it starts from the values last
    # used with this model in any unit system (SI, exact), so that a switch of the unit system converts what was
    # typed instead of dropping it.
    model_key = f"sim.values.{name}.{','.join(effects)}"
    key = f"{model_key}.{system}"
    if st.session_state.get("sim.values.table") != key or f"{key}.start" not in st.session_state:
        last = st.session_state.get(f"{model_key}.si", {})
        st.session_state[f"{key}.start"] = {p.name: float(last.get(p.name, p.default)) for p in model.parameters}
        st.session_state.pop(key, None)  # a table left earlier in this system holds stale edits
        st.session_state["sim.values.table"] = key
    start = st.session_state[f"{key}.start"]
    # each value in a prefixed unit of the unit system that keeps it between 1 and 1000, to 4 significant figures
    # (43.24 MN/m, not 43241692.2085 N/m); a value left as shown is the exact start value (_to_si)
    shown = {p.name: _display_unit(p.unit, start[p.name]) for p in model.parameters}
    shown_start = {
        p.name: float(round_significant(_to_unit(start[p.name], p.unit, shown[p.name]))) for p in model.parameters
    }
    rows = [
        {
            "parameter": p.name,
            "value": shown_start[p.name],
            "unit": _pretty(shown[p.name]),
            "description": p.description,
        }
        for p in model.parameters
    ]
    edited = st.data_editor(
        rows, key=key, disabled=["parameter", "unit", "description"], hide_index=True, width="stretch"
    )
    try:
        values = tuple(
            (r["parameter"], _to_si(r["parameter"], float(r["value"]), model, shown, shown_start, start))
            for r in edited
        )
        model.check_values(dict(values))
    except (ErdesignError, TypeError, ValueError) as exc:
        st.error(f"Parameter values: {state.clean_message(str(exc))}")
        return None
    st.session_state[f"{model_key}.si"] = dict(values)
    return name, effects, values


def _display_unit(unit: str, value: float) -> str:
    """The unit a parameter of SI unit ``unit`` and start ``value`` is shown and typed in: the unit the unit system
    gives its kind (force, damping, stiffness, length, pressure, ...; in SI the prefix that keeps the value between
    1 and 1000), else ``unit`` itself (plain factors, kinds without a unit choice: 1/m, ...)."""
    kind = kind_of(unit)
    if kind is None:
        return unit
    return pick_unit(Q_(abs(value), unit), kind)


def _pretty(unit: str) -> str:
    """A unit as a table shows it: ``kN·s/m`` (pint's short pretty form), ``-`` for none."""
    return f"{ureg.Unit(unit):~P}" if unit else "-"


def _to_unit(value: float, unit: str, shown: str) -> float:
    """``value`` [``unit``] in the unit ``shown`` (pint)."""
    return value if shown == unit else float(Q_(value, unit).to(shown).magnitude)


def _to_si(name: str, value: float, model, shown: dict, shown_start: dict, start: dict) -> float:
    """A value typed in the table (unit ``shown[name]``) in the model's SI unit, exactly (pint); a value left at
    its shown starting value is the SI starting value itself (``start``), so that a conversion's last bit never
    reads as an edit."""
    (p,) = [p for p in model.parameters if p.name == name]
    if value == shown_start[name]:
        return start[name]
    return value if shown[name] == p.unit else float(Q_(value, shown[name]).to(p.unit).magnitude)


def render() -> None:
    """Draw the Simulate page."""
    st.title("Simulate")
    design = state.current_design()
    text = state.spec_text(design["spec"])
    damper = state.damper_or_error(text)
    if damper is None:
        return
    st.caption(f"Damper: {damper.name or 'design'} ({damper.geometry.configuration}); change it on the Size page.")
    left, right = st.columns([1, 2], gap="large")
    with left:
        st.subheader("Model")
        chosen = _model(damper)
        st.subheader("Excitation")
        excitation = _excitation(damper.fluid, design["field"])
    with right:
        if chosen is None or excitation is None:
            return
        excitation, file = excitation
        upload, upload_name = (None, "") if file is None else (file.getvalue(), file.name)
        name, effects, values = chosen
        try:
            with st.spinner("Simulating ..."):
                sim = state.simulate(text, name, effects, values, excitation, upload, upload_name)
        except ErdesignError as exc:
            st.error(state.clean_message(str(exc)))
            return
        st.session_state["sim.last"] = {"title": sim["title"], "description": sim["description"]}
        label = model_label(name, effects, sim["title"])
        st.caption(
            f"{label}: {sim['description']}"
            + (f" (effects: {', '.join(effects)})" if name == "physics" and len(effects) > 1 else "")
        )
        F = sim["force"]
        base = _baseline(design, damper, name, effects, values, excitation, upload, upload_name)
        Fb = None if base is None else base["force"]
        peak = Q_(float(np.max(np.abs(F))), "N")
        unit = pick_unit(peak if Fb is None else Q_(max(peak.magnitude, float(np.max(np.abs(Fb)))), "N"), "force")
        c = st.columns(4 if Fb is not None else 3)
        c[0].metric("peak force", show(peak, unit, name="peak force").text)
        c[1].metric("samples", f"{F.size}")
        c[2].metric("duration", f"{sim['time'][-1] - sim['time'][0]:.3g} s")
        if Fb is not None:
            peak_b = Q_(float(np.max(np.abs(Fb))), "N")
            c[3].metric(
                "peak force, pinned design",
                show(peak_b, unit, name="pinned design's peak force").text,
                help="The design pinned on the Size page, with the same model, effects and excitation.",
            )
        st.plotly_chart(
            figures.loops_figure(
                sim["displacement"], sim["velocity"], F, label=label, measured=sim["measured"], baseline=Fb
            ),
            key="sim.fig.loops",
            config=state.chart_config("sim.fig.loops"),
        )
        st.plotly_chart(
            figures.time_figure(sim["time"], F, label=label, measured=sim["measured"], baseline=Fb),
            key="sim.fig.time",
            config=state.chart_config("sim.fig.time"),
        )
        _download(sim, damper, name, effects, values)


def model_label(name: str, effects: Sequence[str], title: str) -> str:
    """The short name of a simulated model on a legend: ``"design"``, ``"design + seal_friction"``, ``"design + 3
    effects"`` (the list goes in the caption), or a library model's title.

    >>> model_label("physics", (), "physics damper"), model_label("physics", ("a", "b", "c"), "")
    ('design', 'design + 3 effects')
    """
    if name != "physics":
        return title
    if len(effects) > 1:
        return f"design + {len(effects)} effects"
    return "design" + "".join(f" + {e}" for e in effects)


def _baseline(design: dict, damper, name: str, effects, values, excitation, upload, upload_name) -> dict | None:
    """The simulation of the baseline design pinned on the Size page (same model, effects and excitation), or None.

    A parameter whose value was edited in the table is applied to both designs; the others take each design's own
    default (an effect's prior from its geometry and fluid).
    """
    base = state.pinned_baseline(design)
    if base is None:
        return None
    text = state.spec_text(base["spec"])
    try:
        base_damper = state.build_damper(text)[0]
        if name == "physics":
            defaults = {p.name: p.default for p in get_model("physics", damper=damper, effects=effects).parameters}
            edited = {k: v for k, v in values if v != defaults.get(k)}
            model = get_model("physics", damper=base_damper, effects=effects)
            values = tuple((p.name, edited.get(p.name, p.default)) for p in model.parameters)
        sim = state.simulate(text, name, effects, values, excitation, upload, upload_name)
    except ErdesignError as exc:
        st.info(f"The pinned baseline design cannot be simulated: {state.clean_message(str(exc))}")
        return None
    changed = [
        f"{section}.{k} = {v}"
        for section in ("geometry", "fluid")
        for k, v in base["spec"].get(section, {}).items()
        if design["spec"].get(section, {}).get(k) != v
    ]
    st.caption(
        f"Dashed: the design pinned on the Size page ({base['spec'].get('name') or 'design'}"
        + (f"; where it differs: {', '.join(changed)}" if changed else "")
        + "), with the same model, effects "
        "and excitation."
    )
    return sim


def _download(sim: dict, damper, name: str, effects, values) -> None:
    """The simulated time history as a measurement file (CSV, units in the header): it reads back as a record."""
    fluid = damper.fluid
    column = {"A": "current", "V": "voltage"}.get(fluid.control_unit, "field")
    # every number in SI (EXPORT_UNITS), the unit in the header: the control in its SI unit too (V/m, A/m, A)
    columns = [
        ("time", "s", sim["time"]),
        ("displacement", "m", sim["displacement"]),
        ("velocity", "m/s", sim["velocity"]),
        ("force", "N", sim["force"]),
        (column, fluid.control_unit, np.asarray(sim["control"], float)),
    ]
    if sim["measured"] is not None:
        columns.append(("measured force", "N", sim["measured"]))
    model = name + ("".join(f" + {e}" for e in effects) if name == "physics" else "")
    parameters = ", ".join(f"{k} = {v:.6g} {sim['units'].get(k) or ''}".strip() for k, v in dict(values).items())
    comment = (
        f"simulated by erdesign: {model} on {sim['description']}; numbers in {EXPORT_UNITS} units\n"
        f"damper: {damper.name or 'design'}; parameters: {parameters or 'none'}"
    )
    stem = state.file_stem(damper.name or "design", f"-{name}-simulated")
    st.download_button(
        "Simulated time history (CSV)",
        csv_text(columns, comment=comment),
        file_name=f"{stem}.csv",
        mime="text/csv",
        key="sim.dl.history",
        icon=":material/download:",
        help="time, displacement, velocity, force and control with units in the header: it reads "
        "back as a measurement (Compare page).",
    )


if __name__ == "__main__":
    render()
