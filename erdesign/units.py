"""The one unit registry of erdesign and the conversions at the edge of the library.

Public functions take pint quantities or strings such as ``"0.8 mm"`` and return quantities; everything inside
(the kernels in :mod:`erdesign.flow` and :mod:`erdesign.constitutive`) works on plain SI floats or numpy arrays.
This module is the only place where the two worlds meet:

* :data:`ureg` is pint's application registry, so that quantities made here survive pickling (Streamlit caches,
  multiprocessing) and mix with quantities made by the user's own ``pint.get_application_registry()``.
* :func:`to_si` turns a user value into an SI magnitude and raises a :class:`~erdesign.errors.UnitError` that names
  the argument and the expected dimension when the value does not fit.
* :func:`unit_aware` builds the public, unit-aware version of an SI kernel.

Example
-------
>>> from erdesign.units import Q_, to_si
>>> to_si("0.0315 in", "m", "gap")
0.0008001
>>> to_si("3 kg", "m", "gap")
Traceback (most recent call last):
...
erdesign.errors.UnitError: gap: expected a length (a value with a unit such as 'm'), got '3 kg' (a mass)
"""

from __future__ import annotations

import functools
import inspect
import math
import re
import sys
import unicodedata
import warnings
from typing import Any, Callable, Mapping

import numpy as np

from ._pint import application_registry, pint
from ._util import broadcast_named
from .errors import UnitError

__all__ = [
    "ureg",
    "Q_",
    "to_si",
    "positive_si",
    "plain_number",
    "parse_quantity",
    "parse_unit",
    "clean_value_text",
    "to_quantity",
    "unit_aware",
    "dimension_name",
    "same_dimension",
]

ureg = application_registry()  # pint's application registry, its definitions cached (erdesign/_pint.py)

#: Units pint lacks that damper rigs write: (definition for the registry, the name it defines).
EXTRA_UNITS = (("inch_per_second = inch / second = ips", "ips"),)  # US rigs' controllers and data sheets


def _define_extra_units(registry) -> None:
    """Define :data:`EXTRA_UNITS` in ``registry`` unless it knows the name already (a user's own registry)."""
    for definition, unit in EXTRA_UNITS:
        try:
            registry.parse_units(unit)
        except pint.errors.UndefinedUnitError:
            registry.define(definition)


_define_extra_units(ureg)


def _plain_magnitude(value: Any) -> Any:
    """``value`` as pint can wrap it: a pandas Series (or an xarray DataArray) as a numpy array of its values, which
    pint refuses to wrap ("PlainQuantity cannot wrap upcast type"); a DataFrame refused naming its columns."""
    if not pint.compat.is_upcast_type(type(value)):
        return value
    kind = type(value).__name__
    if kind in ("DataFrame", "Dataset"):
        columns = [str(c) for c in getattr(value, "columns", getattr(value, "data_vars", []))]
        first = columns[0] if columns else "v"
        raise UnitError(
            f"Q_: got a {kind} of {len(columns)} column(s) {', '.join(map(repr, columns[:4]))[:80]}; give one "
            f"column, e.g. Q_(frame[{first!r}], 'm/s')"
        )
    if getattr(value.dtype, "kind", "O") in "iuf":  # pandas' nullable Float64 and Int64 too (pd.NA as NaN)
        try:
            return value.to_numpy(dtype=float, na_value=np.nan)
        except TypeError:  # xarray's to_numpy() takes no arguments
            pass
    return value.to_numpy()  # texts, booleans, objects: as they are, for the argument's checks to name


class _QuantityType(type):
    """The type of :data:`Q_`: calling it makes pint's quantity of :data:`ureg` (:func:`_plain_magnitude` first);
    ``isinstance(x, Q_)`` and its class attributes are pint's."""

    def __call__(cls, value: Any, units: Any = None) -> Any:
        try:
            return ureg.Quantity(_plain_magnitude(value), units)
        except TypeError as exc:  # pint's "Invalid magnitude for Quantity: True" (a bool, a dict ...)
            raise UnitError(f"Q_: {' '.join(str(exc).split())[:200]}; give a number or an array of numbers") from None

    def __instancecheck__(cls, obj: Any) -> bool:
        return isinstance(obj, ureg.Quantity)

    def __subclasscheck__(cls, sub: type) -> bool:
        return issubclass(sub, ureg.Quantity)

    def __getattr__(cls, name: str) -> Any:
        return getattr(ureg.Quantity, name)


class Q_(metaclass=_QuantityType):  # noqa: N801 - pint's customary name for a registry's Quantity
    """A quantity of erdesign's unit registry: ``Q_(0.8, "mm")``, ``Q_("0.8 mm")``, ``Q_(series, "m/s")`` (a pandas
    Series or xarray DataArray is taken as a numpy array of its values; a DataFrame is refused, naming its
    columns).  Instances are pint's quantities of :data:`ureg` (``isinstance(q, Q_)`` holds for them)."""


