"""Design page: requirements with units -> the design search -> ranked designs, the Pareto front or the conflicts,
and "open this design", which makes a found design the current damper of every page.

The requirements start from a bundled requirements file (``erdesign/examples/requirements/``): each of its values
is an input, lengths, forces and velocities shown in the chosen unit system.  The page builds the file's content
back from the inputs and hands it to :func:`erdesign.design.requirements_from_dict` (its checks name the key); the
search is :func:`erdesign.design.design`, the conflicts are the ones it explains, and the opened design is
:meth:`erdesign.design.DesignResult.damper_spec` - the damper file ``erdesign design --write-damper`` writes.  No
physics here.
"""

from __future__ import annotations

import copy
import re
from importlib import resources
from typing import Any

import numpy as np
import streamlit as st

from erdesign.app import state
from erdesign.damper.files import read_toml
from erdesign.design import design as run_design
from erdesign.design import example_requirements_names, requirements_from_dict
from erdesign.design.figures import FIGURES
from erdesign.design.result import figure_value
from erdesign.errors import ErdesignError
from erdesign.report.formatting import kind_of, pick_unit, round_significant
from erdesign.units import Q_, plain_number, to_si

__all__ = ["DEFAULT_REQUIREMENTS", "render", "requirement_inputs", "requirements_data"]

#: The requirements the page opens on.
DEFAULT_REQUIREMENTS = "makris_requirements"
#: Candidates sampled by default on the page (the command line's default, 2**17, takes seconds more).
DEFAULT_SAMPLES = 8192
_PREFIX = "designer."
_RESULT = _PREFIX + "result"
_OPENED = _PREFIX + "opened"
#: Search settings that have inputs of their own on the page (not among the requirement values).
_OWN_INPUTS = (("design", "search", "samples"), ("design", "search", "designs"))
_SECTIONS = {
    "fluid": "Fluid",
    "point": "Design point",
    "limits": "Limits",
    "bounds": "Bounds of the geometry",
    "coil": "Coil",
    "envelope": "Envelope",
    "search": "Search",
    "": "Damper",
}


# ------------------------------------------------------------------------------------------------ requirements
def _example_data(name: str) -> dict:
    with resources.as_file(resources.files("erdesign.examples") / "requirements" / f"{name}.toml") as path:
        return read_toml(path)


def _leaves(data: Any, path: tuple = ()) -> list[tuple[tuple, Any]]:
    """The scalar values of a parsed TOML file with their paths (list items by index)."""
    if isinstance(data, dict):
        return [leaf for key, value in data.items() for leaf in _leaves(value, (*path, key))]
    if isinstance(data, list):
        return [leaf for i, value in enumerate(data) for leaf in _leaves(value, (*path, i))]
    return [(path, data)]


def _dotted(path: tuple) -> str:
    return ".".join(f"{p}" for p in path)


def _where(path: tuple) -> str:
    """The dotted key of a value as the library's messages name it, items counted from 1 as users count:
    ``design.point[1].min_force``, ``design.bounds.ducts[2]`` (the high end of the range)."""
    parts: list[str] = []
    for p in path:
        if isinstance(p, int) and parts:
            parts[-1] += f"[{p + 1}]"
        else:
            parts.append(f"{p}")
    return ".".join(parts)


def _section(path: tuple) -> str:
    """The group a value is shown in: ``Design point 1``, ``Limits``, ``Bounds of the geometry``, ..."""
    if path[0] == "fluid":
        return "Fluid"
    if len(path) < 3:
        return _SECTIONS[""]
    name = _SECTIONS.get(path[1], path[1])
    return f"{name} {path[2] + 1}" if path[1] == "point" else name


def _label(path: tuple) -> str:
    """``design.bounds.gap[0]`` -> ``gap (low)``: the key, and low/high for a range."""
    if isinstance(path[-1], int) and len(path) > 2 and path[-3] != "design":
        return f"{path[-2]} ({'low' if path[-1] == 0 else 'high'})".replace("_", " ")
    return f"{path[-1]}".replace("_", " ")


