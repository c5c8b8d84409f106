"""Declaring the tables of erdesign's TOML files once (pydantic 2), with one-line messages that name the dotted key.

A file's table is a :class:`Table` (a pydantic model that forbids unknown keys); its values use the field types
below, each with its own check and message:

* :func:`quantity` - a value with a unit, as a string that :mod:`erdesign.units` parses (``"0.8 mm"``, ``"7 Pa*s"``),
  whose dimension is checked (and its sign, when the field says so); the field keeps the text as given, the objects
  built from it (:class:`~erdesign.geometry.Geometry`, :class:`~erdesign.fluid.Fluid`) convert it to SI;
* :data:`Number`, :data:`WholeNumber`, :data:`Text`, :data:`Flag`, :func:`choice` - plain TOML values, a bool never
  taken for a number.

:func:`validate` checks a parsed file against a model and turns pydantic's report into one
:class:`~erdesign.errors.ErdesignError` of the caller's class whose message names the dotted key, as
``geometry.gap: expected a length ...``, ``geometry.gap_size: unknown key in [geometry]; allowed keys: ...``,
``[fluid]: missing table`` or ``fluid.yield_exponent: expected a number, got '2'``.  :func:`key_table` writes a
model's keys as a Markdown table (the key tables of docs/file_formats.md are made by it).

Example
-------
>>> class Pipe(Table):
...     length: Length = field("the pipe's length")
...     count: WholeNumber = field("how many", default=1)
>>> validate(Pipe, {"length": "2 m"}).length
'2 m'
>>> validate(Pipe, {"length": "2 kg"}, "pipe")
Traceback (most recent call last):
...
erdesign.errors.ErdesignError: pipe.length: expected a length (a value with a unit such as 'm'), got '2 kg' (a mass)
>>> validate(Pipe, {"length": "2 m", "colour": 1}, "pipe")
Traceback (most recent call last):
...
erdesign.errors.ErdesignError: pipe.colour: unknown key in [pipe]; allowed keys: length, count
"""

from __future__ import annotations

import math
import numbers
import typing
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Annotated, Any

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, ValidationError, ValidationInfo

from .errors import ErdesignError, PlausibilityWarning, did_you_mean
from .units import to_si

__all__ = [
    "Table",
    "field",
    "quantity",
    "Length",
    "Number",
    "WholeNumber",
    "PositiveWholeNumber",
    "Text",
    "Flag",
    "choice",
    "whole_number",
    "checked",
    "validate",
    "key_table",
    "QuantitySpec",
    "implausible",
]


class Table(BaseModel):
    """A table of a TOML file: unknown keys are errors, values are not coerced, the model is read-only."""

    model_config = ConfigDict(extra="forbid", frozen=True, strict=False, arbitrary_types_allowed=True)

    def given(self) -> dict[str, Any]:
        """The keys the file gave (not the defaults), with their values as given."""
        return {k: getattr(self, k) for k in self.model_fields_set}


def field(description: str, default: Any = ..., **kwargs: Any) -> Any:
    """A key of a table: ``description`` goes into the docs' key table; no ``default`` means required."""
    return Field(default, description=description, **kwargs)


# ------------------------------------------------------------------------------------------------- value types
class _Refused(ValueError):
    """A value refused by one of the field types below: its message is the text after the dotted key."""


@dataclass(frozen=True)
class QuantitySpec:
    """What a :func:`quantity` field takes: the SI unit of its dimension and its sign (for the docs and checks)."""

    unit: str
    sign: str = ""  # "", "positive" or "non-negative"
    dimension: str = ""  # what the docs call it ("length"); the unit's dimension by default
    text: bool = False  # only a string (a bare number is refused as such, not as a number without unit)
    #: (low, high, why): the range real dampers take, SI; a value outside is warned (a unit mistake is likely),
    #: the warning naming the key and ``why`` (whose range it is: "any damper's force")
    plausible: tuple[float, float, str] | None = None

    def check(self, value: Any) -> Any:
        if (
            isinstance(value, bool)
            or not isinstance(value, (str, numbers.Real))
            or (self.text and not isinstance(value, str))
        ):
            raise _Refused(f'expected a value with a unit as a string (e.g. "1 {self.unit}"), got {value!r}')
        try:
            x = to_si(value, self.unit, "\x00")
        except ErdesignError as exc:
            raise _Refused(str(exc).removeprefix("\x00: ")) from None
        if self.sign == "positive" and not x > 0:
            raise _Refused(f"must be positive, got {value!r}")
        if self.sign == "non-negative" and not x >= 0:
            raise _Refused(f"must not be negative, got {value!r}")
        return value