# Plain-language names of the dimensions erdesign deals with, for error messages.
_DIMENSION_NAMES = {
    ureg.Unit(unit).dimensionality: name
    for unit, name in [
        ("m", "a length"),
        ("kg", "a mass"),
        ("s", "a time"),
        ("m/s", "a velocity"),
        ("m/s^2", "an acceleration"),
        ("m^2", "an area"),
        ("m^3", "a volume"),
        ("m^3/s", "a volumetric flow rate"),
        ("Pa", "a pressure or stress"),
        ("Pa*s", "a dynamic viscosity"),
        ("m^2/s", "a kinematic viscosity"),
        ("kg/m^3", "a density"),
        ("N", "a force"),
        ("N*s/m", "a damping constant"),
        ("N/m", "a stiffness"),
        ("J", "an energy"),
        ("W", "a power"),
        ("V/m", "an electric field"),
        ("A/m", "a magnetic field strength"),
        ("T", "a magnetic flux density"),
        ("A", "an electric current"),
        ("V", "a voltage"),
        ("K", "a temperature"),
        ("1/s", "a frequency or shear rate"),
        ("Pa/m", "a pressure gradient"),
        ("N*s^2/m", "a mass"),
        ("", "a plain number"),
    ]
}


_VISCOSITY = ureg.Unit("Pa*s").dimensionality


def dimension_name(dimensionality: Any) -> str:
    """Plain-language name of a pint dimensionality (``[length]`` -> ``"a length"``)."""
    return _DIMENSION_NAMES.get(dimensionality, f"a quantity of dimension {dimensionality}")


#: Signs that are minus signs in typeset text: read as '-'.  (U+2212 MINUS SIGN, U+FE63 SMALL HYPHEN-MINUS,
#: U+FF0D FULLWIDTH HYPHEN-MINUS)
_MINUS_SIGNS = {"\u2212": "-", "\ufe63": "-", "\uff0d": "-"}
#: Dashes and hyphens that look like a minus sign but are not one (a range "1–2 mm", a word processor's en dash):
#: refused rather than guessed.
_DASHES = "\u2010\u2011\u2012\u2013\u2014\u2015\u2043\u02d7\u2796"
#: Characters outside ASCII that unit symbols use (micro, ohm, degree, middle dot, superscripts, angstrom).
_UNIT_CHARACTERS = set("µμΩΩ°·⋅×²³¹⁰⁴⁵⁶⁷⁸⁹⁻Åℓ")
#: Typed degree signs that are not U+00B0 (a masculine ordinal, a ring above): read as the degree sign.
_DEGREE_SIGNS = {"\u00ba": "\u00b0", "\u02da": "\u00b0"}
#: Blocks of compatibility characters that are units written as one character ('\u2103' DEGREE CELSIUS,
#: '\u339c' SQUARE MM, '\u339b' SQUARE MU M): read as their letters (NFKC).
_UNIT_SYMBOL_BLOCKS = (("\u2100", "\u214f"), ("\u3380", "\u33ff"))
_DIGIT_SEPARATOR = re.compile(r"\d_\d|\d'\d")
_DECIMAL_COMMA = re.compile(r"^\s*[-+]?\d+,\d+(\s|$)")