def _in_system(value: Any) -> str:
    """A value as its input shows it: lengths, forces, velocities ... in the chosen unit system (six figures, so
    that a bound is not moved by rounding), controls and words as written."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if not isinstance(value, str):
        return repr(value)
    try:
        q = Q_(value)
    except Exception:  # noqa: BLE001  (a word such as a material name or an objective)
        return value
    kind = kind_of(f"{q.units}") if hasattr(q, "units") and not q.dimensionless else None
    if kind is None:
        return value
    unit = pick_unit(abs(q), kind)
    return f"{round_significant(float(q.to(unit).magnitude), 6)} {unit}"


def requirement_inputs(data: dict) -> list[tuple[tuple, Any, str]]:
    """``(path, value as written, widget key)`` of each value of a requirements file that has an input."""
    return [(path, value, f"{_PREFIX}req.{_dotted(path)}") for path, value in _leaves(data) if path not in _OWN_INPUTS]


def requirements_data(data: dict, texts: dict[str, str]) -> dict:
    """The requirements file's content with each input's text (by widget key) put back in the type the file had
    (a number stays a number, true/false a boolean); an :class:`ErdesignError` naming the key otherwise."""
    out = copy.deepcopy(data)
    for path, value, key in requirement_inputs(data):
        text = texts.get(key, _in_system(value)).strip()
        where = _where(path)
        try:
            if isinstance(value, bool):
                if text.lower() not in ("true", "false"):
                    raise ValueError
                new: Any = text.lower() == "true"
            elif isinstance(value, int):  # ASCII digits only: int() reads '\u0663' (ARABIC-INDIC THREE) and '1_0'
                if not re.fullmatch(r"\s*[-+]?\d+\s*", text, re.ASCII):
                    raise ValueError
                new = int(text)
            elif isinstance(value, float):  # the one reader of plain numbers (float() reads other scripts' digits)
                new = plain_number(text)
                if new is None:
                    raise ValueError
            else:
                new = text
        except ValueError:
            kind = (
                "true or false" if isinstance(value, bool) else "an integer" if isinstance(value, int) else "a number"
            )
            raise ErdesignError(f"{where}: expected {kind}, got {text!r}") from None
        target = out
        for p in path[:-1]:
            target = target[p]
        target[path[-1]] = new
    return out


def _on_example() -> None:
    state.forget(_PREFIX + "req.")
    st.session_state.pop(_RESULT, None)
    st.session_state.pop(_OPENED, None)


def _follow_unit_system(data: dict) -> None:
    """Inputs drawn in another unit system are shown again in the chosen one (edited values too: a quantity is
    converted, a word left alone)."""
    system = state.unit_system()
    if st.session_state.get(_PREFIX + "system", system) != system:
        for _, _, key in requirement_inputs(data):
            text = state.widget_value(key)
            if isinstance(text, str):
                state.set_widget(key, _in_system(text))
    st.session_state[_PREFIX + "system"] = system


def _inputs(data: dict) -> dict[str, str]:
    _follow_unit_system(data)
    groups: dict[str, list] = {}
    for item in requirement_inputs(data):
        groups.setdefault(_section(item[0]), []).append(item)
    texts = {}
    for title, items in groups.items():
        with st.expander(title, expanded=title.startswith(("Design point", "Limits"))):
            cols = st.columns(3)
            for i, (path, value, key) in enumerate(items):
                with cols[i % 3]:
                    texts[key] = state.widget(
                        st.text_input,
                        _label(path),
                        key,
                        _in_system(value),
                        help=f"{_where(path)} of the requirements file (docs/design.md)",
                    )
    return texts


# ------------------------------------------------------------------------------------------------ results
#: Column titles of the figures (FIGURES describes them in full).
_SHORT = {
    "force": "force F",
    "controllable_force": "controllable force",
    "zero_field_force": "zero-field force F0",
    "dynamic_range": "dynamic range F/F0",
    "fluid_volume": "active fluid volume",
    "total_fluid_volume": "fluid volume",
    "outer_diameter": "outer diameter",
    "length": "body length",
    "coil_power": "coil power",
    "time_constant": "coil time constant",
}


def _column(values: list[float | None], si_unit: str) -> tuple[list[str], str]:
    """Values of one SI unit shown in one display unit of the chosen system: (texts, unit)."""
    finite = [abs(v) for v in values if v is not None and np.isfinite(v)]
    kind = kind_of(si_unit) if si_unit else None
    unit = pick_unit(Q_(max(finite), si_unit), kind) if kind and finite else si_unit
    texts = [
        "-" if v is None else round_significant(float(Q_(v, si_unit).to(unit).magnitude if unit else v)) for v in values
    ]
    return texts, f"{Q_(1.0, unit).units:~P}" if unit else ""


def _table(records: list[dict], req) -> list[dict]:
    """One row per design: geometry, figures at point 1 and the limits it sits on, in the chosen unit system."""
    columns: dict[str, tuple[list[str], str]] = {}
    geometry_keys = [
        k
        for k in ("gap", "duct_length", "duct_mean_diameter", "piston_diameter", "rod_diameter")
        if k in records[0]["geometry"]
    ]
    for key in geometry_keys:
        columns[key.replace("_", " ")] = _column([to_si(r["geometry"][key], "m", key) for r in records], "m")
    figures = ["force", "zero_field_force", "dynamic_range", "fluid_volume", "outer_diameter", "length"]
    if req.coil is not None:
        figures += ["coil_power", "time_constant"]
    for name in figures:
        columns[_SHORT[name]] = _column([figure_value(r, name) for r in records], FIGURES[name].unit)
    rows = []
    for i, rec in enumerate(records):
        row = {"rank": str(rec.get("rank", "nearest"))}
        for title, (texts, unit) in columns.items():
            row[f"{title} [{unit}]" if unit else title] = texts[i]
        if "ducts" in rec["geometry"]:
            row["ducts"] = str(rec["geometry"]["ducts"])
        if "coil" in rec:
            row["turns"] = str(rec["coil"]["turns"])
        rows.append(row)
    return rows


def _limits(records: list[dict]) -> str:
    """Below the table (a column would not fit): the limits each design sits on, or the nearest one's shortfalls."""
    lines = []
    for rec in records:
        if "violations" in rec:
            short = "; ".join(f"{k} by {100 * v:.3g} %" for k, v in rec["violations"].items() if v)
            lines.append(f"- nearest design: short of {short}")
        else:
            lines.append(f"- {rec['rank']}: {', '.join(rec['active_constraints']) or 'inside every limit'}")
    return "\n".join(lines)


