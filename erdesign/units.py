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
from typing import Any, Callable, Mapping

import numpy as np

from ._pint import application_registry, pint
from .errors import UnitError

__all__ = ["ureg", "Q_", "to_si", "to_quantity", "unit_aware", "dimension_name", "same_dimension"]

ureg = application_registry()   # pint's application registry, its definitions cached (erdesign/_pint.py)
Q_ = ureg.Quantity

# Plain-language names of the dimensions erdesign deals with, for error messages.
_DIMENSION_NAMES = {
    ureg.Unit(unit).dimensionality: name
    for unit, name in [
        ("m", "a length"), ("kg", "a mass"), ("s", "a time"), ("m/s", "a velocity"),
        ("m/s^2", "an acceleration"), ("m^2", "an area"), ("m^3", "a volume"),
        ("m^3/s", "a volumetric flow rate"), ("Pa", "a pressure or stress"), ("Pa*s", "a dynamic viscosity"),
        ("m^2/s", "a kinematic viscosity"), ("kg/m^3", "a density"), ("N", "a force"),
        ("N*s/m", "a damping constant"), ("N/m", "a stiffness"), ("J", "an energy"), ("W", "a power"),
        ("V/m", "an electric field"), ("A/m", "a magnetic field strength"), ("T", "a magnetic flux density"),
        ("A", "an electric current"), ("V", "a voltage"), ("K", "a temperature"),
        ("1/s", "a frequency or shear rate"), ("Pa/m", "a pressure gradient"), ("N*s^2/m", "a mass"),
        ("", "a plain number"),
    ]
}


def dimension_name(dimensionality: Any) -> str:
    """Plain-language name of a pint dimensionality (``[length]`` -> ``"a length"``)."""
    return _DIMENSION_NAMES.get(dimensionality, f"a quantity of dimension {dimensionality}")


def _parse(value: Any, name: str) -> Any:
    """Turn a string into a quantity; leave quantities, numbers and arrays alone."""
    if isinstance(value, str):
        try:
            return Q_(value)
        except (pint.errors.UndefinedUnitError, pint.errors.DefinitionSyntaxError) as exc:
            raise UnitError(f"{name}: unknown unit in {value!r} ({exc})") from None
        except Exception as exc:  # pint raises assorted errors for garbled strings
            raise UnitError(f"{name}: cannot read {value!r} as a value with a unit ({exc})") from None
    return value


def same_dimension(a: Any, b: Any) -> bool:
    """True when two quantities (or unit strings) share a dimension."""
    qa = Q_(a) if isinstance(a, str) else a
    qb = Q_(b) if isinstance(b, str) else b
    return getattr(qa, "dimensionality", None) == getattr(qb, "dimensionality", None)


def to_si(value: Any, unit: str, name: str, *, allow_nonfinite: bool = False) -> float | np.ndarray:
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
    value = _parse(value, name)
    target = ureg.Unit(unit)
    if isinstance(value, pint.Quantity):
        if value.dimensionality != target.dimensionality:
            shown = given if isinstance(given, str) else f"{value:~P}"
            raise UnitError(
                f"{name}: expected {dimension_name(target.dimensionality)} (a value with a unit such as "
                f"'{unit}'), got '{shown}' ({dimension_name(value.dimensionality)})"
            )
        magnitude = value.to(target).magnitude
    else:
        if isinstance(value, (bool, np.bool_)):
            raise UnitError(f"{name}: expected {dimension_name(target.dimensionality)}, got {value!r}")
        if target.dimensionality:
            raise UnitError(
                f"{name}: {value!r} has no unit; expected {dimension_name(target.dimensionality)}, "
                f"e.g. '{value} {unit}'"
            )
        magnitude = value
    try:
        magnitude = np.asarray(magnitude, dtype=float)
    except (TypeError, ValueError):
        raise UnitError(f"{name}: {value!r} is not a number") from None
    if not allow_nonfinite and not np.all(np.isfinite(magnitude)):
        shown = f"{value:~P}" if isinstance(value, pint.Quantity) else repr(value)
        raise UnitError(f"{name}: value must be finite, got {shown}")
    return float(magnitude) if magnitude.ndim == 0 else magnitude


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
                key: (to_si(val, units[key], key) if key in units and val is not None else val)
                for key, val in bound.arguments.items()
            }
            return _attach(kernel(**si), returns)

        wrapper.kernel = kernel
        wrapper.__doc__ = (
            f"Unit-aware form of :func:`{kernel.__module__}.{kernel.__name__}`: arguments are pint quantities or "
            f"strings, results are quantities.\n\n" + (kernel.__doc__ or "")
        )
        return wrapper

    return decorate


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
