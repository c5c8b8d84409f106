"""Engineering reports: the numbers printed are the library's, every quantity has a unit, the HTML is offline.

The Makris damper (Makris et al. 1996) is the reference case: the report must print its damping constant (eq 15,
120 kN s/m), its forces and Reynolds numbers as the library computes them.  Numbers are printed to 4 significant
figures, so a printed value agrees with the library to 5e-4 relative (half a unit in the 4th digit of a number
whose leading digit is 1); that is the tolerance of every comparison below.
"""

import json
import re
import warnings
from html.parser import HTMLParser
from pathlib import Path

import jinja2
import numpy as np
import pytest

import erdesign.cli.report  # noqa: F401  (registers the command until erdesign/cli/__init__.py imports it)
from erdesign import load_example
from erdesign.cli import main
from erdesign.damper.files import damper_from_dict, load_damper
from erdesign.errors import ErdesignError, UnitError, ValidityWarning
from erdesign.report import (
    ErrorHistoryStep,
    MeasurementComparison,
    build_report,
    render_html,
    render_markdown,
    show,
    write_report,
)
from erdesign.units import Q_

ROUNDING = 5e-4  # 4 significant figures (module docstring)
ROOT = Path(__file__).resolve().parents[1]
MAKRIS = str(ROOT / "erdesign" / "examples" / "makris.toml")


@pytest.fixture(scope="module")
def makris_report():
    return build_report(MAKRIS, velocity_range=("0 in/s", "2 in/s"), fields=["1.5 kV/mm", "3 kV/mm"])


@pytest.fixture(scope="module")
def html(makris_report):
    return render_html(makris_report)


@pytest.fixture(scope="module")
def markdown(makris_report):
    return render_markdown(makris_report)


def parse_quantity(text):
    """A printed quantity back into pint ("120.3 kN·s/m", "7.768 cm²", "1.8 %", "0.04366")."""
    t = text.replace("·", "*").replace("²", "**2").replace("³", "**3").replace("%", "percent")
    q = Q_(t)
    return q if hasattr(q, "units") else Q_(float(q), "")


def close(printed, expected):
    """printed (text) equals expected (quantity) to the rounding of 4 significant figures."""
    q = parse_quantity(printed)
    assert q.dimensionality == expected.dimensionality, (printed, expected)
    assert q.to(expected.units).magnitude == pytest.approx(expected.magnitude, rel=ROUNDING, abs=1e-12), printed


class Spans(HTMLParser):
    """Collect the quantity spans of a report and the text of its value cells outside them."""

    def __init__(self):
        super().__init__()
        self.spans, self.cells = {}, []
        self._span = None
        self._cell = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "td" and a.get("class") == "value":
            self._cell = ""
        if tag == "span" and a.get("class") == "q":
            self._span = {"id": a.get("id"), "si": float(a["data-si"]), "si_unit": a["data-si-unit"], "text": ""}

    def handle_endtag(self, tag):
        if tag == "span" and self._span is not None:
            self.spans[self._span["id"] or f"anon{len(self.spans)}"] = self._span
            self._span = None
        if tag == "td" and self._cell is not None:
            self.cells.append(self._cell)
            self._cell = None

    def handle_data(self, data):
        if self._span is not None:
            self._span["text"] += data
        elif self._cell is not None:
            self._cell += data


@pytest.fixture(scope="module")
def spans(html):
    parser = Spans()
    parser.feed(re.sub(r"<script.*?</script>", "", html, flags=re.DOTALL))
    return parser


# ------------------------------------------------------------------------------------- numbers against the library
def test_html_damping_constant_and_area_are_the_librarys(spans):
    d = load_example("makris")
    # Makris eq 15: C = 120 kN s/m for this damper (the paper's own number, 690 lb s/in).
    close(spans.spans["q-damping_constant"]["text"], Q_(120.3e3, "N*s/m"))
    close(spans.spans["q-damping_constant"]["text"], d.damping_constant())
    close(spans.spans["q-piston_area"]["text"], Q_(d.geometry.piston_area, "m^2"))


