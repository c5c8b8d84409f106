"""A fit as an engineer reads it, for the app and the report alike: the fitted values with their uncertainties,
statistics and correlations of a :class:`~erdesign.identification.result.FitResult` as shown text.

The numbers come from the fit's own tables (:func:`~erdesign.identification.result.parameter_table`,
:func:`~erdesign.identification.result.fit_statistics`, :func:`~erdesign.identification.result.strong_correlations`,
the content of :meth:`FitResult.report`); this module only formats them, each value to
:data:`~erdesign.formatting.SIGNIFICANT_DIGITS` significant figures in the unit the unit system gives its kind, so
that a value reads "120.3 kN·s/m", never "120300000 N*s/m" or "1.282e-16 g":

* a value beyond the largest (or below the smallest) unit of its kind is written in powers of ten (``1.203e+05
  MN·s/m``), a value within a millionth of zero at a bound as ``0``;
* a standard error larger than the value itself reads "larger than the value" and keeps its percentage;
* a parameter at a bound, fixed, or not identifiable says so instead of a standard error.

>>> from erdesign.parameters import Parameter
>>> p = Parameter("c", "N*s/m", 1e4, 0.0, 1e12)
>>> value_text(p, 1.203e11), value_text(p, 120345.6), value_text(Parameter("m", "kg", 1.0, 0.0, 10.0), 1.282e-19)
('1.203e+05 MN·s/m', '120.3 kN·s/m', '0 kg')
"""

from __future__ import annotations

import math
from typing import Any

from ..formatting import SIGNIFICANT_DIGITS, round_significant, show_in_system

__all__ = [
    "value_text",
    "error_text",
    "parameter_rows",
    "statistics_rows",
    "correlation_rows",
    "parameters_csv",
    "EXPORT_UNITS",
]

#: The unit system of every CSV file erdesign writes for a user (numbers in the cells, units in the headers).
EXPORT_UNITS = "SI"

#: Below this share of the parameter's scale (its default, else 1) a fitted value is shown as zero.
_ZERO = 1e-9


def _compact(shown) -> str:
    """``shown.text`` with a number outside 0.001 to 9999 in powers of ten (the unit is the largest of its kind)."""
    try:
        x = float(shown.number)
    except ValueError:
        return shown.text
    if x == 0 or 1e-3 <= abs(x) < 1e4:
        return shown.text
    number = f"{x:.{SIGNIFICANT_DIGITS - 1}e}"
    return f"{number} {shown.unit}".strip()


def value_text(parameter, value: float, *, like: Any = None, digits: int = SIGNIFICANT_DIGITS) -> str:
    """A fitted value of ``parameter`` (:class:`~erdesign.parameters.Parameter`, SI ``value``) as shown text."""
    if not math.isfinite(value):
        return "undefined"
    scale = abs(parameter.default) or 1.0
    if value != 0 and abs(value) < _ZERO * scale:
        value = 0.0
    return _compact(
        show_in_system(
            parameter.quantity(value),
            name=parameter.name,
            digits=digits,
            like=None if like is None else parameter.quantity(like),
        )
    )


def error_text(parameter, value: float, stderr: float | None, status: str) -> tuple[str, str]:
    """The standard error of a fitted value and its share of the value, ``("± 0.012 kN", "3.1 %")``; the status
    instead where there is none ("fixed", "at lower bound", "not identifiable")."""
    if status != "free" or stderr is None or not math.isfinite(stderr):
        return (status if status != "free" else "not identifiable"), ""
    relative = abs(stderr / value) if value else math.inf
    share = f"{100 * relative:.2g} %" if math.isfinite(relative) else ""
    if relative > 1:
        return "larger than the value", share
    return "± " + value_text(parameter, stderr, like=value, digits=2), share


def parameter_rows(result) -> list[dict]:
    """One row per parameter of a fit: ``parameter``, ``value``, ``± 1σ``, ``±``, ``initial``, ``bounds``,
    ``status``, ``description``."""
    from ..identification.result import parameter_table

    model = result.model
    rows = []
    for name, row in parameter_table(result).items():
        p = model.parameter(name)
        error, share = error_text(p, row["value"], row["stderr"], row["status"])
        lo = value_text(p, p.lower) if math.isfinite(p.lower) else "-∞"
        hi = value_text(p, p.upper) if math.isfinite(p.upper) else "∞"
        rows.append(
            {
                "parameter": name,
                "value": value_text(p, row["value"]),
                "± 1σ": error,
                "±": share,
                "initial": "" if row["initial"] is None else value_text(p, row["initial"]),
                "bounds": f"{lo} to {hi}",
                "status": row["status"],
                "description": p.description,
            }
        )
    return rows


def statistics_rows(result) -> list[dict]:
    """The fit's statistics (ESR, R², RMS residual, AIC, BIC, samples, free parameters) as ``quantity``/``value``."""
    from ..identification.result import fit_statistics
    from ..units import Q_

    s = fit_statistics(result)
    return [
        {"quantity": "ESR (Vivas-López et al., eq 7)", "value": round_significant(s["esr"], 3)},
        {"quantity": "R²", "value": round_significant(s["r_squared"])},
        {"quantity": "RMS residual", "value": show_in_system(Q_(s["rms_residual_N"], "N"), name="RMS").text},
        {"quantity": "AIC", "value": f"{s['aic']:.1f}"},
        {"quantity": "BIC", "value": f"{s['bic']:.1f}"},
        {"quantity": "samples fitted", "value": f"{s['samples']}"},
        {"quantity": "free parameters", "value": f"{s['free_parameters']}"},
    ]


def correlation_rows(result) -> list[dict]:
    """The strongly correlated pairs of free parameters (|r| above the report's threshold), strongest first."""
    from ..identification.result import strong_correlations

    return [{"parameters": f"{a}, {b}", "correlation": f"{r:+.3f}"} for a, b, r in strong_correlations(result)]


def parameters_csv(result, *, comment: str = "") -> str:
    """The fit's parameters as CSV in SI: one column per parameter headed ``name [unit]`` (``[1]`` for a factor),
    rows ``value``, ``stderr``, ``initial``, ``lower bound``, ``upper bound`` (empty where there is none); the
    status of each parameter in a comment line (tests/test_report_fit.py reads one back).
    """
    import csv
    import io

    from ..identification.result import parameter_table

    table = parameter_table(result)
    model = result.model
    names = list(table)
    out = io.StringIO()
    status = ", ".join(f"{n} {table[n]['status']}" for n in names)
    for line in [*comment.splitlines(), f"numbers in {EXPORT_UNITS} units; status: {status}"]:
        out.write(f"# {line}\n")
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(["quantity", *(f"{n} [{table[n]['unit'] or '1'}]" for n in names)])

    def cell(x) -> str:
        return "" if x is None or not math.isfinite(x) else f"{x:.10g}"

    for label, get in (
        ("value", lambda n: table[n]["value"]),
        ("stderr", lambda n: table[n]["stderr"]),
        ("initial", lambda n: table[n]["initial"]),
        ("lower bound", lambda n: model.parameter(n).lower),
        ("upper bound", lambda n: model.parameter(n).upper),
    ):
        writer.writerow([label, *(cell(get(n)) for n in names)])
    return out.getvalue()
