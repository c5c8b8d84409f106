"""The Streamlit app through Streamlit's AppTest (issue 6): every page, inputs change outputs, bad uploads give a
message (never a traceback), figures checked through their data, state survives page switches.

The app holds no physics, so most expected numbers come from the library; where a published number or a limit
applies it is used instead and cited at the assert.  Caches are cleared before each test.
"""

from __future__ import annotations

import base64
import json
import math
import re
from html import unescape
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest
import streamlit as st
from streamlit.testing.v1 import AppTest

from erdesign import load_example
from erdesign.app import state
from erdesign.units import Q_

MAIN = str(Path(state.__file__).with_name("main.py"))
#: Generous per-run limit: the first run imports scipy and plotly; each test still takes a few seconds.
TIMEOUT = 60
#: Metrics show 4 significant figures (erdesign.report.formatting.SIGNIFICANT_DIGITS): half a unit of the 4th.
FOUR_FIGURES = 5e-4
#: The diagnosis' ESRs read to the 3 figures of its verdict's sentence (one number, one rounding).
THREE_FIGURES = 5e-3


@pytest.fixture(autouse=True)
def _clear_caches():
    state.clear_caches()
    st.cache_data.clear()
    yield


@pytest.fixture
def app() -> AppTest:
    at = AppTest.from_file(MAIN, default_timeout=TIMEOUT).run()
    assert not at.exception, at.exception
    return at


def metric(at: AppTest, label: str):
    """A metric's value as a quantity (or float)."""
    (m,) = [m for m in at.metric if m.label == label]
    return Q_(m.value.replace("·", "*")) if " " in m.value else float(m.value)


def figure(at: AppTest, key_part: str) -> dict:
    """The plotly figure (as JSON data) of the chart whose key contains ``key_part``."""
    charts = [c for c in at.get("plotly_chart") if key_part in c.proto.id]
    assert charts, f"no chart {key_part!r}"
    return json.loads(charts[0].proto.spec)


def values(data) -> np.ndarray:
    """Trace data as an array: plotly 6+ stores numpy arrays as ``{"dtype": ..., "bdata": base64}``."""
    if isinstance(data, dict) and "bdata" in data:
        a = np.frombuffer(base64.b64decode(data["bdata"]), dtype=np.dtype(data["dtype"]))
        return a.reshape(data["shape"]) if "shape" in data else a
    return np.asarray(data, dtype=float)


def no_error(at: AppTest) -> None:
    assert not at.exception, at.exception
    assert not at.error, [e.value for e in at.error]


def page_content(at: AppTest) -> list:
    """What the page shows, element by element: each element's message to the browser, for a widget with the
    value it shows instead of how the value was set (AppTest's first run sets a widget's default, later runs its
    state), and with the random id pandas gives a styled table (``Styler.uuid``, in its CSS too) taken out."""
    from streamlit.testing.v1.element_tree import Widget

    content = []
    for element in at.main:
        proto = getattr(element, "proto", None)
        if proto is None:
            content.append(repr(element))
            continue
        if isinstance(element, Widget):
            proto = type(proto)()
            proto.CopyFrom(element.proto)
            for field in ("value", "default", "set_value", "raw_value"):
                if field in proto.DESCRIPTOR.fields_by_name:
                    proto.ClearField(field)
            content.append((proto.SerializeToString(), repr(element.value)))
            continue
        data = proto.SerializeToString()
        uuid = proto.arrow_data.styler.uuid if "arrow_data" in proto.DESCRIPTOR.fields_by_name else ""
        content.append(data.replace(uuid.encode(), b"") if uuid else data)
    return content


def same_in_every_unit_system(at: AppTest) -> None:
    """The page in view shows the same in SI, mm-kN-s and in-lbf-s (tests/test_app_browser.py then checks its
    layout in one unit system only: add the page to its walk in all three if this fails)."""
    from erdesign.report.formatting import UNIT_SYSTEMS

    shown = {}
    for system in UNIT_SYSTEMS:
        at.radio(key=state.UNITS).set_value(system).run()
        no_error(at)
        shown[system] = page_content(at)
    first, *others = UNIT_SYSTEMS
    for system in others:
        assert shown[system] == shown[first], f"the page differs in {system} from {first}"


# ------------------------------------------------------------------------------------------------ Size
def test_opens_on_the_makris_damper(app):
    no_error(app)
    assert app.text_input(key="size.geo.gap").value == "0.8 mm"
    assert app.text_input(key="size.geo.duct_length").value == "54.6 mm"
    # Makris et al. (1996) eq 15: C = 120 kN s/m for this damper (the library gives 120.3).
    assert metric(app, "damping constant C").to("kN*s/m").magnitude == pytest.approx(120.0, rel=0.01)
    # The design point is the library's Damper.size, shown to 4 figures.
    r = load_example("makris").size(velocity=app.text_input(key="size.velocity").value, field="3 kV/mm")
    assert metric(app, "force F").to("N").magnitude == pytest.approx(r.force.to("N").magnitude, rel=FOUR_FIGURES)
    assert metric(app, "dynamic range F(E)/F(0)") == pytest.approx(r.dynamic_range, rel=FOUR_FIGURES)
    assert app.success, "the validity checks should pass for the Makris damper"


def test_size_gap_changes_force_and_curves(app):
    before = metric(app, "force F").to("N").magnitude
    app.text_input(key="size.geo.gap").set_value("0.5 mm").run()
    no_error(app)
    after = metric(app, "force F").to("N").magnitude
    # A smaller gap raises the Bingham pressure drop (viscous part ~ 1/h^3, yield part ~ 1/h): more force.
    assert after > 2 * before
    fig = figure(app, "size.fig.force")
    assert [t["name"] for t in fig["data"]] == ["E = 0 kV/mm", "E = 1 kV/mm", "E = 2 kV/mm", "E = 3 kV/mm"]
    # The top of each curve is the damper's force at the top velocity (50 mm/s) and that field, in kN.
    damper, _ = state.build_damper(state.spec_text(app.session_state[state.SPEC]))
    expected = damper.state(0.05, np.array([0.0, 1e6, 2e6, 3e6])).force / 1e3
    got = [values(t["y"])[-1] for t in fig["data"]]
    assert got == pytest.approx(expected, rel=1e-12)  # the same numbers, converted N -> kN


