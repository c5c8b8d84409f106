"""The result of a fit (:class:`FitResult`) and its one report and one JSON object: fit statistics, values with
standard errors, initial values, bounds reached, parameters the data do not identify, correlations above
:data:`~erdesign.identification.engine.CORRELATION_THRESHOLD`, warnings."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from ..data.measurement import Measurement
from ..data.metrics import esr
from ..models.base import Model
from .engine import CORRELATION_THRESHOLD, at_bound
from .engine import strong_correlations as _pairs

__all__ = ["FitResult", "fit_report", "fit_statistics", "parameter_table", "result_json", "strong_correlations"]


@dataclass
class FitResult:
    """Outcome of :func:`fit`: parameter values (SI), uncertainties and figures of merit."""

    model: Model
    values: dict[str, float]
    """All parameter values, fixed ones included, SI."""
    free: tuple[str, ...]
    stderr: dict[str, float]
    """Standard error of each free parameter (NaN where not identifiable), SI."""
    correlation: np.ndarray
    """Correlation matrix of the free parameters, in the order of :attr:`free`."""
    force: np.ndarray
    """Model force on the fitted record, [N]."""
    residual: np.ndarray
    """Measured minus model force, [N]."""
    esr: float
    rss: float
    n: int
    aic: float
    bic: float
    success: bool
    message: str
    record_name: str = ""
    initial: dict = field(default_factory=dict)
    """Start values of the parameters (the report's "init"), SI."""
    not_identifiable: list = field(default_factory=list)
    """Free parameters the data do not determine (held at their start values when that fits as well)."""
    warnings: list = field(default_factory=list)
    """Notes on the fit, one line each (time budget, poor fit, clipped samples ...)."""
    baseline_esr: float | None = None
    """ESR of the reference Bingham fit on the same samples (identification)."""
    poor_fit: bool = False
    """No better than the reference fit, or most parameters at a bound: not a success."""
    starts_tried: int = 0
    simulations: int | None = None
    """Simulations of the best start."""
    nfev: int | None = None
    seconds: float = 0.0
    projected: list = field(default_factory=list)
    """Parameters solved by variable projection (entering the force linearly)."""
    clipped_samples: int = 0
    excluded_samples: int | list = 0
    """Samples left out of the fit (clipped force): a count, or one per record of a joint fit."""
    decimate: int = 1
    mask: np.ndarray | None = field(default=None, repr=False)
    """The samples fitted (None: all)."""
    findings: list = field(default_factory=list)
    """Data findings of the records (calibration)."""
    records: list = field(default_factory=list)
    """ESR on each record (calibration and joint fits of several records): dicts ``name``, ``samples``, ``esr``."""
    search: np.ndarray | None = field(default=None, repr=False)
    """The optimum in the search space (:class:`~erdesign.identification.engine.Transform`)."""
    jacobian: np.ndarray | None = field(default=None, repr=False)
    """Jacobian of the fitted residual with respect to :attr:`search` at the optimum."""
    out_of_time: bool = False
    """The time budget stopped the fit (the values are the best found so far)."""

    @property
    def k(self) -> int:
        """Number of free parameters."""
        return len(self.free)

    def parameters_with_units(self, digits: int = 4) -> dict[str, str]:
        """``name -> "value unit"`` strings of all parameters (the ``parameters`` of the CLI's JSON)."""
        return {name: self.model.parameter(name).format(v, digits) for name, v in self.values.items()}

    def predict(self, record: Measurement) -> np.ndarray:
        """Force [N] of the fitted model on another record."""
        return self.model.simulate(record, self.values)

    def validate(self, record: Measurement) -> float:
        """ESR of the fitted model on a held-out record (cross-validation in the style of Vivas-López et al., Table 4)."""
        return esr(record.require_force(), self.predict(record))

    def report(self, validation: Sequence[tuple[str, dict]] = ()) -> str:
        """The fit report (lmfit's content): statistics, values +- standard error (and %), initial values, bounds
        reached, parameters not identifiable, strong correlations, validation scores, warnings."""
        return fit_report(self, validation)

    def to_dict(
        self,
        model_name: str | None = None,
        control_reference: str | None = None,
        validation: Sequence[tuple[str, dict]] = (),
    ) -> dict:
        """The JSON object of ``erdesign identify --json`` (:func:`result_json`)."""
        return result_json(self, model_name or self.model.name, control_reference, validation)


def parameter_table(result: FitResult) -> dict[str, dict]:
    """Per parameter: SI value, unit, standard error (None where not available), initial value and status
    ("free", "fixed", "not identifiable", "at lower bound", "at upper bound")."""
    model = result.model
    initial = result.initial
    unident = set(result.not_identifiable)
    out = {}
    for name in model.parameter_names:
        v = float(result.values[name])
        se = result.stderr.get(name)
        if name in unident:
            status = "not identifiable"
        elif name not in result.free:
            status = "fixed"
        else:
            bound = at_bound(model.parameter(name), v, se)
            status = f"at {bound} bound" if bound else "free"
        out[name] = {
            "value": v,
            "unit": model.parameter(name).unit,
            "stderr": None if se is None or not math.isfinite(se) or status.startswith("at ") else float(se),
            "initial": None if name not in initial else float(initial[name]),
            "status": status,
        }
    return out


def strong_correlations(result: FitResult, threshold: float = CORRELATION_THRESHOLD) -> list[tuple[str, str, float]]:
    """Pairs of free parameters whose correlation exceeds ``threshold`` in magnitude, strongest first."""
    return _pairs(result.free, result.correlation, threshold)


def fit_statistics(result: FitResult) -> dict:
    """ESR, R^2, RMS residual, reduced chi-square (RSS / (n - k), N^2: no measurement error is known), AIC, BIC."""
    n, k = result.n, result.k
    return {
        "esr": result.esr,
        "r_squared": 1.0 - result.esr,
        "rms_residual_N": math.sqrt(result.rss / n),
        "reduced_chi_square_N2": result.rss / max(n - k, 1),
        "aic": result.aic,
        "bic": result.bic,
        "samples": n,
        "free_parameters": k,
    }


def fit_report(result: FitResult, validation: Sequence[tuple[str, dict]] = ()) -> str:
    """The identification report (the content of lmfit's): statistics, parameters with standard errors and
    initial values, parameters at a bound or not identifiable said so, strong correlations, warnings."""
    model = result.model
    st = fit_statistics(result)
    lines = [
        f"[[Fit]] {model.title or model.name} on {result.record_name or 'record'}",
        f"  samples {st['samples']}"
        + (f" ({result.excluded_samples} clipped left out)" if result.excluded_samples else "")
        + f", free parameters {st['free_parameters']}, simulations {'?' if result.simulations is None else result.simulations}, "
        f"{result.seconds:.1f} s" + ("" if result.success else f"  - {result.message}"),
        "[[Statistics]]",
        f"  ESR {st['esr']:.4g}   R^2 {st['r_squared']:.4g}   RMS residual {st['rms_residual_N']:.4g} N   "
        f"reduced chi-square {st['reduced_chi_square_N2']:.4g} N^2",
        f"  AIC {st['aic']:.1f}   BIC {st['bic']:.1f}"
        + (f"   (reference Bingham fit: ESR {result.baseline_esr:.4g})" if result.baseline_esr is not None else ""),
        "[[Parameters]]",
    ]
    table = parameter_table(result)
    width = max(len(n) for n in table)
    for name, row in table.items():
        p = model.parameter(name)
        text = p.format(row["value"])
        if row["status"] == "free" and row["stderr"] is not None:
            rel = abs(row["stderr"] / row["value"]) if row["value"] else math.inf
            text += f" +/- {p.format(row['stderr'], 2)}" + (f" ({100 * rel:.2g} %)" if math.isfinite(rel) else "")
        elif row["status"] == "not identifiable":
            text = (
                f"not identifiable from this record ({'fitted' if name in result.free else 'held at'} "
                f"{p.format(row['value'])})"
            )
        elif row["status"] == "fixed":
            text += " (fixed)"
        else:
            text += f" ({row['status']}: no standard error)" if row["status"].startswith("at ") else ""
        if row["initial"] is not None and row["status"] not in ("fixed", "not identifiable"):
            text += f"   init {p.format(row['initial'])}"
        lines.append(f"  {name:<{width}}  {text}")
    corr = strong_correlations(result)
    if corr:
        lines.append(
            f"[[Correlations]] (|r| > {CORRELATION_THRESHOLD:g}: these combinations, not the single values, are what the data fix)"
        )
        lines += [f"  {a}, {b}: {c:+.3f}" for a, b, c in corr]
    if validation:
        lines.append("[[Validation]] (the identified set on other records)")
        lines += [f"  {name}: ESR {m['esr']:.4g}, RMS residual {m['rms_residual_N']:.4g} N" for name, m in validation]
    warnings = list(result.warnings)
    if warnings:
        lines.append("[[Warnings]]")
        lines += [f"  {w}" for w in warnings]
    return "\n".join(lines)


def result_json(
    result: FitResult, model_name: str, control_reference: str | None, validation: Sequence[tuple[str, dict]] = ()
) -> dict:
    """The ``identify --json`` object: the contract's ``model``, ``esr``, ``parameters`` (strings) and, in SI,
    ``parameters_si`` (value, unit, stderr, initial, status), ``statistics``, ``correlations``,
    ``not_identifiable``, ``at_bounds``, ``warnings``, ``control_reference`` and ``validation``.  No NaN or inf."""

    def num(x):
        return None if x is None or not math.isfinite(x) else float(x)

    table = parameter_table(result)
    st = {k: (num(v) if isinstance(v, float) else v) for k, v in fit_statistics(result).items()}
    return {
        "model": model_name,
        "esr": num(result.esr),
        "parameters": result.parameters_with_units(),
        "parameters_si": table,
        "statistics": st,
        "control_reference": control_reference,
        "correlations": [{"a": a, "b": b, "r": c} for a, b, c in strong_correlations(result)],
        "not_identifiable": [n for n, r in table.items() if r["status"] == "not identifiable"],
        "at_bounds": [n for n, r in table.items() if r["status"].startswith("at ")],
        "success": bool(result.success),
        "poor_fit": bool(result.poor_fit),
        "message": result.message,
        "simulations": result.simulations,
        "seconds": num(result.seconds),
        "clipped_samples": result.clipped_samples,
        "excluded_samples": result.excluded_samples,
        "warnings": list(result.warnings),
        "validation": [
            {"record": name, **{k: num(v) if isinstance(v, float) else v for k, v in m.items()}}
            for name, m in validation
        ],
    }
