"""Run a fixed set of fits through every fitting entry point and write their ESRs and parameter values to JSON.

Used to check that a refactor of the fitting engine changes no fit: run before and after, then compare::

    PYTHONPATH=. python benchmarks/compare_fits.py fits_before.json
    PYTHONPATH=. python benchmarks/compare_fits.py fits_after.json --compare fits_before.json

Covers :func:`erdesign.identification.fit.fit`, :func:`~erdesign.identification.identify.identify` (projected and
plain, with a fixed parameter, on a record with a control), :func:`~erdesign.identification.identify.identify_joint`,
:func:`~erdesign.identification.identify.cross_validation` and :func:`erdesign.diagnosis.calibration.calibrate`, on
the inputs of tests/test_fit.py, tests/test_identify.py and tests/test_identify_projection.py.  About a minute.
"""

from __future__ import annotations

import argparse
import json
import sys
import time

import numpy as np


def _bingham_record(amplitude=0.01, f_hz=1.0, current=None, noise_n=5.0, seed=0, n=401):
    from erdesign.data.measurement import Measurement
    from erdesign.models.registry import get_model

    true = {"c0": 3000.0, "f_c": 150.0, "f0": 5.0, "f_c_u": 600.0, "c0_u": 4000.0}
    t = np.linspace(0.0, 1.0 / f_hz, n)
    x = amplitude * np.sin(2 * np.pi * f_hz * t)
    kw = {} if current is None else {"control": current, "control_kind": "current"}
    rec = Measurement.from_arrays(t, x, **kw, name=f"{amplitude * 1e3:g} mm {f_hz:g} Hz {current} A")
    clean = get_model("bingham").simulate(
        rec, true if current is not None else {k: true[k] for k in ("c0", "f_c", "f0")}
    )
    return rec.with_force(clean + noise_n * np.random.default_rng(seed).standard_normal(n))


def _spencer_record(n=2001):
    from erdesign.data.measurement import Measurement
    from erdesign.models.registry import get_model

    t = np.linspace(0.0, 2.0, n)
    x = 0.01 * np.sin(2 * np.pi * t) + 0.004 * np.sin(2 * np.pi * 2.7 * t)
    u = 1.0 + 0.5 * np.sin(2 * np.pi * 0.6 * t)
    rec = Measurement.from_arrays(t, x, control=u, control_kind="voltage", name="Spencer 1997 synthetic")
    F = get_model("bouc_wen_modified").simulate(rec, {"c0b": 2000.0, "alpha_b": 5e4, "k1": 300.0, "x0": 0.01})
    return rec.with_force(F + 5.0 * np.random.default_rng(1).standard_normal(n))


def _entry(result):
    values = getattr(result, "values", {})
    e = (
        [r["esr"] for r in result.records]
        if getattr(result, "records", None) and hasattr(result, "names")
        else result.esr
    )
    return {
        "esr": [float(x) for x in e] if isinstance(e, (list, tuple)) else float(e),
        "values": {k: float(v) for k, v in values.items()},
        "success": bool(getattr(result, "success", True)),
    }


def cases():
    """name -> zero-argument callable returning an entry dict."""
    from erdesign import load_example
    from erdesign.diagnosis.calibration import calibrate
    from erdesign.identification.fit import fit
    from erdesign.identification.identify import (
        cross_validation,
        identify,
        identify_joint,
    )
    from erdesign.models.registry import get_model
    from erdesign.simulation.rig import run_rig, sine

    out = {}
    rec_u = _bingham_record(current=0.5)
    rec0 = _bingham_record()
    out["fit bingham"] = lambda: _entry(fit(get_model("bingham"), rec0))
    out["fit bingham starts=3"] = lambda: _entry(fit(get_model("bingham"), rec0, starts=3))
    out["fit bingham fixed f0"] = lambda: _entry(fit(get_model("bingham"), rec0, fixed={"f0": 0.0}))
    out["identify bingham 0.5 A"] = lambda: _entry(identify(get_model("bingham"), rec_u, starts=1))
    out["identify bingham plain"] = lambda: _entry(identify(get_model("bingham"), rec_u, starts=1, projection=False))
    spencer = _spencer_record()
    for name in ("kwok_tanh", "dahl", "bouc_wen_normalized"):
        out[f"identify {name} spencer"] = lambda name=name: _entry(identify(get_model(name), spencer, starts=1))
        out[f"identify {name} spencer plain"] = lambda name=name: _entry(
            identify(get_model(name), spencer, starts=1, projection=False)
        )
    out["identify bouc_wen_modified spencer max_nfev=20"] = lambda: _entry(
        identify(get_model("bouc_wen_modified"), spencer, starts=1, max_nfev=20)
    )
    recs = [_bingham_record(current=i, seed=k) for k, i in enumerate((0.0, 0.5, 1.0))]
    out["identify_joint bingham"] = lambda: _entry(identify_joint(get_model("bingham"), recs))
    out["identify_joint kwok_tanh"] = lambda: _entry(identify_joint(get_model("kwok_tanh"), recs, max_nfev=60))
    cv_recs = [_bingham_record(amplitude=a, seed=k) for k, a in enumerate((0.005, 0.01, 0.02))]

    def cv():
        table = cross_validation(lambda: get_model("bingham"), cv_recs, starts=1).table
        return {"esr": [float(x) for x in table.ravel()], "values": {}, "success": True}

    out["cross_validation bingham"] = cv
    damper = load_example("makris")
    rig = run_rig(damper, sine(0.005, 2.0, 3e6, cycles=2, rate=200), seed=1).record
    out["calibrate makris"] = lambda: _entry(calibrate(damper, rig))
    rig0 = run_rig(damper, sine(0.005, 2.0, 0.0, cycles=2, rate=200), seed=2).record
    out["calibrate makris two fields seal_friction"] = lambda: _entry(calibrate(damper, [rig0, rig], ["seal_friction"]))
    return out


