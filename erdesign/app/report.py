"""Report page: download the engineering report (:mod:`erdesign.report`) of the current design and diagnosis.

The report is built from exactly the design the Size page shows (:func:`erdesign.app.state.design_report`: the same
design point, inputs as typed and validity checks), plus the comparison with the measurement and the error history
when a diagnosis was run on the Compare page.
"""

from __future__ import annotations

import streamlit as st

from erdesign.app import state
from erdesign.errors import ErdesignError
from erdesign.report.export import damper_toml

__all__ = ["render", "file_stem"]


def file_stem(name: str) -> str:
    """A file name from a design name (``"makris-1996"`` -> ``"makris-1996-report"``).

    >>> file_stem("my damper / v2")
    'my-damper-v2-report'
    """
    return state.file_stem(name, "-report")


def render() -> None:
    """Draw the Report page."""
    st.title("Report")
    design = state.current_design()
    text = state.design_text(design)
    keep = st.session_state
    comparison = keep.get("report.comparison")
    history = keep.get("report.history") or ()
    include = False
    if comparison is not None:
        include = st.checkbox(
            f"include the comparison with {comparison[0]} and the error history", value=True, key="rep.include"
        )
    base = state.pinned_baseline(design)
    baseline = None
    if base is not None and st.checkbox(
        f"compare with the pinned baseline design {base['spec'].get('name') or ''} "
        f"(v = {base['velocity']}, E = {base['field']})",
        value=True,
        key="rep.baseline",
    ):
        baseline = state.design_text(base)
    fmt = state.widget(
        st.radio,
        "format",
        "rep.format",
        "html",
        options=["html", "md"],
        horizontal=True,
        format_func={"html": "HTML (interactive plots)", "md": "Markdown"}.get,
    )
    system = state.unit_system()
    try:
        with st.spinner("Writing the report ..."):
            report = state.design_report(
                text, system, comparison if include else None, history if include else (), baseline
            )
            body = state.render_report(
                text,
                system,
                comparison if include else None,
                history if include else (),
                fmt,
                baseline,
                state.image_format(),
            )
    except ErdesignError as exc:
        st.error(f"The report could not be built: {state.clean_message(str(exc))}")
        return
    if report.baseline is not None:
        st.caption(
            f"With the baseline design {report.baseline['name']}: a section beside this design's design "
            "point and the figure of both designs' force against velocity."
        )
    name = design["spec"].get("name") or "design"
    point = f"{report.setting('velocity_design').value.text} and {report.setting('field_design').value.text}"
    st.markdown(
        f"Design **{name}** ({report.configuration}) at the design point **{point}** (from the Size page); "
        f"curves from {report.setting('velocity_min').value.text} to "
        f"{report.setting('velocity_max').value.text} at {len(report.sweep.field)} controls; "
        f"numbers in {system} units; validity checks: {len(report.checks) - report.warnings} pass or info, "
        f"{report.warnings} warn."
        + ("" if comparison is not None else " Run a diagnosis on the Compare page to add a measurement.")
    )
    rows = [{"quantity": r.label, "value": r.value.text} for r in report.design_point]
    st.table(rows)  # a table, not a dataframe: all rows in view, no scrolling inside the page
    file_name = f"{file_stem(name)}.{fmt}"
    cols = st.columns([3, 2, 2])
    cols[0].download_button(
        f"Download {file_name}",
        body,
        file_name=file_name,
        type="primary",
        key="rep.download",
        mime="text/html" if fmt == "html" else "text/markdown",
        icon=":material/download:",
    )
    cols[1].download_button(
        "Damper file (TOML)",
        damper_toml(design["spec"], comment=_comment(design)),
        file_name=f"{state.file_stem(name)}.toml",
        mime="application/toml",
        key="rep.toml",
        icon=":material/download:",
    )
    cols[2].caption(
        f"{len(body) / 1e3:.0f} kB; figures: each plot's camera button in the app and in the HTML "
        f"report saves it as {state.image_format().upper()} (sidebar)."
    )
    _images(text, system, comparison if include else None, history if include else (), baseline, name)
    if fmt == "md":
        with st.expander("preview"):
            st.markdown(body)


def _images(text: str, system: str, comparison, history, baseline, name: str) -> None:
    """Static images of every figure of the report (kaleido, with a browser already installed), on request."""
    fmt = state.image_format()
    key = ("rep.images", text, system, comparison is not None, history, baseline, fmt)
    if st.button(
        f"Make the report's figures as {fmt.upper()} files",
        key="rep.make_images",
        icon=":material/image:",
        help="Static images drawn on this server by kaleido in a headless "
        'Chrome or Chromium (optional: pip install "erdesign[docs]").',
    ):
        try:
            with st.spinner("Drawing the figures ..."):
                st.session_state["rep.images"] = (
                    key,
                    state.report_images(text, system, comparison, history, baseline, fmt),
                )
        except ErdesignError as exc:
            # the fallback needs nothing more: each figure as an interactive page whose camera button saves it
            st.session_state["rep.images"] = (key, None)
            st.info(
                state.clean_message(str(exc)) + ". Offered instead: each figure as an interactive HTML page "
                f"(plotly's own script beside them, no download); its camera button saves it as {fmt.upper()}."
            )
    made = st.session_state.get("rep.images")
    if made is not None and made[0] == key and made[1] is not None:
        st.download_button(
            f"Figures ({fmt.upper()}, zip)",
            made[1],
            file_name=f"{state.file_stem(name)}-figures.zip",
            mime="application/zip",
            key="rep.dl.images",
            icon=":material/download:",
        )
    elif made is not None and made[0] == key:
        st.download_button(
            "Figures (HTML pages, zip)",
            state.report_pages(text, system, comparison, history, baseline, fmt),
            file_name=f"{state.file_stem(name)}-figures-html.zip",
            mime="application/zip",
            key="rep.dl.pages",
            icon=":material/download:",
        )


def _comment(design: dict) -> str:
    from erdesign.app.size import design_comment

    return design_comment(design)


if __name__ == "__main__":
    render()
