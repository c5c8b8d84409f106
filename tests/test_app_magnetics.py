"""The app's Size page on a damper with a [coil] (issue 16): B(I), tau_y(I) and the coil figures of the library."""

import json

import pytest

pytest.importorskip("streamlit")
from streamlit.testing.v1 import AppTest  # noqa: E402

from erdesign.app import state  # noqa: E402
from erdesign.damper.files import load_example  # noqa: E402
from erdesign.magnetics import load_magnetic_circuit  # noqa: E402
from tests.test_app import MAIN, TIMEOUT, metric  # noqa: E402


@pytest.fixture
def coil_app():
    state.clear_caches()
    at = AppTest.from_file(MAIN, default_timeout=TIMEOUT).run()
    at.selectbox(key="size.example").select("mr_coil").run()
    assert not at.exception, at.exception
    return at


def test_size_page_shows_the_circuit(coil_app):
    at = coil_app
    assert at.text_input(key="size.field").value == "2 A"
    c = load_magnetic_circuit("erdesign/examples/mr_coil.toml")
    # the coil figures at the rated current are the circuit's, to the 4 figures shown
    assert metric(at, "time constant L/R at I").m_as("s") == pytest.approx(float(c.time_constant(2.0)[0]), rel=5e-4)
    assert metric(at, "coil power I²R at I").m_as("W") == pytest.approx(4.0 * c.resistance, rel=5e-4)
    assert metric(at, "gap flux density B_g at I").m_as("T") == pytest.approx(
        float(c.state(2.0).gap_flux_density[0]), rel=5e-4
    )
    charts = [ch for ch in at.get("plotly_chart") if "size.fig.magnetics" in ch.proto.id]
    data = json.loads(charts[0].proto.spec)["data"]
    assert [t["name"] for t in data] == ["gap flux density B_g", "yield stress τ_y"]
    # the force at the design point goes through the circuit too (Damper.size of the damper file)
    r = load_example("mr_coil").size(velocity=at.text_input(key="size.velocity").value, field="2 A")
    assert metric(at, "force F").m_as("N") == pytest.approx(r.force.m_as("N"), rel=5e-4)