def test_html_design_table_is_the_librarys_state(makris_report, spans):
    d = load_example("makris")
    v = 2 * 0.0254  # the design velocity: top of the range, 2 in/s
    cols = makris_report.design_table.columns
    i_force = cols.index(next(c for c in cols if c.startswith("force F")))
    i_re = cols.index(next(c for c in cols if c.startswith("Reynolds")))
    i_dp = cols.index(next(c for c in cols if c.startswith("pressure drop")))
    for i, E in enumerate([0.0, 1.5e6, 3e6]):
        s = d.state(v, E)
        close(spans.spans[f"q-design-{i}-{i_force}"]["text"], Q_(s.force, "N"))
        close(spans.spans[f"q-design-{i}-{i_dp}"]["text"], Q_(s.pressure_drop, "Pa"))
        close(spans.spans[f"q-design-{i}-{i_re}"]["text"], Q_(s.reynolds, ""))


def test_html_sine_energy_is_the_librarys(makris_report, spans):
    d = load_example("makris")
    X0, f = 0.01, 2 * 0.0254 / (2 * np.pi * 0.01)  # default 10 mm; peak velocity = top of the range
    for i, E in enumerate(["0 kV/mm", "1.5 kV/mm", "3 kV/mm"]):
        r = d.sine_response(Q_(X0, "m"), Q_(f, "Hz"), E, samples_per_cycle=480)
        close(spans.spans[f"q-sine-{i}-2"]["text"], Q_(r.energy_per_cycle, "J"))
        close(spans.spans[f"q-sine-{i}-3"]["text"], Q_(r.equivalent_damping, "N*s/m"))


def test_checks_carry_the_librarys_numbers(makris_report, spans):
    d = load_example("makris")
    # The largest Reynolds number of the sweep is at the top velocity and zero field (lowest viscosity).
    close(spans.spans["q-check-laminar-value"]["text"], Q_(d.state(2 * 0.0254, 0.0).reynolds, ""))
    close(spans.spans["q-check-thin_gap-value"]["text"], Q_(0.8 / 14.3, ""))
    share = 112.0 / d.state(2 * 0.0254, 0.0).force
    close(spans.spans["q-check-seal_friction-value"]["text"], Q_(share * 100, "percent"))
    assert [c.status for c in makris_report.checks] == ["pass", "pass", "info", "pass", "pass"]


def test_inputs_are_shown_as_given_and_in_si(makris_report, spans, markdown):
    gap = next(r for r in makris_report.inputs if r.key == "gap")
    assert gap.given == "0.8 mm" and gap.origin == "damper file"
    close(spans.spans["q-input-geometry-gap"]["text"], Q_(0.8e-3, "m"))
    assert "| fluid | `reference_field` | `3 kV/mm` | 3000000 V/m | damper file |" in markdown


def test_markdown_numbers_are_the_librarys(makris_report, markdown):
    d = load_example("makris")
    row = next(r for r in makris_report.derived if r.key == "damping_constant")
    line = next(ln for ln in markdown.splitlines() if ln.startswith(f"| {row.label} |"))
    close(line.split("|")[2].strip(), d.damping_constant())
    # The force-velocity table of the figure section: 11 velocities from 0 to 2 in/s, one column per control.
    table = tables(markdown)["Force versus velocity"]
    for cells in table["rows"]:
        v = parse_quantity(cells[0]).to("m/s").magnitude
        for E, cell in zip([0.0, 1.5e6, 3e6], cells[1:]):
            close(cell, Q_(d.state(v, E).force, "N"))


