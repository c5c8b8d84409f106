"""The report's magnetic section (issue 16): the numbers are those of the circuit, shown only with a [coil]."""

from importlib import resources

import pytest

from erdesign.magnetics import load_magnetic_circuit
from erdesign.report import build_report, render_markdown

MR_COIL = str(resources.files("erdesign.examples") / "mr_coil.toml")


@pytest.fixture(scope="module")
def report():
    return build_report(MR_COIL)


def test_magnetic_rows_are_the_circuit_at_the_rated_current(report):
    c = load_magnetic_circuit(MR_COIL)
    rows = {r.key: r.value for r in report.magnetics["rows"]}
    # Shown.si is the number rounded to four significant figures, in SI
    assert rows["time_constant"].si == pytest.approx(float(c.time_constant(2.0)[0]), rel=5e-4)  # 46.03 ms
    assert rows["coil_resistance"].si == pytest.approx(c.resistance, rel=5e-4)  # 2.648 ohm
    assert rows["power"].si == pytest.approx(4.0 * c.resistance, rel=5e-4)  # 10.59 W
    assert rows["gap_flux_density"].si == pytest.approx(float(c.state(2.0).gap_flux_density[0]), rel=5e-4)
    assert rows["knee_current"].si == pytest.approx(c.knee_current(), rel=5e-4)
    assert report.magnetics["limiting_part"] == "core" and report.magnetics["saturated"]
    # one row per control of the report (0, 1/3, 2/3, 1 x the rated current)
    table = report.magnetics["table"]
    assert [r[0].text for r in table.rows] == ["0 A", "0.6667 A", "1.333 A", "2 A"]
    assert table.rows[-1][3].si == pytest.approx(float(c.state(2.0).yield_stress[0]), rel=5e-4)
    assert report.figures[0].key == "magnetics"


def test_markdown_has_the_section_and_a_damper_without_coil_has_none(report):
    text = render_markdown(report)
    assert "### Magnetic circuit (coil of steel-1018, fluid lord-mrf-132dg)" in text
    assert "| time constant L/R at I | 46.03 ms |" in text
    makris = build_report(str(resources.files("erdesign.examples") / "makris.toml"))
    assert makris.magnetics is None and "Magnetic circuit" not in render_markdown(makris)


@pytest.mark.parametrize("system, unit", [("SI", "kPa"), ("mm-kN-s", "MPa"), ("in-lbf-s", "psi")])
def test_yield_stress_follows_the_unit_system(system, unit):
    """Issue 26 leftover: the circuit's tau_y read in kPa whatever the unit system; now in the system's pressure unit
    (the rated row, the table and the curve table alike), the same stress in each."""
    from erdesign.formatting import use_unit_system

    c = load_magnetic_circuit(MR_COIL)
    with use_unit_system(system):
        r = build_report(MR_COIL)
    table = r.magnetics["table"]
    assert table.columns[3] == f"τ_y [{unit}]"
    assert table.rows[-1][3].text.endswith(f" {unit}")
    assert table.rows[-1][3].si == pytest.approx(float(c.state(2.0).yield_stress[0]), rel=5e-4)
    rated = {row.key: row.value for row in r.magnetics["rows"]}["yield_stress_rated"]
    assert rated.text.endswith(f" {unit}")
    assert r.figures[0].table.columns[2] == f"τ_y [{unit}]"
    fig = r.figures[0].figure  # the figure's axis too, and its curve in that unit
    assert fig.layout.yaxis2.title.text == f"τ_y [{unit}]"
    (tau,) = [t for t in fig.data if t.name == "yield stress τ_y"]
    last = r.figures[0].table.rows[-1][2]  # the curve table's last row is the curve's last point (31 points, every 3rd)
    assert float(last.text.split()[0]) == pytest.approx(tau.y[-1], rel=5e-4)
