"""Session state and cached calls into the library, shared by the pages of the app.

The current design lives in ``st.session_state`` as a *damper spec*: the content of a damper file as plain data
(``{"name": ..., "geometry": {...}, "fluid": {...}}``, values as strings with units), exactly what
:func:`erdesign.damper.files.damper_from_dict` reads.  The pages pass it to the cached functions below as its JSON
text (:func:`spec_text`), so that ``st.cache_data`` hashes plain data and never a library object.

Widgets keep their values across page switches through :func:`widget` (Streamlit forgets the state of a widget
that a run does not draw; the value is kept under a second key and put back when the page is drawn again).

Every cached function returns plain data or library records that pickle (``st.cache_data`` stores a copy).
"""

from __future__ import annotations

import dataclasses
import json
import re
import tempfile
import warnings
from importlib import resources
from pathlib import Path
from typing import Any, Callable

import numpy as np
import streamlit as st

from .. import materials
from ..damper import Damper
from ..damper.files import damper_from_dict, example_names, read_toml
from ..data.measurement import Measurement, read_measurement
from ..errors import ErdesignError, one_line
from ..units import Q_, to_si

__all__ = [
    "DEFAULT_EXAMPLE",
    "SPEC",
    "DESIGN",
    "DIAGNOSIS",
    "BASELINE",
    "UNITS",
    "IMAGE_FORMAT",
    "chart_config",
    "image_format",
    "report_images",
    "widget",
    "forget",
    "example_spec",
    "current_spec",
    "set_spec",
    "default_design",
    "current_design",
    "set_design",
    "design_text",
    "design_report",
    "unit_system",
    "pinned_baseline",
    "report_inputs",
    "clean_message",
    "file_stem",
    "spec_text",
    "build_damper",
    "damper_or_error",
    "caught",
    "force_velocity_curves",
    "geometry_sweep",
    "GEOMETRY_SWEEPS",
    "read_record",
    "example_records",
    "example_record_bytes",
    "example_damper_for",
    "RIG_EXAMPLES",
    "simulate",
    "run_diagnosis",
    "render_report",
    "report_pages",
    "clear_caches",
    "material_names",
    "set_widget",
    "widget_value",
]

#: The damper the app opens on.
DEFAULT_EXAMPLE = "makris"
#: Session-state key of the current damper spec (plain data).
SPEC = "spec"
#: Session-state key of the design: the spec, the design point and the curves' settings, as typed
#: (``{"spec": ..., "velocity": "25 mm/s", "field": "3 kV/mm", "v_top": "50 mm/s", "levels": 4}``).  The Size page
#: writes it when its inputs are valid; the report, Simulate and Compare pages read it.
DESIGN = "design"
#: Session-state key of the diagnosis work (record, accepted effects, error history).
DIAGNOSIS = "diagnosis"
#: Session-state key of the design pinned as the baseline of the comparison on the Size page.
BASELINE = "baseline"
#: Widget key of the unit system of displayed numbers (sidebar).
UNITS = "app.units"
#: Widget key of the format the figures' camera button saves (sidebar): ``png`` or ``svg``.
IMAGE_FORMAT = "app.image_format"
_KEEP = "_keep."


# ------------------------------------------------------------------------------------------------ widgets
def widget(factory: Callable[..., Any], label: str, key: str, default: Any, **kwargs: Any) -> Any:
    """Draw ``factory(label, key=key, **kwargs)`` (``st.text_input``, ``st.selectbox`` ...) with a value that
    survives page switches; ``default`` is its first value."""
    if key not in st.session_state:
        st.session_state[key] = st.session_state.get(_KEEP + key, default)
    value = factory(label, key=key, **kwargs)
    st.session_state[_KEEP + key] = value
    return value


def set_widget(key: str, value: Any) -> None:
    """Give a widget drawn by :func:`widget` a new value (from a callback, or before the widget is drawn)."""
    st.session_state[key] = value
    st.session_state[_KEEP + key] = value


def widget_value(key: str, default: Any = None) -> Any:
    """The value of a widget drawn by :func:`widget`, also while its page is not drawn."""
    return st.session_state.get(key, st.session_state.get(_KEEP + key, default))


def forget(prefix: str) -> None:
    """Drop the kept values of every widget whose key starts with ``prefix`` (they return to their defaults)."""
    for key in [k for k in st.session_state if k.startswith(prefix) or k.startswith(_KEEP + prefix)]:
        del st.session_state[key]