def test_markdown_loop_table_is_the_sine_through_the_library(markdown):
    # The loop table samples x = X0 sin(phi), v = X0 Omega cos(phi) at phi = 15, 45, ..., 345 degrees; the force is
    # the library's quasi-steady force at that velocity (independent of the sine integration).
    d = load_example("makris")
    X0, v_peak = 0.01, 2 * 0.0254
    table = tables(markdown)["Force-displacement and force-velocity loops"]
    assert len(table["rows"]) == 12
    for k, cells in enumerate(table["rows"]):
        phi = np.radians(15 + 30 * k)
        close(cells[0], Q_(X0 * np.sin(phi), "m"))
        close(cells[1], Q_(v_peak * np.cos(phi), "m/s"))
        for E, cell in zip([0.0, 1.5e6, 3e6], cells[2:]):
            close(cell, Q_(d.state(v_peak * np.cos(phi), E).force, "N"))


# ------------------------------------------------------------------------------------------- every number's unit
def test_every_html_quantity_has_its_unit_and_si_value(spans):
    assert len(spans.spans) > 60
    for key, s in spans.spans.items():
        q = parse_quantity(s["text"])
        if s["si_unit"] == "dimensionless":
            assert q.dimensionless, (key, s)
        else:
            expected = Q_(1.0, s["si_unit"])
            assert q.dimensionality == expected.dimensionality and not q.dimensionless, (key, s)
        # The printed number is the SI value, rounded.
        assert q.to_base_units().magnitude == pytest.approx(s["si"], rel=ROUNDING, abs=1e-12), (key, s)
        digits = re.sub(r"[^0-9]", "", s["text"].split()[0].lstrip("0.").split("e")[0])
        assert len(digits.rstrip("0")) <= 4, (key, s)  # consistent significant figures


def test_no_bare_number_in_a_value_cell(spans):
    # Every value cell prints its numbers through the unit helper (inside quantity spans) or says "(text)".
    for cell in spans.cells:
        assert not re.search(r"\d", cell), cell


def tables(markdown):
    """Markdown tables by the heading above them: {heading: {"columns": [...], "rows": [[...], ...]}}."""
    out, heading, lines = {}, None, markdown.splitlines()
    i = 0
    while i < len(lines):
        if lines[i].startswith("#"):
            heading = lines[i].lstrip("#").strip()
        if lines[i].startswith("|") and i + 1 < len(lines) and re.match(r"^\|[ :-]+\|", lines[i + 1]):
            columns = [c.strip() for c in lines[i].strip().strip("|").split("|")]
            rows = []
            i += 2
            while i < len(lines) and lines[i].startswith("|"):
                rows.append([c.strip() for c in lines[i].strip().strip("|").split("|")])
                i += 1
            out[heading] = {"columns": columns, "rows": rows}
            continue
        i += 1
    return out


def test_every_markdown_quantity_has_the_unit_of_its_column(markdown):
    checked = 0
    for heading, t in tables(markdown).items():
        for j, column in enumerate(t["columns"]):
            m = re.search(r"\[([^\]]+)\]$", column)
            if m is None:
                continue
            unit = m[1].replace("·", "*").replace("²", "**2").replace("³", "**3")
            for row in t["rows"]:
                q = parse_quantity(row[j])
                if unit == "-":
                    assert q.dimensionless, (heading, column, row[j])
                else:
                    assert q.dimensionality == Q_(1.0, unit).dimensionality, (heading, column, row[j])
                    assert not q.dimensionless and row[j].split()[-1] == m[1], (heading, column, row[j])
                checked += 1
    assert checked > 150


# ---------------------------------------------------------------------------------------------- offline, strict
def test_html_embeds_plotly_once_and_loads_nothing(html, makris_report):
    assert not re.search(r"<script[^>]*\bsrc\s*=", html)
    assert not re.search(r"<link[^>]*\bhref\s*=\s*[\"']https?:", html)
    assert len(re.findall(r"plotly\.js v\d", html)) == 1  # the library, embedded once
    assert html.count('class="plotly-graph-div"') == len(makris_report.figures) == 4


