"""``erdesign batch`` (issue 24, "Batches of records"; CONTRACTS.md section 6): one row per record in input order,
the same table on every executor, a bad file as an error row, resume after a kill without redoing finished
records, an existing table never overwritten, outliers flagged by a robust z-score.

Records come from the truth rig (erdesign/simulation/truthrig) on the Makris damper: one cycle at 100 Hz (101
samples) keeps a fit at a few tens of milliseconds.  A diagnosis of such a record costs about 3-6 s on the loaded
two-core test machine (every candidate effect is fitted), so the 200-record runs use ``batch fit`` and the
diagnosis runs use three records.
"""

from __future__ import annotations

import csv
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from erdesign.campaign.batch import flag_outliers, read_table, run_batch
from erdesign.cli import main
from erdesign.damper.files import load_example
from erdesign.data.measurement import write_measurement
from erdesign.simulation.rig import sine
from erdesign.simulation.truthrig import TruthDamper, simulate_truth

ROOT = Path(__file__).resolve().parents[1]


def _write_records(folder: Path, n: int, *, viscosity_factor: float = 1.05, start_seed: int = 0,
                   prefix: str = "r") -> list[str]:
    damper = load_example("makris")
    motion = sine(0.01, 1.0, damper.fluid.reference_field, cycles=1, rate=100)
    truth = TruthDamper(damper, {}, viscosity_factor=viscosity_factor, yield_stress_factor=0.95)
    names = []
    for i in range(n):
        name = f"{prefix}{i:03d}.csv"
        write_measurement(folder / name, simulate_truth(truth, motion, seed=start_seed + i, name=name).measured)
        names.append(name)
    return names


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """200 records of one damper and a corrupt file (a header without units) in the middle."""
    path = tmp_path_factory.mktemp("batch")
    names = _write_records(path, 200)
    (path / "corrupt.csv").write_text("garbage,more\n1,2\n")
    names.insert(100, "corrupt.csv")
    return path, names


def _run(folder: Path, *args: str) -> int:
    old = os.getcwd()
    os.chdir(folder)                    # records named relative to the folder, as a user types them
    try:
        return main(["batch", *args])
    finally:
        os.chdir(old)


def _without_seconds(path: Path) -> list[dict]:
    return [{k: v for k, v in row.items() if k != "seconds"} for row in read_table(path)]


@pytest.fixture(scope="module")
def serial(folder):
    """The 200 records' table made serially (the reference of the other executors and of a resumed batch)."""
    path, names = folder
    assert _run(path, "fit", *names, "--damper", "makris", "--jobs", "1", "--out", "serial.csv") == 0
    return path / "serial.csv"


@pytest.mark.slow
def test_fit_of_200_records_gives_one_table_serially_on_a_pool_and_on_dask(folder, serial, dask_client):
    path, names = folder
    assert _run(path, "fit", *names, "--damper", "makris", "--jobs", "2", "--out", "pool.csv") == 0
    assert _run(path, "fit", *names, "--damper", "makris", "--scheduler", dask_client.scheduler.address,
                "--out", "dask.csv") == 0
    serial = _without_seconds(path / "serial.csv")
    assert [r["record"] for r in serial] == names                       # input order, whatever finished first
    assert serial == _without_seconds(path / "pool.csv") == _without_seconds(path / "dask.csv")
    bad = serial[100]
    assert bad["status"] == "error" and "corrupt.csv" in bad["error"] and "unit" in bad["error"]
    assert bad["esr"] is None and not bad["outlier"]
    ok = [r for r in serial if r["status"] == "ok"]
    assert len(ok) == 200 and all(r["error"] == "" for r in ok)
    # the truth rig's fluid is 5 % more viscous than the file's: every fit finds it to 1 %
    assert all(r["viscosity_factor [-]"] == pytest.approx(1.05, rel=0.01) for r in ok)
    assert all(0 < r["esr"] < 1e-3 for r in ok)                         # 1 % force noise: ESR ~ 1e-4


def _rows(path: Path) -> int:
    try:
        with open(path, newline="") as fh:
            return max(0, sum(1 for _ in fh) - 1)
    except FileNotFoundError:
        return 0