# ------------------------------------------------------------------------------------------------ the design
def example_spec(name: str = DEFAULT_EXAMPLE) -> dict:
    """The damper spec of a shipped example damper file (``makris``, ...)."""
    if name not in example_names():
        raise ErdesignError(f"example: unknown example {name!r}; available: {', '.join(example_names())}")
    with resources.as_file(resources.files("erdesign.examples") / f"{name}.toml") as path:
        return read_toml(path)


def current_spec() -> dict:
    """The design the user is working on (the Makris damper until the Size page changes it)."""
    if SPEC not in st.session_state:
        st.session_state[SPEC] = example_spec(DEFAULT_EXAMPLE)
    return st.session_state[SPEC]


def set_spec(spec: dict) -> None:
    st.session_state[SPEC] = spec


def spec_text(spec: dict) -> str:
    """The spec as canonical JSON text: the hashable form the cached functions take."""
    return json.dumps(spec, sort_keys=True)


def _quantity_text(q) -> str:
    """``"25 mm/s"``: a quantity as an input shows it (and pint reads it back)."""
    return f"{q.magnitude:.4g} {q.units:~C}"


def file_stem(name: str, suffix: str = "") -> str:
    """A file name from a design name: ``file_stem("my damper / v2", "-report")`` -> ``"my-damper-v2-report"``.

    >>> file_stem("makris-1996", "-report"), file_stem("../../etc")
    ('makris-1996-report', 'etc')
    """
    stem = re.sub(r"[^A-Za-z0-9_-]+", "-", name).strip("-.") or "erdesign"
    return f"{stem}{suffix}"


def default_design(spec: dict) -> dict:
    """The design point a spec opens with: half the top velocity of its curves (module notes of
    :mod:`erdesign.report.builder`) at the fluid's reference field, as the user would type them."""
    from ..report.builder import default_velocity_max
    from ..report.formatting import pick_unit

    damper = caught(lambda: damper_from_dict(spec, source="design"))[0]
    v_top = default_velocity_max(damper)
    unit = pick_unit(Q_(v_top, "m/s"), "velocity")
    fluid = damper.fluid
    return {
        "spec": spec,
        "velocity": _quantity_text(Q_(v_top / 2, "m/s").to(unit)),
        "field": _quantity_text(Q_(fluid.reference_field, fluid.control_unit).to(fluid.field_unit)),
        "v_top": _quantity_text(Q_(v_top, "m/s").to(unit)),
        "levels": 4,
    }


def current_design() -> dict:
    """The design every page works on (:data:`DESIGN`): the last valid one the Size page saw."""
    if DESIGN not in st.session_state:
        st.session_state[DESIGN] = default_design(current_spec())
    return st.session_state[DESIGN]


def set_design(design: dict) -> None:
    st.session_state[DESIGN] = design
    st.session_state[SPEC] = design["spec"]


def design_text(design: dict) -> str:
    """The design as canonical JSON text (hashable, for the cached functions)."""
    return json.dumps(design, sort_keys=True)


def chart_config(key: str) -> dict:
    """The plotly config of the chart ``key`` (``"size.fig.force"``): its camera button saves
    ``<design>-<figure>.png`` (or ``.svg``, as chosen in the sidebar) - the browser draws the image."""
    from ..report.plots import export_config

    name = current_design()["spec"].get("name") or "design"
    return export_config(file_stem(f"{name}-{key.rsplit('.', 1)[-1]}"), image_format())


def pinned_baseline(design: dict) -> dict | None:
    """The design pinned as the baseline on the Size page (:data:`BASELINE`), or None when none is pinned or it
    is the design itself."""
    base = st.session_state.get(BASELINE)
    return None if base is None or design_text(base) == design_text(design) else base


def unit_system() -> str:
    """The unit system chosen in the sidebar (``SI`` until changed)."""
    return st.session_state.get(UNITS) or st.session_state.get(_KEEP + UNITS) or "SI"


def report_inputs(design: dict, control_unit: str) -> dict:
    """The keyword arguments of :func:`erdesign.report.build_report` for a design: the curves from 0 to the top
    velocity at ``levels`` controls from 0 to the design control, the design point as typed."""
    E = abs(float(to_si(design["field"], control_unit, "design field")))
    levels = int(design.get("levels", 4))
    fields = [Q_(float(x), control_unit) for x in np.linspace(0.0, E, levels)[1:]] if E else []
    return {
        "velocity_range": (Q_(0.0, "m/s"), design["v_top"]),
        "fields": fields or None,
        "design_velocity": design["velocity"],
        "design_field": design["field"],
        "origin": "as typed in the app",
    }


