"""Pinned designs: several designs side by side with the current one, on the Size page (issue 26).

Each pinned design is a design of the app (:data:`erdesign.app.state.DESIGN`'s form).  The table puts the current
design and every pinned one in columns, the inputs that differ first (with readable labels), then every figure of
the design point; beside each pinned value its change against the current design in percent
(:func:`erdesign.report.builder.compare_designs`, the report's own comparison: nothing is recomputed).  The first
pinned design is *the baseline* the Simulate and Report pages compare with (:data:`erdesign.app.state.BASELINE`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import streamlit as st

from erdesign.app import state
from erdesign.errors import ErdesignError
from erdesign.report import plots
from erdesign.report.builder import compare_designs

__all__ = ["MAX_PINNED", "PINNED", "comparison_rows", "pin", "pinned_designs", "readable", "render", "unpin"]

#: Session-state key of the pinned designs (a list, the baseline first).
PINNED = "pinned"
#: At most this many designs are pinned (the table stays readable at 1280 px).
MAX_PINNED = 4
_THIS = "this design"


def readable(key: str, labels: Mapping[str, str]) -> str:
    """The label of an input key (``geometry.gap`` -> the Size page's ``gap h``; else ``Gap``, ``Coil: turns``).

    >>> readable("geometry.gap", {}), readable("coil.wire_diameter", {}), readable("geometry.gap", {"geometry.gap": "gap h"})
    ('Gap', 'Coil: wire diameter', 'gap h')
    """
    if key in labels:
        return labels[key]
    section, _, name = key.partition(".")
    text = (name or section).replace("_", " ")
    if section in ("geometry", "fluid") or not name:
        return text[:1].upper() + text[1:]
    return f"{section.capitalize()}: {text}"


def pinned_designs() -> list[dict]:
    """The pinned designs, the baseline first (a design pinned before this list existed is kept as the first)."""
    if PINNED not in st.session_state:
        base = st.session_state.get(state.BASELINE)
        st.session_state[PINNED] = [base] if base is not None else []
    return st.session_state[PINNED]


def _sync() -> None:
    designs = pinned_designs()
    if designs:
        st.session_state[state.BASELINE] = designs[0]
    else:
        st.session_state.pop(state.BASELINE, None)


def pin(design: dict) -> str:
    """Pin ``design``; the reason when it is not pinned (already pinned, or :data:`MAX_PINNED` reached), else ``""``."""
    designs = pinned_designs()
    if any(state.design_text(d) == state.design_text(design) for d in designs):
        return "this design is pinned already"
    if len(designs) >= MAX_PINNED:
        return f"{MAX_PINNED} designs are pinned already: unpin one first"
    designs.append(design)
    _sync()
    return ""


def unpin(index: int) -> None:
    """Unpin the design at ``index`` (0 is the baseline; the next one becomes the baseline)."""
    designs = pinned_designs()
    if 0 <= index < len(designs):
        del designs[index]
    _sync()


def comparison_rows(report, pinned: Sequence[tuple[str, object]], labels: Mapping[str, str]) -> list[dict]:
    """The rows of the table: the current design's report ``report`` and ``(name, report)`` of each pinned design.

    One row per input that differs between the current design and any pinned one (label, value as typed), then one
    per figure of the design point; columns ``quantity``, ``this design``, then for each pinned design its value
    and ``<name> vs this`` (its change against the current design, ``"+12.3 %"``).
    """
    diffs = [(name, compare_designs(other, report)) for name, other in pinned]
    given = {f"{r.section}.{r.key}": r.given for r in report.inputs}
    keys = list(dict.fromkeys(row["key"] for _, diff in diffs for row in diff["inputs"]))
    rows = []
    for key in keys:
        row = {"quantity": readable(key, labels), _THIS: given.get(key, "")}
        for name, diff in diffs:
            found = next((r for r in diff["inputs"] if r["key"] == key), None)
            row[name] = given.get(key, "") if found is None else found["this"]
            row[f"{name} vs this"] = "" if found is None else found["change"]
        rows.append(row)
    for i, point in enumerate(report.design_point):
        row = {"quantity": point.label, _THIS: point.value.text}
        for name, diff in diffs:
            found = next((r for r in diff["rows"] if r["key"] == point.key), None)
            row[name] = "" if found is None else found["this"].text
            row[f"{name} vs this"] = "" if found is None else found["change"]
        rows.append(row)
    return rows


def render(design: dict, report, labels: Mapping[str, str]) -> None:
    """The Size page's comparison: pin and unpin buttons, the table, and the force curves beside the baseline's."""
    st.subheader("Compare designs")
    designs = pinned_designs()
    cols = st.columns([2, 2, 3])
    if cols[0].button(
        "Pin this design",
        key="size.pin",
        icon=":material/push_pin:",
        help=f"Keep it for comparison (up to {MAX_PINNED}); the first pinned is the baseline the "
        "Simulate and Report pages compare with.",
    ):
        why = pin(design)
        if why:
            cols[2].info(why)
    if designs:
        names = [f"pinned {i + 1}" for i in range(len(designs))]
        which = cols[1].selectbox(
            "unpin",
            range(len(designs)),
            format_func=lambda i: names[i],
            key="size.unpin.which",
            label_visibility="collapsed",
        )
        if cols[1].button("Unpin", key="size.unpin", icon=":material/close:"):
            unpin(int(which))
            st.rerun()
    if not designs:
        cols[2].caption("Pin a design, then change the inputs: the new design is shown beside the pinned ones.")
        return
    reports = []
    for i, pinned in enumerate(list(designs)):
        try:
            reports.append((f"pinned {i + 1}", state.design_report(state.design_text(pinned), state.unit_system())))
        except ErdesignError as exc:  # a design from before a change of the library: drop it
            unpin(i)
            st.info(f"Pinned design {i + 1} can no longer be evaluated ({state.clean_message(str(exc))}); unpinned.")
            return
    st.caption(
        "; ".join(
            f"pinned {i + 1}: {d['spec'].get('name') or 'design'} at v = {d['velocity']}, E = {d['field']}"
            for i, d in enumerate(designs)
        )
        + ". 'vs this': the pinned value's change against this design."
    )
    st.table(comparison_rows(report, reports, labels))
    st.plotly_chart(
        plots.force_velocity_figure(report.sweep, pinned=[(label, r.sweep) for label, r in reports]),
        key="size.fig.compare",
        config=state.chart_config("size.fig.compare"),
    )
    styles = ("dashed", "dotted", "dash-dotted", "long-dashed")
    st.caption("; ".join(f"{styles[i % len(styles)]}: {label}" for i, (label, _) in enumerate(reports)) + ".")