@pytest.mark.slow
def test_a_batch_killed_half_way_resumes_without_redoing_finished_records(folder, serial):
    path, names = folder
    out = path / "killed.csv"
    command = [sys.executable, "-m", "erdesign", "batch", "fit", *names, "--damper", "makris", "--jobs", "1",
               "--save-every", "0", "--out", str(out)]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.Popen(command, cwd=path, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 120
    while _rows(out) < 60 and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.01)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    first = read_table(out)
    assert 60 <= len(first) < len(names), "the batch was not caught half-way"
    assert [r["record"] for r in first] == names[:len(first)]          # the serial batch's finished prefix
    assert _run(path, "fit", *names, "--damper", "makris", "--jobs", "1", "--out", "killed.csv") == 1  # refused
    assert _run(path, "fit", *names, "--damper", "makris", "--jobs", "1", "--out", "killed.csv", "--resume") == 0
    final = read_table(out)
    assert [r["record"] for r in final] == names
    # the rows finished before the kill were kept, not run again: same seconds to the last digit
    assert [r["seconds"] for r in final[:len(first)]] == [r["seconds"] for r in first]
    # and the resumed table is the uninterrupted one (outliers are judged on the whole table in both)
    assert _without_seconds(out) == _without_seconds(serial)


@pytest.mark.slow
def test_diagnose_gives_one_table_on_every_executor(folder, dask_client, tmp_path):
    path, names = folder
    records = [str(path / n) for n in names[:2]] + [str(path / "corrupt.csv")]
    tables = {}
    for label, kwargs in {"serial": {"jobs": 1}, "pool": {"jobs": 2},
                          "dask": {"scheduler": dask_client}}.items():
        result = run_batch("diagnose", records, damper="makris", out=tmp_path / f"{label}.csv", **kwargs)
        assert result.errors == 1
        tables[label] = _without_seconds(tmp_path / f"{label}.csv")
    assert tables["serial"] == tables["pool"] == tables["dask"]
    ok = tables["serial"][:2]
    # no mechanism switched on in the truth rig beyond the file's physics: nothing is missing
    assert [r["verdict"] for r in ok] == ["nothing_missing"] * 2
    assert all(r["missing_effect"] == "" and r["viscosity_factor [-]"] == pytest.approx(1.05, rel=0.01) for r in ok)
    assert tables["serial"][2]["status"] == "error"


def test_an_existing_table_is_refused_without_resume(tmp_path, capsys):
    names = _write_records(tmp_path, 1)
    out = tmp_path / "t.csv"
    out.write_text("precious\n")
    assert _run(tmp_path, "fit", *names, "--damper", "makris", "--jobs", "1", "--out", "t.csv") == 1
    err = capsys.readouterr().err
    assert "t.csv exists" in err and "--resume" in err and "Traceback" not in err
    assert out.read_text() == "precious\n"                              # untouched


def test_bad_arguments_are_one_line_errors(tmp_path, capsys):
    names = _write_records(tmp_path, 1)
    cases = {("fit", *names, "--out", "a.csv"): "--damper",
             ("identify", *names, "--out", "a.csv"): "--model",
             ("diagnose", *names, "--damper", "makris", "--model", "bingham", "--out", "a.csv"): "model",
             ("fit", *names, "--damper", "makris", "--out", "a.txt"): ".csv or .parquet",
             ("fit", "--manifest", "none.csv", "--damper", "makris", "--out", "a.csv"): "no such file"}
    for args, named in cases.items():
        assert _run(tmp_path, *args) == 1, args
        err = capsys.readouterr().err.strip()
        assert named in err and "\n" not in err and "Traceback" not in err, (args, err)
    assert not (tmp_path / "a.csv").exists()


def test_a_manifest_names_each_records_damper_relative_to_itself(tmp_path):
    sub = tmp_path / "line"
    sub.mkdir()
    names = _write_records(sub, 2)
    (sub / "damper.toml").write_text((ROOT / "erdesign" / "examples" / "makris.toml").read_text())
    (sub / "manifest.csv").write_text("record,damper,effects\n"
                                      f"{names[0]},damper.toml,\n"
                                      f"{names[1]},mr_valve_current,\n"     # an MR valve for an ER record
                                      "missing.csv,,\n")
    result = run_batch("fit", manifest=sub / "manifest.csv", damper="makris", out=tmp_path / "t.parquet")
    rows = read_table(tmp_path / "t.parquet")
    assert [r["record"] for r in rows] == [names[0], names[1], "missing.csv"]
    assert [r["status"] for r in rows] == ["ok", "error", "error"]
    assert rows[0]["damper"] == str((sub / "damper.toml").resolve())
    assert rows[0]["viscosity_factor [-]"] == pytest.approx(1.05, rel=0.01)
    assert "missing.csv" in rows[2]["error"] and rows[2]["sha256"] == ""
    assert result.errors == 2 and rows[1]["error"]