@st.cache_data(show_spinner=False, max_entries=32)
def design_report(
    text: str,
    system: str,
    comparison: tuple | None = None,
    history: tuple[tuple[int, str, float], ...] = (),
    baseline: str | None = None,
):
    """:func:`erdesign.report.build_report` of a design (:func:`design_text`) in the unit system ``system``.

    The Size page shows its design point, checks and curves; the Report page renders it: one computation, so the
    numbers on screen and in the download are the same.  ``comparison`` is ``(label, esr, samples, rms, x, v,
    F_measured, F_model, details)``: the diagnosis' ESR and RMS residual [N] on the samples it judged (their number),
    SI arrays as tuples for the loops, and JSON text of the verdict, its reason, the noise floor and the
    calibration's fit report (``erdesign.app.compare``); or None.  ``baseline`` is the pinned baseline design
    (:data:`BASELINE`, as :func:`design_text`): the report then compares the design with it.

    Raises :class:`~erdesign.errors.ErdesignError` for an invalid design.
    """
    from ..report import build_report
    from ..report.builder import ErrorHistoryStep, MeasurementComparison
    from ..report.formatting import use_unit_system

    design = json.loads(text)
    damper, _ = build_damper(spec_text(design["spec"]))
    base = design_report(baseline, system) if baseline is not None else None
    comp = None
    if comparison is not None:
        label, esr_value, samples, rms, x, v, Fm, Fmod, details = comparison
        Fm, Fmod = np.asarray(Fm), np.asarray(Fmod)
        extra = json.loads(details) if details else {}
        comp = MeasurementComparison(
            label=label,
            esr=esr_value,
            samples=samples,
            rms_error=Q_(rms, "N"),
            verdict=extra.get("verdict", ""),
            reason=extra.get("reason", ""),
            noise_floor_esr=extra.get("noise_floor_esr"),
            parameters=tuple(extra.get("parameters", ())),
            statistics=tuple(extra.get("statistics", ())),
            correlations=tuple(extra.get("correlations", ())),
            peak_force_measured=Q_(float(np.max(np.abs(Fm))), "N"),
            peak_force_model=Q_(float(np.max(np.abs(Fmod))), "N"),
            displacement=np.asarray(x),
            velocity=np.asarray(v),
            force_measured=Fm,
            force_model=Fmod,
        )
    with use_unit_system(system):
        return caught(
            lambda: build_report(
                design["spec"],
                **report_inputs(design, damper.fluid.control_unit),
                comparison=comp,
                history=[ErrorHistoryStep(*h) for h in history] or None,
                baseline=base,
            )
        )[0]


_PATH = re.compile(r"(?:[A-Za-z]:)?(?:[\\/][^\\/\s:'\"]+)+[\\/]([^\\/\s:'\"]+)")


def clean_message(text: str) -> str:
    """An error message for the page: one line, server paths cut to the file name.

    >>> clean_message("/tmp/tmpab12/upload.csv: line 2, column 'force': not a number")
    "upload.csv: line 2, column 'force': not a number"
    """
    return _PATH.sub(lambda m: m.group(1), one_line(text))


def caught(call: Callable[[], Any]) -> tuple[Any, list[str]]:
    """``call()`` and the messages of the warnings it issued (validity warnings are shown in the page)."""
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        value = call()
    messages = []
    for w in seen:
        text = " ".join(str(w.message).split())
        if text not in messages:
            messages.append(text)
    return value, messages


def build_damper(text: str) -> tuple[Damper, list[str]]:
    """The :class:`~erdesign.damper.Damper` of a spec (JSON text) and the validity warnings building it gave.

    Raises :class:`~erdesign.errors.ErdesignError` (naming the key) for an invalid spec.
    """
    return caught(lambda: damper_from_dict(json.loads(text), source="design"))


def damper_or_error(text: str) -> Damper | None:
    """The damper of a spec for a page to use, or None after showing in the page why the design is not valid."""
    try:
        return build_damper(text)[0]
    except ErdesignError as exc:
        st.error(f"The design of the Size page is not valid: {clean_message(str(exc))}")
        return None


def material_names() -> list[str]:
    return materials.names()