def clean_value_text(text: str, name: str, *, number: bool = True) -> str:
    """The text of a value with a unit (``number``) or of a unit alone, made safe for pint, or a
    :class:`~erdesign.errors.UnitError` naming ``name``.

    Pint reads some slips silently and wrongly; they are refused or read as meant here:

    * a typeset minus sign (U+2212, also small and fullwidth) is a minus sign; fullwidth digits and letters are
      their ASCII forms; any Unicode space is a space; invisible format characters (zero-width space, BOM) are
      dropped;
    * a dash that is not a minus (en dash, em dash, hyphen: pint reads ``"–0.8 mm"`` as +0.8 mm), a digit
      separator (``"4_446.6 N"``), a comma (a decimal comma ``"0,8 mm"`` is read by pint as 0 mm, a list
      ``"1,2, A"`` as 12 A), two signs or two decimal points in a row, a ``#``, a control character, other digits
      than ASCII, and text longer than :data:`erdesign.limits.MAX_VALUE_CHARS` are refused;
    * a value with no number at all (``"mm"``, read by pint as 1 mm) is refused when ``number``.

    >>> clean_value_text("\u22120.8 mm", "gap")
    '-0.8 mm'
    >>> clean_value_text("0,8 mm", "gap")
    Traceback (most recent call last):
    ...
    erdesign.errors.UnitError: gap: '0,8 mm' has a decimal comma; write '0.8 mm' with a point
    """
    from .limits import MAX_VALUE_CHARS

    shown = text if len(text) <= 60 else text[:57] + "..."
    if len(text) > MAX_VALUE_CHARS:
        raise UnitError(
            f"{name}: {len(text)} characters is too long for a value with a unit (at most "
            f"{MAX_VALUE_CHARS}), got {shown!r}"
        )
    out = []
    for ch in text:
        if ch.isascii():
            if ch.isprintable():
                out.append(ch)
            elif ch.isspace():  # tab, line break
                out.append(" ")
            else:
                raise UnitError(f"{name}: {shown!r} holds the control character {ch!r}")
        elif ch in _MINUS_SIGNS:
            out.append(_MINUS_SIGNS[ch])
        elif ch in _DEGREE_SIGNS:
            out.append(_DEGREE_SIGNS[ch])
        elif any(lo <= ch <= hi for lo, hi in _UNIT_SYMBOL_BLOCKS) and unicodedata.normalize("NFKC", ch) != ch:
            out.append(unicodedata.normalize("NFKC", ch))
        elif "\uff01" <= ch <= "\uff5e":  # fullwidth ASCII
            out.append(chr(ord(ch) - 0xFEE0))
        elif ch.isspace():
            out.append(" ")
        elif unicodedata.category(ch) == "Cf":  # zero-width space, BOM, direction marks: invisible
            continue
        elif ch in _DASHES:
            raise UnitError(
                f"{name}: {shown!r} has the {unicodedata.name(ch, 'dash').lower()} U+{ord(ch):04X}, "
                "which is not a minus sign; write '-' for a negative value"
            )
        elif ch in _UNIT_CHARACTERS or (ch.isalpha() and not unicodedata.category(ch).startswith("N")):
            out.append(ch)
        else:
            digit = ch.isdigit() or ch.isnumeric()
            raise UnitError(
                f"{name}: {shown!r} holds the {'digit' if digit else 'character'} {ch!r} "
                f"({unicodedata.name(ch, 'unnamed')}, U+{ord(ch):04X}); write the value "
                f"{'in ASCII digits' if digit else 'and its unit in plain letters and digits'}, e.g. '0.8 mm'"
            )
    clean = "".join(out)
    if "," in clean:
        if _DECIMAL_COMMA.match(clean):
            raise UnitError(f"{name}: {shown!r} has a decimal comma; write {clean.replace(',', '.', 1)!r} with a point")
        raise UnitError(
            f"{name}: {shown!r} has a ',' (neither a decimal point nor a list is read here); give one "
            "value with its unit"
        )
    if _DIGIT_SEPARATOR.search(clean):
        plain = _DIGIT_SEPARATOR.sub(lambda m: m[0][0] + m[0][2], clean)
        raise UnitError(f"{name}: {shown!r} has a digit separator; write the number without it ({plain!r})")
    if re.search(r"(?<![\w.])0[xX][0-9a-fA-F]", clean):  # '0x1p-10 m' was "a '-' between units"
        raise UnitError(f"{name}: {shown!r} has a hexadecimal number; write the value in decimal, e.g. '0.8 mm'")
    if '"' in clean or "''" in clean:  # 0.0315" (inches): "cannot read" without a reason
        raise UnitError(f"{name}: {shown!r} has a '\"' (an inch mark?); write the unit as 'in'")
    if "#" in clean:
        raise UnitError(f"{name}: {shown!r} has a '#'; give the value and its unit only")
    if re.search(r"[-+]\s*[-+]", clean):
        raise UnitError(f"{name}: {shown!r} has two signs in a row")
    if re.search(r"\d*\.\d*\.", clean):
        raise UnitError(f"{name}: {shown!r} is not a number (two decimal points)")
    if number and clean.strip() and not re.search(r"[0-9]|inf|nan", clean, re.IGNORECASE):
        example = f", e.g. '1 {clean.strip()}'" if _is_unit(clean.strip()) else ""
        raise UnitError(
            f"{name}: cannot read {shown!r} as a value with a unit: it has no number; give a value "
            f"with its unit{example}"
        )
    return clean


_PLAIN_NUMBER = re.compile(
    r"\s*[-+]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|nan|inf|infinity)\s*", re.ASCII | re.IGNORECASE
)


def plain_number(text: str) -> float | None:
    """The number of a text that is a plain number in ASCII (``"0.0254"``, ``"-1e3"``, ``"nan"``), else None.

    Python's ``float()`` also reads digit separators (``"4_446.6"``) and other scripts' digits, which a user never
    means as a plain number: such text is left to :func:`parse_quantity`, which refuses it by name.

    >>> plain_number(" -2.5e3 "), plain_number("4_446.6"), plain_number("2 A")
    (-2500.0, None, None)
    """
    return float(text) if isinstance(text, str) and _PLAIN_NUMBER.fullmatch(text) else None


def _is_unit(text: str) -> bool:
    try:
        ureg.Unit(text)
    except Exception:  # noqa: BLE001 - any failure: not a unit
        return False
    return True


#: A value as erdesign reads it: one number (ASCII, with an optional exponent; or nan, inf), then its unit.
_QUANTITY_TEXT = re.compile(
    r"\s*([-+]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|nan(?![a-z])|inf(?:inity)?(?![a-z])))\s*(.*?)\s*",
    re.ASCII | re.IGNORECASE,
)
#: The unit word 'mil' (or 'mils'): read as 'thou', a thousandth of an inch (see :func:`_units`).
_MIL = re.compile(r"(?<![A-Za-z_])mils?(?![A-Za-z_])")
#: A power of a power (``m^2^3``, ``10**10**10``): pint evaluates it exactly, for minutes and gigabytes.
_POWER_TOWER = re.compile(r"(?:\*\*|\^)\s*[-+(\s]*[\d.]+[\s)]*(?:\*\*|\^)")


