"""Benchmark: the kernels of issue 27's table, each against a baseline timed in the same process.

Run:  python benchmarks/bench_kernels_speed.py [--quick] [--only {annulus,mixed,dp,reading}]

One row per line of the table, each printing "now", the baseline and their ratio:

1. exact Bingham annulus dp(Q) (erdesign.flow.annulus_bingham_pressure_drop), per element, against the thin-gap
   kernel on the same flows (erdesign.flow.bingham_pressure_drop: the numpy path, below 4096 elements, and the
   compiled one); goal <= 10 x the thin-gap kernel;
2. mixed-mode (moving-electrode) damper force (erdesign.flow.mixed_mode_damper_force), per element, against the
   thin-gap kernel; goal <= 10 x; and the mixed-mode design sweep in designs per second against the valve sweep
   (examples mr_requirements and makris_requirements, no refinement); goal >= 500 k designs/s;
3. Bingham dp(Q) on 1e7 flows against a plain numba loop of the same closed form (written here); goal >= 0.8 x the
   loop's speed;
4. reading a 60,000-row measurement (erdesign.data.read_measurement, velocity and acceleration derived) against
   pandas.read_csv of the same file, for a non-periodic record (band-limited random motion: the periodicity test
   rejects it) and a periodic one (a sine: the harmonic fits run), with pandas loaded and, in a fresh interpreter,
   without; goal <= 2 x pandas.read_csv.  Every timed read is a first read: the Butterworth design that the reader
   keeps for the next record of the same rate and cut-off is cleared before it (one more line shows a read that
   finds it kept).  The fresh interpreter reads once before the timed reads (imports and first calls are not
   counted).

Each figure is the least CPU time (time.process_time) of several runs, interleaved with its baseline's (the machine
may be shared).  One BLAS thread (OMP_NUM_THREADS=1).  Not a
test: timings depend on the machine; docs/performance.md records a run.
"""

from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")

import numba
import numpy as np

from erdesign.flow import (
    annulus_bingham_pressure_drop,
    bingham_pressure_drop,
    mixed_mode_damper_force,
)

ROOT = Path(__file__).resolve().parents[1]
L, d, h = 0.0546, 0.0143, 0.0008  # Makris duct
TAU_Y, ETA = 1800.0, 13.0


def best_of(fn, repeat: int) -> float:
    """Least CPU time of the process over ``repeat`` runs: on a shared machine the wall time of a long call also
    counts the time other processes held the core (a 50 ms call was measured 4 x slower per element than a 1 ms
    one of the same work at a load average of 12), the CPU time does not (one thread: OMP_NUM_THREADS=1)."""
    times = []
    for _ in range(repeat):
        t0 = time.process_time()
        fn()
        times.append(time.process_time() - t0)
    return min(times)


def paired(*fns, repeat: int) -> list[float]:
    """Best time of each function, their runs interleaved so that each sees the same (shared) machine load."""
    times = [[] for _ in fns]
    for _ in range(repeat):
        for fn, t in zip(fns, times):
            t.append(best_of(fn, 1))
    return [min(t) for t in times]


def flows(n: int, seed: int = 1) -> np.ndarray:
    """Signed flows over Bingham numbers 1e-3 .. 1e5 (log-uniform): every regime from nearly Newtonian to nearly
    blocked."""
    rng = np.random.default_rng(seed)
    bingham = 10.0 ** rng.uniform(-3, 5, n)
    return TAU_Y * h * math.pi * d * h / (ETA * bingham) * rng.choice([-1.0, 1.0], n)


def thin_gap_numpy(Q):
    """The thin-gap kernel's numpy path: chunks below the compiled path's threshold."""
    return np.concatenate([bingham_pressure_drop(Q[i : i + 4000], TAU_Y, ETA, L, d, h) for i in range(0, Q.size, 4000)])


def row(label: str, now: float, base: float, unit: str, base_label: str, goal: str, scale: float = 1e6) -> None:
    print(
        f"{label:<44s} {now * scale:9.3f} {unit}  {base_label} {base * scale:9.3f} {unit}  "
        f"ratio {now / base:7.2f}   ({goal})"
    )


