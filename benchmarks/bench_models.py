"""Speed of the model library (not a timed test): run `python benchmarks/bench_models.py [--quick]`.

1. The time-stepping models at 3 kHz (Dyke's ransim records are sampled at 3004.8 Hz), 20 s of motion: erdesign's
   compiled kernels against scipy.integrate.solve_ivp on the same model in the same process.  For each model:
   the kernel's time (warm: compiled code loaded; the first call of a fresh process adds the numba import and the
   cache load, printed as 'first call'), LSODA's time at rtol 1e-8 on the analytic inputs and the ratio, and the
   kernel's relative error max |F - F_ref| / range against a tight reference for the same sampled inputs (motion
   and control linear between samples, as the kernels read a record): solve_ivp at rtol 1e-11 on each sample
   interval (LSODA; Radau for the stiff extended Bingham model), over the first second.  Issue 12 asks for >= 50 x
   LSODA at <= 1e-4.  (A sampled record itself differs from the continuous motion it samples: at a reversal the
   peak between two samples is cut by about a h^2 / 8, which moves the Bouc-Wen force by ~1e-3 of its range at
   3 kHz for this motion - a property of the data, not of the solver.)
2. Identification of the six-parameter Kamath-Wereley model on 20,000 samples (one core).
"""

import math
import os
import sys
import time

# "one core": small least-squares SVDs run ~40x slower with multithreaded BLAS on a busy 2-core machine
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402

from erdesign.data.measurement import Measurement  # noqa: E402
from erdesign.identification.fit import fit  # noqa: E402
from erdesign.models.bouc_wen import SPENCER_PASSIVE  # noqa: E402
from erdesign.models.kamath_wereley import KAMATH_WERELEY_TABLE1  # noqa: E402
from erdesign.models.registry import get_model  # noqa: E402

FS = 3000.0
#: Spencer, Dyke, Sain and Carlson (1997) in SI (shared/data/README.md).
SPENCER_1997 = dict(
    c0a=2100.0,
    c0b=350.0,
    k0=4690.0,
    c1a=28300.0,
    c1b=295.0,
    k1=500.0,
    x0=0.143,
    alpha_a=14000.0,
    alpha_b=69500.0,
    alpha_c=0.0,
    gamma=3.63e6,
    beta=3.63e6,
    delta=301.0,
    n=2.0,
    eta=190.0,
)
# displacement: 1.1 cm multisine 0.5-15 Hz (band of Dyke's random records); voltage 0-2.25 V, smooth, 2 and 7 Hz
_rng = np.random.default_rng(0)
_F, _PH = _rng.uniform(0.5, 15.0, 12), _rng.uniform(0, 2 * np.pi, 12)
_AMP = 0.011 / 7.0


def x_of(t):
    return _AMP * np.sum(np.sin(2 * np.pi * _F[:, None] * np.atleast_1d(t) + _PH[:, None]), axis=0)


def v_of(t):
    return _AMP * np.sum(
        2 * np.pi * _F[:, None] * np.cos(2 * np.pi * _F[:, None] * np.atleast_1d(t) + _PH[:, None]), axis=0
    )


def u_of(t):
    return 1.125 * (1.0 + 0.6 * np.sin(2 * np.pi * 2.0 * t) + 0.4 * np.sin(2 * np.pi * 7.0 * t + 1.0))


def _scalar(f):
    """A fast scalar version of x_of / v_of for the ODE right-hand sides."""
    F, PH, A = _F.tolist(), _PH.tolist(), _AMP
    if f == "x":
        return lambda t: A * sum(math.sin(2 * math.pi * a * t + b) for a, b in zip(F, PH))
    return lambda t: A * sum(2 * math.pi * a * math.cos(2 * math.pi * a * t + b) for a, b in zip(F, PH))


def record(duration, control=False):
    t = np.arange(0.0, duration, 1.0 / FS)
    if control:
        return Measurement.from_arrays(t, x_of(t), control=u_of(t), control_kind="voltage", velocity=v_of(t))
    return Measurement.from_arrays(t, x_of(t), velocity=v_of(t))


def timed(fn, repeat=5):
    best = math.inf
    out = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def ivp(rhs, y0, t, method, rtol):
    """solve_ivp on the analytic inputs: rhs(t, y, x(t), v(t), u(t))."""
    x, v = _scalar("x"), _scalar("v")

    def f(tt, y):
        return rhs(tt, y, x(tt), v(tt), float(u_of(tt)))

    t0 = time.perf_counter()
    sol = solve_ivp(f, (t[0], t[-1]), y0, t_eval=t, method=method, rtol=rtol, atol=1e-14)
    return time.perf_counter() - t0, sol.y