def test_size_bad_value_shows_a_message(app):
    app.text_input(key="size.geo.gap").set_value("0.8 kg").run()
    assert not app.exception
    assert any("geometry.gap" in e.value for e in app.error)


def test_size_validity_warning(app):
    # Makris eq 1: Re = Q/(pi d nu) is about 0.04 at 25 mm/s; 1000 times the speed with a thin fluid leaves the
    # laminar range (Re > 2300), which must be said in the page.
    app.text_input(key="size.fluid.viscosity").set_value("0.001 Pa*s").run()
    app.text_input(key="size.fluid.viscosity_at_reference_field").set_value("").run()
    app.text_input(key="size.velocity").set_value("5 m/s").run()
    assert not app.exception
    assert metric(app, "Reynolds number Re") > 2300
    assert any("Reynolds" in w.value for w in app.warning)


def test_material_picker_and_override(app):
    app.selectbox(key="size.material").select("lord-mrf-132dg").run()
    no_error(app)
    assert app.text_input(key="size.field").value == "250 kA/m"
    spec = app.session_state[state.SPEC]
    # Only what differs from the material is written, so the material's yield curve stays in force.
    assert spec["fluid"] == {"material": "lord-mrf-132dg", "seal_friction": "112 N"}
    F0 = metric(app, "zero-field force F(0)").to("N").magnitude
    app.text_input(key="size.fluid.viscosity").set_value("0.224 Pa*s").run()
    no_error(app)
    assert app.session_state[state.SPEC]["fluid"]["viscosity"] == "0.224 Pa*s"
    # Zero field: F = C v + F_s with C proportional to the viscosity (Makris eq 15): doubling eta doubles C v.
    F0_twice = metric(app, "zero-field force F(0)").to("N").magnitude
    assert F0_twice - 112.0 == pytest.approx(2 * (F0 - 112.0), rel=2 * FOUR_FIGURES)


def test_mixed_example(app):
    app.selectbox(key="size.example").select("mr_mixed").run()
    no_error(app)
    assert app.radio(key="size.configuration").value == "mixed"
    assert "size.geo.duct_mean_diameter" not in [t.key for t in app.text_input]
    r = load_example("mr_mixed").size(velocity=app.text_input(key="size.velocity").value, field="200 kA/m")
    assert metric(app, "force F").to("N").magnitude == pytest.approx(r.force.to("N").magnitude, rel=FOUR_FIGURES)


def test_sweep_explorer(app):
    app.text_input(key="size.sweep.from.gap").set_value("0.4 mm")
    app.text_input(key="size.sweep.to.gap").set_value("1.6 mm")
    app.slider(key="size.sweep.points").set_value(13).run()
    no_error(app)
    fig = figure(app, "size.fig.tradeoff")
    force, zero, dyn, re_ = fig["data"]
    x = values(force["x"])
    assert x[0] == pytest.approx(0.4) and x[-1] == pytest.approx(1.6)  # mm
    i = int(np.argmin(np.abs(x - 0.8)))
    # Round trip: the sweep point at the design's own gap is the design point.
    design = metric(app, "force F").to("kN").magnitude
    assert values(force["y"])[i] == pytest.approx(design, rel=FOUR_FIGURES)
    # Makris eq 1: Re = v_mean h / nu = Q / (pi d nu) does not depend on the gap at a given piston speed.
    Re = values(re_["y"])
    assert np.ptp(Re) == pytest.approx(0.0, abs=1e-12 * Re.max())
    # Zero field, thin gap (h/d <= 0.1): F(0) - F_s = C v with C ~ 1/h^3 (Makris eq 15), so (F(0) - F_s) h^3 is
    # the same at every gap of the sweep (to rounding: the same formula, evaluated at each h).
    thin = x / 14.3 <= 0.1
    F0 = values(zero["y"]) * 1e3 - 112.0  # kN -> N, minus the seal friction of examples/makris.toml
    assert np.ptp(F0[thin] * x[thin] ** 3) == pytest.approx(0.0, abs=1e-9 * np.max(F0[thin] * x[thin] ** 3))
    assert values(dyn["y"]) == pytest.approx(values(force["y"]) / values(zero["y"]), rel=1e-12)