# ------------------------------------------------------------------------------------------------ sizing
@st.cache_data(show_spinner=False, max_entries=64)
def force_velocity_curves(text: str, v_max: float, fields: tuple[float, ...], points: int = 81):
    """:func:`erdesign.damper.curves.force_velocity_curves` of the spec from 0 to ``v_max`` [m/s] at ``fields``
    (SI)."""
    from ..damper import curves

    damper, _ = build_damper(text)
    return caught(
        lambda: curves.force_velocity_curves(damper, np.linspace(0.0, v_max, points), np.asarray(fields, dtype=float))
    )[0]


#: Geometry values the sweep explorer varies: key -> label.
GEOMETRY_SWEEPS = {"gap": "gap h", "duct_length": "duct length L", "piston_diameter": "piston diameter Dp"}


@st.cache_data(show_spinner=False, max_entries=64)
def geometry_sweep(text: str, parameter: str, values: tuple[float, ...], velocity: float, field: float) -> dict:
    """Design figures of the spec with one geometry value (``GEOMETRY_SWEEPS``) replaced by each of ``values`` [m].

    Returns SI arrays: ``value``, ``force``, ``zero_field_force``, ``dynamic_range``, ``reynolds``, ``gap_ratio``
    (NaN where the geometry is not buildable) and ``invalid`` (the first reason a value was rejected, or "").
    Each point is :meth:`erdesign.damper.Damper.state` of the damper with that geometry.
    """
    if parameter not in GEOMETRY_SWEEPS:
        raise ErdesignError(f"sweep: unknown parameter {parameter!r}; choose one of {', '.join(GEOMETRY_SWEEPS)}")
    damper, _ = build_damper(text)
    g = damper.geometry
    n = len(values)
    out = {k: np.full(n, np.nan) for k in ("force", "zero_field_force", "dynamic_range", "reynolds", "gap_ratio")}
    invalid = ""
    for i, value in enumerate(values):
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # the thin-gap warning: the sweep shows h/d instead
                geometry = g.with_(**{parameter: float(value)})  # a mixed gap's mean diameter follows
                d = dataclasses.replace(damper, geometry=geometry)
                s, s0 = d.state(velocity, field), d.state(velocity, 0.0)
        except ErdesignError as exc:
            invalid = invalid or f"{Q_(value, 'm').to('mm').magnitude:.4g} mm: {exc}"
            continue
        out["force"][i], out["zero_field_force"][i] = s.force, s0.force
        out["dynamic_range"][i] = s.force / s0.force if s0.force != 0 else np.nan
        out["reynolds"][i], out["gap_ratio"][i] = s.reynolds, geometry.gap_ratio
    out["value"] = np.asarray(values, dtype=float)
    out["invalid"] = invalid
    return out


# ------------------------------------------------------------------------------------------------ records
@st.cache_data(show_spinner=False, max_entries=32)
def read_record(data: bytes, name: str, require_force: bool = True) -> Measurement:
    """A measurement CSV given as bytes (an upload), read by :func:`erdesign.data.measurement.read_measurement`.

    ``require_force=False`` accepts a displacement-only record (Simulate's uploaded displacement).

    Raises :class:`~erdesign.data.measurement.MeasurementError` whose message starts with ``name``.
    """
    from ..data.measurement import MeasurementError

    with tempfile.TemporaryDirectory() as folder:
        base = Path(name).name or "upload.csv"
        if len(base.encode()) > 200:  # a file system takes 255 bytes a name: "File name too long" was an internal error
            suffix = Path(base).suffix if len(Path(base).suffix) <= 10 else ""
            base = base.encode()[:150].decode("utf-8", "ignore") + "..." + suffix
        path = Path(folder) / base
        path.write_bytes(data)
        try:
            record = read_measurement(path, require_force=require_force)
        except MeasurementError as exc:  # the message names the temporary file: show the upload's name
            raise MeasurementError(clean_message(str(exc).replace(str(path), path.name))) from None
    return record


#: Built-in records made on the virtual rig (:mod:`erdesign.simulation.rig`) with the Makris damper, offered while the
#: package ships no example measurements: name -> (hidden effects, true fluid over nominal).  Sine sweeps at two
#: amplitudes, frequencies and fields, 2 % force noise.
RIG_EXAMPLES = {
    "rig: makris, hidden effect A": ({"seal_friction": {"friction_force": 400.0}}, 1.2),
    "rig: makris, hidden effect B": ({"gas_spring": {"gas_preload": 300.0, "gas_stiffness": 3e4}}, 0.9),
}


