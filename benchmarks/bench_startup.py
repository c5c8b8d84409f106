"""Start-up cost of the command line (not a timed test): run `python benchmarks/bench_startup.py`.

CPU time (user + system, of the child process) of

* `python -c "import numpy"` - the yardstick;
* `python -m erdesign --help` and `python -m erdesign size <makris example> --velocity 0.0254 --json` (the
  checkout's code, run as the console script runs it);
* `python -c "import erdesign"` - the package's own import, which every command pays (lazy: PEP 562);
* `python -m erdesign identify --help` - one command's help, which imports that command's module only.

Issue 12 asked for `erdesign --help` < 3 x and `erdesign size` < 6 x the yardstick, issue 26 for `erdesign size`
<= 3 x (pint imported without dask and scipy, its registry built from a cache: erdesign/_pint.py).  Each figure is
the median of five runs after one warm-up run, as a user's second command runs: bytecode written and read
(``PYTHONDONTWRITEBYTECODE`` is dropped for the children: an installed package has its bytecode compiled) and the
unit cache in place.
"""

import os
import resource
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "erdesign" / "examples" / "makris.toml"


ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def cpu_seconds(argv, repeat=5):
    subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False, cwd=ROOT, env=ENV)
    times = []
    for _ in range(repeat):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False, cwd=ROOT, env=ENV)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        times.append((after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime))
    return statistics.median(times)


def main():
    py = sys.executable
    exe = [py, "-m", "erdesign"]  # this checkout's code (the console script may point at another install)
    base = cpu_seconds([py, "-c", "import numpy"])
    rows = [
        ("python -m erdesign --help", exe + ["--help"], 3.0),
        (
            "python -m erdesign size (makris example)",
            exe + ["size", str(EXAMPLE), "--velocity", "0.0254", "--json"],
            3.0,
        ),
        ("python -m erdesign size makris (by name)", exe + ["size", "makris", "--velocity", "0.0254 m/s"], 3.0),
        ("python -c 'import erdesign'", [py, "-c", "import erdesign"], None),
        ("python -m erdesign identify --help", exe + ["identify", "--help"], None),
    ]
    print(f"yardstick python -c 'import numpy': {base:.3f} s CPU")
    for label, argv, target in rows:
        t = cpu_seconds(argv)
        goal = f"   (target <= {target:g} x: {'met' if t / base <= target else 'NOT met'})" if target else ""
        print(f"  {label:<42} {t:6.3f} s CPU   {t / base:5.1f} x{goal}")


if __name__ == "__main__":
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    main()
