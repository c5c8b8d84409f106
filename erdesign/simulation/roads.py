r"""Road inputs of the quarter vehicle: a step, a (1 - cos) bump and a random road of an ISO 8608 class.

A road is a :class:`Road`: the profile u0(t) [m] and its rate du0/dt [m/s] as vectorised functions of time, plus the
impulse of a step (the tyre damper C du0/dt of a step is a Dirac pulse, applied as a jump of the axle velocity).
The registry :data:`ROADS` maps the names of ``erdesign vehicle --road`` to their constructors.

The random road follows ISO 8608 (2016): the displacement power spectral density of a road of class k is

.. math:: G_d(n) = G_d(n_0)\,(n / n_0)^{-w}, \qquad n_0 = 0.1\ \text{cycles/m},\ w = 2,

with :math:`G_d(n_0) = 16\cdot 4^{k-1}\times 10^{-6}\ \text{m}^3` for classes A (k = 1) to H (k = 8), the geometric
means of the class bands.  The profile is a sum of cosines with random phases over the spatial frequencies
0.011-2.83 cycles/m that ISO 8608 covers, driven at a constant speed V (u0(t) = z(V t)).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import warnings

import numpy as np

from ..errors import ErdesignError, PlausibilityWarning

__all__ = ["Road", "step_road", "bump_road", "iso8608_road", "iso8608_psd", "ISO8608_CLASSES", "ROADS", "make_road"]

#: Largest plausible road input: a step or bump height [m] and a vehicle speed [m/s] (250 km/h); beyond them a
#: warning asks whether the value or its unit is meant.
PLAUSIBLE_HEIGHT = 0.3
PLAUSIBLE_SPEED = 70.0

#: ISO 8608 road classes -> G_d(n0) [m^3] at n0 = 0.1 cycles/m (geometric mean of the class band).
ISO8608_CLASSES = {c: 16e-6 * 4.0**i for i, c in enumerate("ABCDEFGH")}
ISO8608_N0 = 0.1
ISO8608_BAND = (0.011, 2.83)


@dataclass(frozen=True)
class Road:
    """A road input: profile u0(t) [m], rate du0/dt(t) [m/s] (vectorised), and the height of a step at t = 0 [m]
    whose tyre-damper impulse the vehicle applies as a jump of the axle velocity."""

    name: str
    profile: Callable[[np.ndarray], np.ndarray]
    rate: Callable[[np.ndarray], np.ndarray]
    step: float = 0.0
    description: str = ""
    settles_to: float | None = field(default=None)
    """Final road level for a transient input (step, bump): the level the body returns to, [m]; None for a random
    road."""


def step_road(height: float = 0.1) -> Road:
    """Road step of ``height`` [m] at t = 0 (Butz and von Stryk 2002, section 4.4: 0.1 m)."""
    _positive(height, "height", allow_zero=False, signed=True)
    _plausible(abs(height), PLAUSIBLE_HEIGHT, "height", "m", "road step")
    return Road(
        "step",
        lambda t: np.full(np.shape(t), float(height)),
        lambda t: np.zeros(np.shape(t)),
        step=float(height),
        description=f"step of {height:g} m at t = 0",
        settles_to=float(height),
    )


def bump_road(height: float = 0.1, duration: float = 0.5, start: float = 0.0) -> Road:
    """Sinusoidal (1 - cos) bump of ``height`` [m] lasting ``duration`` [s] from ``start`` [s].

    Butz and von Stryk (2002) section 4.5 and Figure 25 show a bump of 0.1 m; its duration is not printed: 0.5 s is
    this project's assumption (a 10 m long bump at 72 km/h)."""
    _positive(height, "height", allow_zero=False, signed=True)
    _positive(duration, "duration", allow_zero=False)
    _plausible(abs(height), PLAUSIBLE_HEIGHT, "height", "m", "bump")
    w = 2 * np.pi / duration

    def inside(t):
        t = np.asarray(t, dtype=float)
        return (t >= start) & (t <= start + duration), t

    def profile(t):
        on, t = inside(t)
        return np.where(on, 0.5 * height * (1 - np.cos(w * (t - start))), 0.0)

    def rate(t):
        on, t = inside(t)
        return np.where(on, 0.5 * height * w * np.sin(w * (t - start)), 0.0)

    return Road(
        "bump", profile, rate, description=f"(1 - cos) bump of {height:g} m over {duration:g} s", settles_to=0.0
    )