def test_templates_are_strict(makris_report):
    class Incomplete:  # has what the renderer reads in Python, lacks what the template reads
        title = "x"
        history = ()

    with pytest.raises(jinja2.UndefinedError):
        render_markdown(Incomplete())


def test_the_unit_helper_fails_loudly():
    assert show(Q_(120345.6, "N*s/m"), "kN*s/m", name="C").text == "120.3 kN·s/m"
    with pytest.raises(UnitError, match=r"report: force: cannot show 3 kg \(a mass\) in kN \(a force\)"):
        show(Q_(3, "kg"), "kN", name="force")
    with pytest.raises(UnitError, match="report: force: the number 3.0 has no unit"):
        show(3.0, "kN", name="force")
    assert show(float("nan"), "", name="dynamic range").text == "undefined"


# ------------------------------------------------------------------------------------------------- the checks
def test_low_velocity_warns_of_seal_friction_and_of_the_plug():
    d = load_example("makris")
    r = build_report(d, velocity_range=("0 mm/s", "0.01 mm/s"), fields=["3 kV/mm"])
    status = {c.key: c for c in r.checks}
    # At 0.01 mm/s the zero-field force is C v + F_s = 1.2 N + 112 N: the seals take 99 %.
    assert status["seal_friction"].status == "warn"
    assert parse_quantity(status["seal_friction"].value.text).to("").magnitude == pytest.approx(
        112.0 / d.state(0.01e-3, 0.0).force, rel=ROUNDING
    )
    # At 3 kV/mm the plug fills 91 % of the gap (Makris eqs 5-7); the check warns above 90 %.
    close(status["plug"].value.text, Q_(d.state(0.01e-3, 3e6).plug_fraction, ""))
    assert status["plug"].status == "warn"


def test_field_outside_the_material_range_warns(tmp_path):
    path = tmp_path / "mr.toml"
    path.write_text(
        'name = "mr"\n[geometry]\nconfiguration = "mixed"\nduct_length = "25 mm"\ngap = "1 mm"\n'
        'piston_diameter = "40 mm"\nrod_diameter = "12 mm"\n[fluid]\nmaterial = "lord-mrf-132dg"\n'
    )
    with pytest.warns(ValidityWarning, match="300 kA/m is outside the range 0 to 250 kA/m"):
        r = build_report(path, fields=["300 kA/m"], velocity_range=("0 m/s", "20 m/s"))
    status = {c.key: c.status for c in r.checks}
    assert status["field_range"] == "warn"
    assert status["laminar"] == "warn"  # 20 m/s in a 1 mm gap of a 0.112 Pa s fluid: Re about 5000
    assert r.material["name"] == "lord-mrf-132dg" and "saturating law" in r.material["law"]
    origins = {row.key: row.origin for row in r.inputs}
    assert origins["viscosity"] == "material lord-mrf-132dg"


# ------------------------------------------------------------------------------------------ the optional section
def test_measurement_section_only_when_given(markdown, html):
    assert "Measurement comparison" not in markdown and "Measurement comparison" not in html
    d = load_example("makris")
    x = np.linspace(0, 1, 50)
    r = build_report(
        d,
        fields=["3 kV/mm"],
        comparison=MeasurementComparison(
            "test.csv",
            esr=0.082,
            samples=50,
            rms_error="85 N",
            displacement=x * 1e-3,
            velocity=x * 1e-2,
            force_measured=x * 1e3,
            force_model=x * 1.1e3,
        ),
        history=[(0, "baseline", 0.31), ErrorHistoryStep(1, "seal_friction", 0.082)],
    )
    md = render_markdown(r)
    assert "## 7. Measurement comparison and error history (optional)" in md
    # the RMS error in the report's one force unit (kN: the curves' forces), not N beside the tables' kN
    assert "| ESR (Vivas-López et al., eq 7) | 0.082 |" in md and "| RMS force error | 0.085 kN |" in md
    assert "| 1 | seal_friction | 0.082 |" in md
    assert [f.key for f in r.figures][-2:] == ["measurement", "history"]
    page = render_html(r)
    assert 'id="measurement"' in page and page.count('class="plotly-graph-div"') == 6
    assert re.search(r'id="q-history-1"[^>]*>0.082</span>', page)
    with pytest.raises(ErdesignError, match=r"history\[0\].esr"):
        build_report(d, fields=["3 kV/mm"], history=[(0, "baseline", float("nan"))])