def test_a_damper_off_the_line_is_flagged_as_an_outlier(tmp_path):
    names = _write_records(tmp_path, 8)
    # the same damper built with a fluid 30 % more viscous (the others: 5 %)
    names += _write_records(tmp_path, 1, viscosity_factor=1.3, start_seed=50, prefix="odd")
    result = run_batch("fit", [str(tmp_path / n) for n in names], damper="makris")
    flags = [r["outlier"] for r in result.rows]
    assert flags == [False] * 8 + [True]
    assert "viscosity_factor [-] z=+" in result.rows[-1]["outlier_reason"]


def test_outlier_rule_is_the_robust_z_score_from_median_and_mad():
    values = [1.0, 1.1, 0.9, 1.05, 0.95, 1.6]
    rows = [{"status": "ok", "esr": 0.01, "p [N]": v} for v in values] + [{"status": "error", "p [N]": 100.0}]
    flag_outliers(rows, ["p [N]"])
    # median 1.025, |deviations| 0.025 0.075 0.125 0.025 0.075 0.575 -> MAD 0.075, sigma = 1.4826 * 0.075
    z = (1.6 - 1.025) / (1.4826 * 0.075)
    assert z == pytest.approx(5.171, abs=1e-3)
    assert [r["outlier"] for r in rows] == [False] * 5 + [True, False]
    assert rows[5]["outlier_reason"] == f"p [N] z=+{z:.1f}"
    # fewer than five ok rows: not judged; a value the same on every row (a fixed parameter) flags nothing
    few = [{"status": "ok", "esr": 0.01, "p [N]": v} for v in (1.0, 1.0, 9.0)]
    flag_outliers(few, ["p [N]"])
    assert not any(r["outlier"] for r in few)
    same = [{"status": "ok", "esr": 0.01, "p [N]": 2.0} for _ in range(6)]
    flag_outliers(same, ["p [N]"])
    assert not any(r["outlier"] for r in same)


def test_the_table_is_written_atomically_and_reads_back_exactly(tmp_path):
    names = _write_records(tmp_path, 2)
    result = run_batch("fit", [str(tmp_path / n) for n in names], damper="makris", out=tmp_path / "t.csv")
    assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith(".")) == []   # no temporary left
    back = read_table(tmp_path / "t.csv")
    assert [r["esr"] for r in back] == [r["esr"] for r in result.rows]  # floats round-trip to the last bit
    with open(tmp_path / "t.csv", newline="") as fh:
        header = next(csv.reader(fh))
    assert header[:4] == ["record", "status", "error", "esr"]
    assert {"viscosity_factor [-]", "yield_stress_factor [-]", "seconds", "sha256", "outlier"} <= set(header)


def test_identify_rows_carry_the_models_parameters_with_units(tmp_path, capsys):
    names = _write_records(tmp_path, 2)
    assert _run(tmp_path, "identify", *names, "--model", "bingham", "--jobs", "1", "--out", "t.csv", "--json") == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["records"] == 2 and summary["ok"] == 2 and summary["errors"] == 0 and summary["ran"] == 2
    rows = read_table(tmp_path / "t.csv")
    assert [r["status"] for r in rows] == ["ok", "ok"] and all(r["success"] for r in rows)
    units = {k for k in rows[0] if k.endswith("]")}
    assert units and all("[" in k for k in units)
    assert all(0 < r["esr"] < 0.2 for r in rows)     # Bingham on an ER damper's loop: a good first fit


def test_resume_of_a_parquet_table_runs_only_the_new_records(tmp_path):
    names = [str(tmp_path / n) for n in _write_records(tmp_path, 3)]
    out = tmp_path / "t.parquet"
    first = run_batch("fit", names[:2], damper="makris", out=out)
    again = run_batch("fit", names, damper="makris", out=out, resume=True)
    assert (again.reused, again.summary()["ran"]) == (2, 1)
    assert [r["seconds"] for r in again.rows[:2]] == [r["seconds"] for r in first.rows]
    assert [r["record"] for r in read_table(out)] == names
    # another damper is another task: nothing is kept
    other = run_batch("fit", names, damper="makris", effects="seal_friction", out=out, resume=True)
    assert other.reused == 0 and [r["effects"] for r in read_table(out)] == ["seal_friction"] * 3
