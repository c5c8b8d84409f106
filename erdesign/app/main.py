"""The app's entry script: page configuration and the navigation over the four pages.

Run it with ``streamlit run app.py`` from a clone (the root ``app.py`` calls :func:`main`) or ``erdesign app``
(which runs this file).  Each page is a file beside this one, so that Streamlit's page URLs and its test
harness (``AppTest.switch_page("size.py")``) address them by file.
"""

from __future__ import annotations

from pathlib import Path

import streamlit as st

__all__ = ["main", "PAGES"]

_HERE = Path(__file__).resolve().parent

#: (file, title, icon, URL path) of each page, in the order of the navigation; the first opens by default.
PAGES = (
    ("size.py", "Size", ":material/straighten:", "size"),
    ("simulate.py", "Simulate", ":material/show_chart:", "simulate"),
    ("compare.py", "Compare and diagnose", ":material/troubleshoot:", "compare"),
    ("report.py", "Report", ":material/description:", "report"),
)


def main() -> None:
    """Configure the page and run the page the user chose."""
    st.set_page_config(page_title="erdesign", page_icon=":material/tune:", layout="wide")
    pages = [st.Page(_HERE / file, title=title, icon=icon, url_path=url, default=(i == 0))
             for i, (file, title, icon, url) in enumerate(PAGES)]
    page = st.navigation(pages)
    with st.sidebar:
        st.caption("erdesign: design and diagnose ER and MR dampers with annular ducts. The design you enter on "
                   "the Size page is used by every page.")
    page.run()


if __name__ == "__main__":
    main()
