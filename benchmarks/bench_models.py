"""Speed of the model library (not a timed test): run `python benchmarks/bench_models.py`.

1. 10^5 samples of Spencer's modified Bouc-Wen model (seed 001 section 4.3 parameters), erdesign's exact-z kernel
   vs scipy.integrate.solve_ivp (RK45 at rtol 1e-6 and LSODA at rtol 1e-8) on the same model in the same run.
2. Identification of the six-parameter Kamath-Wereley model on 20,000 samples (one core).
"""

import os
import time

# "one core": small least-squares SVDs run ~40x slower with multithreaded BLAS on a busy 2-core machine
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402

from erdesign.fit import fit  # noqa: E402
from erdesign.measurement import Measurement  # noqa: E402
from erdesign.models.bouc_wen import SPENCER_PASSIVE  # noqa: E402
from erdesign.models.kamath_wereley import KAMATH_WERELEY_TABLE1  # noqa: E402
from erdesign.models.registry import get_model  # noqa: E402


def bouc_wen_speed(n=100_000, duration=100.0):
    p = SPENCER_PASSIVE
    t = np.linspace(0, duration, n)
    rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    model = get_model("bouc_wen_modified")
    t0 = time.perf_counter()
    F = model.simulate(rec, p)
    fast = time.perf_counter() - t0

    def rhs(tt, s):
        w, z = s
        xd = 0.01 * 2 * np.pi * np.cos(2 * np.pi * tt)
        wd = (p["c1a"] * xd - p["alpha_a"] * z - p["k0"] * w) / (p["c0a"] + p["c1a"])
        return [wd, wd * p["delta"] - p["gamma"] * abs(wd) * z * abs(z) - p["beta"] * wd * z * z]

    out = {"erdesign_s": fast}
    for method, rtol in (("RK45", 1e-6), ("LSODA", 1e-8)):
        t0 = time.perf_counter()
        sol = solve_ivp(rhs, (0, duration), [0.0, 0.0], t_eval=t, method=method, rtol=rtol, atol=1e-12)
        out[f"solve_ivp_{method}_s"] = time.perf_counter() - t0
        w, z = sol.y
        wd = (p["c1a"] * rec.velocity - p["alpha_a"] * z - p["k0"] * w) / (p["c0a"] + p["c1a"])
        F_ref = p["c1a"] * (rec.velocity - wd) + p["k1"] * rec.displacement
        out[f"max_diff_vs_{method}_fraction_of_range"] = float(np.max(np.abs(F - F_ref)) / np.ptp(F_ref))
    return out


def kamath_wereley_identification(n=20_000):
    t = np.linspace(0, 2.0, n)
    rec = Measurement.from_arrays(t, 1e-3 * np.sin(2 * np.pi * 10 * t))
    model = get_model("kamath_wereley_6")
    clean = model.simulate(rec, KAMATH_WERELEY_TABLE1)
    data = rec.with_force(clean + 0.01 * np.std(clean) * np.random.default_rng(0).standard_normal(n))
    t0 = time.perf_counter()
    r = fit(model, data)
    return {"seconds": time.perf_counter() - t0, "esr": r.esr, "nfev": r.extra["nfev"],
            "max_rel_param_error": max(abs(r.values[k] / KAMATH_WERELEY_TABLE1[k] - 1) for k in ("C1", "C2", "K1",
                                                                                                  "Cv", "R"))}


if __name__ == "__main__":
    bw = bouc_wen_speed()
    print("modified Bouc-Wen, 1e5 samples:", {k: round(v, 4) for k, v in bw.items()})
    for m in ("RK45", "LSODA"):
        print(f"  ratio solve_ivp {m} / erdesign: {bw[f'solve_ivp_{m}_s'] / bw['erdesign_s']:.1f}")
    print("Kamath-Wereley 6-parameter identification, 20,000 samples:",
          {k: round(v, 4) for k, v in kamath_wereley_identification().items()})
