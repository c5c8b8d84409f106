"""Characterize page: the method of Vivas-López et al. (n.d.) on a damper's records (docs/characterize.md).

Records are uploaded measurement CSVs (the experiments E1-E5 of ``erdesign doe`` played on a rig) or the example
records of the truth rig; the work is :func:`erdesign.characterization.method.characterize`, the figures
:mod:`erdesign.report.characterization`.  The page holds no physics.
"""

from __future__ import annotations

import pandas as pd
import streamlit as st

from erdesign.app import state
from erdesign.errors import ErdesignError

__all__ = ["SOURCES", "render"]

SOURCES = {
    "example": "example: truth-rig records E2-E5 (friction, gas spring, single-ended rod)",
    "upload": "upload measurement CSVs (one per experiment)",
}


@st.cache_data(show_spinner=False, max_entries=4)
def _example() -> tuple[tuple[str, bytes], ...]:
    """The example records as CSV bytes (made once per session by the truth rig)."""
    import tempfile
    from pathlib import Path

    from erdesign.characterization.method import demo_records
    from erdesign.data.measurement import write_measurement

    out = []
    with tempfile.TemporaryDirectory() as folder:
        for r in demo_records():
            path = Path(folder) / f"{r.name}.csv"
            write_measurement(path, r, units={"current": "A"})
            out.append((path.name, path.read_bytes()))
    return tuple(out)


@st.cache_data(show_spinner=False, max_entries=4)
def _characterize(files: tuple[tuple[str, bytes], ...], threshold: float):
    from erdesign.characterization.method import characterize

    records = [state.read_record(data, name) for name, data in files]
    return characterize(records, threshold=threshold)


def render() -> None:
    st.title("Characterize")
    st.caption(
        "Vivas-López et al.: the characteristics of the records (Table 2), the customized model they call "
        "for (eqs 2-6), its cross-validation (Table 4) against the Eyring-plastic model (eq 8) and the "
        "2D densities of Fig 5. Test plans: `erdesign doe --programme E1 ... E5`."
    )
    source = state.widget(
        st.radio, "records", "chr.source", "example", options=list(SOURCES), format_func=SOURCES.get, horizontal=True
    )
    if source == "upload":
        uploads = st.file_uploader(
            "measurement CSVs (time, displacement, force, control)",
            type=["csv"],
            accept_multiple_files=True,
            key="chr.upload",
        )
        if not uploads:
            st.info("Upload the records of one damper, e.g. E2-E5 (two at least for the cross-validation).")
            return
        files = tuple((u.name, u.getvalue()) for u in uploads)
    else:
        files = _example()
    threshold = state.widget(
        st.number_input,
        "threshold (ESR rise)",
        "chr.threshold",
        0.001,
        min_value=0.0,
        max_value=0.5,
        step=0.0005,
        format="%.4f",
        help="A characteristic is found when leaving its term out raises the ESR of its "
        "diagram's fit by more than this fraction of the force variance.",
    )
    try:
        with st.spinner("identifying the customized and the Eyring-plastic model on every record ..."):
            result = _characterize(files, float(threshold))
    except ErdesignError as exc:
        st.error(state.clean_message(str(exc)))
        return
    doc = result.to_dict()
    st.subheader("Characteristics")
    st.dataframe(
        pd.DataFrame(
            [
                {
                    "characteristic": c["title"],
                    "diagram": c["diagram"],
                    "model term": c["model_term"],
                    "found": c["found"],
                    "evidence": c["evidence"],
                }
                for c in doc["characteristics"]
            ]
        ),
        hide_index=True,
        key="chr.findings",
    )
    m = doc["model"]
    st.subheader("Customized model")
    st.write(
        f"Terms: {', '.join(m['terms'])}; {'asymmetric' if m['asymmetric'] else 'symmetric'} coefficients; "
        f"manipulation V = u^{m['control_exponent']:.3g}; "
        f"{m['parameter_count']} parameters, identified on {m['identified_on']} (ESR {m['esr']:.4f})."
    )
    st.dataframe(
        pd.DataFrame({"parameter": list(m["parameters"]), "value": list(m["parameters"].values())}),
        hide_index=True,
        key="chr.parameters",
    )
    cv = doc["cross_validation"]
    columns = st.columns(2)
    for col, (key, title) in zip(columns, (("customized", "customized"), ("eyring_plastic", "Eyring-plastic"))):
        table = pd.DataFrame(cv[key]["table"], index=cv["records"], columns=cv["records"])
        table.loc["average"] = cv[key]["average"]
        col.markdown(f"**Cross-validation, {title}** (column: identified on; row: validated on)")
        col.dataframe(table.style.format("{:.4f}"), key=f"chr.cv.{key}")
    c = doc["comparison"]
    st.metric(
        "cross-validation mean ESR, customized",
        f"{c['cross_validation']['customized_mean_esr']:.4f}",
        delta=f"{-100 * c['cross_validation']['esr_reduction']:.1f} % against Eyring-plastic",
        delta_color="inverse",
    )
    from erdesign.report.characterization import (
        density_figure,
        diagram_figure,
        render_characterization,
    )

    st.download_button(
        "Download the page (HTML: tables, diagrams, densities)",
        render_characterization(result),
        file_name="characterization.html",
        mime="text/html",
        key="chr.download",
    )

    names = [r.name for r in result.records]
    k = names.index(
        state.widget(st.selectbox, "record shown", "chr.record", names[result.identified_on], options=names)
    )
    st.plotly_chart(diagram_figure(result, k), key="chr.fig.diagrams", config=state.chart_config("chr.fig.diagrams"))
    st.plotly_chart(density_figure(result, k), key="chr.fig.density", config=state.chart_config("chr.fig.density"))


if __name__ == "__main__":
    render()
