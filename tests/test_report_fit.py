"""A fit report as the app and the report show it (erdesign.report.fit) and the report's diagnosis section: values to
4 significant figures in prefixed units, uncertainties said plainly, CSV in SI that reads back to the fit's values."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest

from erdesign import load_example
from erdesign.formatting import use_unit_system
from erdesign.identification.fit import fit
from erdesign.parameters import Parameter
from erdesign.report import MeasurementComparison, build_report, render_html, render_markdown
from erdesign.report.fit import error_text, parameter_rows, parameters_csv, statistics_rows, value_text
from erdesign.units import Q_
from tests.test_fit import DashpotFriction, record


@pytest.fixture(scope="module")
def result():
    m, _ = record()
    return fit(DashpotFriction(), m, fixed={"k": 2.0e4})


def test_values_read_in_prefixed_units_to_four_figures():
    """Issue 26: "120300 MN s/m", "1.282e-16 g" and "43241692.2085 N/m" become readable values."""
    c = Parameter("c", "N*s/m", 1e4, 0.0, 1e12)
    assert value_text(c, 120345.6) == "120.3 kN·s/m"
    assert value_text(c, 1.203e11) == "1.203e+05 MN·s/m"  # beyond the largest unit: powers of ten
    assert value_text(Parameter("k", "N/m", 1e4, 0.0, 1e9), 43241692.2085) == "43.24 MN/m"
    assert value_text(Parameter("m", "kg", 1.0, 0.0, 10.0), 1.282e-19) == "0 kg"  # a value at its zero bound
    with use_unit_system("in-lbf-s"):
        # 1 lbf = 4.4482216152605 N (NIST SP 811, B.8): 400 N = 89.92 lbf
        assert value_text(Parameter("f", "N", 10.0, 0.0, 1e5), 400.0) == "89.92 lbf"


def test_uncertainties_say_plainly_what_they_are():
    c = Parameter("c", "N*s/m", 1e4, 0.0, 1e12)
    assert error_text(c, 5000.0, 50.0, "free") == ("± 0.05 kN·s/m", "1 %")  # in the value's unit (5 kN·s/m)
    # a standard error larger than the value (issue 26: "120300 MN s/m +- 120000000 MN s/m")
    assert error_text(c, 1.203e11, 1.2e14, "free") == ("larger than the value", "1e+05 %")
    assert error_text(c, 0.0, None, "at lower bound") == ("at lower bound", "")
    assert error_text(c, 5000.0, math.nan, "free") == ("not identifiable", "")
    assert error_text(c, 5000.0, None, "fixed") == ("fixed", "")


def test_parameter_rows_are_the_fits_numbers(result):
    rows = {r["parameter"]: r for r in parameter_rows(result)}
    assert rows["k"]["status"] == "fixed" and rows["k"]["± 1σ"] == "fixed"
    assert rows["c"]["status"] == "free" and rows["c"]["± 1σ"].startswith("± ")
    # the shown value is the fitted SI value to 4 significant figures
    assert Q_(rows["c"]["value"].replace("·", "*")).to("N*s/m").magnitude == pytest.approx(result.values["c"], rel=5e-4)
    assert rows["c"]["bounds"] == "0 kN·s/m to 10 MN·s/m"
    stats = {r["quantity"]: r["value"] for r in statistics_rows(result)}
    assert stats["free parameters"] == "2" and float(stats["R²"]) == pytest.approx(1 - result.esr, rel=5e-4)


def test_parameters_csv_reads_back_to_the_fitted_values(result):
    """Numbers in the cells, SI units in the headers: the CSV round-trips to the fit's values and errors."""
    lines = [line for line in parameters_csv(result, comment="test").splitlines() if not line.startswith("#")]
    table = {row["quantity"]: row for row in csv.DictReader(lines)}
    assert set(table["value"]) == {"quantity", "c [N*s/m]", "f [N]", "k [N/m]"}
    for name, unit in (("c", "N*s/m"), ("f", "N"), ("k", "N/m")):
        assert float(table["value"][f"{name} [{unit}]"]) == pytest.approx(result.values[name], rel=1e-9)
    assert float(table["stderr"]["c [N*s/m]"]) == pytest.approx(result.stderr["c"], rel=1e-9)
    assert table["stderr"]["k [N/m]"] == ""  # fixed: no standard error
    assert float(table["upper bound"]["c [N*s/m]"]) == 1e7


def test_the_report_states_the_verdict_and_the_calibration(result):
    """Issue 26: the report had no verdict, no calibrated parameters, no uncertainties and no noise floor."""
    x = np.linspace(0, 1, 50)
    comparison = MeasurementComparison(
        "test.csv",
        esr=0.00238,
        samples=1401,
        rms_error="242.9 N",
        verdict="missing_effect",
        reason="Adding seal_friction lowers the ESR from 0.00238 to 3.86e-05.",
        noise_floor_esr=2.71e-05,
        parameters=tuple(parameter_rows(result)),
        statistics=tuple(statistics_rows(result)),
        displacement=x * 1e-3,
        velocity=x * 1e-2,
        force_measured=x * 1e3,
        force_model=x * 1.1e3,
    )
    report = build_report(
        load_example("makris"),
        fields=["3 kV/mm"],
        comparison=comparison,
        history=[(0, "baseline", 0.00238), (1, "seal_friction", 3.86e-05)],
    )
    md = render_markdown(report)
    assert "| ESR (Vivas-López et al., eq 7) | 0.00238 |" in md
    assert "| noise floor ESR (the same samples) | 2.71e-05 |" in md  # as the verdict prints it
    assert "**Verdict: a missing effect.** Adding seal_friction lowers the ESR" in md
    c = next(r for r in parameter_rows(result) if r["parameter"] == "c")
    assert f"| `c` | {c['value']} | {c['± 1σ']} | {c['±']} |" in md
    html = render_html(report)
    assert 'id="verdict"' in html and 'id="table-calibration"' in html
    # the error history's figure draws the floor of the comparison
    (history,) = [f for f in report.figures if f.key == "history"]
    assert [s.y0 for s in history.figure.layout.shapes] == [2.71e-05]
    with pytest.raises(Exception, match="comparison.verdict"):
        build_report(load_example("makris"), comparison=MeasurementComparison("t", esr=0.1, verdict="maybe"))