def _units(text: str, name: str, shown: str, what: str) -> Any:
    """The pint unit of ``text`` (the unit part of a value, or a header's unit), or a
    :class:`~erdesign.errors.UnitError` naming ``name``: an unknown unit, a garbled one, or a unit with a number in
    it (``"mm * 2"``: pint would multiply the value by it) is refused."""
    if what == "value" and text[:1] in "*/^":
        raise UnitError(
            f"{name}: cannot read {shown!r} as a value with a unit: an expression; give one number (a fraction as a "
            "decimal), then its unit "
            "(e.g. '0.5 mm')"
        )
    if _POWER_TOWER.search(text):
        raise UnitError(f"{name}: {shown!r} has a power of a power; give the unit with one exponent, e.g. 'm^3'")
    if text.count("(") != text.count(")"):  # was "(('EOF in multi-line statement', (2, 0)))"
        raise UnitError(f"{name}: {shown!r} has unbalanced brackets; close each '(' with a ')'")
    if text.rstrip()[-1:] in ("/", "*", "^", "-", "+"):
        raise UnitError(f"{name}: {shown!r}: the unit ends in {text.rstrip()[-1]!r}; complete or remove it")
    if what == "value" and re.match(r"\d[\d.]*(?:\s|$|[A-Za-zµμ])", text):  # '1 112 N': digits grouped by a space
        raise UnitError(
            f"{name}: {shown!r} has a space between digits (a digit group separator?); write the number without it"
        )
    if what == "value" and re.match(r"[eE][-+]?\d", text):  # '5 e-3 m': "a '-' between units"
        raise UnitError(f"{name}: {shown!r} has a space inside the number; write it without (e.g. '5e-3 m')")
    for dash in re.finditer(r"\s-\s*[\d.]", f" {text}"):  # '0.8 mm - 0.9 mm': "a '-' between units"
        before = f" {text}"[: dash.start()].rstrip()
        if what == "value" and (not before or before[-1] not in "^*"):  # not an exponent ('m ^ -1')
            raise UnitError(f"{name}: {shown!r} is a range (a '-' between two values); give one value with its unit")
    ranged = re.search(r"([A-Za-zµμ]+)-(\d*\.?\d+)\s*([A-Za-zµμ]+)", text)
    if what == "value" and ranged and ("." in ranged[2] or ranged[1] == ranged[3]):  # '0.8 mm-0.9 mm'
        raise UnitError(f"{name}: {shown!r} is a range (a '-' between two values); give one value with its unit")
    exponent = re.search(r"([A-Za-zµμ]+)-(\d)", text)
    if exponent and exponent[1] not in ("e", "E"):  # 'N s m-1': "a '-' between units"
        raise UnitError(f"{name}: {shown!r} has a power without '^'; write e.g. '{exponent[1]}^-{exponent[2]}'")
    text = _hyphen_products(text, name, shown)
    # 'mil' is a thousandth of an inch on every drawing a damper comes from; pint's 'mil' is an angle (1/6400 turn)
    text = _MIL.sub("thou", text)
    try:
        return ureg.parse_units(text)
    except pint.errors.UndefinedUnitError as exc:
        raise UnitError(
            f"{name}: unknown unit {'in ' if what == 'value' else ''}{shown!r} ({exc}){_unit_hint(exc, text)}"
        ) from None
    except ValueError as exc:
        if "scaling factor" in str(exc) and what == "value":
            raise UnitError(
                f"{name}: {shown!r} has a number or an expression after the unit; give one number, then its unit "
                "(e.g. '0.8 mm')"
            ) from None
        if "scaling factor" in str(exc):
            raise UnitError(f"{name}: the unit {shown!r} holds a number; give the unit alone, e.g. 'mm'") from None
        raise UnitError(
            f"{name}: cannot read {shown!r} as {'a value with a unit' if what == 'value' else 'a unit'} ({exc})"
        ) from None
    except Exception as exc:  # noqa: BLE001 - pint raises assorted errors (AssertionError too) for garbled strings
        # pint's own words when they say something ("missing unary operator"), never Python's about its internals
        # ("unsupported operand type(s) for -: 'ParserHelper' and 'ParserHelper'")
        detail = f" ({exc})" if str(exc) and not isinstance(exc, TypeError) else ""
        if "-" in text.strip("-"):
            detail = " (a '-' between units; write a product with '*' or a space, e.g. 'N*s/m')"
        kind = "a value with a unit" if what == "value" else "a unit"
        raise UnitError(f"{name}: cannot read {shown!r} as {kind}{detail}") from None


#: A hyphen between two unit words ('N-s/m', 'lbf-s/in', 'kN-m'): the product as US data sheets write it.
_HYPHEN_PRODUCT = re.compile(r"(?<=[A-Za-zµμΩ°)])-(?=[A-Za-zµμΩ(])")


def _hyphen_products(text: str, name: str, shown: str) -> str:
    """``text`` with each hyphen between unit words read as a product ('N-s/m' is N*s/m) where that is unambiguous:
    before any '/'.  After a '/' the writer may mean the product in the denominator ('W/m-K': W/(m*K)) or the
    rule of '*' and '/' from left to right (W*K/m), so it is refused with both spellings."""
    if "-" not in text or not _HYPHEN_PRODUCT.search(text):
        return text
    slash = text.find("/")
    head, tail = (text, "") if slash < 0 else (text[:slash], text[slash:])
    if _HYPHEN_PRODUCT.search(tail):
        word = re.search(r"/\s*([^/]*?-[^/]*?)\s*(?:/|$)", tail)
        group = word[1] if word else tail[1:]
        product = _HYPHEN_PRODUCT.sub("*", group)
        raise UnitError(
            f"{name}: {shown!r} has a '-' after '/', which is ambiguous: for a product below the line write it in "
            f"brackets, e.g. '{_HYPHEN_PRODUCT.sub('*', head)}/({product})'"
        )
    return _HYPHEN_PRODUCT.sub("*", head) + tail


