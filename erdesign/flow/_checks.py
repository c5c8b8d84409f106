"""Argument checks of the flow kernels: a value outside the domain of the formula is an error naming the argument.

The kernels are vectorised and called in tight loops (design search, fitting), so the check is one comparison per
argument; NaN passes (the caller's business), a negative or zero gap does not (it used to end in a bare
ZeroDivisionError, or a silently dropped yield stress).
"""

from __future__ import annotations

import numpy as np

from .._util import broadcast_named
from ..errors import ErdesignError

__all__ = ["check_flow_args"]

_POSITIVE = ("eta", "L", "d", "h", "Dp", "K", "m")
_NONNEGATIVE = ("tau_y", "dr")


# Python and numpy floats, and None: checked by plain comparisons, the same rules as arrays at a tenth of the cost (a
# geometry's piston area alone is asked for thousands of times in one diagnosis); anything else (ints, which may not
# fit a float, subclasses, arrays) takes the general path
_PLAIN = frozenset({float, np.float64, type(None)})


def _check_plain(annulus: bool, values: dict) -> None:
    """:func:`check_flow_args` for scalars (:data:`_PLAIN`): the same errors with the same messages."""
    for name, value in values.items():
        if value is None:
            continue
        if name in _POSITIVE and value <= 0.0:
            raise ErdesignError(f"{name}: must be positive, got {float(value):g} (SI)")
        if name in _NONNEGATIVE and value < 0.0:
            raise ErdesignError(f"{name}: must not be negative, got {float(value):g} (SI)")
    h, d = values.get("h"), values.get("d")
    if h is not None and d is not None and (h >= d if annulus else h > d):
        raise ErdesignError(
            f"h: the gap ({float(h):g} m) must be smaller than the mean diameter d of the annulus ({float(d):g} m); is "
            "the gap's unit right?"
        )


def _first(arr: np.ndarray, bad: np.ndarray) -> float:
    return float(arr[bad][0] if arr.ndim else arr)


def check_flow_args(*, annulus: bool = False, **values) -> None:
    """Raise :class:`~erdesign.errors.ErdesignError` naming the first argument outside its domain: ``eta``, ``L``,
    ``d``, ``h``, ``Dp``, ``K``, ``m`` positive; ``tau_y``, ``dr`` not negative; any other (a flow rate ``Q``, a
    pressure drop ``dp``, a velocity) numbers of any sign; array arguments of shapes that do not broadcast together
    named in pairs (the flow arrays too: a kernel given Q of 3 flows and tau_y of 4 names them, not numpy); ``h <= d``
    (the slit formulas are also used in dimensionless form, with h = d = 1), and ``h < d`` for an ``annulus``."""
    if all(type(value) in _PLAIN for value in values.values()):
        _check_plain(annulus, values)
        return
    arrays = {}
    for name, value in values.items():
        if type(value) in _PLAIN:  # a float among arrays: compared as such (None passes)
            if value is not None and (value <= 0.0 if name in _POSITIVE else name in _NONNEGATIVE and value < 0.0):
                _check_plain(annulus, {name: value})  # raises its message
            continue
        try:
            arr = np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            raise ErdesignError(f"{name}: expected a number or an array of numbers (SI), got {value!r}") from None
        if arr.ndim:
            arrays[name] = value
        if name in _POSITIVE:
            bad = arr <= 0.0
            if bad.any():
                raise ErdesignError(f"{name}: must be positive, got {_first(arr, bad):g} (SI)")
        elif name in _NONNEGATIVE:
            bad = arr < 0.0
            if bad.any():
                raise ErdesignError(f"{name}: must not be negative, got {_first(arr, bad):g} (SI)")
    if len(arrays) > 1:
        broadcast_named(**arrays)
    if values.get("h") is not None and values.get("d") is not None:
        h, d = np.asarray(values["h"], dtype=float), np.asarray(values["d"], dtype=float)
        # a gap wider than the annulus's mean diameter leaves its inner wall a negative diameter: the thin-gap formulas
        # gave a pressure drop for it without a word (h = d is the slit formulas' dimensionless form)
        bad = h >= d if annulus else h > d
        if np.any(bad):
            i = np.flatnonzero(np.broadcast_to(bad, np.broadcast_shapes(h.shape, d.shape)).ravel())[0]
            hv, dv = np.broadcast_to(h, bad.shape).ravel()[i], np.broadcast_to(d, bad.shape).ravel()[i]
            raise ErdesignError(
                f"h: the gap ({hv:g} m) must be smaller than the mean diameter d of the annulus ({dv:g} m); is the "
                "gap's unit right?"
            )
