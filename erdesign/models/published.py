"""Published parameter sets of the damper models (data: ``published.toml`` beside this module), and the reading of
parameter values given with units (``"c0b=3.50 N*s/(cm*V)"``) into a model's SI values.

A set is named per model (``spencer1997`` for ``bouc_wen_modified``); each value keeps the unit of its print and
its source.  Coefficients per unit control are given per unit of the control (N s/(cm V)) and converted with the
set's ``control_reference``: the model's equations take the dimensionless control u = control / reference.

Examples
--------
>>> s = published_set("bouc_wen_modified", "spencer1997")
>>> s.control_kind, s.control_reference
('voltage', 1.0)
>>> round(s.values["c0a"], 6), round(s.values["alpha_b"], 6)     # 21.0 N s/cm, 695 N/(cm V) in SI per volt
(2100.0, 69500.0)
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Mapping

from .base import Model, ParameterError

__all__ = [
    "PublishedSet",
    "published_set",
    "published_sets",
    "parse_parameter_values",
    "parse_parameter_list",
    "PUBLISHED_FILE",
]

PUBLISHED_FILE = Path(__file__).with_name("published.toml")


@dataclass(frozen=True)
class PublishedSet:
    """One published parameter set of one model (SI values, per unit u for control coefficients)."""

    name: str
    model: str
    source: str
    values: dict[str, float]
    control_kind: str | None = None
    """Kind of control the set is for (a key of :data:`erdesign.fluid.CONTROL_UNITS`), None for a fixed field."""
    control_reference: float = 1.0
    """Control (SI) that maps to u = 1."""
    note: str = ""
    value_sources: dict[str, str] = field(default_factory=dict)
    printed: dict[str, str] = field(default_factory=dict)
    """The values as printed (with their units)."""


@lru_cache(maxsize=1)
def _table() -> dict:
    with open(PUBLISHED_FILE, "rb") as fh:
        return tomllib.load(fh)


def published_sets(model_name: str | None = None) -> list[tuple[str, str]]:
    """(model, set name) of every shipped set, or of one model's sets."""
    return [(m, s) for m, sets in _table().items() for s in sets if model_name in (None, m)]


def published_set(model_name: str, set_name: str) -> PublishedSet:
    """The published set ``set_name`` of the model ``model_name``, in SI (raises naming the known sets)."""
    from .registry import get_model

    sets = _table().get(model_name, {})
    if set_name not in sets:
        known = ", ".join(f"{s} ({m})" for m, s in published_sets()) or "none"
        raise ParameterError(f"--params: no published set {set_name!r} for model {model_name}; published sets: {known}")
    entry = sets[set_name]
    kind = entry.get("control")
    reference = 1.0
    if kind is not None:
        from ..fluid import CONTROL_UNITS
        from ..units import Q_

        reference = float(Q_(entry["control_reference"]).to(CONTROL_UNITS[kind]).magnitude)
    printed = {k: v["value"] for k, v in entry["parameters"].items()}
    model = get_model(model_name)
    values = parse_parameter_values(
        model, printed, control_kind=kind, control_reference=reference, where=f"{model_name}.{set_name}"
    )
    return PublishedSet(
        set_name,
        model_name,
        entry["source"],
        values,
        kind,
        reference,
        entry.get("note", ""),
        {k: v.get("source", "") for k, v in entry["parameters"].items()},
        printed,
    )


def parse_parameter_list(text: str, where: str = "--params") -> dict[str, str]:
    """``"c0=4000 N*s/m, f_c=0.5 kN"`` -> ``{"c0": "4000 N*s/m", "f_c": "0.5 kN"}`` (bad items are errors naming
    them)."""
    out: dict[str, str] = {}
    for item in (part.strip() for part in text.split(",")):
        if not item:
            continue
        name, sep, value = item.partition("=")
        if not sep or not name.strip() or not value.strip():
            raise ParameterError(f"{where}: {item!r} is not 'name=value unit'")
        if name.strip() in out:
            raise ParameterError(f"{where}: {name.strip()} is given twice")
        out[name.strip()] = value.strip()
    if not out:
        raise ParameterError("--params: no 'name=value unit' item")
    return out


def parse_parameter_values(
    model: Model,
    texts: Mapping[str, str | float],
    *,
    control_kind: str | None = None,
    control_reference: float = 1.0,
    where: str = "--params",
) -> dict[str, float]:
    """SI values of ``model``'s parameters from values with units.

    A value whose dimension is the parameter's is converted to the parameter's SI unit.  A coefficient per unit
    control may instead be given per unit of the control (``"3.5 N*s/(cm*V)"`` for a per-u damping): it is
    multiplied by ``control_reference`` (SI, in the unit of ``control_kind``) once, or twice for a per-u^2
    coefficient.  A plain number is read in the parameter's SI unit.  Errors name the parameter.
    """
    from ..errors import ErdesignError
    from ..units import Q_, parse_quantity

    out: dict[str, float] = {}
    for name, text in texts.items():
        p = model.parameter(name)  # unknown names are errors naming the known ones
        if not isinstance(text, str) or _plain_number(text):
            out[name] = _finite(float(text), name, text, where)
            continue
        try:
            q = parse_quantity(text, f"{where}: {name}")
        except ErdesignError as exc:
            raise ParameterError(str(exc)) from None
        target = Q_(1.0, p.unit or "dimensionless")
        value = None
        if not hasattr(q, "dimensionality"):
            value = float(q)
        elif q.dimensionality == target.dimensionality:
            value = float(q.to(target.units).magnitude)
        elif control_kind is not None:
            from ..fluid import CONTROL_UNITS

            ref = Q_(control_reference, CONTROL_UNITS[control_kind])
            for power in (1, 2):
                scaled = q * ref**power
                if scaled.dimensionality == target.dimensionality:
                    value = float(scaled.to(target.units).magnitude)
                    break
        if value is None:
            per = "" if control_kind is None else f" (or per unit {control_kind})"
            raise ParameterError(
                f"{where}: {name} = {text!r} does not have the unit of {name}: {p.unit or 'none'}{per}"
            )
        out[name] = _finite(value, name, text, where)
    return out


def _finite(value: float, name: str, text, where: str) -> float:
    if not math.isfinite(value):
        raise ParameterError(f"{where}: {name} = {text!r} is not finite")
    return value


def _plain_number(text: str) -> bool:
    from ..units import plain_number

    return plain_number(text) is not None