#: A number times a power of ten as typeset or typed ('1 ×10³ N', '1.5·10⁻³ m', '2 x 10^3 N', '2*10**-3 m'): the power
#: written with '^', '**' or superscript digits (pint read the superscripts as "missing unary operator").
_TIMES_TEN = re.compile(
    r"^\s*([-+]?(?:\d+\.?\d*|\.\d+))\s*[×xX*·⋅]\s*10\s*"
    r"(?:(?:\^|\*\*)\s*\(?\s*([-+]?)\s*(\d+)\s*\)?|([⁻⁺]?)([⁰¹²³⁴⁵⁶⁷⁸⁹]+))(?![\d.])",
    re.ASCII,
)
_SUPERSCRIPTS = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺", "0123456789-+")


def _as_exponent(m: re.Match) -> str:
    sign = (m[2] or m[4] or "").translate(_SUPERSCRIPTS)
    return f"{m[1]}e{sign}{(m[3] or m[5]).translate(_SUPERSCRIPTS)} "


def _unit_hint(exc: pint.errors.UndefinedUnitError, text: str = "") -> str:
    """What an unknown unit was likely meant as: a power written without '^' ('cm3'), the unit ``text`` with a
    word in another case or split in two that gives a quantity erdesign knows ('KPa' -> 'kPa', 'Ns/m' -> 'N s/m',
    not 'ns/m'), or else a unit in another case: '; did you mean ...?'."""
    names = exc.unit_names if isinstance(exc.unit_names, (list, tuple)) else [exc.unit_names]
    for token in map(str, names):
        power = re.fullmatch(r"([A-Za-zµμ]+?)([23])", token)
        if power and _is_unit(power[1]):
            return f"; write a power with '^', e.g. '{power[1]}^{power[2]}'"
    fixed = _meant(f"1 {text}", None) if text else None
    if fixed is not None:
        return f"; did you mean {fixed[2:]!r}?"
    for token in map(str, names):
        variants = [token[:1].swapcase() + token[1:], token[:-1] + token[-1:].swapcase(), token.lower()]
        variants += [token[:1].swapcase() + token[1:-1] + token[-1:].swapcase(), token[:1] + token[1:].lower()]
        for v in dict.fromkeys(variants):
            if v != token and _is_unit(v):
                return f"; units are case-sensitive: did you mean {v!r}?"
    return ""


def _dimension_quietly(text: str) -> Any:
    """The dimension of a value's text as pint reads it, without erdesign's checks and hints (the hints try
    variants of a unit through it: through :func:`parse_quantity` they would try variants of the variants)."""
    m = _QUANTITY_TEXT.fullmatch(text)
    if m is None:
        raise ValueError(text)
    return ureg.parse_units(_MIL.sub("thou", m[2])).dimensionality if m[2] else ureg.Unit("").dimensionality


def _meant(text: str, target: Any, *, known_too: bool = False) -> str | None:
    """``text`` with one unit word changed so that the value has the dimension of ``target`` (None: any dimension
    erdesign names, :func:`dimension_name`): the word in another case ('KPa' -> 'kPa', '7 pa*s' -> '7 Pa*s') or two
    units written together ('Ns/m' -> 'N s/m'); only unknown words unless ``known_too``; None when no change does."""
    for word in dict.fromkeys(re.findall(r"[A-Za-z]+", text)):
        if not known_too and _is_unit(word):
            continue
        # 'KN' -> 'kN' (not 'kn', knots), 'MM' -> 'mm' ('mM' is millimolar, 'Mm' a megametre), 'kv' -> 'kV'
        variants = [word[:1].swapcase() + word[1:], word.lower(), word[:-1] + word[-1:].swapcase()]
        # two units written together ('Ns', 'ms^-1' for m s^-1), never a unit split into itself twice ('mm')
        variants += [
            f"{word[:i]} {word[i:]}"
            for i in range(1, len(word))
            if word[:i] != word[i:] and _is_unit(word[:i]) and _is_unit(word[i:])
        ]
        for v in dict.fromkeys(variants):
            fixed = re.sub(rf"(?<![A-Za-z]){word}(?![A-Za-z])", v, text)
            try:
                dim = _dimension_quietly(fixed)
                if dim == target.dimensionality if target is not None else (dim in _DIMENSION_NAMES and dim):
                    return fixed
            except Exception:  # noqa: BLE001 - any failure: not what was meant
                continue
    return None


def _case_hint(text: str, target: Any) -> str:
    """'; did you mean ...?' when one unit word of ``text`` changed (:func:`_meant`) gives the dimension of
    ``target`` ('7 pa*s' is 7 peta-years squared, '10 kn' 10 knots, '1 Nm' a nanometre per ... ), else ""."""
    fixed = _meant(text, target, known_too=True)
    if fixed is None and text != text.lower():  # '0.1 M/S': every letter in capitals
        try:
            if _dimension_quietly(text.lower()) == target.dimensionality:
                fixed = text.lower()
        except Exception:  # noqa: BLE001 - any failure: no hint
            pass
    return "" if fixed is None else f"; did you mean {fixed!r}?"


