"""``erdesign characterize RECORDS... [--json] [--out report.html]`` (docs/cli.md, docs/characterize.md): the
characterization-and-customization method of Vivas-López et al. (n.d.) on a damper's records.

The workflow is :func:`erdesign.characterization.method.characterize`; the page is
:mod:`erdesign.report.characterization`; this module parses options and prints.
"""

from __future__ import annotations

import click

from .main import NumberRange, cli, emit_json, WholeNumber, executor_options

__all__ = ["characterize"]

_EXAMPLES = """
\b
Examples:
  erdesign characterize e1.csv e2.csv e3.csv e4.csv e5.csv
  erdesign characterize e*.csv --json --jobs 2
  erdesign characterize e*.csv --out damper-characterization.html
  erdesign characterize e2.csv e3.csv e4.csv e5.csv --characterize-on e1.csv
"""


@cli.command(epilog=_EXAMPLES)
@click.argument("records", nargs=-1, required=True, metavar="RECORDS...")
@click.option(
    "--characterize-on",
    "characterize_on",
    multiple=True,
    metavar="RECORD.csv",
    help="Read the characteristics from this record (repeatable; the paper's E1) and only identify and "
    "cross-validate RECORDS (E2-E5); default: RECORDS.",
)
@click.option(
    "--threshold",
    default=0.001,
    show_default=True,
    type=NumberRange(min=0.0, max=1.0),
    help="Rise of the ESR (a fraction of the force variance) a characteristic must account for to be found.",
)
@click.option(
    "--starts",
    default=1,
    show_default=True,
    type=WholeNumber(min=1),
    help="Starts of each identification (more only run when the first is no better than a Bingham fit).",
)
@click.option(
    "--max-time",
    default=None,
    type=NumberRange(min=0.0, min_open=True),
    metavar="SECONDS",
    help="Time limit of each identification.",
)
@executor_options(default_jobs="1")
@click.option(
    "--out", default=None, metavar="REPORT.html", help="Write the diagrams, densities and tables as one HTML page."
)
@click.option("--force", "overwrite", is_flag=True, help="Let --out replace an existing file.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of a report.")
def characterize(
    records: tuple[str, ...],
    characterize_on: tuple[str, ...],
    threshold: float,
    starts: int,
    max_time: float | None,
    executor: dict,
    out: str | None,
    overwrite: bool,
    as_json: bool,
) -> None:
    """Find a damper's characteristics, build its customized model and cross-validate it (Vivas-López et al.)."""
    from .._util import check_output_path
    from ..characterization.method import characterize as run
    from ..data.measurement import read_measurement
    from ..executor import executor_scope

    if out is not None:
        out, _ = check_output_path(out, force=overwrite, formats={".html": "html"}, inputs=(*records, *characterize_on))
    recs = [read_measurement(r) for r in records]
    options = {"starts": starts, **({} if max_time is None else {"max_time": max_time})}
    with executor_scope(**executor) as runner:
        result = run(
            recs,
            characterize_on=[read_measurement(r) for r in characterize_on],
            threshold=threshold,
            executor=runner,
            identify_options=options,
        )
    if out is not None:
        from ..report.characterization import write_characterization

        write_characterization(result, out, overwrite=overwrite, option="--out")
    doc = result.to_dict()
    if as_json:
        emit_json({**doc, "out": None if out is None else str(out)})
        return
    click.echo(_text(doc) + (f"\n  report written to {out}" if out is not None else ""))


def _cell(x) -> str:
    """An ESR in a 12-wide column; a dash where the model diverged (null in the JSON)."""
    return f"{x:12.4f}" if x is not None else f"{'-':>12}"


def _text(doc: dict) -> str:
    """The readable report of the JSON document."""
    from ..report.characterization import esr_change_text as _less

    lines = [f"Characteristics of {', '.join(r['name'] for r in doc['characterized_on'])} (Vivas-López et al.):"]
    for c in doc["characteristics"]:
        lines.append(
            f"  [{'x' if c['found'] else ' '}] {c['title']} ({c['diagram']} -> {c['model_term']}): {c['evidence']}"
        )
    m = doc["model"]
    lines.append(
        f"Customized model: terms {', '.join(m['terms'])}; "
        f"{'asymmetric' if m['asymmetric'] else 'symmetric'} coefficients; manipulation V = u^"
        f"{m['control_exponent']:.3g}; {m['parameter_count']} parameters; identified on {m['identified_on']} (ESR {m['esr']:.4f})"
    )
    width = max(len(k) for k in m["parameters"])
    lines += [f"  {k:<{width}}  {v}" for k, v in m["parameters"].items()]
    cv = doc["cross_validation"]
    names = cv["records"]
    for key, title in (("customized", "customized model"), ("eyring_plastic", "Eyring-plastic model (eq 8)")):
        lines.append(f"Cross-validation, {title} (column: identified on; row: validated on; ESR):")
        w = max(len(n) for n in names + ["average"])
        lines.append("  " + " " * w + "".join(f"{n:>12}" for n in names))
        for n, row in zip(names, cv[key]["table"]):
            lines.append(f"  {n:<{w}}" + "".join(_cell(x) for x in row))
        lines.append(f"  {'average':<{w}}" + "".join(_cell(x) for x in cv[key]["average"]))
    c = doc["comparison"]
    ident, cvc = c["identification"], c["cross_validation"]
    lines.append(
        f"Identification ESR (Table 6): customized {', '.join(_cell(x).strip() for x in ident['customized'])}; "
        f"Eyring-plastic {', '.join(_cell(x).strip() for x in ident['eyring_plastic'])} "
        f"({_less(ident['esr_reduction'])} on average)"
    )
    lines.append(
        f"Cross-validation mean ESR: customized {cvc['customized_mean_esr']:.4f}, Eyring-plastic "
        f"{cvc['eyring_plastic_mean_esr']:.4f} ({_less(cvc['esr_reduction'])}); the customized "
        f"model is {'better' if c['customized_better'] else 'not better'}"
    )
    return "\n".join(lines)
