"""The Characterize page and the test programmes on the Simulate page (Streamlit AppTest)."""

from pathlib import Path

import numpy as np
import pytest
import streamlit as st
from streamlit.testing.v1 import AppTest

from erdesign.app import state
from tests.test_app import same_in_every_unit_system

MAIN = str(Path(state.__file__).with_name("main.py"))
TIMEOUT = 120


@pytest.fixture
def app() -> AppTest:
    state.clear_caches()
    st.cache_data.clear()
    at = AppTest.from_file(MAIN, default_timeout=TIMEOUT).run()
    assert not at.exception, at.exception
    return at


def test_simulate_runs_a_test_programme(app):
    app.switch_page("simulate.py").run()
    app.selectbox(key="sim.kind").select("programme").run()
    app.selectbox(key="sim.programme").select("E2").run()
    assert not app.exception and not app.error, [e.value for e in app.error]
    # the Makris damper's design field is the high control; the PRBS steps between it and an eighth of it
    assert any("E2: RP" in c.value for c in app.caption) or any("E2: RP" in m.value for m in app.markdown)


@pytest.mark.slow
def test_characterize_page_on_the_example_records(app):
    app.switch_page("characterize.py").run()
    assert not app.exception and not app.error, [e.value for e in app.error]
    findings, parameters, cv, _ = (d.value for d in app.dataframe)
    found = set(findings.loc[findings["found"], "characteristic"])
    assert {"Friction", "Stiffness", "Gain in force due to manipulation"} <= found
    assert len(parameters) >= 5
    assert list(cv.index)[-1] == "average" and np.allclose(cv.iloc[:-1].mean(axis=0), cv.iloc[-1])
    same_in_every_unit_system(app)  # (the browser walk shows this page in one unit system)
    # bad upload: one line naming the file, no traceback
    app.radio(key="chr.source").set_value("upload").run()
    app.file_uploader(key="chr.upload").set_value(
        [("broken.csv", b"time,displacement,force\n1,2,3\n", "text/csv")]
    ).run()
    assert not app.exception
    assert any("broken.csv" in e.value for e in app.error)