def piecewise_reference(rhs, y0, rec, method):
    """The same model for the record's samples read as the kernels read them (motion and control linear between
    samples), by solve_ivp at rtol 1e-11 on each sample interval (each is one smooth ODE)."""
    t, x, u = rec.time, rec.displacement, rec.control
    y = np.asarray(y0, dtype=float)
    out = [y]
    for i in range(t.size - 1):
        h = t[i + 1] - t[i]
        xd, r = (x[i + 1] - x[i]) / h, (u[i + 1] - u[i]) / h

        def f(s, yy, i=i, xd=xd, r=r):
            return rhs(t[i] + s, yy, x[i] + xd * s, xd, u[i] + r * s)

        y = solve_ivp(f, (0.0, h), y, method=method, rtol=1e-11, atol=1e-15).y[:, -1]
        out.append(y)
    return np.array(out).T


# --------------------------------------------------------------------------------------------------- the models
# Each case: (run the erdesign model, rhs(t, y, x, v, u) of its ODE, initial state, force from the states, the
# reference method).  Parameters: the ones the tests use.
def case_modified_bouc_wen(rec):
    p = SPENCER_1997
    model = get_model("bouc_wen_modified")

    def rhs(t, s, x, v, u):
        uf, w, z = s
        al, c0, c1 = p["alpha_a"] + p["alpha_b"] * uf, p["c0a"] + p["c0b"] * uf, p["c1a"] + p["c1b"] * uf
        wd = (c1 * v - al * z - p["k0"] * w) / (c0 + c1)
        return [-p["eta"] * (uf - u), wd, wd * p["delta"] - p["gamma"] * abs(wd) * z * abs(z) - p["beta"] * wd * z * z]

    def force(y, rec):
        uf, w, z = y
        al, c0, c1 = p["alpha_a"] + p["alpha_b"] * uf, p["c0a"] + p["c0b"] * uf, p["c1a"] + p["c1b"] * uf
        return c1 * (al * z + c0 * rec.velocity + p["k0"] * w) / (c0 + c1) + p["k1"] * (rec.displacement - p["x0"])

    return (lambda r: model.simulate(r, p)), rhs, [float(rec.control[0]), 0.0, 0.0], force, "LSODA"


def case_bouc_wen(rec):
    p = dict(c0a=5300.0, k0=1400.0, x0=0.0, alpha_a=96300.0, beta=2e6, gamma=2e6, delta=207.0, n=2.0)
    model = get_model("bouc_wen")

    def rhs(t, s, x, v, u):
        z = s[0]
        return [-p["gamma"] * abs(v) * z * abs(z) - p["beta"] * v * z * z + p["delta"] * v]

    def force(y, rec):
        return p["c0a"] * rec.velocity + p["k0"] * rec.displacement + p["alpha_a"] * y[0]

    return (lambda r: model.simulate(r, p)), rhs, [0.0], force, "LSODA"


def case_bouc_wen_normalized(rec):
    p = dict(k_x=1000.0, k_v=3000.0, k_w=500.0, rho=800.0, sigma=1.5, n=1.0, f0=0.0)
    model = get_model("bouc_wen_normalized")

    def rhs(t, s, x, v, u):
        w = s[0]
        return [p["rho"] * (v - p["sigma"] * abs(v) * w + (p["sigma"] - 1.0) * v * abs(w))]

    def force(y, rec):
        return p["k_x"] * rec.displacement + p["k_v"] * rec.velocity + p["k_w"] * y[0]

    return (lambda r: model.simulate(r, p)), rhs, [0.0], force, "LSODA"


def case_dahl(rec):
    p = dict(k0=1000.0, c0=2500.0, f_d=500.0, rho=2000.0, f0=0.0)
    model = get_model("dahl")

    def rhs(t, s, x, v, u):
        return [p["rho"] * (v - abs(v) * s[0])]

    def force(y, rec):
        return p["k0"] * rec.displacement + p["c0"] * rec.velocity + p["f_d"] * y[0]

    return (lambda r: model.simulate(r, p)), rhs, [0.0], force, "LSODA"