def parse_quantity(text: str, name: str) -> pint.Quantity:
    """A quantity from a string such as ``"0.8 mm"`` or ``"-40 degC"``, or a :class:`~erdesign.errors.UnitError`
    naming ``name``: the one parser of values with units (:func:`clean_value_text` says what it refuses).

    A value is one number, then its unit.  Pint's own string parser evaluates expressions, so that ``"0.8 mm 2"``
    or ``"0.8 mm * 2"`` (a slip) is read silently as 1.6 mm and ``"10**10**10 mm"`` runs for ever: text other than
    a number followed by a unit is refused.

    >>> parse_quantity("\u22120.8 mm", "gap")
    <Quantity(-0.8, 'millimeter')>
    >>> parse_quantity("0.8 mm * 2", "gap")
    Traceback (most recent call last):
    ...
    erdesign.errors.UnitError: gap: '0.8 mm * 2' has a number or an expression after the unit; give one number, then its unit (e.g. '0.8 mm')
    """
    if not isinstance(text, str):
        raise UnitError(f"{name}: expected a value with a unit as a string, got {type(text).__name__} {text!r:.60}")
    clean = clean_value_text(text, name)
    shown = text if len(text) <= 60 else text[:57] + "..."
    clean = _TIMES_TEN.sub(_as_exponent, clean, count=1)  # '1 ×10³ N' (scientific notation as typeset): '1e3 N'
    m = _QUANTITY_TEXT.fullmatch(clean)
    if m is None:
        raise UnitError(
            f"{name}: cannot read {shown!r} as a value with a unit; give one number, then its unit (e.g. '0.8 mm')"
        )
    number, unit = m[1], m[2]
    if "[" in unit or "]" in unit:  # '0.8 [mm]' (a unit in a header's brackets), 'N/[m/s]': brackets
        unit = unit.replace("[", "(").replace("]", ")")
    magnitude = float(number)
    mantissa = re.split("[eE]", number)[0]
    if magnitude != 0.0 and abs(magnitude) < sys.float_info.min or magnitude == 0.0 and re.search("[1-9]", mantissa):
        # 1e-400 was read as 0 (a seal friction of "1e-400 N" as none); 1e-320, a subnormal, loses its digits
        raise UnitError(
            f"{name}: {shown!r}: the number is too small to compute with (below {sys.float_info.min:.3g}); "
            "check the value and its unit"
        )
    if not unit:
        return Q_(magnitude)
    return Q_(magnitude, _units(unit, name, shown, "value"))


def parse_unit(text: str, name: str, *, value: float = 1.0) -> pint.Quantity:
    """``value`` in the unit ``text`` (a header's ``"kN"``, ``"degC"``), or a :class:`~erdesign.errors.UnitError`
    naming ``name`` for an unknown or garbled unit."""
    if not isinstance(text, str):
        raise UnitError(f"{name}: expected a unit as a string, got {text!r:.60}")
    clean = clean_value_text(text, name, number=False)
    shown = text if len(text) <= 60 else text[:57] + "..."
    if not clean.strip():
        raise UnitError(f"{name}: empty unit")
    return Q_(value, _units(clean.strip(), name, shown, "unit"))


def _parse(value: Any, name: str) -> Any:
    """Turn a string into a quantity; leave quantities, numbers and arrays alone."""
    return parse_quantity(value, name) if isinstance(value, str) else value


def same_dimension(a: Any, b: Any) -> bool:
    """True when two quantities (or unit strings) share a dimension."""
    qa = parse_quantity(a, "value") if isinstance(a, str) else a
    qb = parse_quantity(b, "value") if isinstance(b, str) else b
    return getattr(qa, "dimensionality", None) == getattr(qb, "dimensionality", None)