# ------------------------------------------------------------------------------------------------------ the CLI
def test_cli_writes_markdown_and_reports_json(tmp_path, capsys):
    out = tmp_path / "r.md"
    code = main(
        ["report", MAKRIS, "--velocity-range", "0 in/s", "1 in/s", "--field", "3 kV/mm", "--out", str(out), "--json"]
    )
    stdout, stderr = capsys.readouterr()
    data = json.loads(stdout)
    assert code == 0 and stderr == "" and data["format"] == "md" and data["warnings"] == 0
    assert [c["check"] for c in data["checks"]] == ["laminar", "thin_gap", "field_range", "plug", "seal_friction"]
    text = out.read_text()
    assert text.startswith("# Damper report: makris-1996") and "| 3 kV/mm |" in text


def test_cli_html_and_errors(tmp_path, capsys):
    out = tmp_path / "r.html"
    assert main(["report", MAKRIS, "--field", "3 kV/mm", "--out", str(out)]) == 0
    assert out.read_text().startswith("<!DOCTYPE html>") and "wrote" in capsys.readouterr().out
    code = main(["report", MAKRIS, "--field", "40 kA/m", "--out", str(out), "--force", "--json"])
    stdout, stderr = capsys.readouterr()
    assert code == 1 and stdout == "" and stderr.count("\n") == 1
    assert "field[0]: expected an electric field" in stderr


def test_write_report_chooses_the_format_from_the_suffix(tmp_path, makris_report):
    assert write_report(makris_report, tmp_path / "a.md").read_text().startswith("# ")
    with pytest.raises(ErdesignError, match="format: expected one of html, md"):
        write_report(makris_report, tmp_path / "a.pdf", "pdf")


def test_report_of_a_mixed_damper_from_python():
    d = load_damper(ROOT / "erdesign" / "examples" / "kamath_wereley.toml")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = build_report(d, velocity_range=("0 m/s", "0.1 m/s"), fields=["3 kV/mm"])
    keys = [e.key for e in r.equations]
    assert r.configuration == "mixed" and "flow" in keys and "damping_constant" in keys
    assert all(row.origin == "Python" for row in r.inputs)


def test_cli_default_name_no_overwrite_never_the_input(tmp_path, capsys, monkeypatch):
    """Issue 14: without --out the report is <damper name>-report.html; an existing file needs --force; the damper
    file itself is never overwritten."""
    monkeypatch.chdir(tmp_path)
    assert main(["report", MAKRIS]) == 0
    out, _ = capsys.readouterr()
    written = tmp_path / "makris-1996-report.html"
    assert written.read_text().startswith("<!DOCTYPE html>") and f"wrote {written.name}" in out
    before = written.stat().st_mtime_ns
    code = main(["report", MAKRIS])
    _, err = capsys.readouterr()
    assert code == 1 and "makris-1996-report.html: exists; give --force" in err and err.count("\n") == 1
    assert written.stat().st_mtime_ns == before
    assert main(["report", MAKRIS, "--force", "--format", "md"]) == 0
    assert (tmp_path / "makris-1996-report.md").read_text().startswith("# Damper report")
    copy = tmp_path / "d.toml"
    copy.write_text(Path(MAKRIS).read_text())
    code = main(["report", str(copy), "--out", str(copy), "--force"])
    _, err = capsys.readouterr()
    assert code == 1 and "that is the damper file itself" in err
    assert copy.read_text() == Path(MAKRIS).read_text()


