"""Compare and diagnose page: a measurement against the physics damper of the design, the missing effect, the refit.

The record comes from an upload (:func:`erdesign.data.measurement.read_measurement`) or the built-in examples; the
diagnosis is :func:`erdesign.diagnosis.diagnose.diagnose` (calibration, residual analysis in words, ranking of the
effects, and a verdict: a missing effect, nothing missing - the residual is at the noise floor -, or unexplained);
"add effect and refit" diagnoses again with the effect accepted, and the error history shows the ESR after each step.
"""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import streamlit as st

from erdesign.app import figures, state
from erdesign.data.measurement import check_record
from erdesign.diagnosis.diagnose import fitted_model
from erdesign.effects import EFFECTS
from erdesign.errors import ErdesignError
from erdesign.formatting import esr_shown
from erdesign.report import plots
from erdesign.report.builder import ErrorHistoryStep
from erdesign.report.export import csv_text, rows_csv
from erdesign.report.fit import EXPORT_UNITS, correlation_rows, parameter_rows, parameters_csv, statistics_rows
from erdesign.report.formatting import pick_unit, show
from erdesign.units import Q_

__all__ = ["render", "history_steps", "judged_samples"]

_BUILT_IN, _UPLOAD = "built-in example (hidden effect)", "upload a measurement CSV"


def _record_source() -> tuple[bytes, str, bool] | None:
    """Draw the source inputs; return (CSV bytes, name, built in) or None."""
    source = state.widget(
        st.radio, "measurement", "cmp.source", _BUILT_IN, options=[_BUILT_IN, _UPLOAD], horizontal=True
    )
    if source == _BUILT_IN:
        name = state.widget(
            st.selectbox,
            "example",
            "cmp.example",
            state.example_records()[0],
            options=state.example_records(),
            help="Measured on the virtual rig (erdesign.simulation.rig) with effects the quasi-steady "
            "model leaves out; the diagnosis has to find them.",
        )
        return state.example_record_bytes(name), name, True
    upload = st.file_uploader(
        "measurement CSV",
        type=["csv", "txt"],
        key="cmp.upload",
        help="Columns with units in brackets: time [s], displacement [mm], force [N], "
        "optionally field [kV/mm] (docs/cli.md).",
    )
    if upload is None:
        st.info("Upload a CSV file with a header such as `time [s],displacement [mm],force [N],field [kV/mm]`.")
        return None
    return upload.getvalue(), upload.name, False


def history_steps(diagnoses) -> list[ErrorHistoryStep]:
    """The error history: the calibrated baseline, then one step per accepted effect, with the ESR after it.

    ``diagnoses`` are the diagnoses with 0, 1, 2 ... accepted effects (each adds one to the previous).
    """
    steps = []
    for i, d in enumerate(diagnoses):
        steps.append(ErrorHistoryStep(i, "baseline" if i == 0 else d.effects[-1], float(d.baseline_esr)))
    return steps


def _report_details(diagnosis) -> str:
    """What the report adds to the comparison (verdict, its reason, noise floor, the calibration's fit report), as
    JSON text (hashable, for the cached report); numbers formatted in the unit system by :mod:`erdesign.report.fit`."""
    result = diagnosis.baseline
    return json.dumps(
        {
            "verdict": diagnosis.verdict,
            "reason": _sentence(diagnosis.reason),
            "noise_floor_esr": float(diagnosis.noise_floor_esr),
            "parameters": parameter_rows(result),
            "statistics": statistics_rows(result),
            "correlations": correlation_rows(result),
        }
    )


def judged_samples(diagnosis) -> int:
    """Number of samples a diagnosis judged its ESRs, RMS and verdict on (its ``judged_share`` of those analysed)."""
    return round(diagnosis.judged_share * diagnosis.samples[1])


def _parameters_table(result) -> list[dict]:
    """The fit report of the calibration as a table (:func:`erdesign.report.fit.parameter_rows`)."""
    return parameter_rows(result)


