"""The app's entry script: page configuration and the navigation over the pages.

Run it with ``streamlit run app.py`` from a clone (the root ``app.py`` calls :func:`main`) or ``erdesign app``
(which runs this file).  Each page is a file beside this one, so that Streamlit's page URLs and its test
harness (``AppTest.switch_page("size.py")``) address them by file.
"""

from __future__ import annotations

import logging
from pathlib import Path

import streamlit as st

from erdesign.app import state
from erdesign.report.formatting import UNIT_SYSTEMS, use_unit_system

__all__ = ["main", "PAGES"]

_HERE = Path(__file__).resolve().parent

#: (file, title, icon, URL path) of each page, in the order of the navigation; the first opens by default.
PAGES = (
    ("size.py", "Size", ":material/straighten:", "size"),
    ("design.py", "Design", ":material/architecture:", "design"),
    ("simulate.py", "Simulate", ":material/show_chart:", "simulate"),
    ("compare.py", "Compare and diagnose", ":material/troubleshoot:", "compare"),
    ("report.py", "Report", ":material/description:", "report"),
    ("characterize.py", "Characterize", ":material/analytics:", "characterize"),
    ("vehicle.py", "Vehicle", ":material/directions_car:", "vehicle"),
)


#: Metrics hold their number whole at 1280 px (three to a row in two thirds of the page): a smaller value font,
#: and a label that wraps instead of being cut ("120.3 k..." was the damping constant).
_STYLE = """<style>
[data-testid="stMetricValue"] { font-size: 1.6rem; }
[data-testid="stMetricValue"] > div { overflow: visible; text-overflow: clip; white-space: nowrap; }
[data-testid="stMetricLabel"] p { white-space: normal; }
</style>"""


def main() -> None:
    """Configure the page and run the page the user chose."""
    st.set_page_config(page_title="erdesign", page_icon=":material/tune:", layout="wide")
    pages = [
        st.Page(_HERE / file, title=title, icon=icon, url_path=url, default=(i == 0))
        for i, (file, title, icon, url) in enumerate(PAGES)
    ]
    page = st.navigation(pages)
    st.html(_STYLE)
    with st.sidebar:
        system = state.widget(
            st.radio,
            "units of displayed numbers",
            state.UNITS,
            "SI",
            options=list(UNIT_SYSTEMS),
            help="Numbers shown and reported in this unit system; controls stay in the fluid's "
            "own unit (kV/mm, kA/m, A, V). Inputs take any unit you type.",
        )
        state.widget(
            st.radio,
            "figures save as",
            state.IMAGE_FORMAT,
            "png",
            options=["png", "svg"],
            horizontal=True,
            format_func=str.upper,
            help="The camera button at the top right of every figure saves it in this format (drawn by your browser).",
        )
        st.caption(
            "erdesign: design and diagnose ER and MR dampers with annular ducts. The design you enter on "
            "the Size page is used by every page."
        )
    with use_unit_system(system):
        try:
            page.run()
        except Exception as exc:  # a bug, not bad input: one line in the page, never a traceback or a server path
            logging.getLogger("erdesign.app").exception("internal error on page %s", page.title)
            st.error(
                f"Internal error: {type(exc).__name__}: {state.clean_message(str(exc))} (please report it "
                "with the steps that led here)."
            )


if __name__ == "__main__":
    main()
