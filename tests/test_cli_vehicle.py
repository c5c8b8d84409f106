"""``erdesign vehicle`` (docs/cli.md): JSON keys, the table, the history file and one-line errors."""

import json

import numpy as np
import pytest

from erdesign.cli import main

RIDE_KEYS = {
    "body_acceleration_rms_m_per_s2",
    "body_acceleration_weighted_rms_m_per_s2",
    "suspension_travel_rms_m",
    "suspension_travel_peak_m",
    "tyre_load_rms_N",
    "tyre_load_peak_N",
    "tyre_load_rms_relative",
    "damper_force_peak_N",
    "control_mean",
    "unreachable_fraction",
    "settling_time_s",
}
CONVENTIONAL = ["--model", "bingham", "--params", "c0=6000 N*s/m, f_c=0 N"]


def run(capsys, *args):
    code = main(["vehicle", *args])
    out, err = capsys.readouterr()
    return code, out, err


def test_json_has_the_documented_keys_and_the_vehicle_of_the_paper(capsys):
    code, out, err = run(capsys, *CONVENTIONAL, "--road", "bump", "--duration", "1 s", "--json")
    assert code == 0 and err == ""
    data = json.loads(out)
    assert RIDE_KEYS <= set(data)
    assert {
        "damper",
        "model",
        "control",
        "road",
        "gain_N_s_per_m",
        "control_kind",
        "control_range",
        "duration_s",
        "dt_s",
        "samples",
        "vehicle",
        "warnings",
    } <= set(data)
    # Butz and von Stryk (2002) section 4.1
    assert data["vehicle"] == {
        "m1_kg": 250.0,
        "m2_kg": 1300.0,
        "K_N_per_m": 650e3,
        "C_N_s_per_m": 800.0,
        "k_N_per_m": 110e3,
    }
    assert data["samples"] == 4001 and data["settling_time_s"] is not None


def test_table_and_history_file(capsys, tmp_path):
    out_file = tmp_path / "history.csv"
    code, out, err = run(capsys, *CONVENTIONAL, "--road", "step", "--duration", "0.5 s", "--out", str(out_file))
    assert code == 0, err
    assert "ISO 2631" in out and "dynamic tyre load" in out
    header = out_file.read_text().splitlines()[1]
    assert header.startswith("time [s],road [m],axle_displacement [m]")
    data = np.loadtxt(out_file, delimiter=",", skiprows=2)
    assert data.shape == (2001, 11)
    assert data[0, 4] == pytest.approx(0.32)  # axle velocity jump C h / m1
    # an existing file is never replaced without --force
    code, _, err = run(capsys, *CONVENTIONAL, "--duration", "0.5 s", "--out", str(out_file))
    assert code == 1 and "exists" in err and "\n" not in err.strip()


@pytest.mark.parametrize(
    "args,words",
    [
        (["--road", "random", "--road-class", "Q", *CONVENTIONAL], "road_class"),
        (["--model", "bingham"], "--params"),
        ([], "--damper"),
        (
            [
                "--model",
                "bouc_wen_modified",
                "--params",
                "spencer1997",
                "--max-field",
                "2.25 V",
                "--control",
                "skyhook",
            ],
            "clipped-optimal",
        ),
        ([*CONVENTIONAL, "--vehicle", "m9=3 kg"], "unknown key 'm9'"),
        ([*CONVENTIONAL, "--duration", "3 parsecs"], "duration"),
    ],
)
def test_bad_input_is_one_line(capsys, args, words):
    code, out, err = run(capsys, *args, "--json")
    assert code != 0 and out == ""
    assert words in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err
