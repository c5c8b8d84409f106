"""Tolerance studies (erdesign/campaign/tolerance.py, ``erdesign tolerance``): the same numbers on every executor,
quantiles against closed form, Sobol indices against a one-at-a-time linearisation, clear errors."""

import json
import math

import numpy as np
import pytest
from scipy.special import ndtri

from erdesign import load_example
from erdesign.campaign.tolerance import (
    OUTPUTS,
    ToleranceError,
    ToleranceStudy,
    evaluate_samples,
    parse_variation,
    tolerance_study,
)
from erdesign.cli import main

VARY = ["geometry.gap=0.8 mm +- 0.02 mm", "fluid.viscosity=+-10 %", "fluid.yield_stress=+-15 %"]
VARY_ARGS = [arg for v in VARY for arg in ("--vary", v)]


@pytest.fixture(scope="module")
def makris():
    return load_example("makris")


def run(capsys, *args):
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize(
    "example, field", [("makris", 3e6), ("kamath_wereley", None), ("mr_valve_current", 1.0), ("mr_mixed", None)]
)
def test_nominal_sample_is_damper_size(example, field):
    """A sample at the file's values gives what ``erdesign size`` gives (the same kernel), to rounding."""
    d = load_example(example)
    E = d.fluid.reference_field if field is None else field
    r = d.size(velocity="0.05 m/s", field=f"{E} {d.fluid.control_unit}").as_json()
    vary = tuple(
        parse_variation(s, d)
        for s in (
            "geometry.gap=+-1 %",
            "fluid.viscosity=+-5 %",
            "fluid.yield_stress=+-5 %",
            "geometry.duct_length=+-1 %",
        )
    )
    study = ToleranceStudy(d, 0.05, float(E), vary)
    y = evaluate_samples(study, np.array([[v.nominal for v in vary]]))
    for key in OUTPUTS:
        assert y[key][0] == pytest.approx(r[key], rel=1e-12), key


def test_quantiles_of_a_linear_output_are_the_normal_quantiles(makris):
    """C = 12 eta0 L Ap^2 / (pi d h^3) is linear in eta0 (Makris eq 15): with eta0 normal (sd 5 %), the quantiles of
    C are C0 (1 + 0.05 z_p).  Tolerance: 4 standard errors of a sample quantile, sqrt(p(1-p)/n)/phi(z_p), in C0 0.05
    units (2.6e-4 C0 at the 1 % quantile with 4e5 samples)."""
    n = 400_000
    r = tolerance_study(makris, ["fluid.viscosity=+-5 %"], velocity=0.0254, samples=n, seed=7, sensitivity=False)
    C0 = makris.damping_constant_si()
    assert r.nominal["damping_constant_N_s_per_m"] == pytest.approx(C0, rel=1e-12)
    for q, value in r.quantiles["damping_constant_N_s_per_m"].items():
        p = int(q) / 100
        z = ndtri(p)
        se = math.sqrt(p * (1 - p) / n) / (math.exp(-z * z / 2) / math.sqrt(2 * math.pi))
        assert value == pytest.approx(C0 * (1 + 0.05 * z), abs=4 * se * 0.05 * C0), q
    assert r.rejected == 0


