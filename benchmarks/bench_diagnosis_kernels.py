"""Benchmark: the loops a diagnosis spends most in, each against a baseline run in the same process.

* the compressible column (:func:`erdesign.effects.compressibility.compliant_pressure_force`, compiled backward
  Euler with a root per substep) against :func:`scipy.integrate.solve_ivp` (Radau, rtol 1e-8) on the same series
  ODE dP/dt = k (v - u(P)) of a Bingham valve; the largest difference is printed beside the ratio;
* the Herschel-Bulkley pressure drop of a flow (:func:`erdesign.flow.herschel_bulkley.herschel_bulkley_pressure_drop`,
  compiled Newton) against scipy's elementwise ``bracket_root`` + ``find_root`` on the same equation (the code it
  replaced), on 6,600 flows (a diagnosis-sized record);
* the pressure drop of a damper with a bypass in parallel (:func:`erdesign.effects.leakage.leaky_pressure_drop` with
  the physics damper's gap, compiled per element) against the same equation solved on whole arrays
  (:func:`erdesign.numerics.find_root`, the generic path), on a moving-electrode head (Spencer et al. 1997) and on a
  valve (Makris 1996), 6,600 samples from creep to full flow; and the head's table read in one compiled pass
  (:meth:`erdesign.damper.quasi_steady.MixedGapTable.forces`) against the same read by ``np.interp``.

Run: ``python benchmarks/bench_diagnosis_kernels.py`` (with erdesign installed from this checkout, as the README's
commands do; otherwise ``PYTHONPATH=.``) (CPU time, best of 7 interleaved runs, one BLAS thread).
"""

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import math  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from erdesign.effects.base import DuctLaw  # noqa: E402
from erdesign.effects.compressibility import _piston_speed, compliant_pressure_force  # noqa: E402
from erdesign.flow.herschel_bulkley import (  # noqa: E402
    _slit_flow_rate,
    herschel_bulkley_pressure_drop,
)


def paired(*fns, repeat: int = 7) -> list[float]:
    """Least CPU time of each function, their runs interleaved so that each sees the same machine load."""
    best = [math.inf] * len(fns)
    for _ in range(repeat):
        for i, fn in enumerate(fns):
            t0 = time.process_time()
            fn()
            best[i] = min(best[i], time.process_time() - t0)
    return best


def column_rows() -> None:
    from scipy.integrate import solve_ivp

    n = 2001  # 2 s at 1 kHz: a sine with a field step
    t = np.linspace(0.0, 2.0, n)
    v = 0.2 * np.sin(2 * np.pi * 2.0 * t)
    tau = np.where(t < 1.0, 2e4, 2e3)
    L, dm, h, Ap = 0.05, 0.05, 1e-3, 1.2e-3
    law = DuctLaw(0, tau, np.full(n, 0.3), 1.0, L, dm, h, Ap, 1)
    for k in (1e5, 1e6, 1e7):
        ours = lambda: compliant_pressure_force(t, v, k, law, 0.0)  # noqa: E731, B023

        def rhs(s, P, k=k):
            i = min(int(s * 1000.0), n - 1)  # the sample's control (zero-order hold, as the loop)
            vs = np.interp(s, t, v)
            return [k * (vs - _piston_speed(P[0], vs, 0, tau[i], 0.3, 1.0, L, dm, h, Ap, 1, 0.0))]

        ref = lambda: solve_ivp(rhs, (0.0, 2.0), [0.0], method="Radau", t_eval=t, rtol=1e-8, atol=1e-6)  # noqa: E731
        ours()
        t_ours, t_ref = paired(ours, ref, repeat=3)
        P, R = ours(), ref().y[0]
        # away from the field step: the loop takes a sample's new control in its last substep, the reference
        # from the sample on, so the two differ there by the step itself for a millisecond
        away = np.abs(t - 1.0) > 0.005
        diff = np.max(np.abs(P - R)[away]) / np.max(np.abs(R))
        print(
            f"compressible column, k = {k:.0e} N/m, {n} samples: {t_ours * 1e3:8.2f} ms  solve_ivp Radau "
            f"{t_ref * 1e3:9.1f} ms  ratio {t_ours / t_ref:8.4f}   (max |difference| {diff:.1e} of the peak "
            "outside the field step)"
        )


