"""The app's Design page (issue 26) through Streamlit's AppTest: requirements with units, the search, the ranked
designs and the Pareto front, the conflicts, and "open this design" - after which Size, Simulate and Report show the
design found, with the numbers the library gives for it."""

from __future__ import annotations

import dataclasses

import pytest
from streamlit.testing.v1 import AppTest

from erdesign.design import design, load_example_requirements

from .test_app import (
    MAIN,
    TIMEOUT,
    _clear_caches,  # noqa: F401  (autouse: caches cleared before each test)
    figure,
    metric,
    no_error,
    values,
)

SAMPLES = 2048


@pytest.fixture
def page() -> AppTest:
    at = AppTest.from_file(MAIN, default_timeout=TIMEOUT).run()
    at.switch_page("design.py").run()
    no_error(at)
    return at


def search(at: AppTest, example: str = "makris_requirements") -> AppTest:
    if at.selectbox(key="designer.example").value != example:
        at.selectbox(key="designer.example").set_value(example).run()
    at.number_input(key="designer.samples").set_value(SAMPLES).run()
    at.button(key="designer.search").click().run()
    assert not at.exception, at.exception
    return at


def library(example: str):
    """The same search straight from the library (same requirements, sample and seed: the same designs)."""
    return design(load_example_requirements(example).with_search(samples=SAMPLES, designs=10))


def test_search_open_and_size_shows_the_design(page):
    found = library("makris_requirements")
    best = found.designs[0]
    search(page)
    no_error(page)
    (table,) = [t.value for t in page.table if "force F [kN]" in t.value]
    assert len(table) == len(found.designs)
    # the table shows the library's figures at point 1, to its four figures
    assert float(table["force F [kN]"][0]) == pytest.approx(best["force_N"] / 1e3, rel=5e-4)
    assert float(table["dynamic range F/F0"][0]) == pytest.approx(best["dynamic_range"], rel=5e-4)
    # the Pareto front: one marker per feasible front design, and the ranked designs over it
    fig = figure(page, "designer.fig.pareto")
    front = next(t for t in fig["data"] if t["name"].startswith("Pareto front"))
    assert len(values(front["x"])) == len(found.pareto)

    page.button(key="designer.open").click().run()
    no_error(page)
    assert "Design 1" in page.success[0].value
    page.switch_page("size.py").run()
    no_error(page)
    assert page.text_input(key="size.geo.gap").value == best["geometry"]["gap"]
    # the example box no longer names the example the session started from (it said "makris")
    assert page.selectbox(key="size.example").value == "(the current design)"
    # makris_requirements' point: 1 in/s and 3 kV/mm; Size computes the force of the opened file itself
    assert metric(page, "force F").to("N").magnitude == pytest.approx(best["force_N"], rel=5e-4)
    assert metric(page, "force F").to("N").magnitude >= 6000.0  # the requirement min_force = 6 kN
    page.switch_page("simulate.py").run()
    no_error(page)
    page.switch_page("report.py").run()
    no_error(page)
    assert any("makris-like requirements #1" in m.value for m in page.markdown)


def test_conflicts_are_the_librarys_and_nothing_opens(page):
    found = library("infeasible_requirements")
    search(page, "infeasible_requirements")
    expected = f"No design meets every requirement: {len(found.conflicts)} conflict(s)."
    assert [e.value for e in page.error] == [expected]
    shown = "\n".join(m.value for m in page.markdown)
    for conflict in found.conflicts:
        assert f"- {conflict}" in shown
    (nearest,) = [t.value for t in page.table]
    assert list(nearest["rank"]) == ["nearest"]
    assert any(m.value.startswith("- nearest design: short of") and "min_force" in m.value for m in page.markdown)
    assert not [b for b in page.button if b.key == "designer.open"]


def test_inputs_follow_the_unit_system_and_a_bad_value_names_its_key(page):
    assert page.text_input(key="designer.req.design.limits.max_outer_diameter").value == "44 mm"
    page.text_input(key="designer.req.design.limits.max_length").set_value("0.13 m").run()  # edited
    page.sidebar.radio(key="app.units").set_value("in-lbf-s").run()
    # 1 in/s (makris_requirements), 44 mm = 1.73228 in and 130 mm = 5.11811 in (/ 25.4) in the inch system
    assert page.text_input(key="designer.req.design.point.0.velocity").value == "1 in/s"
    assert page.text_input(key="designer.req.design.limits.max_outer_diameter").value == "1.73228 in"
    assert page.text_input(key="designer.req.design.limits.max_length").value == "5.11811 in"
    assert page.text_input(key="designer.req.fluid.material").value == "makris-zeolite-silicone"
    page.text_input(key="designer.req.design.point.0.min_force").set_value("6 kg").run()
    (error,) = [e.value for e in page.error]
    assert "min_force" in error and "force" in error and "\n" not in error
    page.text_input(key="designer.req.design.point.0.min_dynamic_range").set_value("high").run()
    assert any("min_dynamic_range" in e.value for e in page.error)