def _fitted(candidate) -> str:
    """The effect parameters a candidate fitted, each ``name = value ± error (share)`` in the unit system (the
    values and errors of its fit, formatted by :mod:`erdesign.report.fit`)."""
    result = candidate.result
    model = fitted_model(result)  # fitted on part of the record: the model for the whole record
    rows = {r["parameter"]: r for r in parameter_rows(dataclasses.replace(result, model=model))}
    parts = []
    for name in candidate.parameters():
        r = rows[name]
        error = r["± 1σ"] + (f" ({r['±']})" if r["±"] else "")
        parts.append(f"{name} = {r['value']} {error if error.startswith('±') else '(' + error + ')'}")
    return "; ".join(parts)


def _ranking_table(diagnosis) -> list[dict]:
    """One row per candidate; a candidate that could not be evaluated says "not evaluated" and why."""
    rows = []
    for i, c in enumerate(diagnosis.ranking, 1):
        row = {"rank": i, "effect": c.effect, "significant": "yes" if c.significant else "no"}
        if not c.evaluated:
            row.update(
                {
                    "ESR after adding": "not evaluated",
                    "explains": "",
                    "ΔBIC": "",
                    "gain": "",
                    "fitted": "",
                    "against the prior": "",
                    "note": c.reason or c.note,
                }
            )
            rows.append(row)
            continue
        notes = [c.note] if c.note else []
        if c.implausible:  # the diagnosis marks a fitted size it does not believe: shown as such
            notes.insert(0, "implausible: " + "; ".join(c.implausible))
        if c.at_bounds:
            notes.append("at bounds: " + "; ".join(c.at_bounds))
        row.update(
            {
                "ESR after adding": f"{c.esr:.4g}",
                # a negative share is a refit that ended a hair worse than the baseline: nothing explained
                "explains": f"{100 * max(c.explained, 0.0):.0f} % of the excess",
                "ΔBIC": f"{c.delta_bic:+.1f}" if math.isfinite(c.delta_bic) else "",
                "gain": f"{100 * c.gain:.1f} %",
                "fitted": _fitted(c),
                "against the prior": c.plausibility,
                "note": "; ".join(notes),
            }
        )
        rows.append(row)
    return rows


def _effect_title(option: str) -> str:
    """An effect to add (or two joined by " + ") with its title."""
    return " + ".join(f"{e}: {EFFECTS[e].title}" for e in option.split(" + "))


def _add_effect(chosen: str | None = None) -> None:
    """Callback of the refit buttons: accept ``chosen`` (or the effect of the selectbox; both of a pair)."""
    chosen = chosen or st.session_state.get("cmp.add")
    work = st.session_state.setdefault(state.DIAGNOSIS, {"effects": []})
    for effect in chosen.split(" + ") if chosen else []:
        if effect not in work["effects"]:
            work["effects"] = [*work["effects"], effect]


def _reset(source_key: str) -> dict:
    work = st.session_state.get(state.DIAGNOSIS)
    if work is None or work.get("source") != source_key:
        work = {"source": source_key, "effects": [], "run": False}
        st.session_state[state.DIAGNOSIS] = work
    return work


def render() -> None:
    """Draw the Compare and diagnose page."""
    st.title("Compare and diagnose")
    source = _record_source()
    if source is None:
        return
    data, name, built_in = source
    spec = state.current_design()["spec"]
    example = state.example_damper_for(data) if built_in else None
    if example is not None and state.example_spec(example).get("name") != spec.get("name"):
        spec = state.example_spec(example)
        st.caption(
            f"This example was measured on the damper of examples/{example}.toml: it is compared with that "
            "damper, not with the design of the Size page."
        )
    text = state.spec_text(spec)
    damper = state.damper_or_error(text)
    if damper is None:
        return
    st.caption(
        f"Model: the physics damper of {damper.name or 'the design'}, calibrated to the record "
        "(viscosity and yield-stress factors) plus the effects accepted below."
    )
    try:
        record = state.read_record(data, name)
    except ErdesignError as exc:
        st.error(f"Cannot read the measurement: {state.clean_message(str(exc))}")
        return
    try:  # what looks wrong in the record and against the damper (a unit mistake): said before any fit
        doubts = check_record(record, damper, warn=False)
    except ErdesignError as exc:
        st.error(f"Cannot use the measurement: {state.clean_message(str(exc))}")
        return
    for doubt in doubts:
        st.warning(f"Check the record: {doubt}", icon="⚠️")
    control = record.control_kind or "no control column (zero field)"
    st.caption(f"{name}: {len(record)} samples over {record.duration:.3g} s; {control}.")
    work = _reset(f"{name}:{hash(data)}:{text}")
    if not work["run"]:
        if st.button("Diagnose", type="primary", key="cmp.run"):
            work["run"] = True
        else:
            st.info("Press **Diagnose** to calibrate the model to the record and rank the missing effects.")
            return
    effects = tuple(work["effects"])
    diagnoses = []
    try:
        with st.status(
            "Diagnosing: calibrating the baseline and refitting with each effect ...", expanded=False
        ) as status:
            for k in range(len(effects) + 1):
                status.update(label=f"Diagnosing with {', '.join(effects[:k]) or 'the baseline'} ...")
                diagnoses.append(state.run_diagnosis(text, data, name, effects[:k]))
            status.update(label="Diagnosis done", state="complete")
    except ErdesignError as exc:
        st.error(f"The diagnosis failed: {state.clean_message(str(exc))}")
        return
    diagnosis, record, model_force = diagnoses[-1]
    _show(diagnosis, record, model_force, [d[0] for d in diagnoses], name)