def _pareto_figure(result):
    """The Pareto front of the search's figures (first two on the axes, a third as colour) and the ranked designs."""
    import plotly.graph_objects as go

    names = list(result.requirements.search.pareto)
    front, ranked = result.pareto, result.designs

    def axis(name: str, records: list[dict]) -> tuple[list[float], str]:
        si = [figure_value(r, name) for r in records]
        texts, unit = _column(si, FIGURES[name].unit)
        return [float(t) if t != "-" else None for t in texts], unit

    x_name, y_name = (names[1], names[0]) if len(names) > 1 else (names[0], names[0])
    title = {n: _SHORT[n] for n in names}
    (fx, ux), (fy, uy) = axis(x_name, front + ranked), axis(y_name, front + ranked)
    n = len(front)
    marker: dict[str, Any] = {"size": 7, "opacity": 0.75}
    if len(names) > 2:
        colour, uc = axis(names[2], front)
        marker.update(
            color=colour,
            colorscale="Viridis",
            showscale=True,
            colorbar={"title": {"text": f"{title[names[2]]} [{uc}]" if uc else title[names[2]]}},
        )
    fig = go.Figure()
    fig.add_trace(go.Scatter(x=fx[:n], y=fy[:n], mode="markers", marker=marker, name="Pareto front (feasible)"))
    fig.add_trace(
        go.Scatter(
            x=fx[n:],
            y=fy[n:],
            mode="markers+text",
            text=[str(r["rank"]) for r in ranked],
            textposition="top center",
            name="ranked designs",
            marker={"symbol": "diamond-open", "size": 12, "color": "#d62728", "line": {"width": 2}},
        )
    )
    fig.update_layout(
        xaxis_title=f"{title[x_name]} [{ux}]" if ux else title[x_name],
        yaxis_title=f"{title[y_name]} [{uy}]" if uy else title[y_name],
        legend={"orientation": "h", "yanchor": "bottom", "y": 1.02, "x": 0},
        margin={"t": 40},
        height=480,
    )
    return fig


def _open(result, rank: int, point: dict) -> None:
    """Make the design of rank ``rank`` the current damper at the requirements' first point."""
    spec = result.damper_spec(rank)
    design = {**state.default_design(spec), **point}
    if to_si(design["v_top"], "m/s", "top velocity") < to_si(point["velocity"], "m/s", "velocity"):
        design["v_top"] = point["velocity"]
    state.set_design(design)
    state.forget("size.")  # the Size page reloads its inputs from the current design
    state.forget("sim.field")  # Simulate's control starts at the new design's (its unit may differ)
    st.session_state[_OPENED] = (rank, spec["name"])