def example_records() -> list[str]:
    """Names of the built-in example measurements: the CSV files of ``erdesign/examples/measurements`` or, while
    there are none, the virtual-rig records of :data:`RIG_EXAMPLES`."""
    try:
        folder = resources.files("erdesign.examples") / "measurements"
        files = sorted(p.name for p in folder.iterdir() if p.name.endswith(".csv"))
    except (FileNotFoundError, NotADirectoryError):
        files = []
    return files or list(RIG_EXAMPLES)


def example_damper_for(data: bytes) -> str | None:
    """The shipped example damper a built-in record was measured on, or None.

    The rigs write ``# virtual rig: <damper name>; ...`` (:mod:`erdesign.simulation.rig`) or ``# truth rig: <damper
    name> (<configuration>); ...`` (:mod:`erdesign.simulation.truthrig`) as the first line of their records; the name is
    matched against the ``name`` of the example damper files.
    """
    first = data[:400].decode("utf-8", "replace").splitlines()[0] if data else ""
    prefix = next((p for p in ("# virtual rig:", "# truth rig:") if first.startswith(p)), None)
    if prefix is None:
        return None
    damper_name = first[len(prefix) :].split(";")[0].strip()
    if damper_name.endswith(")") and " (" in damper_name:  # the truth rig adds the configuration
        damper_name = damper_name[: damper_name.rindex(" (")]
    for example in example_names():
        if example_spec(example).get("name") == damper_name:
            return example
    return None


@st.cache_data(show_spinner=False, max_entries=8)
def example_record_bytes(name: str) -> bytes:
    """The CSV text of a built-in example measurement (:func:`example_records`)."""
    if name not in RIG_EXAMPLES:
        return (resources.files("erdesign.examples") / "measurements" / name).read_bytes()
    from ..damper.files import load_example
    from ..data.measurement import write_measurement
    from ..simulation.rig import run_rig, stepped_sine

    hidden, viscosity_factor = RIG_EXAMPLES[name]
    motion = stepped_sine([0.005, 0.01], [2.0, 1.0], [3e6, 1.5e6], cycles=2, rate=500)
    rig = run_rig(
        load_example("makris"),
        motion,
        hidden=hidden,
        viscosity_factor=viscosity_factor,
        force_noise=0.02,
        seed=2,
        name=name.replace(" ", "_"),
    )
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "rig.csv"
        write_measurement(
            path,
            rig.record,
            units={"displacement": "mm", "field": "kV/mm"},
            comment="virtual rig (erdesign.simulation.rig); the hidden effect is for the diagnosis to find",
        )
        return path.read_bytes()


# ------------------------------------------------------------------------------------------------ simulate
@st.cache_data(show_spinner=False, max_entries=32)
def simulate(
    text: str,
    model_name: str,
    effects: tuple[str, ...],
    values: tuple[tuple[str, float], ...],
    excitation: tuple[tuple[str, Any], ...],
    upload: bytes | None = None,
    upload_name: str = "",
) -> dict:
    """Force of a model (``physics`` with ``effects``, or a registry model) for an excitation.

    ``excitation`` is plain data: ``kind`` (``sine``, ``sweep``, ``earthquake``, ``programme`` or ``upload``) and its numbers
    (SI), handed to :mod:`erdesign.simulation.rig` (``upload``: the displacement of a measurement CSV).  Returns SI
    arrays ``time``, ``displacement``, ``velocity``, ``control``, ``force``, the measured force of an upload (or None),
    the parameter values used, and the description of the motion.
    """
    from ..models.registry import get_model
    from ..simulation import rig

    damper, _ = build_damper(text)
    ex = dict(excitation)
    kind = ex.pop("kind")
    measured = None
    if kind == "upload":
        record = read_record(upload, upload_name, require_force=False)
        if record.control_kind is None:
            record = dataclasses.replace(
                record, control=np.full(len(record), float(ex["field"])), control_kind=damper.fluid.control
            )
        measured = record.force
        description = f"displacement of {upload_name} ({len(record)} samples)"
    else:
        if kind in ("sine", "sweep"):  # the description prints the control in the fluid's unit (3 kV/mm)
            ex["control_unit"] = damper.fluid.field_unit
        from ..simulation.programmes import programme

        motion = {
            "sine": rig.sine,
            "sweep": rig.stepped_sine,
            "earthquake": rig.earthquake_motion,
            "programme": programme,
        }[kind](**ex)
        record = motion.record(damper.fluid.control, kind)
        description = motion.description
    damper.fluid.check_plausible_field(record.control, "field")  # a unit mistake is an error, not a result
    if model_name == "physics":
        model = get_model("physics", damper=damper, effects=effects)
    else:
        model = get_model(model_name)
        model.control_reference = damper.fluid.reference_field  # u = 1 at the fluid's reference control
    used = model.check_values(dict(values))
    force = model.simulate(record, used)
    return {
        "time": record.time,
        "displacement": record.displacement,
        "velocity": record.velocity,
        "control": record.control,
        "force": force,
        "measured": measured,
        "values": used,
        "units": {p.name: p.unit for p in model.parameters},
        "description": description,
        "title": model.title or model.name,
    }


