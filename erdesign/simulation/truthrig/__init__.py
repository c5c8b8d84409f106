"""A truth rig: an independent simulator of a damper on a displacement-controlled test machine.

Test data for the diagnosis, made by physics that shares no code with the model the diagnosis fits (module notes
of :mod:`erdesign.simulation.truthrig.simulate`; the page docs/truthrig.md).  Mechanisms (:data:`MECHANISMS`):
compressible fluid column, Herschel-Bulkley fluid, leakage bypass, gas accumulator, Stribeck seal friction, fluid slug
inertia, coil lag, viscous heating, Makris pre-yield elasticity, and four outside the effect library (rebound blow-off,
single-ended rod, cavitation, free play).

>>> from erdesign.damper.files import load_example
>>> from erdesign.simulation.rig import sine
>>> truth = TruthDamper(load_example("makris"), {"bypass": {}, "coil_lag": {}}, yield_stress_factor=0.9)
>>> rec = simulate_truth(truth, sine(0.005, 2.0, 3e6, cycles=2, rate=200), seed=0, name="case-001")
>>> rec.measured.name, len(rec.true_force)
('case-001', 201)
"""

from .mechanisms import MECHANISMS, Mechanism, mechanism_names
from .simulate import TruthDamper, TruthRecord, simulate_truth
from .valve import bingham_valve_flow, herschel_bulkley_valve_flow, mixed_gap_flow

__all__ = [
    "MECHANISMS",
    "Mechanism",
    "mechanism_names",
    "TruthDamper",
    "TruthRecord",
    "simulate_truth",
    "bingham_valve_flow",
    "herschel_bulkley_valve_flow",
    "mixed_gap_flow",
]
