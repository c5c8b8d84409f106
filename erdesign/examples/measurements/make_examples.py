"""Regenerate the example measurements of this folder with the truth rig (erdesign.simulation.truthrig).

The truth rig is the independent simulator (its own flow laws and time stepping, docs/truthrig.md), so that the
diagnosis shown on these records is not the fitted model agreeing with itself.  Each file says in its first comment
line what the rig hid.  Run from the repository root: ``python examples/measurements/make_examples.py``
(existing files are not overwritten: delete them first).
"""

from pathlib import Path

from erdesign import load_example
from erdesign.simulation.rig import field_steps, stepped_sine
from erdesign.simulation.truthrig import TruthDamper, simulate_truth

HERE = Path(__file__).resolve().parent

#: Seal friction of the two Makris records: Coulomb 800 N (the damper file says 112 N), a Stribeck peak 20 % above
#: it below 5 mm/s.
FRICTION = {"coulomb_force": 800.0, "static_force": 960.0, "stribeck_speed": 0.005, "viscous_friction": 0.0}


def main() -> None:
    makris = load_example("makris")
    motion = stepped_sine([0.004, 0.008], [1.0, 2.5], [0.0, 3e6, 1.8e6], cycles=2, rate=300, control_unit="kV/mm")
    truth = TruthDamper(makris, {"stribeck_friction": FRICTION}, viscosity_factor=1.2, yield_stress_factor=0.8)
    simulate_truth(truth, motion, force_noise=0.005, seed=1, name="makris_hidden_seal_friction.csv").write(
        HERE / "makris_hidden_seal_friction.csv"
    )

    truth = TruthDamper(
        makris,
        {"stribeck_friction": FRICTION, "slug_inertia": {"slug_mass": 400.0}},
        viscosity_factor=1.2,
        yield_stress_factor=0.8,
    )
    simulate_truth(truth, motion, force_noise=0.005, seed=5, name="makris_two_hidden_effects.csv").write(
        HERE / "makris_two_hidden_effects.csv", units={"displacement": "in", "force": "lbf"}
    )

    mr = load_example("mr_mixed")
    motion = field_steps(0.006, 2.0, 2e5, cycles=4, step_period=0.3, rate=500, control_unit="kA/m")
    truth = TruthDamper(mr, {"coil_lag": {"time_constant": 0.015}}, viscosity_factor=0.8, yield_stress_factor=1.15)
    simulate_truth(truth, motion, force_noise=0.005, seed=2, name="mr_hidden_field_lag.csv").write(
        HERE / "mr_hidden_field_lag.csv"
    )


if __name__ == "__main__":
    main()