def _hb_scipy(Q, tau_y, K, m, L, d, h):
    """The pressure drop of scipy's elementwise bracket_root + find_root on ln(dp) (the code before the loop)."""
    from scipy.optimize.elementwise import bracket_root, find_root

    Q = np.asarray(Q, dtype=float)
    tau_y, K = np.broadcast_arrays(np.asarray(tau_y, dtype=float) + 0 * Q, np.asarray(K, dtype=float) + 0 * Q)
    Qa = np.abs(Q)
    dp_y = 2.0 * tau_y * L / h
    p = 1.0 / m
    with np.errstate(divide="ignore"):
        tau_pl = (Qa / (np.pi * d) * (p + 2) * K**p / (2 * (0.5 * h) ** 2)) ** (1.0 / p)
    x0 = np.log(np.maximum(dp_y + tau_pl * 2.0 * L / h, np.maximum(dp_y, 1e-300) * (1 + 1e-12)) + 1e-300)

    def f(logdp, Qa, tau_y, K):
        return _slit_flow_rate(np.exp(logdp), tau_y, K, m, L, d, h) - Qa

    flowing = Qa > 0
    out = np.array(dp_y, dtype=float)
    a = (Qa[flowing], tau_y[flowing], K[flowing])
    xf = x0[flowing]
    xmin = np.where(dp_y[flowing] > 0, np.log(np.maximum(dp_y[flowing], 1e-300)), xf - 60.0)
    br = bracket_root(f, np.maximum(xf - 0.5, xmin), xf + 0.5, xmin=xmin, args=a, maxiter=200)
    res = find_root(f, (br.bracket[0], br.bracket[1]), args=a, tolerances={"xatol": 1e-13, "xrtol": 0})
    out[flowing] = np.exp(res.x)
    return np.copysign(out, Q)


def hb_row() -> None:
    n = 6600
    t = np.linspace(0.0, 10.0, n)
    Q = 2e-5 * np.sin(2 * np.pi * t) * (1 + 0.3 * np.sin(7 * t))
    tau = np.where((t % 3) < 1.5, 2e4, 2e3)
    K = np.full(n, 0.5)
    args = (Q, tau, K, 0.7, 0.05, 0.02, 1e-3)
    herschel_bulkley_pressure_drop(*args)
    t_now, t_base = paired(lambda: herschel_bulkley_pressure_drop(*args), lambda: _hb_scipy(*args))
    diff = np.max(np.abs(herschel_bulkley_pressure_drop(*args) / _hb_scipy(*args) - 1))
    print(
        f"Herschel-Bulkley dp(Q), {n} flows: {t_now * 1e3:8.2f} ms  scipy elementwise roots {t_base * 1e3:8.2f} ms  "
        f"ratio {t_now / t_base:6.3f}   (max relative difference {diff:.1e})"
    )


def leakage_rows() -> None:
    from erdesign.damper.files import load_example
    from erdesign.effects.base import GapLaw
    from erdesign.effects.chain import PhysicsDamper, _GapDrop
    from erdesign.effects.leakage import leaky_pressure_drop

    n = 6600
    t = np.linspace(0.0, 10.0, n)
    v = 0.2 * np.sin(2 * np.pi * t) * (1 + 0.3 * np.sin(7 * t))
    tau = np.where((t % 3) < 1.5, 2e4, 2e3)
    eta = np.full(n, 0.3)
    for name in ("spencer1997", "makris"):
        d = load_example(name)
        gap = _GapDrop(PhysicsDamper(d, ["leakage"]), GapLaw())
        Ap, C_l = d.geometry.piston_area, 2e4
        fast = lambda: leaky_pressure_drop(v, Ap, C_l, gap, args=(v, tau, eta))  # noqa: E731
        slow = lambda: leaky_pressure_drop(v, Ap, C_l, lambda *a: gap(*a), args=(v, tau, eta))  # noqa: E731
        fast()
        t_now, t_base = paired(fast, slow)
        diff = np.max(np.abs(fast() - slow())) / np.max(np.abs(slow()))
        print(
            f"bypass root, {d.geometry.configuration} ({name}), {n} samples: {t_now * 1e3:8.2f} ms  whole-array "
            f"Chandrupatla {t_base * 1e3:8.2f} ms  ratio {t_now / t_base:6.3f}   (max difference {diff:.1e} of the "
            "largest drop)"
        )
    table = PhysicsDamper(load_example("spencer1997"), [])._mixed_table()
    L = 0.0254

    def interp():
        scale = eta * np.abs(v) + tau * table.h
        w = np.sqrt(np.where(scale > 0, eta * np.abs(v) / scale, 1.0))
        sign = np.copysign(1.0, v)
        dp = sign * np.interp(w, table.w, table.pressure) * scale / table.h**2 * L
        return dp, -sign * np.interp(w, table.w, table.shear) * scale / table.h * np.pi * table.Dp * L

    table.forces(v, tau, eta, L)
    t_now, t_base = paired(lambda: table.forces(v, tau, eta, L), interp, repeat=50)
    diff = np.max(np.abs(table.forces(v, tau, eta, L)[0] / interp()[0] - 1))
    print(
        f"mixed head table, {n} samples: {t_now * 1e6:8.1f} us  np.interp {t_base * 1e6:8.1f} us  "
        f"ratio {t_now / t_base:6.3f}   (max relative difference {diff:.1e})"
    )


if __name__ == "__main__":
    column_rows()
    hb_row()
    leakage_rows()
