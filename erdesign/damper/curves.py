"""The force-velocity curves of a damper over controls, and its sine loops: the numbers behind the report's tables
and figures and the app's Size page.

They call the damper (:meth:`erdesign.Damper.state`, :meth:`erdesign.Damper.sine_response`) and hold SI arrays;
they add no physics.  The figures of :mod:`erdesign.report.plots` and the Streamlit app take them as they are.
(:func:`force_velocity_curves` was ``erdesign.report.sweep.velocity_sweep``, a deprecated alias now.)
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .._deprecated import renamed
from ..errors import ValidityWarning
from ..units import Q_
from .damper import Damper, SineResponse

__all__ = ["ForceVelocityCurves", "force_velocity_curves", "SineLoops", "sine_loops"]


@dataclass(frozen=True)
class ForceVelocityCurves:
    """Quasi-steady state of a damper on a grid of controls x velocities, SI arrays of shape (fields, velocities)."""

    velocity: np.ndarray
    """Piston velocities, [m/s], shape (nv,)."""
    field: np.ndarray
    """Controls, SI unit of the fluid's control, shape (nf,)."""
    control_unit: str
    """SI unit of :attr:`field` (``"V/m"``, ``"A/m"``...)."""
    field_unit: str
    """Unit to show the controls in (the one the damper file used, ``"kV/mm"``)."""
    force: np.ndarray
    """Total force, [N], shape (nf, nv)."""
    pressure_drop: np.ndarray
    """Pressure drop across the piston, [Pa]."""
    zero_field_force: np.ndarray
    """Force at zero control, [N], shape (nv,)."""
    dynamic_range: np.ndarray
    """force / zero_field_force, [-] (NaN where the zero-field force is 0)."""
    reynolds: np.ndarray
    """Reynolds number (Makris eq 1), [-]."""
    plug_fraction: np.ndarray
    """Plug thickness over gap, [-]."""

    def field_labels(self) -> list[str]:
        """``"E = 3 kV/mm"`` for each control, in the display unit."""
        return _labels(self.field, self.control_unit, self.field_unit)


def force_velocity_curves(damper: Damper, velocity, field) -> ForceVelocityCurves:
    """The damper's quasi-steady state at every (control, velocity) pair, vectorised over both.

    Parameters
    ----------
    damper : Damper
    velocity : array
        Piston velocities, [m/s].
    field : array
        Controls, SI unit of the damper fluid's control.
    """
    v = np.asarray(velocity, dtype=float).ravel()
    E = np.asarray(field, dtype=float).ravel()
    s = damper.state(v[None, :], E[:, None])
    s0 = damper.state(v, 0.0)
    force = np.broadcast_to(s.force, (E.size, v.size))
    with np.errstate(divide="ignore", invalid="ignore"):
        dyn = np.where(s0.force != 0, force / np.where(s0.force != 0, s0.force, 1.0), np.nan)
    return ForceVelocityCurves(
        velocity=v,
        field=E,
        control_unit=damper.fluid.control_unit,
        field_unit=damper.fluid.field_unit,
        force=np.array(force),
        pressure_drop=np.broadcast_to(s.pressure_drop, force.shape).copy(),
        zero_field_force=np.asarray(s0.force, dtype=float),
        dynamic_range=dyn,
        reynolds=np.broadcast_to(s.reynolds, force.shape).copy(),
        plug_fraction=np.broadcast_to(s.plug_fraction, force.shape).copy(),
    )


#: Deprecated names of :class:`ForceVelocityCurves` and :func:`force_velocity_curves` ("sweep" also named a sample of
#: the design space and a motion).
VelocitySweep = ForceVelocityCurves
velocity_sweep = renamed(force_velocity_curves, "erdesign.report.velocity_sweep")


@dataclass(frozen=True)
class SineLoops:
    """Quasi-steady responses to one sine (amplitude, frequency) at several controls."""

    amplitude: float
    """X0, [m]."""
    frequency: float
    """f, [Hz]."""
    field: np.ndarray
    """Controls, SI unit of the control."""
    control_unit: str
    field_unit: str
    responses: tuple[SineResponse, ...]
    """One :class:`~erdesign.damper.SineResponse` per control."""

    def field_labels(self) -> list[str]:
        """``"E = 3 kV/mm"`` for each control, in the display unit."""
        return _labels(self.field, self.control_unit, self.field_unit)


def _labels(field, control_unit: str, field_unit: str) -> list[str]:
    unit = f"{Q_(1.0, field_unit).units:~P}"
    return [f"E = {Q_(E, control_unit).to(field_unit).magnitude:.4g} {unit}" for E in field]


def sine_loops(damper: Damper, amplitude: float, frequency: float, field, *, samples_per_cycle: int = 480) -> SineLoops:
    """Force-displacement and force-velocity loops of x = X0 sin(2 pi f t) at each control (SI inputs).

    480 samples per cycle: a multiple of 24, so that the report's loop table can sample the cycle at 15, 45, ...
    degrees exactly (away from the turning points, where the quasi-steady force jumps).
    """
    E = np.asarray(field, dtype=float).ravel()
    unit = damper.fluid.control_unit
    with warnings.catch_warnings():
        # The controls were range-checked by the caller; do not repeat the warning once per control here.
        warnings.filterwarnings("ignore", message=r".*is outside the range", category=ValidityWarning)
        responses = tuple(
            damper.sine_response(
                Q_(amplitude, "m"), Q_(frequency, "Hz"), Q_(float(e), unit), samples_per_cycle=samples_per_cycle
            )
            for e in E
        )
    return SineLoops(amplitude, frequency, E, unit, damper.fluid.field_unit, responses)