def _results(result, data: dict) -> None:
    req = result.requirements
    st.caption(f"{result.evaluated} candidates evaluated, {result.feasible_count} feasible; {result.ranking_note()}.")
    if not result.feasible:
        st.error(f"No design meets every requirement: {len(result.conflicts)} conflict(s).", icon="🚫")
        st.markdown("\n".join(f"- {c}" for c in result.conflicts))
        if result.nearest is not None:
            st.caption("The design nearest to meeting them (figures at design point 1):")
            st.table(_table([result.nearest], req))
            st.markdown(_limits([result.nearest]))
        return
    st.subheader("Ranked designs")
    p = data["design"]["point"][0]
    st.caption(f"Figures at design point 1 (v = {p['velocity']}, control {p['field']}), best first.")
    st.table(_table(result.designs, req))  # a table: every column in view, no inner scrolling
    st.caption("The limits each design sits on (within the active tolerance):")
    st.markdown(_limits(result.designs))
    cols = st.columns([2, 2, 3])
    rank = cols[0].selectbox(
        "design to open", [r["rank"] for r in result.designs], key=_PREFIX + "rank", format_func=lambda r: f"design {r}"
    )
    if cols[1].button(
        "Open this design",
        key=_PREFIX + "open",
        icon=":material/open_in_new:",
        help="Makes it the current damper: the Size, Simulate and Report pages show it.",
    ):
        _open(result, rank, {"velocity": str(p["velocity"]), "field": str(p["field"])})
    if _OPENED in st.session_state:
        opened, name = st.session_state[_OPENED]
        cols[2].success(f"Design {opened} ({name}) is the current damper: the Size, Simulate and Report pages show it.")
    st.subheader("Trade-offs")
    st.caption(
        f"Pareto front of {', '.join(_SHORT[n] for n in req.search.pareto)}: {len(result.pareto)} "
        "feasible sampled designs that no other beats on all of them; the ranked designs are marked."
    )
    st.plotly_chart(_pareto_figure(result), key=_PREFIX + "fig.pareto", config=state.chart_config("design.pareto"))


def render() -> None:
    """Draw the Design page."""
    st.title("Design from requirements")
    st.caption(
        "What the damper must do, the room it has and the parts you can make; the search finds the "
        "geometries that meet them all, ranked, or says which requirements conflict."
    )
    names = example_requirements_names()
    top = st.columns([2, 1, 1])
    name = state.widget(
        top[0].selectbox,
        "start from the requirements of",
        _PREFIX + "example",
        DEFAULT_REQUIREMENTS,
        options=names,
        on_change=_on_example,
    )
    data = _example_data(name)
    search = data.get("design", {}).get("search", {})
    samples = state.widget(
        top[1].number_input,
        "candidates to sample",
        _PREFIX + "samples",
        int(min(search.get("samples", DEFAULT_SAMPLES), DEFAULT_SAMPLES)),
        min_value=256,
        max_value=2**20,
        step=1024,
    )
    keep = state.widget(
        top[2].number_input,
        "designs to keep",
        _PREFIX + "designs",
        int(search.get("designs", 5)),
        min_value=1,
        max_value=50,
    )
    texts = _inputs(data)
    try:
        values = requirements_data(data, texts)
        values.setdefault("design", {}).setdefault("search", {}).update(samples=int(samples), designs=int(keep))
        # the requirements' plausibility warnings ("min_force: 1e+12 N is beyond the force of any damper") were
        # printed to the server's log, not shown
        req, warned = state.caught(lambda: requirements_from_dict(values, source="requirements"))
    except ErdesignError as exc:
        st.error(state.clean_message(str(exc)), icon="🚫")
        return
    for message in warned:
        st.warning(state.clean_message(message), icon="⚠️")
    if st.button("Search", key=_PREFIX + "search", type="primary", icon=":material/search:"):
        bar = st.progress(0.0, text="sampling the design space")

        def progress(evaluated: int, total: int, feasible: int) -> None:
            bar.progress(
                min(evaluated / total, 1.0), text=f"{evaluated} of {total} candidates evaluated, {feasible} feasible"
            )

        try:
            result, warned = state.caught(lambda: run_design(req, progress=progress))
        except ErdesignError as exc:
            st.error(state.clean_message(str(exc)), icon="🚫")
            return
        finally:
            bar.empty()
        for message in warned:
            st.warning(message, icon="⚠️")
        st.session_state[_RESULT] = (result, values)
        st.session_state.pop(_OPENED, None)
    if _RESULT in st.session_state:
        result, used = st.session_state[_RESULT]
        if used != values:
            st.info("The requirements changed since this search: search again to update the designs.")
        _results(result, used)


if __name__ == "__main__":
    render()