def iso8608_psd(n, road_class: str) -> np.ndarray:
    """Displacement PSD G_d(n) [m^3] of an ISO 8608 road class at spatial frequencies ``n`` [cycles/m]."""
    return _class_value(road_class) * (np.asarray(n, dtype=float) / ISO8608_N0) ** -2.0


def iso8608_road(road_class: str = "C", speed: float = 20.0, *, seed: int = 0, components: int = 400) -> Road:
    r"""Random road of ISO 8608 class ``road_class`` (A-H) driven at ``speed`` [m/s].

    .. math:: u_0(t) = \sum_k A_k \cos(2\pi n_k V t + \varphi_k), \qquad A_k = \sqrt{2\,G_d(n_k)\,\Delta n_k}

    with ``components`` log-spaced spatial frequencies n_k over 0.011-2.83 cycles/m and phases uniform in
    [0, 2 pi) from ``seed``.  The variance of the profile is :math:`\sum_k G_d(n_k)\Delta n_k`, which tends to
    :math:`G_d(n_0)\,n_0^2\,(1/n_1 - 1/n_2)` (tests/test_vehicle.py checks both).
    """
    gd0 = _class_value(road_class)
    _positive(speed, "speed", allow_zero=False)
    _plausible(speed, PLAUSIBLE_SPEED, "speed", "m/s", "road vehicle")
    if int(components) < 10:
        raise ErdesignError(f"components: at least 10 cosines, got {components!r}")
    edges = np.geomspace(*ISO8608_BAND, int(components) + 1)
    n = np.sqrt(edges[:-1] * edges[1:])
    amplitude = np.sqrt(2 * gd0 * (n / ISO8608_N0) ** -2.0 * np.diff(edges))
    phase = np.random.default_rng(seed).uniform(0, 2 * np.pi, n.size)
    omega = 2 * np.pi * n * speed

    def profile(t):
        t = np.asarray(t, dtype=float)
        return np.cos(np.multiply.outer(t, omega) + phase) @ amplitude

    def rate(t):
        t = np.asarray(t, dtype=float)
        return -np.sin(np.multiply.outer(t, omega) + phase) @ (amplitude * omega)

    return Road(
        "random", profile, rate, description=f"ISO 8608 class {road_class.upper()} road at {speed:g} m/s (seed {seed})"
    )


def _class_value(road_class: str) -> float:
    key = str(road_class).strip().upper()
    if key not in ISO8608_CLASSES:
        raise ErdesignError(f"road_class: ISO 8608 classes are A to H, got {road_class!r}")
    return ISO8608_CLASSES[key]


def _plausible(value, limit, name, unit, what):
    if value > limit:
        warnings.warn(
            f"{name}: {value:g} {unit} is beyond any plausible {what} ({limit:g} {unit}); check the value and its unit",
            PlausibilityWarning,
            stacklevel=3,
        )


def _positive(value, name, *, allow_zero=True, signed=False):
    v = float(value)
    bad = not np.isfinite(v) or (not signed and v < 0) or (not allow_zero and v == 0)
    if bad:
        raise ErdesignError(f"{name}: must be a finite {'non-zero' if signed else 'positive'} number, got {value!r}")


#: ``erdesign vehicle --road`` names -> constructors.
ROADS: dict[str, Callable[..., Road]] = {"step": step_road, "bump": bump_road, "random": iso8608_road}


def make_road(name: str, **options) -> Road:
    """The road ``name`` (a key of :data:`ROADS`) with its options (``height``, ``duration``, ``road_class``,
    ``speed``, ``seed``)."""
    try:
        factory = ROADS[name]
    except KeyError:
        raise ErdesignError(f"road: expected one of {', '.join(ROADS)}, got {name!r}") from None
    try:
        return factory(**options)
    except TypeError as exc:
        raise ErdesignError(f"road {name}: {exc}") from None