def test_cli_design_point_and_bare_numbers(tmp_path, capsys):
    out = tmp_path / "r.md"
    code = main(["report", MAKRIS, "--design-velocity", "25 mm/s", "--design-field", "2 kV/mm", "--out", str(out)])
    stdout, stderr = capsys.readouterr()
    assert code == 0 and "at the design point 25 mm/s and 2 kV/mm" in stdout and stderr == ""
    text = out.read_text()
    force = load_damper(MAKRIS).size(velocity="25 mm/s", field="2 kV/mm").force
    (row,) = [line for line in text.splitlines() if line.startswith("| force F |")]
    close(row.split("|")[2].strip(), force)
    # a bare number is read in SI units, with a warning that says so
    code = main(["report", MAKRIS, "--design-velocity", "0.025", "--out", str(out), "--force"])
    _, stderr = capsys.readouterr()
    assert code == 0 and "warning: --design-velocity 0.025: a bare number, read as 0.025 m/s" in stderr


def test_report_from_the_content_of_a_damper_file_at_a_design_point():
    """The app's path: the spec as typed (a mapping), a design point inside the curves' range."""
    from erdesign.damper.files import read_toml

    spec = read_toml(MAKRIS)
    spec["geometry"]["gap"] = "0.0315 in"
    r = build_report(
        spec,
        velocity_range=("0 mm/s", "50 mm/s"),
        design_velocity="1 in/s",
        design_field="3 kV/mm",
        origin="as typed in the app",
    )
    assert r.setting("velocity_design").value.text == "25.4 mm/s"
    assert r.setting("velocity_max").value.text == "50 mm/s"
    gap = [row for row in r.inputs if row.key == "gap"][0]
    assert (gap.given, gap.origin) == ("0.0315 in", "as typed in the app")
    rows = {row.key: row for row in r.design_point}
    # Damper.size's doctest: 6.07 kN at 1 in/s and 3 kV/mm (the gap 0.0315 in is Makris's 0.8 mm to 0.01 %)
    assert rows["force"].value.text.startswith("6.07")
    # the design table's row at the design control is the design point
    (design_row,) = [row for row in r.design_table.rows if row[0].text == "3 kV/mm"]
    assert design_row[4].si == pytest.approx(rows["force"].value.si, rel=1e-12)


def test_baseline_section_is_the_librarys_design_point_of_each_design():
    """A report built with a baseline (issue 14, compare designs) shows both designs' design points: each number
    is Damper.size of that design, and the change is their ratio."""
    from erdesign.damper.files import read_toml
    from erdesign.examples import __file__ as examples

    spec = read_toml(Path(examples).with_name("makris.toml"))
    narrow = {**spec, "geometry": {**spec["geometry"], "gap": "0.6 mm"}}
    point = dict(design_velocity="25 mm/s", design_field="3 kV/mm")
    baseline = build_report(spec, **point)
    report = build_report(narrow, **point, baseline=baseline)
    rows = {r["key"]: r for r in report.baseline["rows"]}
    F_base = load_example("makris").size(velocity="25 mm/s", field="3 kV/mm").force.to("N").magnitude
    F_now = damper_from_dict(narrow, source="test").size(velocity="25 mm/s", field="3 kV/mm").force.to("N").magnitude
    assert rows["force"]["baseline"].si == pytest.approx(F_base, rel=1e-12)
    assert rows["force"]["this"].si == pytest.approx(F_now, rel=1e-12)
    assert rows["force"]["change"] == f"{100 * (F_now / F_base - 1):+.1f} %"
    # the inputs that differ, with the change of this design against the baseline: 0.6 / 0.8 - 1 = -25 %
    assert report.baseline["inputs"] == (
        {"key": "geometry.gap", "baseline": "0.8 mm", "this": "0.6 mm", "change": "-25.0 %"},
    )
    assert [f.key for f in report.figures][-1] == "baseline" and build_report(narrow, **point).baseline is None
    md = render_markdown(report)
    assert f"| force F | {rows['force']['baseline'].text} | {rows['force']['this'].text} |" in md