def test_damper_file_round_trip(app, downloads, tmp_path, capsys):
    """The design downloads as a damper file that `erdesign size` and the app's upload read back."""
    app.text_input(key="size.geo.gap").set_value("0.0315 in")
    app.text_input(key="size.fluid.seal_friction").set_value("25 lbf")
    app.text_input(key="size.velocity").set_value("1 in/s").run()
    no_error(app)
    force = metric(app, "force F")
    toml = downloads["makris-1996.toml"].decode()
    path = tmp_path / "makris-1996.toml"
    path.write_text(toml)
    from erdesign.cli import main

    assert main(["size", str(path), "--velocity", "1 in/s", "--field", "3 kV/mm", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["force_N"] == pytest.approx(force.to("N").magnitude, rel=FOUR_FIGURES)
    # Upload it into a fresh app: the same inputs as typed, the same design point and force.
    fresh = AppTest.from_file(MAIN, default_timeout=TIMEOUT).run()
    fresh.file_uploader(key="size.upload").set_value(("makris-1996.toml", toml.encode(), "application/toml")).run()
    no_error(fresh)
    assert fresh.text_input(key="size.geo.gap").value == "0.0315 in"
    assert fresh.text_input(key="size.fluid.seal_friction").value == "25 lbf"
    assert fresh.text_input(key="size.velocity").value == "1 in/s"
    assert fresh.session_state[state.DESIGN]["spec"] == app.session_state[state.DESIGN]["spec"]
    assert metric(fresh, "force F") == force
    # a broken file says why, names the file and nothing of the server
    fresh.file_uploader(key="size.upload").set_value(
        ("bad.toml", b"[geometry]\ngap = '1 kg'\n", "application/toml")
    ).run()
    assert not fresh.exception
    (err,) = fresh.error
    assert err.value.startswith("bad.toml: ") and "/tmp" not in err.value


def test_pin_a_baseline_and_compare(app):
    F0 = metric(app, "force F")
    app.button(key="size.pin").click().run()
    app.text_input(key="size.geo.gap").set_value("0.6 mm").run()
    no_error(app)
    F1 = metric(app, "force F")
    (table,) = [t.value for t in app.table if "pinned 1" in t.value]
    rows = {r["quantity"]: r for r in table.to_dict("records")}
    assert rows["gap h"]["pinned 1"] == "0.8 mm" and rows["gap h"]["this design"] == "0.6 mm"
    assert rows["gap h"]["pinned 1 vs this"] == "+33.3 %"  # 0.8 mm against 0.6 mm
    assert Q_(rows["force F"]["pinned 1"]) == F0 and Q_(rows["force F"]["this design"]) == F1
    change = float(rows["force F"]["pinned 1 vs this"].split()[0])
    assert change == pytest.approx(100 * (F0 / F1 - 1).to("").magnitude, abs=0.1)
    fig = figure(app, "size.fig.compare")
    names = [t["name"] for t in fig["data"]]
    assert "E = 3 kV/mm" in names and "pinned 1, E = 3 kV/mm" in names


def test_state_survives_page_switches(app):
    app.text_input(key="size.velocity").set_value("1 in/s").run()
    app.switch_page("simulate.py").run()
    assert not app.exception
    app.switch_page("size.py").run()
    assert app.text_input(key="size.velocity").value == "1 in/s"
    # Damper.size's doctest: 6.07 kN at 1 in/s and 3 kV/mm.
    assert metric(app, "force F").to("kN").magnitude == pytest.approx(6.07, abs=0.005)


# ------------------------------------------------------------------------------------------------ Simulate
def test_simulate_sine(app):
    app.switch_page("simulate.py").run()
    no_error(app)
    fig = figure(app, "sim.fig.loops")
    v = values(fig["data"][1]["x"])  # mm/s
    # Peak velocity of x = X0 sin(2 pi f t): X0 * 2 pi f = 10 mm * 2 pi * 1 Hz (sampled at the peak, t = 0).
    assert v.max() == pytest.approx(20 * math.pi, rel=1e-4)
    peak = metric(app, "peak force").to("N").magnitude
    app.text_input(key="sim.amplitude").set_value("20 mm").run()
    no_error(app)
    assert metric(app, "peak force").to("N").magnitude > peak


def test_simulated_history_downloads_as_a_measurement(app, downloads, tmp_path):
    app.switch_page("simulate.py").run()
    no_error(app)
    (name,) = [k for k in downloads if k.endswith("-simulated.csv")]
    path = tmp_path / name
    path.write_bytes(downloads[name])
    from erdesign.data.measurement import read_measurement

    record = read_measurement(path)
    F = values(figure(app, "sim.fig.time")["data"][-1]["y"])  # kN on the page
    assert record.force / 1e3 == pytest.approx(F, rel=1e-9, abs=1e-9 * np.abs(F).max())
    assert record.control_kind is not None and record.control.max() == pytest.approx(3e6)  # 3 kV/mm


def test_simulate_library_model_and_effects(app):
    app.switch_page("simulate.py").run()
    app.multiselect(key="sim.effects").select("seal_friction").run()
    no_error(app)
    assert "seal_friction" in app.caption[0].value or any("seal_friction" in c.value for c in app.caption)
    app.selectbox(key="sim.model").select("bingham").run()
    no_error(app)
    fig = figure(app, "sim.fig.loops")
    F = values(fig["data"][0]["y"])
    assert np.all(np.isfinite(F)) and np.ptp(F) > 0


def test_simulate_uploaded_displacement_and_bad_upload(app):
    app.switch_page("simulate.py").run()
    app.selectbox(key="sim.kind").select("upload").run()
    # A displacement-only record drives the model (no force column needed).
    t = np.linspace(0, 1, 201)
    rows = "\n".join(f"{ti:.4f},{10 * np.sin(2 * np.pi * 2 * ti):.5f}" for ti in t)
    app.file_uploader(key="sim.upload").set_value(
        ("motion.csv", f"time [s],displacement [mm]\n{rows}\n".encode(), "text/csv")
    ).run()
    no_error(app)
    F = values(figure(app, "sim.fig.loops")["data"][0]["y"])
    assert np.all(np.isfinite(F)) and np.ptp(F) > 0
    # Too few rows: a clear message, no traceback.
    app.file_uploader(key="sim.upload").set_value(
        ("motion.csv", b"time [s],displacement [mm]\n0,1\n1,2\n", "text/csv")
    ).run()
    assert not app.exception
    assert any("a record needs at least 5" in e.value for e in app.error)


# ------------------------------------------------------------------------------------------------ Compare
def test_compare_bad_upload(app):
    app.switch_page("compare.py").run()
    app.radio(key="cmp.source").set_value("upload a measurement CSV").run()
    app.file_uploader(key="cmp.upload").set_value(("broken.csv", b"time,displacement,force\n1,2,3\n", "text/csv")).run()
    assert not app.exception
    (err,) = app.error
    assert "broken.csv" in err.value and "unit in square brackets" in err.value


def test_compare_diagnose_add_effect_refit(app, downloads):
    app.switch_page("compare.py").run()
    examples = app.selectbox(key="cmp.example").options
    example = (
        next(e for e in examples if "seal_friction" in e)
        if any("seal_friction" in e for e in examples)
        else examples[0]
    )
    app.selectbox(key="cmp.example").select(example).run()
    app.button(key="cmp.run").click().run()
    no_error(app)
    # The record hides seal friction (examples/measurements/make_examples.py or state.RIG_EXAMPLES): found, named
    # first in the ranking, explained in words.
    assert any("Missing effect: seal_friction" in s.value for s in app.success)
    assert not app.warning
    ranking = app.table[0].value
    assert ranking["effect"].iloc[0] == "seal_friction"
    # the named effect removes at least erdesign.diagnosis.diagnose.EXPLAINS (60 %) of the excess over the noise floor
    assert int(ranking["explains"].iloc[0].split()[0]) >= 60
    assert metric(app, "noise floor ESR") < float(app.metric[0].value)
    assert any("seal friction" in m.value for m in app.markdown)
    esr0 = float(app.metric[0].value)
    # the verdict box carries the button that adds the named effect and refits
    assert app.button(key="cmp.add_named").label == "Add seal_friction and refit"
    app.button(key="cmp.add_named").click().run()
    no_error(app)
    esr1 = float(app.metric[0].value)
    assert esr1 < esr0 / 3  # the hidden effect carried most of the error
    assert any(m.value == "**Model:** baseline + seal_friction" for m in app.markdown)
    bars = figure(app, "cmp.fig.history")
    assert list(bars["data"][0]["x"]) == ["0: baseline", "1: seal_friction"]
    assert list(values(bars["data"][0]["y"])) == pytest.approx([esr0, esr1], rel=THREE_FIGURES)
    # the noise floor is drawn on the history, at the value of its metric
    (floor,) = [sh["y0"] for sh in bars["layout"]["shapes"]]
    assert floor == pytest.approx(metric(app, "noise floor ESR"), rel=5e-3)
    (params,) = [d.value for d in app.dataframe if "parameter" in d.value]
    rows = {r["parameter"]: r for r in params.to_dict("records")}
    assert "friction_force" in rows and rows["friction_force"]["± 1σ"].startswith("± ")
    assert rows["friction_force"]["value"].endswith(" N") and rows["friction_force"]["±"].endswith(" %")
    # downloads: time histories with the residual, ranking, parameters, history
    files = {k: v.decode() for k, v in downloads.items() if k.endswith(".csv")}
    (history,) = [v for k, v in files.items() if k.endswith("-model.csv")]
    lines = [l for l in history.splitlines() if not l.startswith("#")]
    assert lines[0] == ("time [s],displacement [m],velocity [m/s],force [N],model force [N],residual [N]")
    data = np.loadtxt(lines[1:], delimiter=",")
    assert np.allclose(data[:, 3] - data[:, 4], data[:, 5], atol=1e-6 * np.abs(data[:, 3]).max())
    (ranking,) = [v for k, v in files.items() if k.endswith("-ranking.csv")]
    assert [line for line in ranking.splitlines() if not line.startswith("#")][0].startswith("rank,effect")
    (params_csv,) = [v for k, v in files.items() if k.endswith("-parameters.csv")]
    # numbers in SI, the unit in the header: the friction force's value is the page's, to its 4 figures
    head, value_row = [line.split(",") for line in params_csv.splitlines() if not line.startswith("#")][:2]
    F_s = float(value_row[head.index("friction_force [N]")])
    assert Q_(rows["friction_force"]["value"]).to("N").magnitude == pytest.approx(F_s, rel=FOUR_FIGURES)
    import csv as _csv

    table = list(_csv.DictReader(line for line in ranking.splitlines() if not line.startswith("#")))
    quantities = [k for k in table[0] if k.endswith("]")]
    assert "ESR after adding [1]" in quantities and len(quantities) > 7  # each fitted parameter a column
    for row in table:  # numbers in the cells, never "815.4 N"
        for k in quantities:
            assert row[k] == "" or math.isfinite(float(row[k])), (k, row[k])
    (steps,) = [v for k, v in files.items() if k.endswith("-error-history.csv")]
    head, *rows_ = steps.splitlines()
    assert head == "step,effect added,ESR [1]"
    assert [r.split(",")[1] for r in rows_] == ["baseline", "seal_friction", "noise floor"]
    assert [float(r.split(",")[2]) for r in rows_[:2]] == pytest.approx([esr0, esr1], rel=THREE_FIGURES)


@pytest.fixture(scope="module")
def truth_csv(tmp_path_factory):
    """CSV bytes of records of the truth rig (erdesign.simulation.truthrig, physics independent of the diagnosed model)
    on the Makris damper: ``clean`` (nothing missing) and ``blowoff`` (a rebound blow-off valve, outside the effect
    library).  Short sweeps at 100 samples/s keep each diagnosis to a fraction of a second."""
    from erdesign.simulation.rig import stepped_sine
    from erdesign.simulation.truthrig import TruthDamper, simulate_truth

    folder = tmp_path_factory.mktemp("truth")
    motion = stepped_sine([0.01], [1.0], [3e6, 1.5e6], cycles=2, rate=100)
    out = {}
    for name, mechanisms in (("clean", {}), ("blowoff", {"blowoff": {}})):
        rec = simulate_truth(TruthDamper(load_example("makris"), mechanisms), motion, seed=1, name=name)
        out[name] = rec.write(folder / f"{name}.csv").read_bytes()
    return out


@pytest.fixture
def few_candidates(monkeypatch):
    """Judge only two candidate effects (the page's handling of the verdict is under test, not the library's
    ranking, which tests/test_diagnose.py covers); ``spoil`` names a candidate to show as not evaluated."""
    import erdesign.diagnosis.diagnose

    real = erdesign.diagnosis.diagnose.diagnose
    spoil = []

    def diagnose(damper, record, effects=(), **kwargs):
        d = real(damper, record, effects, candidates=("gas_spring", "seal_friction"), **kwargs)
        for c in d.ranking:
            if c.effect in spoil:
                c.result, c.esr, c.reason = None, None, "could not be evaluated: a test says so"
        return d

    monkeypatch.setattr(erdesign.diagnosis.diagnose, "diagnose", diagnose)
    return spoil


def upload_and_diagnose(app: AppTest, name: str, data: bytes) -> AppTest:
    app.switch_page("compare.py").run()
    app.radio(key="cmp.source").set_value("upload a measurement CSV").run()
    app.file_uploader(key="cmp.upload").set_value((name, data, "text/csv")).run()
    app.button(key="cmp.run").click().run()
    return app


def test_compare_nothing_missing(app, truth_csv, few_candidates):
    few_candidates.append("gas_spring")
    upload_and_diagnose(app, "clean.csv", truth_csv["clean"])
    no_error(app)
    assert not app.success and not app.warning
    (info,) = [i.value for i in app.info]
    assert info.startswith("**Nothing missing: the residual is at the noise floor.**")
    # The record's own noise floor is shown next to the ESR; nothing is missing, so the ESR is within the
    # factor erdesign.diagnosis.diagnose.AT_FLOOR of it.
    from erdesign.diagnosis.diagnose import ABSOLUTE_SLACK, AT_FLOOR

    esr, floor = metric(app, "ESR of the calibrated model"), metric(app, "noise floor ESR")
    assert 0 < floor and esr <= AT_FLOOR * floor * (1 + FOUR_FIGURES) + ABSOLUTE_SLACK
    rows = {r["effect"]: r for r in app.table[0].value.to_dict("records")}
    assert rows["gas_spring"]["ESR after adding"] == "not evaluated"
    assert rows["gas_spring"]["note"] == "could not be evaluated: a test says so"
    assert rows["seal_friction"]["explains"].endswith(" % of the excess")
    # only an evaluated candidate can be added
    assert [o.split(":")[0] for o in app.selectbox(key="cmp.add").options] == ["seal_friction"]


def test_compare_unexplained_and_refit(app, truth_csv, few_candidates):
    upload_and_diagnose(app, "blowoff.csv", truth_csv["blowoff"])
    no_error(app)
    assert not app.success
    verdicts = [w.value for w in app.warning if w.value.startswith("**Unexplained:**")]
    assert len(verdicts) == 1 and "noise floor" in verdicts[0] and "outside the effect library" in verdicts[0]
    # A one-sided relief valve is far from the baseline: the ESR stays many times the noise floor
    # (erdesign.diagnosis.diagnose.WELL_ABOVE is the least for "unexplained").
    assert metric(app, "ESR of the calibrated model") > 10 * metric(app, "noise floor ESR")
    # the calibration's warnings are shown too
    assert all(w.value.startswith("Check: ") for w in app.warning if w.value not in verdicts)
    # adding an effect anyway keeps working: the page diagnoses again with it
    app.selectbox(key="cmp.add").set_value("seal_friction").run()
    app.button(key="cmp.refit").click().run()
    no_error(app)
    assert [m.value for m in app.markdown if m.value.startswith("**Model:**")] == [
        "**Model:** baseline + seal_friction"
    ]
    bars = figure(app, "cmp.fig.history")["data"][0]
    assert list(bars["x"]) == ["0: baseline", "1: seal_friction"]


# ------------------------------------------------------------------------------------------------ Report
@pytest.fixture
def downloads(monkeypatch) -> dict:
    """The files of the app's download buttons, by file name (recorded as Streamlit stores them)."""
    from streamlit.runtime.memory_media_file_storage import MemoryMediaFileStorage

    files: dict[str, bytes] = {}
    real = MemoryMediaFileStorage.load_and_get_id

    def load_and_get_id(self, path_or_data, mimetype, kind, filename=None):
        if filename:
            files[filename] = path_or_data if isinstance(path_or_data, bytes) else str(path_or_data).encode()
        return real(self, path_or_data, mimetype, kind, filename)

    monkeypatch.setattr(MemoryMediaFileStorage, "load_and_get_id", load_and_get_id)
    return files


class Quantities(HTMLParser):
    """The quantity spans of a report, by id: ``{"q-point-force": "5.984 kN", ...}``."""

    def __init__(self, html: str):
        super().__init__()
        self.spans: dict[str, str] = {}
        self._id = None
        self.feed(html)

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "span" and a.get("class") == "q" and a.get("id"):
            self._id = a["id"]

    def handle_data(self, data):
        if self._id:
            self.spans[self._id] = self.spans.get(self._id, "") + data

    def handle_endtag(self, tag):
        if tag == "span":
            self._id = None


def test_report_page(app, downloads):
    app.switch_page("report.py").run()
    no_error(app)
    buttons = app.get("download_button")
    assert buttons and "makris-1996-report.html" in buttons[0].proto.label
    html = downloads["makris-1996-report.html"].decode()
    assert "120.3 kN·s/m" in html  # Makris eq 15, as on the Size page
    app.radio(key="rep.format").set_value("md").run()
    no_error(app)
    assert "makris-1996-report.md" in app.get("download_button")[0].proto.label
    assert "| damping constant C | 120.3 kN·s/m |" in downloads["makris-1996-report.md"].decode()


def test_the_report_is_the_design_on_screen(app, downloads):
    """Issue 14: sized at one velocity and field, the report said another; its checks differed from the page's;
    its "as given" column was empty.  Now the report is built from the design on screen."""
    app.text_input(key="size.geo.gap").set_value("0.0315 in").run()  # Makris's own unit (Makris et al. 1996)
    app.text_input(key="size.velocity").set_value("1 in/s").run()
    app.text_input(key="size.field").set_value("2 kV/mm").run()
    no_error(app)
    shown = {m.label: m.value for m in app.metric}
    checks = app.table[0].value.to_dict("records")
    app.switch_page("report.py").run()
    no_error(app)
    html = downloads["makris-1996-report.html"].decode()
    q = Quantities(html).spans
    # the design point typed on the Size page, in the report
    assert q["q-design-velocity"] == "25.4 mm/s" and q["q-design-field"] == "2 kV/mm"
    assert "At the design velocity 25.4 mm/s" in html
    # every figure the Size page showed, with the same text, in the report's design-point table
    from erdesign.report import build_report

    report = build_report(load_example("makris"), design_velocity="1 in/s", design_field="2 kV/mm")
    for row in report.design_point:
        if row.key in ("velocity", "field"):
            continue
        assert q[f"q-point-{row.key}"] == shown[row.label], row.label
    # an independent number: Damper.size at the design point (not the top of the curves' range)
    r = load_example("makris").size(velocity="1 in/s", field="2 kV/mm")
    assert Q_(q["q-point-force"]).to("N").magnitude == pytest.approx(r.force.to("N").magnitude, rel=FOUR_FIGURES)
    # the same validity checks, status by status
    statuses = re.findall(r'<tr id="check-(\w+)"><td>([^<]+)</td><td class="status-(\w+)"', html)
    assert [(unescape(name), status) for _, name, status in statuses] == [
        (c["check"], c["status"].lower()) for c in checks
    ]
    # inputs as typed, with their units
    assert re.search(r"<code>gap</code></td><td><code>0.0315 in</code>", html)
    assert "as typed in the app" in html and "Python" not in re.sub(r"<script.*?</script>", "", html, flags=re.S)


def test_a_bad_value_keeps_the_last_good_design(app):
    force = metric(app, "force F")
    app.text_input(key="size.geo.gap").set_value("0.8 kg").run()
    assert not app.exception
    (err,) = app.error
    assert "geometry.gap" in err.value and "last valid design" in err.value
    assert metric(app, "force F") == force  # still shown
    assert app.session_state[state.DESIGN]["spec"]["geometry"]["gap"] == "0.8 mm"
    app.text_input(key="size.geo.gap").set_value("0.8 mm")
    app.text_input(key="size.velocity").set_value("fast").run()
    assert not app.exception and [e.value for e in app.error if "design velocity" in e.value]
    assert metric(app, "force F") == force
    app.switch_page("report.py").run()  # the report keeps the last good design
    no_error(app)


def test_unit_systems_and_fields_in_their_own_unit(app):
    F = metric(app, "force F").to("N").magnitude
    app.radio(key=state.UNITS).set_value("in-lbf-s").run()
    no_error(app)
    (m,) = [m for m in app.metric if m.label == "force F"]
    assert m.value.endswith(" lbf")
    assert Q_(m.value).to("N").magnitude == pytest.approx(F, rel=FOUR_FIGURES)
    assert [m.value for m in app.metric if m.label == "pressure drop Δp"][0].endswith(" psi")
    assert "3 kV/mm" in app.caption[0].value or any("E = 3 kV/mm" in c.value for c in app.caption)
    assert not any("e+0" in c.value for c in app.caption)
    app.radio(key=state.UNITS).set_value("mm-kN-s").run()
    assert [m.value for m in app.metric if m.label == "force F"][0].endswith(" kN")


def test_simulate_caption_and_numbers_in_the_unit_system(app):
    """Issue 14: the Simulate caption said "control 3e+06"; the control reads in the fluid's unit, the numbers in
    the unit system chosen."""
    app.switch_page("simulate.py").run()
    no_error(app)
    captions = [c.value for c in app.caption]
    assert any("10 mm at 1 Hz, control 3 kV/mm" in c for c in captions), captions
    assert not any("e+0" in c for c in captions)
    F = metric(app, "peak force").to("N").magnitude
    app.radio(key=state.UNITS).set_value("in-lbf-s").run()
    no_error(app)
    (m,) = [m for m in app.metric if m.label == "peak force"]
    assert m.value.endswith(" lbf") and Q_(m.value).to("N").magnitude == pytest.approx(F, rel=FOUR_FIGURES)
    fig = figure(app, "sim.fig.loops")
    assert fig["layout"]["xaxis2"]["title"]["text"] == "velocity v [in/s]"
    # peak velocity X0 * 2 pi f = 10 mm * 2 pi * 1 Hz, in in/s on the axis
    assert values(fig["data"][1]["x"]).max() == pytest.approx(20 * math.pi / 25.4, rel=1e-4)
    assert any("control 3 kV/mm" in c.value for c in app.caption)  # the control keeps its own unit
    app.text_input(key="sim.field").set_value("1500 V/mm").run()
    assert any("control 1.5 kV/mm" in c.value for c in app.caption)


def test_compare_fitted_parameters_in_the_unit_system(app, few_candidates):
    """The ranking's fitted values and the calibrated parameters read in the unit system (lbf), and are the
    library's numbers converted."""
    from erdesign.diagnosis.diagnose import diagnose

    app.radio(key=state.UNITS).set_value("in-lbf-s").run()
    app.switch_page("compare.py").run()
    app.selectbox(key="cmp.example").select("makris_hidden_seal_friction.csv").run()
    app.button(key="cmp.run").click().run()
    no_error(app)
    ranking = app.table[0].value
    (fitted,) = ranking.loc[ranking["effect"] == "seal_friction", "fitted"]
    value, error = re.fullmatch(r"friction_force = (\S+ lbf) ± (\S+ lbf) \(\S+ %\)", fitted).groups()
    data = state.example_record_bytes("makris_hidden_seal_friction.csv")
    record = state.read_record(data, "a.csv")
    (c,) = [c for c in diagnose(load_example("makris"), record).ranking if c.effect == "seal_friction"]
    # the library's fitted friction (N), shown to 4 figures in lbf
    assert Q_(value).to("N").magnitude == pytest.approx(c.result.values["friction_force"], rel=FOUR_FIGURES)
    assert Q_(error).to("N").magnitude == pytest.approx(c.result.stderr["friction_force"], rel=0.05)
    app.button(key="cmp.add_named").click().run()
    no_error(app)
    (params,) = [d.value for d in app.dataframe if "parameter" in d.value]
    rows = {r["parameter"]: r for r in params.to_dict("records")}
    assert rows["friction_force"]["value"].endswith(" lbf")
    assert rows["friction_force"]["± 1σ"].endswith(" lbf")
    assert " " not in rows["viscosity_factor"]["value"]  # a plain factor stays a plain number


def test_baseline_beside_the_design_on_simulate_and_in_the_report(app, downloads):
    """Issue 14, compare designs beyond the Size page: the pinned baseline is simulated beside the current design
    and has its own section in the report; its numbers are the library's for the baseline's geometry."""
    velocity = app.text_input(key="size.velocity").value
    app.button(key="size.pin").click().run()
    app.text_input(key="size.geo.gap").set_value("0.6 mm").run()
    no_error(app)
    makris = load_example("makris")
    narrow = state.damper_from_dict(app.session_state[state.DESIGN]["spec"], source="test")

    app.switch_page("simulate.py").run()
    no_error(app)
    fig = figure(app, "sim.fig.loops")
    traces = {t["name"]: t for t in fig["data"] if t.get("showlegend", True) is not False}
    # one meaning of "baseline" per plot: the current design is "design", the pinned one "pinned design"
    assert set(traces) == {"design", "pinned design"}
    unit = fig["layout"]["yaxis"]["title"]["text"].split("[")[1].rstrip("]")
    # at t = 0 the sine 10 mm at 1 Hz moves at its peak velocity X0 * 2 pi f: the quasi-steady force there is
    # Damper.size's force at that velocity, for each design (Makris 0.8 mm gap dashed, 0.6 mm solid)
    v0 = Q_(20 * math.pi, "mm/s")
    for trace, damper in (("pinned design", makris), ("design", narrow)):
        F0 = Q_(values(traces[trace]["y"])[0], unit)
        expected = damper.size(velocity=v0, field="3 kV/mm").force
        assert F0.to("N").magnitude == pytest.approx(expected.to("N").magnitude, rel=1e-3), trace
    assert metric(app, "peak force, pinned design") < metric(app, "peak force")  # the wider gap is softer
    assert any("geometry.gap = 0.8 mm" in c.value for c in app.caption)
    assert [t["name"] for t in figure(app, "sim.fig.time")["data"]] == ["design", "pinned design"]

    app.switch_page("report.py").run()
    no_error(app)
    assert app.checkbox(key="rep.baseline").value
    html = downloads["makris-1996-report.html"].decode()
    q = Quantities(html).spans
    for prefix, damper in (("q-baseline-", makris), ("q-this-", narrow)):
        r = damper.size(velocity=velocity, field="3 kV/mm")
        assert Q_(q[prefix + "force"]).to("N").magnitude == pytest.approx(
            r.force.to("N").magnitude, rel=FOUR_FIGURES
        ), prefix
    assert q["q-this-force"] == q["q-point-force"]  # this design: its own design point
    assert re.search(r"<td><code>geometry.gap</code></td><td><code>0.8 mm</code></td><td><code>0.6 mm</code>", html)
    assert 'id="figure-baseline"' in html
    app.checkbox(key="rep.baseline").uncheck().run()
    assert 'id="figure-baseline"' not in downloads["makris-1996-report.html"].decode()
    app.radio(key="rep.format").set_value("md").run()
    assert "## Compared with the baseline" not in downloads["makris-1996-report.md"].decode()
    app.checkbox(key="rep.baseline").check().run()
    md = downloads["makris-1996-report.md"].decode()
    assert "## Compared with the baseline design makris-1996" in md and "| `geometry.gap` | `0.8 mm` | `0.6 mm` |" in md


def test_figures_save_as_named_png_or_svg(app, downloads, monkeypatch):
    """Every figure's camera button saves '<design>-<figure>.<format>' in the format of the sidebar; the report's
    static images come as a zip, or, without kaleido or a browser, as a message (never an exception)."""

    def configs(at):
        return {c.proto.id: json.loads(c.proto.config) for c in at.get("plotly_chart")}

    shown = configs(app)
    (force,) = [c for k, c in shown.items() if "size.fig.force" in k]
    assert force["toImageButtonOptions"] == {"format": "png", "filename": "makris-1996-force", "scale": 2}
    assert all(c["toImageButtonOptions"]["format"] == "png" for c in shown.values())
    app.radio(key=state.IMAGE_FORMAT).set_value("svg").run()
    app.switch_page("simulate.py").run()
    no_error(app)
    assert {
        c["toImageButtonOptions"]["filename"]: c["toImageButtonOptions"]["format"] for c in configs(app).values()
    } == {"makris-1996-loops": "svg", "makris-1996-time": "svg"}

    app.switch_page("report.py").run()
    html = downloads["makris-1996-report.html"].decode()
    assert '"toImageButtonOptions": {"format": "svg", "filename": "makris-1996-force"' in html
    from erdesign.errors import ErdesignError
    from erdesign.report import export

    def no_browser(figures, image_format="png"):
        raise ErdesignError(f"figure images: ChromeNotFoundError: no chrome; {export.IMAGES_NEED}")

    monkeypatch.setattr(export, "figure_images", no_browser)
    app.button(key="rep.make_images").click().run()
    no_error(app)
    assert any("erdesign never downloads a browser" in i.value for i in app.info)
    assert "makris-1996-figures.zip" not in downloads
    # the fallback without kaleido: each figure as an HTML page beside plotly's own script (issue 26)
    import io
    import zipfile

    pages = zipfile.ZipFile(io.BytesIO(downloads["makris-1996-figures-html.zip"]))
    assert pages.namelist()[0] == "plotly.min.js" and "makris-1996-force.html" in pages.namelist()
    page = pages.read("makris-1996-force.html").decode()
    assert '<script charset="utf-8" src="plotly.min.js"></script>' in page and '"format": "svg"' in page
    monkeypatch.setattr(
        export,
        "figure_images",
        lambda figures, image_format="png": {f"{f.key}.{image_format}": b"<svg/>" for f in figures},
    )
    app.button(key="rep.make_images").click().run()
    no_error(app)
    names = zipfile.ZipFile(io.BytesIO(downloads["makris-1996-figures.zip"])).namelist()
    assert names == [
        "makris-1996-pressure_drop.svg",
        "makris-1996-force.svg",
        "makris-1996-dynamic_range.svg",
        "makris-1996-sine_loops.svg",
    ]


# ------------------------------------------------------------------------------------------------ CLI
def test_cli_app_runs_streamlit_on_the_package_app(monkeypatch):
    import subprocess

    from click.testing import CliRunner

    from erdesign.cli import app as cli_app
    from erdesign.cli.main import cli

    calls = []
    monkeypatch.setattr(subprocess, "call", lambda cmd: calls.append(cmd) or 0)
    result = CliRunner().invoke(cli, ["app", "--port", "8765", "--headless"])
    assert result.exit_code == 0, result.output
    (cmd,) = calls
    assert cmd[1:4] == ["-m", "streamlit", "run"] and Path(cmd[4]) == Path(MAIN)
    assert cmd[5:] == ["--server.port", "8765", "--server.headless", "true"]
    assert cli_app.streamlit_command()[4] == cmd[4]


def edit_table(monkeypatch, at: AppTest, key_part: str, edits: dict[int, dict]) -> None:
    """Edit cells of the ``st.data_editor`` whose key contains ``key_part`` (AppTest has no data-editor widget):
    send, with every following run, the edits as a browser does (``{"edited_rows": {row: {column: value}}}``)."""
    from streamlit.proto.WidgetStates_pb2 import WidgetState
    from streamlit.testing.v1.element_tree import ElementTree

    (table,) = [d for d in at.dataframe if key_part in d.proto.id]
    widget_id = table.proto.id
    delta = json.dumps({"edited_rows": {str(r): c for r, c in edits.items()}, "added_rows": [], "deleted_rows": []})
    original = ElementTree.get_widget_states

    def with_edits(self):
        states = original(self)
        states.widgets.append(WidgetState(id=widget_id, string_value=delta))
        return states

    monkeypatch.setattr(ElementTree, "get_widget_states", with_edits)


def parameter_rows(at: AppTest) -> dict[str, dict]:
    (table,) = [d for d in at.dataframe if "sim.values" in d.proto.id]
    return {r["parameter"]: r for r in table.value.to_dict("records")}


def simulated_peak(at: AppTest) -> float:
    """Peak |force| [N] of the simulated time history, from the figure's data (full precision, in the axis' unit)."""
    fig = figure(at, "sim.fig.time")
    unit = re.search(r"\[(.+)\]", fig["layout"]["yaxis"]["title"]["text"]).group(1)
    F = values(fig["data"][-1]["y"])
    return float(Q_(np.max(np.abs(F)), unit.replace("·", "*")).to("N").magnitude)


@pytest.mark.parametrize("system", ["in-lbf-s", "mm-kN-s"])
def test_simulate_parameters_typed_in_the_unit_system(app, monkeypatch, system):
    """Issue 14: the Simulate parameter table reads and is typed in the unit system chosen; a value typed there
    reaches the model as the same SI value (pint), so the simulation is the one of the SI value typed in SI."""
    friction_N = 200.0
    app.switch_page("simulate.py").run()
    app.multiselect(key="sim.effects").select("seal_friction").run()
    no_error(app)
    rows = parameter_rows(app)
    assert rows["friction_force"]["unit"] == "N" and rows["viscosity_factor"]["unit"] == "-"
    default_N = rows["friction_force"]["value"]
    row = list(rows).index("friction_force")
    peak_default = simulated_peak(app)
    edit_table(monkeypatch, app, "sim.values", {row: {"value": friction_N}})
    app.run()
    no_error(app)
    peak_si = simulated_peak(app)
    assert peak_si > peak_default  # the edit reached the model: more friction (200 N > 112 N), more force
    monkeypatch.undo()

    unit = {"in-lbf-s": "lbf", "mm-kN-s": "kN"}[system]
    app.radio(key=state.UNITS).set_value(system).run()
    no_error(app)
    rows = parameter_rows(app)
    assert rows["friction_force"]["unit"] == unit
    # 1 lbf = 4.4482216152605 N exactly (the international pound-force, NIST SP 811 B.8); 1 kN = 1000 N
    per_unit = {"lbf": 4.4482216152605, "kN": 1000.0}[unit]
    # the value typed in SI is carried over, converted, and the simulation is unchanged (it was reset to the
    # default before)
    # (shown to 4 significant figures: issue 26, "43241692.2085 N/m"; left as shown, it is the exact SI value)
    assert rows["friction_force"]["value"] == pytest.approx(friction_N / per_unit, rel=FOUR_FIGURES)
    assert rows["viscosity_factor"]["value"] == 1.0 and rows["viscosity_factor"]["unit"] == "-"
    assert simulated_peak(app) == pytest.approx(peak_si, rel=1e-12)
    # typing the default in this system's unit reaches the model as the SI default
    edit_table(monkeypatch, app, "sim.values", {row: {"value": default_N / per_unit}})
    app.run()
    no_error(app)
    assert simulated_peak(app) == pytest.approx(peak_default, rel=1e-9)
    monkeypatch.undo()
    # and back to SI: the default typed in the other system comes back, in N
    app.radio(key=state.UNITS).set_value("SI").run()
    no_error(app)
    assert parameter_rows(app)["friction_force"]["value"] == pytest.approx(default_N, rel=1e-12)
    assert simulated_peak(app) == pytest.approx(peak_default, rel=1e-9)
