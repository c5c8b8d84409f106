"""The Streamlit design app: ``streamlit run app.py`` (from a clone) or ``erdesign app`` (installed).

One module per page (:mod:`~erdesign.app.size`, :mod:`~erdesign.app.simulate`, :mod:`~erdesign.app.compare`,
:mod:`~erdesign.app.report`, :mod:`~erdesign.app.design`), :mod:`~erdesign.app.state` for session state and the
cached calls into the library, :mod:`~erdesign.app.pinned` for the designs pinned for comparison,
:mod:`~erdesign.app.figures` for the few plotly figures :mod:`erdesign.report.plots` does not have, and
:mod:`~erdesign.app.main` for the navigation.  The app holds no physics: it calls the library and shows its results
(docs/app.md).
"""

from pathlib import Path

__all__ = ["APP_FILE"]

#: The script ``streamlit run`` executes (the navigation over the pages).
APP_FILE = Path(__file__).with_name("main.py")