def annulus_row(n: int, repeat: int) -> None:
    Q = flows(n)
    annulus_bingham_pressure_drop(Q[:8], TAU_Y, ETA, L, d, h)  # load the compiled code
    t_ann, t_np, t_c = (
        t / n
        for t in paired(
            lambda: annulus_bingham_pressure_drop(Q, TAU_Y, ETA, L, d, h),
            lambda: thin_gap_numpy(Q),
            lambda: bingham_pressure_drop(Q, TAU_Y, ETA, L, d, h),
            repeat=repeat,
        )
    )
    row("1 exact annulus dp(Q), per element", t_ann, t_np, "us", "thin gap (numpy)", "goal <= 10")
    row("", t_ann, t_c, "us", "thin gap (compiled)", "same, against the compiled thin gap")


def mixed_rows(n: int, designs: int, repeat: int) -> None:
    rng = np.random.default_rng(2)
    v = rng.uniform(-0.3, 0.3, n)
    args = (2000.0, 0.1, 0.02, 0.03, 0.01, 1e-3)
    mixed_mode_damper_force(v[:8], *args)
    Q = flows(n)
    t_mix, t_np, t_c = (
        t / n
        for t in paired(
            lambda: mixed_mode_damper_force(v, *args),
            lambda: thin_gap_numpy(Q),
            lambda: bingham_pressure_drop(Q, TAU_Y, ETA, L, d, h),
            repeat=repeat,
        )
    )
    row("2 mixed-mode force, per element", t_mix, t_np, "us", "thin gap (numpy)", "goal <= 10")
    row("", t_mix, t_c, "us", "thin gap (compiled)", "same, against the compiled thin gap")

    from erdesign.design import design, load_example_requirements

    mixed = load_example_requirements("mr_requirements").with_search(samples=designs, chunk=2**16, refine=False)
    valve = load_example_requirements("makris_requirements").with_search(samples=designs, chunk=2**16, refine=False)
    design(mixed.with_search(samples=2**12, chunk=2**16, refine=False))
    design(valve.with_search(samples=2**12, chunk=2**16, refine=False))
    t_m, t_v = paired(lambda: design(mixed), lambda: design(valve), repeat=max(1, repeat - 2))
    print(
        f"{'  mixed design sweep':<44s} {designs / t_m / 1e3:9.1f} k/s  valve sweep {designs / t_v / 1e3:9.1f} "
        f"k/s  ratio {t_v / t_m:7.2f}   (goal >= 500 k designs/s; {len(mixed.points)} design points, "
        f"valve {len(valve.points)})"
    )


@numba.njit(cache=True)
def _numba_loop(Q, tau_y, eta, L, d, h, out):
    """The reference: the corrected Makris cubic's trigonometric root with Newton steps near the blocked gap, one
    element at a time (bingham_slit_flow's arithmetic, plain)."""
    dp_y = 2.0 * tau_y * L / h
    c = 12.0 * eta * L / (math.pi * d * h**3)
    for i in range(Q.size):
        N = c * abs(Q[i]) / dp_y
        if N < 0.5:
            e = math.sqrt(2.0 * N / 3.0)
            for _ in range(6):
                g = e * e * (3.0 - e) - 2.0 * N * (1.0 - e)
                slope = 6.0 * e - 3.0 * e * e + 2.0 * N
                if slope > 0.0:
                    e -= g / slope
            phi = 1.0 - e
        else:
            m = math.sqrt(1.0 + 2.0 * N / 3.0)
            phi = 2.0 * m * math.sin(math.asin(m**-3) / 3.0)
        out[i] = math.copysign(dp_y / phi, Q[i])
    return out


