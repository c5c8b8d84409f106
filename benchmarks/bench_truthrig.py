"""Benchmark: the truth rig on a 60 s record at 1 kHz with compliance + thermal + coil lag, against solve_ivp.

Run:  python benchmarks/bench_truthrig.py [--duration 60] [--rate 1000] [--window 2] [--repeat 3]

Prints the time per record of :func:`erdesign.simulation.truthrig.simulate_truth` (best of ``--repeat``, after a warm-up
call that loads or compiles the numba kernels), then, on the first ``--window`` seconds of the same motion, the time
of the rig with compliance alone and of ``scipy.integrate.solve_ivp`` (Radau, rtol 1e-8) on the same compliance ODE

    dP/dt = k_c (v(t) - v_d(P)),   v_d(P) = n Q(P / Ap) / Ap,

with the same valve law (the rig's compiled :func:`~erdesign.simulation.truthrig.kernels.passed_speed`, so only the
integrator differs), their ratio and the largest difference of the pressure force at the samples relative to its
peak.  Target: a 60 s record at 1 kHz in under 5 s on one core.  Not a test: timings depend on the machine.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")  # one core, as the target says

import numpy as np  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402

from erdesign.damper.files import load_example  # noqa: E402
from erdesign.simulation.rig import random_motion  # noqa: E402
from erdesign.simulation.truthrig import TruthDamper, simulate_truth  # noqa: E402
from erdesign.simulation.truthrig import kernels  # noqa: E402

FIELD = 3e6  # 3 kV/mm, the Makris damper's reference field


def best_of(repeat, fn):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=60.0)
    ap.add_argument("--rate", type=float, default=1000.0)
    ap.add_argument("--window", type=float, default=2.0, help="seconds on which solve_ivp is compared")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()

    damper = load_example("makris")
    motion = random_motion(0.003, (0.5, 5.0), FIELD, duration=args.duration, rate=args.rate, seed=2)
    truth = TruthDamper(damper, {"compliance": {}, "thermal": {}, "coil_lag": {}})
    simulate_truth(truth, random_motion(0.003, (0.5, 5.0), FIELD, duration=1.0, rate=args.rate))  # warm-up
    t_full, rec = best_of(args.repeat, lambda: simulate_truth(truth, motion, seed=0))
    print(
        f"truth rig, {args.duration:g} s at {args.rate:g} Hz ({len(motion.time)} samples), compliance + thermal + "
        f"coil_lag: {t_full:.3f} s per record (target < 5 s)"
    )

    # --- the same compliance ODE with a general stiff integrator, on a window of the record
    n = int(round(args.window * args.rate)) + 1
    window = type(motion)(
        *(
            np.asarray(a)[:n]
            for a in (motion.time, motion.displacement, motion.velocity, motion.acceleration, motion.control)
        ),
        "window",
    )
    compliant = TruthDamper(damper, {"compliance": {}})
    t_rig, rec_w = best_of(
        args.repeat, lambda: simulate_truth(compliant, window, force_noise=0.0, displacement_noise=0.0)
    )
    p = compliant.parameter_vector()
    kc = compliant.compliance_stiffness
    tau_y = float(damper.fluid.yield_stress_at(FIELD))
    eta = float(damper.fluid.viscosity_at(FIELD))
    t, v = window.time, window.velocity

    def rhs(time_, P):
        vt = np.interp(time_, t, v)
        s = 1 if P[0] >= 0 else -1
        return [kc * (vt - s * kernels.passed_speed(abs(P[0]), s, tau_y, eta, 1.0, p))]

    t0 = time.perf_counter()
    sol = solve_ivp(rhs, (t[0], t[-1]), [0.0], method="Radau", t_eval=t, rtol=1e-8, atol=1e-6, max_step=1.0 / args.rate)
    t_radau = time.perf_counter() - t0
    P_rig = rec_w.components["fluid"]
    diff = np.max(np.abs(sol.y[0] - P_rig)) / np.max(np.abs(P_rig))
    print(
        f"compliance alone on {args.window:g} s: truth rig {t_rig * 1e3:.1f} ms, solve_ivp Radau "
        f"{t_radau:.2f} s ({sol.nfev} evaluations): ratio {t_radau / t_rig:.0f}x; largest difference "
        f"{diff:.1e} of the peak force"
    )


if __name__ == "__main__":
    main()
