"""Benchmark: a full diagnosis (calibration + all nine candidate effects + held-out check) of a 60 s record sampled
at 1 kHz must finish in under a minute on one core (issue 4).

Run: ``python benchmarks/bench_diagnose.py`` (prints the time of each stage; exits 1 when over the limit).
Long records are analysed on an evenly thinned copy (erdesign.diagnosis.diagnose.MAX_SAMPLES); the derivatives are taken
on the full record and the ESRs are reported for the full record.
"""

import os
import sys
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")  # one core
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from erdesign import load_example  # noqa: E402
from erdesign.diagnosis.diagnose import diagnose  # noqa: E402
from erdesign.simulation.rig import run_rig, stepped_sine  # noqa: E402

LIMIT = 60.0


def main() -> int:
    damper = load_example("makris")
    E = damper.fluid.reference_field
    # 60 s: sweeps over amplitude (4, 8 mm), frequency (0.5-2 Hz) and field (0, 0.6, 1 x 3 kV/mm)
    amplitudes = [0.004, 0.008, 0.006, 0.004, 0.008, 0.006]
    frequencies = [0.5, 1.0, 2.0, 1.0, 0.5, 2.0]
    fields = [0.0, E, 0.6 * E, E, 0.0, 0.6 * E]
    cycles_per_segment = 60.0 / sum(1 / f for f in frequencies)
    t0 = time.perf_counter()
    motion = stepped_sine(amplitudes, frequencies, fields, cycles=cycles_per_segment, rate=1000.0)
    rig = run_rig(
        damper,
        motion,
        hidden={"seal_friction": {"friction_force": 600.0}},
        viscosity_factor=1.2,
        yield_stress_factor=0.8,
        seed=1,
    )
    t1 = time.perf_counter()
    d = diagnose(damper, rig.record)
    t2 = time.perf_counter()
    print(f"record: {len(rig.record)} samples over {rig.record.duration:.1f} s (rig {t1 - t0:.1f} s)")
    print(
        f"diagnosis: {t2 - t1:.1f} s (analysed on {d.samples[1]} samples); missing effect: {d.missing_effect}; "
        f"ESR {d.baseline_esr:.3g} -> {d.ranking[0].esr:.3g}"
    )
    ok = t2 - t1 < LIMIT and d.missing_effect == "seal_friction"
    print("OK" if ok else f"FAIL (limit {LIMIT:g} s)")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