def test_figure_images_without_kaleido_or_a_browser_say_what_is_needed(monkeypatch, makris_report):
    """Static images are optional (kaleido and an installed Chrome/Chromium): their absence is a clear message."""
    import sys

    from erdesign.report.export import IMAGES_NEED, figure_images

    monkeypatch.setitem(sys.modules, "kaleido", None)  # `import kaleido` fails as when not installed
    with pytest.raises(ErdesignError, match="kaleido is not installed") as info:
        figure_images(makris_report.figures, "png")
    assert IMAGES_NEED in str(info.value) and "camera button" in str(info.value)
    monkeypatch.delitem(sys.modules, "kaleido")
    try:
        import kaleido
        from kaleido.errors import ChromeNotFoundError
    except ImportError:
        return

    class NoBrowser:  # what kaleido does on a machine without one
        def __init__(self, **kwargs):
            assert kwargs["mathjax"] is False  # never MathJax from a CDN

        async def __aenter__(self):
            raise ChromeNotFoundError("no chrome found")

        async def __aexit__(self, *exc):
            return False

    monkeypatch.setattr(kaleido, "Kaleido", NoBrowser)
    with pytest.raises(ErdesignError, match="ChromeNotFoundError: no chrome found; static figure images need"):
        figure_images(makris_report.figures, "svg")
    with pytest.raises(ErdesignError, match="image format"):
        figure_images(makris_report.figures, "jpeg")


@pytest.mark.slow
def test_figure_images_with_kaleido_and_an_installed_browser(makris_report):
    """Where kaleido and a Chromium are installed (not in CI), every figure becomes an SVG with its axis titles."""
    pytest.importorskip("kaleido")
    from choreographer.browsers.chromium import Chromium

    if Chromium.find_browser(skip_local=False) is None:
        pytest.skip("no Chrome or Chromium on this machine")
    from erdesign.report.export import figure_images, images_zip

    images = figure_images(makris_report.figures[:2], "svg")
    assert list(images) == ["pressure_drop.svg", "force.svg"]
    svg = images["force.svg"].decode()
    assert svg.startswith("<svg") and "force F [kN]" in svg and "E = 3 kV/mm" in svg
    import io
    import zipfile

    assert zipfile.ZipFile(io.BytesIO(images_zip(images))).namelist() == ["pressure_drop.svg", "force.svg"]


def test_html_figures_save_as_named_images(makris_report):
    """The camera button of each figure of the HTML report saves '<design>-<figure>.<format>'."""
    html = render_html(makris_report, "svg")
    configs = re.findall(r'"toImageButtonOptions": \{"format": "(\w+)", "filename": "([^"]+)"', html)
    assert configs and {f for f, _ in configs} == {"svg"}
    assert [n for _, n in configs] == [f"makris-1996-{f.key}" for f in makris_report.figures]
    assert "saves the figure as\nan image (SVG)" in html


def test_cli_figures_without_kaleido_is_one_line_and_writes_nothing(tmp_path, capsys, monkeypatch):
    """``--figures`` needs the optional kaleido: without it the command says what to install (exit 1, one line,
    no traceback) before it writes anything."""
    import sys

    from erdesign.report.export import IMAGES_NEED

    monkeypatch.setitem(sys.modules, "kaleido", None)  # `import kaleido` fails as when not installed
    out, figs = tmp_path / "r.html", tmp_path / "figs"
    code = main(["report", MAKRIS, "--out", str(out), "--figures", str(figs)])
    stdout, err = capsys.readouterr()
    assert code == 1 and stdout == ""
    assert err.startswith("error: --figures: kaleido is not installed;") and err.count("\n") == 1
    assert " ".join(IMAGES_NEED.split()) in err and "Traceback" not in err
    assert not out.exists() and not figs.exists()
    (tmp_path / "file").write_text("x")
    assert main(["report", MAKRIS, "--out", str(out), "--figures", str(tmp_path / "file")]) == 1
    assert "is a file; give a folder" in capsys.readouterr().err