# ------------------------------------------------------------------------------------------------ pinned designs
def _table(at: AppTest) -> dict:
    (table,) = [t.value for t in at.table if "pinned 1" in t.value]
    return {r["quantity"]: r for r in table.to_dict("records")}


def test_several_pinned_designs_side_by_side_with_changes_against_this_design():
    from erdesign import load_example
    from erdesign.app import state
    from erdesign.units import Q_

    at = AppTest.from_file(MAIN, default_timeout=TIMEOUT).run()
    assert at.button(key="size.pin").label == "Pin this design"  # short: never cut at 1280 px
    at.button(key="size.pin").click().run()  # pinned 1: Makris, gap 0.8 mm
    at.text_input(key="size.geo.gap").set_value("0.6 mm").run()
    at.button(key="size.pin").click().run()  # pinned 2: gap 0.6 mm
    at.text_input(key="size.geo.gap").set_value("0.7 mm").run()  # this design
    no_error(at)
    rows = _table(at)
    assert [rows["gap h"][k] for k in ("this design", "pinned 1", "pinned 2")] == ["0.7 mm", "0.8 mm", "0.6 mm"]
    # inputs: (0.8 / 0.7 - 1) = +14.3 %, (0.6 / 0.7 - 1) = -14.3 %
    assert rows["gap h"]["pinned 1 vs this"] == "+14.3 %" and rows["gap h"]["pinned 2 vs this"] == "-14.3 %"
    # outputs: the library's own forces of the three gaps at the design point (25 mm/s, 3 kV/mm)
    makris = load_example("makris")
    force = {
        h: dataclasses.replace(makris, geometry=makris.geometry.with_(gap=f"{h} mm"))
        .size("25 mm/s", "3 kV/mm")
        .force.m_as("N")
        for h in (0.6, 0.7, 0.8)
    }
    for name, h in (("pinned 1", 0.8), ("pinned 2", 0.6)):
        assert Q_(rows["force F"][name]).m_as("N") == pytest.approx(force[h], rel=5e-4)
        shown = float(rows["force F"][f"{name} vs this"].split()[0])
        assert shown == pytest.approx(100 * (force[h] / force[0.7] - 1), abs=0.06)
    # the force-velocity comparison draws every pinned design, each in its own dash (only pinned 1 was drawn)
    fig = figure(at, "size.fig.compare")
    dash = {t["name"]: t["line"]["dash"] for t in fig["data"]}
    assert dash["E = 3 kV/mm"] == "solid"
    assert dash["pinned 1, E = 3 kV/mm"] == "dash" and dash["pinned 2, E = 3 kV/mm"] == "dot"
    # pinned 2 (gap 0.6 mm) lies above this design (0.7 mm) at every speed: the narrower gap carries more force
    this, two = (values(t["y"]) for t in fig["data"] if t["name"] in ("E = 3 kV/mm", "pinned 2, E = 3 kV/mm"))
    assert (two >= this).all() and two[-1] > this[-1]
    # the first pinned is the baseline of Simulate and Report; unpinning it makes the next one the baseline
    assert at.session_state[state.BASELINE]["spec"]["geometry"]["gap"] == "0.8 mm"
    at.selectbox(key="size.unpin.which").set_value(0).run()
    at.button(key="size.unpin").click().run()
    no_error(at)
    assert at.session_state[state.BASELINE]["spec"]["geometry"]["gap"] == "0.6 mm"
    assert _table(at)["gap h"]["pinned 1"] == "0.6 mm"


def test_an_opened_design_sets_the_control_of_simulate_too(page):
    """A coil design (controlled by a current) and then an MR design controlled by a field: each time Size shows the
    library's force of the opened design and Simulate starts at its control, in its unit."""
    # the first design point of each requirements file: 2 A of coil current; 200 kA/m of field strength
    for example, control in (("mr_coil_requirements", "2 A"), ("mr_requirements", "200 kA/m")):
        found = library(example)
        search(page, example)
        page.button(key="designer.open").click().run()
        page.switch_page("size.py").run()
        no_error(page)
        assert metric(page, "force F").to("N").magnitude == pytest.approx(found.designs[0]["force_N"], rel=5e-4)
        page.switch_page("simulate.py").run()
        no_error(page)  # no "expected a magnetic field strength, got '2 A'"
        assert page.text_input(key="sim.field").value == control
        page.switch_page("design.py").run()