def to_si(
    value: Any, unit: str, name: str, *, allow_nonfinite: bool = False, scalar: bool = False
) -> float | np.ndarray:
    """Magnitude of ``value`` in the SI unit ``unit``, checked.

    Parameters
    ----------
    value : pint.Quantity, str, float or array
        The user's value.  Strings are parsed by pint (``"0.8 mm"``).  Plain numbers are accepted only where
        ``unit`` is dimensionless, because a number without a unit is ambiguous.
    unit : str
        The SI unit the kernel expects (``"m"``, ``"Pa*s"``, ``"V/m"``...).  Its dimension is the expected one.
    name : str
        Name of the argument or file key, used in error messages.
    allow_nonfinite : bool
        Let NaN and infinity through (default: such values are errors).
    scalar : bool
        Only one value (a geometry's length, a fluid's property): an array is an error naming ``name``.

    Returns
    -------
    float or numpy.ndarray
        The magnitude in ``unit`` (a Python float for scalars).

    Raises
    ------
    UnitError
        The value has another dimension, an unknown unit, no unit where one is needed, or is not finite.
    """
    given = value
    if isinstance(
        value, (bytes, bytearray, memoryview)
    ):  # was "b'0.1 m/s' has no unit; expected a velocity, e.g. 'b'0.1 m/s' m/s'"
        raise UnitError(f"{name}: expected text or a quantity, got bytes {value!r:.60}; decode it first")
    if isinstance(value, np.ndarray) and value.ndim == 0 and value.dtype.kind == "U":  # np.array("0.8 mm")
        value = given = str(value)
    target = ureg.Unit(unit)
    _refuse_odd_numbers(value, name, target)
    try:
        value = _parse(value, name)
    except UnitError as exc:
        better = _meant(given, target) if "unknown unit" in str(exc) else None
        if better is None:
            raise
        base = re.split(r"; (?:units are case-sensitive|write a power|did you mean)", str(exc))[0]
        raise UnitError(f"{base}; did you mean {better!r}?") from None
    if isinstance(value, pint.Quantity):
        if value.dimensionality != target.dimensionality:
            shown = given if isinstance(given, str) else _shown_quantity(value)
            hint = ""
            if isinstance(given, str) and re.search(r"Pas\b", given) and target.dimensionality == _VISCOSITY:
                hint = "; 'Pas' reads as pascals: write 'Pa*s' (or 'mPa*s')"  # '7000 mPas', German 'mPas'
            elif isinstance(given, str):
                hint = _case_hint(given, target)  # '7 pa*s' is 7 peta-years squared, '10 kn' 10 knots
            raise UnitError(
                f"{name}: expected {dimension_name(target.dimensionality)} (a value with a unit such as "
                f"'{unit}'), got '{shown}' ({dimension_name(value.dimensionality)}){hint}"
            )
        magnitude = value.to(target).magnitude
    else:
        if isinstance(value, (bool, np.bool_)) or value is None:
            raise UnitError(f"{name}: expected {dimension_name(target.dimensionality)}, got {value!r}")
        held = _holds_text(value)
        if held:  # ["1 mL/s", "2 mL/s"]: the example showed '['1 mL/s', '2 mL/s'] m^3/s'
            raise UnitError(
                f"{name}: a sequence of {held}; give one quantity array, e.g. Q_([1.0, 2.0], '{unit}'), or one "
                "value per call"
            )
        try:
            ndim = np.ndim(value)
        except ValueError:  # a ragged list: numpy's "inhomogeneous shape after 1 dimensions"
            raise UnitError(f"{name}: a ragged sequence (rows of different lengths); give a flat array") from None
        if target.dimensionality:
            if ndim == 0:
                shown = " ".join(repr(value).split())
                example = f", e.g. '{value} {unit}'" if len(shown) <= 40 else ""
                raise UnitError(
                    f"{name}: {shown[:60]}{'...' if len(shown) > 60 else ''} has no unit; expected "
                    f"{dimension_name(target.dimensionality)}{example}"
                )
            # a Series or an array: its repr ran over several lines into the example
            raise UnitError(
                f"{name}: {type(value).__name__} of shape {np.shape(value)} has no unit; expected "
                f"{dimension_name(target.dimensionality)}, e.g. Q_(values, '{unit}')"
            )
        magnitude = value
    if np.ma.isMaskedArray(magnitude) and np.ma.getmaskarray(magnitude).any():  # asarray would use hidden values
        raise UnitError(f"{name}: an array with masked elements; give the values to use (numpy.ma.compressed())")
    try:
        magnitude = np.asarray(magnitude, dtype=float)
    except OverflowError:  # an integer beyond any float (10**400)
        raise UnitError(f"{name}: {' '.join(repr(value).split())[:60]} is beyond the largest float") from None
    except (TypeError, ValueError):
        raise UnitError(f"{name}: {' '.join(repr(value).split())[:60]} is not a number") from None
    if not allow_nonfinite and not np.all(np.isfinite(magnitude)):
        shown = _shown_quantity(value) if isinstance(value, pint.Quantity) else repr(value)
        raise UnitError(f"{name}: value must be finite, got {shown}")
    if scalar and magnitude.ndim != 0:  # an array where one value is meant: "truth value of an array ..." later
        raise UnitError(f"{name}: expected one value, got an array of shape {magnitude.shape}")
    return float(magnitude) if magnitude.ndim == 0 else magnitude


def _refuse_odd_numbers(value: Any, name: str, target: Any) -> None:
    """Refuse, naming ``name``, complex numbers, dates, time spans and true/false given as a value or a quantity's
    magnitude: "has no unit; e.g. '(0.1+0j) m/s'" and "is not a number" told the user to add a unit that would
    not help."""
    magnitude = value.magnitude if isinstance(value, pint.Quantity) else value
    if isinstance(magnitude, (str, bytes)) or magnitude is None:
        return
    if isinstance(magnitude, complex):
        kind = "c"
    else:
        try:
            kind = np.asarray(magnitude).dtype.kind if isinstance(magnitude, np.ndarray) or np.ndim(magnitude) else ""
        except (TypeError, ValueError):  # a ragged list: said later
            return
        kind = kind or getattr(getattr(magnitude, "dtype", None), "kind", "")
    what = {"c": "complex numbers", "M": "a date", "m": "a time span", "b": "true/false"}.get(kind)
    if what is not None:
        shown = " ".join(repr(value).split())
        raise UnitError(
            f"{name}: expected {dimension_name(target.dimensionality)} (real numbers), got {what}: "
            f"{shown[:60]}{'...' if len(shown) > 60 else ''}"
        )


def _holds_text(value: Any) -> str:
    """ "texts" or "quantities" for a list, tuple, array or pandas Series holding strings or quantities rather than
    numbers; "" otherwise."""
    if isinstance(value, (list, tuple)):
        items = value[:100]
    elif getattr(getattr(value, "dtype", None), "kind", "") in "USOT" and np.ndim(value) > 0:  # arrays, Series
        items = list(np.asarray(value, dtype=object).ravel()[:100])
    else:
        return ""
    if any(isinstance(v, str) for v in items):
        return "texts"
    return "quantities" if any(isinstance(v, pint.Quantity) for v in items) else ""