def case_lugre(rec):
    p = dict(sigma0=5e5, sigma1=0.0, sigma2=2500.0, a0=2e-3, f0=0.0)
    model = get_model("lugre")
    kappa = p["sigma0"] * p["a0"]

    def rhs(t, s, x, v, u):
        return [v - kappa * abs(v) * s[0]]

    def force(y, rec):
        return p["sigma0"] * y[0] + p["sigma2"] * rec.velocity

    return (lambda r: model.simulate(r, p)), rhs, [0.0], force, "LSODA"


def case_bingham_extended(rec):
    p = dict(c0=3000.0, f_c=400.0, k1=5e4, c1=3e4, k2=3e5, f0=0.0)
    model = get_model("bingham_extended")

    def rhs(t, s, x, v, u):
        x1, e = s
        F = p["k2"] * (x - x1 - e)
        d = math.copysign(max(abs(F) - p["f_c"], 0.0), F)
        return [d / p["c0"], (F - p["k1"] * e) / p["c1"]]

    def force(y, rec):
        return p["k2"] * (rec.displacement - y[0] - y[1])

    return (lambda r: model.simulate(r, p)), rhs, [float(rec.displacement[0]), 0.0], force, "Radau"


CASES = {
    "bouc_wen_modified (Spencer 1997, voltage)": (case_modified_bouc_wen, True),
    "bouc_wen": (case_bouc_wen, False),
    "bouc_wen_normalized": (case_bouc_wen_normalized, False),
    "dahl": (case_dahl, False),
    "lugre": (case_lugre, False),
    "bingham_extended": (case_bingham_extended, False),
}


def kernel_table(duration=20.0, error_duration=1.0):
    """Speed on ``duration`` seconds; error on the first ``error_duration`` seconds (the per-interval reference
    costs about a millisecond per sample)."""
    rows = []
    for label, (case, control) in CASES.items():
        rec = record(duration, control)
        run, rhs, y0, force, ref_method = case(rec)
        t0 = time.perf_counter()
        run(rec)
        first = time.perf_counter() - t0
        fast, F = timed(lambda: run(rec))
        t_lsoda, _ = ivp(rhs, y0, rec.time, "LSODA", 1e-8)
        short = rec.select(slice(0, int(error_duration * FS)))
        y_ref = piecewise_reference(rhs, y0, short, ref_method)
        F_ref = force(y_ref, short)
        F_short = run(short)
        row = {
            "model": label,
            "samples": len(rec),
            "first_call_s": first,
            "kernel_s": fast,
            "lsoda_1e-8_s": t_lsoda,
            "ratio_vs_lsoda": t_lsoda / fast,
            "ns_per_sample": fast / len(rec) * 1e9,
            "max_error": float(np.max(np.abs(F_short - F_ref)) / np.ptp(F_ref)),
        }
        rows.append(row)
        print(
            f"  {label:<42} kernel {fast * 1e3:8.2f} ms ({row['ns_per_sample']:5.0f} ns/sample; first call "
            f"{first:.2f} s)   LSODA (rtol 1e-8) {t_lsoda:6.2f} s   ratio {row['ratio_vs_lsoda']:6.0f} x   "
            f"max error vs {ref_method} (rtol 1e-11) {row['max_error']:.1e}",
            flush=True,
        )
    return rows


def kamath_wereley_identification(n=20_000):
    t = np.linspace(0, 2.0, n)
    rec = Measurement.from_arrays(t, 1e-3 * np.sin(2 * np.pi * 10 * t))
    model = get_model("kamath_wereley_6")
    clean = model.simulate(rec, KAMATH_WERELEY_TABLE1)
    data = rec.with_force(clean + 0.01 * np.std(clean) * np.random.default_rng(0).standard_normal(n))
    t0 = time.perf_counter()
    r = fit(model, data)
    return {
        "seconds": time.perf_counter() - t0,
        "esr": r.esr,
        "nfev": r.nfev,
        "max_rel_param_error": max(
            abs(r.values[k] / KAMATH_WERELEY_TABLE1[k] - 1) for k in ("C1", "C2", "K1", "Cv", "R")
        ),
    }


if __name__ == "__main__":
    quick = "--quick" in sys.argv
    duration = 2.0 if quick else 20.0
    print(f"time-stepping models, {duration:g} s at {FS:g} Hz ({int(duration * FS)} samples), same process:")
    kernel_table(duration)
    _ = SPENCER_PASSIVE
    print(
        "Kamath-Wereley 6-parameter identification, 20,000 samples:",
        {k: round(v, 4) for k, v in kamath_wereley_identification().items()},
    )
