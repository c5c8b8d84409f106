"""``erdesign simulate --model NAME --params P --motion "sine X0 f"``: a published or given parameter set on a
generated motion, with energy per cycle, C_eqv and energy per unit active fluid volume (Kamath and Wereley 1997,
eqs 1-2 and Fig 6)."""

import json
import math

import pytest

from erdesign.cli import main
from erdesign.damper.files import load_damper


def run(capsys, *args):
    code = main(["simulate", *args])
    out, err = capsys.readouterr()
    return code, out, err


def test_bingham_energy_per_cycle_is_the_closed_form(capsys):
    code, out, err = run(
        capsys, "--model", "bingham", "--params", "c0=2000 N*s/m, f_c=300 N", "--motion", "sine 10 mm 2 Hz", "--json"
    )
    assert code == 0, err
    d = json.loads(out)
    X0, w = 0.01, 2 * math.pi * 2.0
    # loop of a Bingham damper on a sine: U = 4 f_c X0 + pi c0 Omega X0^2; the sign switch lies between samples
    # (400 per cycle), which costs at most f_c * 2 dx ~ 2 x 300 N x 0.16 mm = 0.1 J of 4.9 J: 2 %
    U = 4 * 300.0 * X0 + math.pi * 2000.0 * w * X0**2
    assert d["energy_per_cycle_J"] == pytest.approx(U, rel=0.02)
    # C_eqv = U / (pi Omega X0^2), Kamath and Wereley (1997) eq 2
    assert d["equivalent_damping_N_s_per_m"] == pytest.approx(d["energy_per_cycle_J"] / (math.pi * w * X0**2))
    assert d["active_volume_m3"] is None and d["energy_per_active_volume_J_per_m3"] is None
    assert d["amplitude_m"] == 0.01 and d["frequency_Hz"] == 2.0


def test_physics_damper_energy_per_active_volume(capsys, tmp_path):
    out_file = tmp_path / "forces.csv"
    code, out, err = run(
        capsys,
        "--model",
        "physics",
        "--damper",
        "makris",
        "--params",
        "viscosity_factor=1",
        "--motion",
        "sine 5 mm 1 Hz 2 cycles",
        "--field",
        "2 kV/mm",
        "--json",
        "--out",
        str(out_file),
    )
    assert code == 0, err
    d = json.loads(out)
    g = load_damper("makris").geometry
    # the fluid between the electrodes, pi d h L (Kamath and Wereley 1997, section III.C): 1.96 cm^3 for Makris
    assert d["active_volume_m3"] == pytest.approx(math.pi * 0.0143 * 0.0008 * 0.0546, rel=1e-3)
    assert d["energy_per_active_volume_J_per_m3"] == pytest.approx(d["energy_per_cycle_J"] / g.active_fluid_volume)
    assert out_file.read_text().count("\n") > 800


def test_published_set_on_a_generated_motion(capsys):
    code, out, err = run(
        capsys,
        "--model",
        "kamath_wereley_4",
        "--params",
        "kamath_wereley1997_case2",
        "--motion",
        "sine 1 mm 10 Hz",
        "--active-volume",
        "16.2 cm^3",
    )
    assert code == 0, err
    assert "energy per cycle" in out and "kJ/m^3" in out


@pytest.mark.parametrize(
    "args,words",
    [
        (["--model", "bingham", "--params", "c0=1 kN*s/m"], "MEASUREMENT.csv or --motion"),
        (["REC.csv", "--model", "bingham", "--params", "c0=1 kN*s/m", "--motion", "sine 1 mm 1 Hz"], "one of them"),
        (["--model", "bingham", "--params", "c0=1 kN*s/m", "--motion", "square 1 mm 1 Hz"], "sine AMPLITUDE"),
        (["--model", "bingham", "--params", "c0=1 kN*s/m", "--motion", "sine 1 kg 1 Hz"], "amplitude"),
        (["--model", "bingham", "--params", "c0=1 kN*s/m", "--motion", "sine 1 mm 1 Hz 0.5 cycles"], "cycles"),
    ],
)
def test_bad_motion_is_one_line(capsys, args, words):
    code, out, err = run(capsys, *args, "--json")
    assert code != 0 and out == "" and words in err and len(err.strip().splitlines()) == 1