def _show(diagnosis, record, model_force, chain, name) -> None:
    F = record.force
    steps = history_steps(chain)
    judged = judged_samples(diagnosis)
    rms = Q_(float(diagnosis.analysis.rms), "N")
    # the report states the diagnosis' own numbers (ESR, RMS on the judged samples): one number for one thing
    st.session_state["report.comparison"] = (
        name,
        float(diagnosis.baseline_esr),
        judged,
        float(rms.magnitude),
        record.displacement,
        record.velocity,
        F,
        model_force,
        _report_details(diagnosis),
    )
    st.session_state["report.history"] = tuple((s.step, s.effect, s.esr) for s in steps)
    model = "baseline" + "".join(f" + {e}" for e in diagnosis.effects)
    st.markdown(f"**Model:** {model}")
    c = st.columns(3)
    # ESRs to the 3 figures of the verdict's text, so that the metric and the sentence read the same number
    c[0].metric(
        "ESR of the calibrated model",
        esr_shown(diagnosis.baseline_esr).text,
        delta=None if len(steps) < 2 else f"{steps[-1].esr - steps[-2].esr:.3g}",
        delta_color="inverse",
        help="Error-to-signal ratio (Vivas-López et al., eq 7): residual variance over force variance, on "
        "the judged samples.",
    )
    c[1].metric(
        "noise floor ESR",
        esr_shown(diagnosis.noise_floor_esr).text,
        help="The ESR that the load cell's noise alone would leave on the same samples: one figure per "
        f"record, the same at every step (found by: {diagnosis.noise_floor_method or 'estimate'}; "
        "docs/diagnosis.md).",
    )
    c[2].metric(
        "RMS residual",
        show(rms, pick_unit(rms, "force"), name="RMS residual").text,
        help="Root mean square of measured minus model force on the judged samples (the report's RMS force error).",
    )
    st.caption(
        f"All three on the {judged} judged samples of {diagnosis.samples[1]} analysed "
        f"({100 * diagnosis.judged_share:.0f} %: where the sign of the velocity is known and no data finding "
        "excludes them); the verdict below compares the same ESR with the same floor."
    )
    left, right = st.columns([3, 2], gap="large")
    with left:
        for finding in diagnosis.findings:
            st.info(
                f"Data finding ({finding.kind}): {finding.message}" + (f" ({finding.where})" if finding.where else "")
            )
        _verdict(diagnosis)
        for warning in diagnosis.warnings:
            st.warning(f"Check: {warning}")
    with right:  # the error history stays in view while effects are added
        st.plotly_chart(
            plots.error_history_figure(steps, noise_floor=float(diagnosis.noise_floor_esr)),
            key="cmp.fig.history",
            config=state.chart_config("cmp.fig.history"),
        )

    tabs = st.tabs(["overlay", "residual", "missing effects", "parameters", "downloads"])
    with tabs[0]:
        st.plotly_chart(
            plots.measured_loops_figure(record.displacement, record.velocity, F, model_force),
            key="cmp.fig.loops",
            config=state.chart_config("cmp.fig.loops"),
        )
        st.plotly_chart(
            figures.time_figure(record.time, model_force, label="model", measured=F),
            key="cmp.fig.time",
            config=state.chart_config("cmp.fig.time"),
        )
    with tabs[1]:
        st.plotly_chart(
            figures.residual_figure(record.time, record.velocity, F - model_force),
            key="cmp.fig.res",
            config=state.chart_config("cmp.fig.res"),
        )
        st.markdown("**Where the model fails** (share of samples, RMS there over overall RMS):")
        st.dataframe(
            [
                {"region": k, "share of samples %": round(100 * a, 1), "RMS ratio": round(b, 2)}
                for k, (a, b) in diagnosis.analysis.regions.items()
            ],
            hide_index=True,
        )
    ranking = _ranking_table(diagnosis)
    with tabs[2]:
        st.markdown("**What the residual looks like:**")
        for finding in diagnosis.analysis.findings or ["no pattern stands out of the noise"]:
            st.markdown(f"- {finding}")
        st.markdown("**Ranked candidate effects** (best first; each added to the model and refitted):")
        st.table(ranking)
        for e, why in diagnosis.not_judged.items():
            st.caption(f"not judged: {e}: {why}")
        # a candidate that could not be evaluated cannot be added; a pair is added as both its effects
        options = [c.effect for c in diagnosis.ranking if c.evaluated]
        if options:
            named = " + ".join(diagnosis.pair) if diagnosis.pair else diagnosis.missing_effect
            default = named if named in options else options[0]
            if st.session_state.get("cmp.add") not in options:
                st.session_state["cmp.add"] = default
            cols = st.columns([2, 1])
            cols[0].selectbox("effect to add", options, key="cmp.add", format_func=_effect_title)
            cols[1].button("Add effect and refit", on_click=_add_effect, key="cmp.refit")
    parameters = _parameters_table(diagnosis.baseline)
    with tabs[3]:
        st.markdown(
            f"**Calibrated parameters** of {model}: value, standard error (1 σ) and its share of the value, "
            "start value, bounds and status (free, fixed, at a bound, not identifiable):"
        )
        st.dataframe(parameters, hide_index=True, key="cmp.parameters")
        left, right = st.columns(2)
        left.markdown("**Statistics** of the calibration (on the samples fitted)")
        left.table(statistics_rows(diagnosis.baseline))
        right.markdown("**Strong correlations** (these combinations, not the single values, are what the data fix)")
        correlations = correlation_rows(diagnosis.baseline)
        if correlations:
            right.table(correlations)
        else:
            right.caption("none: every pair of free parameters is correlated less strongly than the threshold")
        with st.expander("fit report (as `erdesign fit` prints it)"):
            st.code(diagnosis.baseline.report(), language=None)
    with tabs[4]:
        _downloads(name, record, model_force, ranking, parameters, steps, diagnosis)