def _shown_quantity(q: pint.Quantity) -> str:
    """A quantity for a message: the value when it is one, else the shape and unit of the array."""
    if np.ndim(q.magnitude) == 0:
        return f"{q:~P}"
    return f"an array of shape {np.shape(q.magnitude)} in {q.units:~P}"


def positive_si(value: Any, unit: str, name: str) -> float:
    """:func:`to_si` of one value that must be positive (an amplitude, a frequency), naming ``name`` otherwise.

    >>> positive_si("0 mm", "m", "amplitude")
    Traceback (most recent call last):
    ...
    erdesign.errors.UnitError: amplitude: must be positive, got '0 mm'
    """
    si = to_si(value, unit, name)
    if np.ndim(si) != 0:
        raise UnitError(f"{name}: expected one value, got an array of shape {np.shape(si)}")
    if not si > 0:
        shown = (
            value
            if isinstance(value, str)
            else (_shown_quantity(value) if isinstance(value, pint.Quantity) else repr(value))
        )
        raise UnitError(f"{name}: must be positive, got '{shown}'")
    return float(si)


def to_quantity(magnitude: Any, unit: str) -> pint.Quantity:
    """Quantity from an SI magnitude (float or array) and its unit."""
    return Q_(magnitude, unit)


def unit_aware(returns: str | tuple[str, ...] | Mapping[str, str], **units: str) -> Callable:
    """Decorator factory: the unit-aware public version of an SI kernel.

    Parameters
    ----------
    returns : str, tuple of str, or mapping
        SI unit of the kernel's result; a tuple for a tuple result; a mapping ``field -> unit`` for a named-tuple
        result (fields not named are returned as they are).
    **units : str
        SI unit of each argument that carries one (``gap="m"``).  Arguments not listed are passed unchanged.

    The wrapper accepts quantities or strings for the listed arguments, checks each dimension (the error names the
    argument), calls the kernel with SI magnitudes, and attaches units to the result.  Unknown keyword arguments
    are a :class:`TypeError`, as for any Python function.
    """

    def decorate(kernel: Callable) -> Callable:
        signature = inspect.signature(kernel)
        unknown = set(units) - set(signature.parameters)
        if unknown:
            raise TypeError(f"unit_aware({kernel.__name__}): no parameter named {sorted(unknown)}")

        @functools.wraps(kernel)
        def wrapper(*args, **kwargs):
            bound = signature.bind(*args, **kwargs)  # the kernel's own defaults (SI) apply to omitted arguments
            si = {
                # None only where the kernel's default is None (an optional argument); else it is named
                key: (
                    to_si(val, units[key], key)
                    if key in units and (val is not None or signature.parameters[key].default is not None)
                    else val
                )
                for key, val in bound.arguments.items()
            }
            arrays = {key: val for key, val in si.items() if isinstance(val, np.ndarray) and val.ndim}
            if len(arrays) > 1:
                broadcast_named(**arrays)
            with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
                result = kernel(**si)
            _warn_nonfinite(kernel.__name__, result)
            return _attach(result, returns)

        wrapper.kernel = kernel
        wrapper.__doc__ = (
            f"Unit-aware form of :func:`{kernel.__module__}.{kernel.__name__}`: arguments are pint quantities or "
            f"strings, results are quantities.\n\n" + (kernel.__doc__ or "")
        )
        return wrapper

    return decorate


def _warn_nonfinite(name: str, result: Any) -> None:
    """A :class:`~erdesign.errors.PlausibilityWarning` when a unit-aware function's result holds NaN or infinity
    for finite arguments (an overflow, a vanishing gap): never a silent NaN."""
    from .errors import PlausibilityWarning

    parts = (
        result._asdict().items()
        if hasattr(result, "_asdict")
        else (enumerate(result) if isinstance(result, tuple) else [("result", result)])
    )
    for key, part in parts:
        try:
            arr = np.asarray(part, dtype=float)
        except (TypeError, ValueError):
            continue
        if not np.all(np.isfinite(arr)):
            what = "" if key == "result" else f" ({key})"
            warnings.warn(
                f"{name}: the result{what} is not finite for these arguments (an overflow, or a gap or "
                "viscosity too small to represent); check their magnitudes and units",
                PlausibilityWarning,
                stacklevel=3,
            )
            return


def _attach(result: Any, returns: str | tuple[str, ...] | Mapping[str, str]) -> Any:
    if isinstance(returns, str):
        return Q_(result, returns)
    if isinstance(returns, tuple):
        return tuple(Q_(r, u) for r, u in zip(result, returns))
    fields = {k: (Q_(v, returns[k]) if k in returns else v) for k, v in result._asdict().items()}
    return type(result)(**fields)


def format_quantity(value: pint.Quantity, unit: str | None = None, digits: int = 4) -> str:
    """``value`` as text with ``digits`` significant figures, in ``unit`` when given (``"120.3 kN·s/m"``)."""
    q = value.to(unit) if unit else value
    mag = q.magnitude
    if isinstance(mag, float) and math.isfinite(mag):
        return f"{mag:.{digits}g} {q.units:~P}"
    return f"{q:~P}"


__all__.append("format_quantity")
