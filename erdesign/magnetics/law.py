r"""The yield stress against coil current through the magnetic circuit: one field law for every consumer.

A damper file with a ``[coil]`` (docs/file_formats.md, [coil]) is controlled by the coil current.  Its fluid
follows :class:`CoilLaw`, a :class:`~erdesign.fluid.field_laws.FieldLaw` whose control is the current in A:

.. math:: \tau_y(I) = \tau_y^\text{fluid}\big(H_g(I)\big)

with :math:`H_g(I)` the gap field of the nonlinear reluctance network (:mod:`erdesign.magnetics.circuit`) and
:math:`\tau_y^\text{fluid}(H)` the fluid's published yield curve against field strength.  ``size``, ``simulate``,
``diagnose``, ``fit``, the physics model, the report and the app all read the yield stress through
:attr:`erdesign.fluid.Fluid.yield_law`, so they all take the current through the circuit without a branch of
their own.

The network is a root find per current; a record of 60 000 samples evaluated a few thousand times in a fit cannot
afford one per sample.  :math:`H_g(I)` is therefore tabulated once on :data:`TABLE_POINTS` currents from 0 to the
top of the law's range and interpolated by the monotone cubic of Fritsch and Carlson
(:class:`scipy.interpolate.PchipInterpolator`); :math:`H_g(I)` is smooth and monotone (linear below the knee,
bending over as the steel saturates), so interpolating the gain :math:`H_g/I` (finite at zero current) keeps the relative error below
3e-5 on the default grid
(tests/test_magnetics.py checks it against the network).  Above the table the network is solved exactly.  The
fluid's yield curve is evaluated exactly at the interpolated field.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
from scipy.interpolate import PchipInterpolator

from .._util import scalar_or_array
from ..errors import ErdesignError
from ..fluid.field_laws import FieldLaw
from .coil import current_rise_time

__all__ = ["CoilLaw", "coil_law", "TABLE_POINTS"]

#: Currents on which the gap field is tabulated (evenly spaced from 0 to the top of the law's range).
TABLE_POINTS = 601


@dataclass(frozen=True)
class CoilLaw(FieldLaw):
    """tau_y(I) [Pa] through a magnetic circuit; control in A.  Build it with :func:`coil_law`.

    >>> from erdesign.damper.files import load_example
    >>> law = load_example("mr_coil").fluid.yield_law
    >>> type(law).__name__, round(float(law.gap_flux_density(2.0)), 3), round(float(law.yield_stress(2.0)))
    ('CoilLaw', 0.524, 27208)
    """

    currents: tuple[float, ...] = ()
    """Currents of the table, [A], first 0, strictly increasing."""
    gap_fields: tuple[float, ...] = ()
    """Gap field H_g at each current, [A/m]."""
    fluid_law: FieldLaw | None = None
    """The fluid's yield stress against field strength (control A/m)."""
    circuit: Any = field(default=None, compare=False, repr=False)
    """The :class:`~erdesign.magnetics.circuit.MagneticCircuit` (solved exactly above the table)."""
    small_current_gain: float = 0.0
    """lim H_g / I at I -> 0, [1/m]."""
    rated_current: float = 0.0
    """The damper's rated current (its ``reference_field``), [A]; the coil figures are quoted there."""
    supply_voltage: float | None = None
    """Voltage the coil's driver can apply, [V] (None: driven at the steady voltage I R)."""

    law: ClassVar[str] = "coil"
    equation: ClassVar[str] = r"\tau_y = \tau_y^\text{fluid}\left(H_g(I)\right)"
    equation_text: ClassVar[str] = "τ_y = τ_y,fluid(H_g(I)), H_g from the reluctance network"
    reference: ClassVar[str] = (
        "Gavin, Hoagg and Dobossy, Optimal design of MR dampers (2001): reluctance network "
        "of the piston head with nonlinear B-H curves; docs/magnetics.md"
    )

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.control_unit != "A":
            raise ErdesignError(f"coil law: the control is the coil current (A), got {self.control_unit}")
        I = np.asarray(self.currents, dtype=float)
        H = np.asarray(self.gap_fields, dtype=float)
        if not (
            I.ndim == 1
            and I.size >= 2
            and I.shape == H.shape
            and I[0] == 0
            and np.all(np.diff(I) > 0)
            and np.all(np.diff(H) >= 0)
            and np.all(np.isfinite(H))
        ):
            raise ErdesignError("coil law: needs increasing currents from 0 and non-decreasing gap fields")
        if self.fluid_law is None or self.fluid_law.control_unit != "A/m":
            raise ErdesignError("coil law: the fluid's yield curve must be against field strength (A/m)")

    @functools.cached_property
    def _interpolant(self) -> PchipInterpolator:
        # the gain H_g / I, smooth and finite at I = 0 (its limit there is the slope of the linear circuit), so
        # that the relative error stays small at small currents too
        I = np.asarray(self.currents)
        H = np.asarray(self.gap_fields)
        gain = np.empty_like(H)
        gain[1:] = H[1:] / I[1:]
        gain[0] = self.small_current_gain
        return PchipInterpolator(I, gain, extrapolate=False)

    @property
    def max_current(self) -> float:
        """Top of the table, [A]."""
        return float(self.currents[-1])

    def gap_field(self, current):
        """Gap field H_g [A/m] at coil current(s) I [A] (even in I)."""
        I = np.abs(np.asarray(current, dtype=float))
        H = I * np.asarray(self._interpolant(np.minimum(I, self.max_current)), dtype=float)
        above = I > self.max_current
        if np.any(above):
            if self.circuit is None:
                raise ErdesignError(
                    f"coil law: current {float(np.max(I)):.4g} A above the table "
                    f"({self.max_current:.4g} A) and no circuit to solve"
                )
            H = np.where(above, 0.0, H)
            H[above] = self.circuit.solve_gap_field(I[above])
        return scalar_or_array(H)

    def gap_flux_density(self, current):
        """Gap flux density B_g [T] at coil current(s) I [A], through the fluid's B-H curve."""
        if self.circuit is None:
            raise ErdesignError("coil law: no circuit (the fluid's B-H curve) to give the flux density")
        return scalar_or_array(self.circuit.fluid.B_of_H(np.asarray(self.gap_field(current), dtype=float)))

    def yield_stress(self, E):
        return scalar_or_array(
            np.asarray(self.fluid_law.yield_stress(np.asarray(self.gap_field(E), dtype=float)), dtype=float)
        )

    def time_constant(self, current: float | None = None) -> float:
        """The coil's L/R [s] at ``current`` (default the rated current), secant inductance."""
        I = self.rated_current if current is None else float(current)
        return float(self.circuit.time_constant(I)[0])

    def response_time(self) -> float:
        """Time for the coil current to reach 63 % of the rated current after a step command, [s]: L/R without a
        driver, shorter with a driver that forces it with its supply voltage (:func:`~erdesign.magnetics.coil.
        current_rise_time`).  The prior of the ``field_lag`` effect of a damper with a ``[coil]``."""
        return self._response_time

    @functools.cached_property
    def _response_time(self) -> float:
        I = self.rated_current
        L = float(self.circuit.inductance(I)[0])
        return current_rise_time(L, self.circuit.resistance, I, self.supply_voltage)

    def describe(self, field_unit: str | None = None) -> str:
        name = getattr(self.circuit, "name", "") or "coil"
        return (
            f"through the magnetic circuit ({name}): tau_y(H_g(I)), H_g tabulated on {len(self.currents)} "
            f"currents up to {self._show(self.max_current, field_unit)}, fluid "
            f"{self.fluid_law.describe('kA/m')}"
        )


def coil_law(
    circuit,
    max_current: float,
    rated_current: float | None = None,
    *,
    supply_voltage: float | None = None,
    points: int = TABLE_POINTS,
) -> CoilLaw:
    """The :class:`CoilLaw` of a circuit, tabulated on ``points`` currents over [0, ``max_current``] [A]."""
    if not max_current > 0:
        raise ErdesignError(f"coil law: max_current must be positive, got {max_current!r}")
    I = np.linspace(0.0, float(max_current), int(points))
    H = np.maximum.accumulate(np.abs(circuit.solve_gap_field(I)))
    tiny = 1e-6 * float(max_current)
    gain0 = float(circuit.solve_gap_field(np.array([tiny]))[0]) / tiny
    return CoilLaw(
        "A",
        currents=tuple(I.tolist()),
        gap_fields=tuple(H.tolist()),
        fluid_law=circuit.yield_law,
        small_current_gain=gain0,
        circuit=circuit,
        rated_current=float(max_current if rated_current is None else rated_current),
        supply_voltage=supply_voltage,
    )