def test_sobol_indices_match_one_at_a_time_linearisation(makris):
    """Newtonian case (zero field): C ~ eta0 / h^3, so ln C is additive in ln eta0 and ln h.  At small tolerances the
    first-order indices are the linearised variance shares (g_i s_i)^2 / sum_j (g_j s_j)^2, with the elasticities
    g_i = d ln C / d ln x_i found one at a time by central differences (-3 for the gap, 1 for the viscosity), and
    first-order = total (no interaction), summing to 1.  Tolerance: 3 bootstrap half-widths of SALib's 95 %
    interval, plus 0.005 for the linearisation (the tolerances are 1-2 %, second-order terms ~ 1e-4)."""
    vary = ["geometry.gap=+-1 %", "fluid.viscosity=+-2 %"]
    r = tolerance_study(makris, vary, velocity=0.0254, field=0.0, samples=200_000, seed=11)
    variations = r.study.variations
    x0 = np.array([[v.nominal for v in variations]])
    shares = []
    for j, v in enumerate(variations):
        step = 1e-6
        up, down = x0.copy(), x0.copy()
        up[0, j] *= 1 + step
        down[0, j] *= 1 - step
        cu = evaluate_samples(r.study, up)["damping_constant_N_s_per_m"][0]
        cd = evaluate_samples(r.study, down)["damping_constant_N_s_per_m"][0]
        g = (math.log(cu) - math.log(cd)) / (2 * step)
        shares.append((g * v.delta / v.nominal) ** 2)
    assert shares[0] / shares[1] == pytest.approx(9 * 0.01**2 / 0.02**2, rel=1e-4)  # g = -3 and 1
    expected = np.array(shares) / sum(shares)
    s = r.sensitivity["damping_constant_N_s_per_m"]
    total_first = 0.0
    for j, v in enumerate(variations):
        si = s[v.key]
        assert si["first"] == pytest.approx(expected[j], abs=3 * si["first_conf"] + 0.005), v.key
        assert si["total"] == pytest.approx(expected[j], abs=3 * si["total_conf"] + 0.005), v.key
        assert si["first_conf"] < 0.05
        total_first += si["first"]
    assert total_first == pytest.approx(1.0, abs=0.03)
    # the field force does not vary with the yield stress, which is not varied: no key for it
    assert set(s) == {"geometry.gap", "fluid.viscosity"}
    # at zero field the force is the zero-field force, and the dynamic range is 1 and does not vary
    assert r.quantiles["force_N"] == r.quantiles["zero_field_force_N"]
    assert all(si["first"] is None for si in r.sensitivity["dynamic_range"].values())


def test_same_seed_same_numbers_serial_and_pool(makris):
    a = tolerance_study(makris, VARY, velocity=0.0254, field=3e6, samples=150_000, seed=5, jobs=1)
    b = tolerance_study(makris, VARY, velocity=0.0254, field=3e6, samples=150_000, seed=5, jobs=2)
    c = tolerance_study(makris, VARY, velocity=0.0254, field=3e6, samples=150_000, seed=6, jobs=1)
    assert a.quantiles == b.quantiles and a.sensitivity == b.sensitivity and a.mean == b.mean
    assert a.quantiles != c.quantiles


@pytest.mark.slow
def test_one_million_samples_same_quantiles_serial_pool_and_dask(makris, dask_client):
    """Done-when of issue 24: 1e6 samples on the local pool and on a Dask LocalCluster, the same quantiles (and
    Sobol indices) as serially, with the same seed."""
    kwargs = {"velocity": 0.0254, "field": 3e6, "samples": 1_000_000, "seed": 2024}
    serial = tolerance_study(makris, VARY, jobs=1, **kwargs)
    pool = tolerance_study(makris, VARY, jobs=2, **kwargs)
    dask = tolerance_study(makris, VARY, executor=dask_client, **kwargs)
    assert "Dask" in dask.executor and "pool" in pool.executor
    for other in (pool, dask):
        assert other.quantiles == serial.quantiles
        assert other.sensitivity == serial.sensitivity
    # the spread is the one of the tolerances: the gap (sd 2.5 %) dominates the force, F ~ h^-3 at Bi = 0.2
    q = serial.quantiles["force_N"]
    assert q["1"] < q["5"] < q["50"] < q["95"] < q["99"]
    assert q["50"] == pytest.approx(serial.nominal["force_N"], rel=0.005)
    assert serial.sensitivity["force_N"]["geometry.gap"]["first"] > 0.9


def test_non_physical_draws_are_rejected_and_counted(makris):
    # gap 0.8 mm with sd 0.4 mm: P(h <= 0) = Phi(-2) = 2.3 %
    r = tolerance_study(
        makris, ["geometry.gap=+-50 %"], velocity=0.0254, samples=20_000, seed=1, sensitivity=False, keep_samples=True
    )
    assert r.samples["geometry.gap"].min() > 0
    assert r.rejected == pytest.approx(0.02275 / (1 - 0.02275) * 20_000, rel=0.2)
    with pytest.raises(ToleranceError, match=r"--vary 'fluid.viscosity=\+-300 %'.*no physical damper"):
        tolerance_study(makris, ["geometry.gap=+-1 %", "fluid.viscosity=+-300 %"], velocity=0.0254, samples=1000)