def test_cli_figures_without_a_browser_is_one_line(tmp_path, capsys, monkeypatch):
    """kaleido without a Chrome or Chromium: the browser error, then what is needed, in one line (exit 1)."""
    kaleido = pytest.importorskip("kaleido")
    from kaleido.errors import ChromeNotFoundError

    class NoBrowser:  # what kaleido does on a machine without one
        def __init__(self, **kwargs):
            pass

        async def __aenter__(self):
            raise ChromeNotFoundError("no chrome found")

        async def __aexit__(self, *exc):
            return False

    monkeypatch.setattr(kaleido, "Kaleido", NoBrowser)
    out = tmp_path / "r.html"
    code = main(["report", MAKRIS, "--out", str(out), "--figures", str(tmp_path)])
    _, err = capsys.readouterr()
    assert code == 1 and err.count("\n") == 1
    assert "ChromeNotFoundError: no chrome found; static figure images need" in err
    assert not out.exists() and list(tmp_path.iterdir()) == []


@pytest.mark.slow
def test_cli_figures_with_kaleido_and_chromium(tmp_path, capsys):
    """Where kaleido and /usr/bin/chromium are installed, every figure of the report is a PNG (or SVG) file in
    the folder, named after the damper and the figure; existing files are kept without --force."""
    pytest.importorskip("kaleido")
    if not Path("/usr/bin/chromium").exists():
        pytest.skip("no /usr/bin/chromium on this machine")
    figs = tmp_path / "figs"
    code = main(["report", MAKRIS, "--out", str(tmp_path / "r.html"), "--figures", str(figs), "--json"])
    stdout, _ = capsys.readouterr()
    assert code == 0
    names = [f"makris-1996-{key}.png" for key in ("pressure_drop", "force", "dynamic_range", "sine_loops")]
    assert sorted(p.name for p in figs.iterdir()) == sorted(names)
    assert json.loads(stdout)["figures"] == [str(figs / n) for n in names]
    for name in names:
        assert (figs / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"  # the PNG signature (RFC 2083, 3.1)
    before = (figs / names[1]).stat().st_mtime_ns
    code = main(["report", MAKRIS, "--out", str(tmp_path / "s.html"), "--figures", str(figs)])
    _, err = capsys.readouterr()
    assert code == 1 and "exists; give --force" in err and not (tmp_path / "s.html").exists()
    assert (figs / names[1]).stat().st_mtime_ns == before
    code = main(
        [
            "report",
            MAKRIS,
            "--out",
            str(tmp_path / "r.html"),
            "--figures",
            str(figs),
            "--force",
            "--figure-format",
            "svg",
        ]
    )
    assert code == 0 and (figs / "makris-1996-force.svg").read_bytes().lstrip().startswith(b"<svg")


def test_the_error_historys_noise_floor_label_is_beside_the_plot_not_over_a_bar():
    """Issue 26 leftover: the label sat inside the plot at the right end of the floor line, over the last bar (a
    bar always reaches above the floor).  Now it is in the right margin, at the floor's height on the log axis."""
    import math
    from types import SimpleNamespace

    from erdesign.report.plots import error_history_figure

    steps = [SimpleNamespace(step=0, effect="baseline", esr=0.158), SimpleNamespace(step=1, effect="lag", esr=0.05)]
    fig = error_history_figure(steps, noise_floor=4.6e-5)
    (label,) = fig.layout.annotations
    assert label.xref == "paper" and label.x > 1 and label.xanchor == "left"
    assert label.y == pytest.approx(math.log10(4.6e-5))
    assert "4.6e-05" in label.text
    assert fig.layout.margin.r >= 90  # room for it
