"""Report page: download the engineering report (:mod:`erdesign.report`) of the current design and diagnosis.

The report is the one ``erdesign report`` writes: inputs, design table, equations, checks and figures, plus the
comparison with the measurement and the error history when a diagnosis was run on the Compare page.
"""

from __future__ import annotations

import re

import numpy as np
import streamlit as st

from erdesign.app import state
from erdesign.errors import ErdesignError
from erdesign.units import to_si

__all__ = ["render", "file_stem"]


def file_stem(name: str) -> str:
    """A file name from a design name (``"makris-1996"`` -> ``"makris-1996-report"``).

    >>> file_stem("my damper / v2")
    'my-damper-v2-report'
    """
    stem = re.sub(r"[^A-Za-z0-9._-]+", "-", name).strip("-") or "erdesign"
    return f"{stem}-report"


def render() -> None:
    """Draw the Report page."""
    st.title("Report")
    spec = state.current_spec()
    text = state.spec_text(spec)
    damper = state.damper_or_error(text)
    if damper is None:
        return
    keep = st.session_state
    v_top_text = keep.get("_keep.size.v_top") or "50 mm/s"
    field_text = keep.get("_keep.size.field") or f"{damper.fluid.reference_field} {damper.fluid.control_unit}"
    levels = int(keep.get("_keep.size.levels") or 4)
    try:
        v_top = float(to_si(v_top_text, "m/s", "top velocity"))
        E = abs(float(to_si(field_text, damper.fluid.control_unit, "design field")))
    except ErdesignError as exc:
        st.error(f"The velocity or field of the Size page is not valid: {exc}")
        return
    fields = tuple(float(x) for x in np.linspace(0.0, E, levels)[1:]) if E else ()
    comparison = keep.get("report.comparison")
    history = keep.get("report.history") or ()
    include = False
    if comparison is not None:
        include = st.checkbox(f"include the comparison with {comparison[0]} and the error history", value=True,
                              key="rep.include")
    st.markdown(f"Design **{damper.name or 'design'}** ({damper.geometry.configuration}); velocities 0 to "
                f"{v_top_text}; {levels} field levels up to {field_text}."
                + ("" if comparison is not None else " Run a diagnosis on the Compare page to add a measurement."))
    fmt = state.widget(st.radio, "format", "rep.format", "html", options=["html", "md"], horizontal=True,
                       format_func={"html": "HTML (interactive plots)", "md": "Markdown"}.get)
    try:
        with st.spinner("Writing the report ..."):
            body = state.render_report(text, v_top, fields, comparison if include else None,
                                       history if include else (), fmt)
    except ErdesignError as exc:
        st.error(f"The report could not be built: {exc}")
        return
    name = f"{file_stem(damper.name or 'erdesign')}.{fmt}"
    st.download_button(f"Download {name}", body, file_name=name, type="primary", key="rep.download",
                       mime="text/html" if fmt == "html" else "text/markdown")
    st.caption(f"{len(body) / 1e3:.0f} kB")
    if fmt == "md":
        with st.expander("preview"):
            st.markdown(body)


if __name__ == "__main__":
    render()
