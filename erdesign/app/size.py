"""Size page: geometry and fluid with units -> the design point, its validity and the trade-offs.

Inputs are values with units as text (``"0.8 mm"``, ``"2.15 in"``), read by pint through the library; the fluid may
come from the materials database, any value of it overridden.  Outputs come from :meth:`erdesign.Damper.size`, the
force-velocity curves from :func:`erdesign.damper.curves.force_velocity_curves` drawn by :mod:`erdesign.report.plots`,
the sweep explorer (one geometry value varied) from :func:`erdesign.app.state.geometry_sweep`, the tolerance study
(quantiles and Sobol indices under tolerances) from :func:`erdesign.campaign.tolerance.tolerance_study`.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import numpy as np
import streamlit as st

from erdesign.app import figures, pinned, state
from erdesign.damper.files import damper_from_dict, example_names, parse_toml_bytes
from erdesign.errors import ErdesignError
from erdesign.limits import decode_text, nested_too_deeply
from erdesign.formatting import si_unit_text
from erdesign.materials import fluid_values
from erdesign.report import plots
from erdesign.report.export import csv_text, damper_toml
from erdesign.report.fit import EXPORT_UNITS
from erdesign.report.formatting import control_label, field_text, pick_unit, show
from erdesign.units import Q_, plain_number, to_si

__all__ = [
    "render",
    "FLUID_FIELDS",
    "GEOMETRY_FIELDS",
    "FILE_VALUES",
    "spec_from_widgets",
    "design_comment",
    "design_point_csv",
]

#: Material choice meaning "the values of the damper file".
FILE_VALUES = "(values of the damper file)"
UPLOADED = "(uploaded damper file)"
#: The example box's entry while the current design is none of the examples (opened on the Design page).
CURRENT = "(the current design)"
#: Entries of the example box that are not examples (choosing one loads nothing).
NOT_EXAMPLES = (UPLOADED, CURRENT)

GEOMETRY_FIELDS = {
    "duct_length": ("duct length L", "Length of each annular duct (mixed: of the piston head)."),
    "duct_mean_diameter": ("duct mean diameter d", "Mean diameter of the annular gap (valve only)."),
    "gap": ("gap h", "Radial gap of the annulus."),
    "piston_diameter": ("piston diameter Dp", "Diameter of the piston (head)."),
    "rod_diameter": ("rod diameter dr", "Diameter of the rod (both ends, or the one rod of a single-ended damper)."),
}
FLUID_FIELDS = {
    "viscosity": ("plastic viscosity η0", "At zero field."),
    "viscosity_at_reference_field": ("viscosity at the reference field", "Optional; empty: independent of the field."),
    "yield_stress": ("yield stress τy at the reference field", ""),
    "reference_field": ("reference field", "Electric (kV/mm), magnetic (kA/m, T) field, or coil current (A)."),
    "yield_exponent": ("field-law exponent n", "τy ∝ E^n (a plain number)."),
    "density": ("density ρ", ""),
    "shear_modulus": ("pre-yield shear modulus G", "Optional."),
    "seal_friction": ("seal friction Fs", "Coulomb friction of seals and bearings."),
}
_ERROR = "size.load_error"


def _text(value: Any) -> str:
    return "" if value is None else str(value)


#: The comment line of a damper file written by the app that carries the design point it was sized for.
_POINT_LINE = re.compile(
    r"^#\s*design point:\s*v\s*=\s*(?P<v>[^;]+);\s*E\s*=\s*(?P<E>[^;]+?)"
    r"(?:;\s*curves to\s*(?P<top>[^;]+?))?\s*$",
    re.MULTILINE,
)


def design_comment(design: dict) -> str:
    """The comment at the top of a damper file downloaded from the app: what it is and its design point.

    >>> print(design_comment({"spec": {"name": "d"}, "velocity": "25 mm/s", "field": "3 kV/mm", "v_top": "50 mm/s"}))
    damper file of the design d, written by the erdesign app; read it with `erdesign size` or the app's upload
    design point: v = 25 mm/s; E = 3 kV/mm; curves to 50 mm/s
    """
    return (
        f"damper file of the design {design['spec'].get('name') or 'design'}, written by the erdesign app; "
        "read it with `erdesign size` or the app's upload\n"
        f"design point: v = {design['velocity']}; E = {design['field']}; curves to {design['v_top']}"
    )


def _load(spec: dict, source: str, point: dict | None = None) -> None:
    """Put a damper spec (and a design point, else the default one) into the widgets (a callback: runs before
    the widgets are drawn)."""
    geo, fluid = spec.get("geometry", {}), dict(spec.get("fluid", {}))
    state.set_widget("size.configuration", geo.get("configuration", "valve"))
    for key in GEOMETRY_FIELDS:
        state.set_widget(f"size.geo.{key}", _text(geo.get(key)))
    state.set_widget("size.geo.ducts", int(geo.get("ducts", 1)))
    material = fluid.pop("material", None)
    st.session_state["size.file_fluid"] = fluid
    # a [coil] has no widgets of its own: it is kept as loaded and shown with the magnetic circuit; so are a
    # single-ended rod and its [accumulator] (docs/file_formats.md)
    st.session_state["size.coil"] = dict(spec["coil"]) if isinstance(spec.get("coil"), dict) else None
    st.session_state["size.kept"] = {
        "rod": {"rod": geo["rod"]} if "rod" in geo else {},
        "accumulator": dict(spec["accumulator"]) if isinstance(spec.get("accumulator"), dict) else None,
    }
    state.set_widget("size.name", str(spec.get("name") or Path(source).stem))
    state.set_widget("size.material", material or FILE_VALUES)
    base = fluid_values(material) if material else {}
    for key in FLUID_FIELDS:
        state.set_widget(f"size.fluid.{key}", _text(fluid.get(key, base.get(key))))
    design = {**state.default_design(spec), **(point or {})}
    for key in ("velocity", "field", "v_top", "levels"):
        state.set_widget(f"size.{key}", design[key])
    state.forget("size.sweep.")


def _example_of(spec: dict) -> str:
    """The example whose damper file ``spec`` is, else :data:`CURRENT` (a design opened on the Design page)."""
    return next((name for name in example_names() if state.example_spec(name) == spec), CURRENT)


def _on_example() -> None:
    name = st.session_state["size.example"]
    st.session_state.pop(_ERROR, None)
    if name not in NOT_EXAMPLES:
        _load(state.example_spec(name), f"examples/{name}.toml")


def _on_upload() -> None:
    upload = st.session_state.get("size.upload")
    st.session_state.pop(_ERROR, None)
    if upload is None:
        return
    name = Path(upload.name).name
    try:
        data = parse_toml_bytes(upload.getvalue(), name)  # the one TOML reader: limits, encodings, line ends
        text = decode_text(upload.getvalue(), name, "a damper file (TOML)")
        damper_from_dict(data, source=name)  # check before taking it
    except RecursionError:
        st.session_state[_ERROR] = nested_too_deeply(name)
        return
    except ErdesignError as exc:
        st.session_state[_ERROR] = state.clean_message(str(exc))
        return
    except Exception as exc:  # noqa: BLE001 - an upload must never crash the page (issue 15)
        st.session_state[_ERROR] = f"{name}: cannot be read as a damper file ({type(exc).__name__})"
        return
    point = None
    match = _POINT_LINE.search(text)
    if match:  # a file the app wrote: take its design point back too
        point = {"velocity": match["v"].strip(), "field": match["E"].strip()}
        if match["top"]:
            point["v_top"] = match["top"].strip()
    _load(data, name, point)
    state.set_widget("size.example", UPLOADED)


def _on_material() -> None:
    """Show the chosen material's values (or the damper file's) in the fluid inputs; seal friction stays."""
    material = st.session_state["size.material"]
    values = st.session_state.get("size.file_fluid", {}) if material == FILE_VALUES else fluid_values(material)
    for key in FLUID_FIELDS:
        if key != "seal_friction":
            state.set_widget(f"size.fluid.{key}", _text(values.get(key)))
    state.set_widget("size.field", _text(values.get("reference_field")))
    state.forget("size.sweep.")


def spec_from_widgets(values: dict) -> dict:
    """The damper spec (damper-file content) of the widget values: ``configuration``, ``ducts``, ``material``,
    and the texts of :data:`GEOMETRY_FIELDS` and :data:`FLUID_FIELDS`.

    With a material, only the values that differ from the material's are written, so that the material's yield
    curve stays in force unless a value of the power law is overridden (docs/materials.md).

    >>> v = {"configuration": "mixed", "ducts": 1, "material": "typical-mr", "duct_length": "25 mm",
    ...      "duct_mean_diameter": "", "gap": "1 mm", "piston_diameter": "40 mm", "rod_diameter": "12 mm",
    ...      **{k: "" for k in FLUID_FIELDS}, "seal_friction": "40 N"}
    >>> spec_from_widgets(v)["fluid"]
    {'material': 'typical-mr', 'seal_friction': '40 N'}

    A single-ended rod and its accumulator have no widgets: they are kept as the file had them.

    >>> kept = {"rod": {"rod": "single"}, "accumulator": {"precharge": "0.9 MPa", "gas_volume": "16 cm^3"}}
    >>> spec = spec_from_widgets({**v, "kept": kept})
    >>> spec["geometry"]["rod"], spec["accumulator"]["precharge"]
    ('single', '0.9 MPa')
    """
    configuration = values["configuration"]
    geometry: dict[str, Any] = {"configuration": configuration}
    for key in GEOMETRY_FIELDS:
        if configuration == "mixed" and key == "duct_mean_diameter":
            continue  # Dp + h for a mixed damper
        geometry[key] = values[key].strip()
    if configuration == "valve":
        geometry["ducts"] = int(values["ducts"])
    material = values.get("material")
    base = fluid_values(material) if material not in (None, FILE_VALUES, "") else {}
    fluid: dict[str, Any] = {"material": material} if base else {}
    for key in FLUID_FIELDS:
        text = values[key].strip()
        if not text or (key in base and text == _text(base[key]).strip()):
            continue
        if key == "yield_exponent":
            fluid[key] = plain_number(text)  # float() read '1_5' as 15 and the ARABIC-INDIC digit three as 3
            if fluid[key] is None:
                raise ErdesignError(f"fluid.yield_exponent: expected a plain number, got {text!r}")
        else:
            fluid[key] = text
    kept = values.get("kept") or {}
    geometry.update(kept.get("rod") or {})
    spec = {"name": values.get("name", "design"), "geometry": geometry, "fluid": fluid}
    if values.get("coil"):
        spec["coil"] = dict(values["coil"])
    if kept.get("accumulator"):
        spec["accumulator"] = dict(kept["accumulator"])
    return spec


def _inputs() -> dict:
    """Draw the inputs; return their values."""
    values: dict[str, Any] = {"coil": st.session_state.get("size.coil"), "kept": st.session_state.get("size.kept")}
    values["name"] = state.widget(
        st.text_input, "design name", "size.name", "design", help="Names the damper file and the report you download."
    )
    st.subheader("Geometry")
    values["configuration"] = state.widget(
        st.radio,
        "configuration",
        "size.configuration",
        "valve",
        options=["valve", "mixed"],
        horizontal=True,
        help="valve: fluid pushed through stationary ducts (Makris); mixed: the piston head is the moving "
        "electrode and shears the fluid it pushes (Kamath and Wereley).",
    )
    for key, (label, helptext) in GEOMETRY_FIELDS.items():
        if key == "duct_mean_diameter" and values["configuration"] == "mixed":
            values[key] = ""
            continue
        values[key] = state.widget(st.text_input, label, f"size.geo.{key}", "", help=helptext + " With its unit.")
    if values["configuration"] == "valve":
        values["ducts"] = state.widget(
            st.number_input, "ducts in parallel n", "size.geo.ducts", 1, min_value=1, max_value=64, step=1
        )
    else:
        values["ducts"] = 1
    st.subheader("Fluid")
    values["material"] = state.widget(
        st.selectbox,
        "material",
        "size.material",
        FILE_VALUES,
        options=[FILE_VALUES, *state.material_names()],
        on_change=_on_material,
        help="From the materials database (docs/materials.md); any value below overrides it.",
    )
    coil = bool(values["coil"])
    for key, (label, helptext) in FLUID_FIELDS.items():
        if coil and key in _CIRCUIT_KEYS:
            # the yield stress of a coil damper follows from the magnetic circuit at each current: a material's
            # value at its own reference field (43.98 kPa at 250 kA/m) would read as the value at the rated current
            st.text_input(
                label,
                value="from the magnetic circuit (below)",
                disabled=True,
                key=f"size.coil.{key}",
                help="With a [coil], τy(I) is the fluid's yield curve at the gap field H_g(I) of the "
                "magnetic circuit: the Magnetic circuit section shows it at each current.",
            )
            values[key] = _text(st.session_state.get("size.file_fluid", {}).get(key))
            continue
        if coil and key == "reference_field":
            label = "reference field: the rated coil current"
        values[key] = state.widget(
            st.text_input, label, f"size.fluid.{key}", "", help=(helptext + " With its unit.").strip()
        )
    return values


#: Fluid values a damper with a [coil] takes from its magnetic circuit instead of the power law.
_CIRCUIT_KEYS = ("yield_stress", "yield_exponent")


def _control_kind(values: dict) -> str | None:
    """The kind of control the typed reference field (or the material's) is, or None while it is not valid."""
    from erdesign.fluid import control_kind

    text = values.get("reference_field") or ""
    if not text.strip() and values.get("material") not in (None, "", FILE_VALUES):
        text = _text(fluid_values(values["material"]).get("reference_field"))
    try:
        return control_kind(text.strip(), "reference_field") if text.strip() else None
    except ErdesignError:
        return None


def _point_inputs(kind: str | None) -> dict:
    """Draw the design point's inputs (as typed) with the control labelled by its ``kind``; return them."""
    cols = st.columns([1, 1, 1, 1])
    point = {
        "velocity": state.widget(
            cols[0].text_input,
            "design velocity v",
            "size.velocity",
            "25 mm/s",
            help="Piston velocity of the design point, with its unit (mm/s, in/s, m/s).",
        ),
        "field": state.widget(
            cols[1].text_input,
            control_label(kind, "design"),
            "size.field",
            "3 kV/mm",
            help="The control, with its unit: the same kind as the fluid's reference field (kV/mm, kA/m, T or A).",
        ),
        "v_top": state.widget(cols[2].text_input, "top velocity of the curves", "size.v_top", "50 mm/s"),
        "levels": int(
            state.widget(
                cols[3].number_input,
                "control levels",
                "size.levels",
                4,
                min_value=1,
                max_value=6,
                step=1,
                help="Controls of the curves, from the design control down to 0.",
            )
        ),
    }
    return point


def _candidate(values: dict, point: dict) -> tuple[dict | None, Any, str]:
    """The design of the inputs and its report, or (None, None, why) when an input is not valid."""
    try:
        spec = spec_from_widgets(values)
        design = {"spec": spec, **point}
        if not to_si(point["v_top"], "m/s", "top velocity of the curves") > 0:
            raise ErdesignError(f"top velocity of the curves: must be positive, got {point['v_top']!r}")
        return design, state.design_report(state.design_text(design), state.unit_system()), ""
    except ErdesignError as exc:
        return None, None, state.clean_message(str(exc))


def _metrics(report) -> None:
    """The design point as metrics, three to a row (labels and numbers of the report's design-point table)."""
    rows = [r for r in report.design_point if r.key not in ("velocity", "field")]
    for i in range(0, len(rows), 3):
        cols = st.columns(3)
        for col, row in zip(cols, rows[i : i + 3]):
            col.metric(row.label, row.value.text, help=row.note or None)


_STATUS = {"pass": "pass", "warn": "WARN", "info": "info"}


def _checks(report) -> None:
    """The validity checks of the report (the same records), and the library's validity warnings."""
    for m in report.validity_messages:
        st.warning(m, icon="⚠️")
    if report.warnings == 0 and not report.validity_messages:
        st.success(f"Validity checks: {len(report.checks)} pass or info, none warns (the report's section 4).")
    else:
        st.warning(f"Validity checks: {report.warnings} of {len(report.checks)} warn (the report's section 4).")
    # a table, not a dataframe: the details wrap instead of being cut off
    st.table(
        [
            {
                "check": c.name,
                "status": _STATUS[c.status],
                "value": c.value.text if c.value else "",
                "limit": c.limit.text if c.limit else "",
                "detail": c.detail,
            }
            for c in report.checks
        ]
    )


def _curves_csv(report) -> str:
    sweep = report.sweep
    columns = [("velocity", "m/s", sweep.velocity)]
    for label, row in zip(sweep.field_labels(), sweep.force):
        columns.append((f"force at {label}", "N", row))
    for label, row in zip(sweep.field_labels(), sweep.pressure_drop):
        columns.append((f"pressure drop at {label}", "Pa", row))
    for label, E, row in zip(sweep.field_labels(), sweep.field, sweep.dynamic_range):
        if E != 0:
            columns.append((f"dynamic range at {label}", "", row))
    for label, row in zip(sweep.field_labels(), sweep.reynolds):
        columns.append((f"Reynolds number at {label}", "", row))
    return csv_text(
        columns,
        comment=f"quasi-steady curves of {report.title} (erdesign.damper.curves); numbers in {EXPORT_UNITS} units",
    )


def _downloads(design: dict, report) -> None:
    stem = state.file_stem(design["spec"].get("name") or "design")
    cols = st.columns([4, 3, 4])  # the labels whole at 1280 px
    cols[0].download_button(
        "Damper file (TOML)",
        damper_toml(design["spec"], comment=design_comment(design)),
        file_name=f"{stem}.toml",
        mime="application/toml",
        key="size.dl.toml",
        icon=":material/download:",
        help="Opens again with the upload above, and in `erdesign size`; the design point is kept as a comment.",
    )
    cols[1].download_button(
        "Curves (CSV)",
        _curves_csv(report),
        file_name=f"{stem}-curves.csv",
        mime="text/csv",
        key="size.dl.curves",
        icon=":material/download:",
    )
    point = design_point_csv(report)
    cols[2].download_button(
        "Design point (CSV)",
        point,
        file_name=f"{stem}-design-point.csv",
        mime="text/csv",
        key="size.dl.point",
        icon=":material/download:",
    )


def design_point_csv(report) -> str:
    """The design point as CSV in SI: one column per figure headed ``label [unit]`` (``[1]`` for a ratio), one row
    of numbers; the validity checks as comment lines (text, not numbers)."""
    rows = [r for r in report.design_point if r.key != "field"]
    field = report.setting("field_design").value
    columns = [("design control", si_unit_text(field.si_unit), field.si)]
    columns += [(r.label, si_unit_text(r.value.si_unit), r.value.si) for r in rows]
    checks = "\n".join(f"check {c.name}: {c.status}" + (f" ({c.detail})" if c.detail else "") for c in report.checks)
    return csv_text(
        [(name, unit, [value]) for name, unit, value in columns],
        comment=f"design point of {report.title} (numbers in {EXPORT_UNITS} units)\n{checks}",
    )


def _baseline(design: dict, report) -> None:
    """Pin designs; show the current design beside the pinned ones (table and curves: :mod:`erdesign.app.pinned`)."""
    labels = {f"geometry.{k}": label for k, (label, _) in GEOMETRY_FIELDS.items()}
    labels |= {f"fluid.{k}": label for k, (label, _) in FLUID_FIELDS.items()}
    pinned.render(design, report, labels)


def _magnetics(report) -> None:
    """The magnetic circuit of a damper with a [coil]: B(I) and tau_y(I), and the coil figures at the rated current
    (the report's magnetic section and figure: no physics here)."""
    m = report.magnetics
    st.subheader("Magnetic circuit")
    fig = next(f for f in report.figures if f.key == "magnetics")
    st.plotly_chart(fig.figure, key="size.fig.magnetics", config=state.chart_config("size.fig.magnetics"))
    rows = {r.key: r for r in m["rows"]}
    keys = [
        "gap_flux_density",
        "yield_stress_rated",
        "coil_resistance",
        "inductance",
        "time_constant",
        "power",
        "voltage",
        "current_density",
        "knee_current",
    ]
    shown = [rows[k] for k in keys if k in rows]
    for i in range(0, len(shown), 3):
        for col, row in zip(st.columns(3), shown[i : i + 3]):
            col.metric(row.label, row.value.text, help=row.note or None)
    if m["saturated"]:
        st.info(
            f"At the rated current the circuit is past the knee of a B-H curve: the {m['limiting_part']} "
            "saturates first (more current buys little more yield stress)."
        )
    st.table(
        [
            {
                "current": r[0].text,
                "B_g": r[1].text,
                "H_g": r[2].text,
                "τ_y": r[3].text,
                "L": r[4].text,
                "L/R": r[5].text,
                "power": r[6].text,
                "saturated": r[7].text,
            }
            for r in m["table"].rows
        ]
    )
    coil = st.session_state.get("size.coil") or {}
    st.caption("coil: " + ", ".join(f"{k} = {v}" for k, v in coil.items()))


def _curves(report) -> None:
    tab_f, tab_d, tab_p = st.tabs(["force - velocity", "dynamic range - velocity", "pressure drop - velocity"])
    tab_f.plotly_chart(
        plots.force_velocity_figure(report.sweep), key="size.fig.force", config=state.chart_config("size.fig.force")
    )
    tab_d.plotly_chart(
        plots.dynamic_range_figure(report.sweep), key="size.fig.range", config=state.chart_config("size.fig.range")
    )
    tab_p.plotly_chart(
        plots.pressure_drop_figure(report.sweep),
        key="size.fig.pressure",
        config=state.chart_config("size.fig.pressure"),
    )


def _explorer(text: str, damper, v: float, E: float) -> None:
    st.subheader("Sweep explorer")
    st.caption(
        "Vary one dimension of the design and see force, dynamic range and Reynolds number trade off "
        "(at the design velocity and field)."
    )
    parameter = state.widget(
        st.selectbox,
        "vary",
        "size.sweep.parameter",
        "gap",
        options=list(state.GEOMETRY_SWEEPS),
        format_func=state.GEOMETRY_SWEEPS.get,
    )
    current = getattr(damper.geometry, parameter)
    cols = st.columns(3)
    lo_text = state.widget(cols[0].text_input, "from", f"size.sweep.from.{parameter}", f"{current * 1e3 * 0.5:.4g} mm")
    hi_text = state.widget(cols[1].text_input, "to", f"size.sweep.to.{parameter}", f"{current * 1e3 * 2:.4g} mm")
    points = state.widget(cols[2].slider, "points", "size.sweep.points", 21, min_value=5, max_value=61)
    try:
        lo = float(to_si(lo_text, "m", "from"))
        hi = float(to_si(hi_text, "m", "to"))
        if not 0 < lo < hi:
            raise ErdesignError(f"sweep: need 0 < from < to, got {lo_text!r} to {hi_text!r}")
    except ErdesignError as exc:
        st.error(state.clean_message(str(exc)))
        return
    with st.spinner(f"Sweeping the {state.GEOMETRY_SWEEPS[parameter]} over {points} designs ..."):
        result = state.geometry_sweep(text, parameter, tuple(np.linspace(lo, hi, points)), v, E)
    if result["invalid"]:
        st.info(f"Some values give no buildable damper and are left out, e.g. {result['invalid']}")
    field_label = field_text(E, damper.fluid.control_unit, damper.fluid.field_unit)
    velocity_label = show(Q_(v, "m/s"), pick_unit(Q_(v, "m/s"), "velocity"), name="velocity").text
    st.plotly_chart(
        figures.tradeoff_figure(result, state.GEOMETRY_SWEEPS[parameter], field_label, velocity_label),
        key="size.fig.tradeoff",
        config=state.chart_config("size.fig.tradeoff"),
    )
    data = csv_text(
        [
            (parameter, "m", result["value"]),
            (f"force at {field_label}", "N", result["force"]),
            ("zero-field force", "N", result["zero_field_force"]),
            ("dynamic range", "", result["dynamic_range"]),
            ("Reynolds number", "", result["reynolds"]),
            ("gap ratio h/d", "", result["gap_ratio"]),
        ],
        comment=f"sweep of the {state.GEOMETRY_SWEEPS[parameter]} at {velocity_label} and {field_label}; "
        f"numbers in {EXPORT_UNITS} units",
    )
    st.download_button(
        "Sweep (CSV)",
        data,
        file_name=f"sweep-{parameter}.csv",
        mime="text/csv",
        key="size.dl.sweep",
        icon=":material/download:",
    )


#: The tolerances the page starts with (issue 24: gap +- 20 um on 0.8 mm, viscosity +- 10 %, yield stress +- 15 %).
DEFAULT_TOLERANCES = "geometry.gap=+-2.5 %\nfluid.viscosity=+-10 %\nfluid.yield_stress=+-15 %"


@st.cache_data(show_spinner=False, max_entries=8)
def _tolerance_study(text: str, specs: tuple[str, ...], v: float, E: float, samples: int, seed: int):
    from erdesign.campaign.tolerance import tolerance_study

    damper, _ = state.build_damper(text)
    return tolerance_study(damper, specs, velocity=v, field=E, samples=samples, seed=seed)


def _tolerances(text: str, v: float, E: float) -> None:
    with st.expander("Tolerances: spread of the design point and what drives it"):
        st.caption(
            "One tolerance per line, as `erdesign tolerance --vary` takes them: `KEY=+-P %` or "
            "`KEY=VALUE +- DELTA` (one standard deviation of a normal; prefix `uniform:` for a uniform "
            "spread of half-width DELTA). Keys as in the damper file (docs/tolerance.md)."
        )
        specs_text = state.widget(st.text_area, "tolerances", "size.tol.vary", DEFAULT_TOLERANCES, height=110)
        cols = st.columns(3)
        samples = state.widget(
            cols[0].number_input, "samples", "size.tol.samples", 2000, min_value=100, max_value=200000, step=1000
        )
        seed = state.widget(cols[1].number_input, "seed", "size.tol.seed", 0, min_value=0, step=1)
        run = state.widget(cols[2].checkbox, "run the study", "size.tol.run", False)
        if not run:
            return
        specs = tuple(line.strip() for line in specs_text.splitlines() if line.strip())
        try:
            with st.spinner(f"Sampling {int(samples)} designs ..."):
                result = _tolerance_study(text, specs, v, E, int(samples), int(seed))
        except ErdesignError as exc:
            st.error(state.clean_message(str(exc)))
            return
        from erdesign.cli.tolerance import tolerance_table

        if result.rejected:
            st.info(f"{result.rejected} non-physical draws were rejected and drawn again.")
        output = state.widget(
            st.selectbox,
            "output",
            "size.tol.output",
            "force_N",
            options=list(plots.TOLERANCE_OUTPUTS),
            format_func=lambda k: plots.TOLERANCE_OUTPUTS[k][0],
        )
        left, right = st.columns(2)
        left.plotly_chart(
            plots.tolerance_histogram_figure(result, output),
            key="size.fig.tolerance",
            config=state.chart_config("size.fig.tolerance"),
        )
        right.plotly_chart(
            plots.sensitivity_tornado_figure(result, output),
            key="size.fig.tornado",
            config=state.chart_config("size.fig.tornado"),
        )
        st.code(tolerance_table(result), language=None)


def render() -> None:
    """Draw the Size page."""
    st.title("Size a damper")
    if "size.configuration" not in st.session_state and "_keep.size.configuration" not in st.session_state:
        design = state.current_design()
        _load(design["spec"], "design", {k: design[k] for k in ("velocity", "field", "v_top", "levels")})
        st.session_state.setdefault("_keep.size.example", _example_of(design["spec"]))
    top = st.columns([2, 3])
    kept = st.session_state.get("_keep.size.example")
    examples = example_names() + ([kept] if kept in NOT_EXAMPLES else [])
    state.widget(
        top[0].selectbox,
        "start from an example",
        "size.example",
        state.DEFAULT_EXAMPLE,
        options=examples,
        on_change=_on_example,
    )
    top[1].file_uploader("or load a damper file (TOML)", type=["toml"], key="size.upload", on_change=_on_upload)
    if _ERROR in st.session_state:
        st.error(st.session_state[_ERROR])
    left, right = st.columns([1, 2], gap="large")
    with left:
        values = _inputs()
    with right:
        st.subheader("Design point")
        point = _point_inputs(_control_kind(values))
        design, report, why = _candidate(values, point)
        if design is None:
            st.error(f"{why}. The pages keep the last valid design until this is corrected.", icon="🚫")
            design = state.current_design()
            try:
                report = state.design_report(state.design_text(design), state.unit_system())
            except ErdesignError:
                return
            st.caption(f"Showing the last valid design: v = {design['velocity']}, E = {design['field']}.")
        else:
            state.set_design(design)
        _metrics(report)
        flow = next(n for n in report.notes if n.startswith("flow model"))
        st.caption(
            f"At v = {report.setting('velocity_design').value.text} and E = "
            f"{report.setting('field_design').value.text}; {flow}."
        )
        _checks(report)
        if report.magnetics is not None:
            _magnetics(report)
        _curves(report)
        _downloads(design, report)
    text = state.spec_text(design["spec"])
    damper, _ = state.build_damper(text)
    _baseline(design, report)
    v = report.setting("velocity_design").value.si
    E = float(to_si(design["field"], damper.fluid.control_unit, "design field"))
    _explorer(text, damper, v, E)
    _tolerances(text, v, E)
    with st.expander("damper file of this design (TOML)"):
        st.code(damper_toml(design["spec"], comment=design_comment(design)), language="toml")


if __name__ == "__main__":
    render()
