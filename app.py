"""Streamlit entry point of a source checkout: ``streamlit run app.py`` opens the design app on the Makris damper.

The app lives in the package (:mod:`erdesign.app`); an installed erdesign offers the same app as ``erdesign app``.
"""

from erdesign.app.main import main

main()