def _downloads(name, record, model_force, ranking, parameters, steps, diagnosis) -> None:
    """CSV files of the comparison: time histories and residual, ranking, fitted parameters, error history."""
    stem = state.file_stem(Path(name).stem)
    F = record.force
    columns = [
        ("time", "s", record.time),
        ("displacement", "m", record.displacement),
        ("velocity", "m/s", record.velocity),
        ("force", "N", F),
        ("model force", "N", model_force),
        ("residual", "N", F - model_force),
    ]
    model = "baseline" + "".join(f" + {e}" for e in diagnosis.effects)
    histories = csv_text(
        columns,
        comment=f"{name}: measured force, force of the calibrated model ({model}) and "
        f"residual (measured minus model); numbers in {EXPORT_UNITS} units",
    )
    st.markdown("Each file is CSV with units in the header; the time histories read back as a measurement.")
    cols = st.columns(4)
    cols[0].download_button(
        "Time histories and residual",
        histories,
        file_name=f"{stem}-model.csv",
        mime="text/csv",
        key="cmp.dl.history",
        icon=":material/download:",
    )
    cols[1].download_button(
        "Ranking of the effects",
        rows_csv(
            _ranking_numbers(diagnosis),
            comment=f"diagnosis of {name} ({model})\nnumbers in {EXPORT_UNITS} units; "
            "each fitted parameter a column NAME [unit], its standard error NAME "
            "stderr [unit]",
        ),
        file_name=f"{stem}-ranking.csv",
        mime="text/csv",
        key="cmp.dl.ranking",
        icon=":material/download:",
    )
    cols[2].download_button(
        "Fitted parameters",
        parameters_csv(diagnosis.baseline, comment=f"calibrated {model} on {name}"),
        file_name=f"{stem}-parameters.csv",
        mime="text/csv",
        key="cmp.dl.parameters",
        icon=":material/download:",
    )
    cols[3].download_button(
        "Error history",
        rows_csv(
            [{"step": s.step, "effect added": s.effect, "ESR [1]": f"{s.esr:.6g}"} for s in steps]
            + [{"step": "", "effect added": "noise floor", "ESR [1]": f"{diagnosis.noise_floor_esr:.6g}"}]
        ),
        file_name=f"{stem}-error-history.csv",
        mime="text/csv",
        key="cmp.dl.steps",
        icon=":material/download:",
    )


