"""Issue 15: the app guards every input and upload: a bad value shows a message naming the field, leaves the last
good design in place, and never shows an exception or a server path (Streamlit's AppTest)."""

from __future__ import annotations

from pathlib import Path

import pytest
import streamlit as st
from streamlit.testing.v1 import AppTest

from erdesign.app import state

from .corpus import GOOD_RECORD, MAKRIS

MAIN = str(Path(state.__file__).with_name("main.py"))

#: (id, widget key, bad value, text the message must contain)
SIZE_INPUTS = [
    ("reference field abc", "size.fluid.reference_field", "abc", "fluid.reference_field"),
    ("gap 1e-300 m", "size.geo.gap", "1e-300 m", "geometry.gap"),
    ("gap 0", "size.geo.gap", "0 mm", "geometry.gap"),
    ("gap mass", "size.geo.gap", "0.8 kg", "geometry.gap"),
    ("piston 1e308 m", "size.geo.piston_diameter", "1e308 m", "geometry.piston_diameter"),
    ("rod above piston", "size.geo.rod_diameter", "40 mm", "geometry.rod_diameter"),
    ("duct length empty", "size.geo.duct_length", "", "geometry.duct_length"),
    ("density 1e30", "size.fluid.density", "1e30 kg/m^3", "fluid.density"),
    ("viscosity negative", "size.fluid.viscosity", "-7 Pa*s", "fluid.viscosity"),
    ("exponent text", "size.fluid.yield_exponent", "two", "fluid.yield_exponent"),
    ("design field 1e9 kV/mm", "size.field", "1e9 kV/mm", "field"),
    ("design velocity text", "size.velocity", "fast", "design velocity"),
    ("design velocity nan", "size.velocity", "nan mm/s", "design velocity"),
    ("top velocity negative", "size.v_top", "-5 mm/s", "top velocity"),
]
#: (id, file name, content, text the message must contain)
SIZE_UPLOADS = [
    ("upload gap 1e-300", "g.toml", MAKRIS.replace('"0.8 mm"', '"1e-300 m"'), "geometry.gap"),
    ("upload reference field abc", "r.toml", MAKRIS.replace('"3 kV/mm"', '"abc"'), "fluid.reference_field"),
    ("upload piston 1e308", "p.toml", MAKRIS.replace('"33.4 mm"', '"1e308 m"'), "geometry.piston_diameter"),
    ("upload binary", "b.toml", b"\xff\xfe\x00", "UTF-8"),
    ("upload invalid TOML", "t.toml", "[geometry\n", "invalid TOML"),
]
COMPARE_UPLOADS = [
    ("compare tab separated", "tab.csv", GOOD_RECORD.replace(",", "\t"), "tabs"),
    ("compare empty", "empty.csv", "", "empty file"),
    (
        "compare force x1e300",
        "big.csv",
        GOOD_RECORD.splitlines()[0] + "\n" + "".join(f"{i * 0.01},{i % 7},1e300\n" for i in range(50)),
        "force",
    ),
    ("compare binary", "bin.csv", b"\xff\xfe\x00\x01", "UTF-8"),
    (
        "compare constant displacement",
        "c.csv",
        GOOD_RECORD.splitlines()[0] + "\n" + "".join(f"{i * 0.01},1,{i}\n" for i in range(50)),
        "displacement",
    ),
]
#: Simulate page, sine excitation: (id, widget key, bad value, text the message must contain)
SIMULATE_INPUTS = [
    ("sim field abc", "sim.field", "abc", "field"),
    ("sim field 1e9 kV/mm", "sim.field", "1e9 kV/mm", "field"),
    ("sim field mass", "sim.field", "2 kg", "field"),
    ("sim amplitude text", "sim.amplitude", "abc", "amplitude"),
    ("sim amplitude negative", "sim.amplitude", "-10 mm", "amplitude"),
    ("sim amplitude zero", "sim.amplitude", "0 mm", "amplitude"),
    ("sim amplitude 1e300 m", "sim.amplitude", "1e300 m", "amplitude"),
    ("sim frequency zero", "sim.frequency", "0 Hz", "frequency"),
    ("sim frequency negative", "sim.frequency", "-1 Hz", "frequency"),
    ("sim frequency mass", "sim.frequency", "1 kg", "frequency"),
    ("sim frequency 1e12 Hz", "sim.frequency", "1e12 Hz", "frequency"),
]
APP_CASES = SIZE_INPUTS + SIZE_UPLOADS + COMPARE_UPLOADS + SIMULATE_INPUTS


@pytest.fixture(scope="module")
def app():
    state.clear_caches()
    st.cache_data.clear()
    at = AppTest.from_file(MAIN, default_timeout=60).run()
    assert not at.exception
    return at


def _clean(at: AppTest, field: str) -> None:
    assert not at.exception, [e.value for e in at.exception]
    messages = [e.value for e in at.error]
    assert any(field in m for m in messages), (field, messages)
    for m in messages:
        assert "Internal error" not in m and "Traceback" not in m and "/tmp" not in m, m


@pytest.mark.parametrize("case", SIZE_INPUTS, ids=[c[0] for c in SIZE_INPUTS])
def test_size_input(app, case):
    _, key, value, field = case
    force = [m.value for m in app.metric if m.label == "force F"]
    good = app.text_input(key=key).value
    app.text_input(key=key).set_value(value).run()
    _clean(app, field)
    assert [m.value for m in app.metric if m.label == "force F"] == force  # the last good design stays
    assert any("last valid design" in e.value for e in app.error)
    app.text_input(key=key).set_value(good).run()
    assert not app.exception and not app.error


@pytest.mark.parametrize("case", SIZE_UPLOADS, ids=[c[0] for c in SIZE_UPLOADS])
def test_size_upload(app, case):
    _, name, content, field = case
    data = content if isinstance(content, bytes) else content.encode()
    before = app.text_input(key="size.geo.gap").value
    app.file_uploader(key="size.upload").set_value((name, data, "application/toml")).run()
    _clean(app, field)
    assert app.text_input(key="size.geo.gap").value == before  # nothing typed is lost


@pytest.mark.parametrize("case", COMPARE_UPLOADS, ids=[c[0] for c in COMPARE_UPLOADS])
def test_compare_upload(app, case):
    _, name, content, field = case
    data = content if isinstance(content, bytes) else content.encode()
    app.switch_page("compare.py").run()
    app.radio(key="cmp.source").set_value("upload a measurement CSV").run()
    app.file_uploader(key="cmp.upload").set_value((name, data, "text/csv")).run()
    _clean(app, field)
    app.switch_page("size.py").run()
    assert not app.exception


def test_compare_warns_on_a_force_unit_mistake(app):
    app.switch_page("compare.py").run()
    app.radio(key="cmp.source").set_value("upload a measurement CSV").run()
    data = GOOD_RECORD.replace("force [N]", "force [mN]").encode()
    app.file_uploader(key="cmp.upload").set_value(("mN.csv", data, "text/csv")).run()
    assert not app.exception
    assert any("force" in w.value and "1000" in w.value for w in app.warning), [w.value for w in app.warning]
    app.switch_page("size.py").run()


@pytest.mark.parametrize("case", SIMULATE_INPUTS, ids=[c[0] for c in SIMULATE_INPUTS])
def test_simulate_input(app, case):
    _, key, value, field = case
    app.switch_page("simulate.py").run()
    good = app.text_input(key=key).value
    app.text_input(key=key).set_value(value).run()
    _clean(app, field)
    app.text_input(key=key).set_value(good).run()
    assert not app.exception and not app.error
    app.switch_page("size.py").run()
