"""Build the damper and the vehicle of a quarter-vehicle run from what a user gives (unit strings, file names).

:func:`vehicle_damper` turns a damper file (the physics damper) or a registered model with a parameter
specification (a published set, ``"name=value unit, ..."`` or an ``identify --json`` file) into a
:class:`~erdesign.simulation.vehicle.VehicleDamper`; :func:`quarter_car` reads vehicle overrides
(``"m2=1300 kg, k=110 kN/m"``).  The command line and the app call these and hold no physics.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import ErdesignError
from .vehicle import QUARTER_CAR, QuarterCar, VehicleDamper

__all__ = ["vehicle_damper", "quarter_car", "CAR_UNITS", "PRESET_DAMPERS"]

#: Dampers of the literature by name -> the options of :func:`vehicle_damper` (the app's choices).
PRESET_DAMPERS = {
    "conventional (Butz and von Stryk eq 33)": {"model": "bingham", "params": "c0=6000 N*s/m, f_c=0 N"},
    "MR, Bingham (Butz and von Stryk 4.2)": {"model": "bingham", "params": "c0=5000 N*s/m, f_c=670 N"},
    "MR, modified Bouc-Wen (Butz and von Stryk 4.3)": {"model": "bouc_wen_modified", "params": "butz_vonstryk2002"},
    "MR, Spencer et al. 1997, 0-2.25 V": {"model": "bouc_wen_modified", "params": "spencer1997", "max_field": "2.25 V"},
}

#: Units of the vehicle keys (Butz and von Stryk 2002 section 4.1 names).
CAR_UNITS = {"m1": "kg", "m2": "kg", "K": "N/m", "C": "N*s/m", "k": "N/m"}


def vehicle_damper(
    *,
    damper: Any = None,
    effects=(),
    model: str | None = None,
    params: str | None = None,
    field: Any = None,
    max_field: Any = None,
) -> VehicleDamper:
    """The damper of a vehicle run.

    Parameters
    ----------
    damper : str, Path or Damper, optional
        A damper file or bundled example name: its physics damper (with ``effects``) is the damper.
    model, params : str, optional
        Instead of ``damper``: a registry model name and its parameters (as ``erdesign simulate --params``).
    field : quantity or str, optional
        Control a passive damper holds (default 0).
    max_field : quantity or str, optional
        Largest control of the semi-active range [0, max_field]; default the damper file's ``reference_field``.
        With a model, its unit gives the kind of control (``"2.25 V"``, ``"1 A"``, ``"3 kV/mm"``).
    """
    from ..fluid import CONTROL_UNITS, control_kind
    from ..models.registry import get_model
    from ..units import to_si

    if (damper is None) == (model is None):
        raise ErdesignError("damper, model: give one of them (a damper file, or a model with its parameters)")
    if damper is not None:
        if params is not None and str(params).strip():
            raise ErdesignError(
                "params: applies to --model; a damper file's physics damper runs at its nominal "
                "fluid (calibrate it with 'erdesign fit' and write the fitted fluid to the file)"
            )
        m = get_model("physics", damper=damper, effects=tuple(effects))
        fluid = m.damper.fluid
        kind = fluid.control
        top = fluid.reference_field if max_field is None else fluid.field_si(max_field, "max_field")
        hold = fluid.field_si(field, "field")
        return VehicleDamper(
            m, m.defaults(), kind, (0.0, float(top)), float(hold), label=m.damper.name or "physics damper"
        )
    if effects:
        raise ErdesignError("effects: apply to a damper file (the physics damper) only")
    if params is None:
        raise ErdesignError(
            f'params: --model {model} needs its parameters (a published set, "name=value unit, '
            '..." or an identify --json file)'
        )
    m = get_model(model)
    kinds = {control_kind(q, name) for q, name in ((field, "field"), (max_field, "max_field")) if q is not None}
    if len(kinds) > 1:
        raise ErdesignError("field, max_field: must be the same kind of control (e.g. both in V)")
    kind = kinds.pop() if kinds else None
    unit = CONTROL_UNITS.get(kind, "")
    hold = 0.0 if field is None else float(to_si(field, unit, "field"))
    top = 0.0 if max_field is None else float(to_si(max_field, unit, "max_field"))
    values, _, notes = _resolve(m, params, kind, max(top, hold))
    d = VehicleDamper(m, values, kind, (0.0, top), hold, label=f"{model} ({params})" if "=" not in params else model)
    d.notes = notes
    return d


def _resolve(model, params, kind, level):
    """Parameter values from a specification, with a probe record carrying the kind of control (the parameter
    resolution of ``simulate`` needs one to set the control reference)."""
    from ..data.measurement import Measurement
    from ..identification.identify import resolve_parameters

    t = np.linspace(0.0, 1.0, 101)
    probe = Measurement.from_arrays(
        t,
        0.01 * np.sin(2 * np.pi * t),
        control=level if kind else None,
        control_kind=kind,
        name="the vehicle's control",
    )
    return resolve_parameters(model, params, probe, where="params")


def quarter_car(text: str | None = None) -> QuarterCar:
    """The vehicle: Butz and von Stryk (2002) section 4.1, with overrides ``"m2=1300 kg, k=110 kN/m"``."""
    from ..models.published import parse_parameter_list
    from ..units import to_si

    if text is None or not text.strip():
        return QuarterCar()
    given = parse_parameter_list(text, where="vehicle")
    unknown = [k for k in given if k not in CAR_UNITS]
    if unknown:
        raise ErdesignError(f"vehicle: unknown key {unknown[0]!r}; keys: {', '.join(CAR_UNITS)}")
    return QuarterCar(**{**QUARTER_CAR, **{k: float(to_si(v, CAR_UNITS[k], f"vehicle.{k}")) for k, v in given.items()}})