def _ranking_numbers(diagnosis) -> list[dict]:
    """The ranking as numbers in SI (the CSV download): ESR, ΔBIC, gain and share explained, and each fitted effect
    parameter with its standard error in a column ``NAME [unit]`` (empty where a candidate has no such parameter)."""

    def number(x) -> str:
        return "" if x is None or not math.isfinite(x) else f"{x:.6g}"

    rows, names = [], {}
    for c in diagnosis.ranking:
        fitted = {}
        if c.evaluated:
            model = fitted_model(c.result)
            for n in c.parameters():
                unit = model.parameter(n).unit or "1"
                names[n] = unit
                fitted[f"{n} [{unit}]"] = number(c.result.values[n])
                fitted[f"{n} stderr [{unit}]"] = number(c.result.stderr.get(n))
        rows.append(
            {
                "rank": len(rows) + 1,
                "effect": " + ".join(c.effects),
                "significant": int(c.significant),
                "ESR after adding [1]": number(c.esr),
                "delta BIC [1]": number(c.delta_bic),
                "gain [%]": number(100 * c.gain) if c.evaluated else "",
                "explains [%]": number(100 * c.explained) if c.evaluated else "",
                **fitted,
                "implausible": "; ".join(c.implausible),
                "note": c.reason or c.note,
            }
        )
    columns = ["rank", "effect", "significant", "ESR after adding [1]", "delta BIC [1]", "gain [%]", "explains [%]"]
    columns += [f"{n} {part}[{u}]" for n, u in names.items() for part in ("", "stderr ")]
    columns += ["implausible", "note"]
    return [{k: r.get(k, "") for k in columns} for r in rows]


def _verdict(diagnosis) -> None:
    """The verdict of the diagnosis, prominently, with its reason (docs/cli.md) and, for a
    missing effect, the button that adds it and refits."""
    if diagnosis.verdict == "missing_effect":
        if diagnosis.pair:
            what = " ".join(f"{e} ({EFFECTS[e].title}): {EFFECTS[e].mechanism}" for e in diagnosis.pair)
            head = f"**Missing effect: {' + '.join(diagnosis.pair)}** (two effects, fitted jointly). {what}"
            named = " + ".join(diagnosis.pair)
        else:
            effect = EFFECTS[diagnosis.missing_effect]
            head = f"**Missing effect: {diagnosis.missing_effect}** ({effect.title}). {effect.mechanism}"
            named = diagnosis.missing_effect
        with st.container(border=True):
            st.success(f"{head}\n\n{_sentence(diagnosis.reason)}")
            st.button(
                f"Add {named} and refit",
                on_click=_add_effect,
                args=(named,),
                key="cmp.add_named",
                type="primary",
                icon=":material/add:",
            )
    elif diagnosis.verdict == "unexplained":
        st.warning(f"**Unexplained:** {_sentence(diagnosis.reason)}")
    else:
        st.info(f"**Nothing missing: the residual is at the noise floor.** {_sentence(diagnosis.reason)}")


def _sentence(text: str) -> str:
    """``text`` with a capital first letter and a full stop."""
    text = text.strip()
    if not text:
        return ""
    return text[0].upper() + text[1:] + ("" if text.endswith(".") else ".")


if __name__ == "__main__":
    render()