@pytest.mark.parametrize(
    "spec, message",
    [
        ("geometry.gapp=+-1 %", "'geometry.gapp' is not a value a study can vary"),
        ("geometry.gap=0.9 mm +- 1 um", "disagrees with the damper file, which gives geometry.gap = 0.8 mm"),
        ("geometry.gap=0.8 mm +- 1 kg", "DELTA '1 kg' is a mass, expected a length"),
        ("geometry.gap=0.8 kg +- 1 um", "VALUE '0.8 kg' is a mass"),
        ("geometry.gap +- 3 um", 'expected "KEY=VALUE'),
        ("geometry.gap=+-0 %", "must be a positive amount"),
        ("geometry.gap=+--3 um", "must be a positive amount"),
        ("geometry.gap=+-3", "has no unit"),
        ("fluid.viscosity=+-lots", "cannot read DELTA"),
    ],
)
def test_bad_vary_is_a_one_line_error_naming_it(capsys, spec, message):
    code, out, err = run(
        capsys, "tolerance", "makris", "--vary", spec, "--velocity", "1 in/s", "--samples", "100", "--jobs", "1"
    )
    assert code == 1 and out == ""
    assert err.startswith(f"error: --vary {spec!r}") and message in err and err.count("\n") == 1


@pytest.mark.parametrize(
    "args, message",
    [
        (["--samples", "0"], "--samples"),
        (["--samples", "-5"], "--samples"),
        (["--vary", "geometry.gap=+-2 %"], "geometry.gap is varied twice"),
    ],
)
def test_bad_options_are_named(capsys, args, message):
    code, _, err = run(
        capsys, "tolerance", "makris", "--vary", "geometry.gap=+-1 %", "--velocity", "1 in/s", "--jobs", "1", *args
    )
    assert code in (1, 2) and message in err and err.count("\n") == 1


def test_cli_json_keys_and_out_file(capsys, tmp_path):
    out = tmp_path / "samples.parquet"
    code, text, err = run(
        capsys,
        "tolerance",
        "makris",
        *VARY_ARGS,
        "--velocity",
        "1 in/s",
        "--field",
        "3 kV/mm",
        "--samples",
        "5000",
        "--seed",
        "3",
        "--jobs",
        "1",
        "--json",
        "--out",
        str(out),
    )
    assert code == 0, err
    obj = json.loads(text)
    assert obj["samples"] == 5000
    assert set(obj["quantiles"]) >= set(OUTPUTS)
    for key in OUTPUTS:
        assert list(obj["quantiles"][key]) == ["1", "5", "50", "95", "99"]
        assert set(obj["sensitivity"][key]) == {"geometry.gap", "fluid.viscosity", "fluid.yield_stress"}
    assert set(obj["sensitivity"]["force_N"]["geometry.gap"]) >= {"first", "total"}
    # the same numbers as the library call
    r = tolerance_study(load_example("makris"), VARY, velocity=0.0254, field=3e6, samples=5000, seed=3)
    assert obj["quantiles"]["force_N"] == pytest.approx(r.quantiles["force_N"], rel=1e-12)
    import pandas as pd

    frame = pd.read_parquet(out)
    assert len(frame) == 5000 and "geometry.gap [m]" in frame.columns and "force_N" in frame.columns
    assert np.quantile(frame["force_N"], 0.05) == pytest.approx(obj["quantiles"]["force_N"]["5"], rel=1e-12)
    # an existing file is never overwritten silently
    code, text, err = run(
        capsys,
        "tolerance",
        "makris",
        "--vary",
        VARY[0],
        "--velocity",
        "1 in/s",
        "--samples",
        "100",
        "--jobs",
        "1",
        "--out",
        str(out),
    )
    assert code == 1 and "exists; give --force" in err
    code, text, err = run(
        capsys,
        "tolerance",
        "makris",
        "--vary",
        VARY[0],
        "--velocity",
        "1 in/s",
        "--samples",
        "100",
        "--jobs",
        "1",
        "--out",
        str(tmp_path / "s.xlsx"),
    )
    assert code == 1 and "cannot write a '.xlsx' file" in err


def test_cli_table(capsys):
    code, text, err = run(
        capsys,
        "tolerance",
        "makris",
        *VARY_ARGS,
        "--velocity",
        "1 in/s",
        "--field",
        "3 kV/mm",
        "--samples",
        "3000",
        "--jobs",
        "1",
    )
    assert code == 0, err
    assert "damping constant [kN s/m]" in text and "Sobol indices" in text and "geometry.gap" in text