def quiroz_cases():
    from erdesign.data.quiroz import quiroz_folder, read_quiroz_sinusoid
    from erdesign.identification.identify import identify
    from erdesign.models.registry import get_model

    folder = quiroz_folder()
    if folder is None:
        return {}
    out = {}
    for test, current in [(t, c) for t in ("5mm3Hz", "10mm1Hz") for c in (0.0, 0.25, 0.5, 1.0)]:
        rec = read_quiroz_sinusoid(folder, test, current)
        out[f"identify bouc_wen_modified quiroz {test} {current} A"] = lambda rec=rec: _entry(
            identify(get_model("bouc_wen_modified"), rec, starts=1, max_time=60)
        )
    return out


def compare(after: dict, before: dict) -> tuple[float, float]:
    """Print each fit's ESR before -> after and its largest relative changes; return the largest relative change
    of an ESR and of a parameter value (relative to the larger magnitude of the two, so that a parameter leaving 0
    counts as 1, not as infinity)."""
    worst_esr = worst_value = 0.0
    for name, b in before.items():
        a = after.get(name)
        if a is None:
            print(f"{name}: missing after")
            continue
        be, ae = np.atleast_1d(b["esr"]), np.atleast_1d(a["esr"])
        d_esr = max((abs(x - y) / max(abs(x), abs(y), 1e-300) for x, y in zip(ae, be)), default=0.0)
        d_val = max(
            (
                abs(a["values"][k] - v) / max(abs(v), abs(a["values"][k]), 1e-300)
                for k, v in b["values"].items()
                if k in a["values"] and a["values"][k] != v
            ),
            default=0.0,
        )
        worst_esr, worst_value = max(worst_esr, d_esr), max(worst_value, d_val)
        print(
            f"{name:<52} ESR {np.round(be, 5).tolist()} -> {np.round(ae, 5).tolist()}  "
            f"largest rel change: ESR {d_esr:.2e}, values {d_val:.2e}"
        )
    return worst_esr, worst_value


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("output")
    ap.add_argument("--compare", help="a JSON written before, to compare with")
    ap.add_argument("--quiroz", action="store_true", help="also the single-record fits of Quiroz's records")
    ap.add_argument("--only", help="run only the cases whose name contains this text")
    args = ap.parse_args(argv)
    todo = cases()
    if args.quiroz:
        todo.update(quiroz_cases())
    results = {}
    for name, run in todo.items():
        if args.only and args.only not in name:
            continue
        t = time.perf_counter()
        results[name] = run()
        results[name]["seconds"] = time.perf_counter() - t
        print(
            f"{name:<52} ESR {np.round(np.atleast_1d(results[name]['esr']), 5).tolist()}  "
            f"{results[name]['seconds']:.1f} s",
            flush=True,
        )
    with open(args.output, "w") as f:
        json.dump(results, f, indent=1)
    if args.compare:
        with open(args.compare) as f:
            before = json.load(f)
        d_esr, d_val = compare(results, before)
        print(f"largest relative change: ESR {d_esr:.3g}, parameter values {d_val:.3g}")


if __name__ == "__main__":
    sys.exit(main())
