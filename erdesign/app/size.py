"""Size page: geometry and fluid with units -> the design point, its validity and the trade-offs.

Inputs are values with units as text (``"0.8 mm"``, ``"2.15 in"``), read by pint through the library; the fluid may
come from the materials database, any value of it overridden.  Outputs come from :meth:`erdesign.Damper.size`, the
curves from :func:`erdesign.report.sweep.velocity_sweep` drawn by :mod:`erdesign.plots`, the sweep explorer from
:func:`erdesign.app.state.geometry_sweep`.
"""

from __future__ import annotations

import json
import sys
from typing import Any

import numpy as np
import streamlit as st

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

from erdesign import plots
from erdesign.app import figures, state
from erdesign.damper_file import damper_from_dict, example_names
from erdesign.errors import ErdesignError
from erdesign.materials import fluid_values
from erdesign.report.builder import default_velocity_max
from erdesign.report.formatting import pick_unit, show
from erdesign.units import Q_, to_si

__all__ = ["render", "FLUID_FIELDS", "GEOMETRY_FIELDS", "FILE_VALUES", "spec_from_widgets"]

#: Material choice meaning "the values of the damper file".
FILE_VALUES = "(values of the damper file)"
UPLOADED = "(uploaded damper file)"

GEOMETRY_FIELDS = {
    "duct_length": ("duct length L", "Length of each annular duct (mixed: of the piston head)."),
    "duct_mean_diameter": ("duct mean diameter d", "Mean diameter of the annular gap (valve only)."),
    "gap": ("gap h", "Radial gap of the annulus."),
    "piston_diameter": ("piston diameter Dp", "Diameter of the piston (head)."),
    "rod_diameter": ("rod diameter dr", "Diameter of the double-ended rod."),
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


def _quantity_text(q) -> str:
    """``"25 mm/s"``: a quantity as an input shows it (and pint reads it back)."""
    return f"{q.magnitude:.4g} {q.units:~C}"


def _load(spec: dict, source: str) -> None:
    """Put a damper spec into the widgets (a callback: runs before the widgets are drawn)."""
    geo, fluid = spec.get("geometry", {}), dict(spec.get("fluid", {}))
    state.set_widget("size.configuration", geo.get("configuration", "valve"))
    for key in GEOMETRY_FIELDS:
        state.set_widget(f"size.geo.{key}", _text(geo.get(key)))
    state.set_widget("size.geo.ducts", int(geo.get("ducts", 1)))
    material = fluid.pop("material", None)
    st.session_state["size.file_fluid"] = fluid
    st.session_state["size.file_name"] = spec.get("name", source)
    state.set_widget("size.material", material or FILE_VALUES)
    base = fluid_values(material) if material else {}
    for key in FLUID_FIELDS:
        state.set_widget(f"size.fluid.{key}", _text(fluid.get(key, base.get(key))))
    with_units = Q_(_text(fluid.get("reference_field", base.get("reference_field"))))
    damper, _ = state.caught(lambda: damper_from_dict(spec, source=source))
    v_top = default_velocity_max(damper)
    unit = pick_unit(Q_(v_top, "m/s"), "velocity")
    state.set_widget("size.velocity", _quantity_text(Q_(v_top / 2, "m/s").to(unit)))
    state.set_widget("size.v_top", _quantity_text(Q_(v_top, "m/s").to(unit)))
    state.set_widget("size.field", _quantity_text(with_units))
    state.forget("size.sweep.")


def _on_example() -> None:
    name = st.session_state["size.example"]
    st.session_state.pop(_ERROR, None)
    if name != UPLOADED:
        _load(state.example_spec(name), f"examples/{name}.toml")


def _on_upload() -> None:
    upload = st.session_state.get("size.upload")
    st.session_state.pop(_ERROR, None)
    if upload is None:
        return
    try:
        data = tomllib.loads(upload.getvalue().decode("utf-8"))
        damper_from_dict(data, source=upload.name)      # check before taking it
    except UnicodeDecodeError:
        st.session_state[_ERROR] = f"{upload.name}: not a text (UTF-8) file; expected a damper file (TOML)"
        return
    except tomllib.TOMLDecodeError as exc:
        st.session_state[_ERROR] = f"{upload.name}: invalid TOML: {exc}"
        return
    except ErdesignError as exc:
        st.session_state[_ERROR] = str(exc)
        return
    _load(data, upload.name)
    state.set_widget("size.example", UPLOADED)


def _on_material() -> None:
    """Show the chosen material's values (or the damper file's) in the fluid inputs; seal friction stays."""
    material = st.session_state["size.material"]
    values = (st.session_state.get("size.file_fluid", {}) if material == FILE_VALUES
              else fluid_values(material))
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
    """
    configuration = values["configuration"]
    geometry: dict[str, Any] = {"configuration": configuration}
    for key in GEOMETRY_FIELDS:
        if configuration == "mixed" and key == "duct_mean_diameter":
            continue                                   # Dp + h for a mixed damper
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
            try:
                fluid[key] = float(text)
            except ValueError:
                raise ErdesignError(f"fluid.yield_exponent: expected a plain number, got {text!r}") from None
        else:
            fluid[key] = text
    return {"name": values.get("name", "design"), "geometry": geometry, "fluid": fluid}


def _inputs() -> dict:
    """Draw the inputs; return their values."""
    values: dict[str, Any] = {}
    st.subheader("Geometry")
    values["configuration"] = state.widget(
        st.radio, "configuration", "size.configuration", "valve", options=["valve", "mixed"], horizontal=True,
        help="valve: fluid pushed through stationary ducts (Makris); mixed: the piston head is the moving "
             "electrode and shears the fluid it pushes (Kamath and Wereley).")
    for key, (label, helptext) in GEOMETRY_FIELDS.items():
        if key == "duct_mean_diameter" and values["configuration"] == "mixed":
            values[key] = ""
            continue
        values[key] = state.widget(st.text_input, label, f"size.geo.{key}", "", help=helptext + " With its unit.")
    if values["configuration"] == "valve":
        values["ducts"] = state.widget(st.number_input, "ducts in parallel n", "size.geo.ducts", 1, min_value=1,
                                       max_value=64, step=1)
    else:
        values["ducts"] = 1
    st.subheader("Fluid")
    values["material"] = state.widget(
        st.selectbox, "material", "size.material", FILE_VALUES, options=[FILE_VALUES, *state.material_names()],
        on_change=_on_material, help="From the materials database (docs/materials.md); any value below overrides it.")
    for key, (label, helptext) in FLUID_FIELDS.items():
        values[key] = state.widget(st.text_input, label, f"size.fluid.{key}", "",
                                   help=(helptext + " With its unit.").strip())
    values["name"] = st.session_state.get("size.file_name", "design")
    return values


def _metric(column, label: str, q, kind: str, help: str = "") -> None:
    if kind:
        text = show(q, pick_unit(q, kind), name=label).text
    else:
        text = "undefined" if q is None or not np.isfinite(q) else f"{q:.4g}"
    column.metric(label, text, help=help or None)


def _outputs(damper, velocity_text: str, field_text: str) -> tuple[float, float] | None:
    """The design point; returns (velocity, field) in SI, or None after showing the error."""
    try:
        v = float(to_si(velocity_text, "m/s", "design velocity"))
        result, messages = state.caught(lambda: damper.size(velocity=Q_(v, "m/s"), field=field_text))
    except ErdesignError as exc:
        st.error(str(exc))
        return None
    E = float(result.field.to(damper.fluid.control_unit).magnitude)
    cols = st.columns(3)
    _metric(cols[0], "force F", result.force, "force", "Quasi-steady force at the design velocity and field.")
    _metric(cols[1], "zero-field force F(0)", result.zero_field_force, "force")
    _metric(cols[2], "dynamic range F(E)/F(0)", result.dynamic_range, "")
    cols = st.columns(3)
    _metric(cols[0], "pressure drop Δp", result.pressure_drop, "pressure")
    _metric(cols[1], "yield force Fy", result.yield_force, "force", "Controllable force of the fluid.")
    _metric(cols[2], "damping constant C", result.damping_constant, "damping", "Makris eq 15, zero field.")
    cols = st.columns(3)
    _metric(cols[0], "Reynolds number Re", result.reynolds, "", "Makris eq 1; laminar below 2300.")
    _metric(cols[1], "plug fraction", result.plug_fraction, "", "Plug thickness over gap: 1 = blocked.")
    _metric(cols[2], "flow rate Q", result.flow_rate, "flow", "Volume the piston displaces per second.")
    st.caption(f"Flow model: {result.flow_model} (h/d = {result.gap_ratio:.3g}); piston area "
               f"{show(result.piston_area, 'cm^2', name='piston area').text}.")
    st.session_state["size.messages"] = st.session_state.get("size.messages", []) + messages
    return v, E


def _warnings() -> None:
    messages = list(dict.fromkeys(st.session_state.pop("size.messages", [])))
    if messages:
        for m in messages:
            st.warning(m, icon="⚠️")
    else:
        st.success("Validity checks pass: laminar flow, thin gap or exact annulus, field within the fluid's range.")


def _curves(text: str, damper, E: float) -> None:
    v_top_text = state.widget(st.text_input, "top velocity of the curves", "size.v_top", "50 mm/s")
    levels = state.widget(st.slider, "field levels (0 to the design field)", "size.levels", 4, min_value=2,
                          max_value=6)
    try:
        v_top = float(to_si(v_top_text, "m/s", "top velocity"))
        if not v_top > 0:
            raise ErdesignError(f"top velocity: must be positive, got {v_top_text!r}")
    except ErdesignError as exc:
        st.error(str(exc))
        return
    fields = tuple(float(x) for x in np.linspace(0.0, abs(E), levels)) if E else (0.0,)
    with st.spinner("Computing the curves ..."):
        sweep = state.velocity_sweep(text, v_top, fields)
    tab_f, tab_d = st.tabs(["force - velocity", "dynamic range - velocity"])
    tab_f.plotly_chart(plots.force_velocity_figure(sweep), key="size.fig.force")
    tab_d.plotly_chart(plots.dynamic_range_figure(sweep), key="size.fig.range")


def _explorer(text: str, damper, v: float, E: float) -> None:
    st.subheader("Sweep explorer")
    st.caption("Vary one dimension of the design and see force, dynamic range and Reynolds number trade off "
               "(at the design velocity and field).")
    parameter = state.widget(st.selectbox, "vary", "size.sweep.parameter", "gap",
                             options=list(state.GEOMETRY_SWEEPS), format_func=state.GEOMETRY_SWEEPS.get)
    current = getattr(damper.geometry, parameter)
    cols = st.columns(3)
    lo_text = state.widget(cols[0].text_input, "from", f"size.sweep.from.{parameter}",
                           f"{current * 1e3 * 0.5:.4g} mm")
    hi_text = state.widget(cols[1].text_input, "to", f"size.sweep.to.{parameter}", f"{current * 1e3 * 2:.4g} mm")
    points = state.widget(cols[2].slider, "points", "size.sweep.points", 21, min_value=5, max_value=61)
    try:
        lo = float(to_si(lo_text, "m", "from"))
        hi = float(to_si(hi_text, "m", "to"))
        if not 0 < lo < hi:
            raise ErdesignError(f"sweep: need 0 < from < to, got {lo_text!r} to {hi_text!r}")
    except ErdesignError as exc:
        st.error(str(exc))
        return
    with st.spinner(f"Sweeping the {state.GEOMETRY_SWEEPS[parameter]} over {points} designs ..."):
        result = state.geometry_sweep(text, parameter, tuple(np.linspace(lo, hi, points)), v, E)
    if result["invalid"]:
        st.info(f"Some values give no buildable damper and are left out, e.g. {result['invalid']}")
    field_label = f"{Q_(E, damper.fluid.control_unit).to(damper.fluid.field_unit):.4g~P}"
    velocity_label = f"{Q_(v, 'm/s').to(pick_unit(Q_(v, 'm/s'), 'velocity')):.4g~P}"
    st.plotly_chart(figures.tradeoff_figure(result, state.GEOMETRY_SWEEPS[parameter], field_label,
                                            velocity_label), key="size.fig.tradeoff")


def render() -> None:
    """Draw the Size page."""
    st.title("Size a damper")
    if "size.configuration" not in st.session_state and "_keep.size.configuration" not in st.session_state:
        spec = state.current_spec()
        _load(spec, "design")
        st.session_state.setdefault("_keep.size.example", state.DEFAULT_EXAMPLE)
    top = st.columns([2, 3])
    examples = example_names() + ([UPLOADED] if st.session_state.get("_keep.size.example") == UPLOADED else [])
    state.widget(top[0].selectbox, "start from an example", "size.example", state.DEFAULT_EXAMPLE,
                 options=examples, on_change=_on_example)
    top[1].file_uploader("or load a damper file (TOML)", type=["toml"], key="size.upload", on_change=_on_upload)
    if _ERROR in st.session_state:
        st.error(st.session_state[_ERROR])
    left, right = st.columns([1, 2], gap="large")
    with left:
        values = _inputs()
    with right:
        st.subheader("Design point")
        cols = st.columns(2)
        velocity_text = state.widget(cols[0].text_input, "design velocity v", "size.velocity", "25 mm/s")
        field_text = state.widget(cols[1].text_input, "design field E", "size.field", "3 kV/mm",
                                  help="The control, with its unit (kV/mm, kA/m, T or A).")
        try:
            spec = spec_from_widgets(values)
            text = state.spec_text(spec)
            damper, messages = state.build_damper(text)
        except ErdesignError as exc:
            st.error(f"The design is not valid: {exc}")
            return
        state.set_spec(spec)
        st.session_state["size.messages"] = messages
        point = _outputs(damper, velocity_text, field_text)
        _warnings()
        if point is None:
            return
        v, E = point
        _curves(text, damper, E)
    _explorer(text, damper, v, E)
    with st.expander("damper file of this design (TOML-like, as data)"):
        st.code(json.dumps(spec, indent=2), language="json")


if __name__ == "__main__":
    render()