def quantity(
    unit: str,
    sign: str = "",
    dimension: str = "",
    *,
    text: bool = False,
    plausible: tuple[float, float, str] | None = None,
) -> Any:
    """The type of a key whose value is a quantity in a unit of ``unit``'s dimension (any unit pint knows);
    ``sign`` "positive" or "non-negative"; ``text``: only strings (a bare number is refused as not text);
    ``plausible``: ``(low, high, why)`` in ``unit``, the range outside which :func:`validate` warns."""
    spec = QuantitySpec(unit, sign, dimension, text, plausible)
    return Annotated[Any, BeforeValidator(spec.check), spec]


def _number(value: Any) -> float:
    # numbers.Real: a dict built in Python may hold numpy numbers (a TOML file never does)
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise _Refused(f"expected a number, got {value!r}")
    if not math.isfinite(value):  # TOML has nan and inf
        raise _Refused(f"expected a finite number, got {value!r}")
    return value


def whole_number(low: int) -> Any:
    """The type of a key that takes a whole number >= ``low``."""

    def check(value: Any) -> int:
        if isinstance(value, bool) or not isinstance(value, numbers.Integral):
            raise _Refused(f"expected a whole number, got {value!r}")
        if value < low:
            raise _Refused(f"must be >= {low}, got {value!r}")
        return int(value)

    return Annotated[Any, BeforeValidator(check), f"whole number >= {low}"]


def checked(check: Any, kind: str) -> Any:
    """The type of a key checked by ``check(value, name)``, a function that raises an
    :class:`~erdesign.errors.ErdesignError` whose message starts with ``name`` and returns the value to keep;
    ``kind`` says what the key takes (the docs' key table)."""

    def run(value: Any, info: ValidationInfo) -> Any:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                kept = check(value, "\x00")
            except ErdesignError as exc:
                raise _Refused(str(exc).removeprefix("\x00: ")) from None
        for w in caught:  # a warning of the check names the key as validate() will: "\x00" is not shown
            text = str(w.message).replace("\x00", f"{_KEY}{info.field_name}")
            warnings.warn(text, w.category, stacklevel=2)
        return kept

    return Annotated[Any, BeforeValidator(run), kind]


#: Where a check's warning names its key: validate() puts the dotted name of the table in front.
_KEY = "\x00key:"


def _text(value: Any) -> str:
    if not isinstance(value, str):
        raise _Refused(f"expected text, got {value!r}")
    return value


def _flag(value: Any) -> bool:
    if not isinstance(value, bool):
        raise _Refused(f"expected true or false, got {value!r}")
    return value


@dataclass(frozen=True)
class _Choice:
    options: tuple[str, ...]

    def check(self, value: Any) -> str:
        if value not in self.options:
            hint = did_you_mean(value, self.options)
            raise _Refused(f"must be one of {', '.join(map(repr, self.options))}, got {value!r}{hint}")
        return value


def choice(*options: str) -> Any:
    """The type of a key that takes one of ``options`` (text)."""
    spec = _Choice(tuple(options))
    return Annotated[Any, BeforeValidator(spec.check), spec]


Length = quantity("m", "positive")
Number = Annotated[Any, BeforeValidator(_number), "number"]
WholeNumber = whole_number(0)
PositiveWholeNumber = whole_number(1)
Text = Annotated[Any, BeforeValidator(_text), "text"]
Flag = Annotated[Any, BeforeValidator(_flag), "true or false"]


# ------------------------------------------------------------------------------------------------- validation
def _dotted(where: str, loc: tuple) -> str:
    parts = [where] if where else []
    for item in loc:
        if isinstance(item, int):
            parts[-1] = f"{parts[-1]}[{item + 1}]"
        else:
            parts.append(str(item))
    return ".".join(parts)


def _model_at(model: type[Table], loc: tuple) -> type[Table] | None:
    """The model of the table at ``loc`` inside ``model`` (None when ``loc`` leaves the declared tables)."""
    for item in loc:
        if isinstance(item, int):
            continue
        info = model.model_fields.get(item)
        if info is None:
            return None
        nested = _table_of(info.annotation)
        if nested is None:
            return None
        model = nested
    return model


def _table_of(annotation: Any) -> type[Table] | None:
    if isinstance(annotation, type) and issubclass(annotation, Table):
        return annotation
    for arg in typing.get_args(annotation):
        found = _table_of(arg)
        if found is not None:
            return found
    return None


