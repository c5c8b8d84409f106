"""The Vehicle page through Streamlit's AppTest: dampers and control laws side by side, figures from the library's
runs, one-line messages for runs that cannot be made."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import streamlit as st
from streamlit.testing.v1 import AppTest

from erdesign.app import state
from erdesign.simulation.roads import bump_road
from erdesign.simulation.vehicle import simulate_vehicle
from erdesign.app.vehicle import short
from erdesign.simulation.vehicle_setup import PRESET_DAMPERS, vehicle_damper
from tests.test_app import same_in_every_unit_system

MAIN = str(Path(state.__file__).with_name("main.py"))


@pytest.fixture(autouse=True)
def _clear_caches():
    state.clear_caches()
    st.cache_data.clear()
    yield


def test_vehicle_page_compares_the_default_dampers_with_the_library_numbers():
    at = AppTest.from_file(MAIN, default_timeout=120).run()
    at.switch_page("vehicle.py").run()
    assert not at.exception, at.exception
    assert not at.error
    charts = {c.proto.id: json.loads(c.proto.spec) for c in at.get("plotly_chart")}
    (comfort,) = [spec for key, spec in charts.items() if "veh.fig.comfort" in key]
    names = list(PRESET_DAMPERS)[:2]
    bars = dict(zip(comfort["data"][0]["x"], comfort["data"][0]["y"]))
    for name in names:
        r = simulate_vehicle(vehicle_damper(**PRESET_DAMPERS[name]), bump_road(0.1, 0.5), duration=2.0)
        # the page shows the library's number for the same run (no physics in the page)
        assert bars[f"{short(name)}, passive"] == pytest.approx(r.ride()["body_acceleration_weighted_rms_m_per_s2"])
    same_in_every_unit_system(at)  # (the browser walk shows this page in one unit system)


def test_a_run_that_cannot_be_made_is_a_warning_not_a_traceback():
    at = AppTest.from_file(MAIN, default_timeout=120).run()
    at.switch_page("vehicle.py").run()
    at.multiselect(key="veh.controls").set_value(["skyhook"]).run()
    assert not at.exception, at.exception
    # the conventional damper has no control: both default dampers are refused for skyhook, each in one line
    assert len(at.warning) == 2 and all("semi-active control needs" in w.value for w in at.warning)
