"""Benchmark: candidate designs per second and peak memory of the design sweep (issue 7).

Run:  python benchmarks/bench_design_sweep.py [--n 1000000] [--big 10000000] [--chunk 65536] [--mixed 100000]

Requirements: examples/requirements/makris_requirements.toml (valve damper, one design point, ten constraints).
Prints, on one core:

1. evaluation only - :func:`erdesign.design.evaluate_candidates` on ``--n`` ready-made candidates, chunk by chunk:
   the cost of the physics and the constraint margins;
2. the whole sweep of :func:`erdesign.design.design` without refinement (Sobol' sampling, evaluation, the running
   best designs, Pareto front, nearest designs and violation counts) on ``--n`` candidates, with its peak traced
   memory (tracemalloc, measured in a second run so that tracing does not slow the timed one);
3. the same sweep on ``--big`` candidates (run ``--big 100000000`` for the 10^8 figure of docs/design.md), whose
   peak memory must match that of ``--n``: memory follows the chunk, not the sweep;
4. the mixed-mode (moving-electrode) damper, whose kernel finds a root per element (compiled), on ``--mixed``
   candidates (examples/requirements/mr_requirements.toml, two design points).

Target (issue 7): at least 10^6 designs per second on one core at one design point.  Not a test: timings depend on
the machine.
"""

from __future__ import annotations

import argparse
import os
import resource
import time
import tracemalloc

os.environ.setdefault("OMP_NUM_THREADS", "1")  # one core, as the target says

import numpy as np  # noqa: E402

from erdesign.design import design, evaluate_candidates, load_example_requirements  # noqa: E402
from erdesign.design.evaluate import constraints_for  # noqa: E402
from erdesign.design.sampling import candidate_chunks  # noqa: E402


def evaluation_only(req, n: int, chunk: int) -> float:
    """Seconds to evaluate n candidates (sampled beforehand, one chunk reused) at every design point."""
    (x,) = list(candidate_chunks(req, samples=chunk, chunk=chunk))
    constraints = constraints_for(req)
    t0 = time.perf_counter()
    done = 0
    while done < n:
        m = min(chunk, n - done)
        evaluate_candidates(
            req,
            *(
                None if x[k] is None else x[k][:m]
                for k in ("gap", "duct_length", "duct_mean_diameter", "piston_diameter", "rod_diameter", "ducts")
            ),
            constraints=constraints,
        ).feasible.sum()
        done += m
    return time.perf_counter() - t0


def sweep(req, n: int, chunk: int, trace: bool = False) -> tuple[float, int, int]:
    """(seconds, feasible count, peak traced bytes or 0) of the chunked sweep without refinement."""
    r = req.with_search(samples=n, chunk=chunk, refine=False)
    if trace:
        tracemalloc.start()
    t0 = time.perf_counter()
    result = design(r)
    dt = time.perf_counter() - t0
    peak = 0
    if trace:
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    return dt, result.feasible_count, peak


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=1_000_000, help="candidates for the speed figures")
    parser.add_argument("--big", type=int, default=10_000_000, help="candidates for the bounded-memory run")
    parser.add_argument("--chunk", type=int, default=2**16)
    parser.add_argument("--mixed", type=int, default=100_000, help="mixed-mode candidates (0 to skip)")
    args = parser.parse_args()

    req = load_example_requirements("makris_requirements")
    print(
        f"valve damper, {len(req.points)} design point, {len(constraints_for(req))} constraints, chunk {args.chunk:,}"
    )
    sweep(req, min(args.n, 2**16), args.chunk)  # warm up (imports, caches)

    t = evaluation_only(req, args.n, args.chunk)
    print(
        f"evaluation only : {args.n / t / 1e6:6.2f} M designs/s   ({t * 1e9 / args.n:6.0f} ns per design, "
        f"{args.n:,} designs)"
    )
    t, feasible, _ = sweep(req, args.n, args.chunk)
    _, _, peak = sweep(req, args.n, args.chunk, trace=True)
    print(
        f"whole sweep     : {args.n / t / 1e6:6.2f} M designs/s   ({t:6.2f} s, {feasible:,} feasible), "
        f"peak traced memory {peak / 2**20:6.1f} MiB"
    )
    if args.big:
        t, feasible, _ = sweep(req, args.big, args.chunk)
        _, _, peak_big = sweep(req, args.big, args.chunk, trace=True) if args.big <= 10**7 else (0, 0, 0)
        shown = f"peak traced memory {peak_big / 2**20:6.1f} MiB" if peak_big else "(not traced above 10^7)"
        print(
            f"big sweep       : {args.big / t / 1e6:6.2f} M designs/s   ({t:6.1f} s, {feasible:,} feasible, "
            f"{args.big:,} designs), {shown}"
        )
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"process peak resident memory: {rss:6.0f} MiB (Python, numpy, scipy and pint included)")
    print("target: >= 1 M designs/s on one core; memory independent of the number of designs")

    if args.mixed:
        mreq = load_example_requirements("mr_requirements")
        t, feasible, _ = sweep(mreq, args.mixed, args.chunk)
        print(
            f"mixed mode      : {args.mixed / t / 1e3:6.1f} k designs/s   ({len(mreq.points)} design points, "
            f"{feasible:,} of {args.mixed:,} feasible; a root per element and point, compiled)"
        )


if __name__ == "__main__":
    np.seterr(all="ignore")
    main()