def _message(model: type[Table], where: str, error: Mapping[str, Any]) -> str:
    loc, kind = tuple(error["loc"]), error["type"]
    name = _dotted(where, loc)
    if kind == "extra_forbidden":
        parent = _model_at(model, loc[:-1])
        allowed = ", ".join(parent.model_fields) if parent is not None else ""
        table = _dotted(where, loc[:-1])
        hint = did_you_mean(loc[-1], parent.model_fields) if parent is not None else ""
        return f"{name}: unknown key" + (f" in [{table}]" if table else "") + f"{hint}; allowed keys: {allowed}"
    if kind == "missing":
        parent = _model_at(model, loc[:-1])
        info = parent.model_fields.get(loc[-1]) if parent is not None else None
        if info is not None and _table_of(info.annotation) is not None:
            if "list of tables" in info.metadata:
                return f"{name}: missing (at least one [[{name}]] table)"
            return f"[{name}]: missing table"
        options = next((m.options for m in (info.metadata if info else ()) if isinstance(m, _Choice)), None)
        return f"{name}: missing" + (f" ({' or '.join(map(repr, options))})" if options else "")
    if kind in ("model_type", "model_attributes_type", "dict_type"):
        return f"{name or 'file'}: expected a table, got {error['input']!r}"
    if kind in ("list_type", "tuple_type"):
        return f"{name}: expected a list of tables, got {error['input']!r}"
    cause = (error.get("ctx") or {}).get("error")
    if isinstance(cause, ValueError):
        return f"{name}: {cause}"
    return f"{name}: {error['msg']}"  # pragma: no cover - a type not declared here


def validate(model: type[Table], data: Any, where: str = "", *, error: type[ErdesignError] = ErdesignError) -> Table:
    """``data`` (a parsed TOML table) checked against ``model``; the first problem is an ``error`` whose one-line
    message names the dotted key (``where`` is the table's own dotted name, "" for a whole file)."""
    prefix = f"{where}." if where else ""
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            table = model.model_validate(data)
    except ValidationError as exc:
        errors = exc.errors(include_url=False)
        # a misspelt key is an unknown key and a missing one: name the unknown one, the cause
        first = next((e for e in errors if e["type"] == "extra_forbidden"), errors[0])
        raise error(" ".join(_message(model, where, first).split())) from None
    for w in caught:
        warnings.warn(str(w.message).replace(_KEY, prefix), w.category, stacklevel=3)
    for message in implausible(table, where):
        warnings.warn(message, PlausibilityWarning, stacklevel=3)
    return table


def implausible(table: Table, where: str = "") -> list[str]:
    """The message of each value of ``table`` (and the tables in it) outside its declared plausible range
    (:func:`quantity`'s ``plausible``), naming the dotted key: possible, but beyond any real damper (a unit mistake
    is likely: "1e9 V" for an ER supply, "1e12 N" for a force)."""
    messages = []
    for key in table.model_fields_set:
        info, value = type(table).model_fields[key], getattr(table, key)
        name = f"{where}.{key}" if where else key
        items = value if isinstance(value, list) else [value]
        for i, item in enumerate(items, start=1):
            if isinstance(item, Table):
                messages += implausible(item, f"{name}[{i}]" if isinstance(value, list) else name)
        spec = next((m for m in info.metadata if isinstance(m, QuantitySpec) and m.plausible), None)
        if spec is None or value is None:
            continue
        lo, hi, why = spec.plausible
        x = to_si(value, spec.unit, name)
        if not lo <= x <= hi:
            messages.append(
                f"{name}: {x:.4g} {spec.unit} is {'below' if x < lo else 'beyond'} {why} ({lo:g} to {hi:g} "
                f"{spec.unit}); check the value and its unit"
            )
    return messages


# ------------------------------------------------------------------------------------------------- the docs
def _kind(info: Any) -> str:
    for meta in info.metadata:
        if isinstance(meta, QuantitySpec):
            from .units import dimension_name, ureg

            what = meta.dimension or dimension_name(ureg.Quantity(1, meta.unit).dimensionality)
            what = what.removeprefix("a ").removeprefix("an ")
            sign = {"positive": " > 0", "non-negative": " >= 0"}.get(meta.sign, "")
            warned = (
                f"; warned outside {meta.plausible[0]:g} to {meta.plausible[1]:g} {meta.unit}" if meta.plausible else ""
            )
            return f'{what}{sign}, with a unit ("1 {meta.unit}"){warned}'
        if isinstance(meta, _Choice):
            return " or ".join(f'"{o}"' for o in meta.options)
        if isinstance(meta, str):
            return meta
    if _table_of(info.annotation) is not None:
        return "list of tables" if "list of tables" in info.metadata else "table"
    return "table" if info.annotation in (dict, Mapping) else str(info.annotation)


def key_table(model: type[Table]) -> str:
    """The keys of ``model`` as a Markdown table: key, value, required or default, meaning."""
    lines = ["| key | value | required / default | meaning |", "| --- | --- | --- | --- |"]
    for key, info in model.model_fields.items():
        if info.is_required():
            need = "required"
        elif info.default is None:
            need = "optional"
        else:
            need = (
                f"default `{info.default!r}`".replace("'", '"')
                if not isinstance(info.default, bool)
                else f"default `{str(info.default).lower()}`"
            )
        lines.append(f"| `{key}` | {_kind(info)} | {need} | {info.description or ''} |")
    return "\n".join(lines) + "\n"
