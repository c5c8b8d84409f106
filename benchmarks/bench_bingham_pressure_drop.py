"""Benchmark: closed-form Bingham pressure drop dp(Q) for 10^6 flows against np.roots per element.

Run:  python benchmarks/bench_bingham_pressure_drop.py [--n 1000000] [--roots-sample 2000]

Prints the time per element of erdesign.flow.bingham_pressure_drop on one core, the time per element of solving
the same corrected Makris cubic (eq 7 with h^3) with np.roots element by element (timed on a sample and scaled),
their ratio, and the largest relative difference between the two.  Targets (issue 2): at least 100x faster than
np.roots and under 100 ns per element.  Not a test: timings depend on the machine.
"""

from __future__ import annotations

import argparse
import math
import os
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")  # one core, as the target says

import numpy as np  # noqa: E402

from erdesign.flow import bingham_pressure_drop  # noqa: E402

L, d, h = 0.0546, 0.0143, 0.0008  # Makris duct
TAU_Y, ETA = 1800.0, 13.0


def flows(n: int, seed: int = 1) -> np.ndarray:
    """Signed flows spanning Bingham numbers 1e-3 .. 1e5 (log-uniform) so every regime is exercised."""
    rng = np.random.default_rng(seed)
    bingham = 10.0 ** rng.uniform(-3, 5, n)
    return TAU_Y * h * math.pi * d * h / (ETA * bingham) * rng.choice([-1.0, 1.0], n)


def with_np_roots(Q: np.ndarray) -> np.ndarray:
    out = np.empty_like(Q)
    for i, q in enumerate(Q):
        dpN = 12 * ETA * L * abs(q) / (math.pi * d * h**3)
        r = np.roots([1.0, -(3 * TAU_Y * L / h + dpN), 0.0, 4 * TAU_Y**3 * (L / h) ** 3])
        out[i] = math.copysign(r.real.max(), q)
    return out


def best_of(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=1_000_000)
    parser.add_argument("--roots-sample", type=int, default=2000)
    args = parser.parse_args()

    Q = flows(args.n)
    t_closed = best_of(lambda: bingham_pressure_drop(Q, TAU_Y, ETA, L, d, h), repeat=5) / args.n
    sample = Q[: args.roots_sample]
    t_roots = best_of(lambda: with_np_roots(sample), repeat=2) / sample.size
    diff = np.max(np.abs(bingham_pressure_drop(sample, TAU_Y, ETA, L, d, h) / with_np_roots(sample) - 1))

    print(f"closed form : {t_closed * 1e9:8.1f} ns per element ({args.n:,} flows)")
    print(f"np.roots    : {t_roots * 1e9:8.1f} ns per element ({sample.size:,} flows, same run)")
    print(f"speed-up    : {t_roots / t_closed:8.0f} x   (target >= 100 x)")
    print(f"max |rel diff| closed form vs np.roots: {diff:.1e}")


if __name__ == "__main__":
    main()