# ------------------------------------------------------------------------------------------------ diagnosis
@st.cache_data(show_spinner=False, max_entries=16)
def run_diagnosis(text: str, data: bytes, name: str, effects: tuple[str, ...]):
    """:func:`erdesign.diagnosis.diagnose.diagnose` of the record (CSV bytes) against the spec's damper with
    ``effects``.

    Returns the :class:`~erdesign.diagnosis.diagnose.Diagnosis`, the record and the calibrated model's force on the
    whole record, [N].
    """
    from ..diagnosis.diagnose import diagnose

    damper, _ = build_damper(text)
    record = read_record(data, name)
    diagnosis = caught(lambda: diagnose(damper, record, effects))[0]
    fitted = diagnosis.baseline
    # the diagnosis may fit on part of the record (a mask wrapper with ``inner``): the force on the whole record
    model = getattr(fitted.model, "inner", fitted.model)
    return diagnosis, record, model.simulate(record, fitted.values)


# ------------------------------------------------------------------------------------------------ report
@st.cache_data(show_spinner=False, max_entries=8)
def render_report(
    text: str,
    system: str,
    comparison: tuple | None,
    history: tuple[tuple[int, str, float], ...],
    fmt: str,
    baseline: str | None = None,
    image_format: str = "png",
) -> str:
    """The report of a design (:func:`design_report`) as HTML (figures saved by their camera button as
    ``image_format``) or Markdown text."""
    from ..report import render_html, render_markdown

    report = design_report(text, system, comparison, history, baseline)
    return render_html(report, image_format) if fmt == "html" else render_markdown(report)


def image_format() -> str:
    """The format the figures' camera button saves (sidebar: ``png`` until changed)."""
    return st.session_state.get(IMAGE_FORMAT) or st.session_state.get(_KEEP + IMAGE_FORMAT) or "png"


@st.cache_data(show_spinner=False, max_entries=4)
def report_images(
    text: str,
    system: str,
    comparison: tuple | None,
    history: tuple[tuple[int, str, float], ...],
    baseline: str | None,
    image_format: str,
) -> bytes:
    """The report's figures as static images in one ZIP archive (:func:`erdesign.report.export.figure_images`:
    kaleido and a Chrome or Chromium already on the machine).

    Raises :class:`~erdesign.errors.ErdesignError` saying what to install when they are missing.
    """
    from ..report.export import figure_images, images_zip

    report = design_report(text, system, comparison, history, baseline)
    stem = file_stem(json.loads(text)["spec"].get("name") or "design")
    return images_zip({f"{stem}-{k}": v for k, v in figure_images(report.figures, image_format).items()})


@st.cache_data(show_spinner=False, max_entries=4)
def report_pages(
    text: str,
    system: str,
    comparison: tuple | None,
    history: tuple[tuple[int, str, float], ...],
    baseline: str | None,
    image_format: str,
) -> bytes:
    """The report's figures as interactive HTML pages in one ZIP archive (:func:`erdesign.report.export.figure_pages`):
    the fallback of :func:`report_images` that needs no extra install."""
    from ..report.export import figure_pages, images_zip

    report = design_report(text, system, comparison, history, baseline)
    stem = file_stem(json.loads(text)["spec"].get("name") or "design")
    pages = figure_pages(report.figures, image_format)
    return images_zip({(k if k.endswith(".js") else f"{stem}-{k}"): v for k, v in pages.items()})


def clear_caches() -> None:
    """Empty every cache of the app (tests call it between tests)."""
    for fn in (
        force_velocity_curves,
        geometry_sweep,
        read_record,
        example_record_bytes,
        simulate,
        run_diagnosis,
        design_report,
        render_report,
        report_images,
        report_pages,
    ):
        fn.clear()