def dp_row(n: int, repeat: int) -> None:
    Q = flows(n)
    out = np.empty(n)
    _numba_loop(Q[:8], TAU_Y, ETA, L, d, h, out[:8])
    bingham_pressure_drop(Q[:5000], TAU_Y, ETA, L, d, h)
    # the loop allocates its output, as a function returning a new array must
    t_now, t_loop = paired(
        lambda: bingham_pressure_drop(Q, TAU_Y, ETA, L, d, h),
        lambda: _numba_loop(Q, TAU_Y, ETA, L, d, h, np.empty(n)),
        repeat=repeat,
    )
    _numba_loop(Q, TAU_Y, ETA, L, d, h, out)
    diff = np.max(np.abs(bingham_pressure_drop(Q, TAU_Y, ETA, L, d, h) / out - 1.0))
    row(
        f"3 Bingham dp(Q), {n:.0e} elements, per element",
        t_now / n,
        t_loop / n,
        "ns",
        "numba loop",
        f"goal: ratio <= 1.25, i.e. >= 0.8 x the loop's speed; max |rel diff| {diff:.1e}",
        scale=1e9,
    )


def write_records(folder: Path, n: int) -> dict[str, Path]:
    from erdesign.simulation.rig import random_motion

    rate = 2000.0
    t = np.arange(n) / rate
    rng = np.random.default_rng(3)
    random = random_motion(0.005, (0.5, 5.0), duration=(n - 1) / rate, rate=rate, seed=3)
    x_random = np.interp(t, random.time, random.displacement)
    x_sine = 0.01 * np.sin(2 * np.pi * 2.0 * t) + 2e-6 * rng.normal(size=n)
    paths = {}
    for name, x in (("non-periodic (random)", x_random), ("periodic (sine)", x_sine)):
        path = folder / f"{name.split()[0]}.csv"
        force = 500.0 * np.tanh(np.gradient(x, t) / 0.01) + rng.normal(size=n)
        with open(path, "w") as fh:
            fh.write("time [s],displacement [m],force [N]\n")
            np.savetxt(fh, np.column_stack([t, x, force]), delimiter=",", fmt="%.10g")
        paths[name] = path
    return paths


_WITHOUT_PANDAS = """
import sys, time
sys.path.insert(0, {root!r})
from erdesign.data.measurement import _butterworth, read_measurement
read_measurement({path!r})
best = min((lambda t0: (_butterworth.cache_clear(), read_measurement({path!r}), time.process_time() - t0)[2])(
    time.process_time()) for _ in range({repeat}))
assert 'pandas' not in sys.modules
print(best)
"""


def reading_rows(n: int, repeat: int) -> None:
    import pandas as pd

    from erdesign.data.measurement import _butterworth, read_measurement

    def first_read(path):
        _butterworth.cache_clear()  # a new record: its low-pass designed again
        return read_measurement(path)

    with tempfile.TemporaryDirectory() as tmp:
        for name, path in write_records(Path(tmp), n).items():
            read_measurement(path)
            t_read, t_again, t_pd = paired(
                lambda p=path: first_read(p),
                lambda p=path: read_measurement(p),
                lambda p=path: pd.read_csv(p),
                repeat=repeat,
            )
            code = _WITHOUT_PANDAS.format(root=str(ROOT), path=str(path), repeat=repeat)
            out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
            t_bare = float(out.stdout.strip().splitlines()[-1])
            row(
                f"4 read {n:,} rows, {name}",
                t_read,
                t_pd,
                "ms",
                "pandas.read_csv",
                "goal <= 2, pandas loaded",
                scale=1e3,
            )
            row("", t_bare, t_pd, "ms", "pandas.read_csv", "goal <= 2, pandas not loaded", scale=1e3)
            row("", t_again, t_pd, "ms", "pandas.read_csv", "pandas loaded, the filter design kept", scale=1e3)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller sizes (a smoke run)")
    parser.add_argument("--only", choices=("annulus", "mixed", "dp", "reading"), help="run one row of the table")
    args = parser.parse_args()
    repeat = 2 if args.quick else 7
    rows = {
        "annulus": lambda: annulus_row(2_000 if args.quick else 20_000, repeat),
        "mixed": lambda: mixed_rows(2_000 if args.quick else 20_000, 20_000 if args.quick else 200_000, repeat),
        "dp": lambda: dp_row(10**6 if args.quick else 10**7, repeat),
        # 15 ms a read: the best of 42 reads, steadier on a shared machine
        "reading": lambda: reading_rows(60_000, 6 * repeat),
    }
    for name, run in rows.items():
        if args.only in (None, name):
            run()


if __name__ == "__main__":
    main()
