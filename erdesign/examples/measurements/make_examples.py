"""Regenerate the example measurements of this folder with the virtual rig (erdesign.rig).

Each file says in its first comment line what the rig hid.  Run from the repository root:
``python examples/measurements/make_examples.py``.
"""

from pathlib import Path

from erdesign import load_example
from erdesign.measurement import write_measurement
from erdesign.rig import field_steps, run_rig, sweep

HERE = Path(__file__).resolve().parent


def main() -> None:
    makris = load_example("makris")
    motion = sweep([0.004, 0.008], [1.0, 2.5], [0.0, 3e6, 1.8e6], cycles=2, rate=300)
    rig = run_rig(makris, motion, hidden={"seal_friction": {"friction_force": 800.0}}, viscosity_factor=1.2,
                  yield_stress_factor=0.8, seed=1, name="makris_hidden_seal_friction.csv")
    write_measurement(HERE / "makris_hidden_seal_friction.csv", rig.record,
                      units={"displacement": "mm", "field": "kV/mm"}, comment=rig.comment)

    rig = run_rig(makris, motion, hidden={"seal_friction": {"friction_force": 800.0},
                                          "fluid_inertia": {"slug_mass": 400.0}},
                  viscosity_factor=1.2, yield_stress_factor=0.8, seed=5, name="makris_two_hidden_effects.csv")
    write_measurement(HERE / "makris_two_hidden_effects.csv", rig.record,
                      units={"displacement": "in", "force": "lbf", "field": "kV/mm"}, comment=rig.comment)

    mr = load_example("mr_mixed")
    motion = field_steps(0.006, 2.0, 2e5, cycles=4, step_period=0.3, rate=500)
    rig = run_rig(mr, motion, hidden={"field_lag": {"field_time_constant": 0.015}}, viscosity_factor=0.8,
                  yield_stress_factor=1.15, seed=2, name="mr_hidden_field_lag.csv")
    write_measurement(HERE / "mr_hidden_field_lag.csv", rig.record, units={"displacement": "mm", "field": "kA/m"},
                      comment=rig.comment)


if __name__ == "__main__":
    main()