def test_app_size_page_shows_the_tolerance_figures():
    """The Size page's "Tolerances" expander runs a small study (2000 samples) and draws the histogram and the
    tornado chart of the chosen output, without exception; a bad tolerance line is a message, not a traceback."""
    from pathlib import Path

    from streamlit.testing.v1 import AppTest

    from erdesign.app import state

    at = AppTest.from_file(str(Path(state.__file__).with_name("main.py")), default_timeout=60).run()
    assert not at.exception, at.exception
    at.checkbox(key="size.tol.run").check().run()
    assert not at.exception, at.exception
    assert not at.error, [e.value for e in at.error]
    ids = [c.proto.id for c in at.get("plotly_chart")]
    assert any("size.fig.tolerance" in i for i in ids) and any("size.fig.tornado" in i for i in ids)
    tornado = json.loads(next(c for c in at.get("plotly_chart") if "size.fig.tornado" in c.proto.id).proto.spec)
    assert set(tornado["data"][0]["y"]) == {"geometry.gap", "fluid.viscosity", "fluid.yield_stress"}
    at.selectbox(key="size.tol.output").set_value("damping_constant_N_s_per_m").run()
    assert not at.exception, at.exception
    at.text_area(key="size.tol.vary").set_value("geometry.gapp=+-1 %").run()
    assert not at.exception, at.exception
    assert any("is not a value a study can vary" in e.value for e in at.error)


def test_report_shows_the_tolerance_figures():
    """``build_report(..., tolerances=...)``: the histogram and the tornado at the design point, the quantiles of
    the force in the table equal to the study's own."""
    from erdesign.campaign.tolerance import tolerance_study
    from erdesign.report import build_report, render_markdown

    vary = ["geometry.gap=+-2.5 %", "fluid.viscosity_at_reference_field=+-10 %"]
    rep = build_report(
        load_example("makris"),
        tolerances=vary,
        tolerance_samples=4000,
        design_velocity="50 mm/s",
        design_field="3 kV/mm",
    )
    keys = [f.key for f in rep.figures]
    assert "tolerance" in keys and "tornado" in keys
    table = next(f for f in rep.figures if f.key == "tolerance").table
    r = tolerance_study(load_example("makris"), vary, velocity=0.05, field=3e6, samples=4000)
    median = table.rows[2][1]  # the 50 % row, force column
    assert median.si == pytest.approx(r.quantiles["force_N"]["50"], rel=1e-3)  # shown to 4 figures
    assert "What drives the spread of the force" in render_markdown(rep)


def test_cli_csv_out_leaves_no_temporary_file(capsys, tmp_path):
    out = tmp_path / "samples.csv"
    code, _, err = run(
        capsys,
        "tolerance",
        "makris",
        "--vary",
        "uniform:geometry.gap=+-20 um",
        "--velocity",
        "1 in/s",
        "--samples",
        "300",
        "--jobs",
        "1",
        "--json",
        "--out",
        str(out),
    )
    assert code == 0, err
    assert [p.name for p in tmp_path.iterdir()] == ["samples.csv"]
    import pandas as pd

    gap = pd.read_csv(out)["geometry.gap [m]"]
    assert len(gap) == 300 and 0.78e-3 <= gap.min() and gap.max() <= 0.82e-3  # uniform, half-width 20 um


@pytest.mark.slow
def test_cli_on_a_dask_scheduler_gives_the_serial_json(capsys, dask_client):
    args = [
        "tolerance",
        "makris",
        *VARY_ARGS,
        "--velocity",
        "1 in/s",
        "--field",
        "3 kV/mm",
        "--samples",
        "100000",
        "--seed",
        "9",
        "--json",
    ]
    _, serial, err = run(capsys, *args, "--jobs", "1")
    code, dask, err = run(capsys, *args, "--scheduler", dask_client.scheduler.address)
    assert code == 0, err
    a, b = json.loads(serial), json.loads(dask)
    assert "Dask" in b["executor"]
    assert a["quantiles"] == b["quantiles"] and a["sensitivity"] == b["sensitivity"]
