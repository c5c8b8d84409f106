r"""A model with a parameter set on a generated motion (no measurement): force, energy per cycle, C_eqv and the
energy per unit active fluid volume.

``erdesign simulate --model NAME --params P --motion "sine 10 mm 2 Hz"`` runs here.  The motion is a sine
(:func:`erdesign.simulation.rig.sine`) written ``"sine AMPLITUDE FREQUENCY [N cycles]"`` with units; the model starts
from rest, so the figures are taken over the last whole cycle:

.. math::
    U = \oint F\,dx, \qquad C_{eqv} = \frac{U}{\pi\,\Omega\,X_0^2}, \qquad u = \frac{U}{V_a}

(Kamath and Wereley 1997, eqs 1-2 and Fig 6: the dissipated energy per unit active fluid volume V_a, the fluid
between the electrodes, pi d h L per duct).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from ..data.measurement import Measurement
from ..data.metrics import energy_per_cycle, equivalent_damping
from ..errors import ErdesignError
from ..models.base import Model
from .rig import Motion, sine

__all__ = ["parse_motion", "SineMotion", "MotionRun", "run_on_motion", "SAMPLES_PER_CYCLE"]

#: Samples per cycle of a generated sine (the energy integral's error is ~1e-4 at 400).
SAMPLES_PER_CYCLE = 400
_SINE = re.compile(
    r"^\s*sine\s+(?P<amp>.+?\S)\s+(?P<freq>[-+0-9.eE]+\s*\S*Hz)"
    r"(?:\s+(?P<cycles>[0-9.]+)\s*cycles?)?\s*$",
    re.IGNORECASE,
)


@dataclass(frozen=True)
class SineMotion:
    """A generated sine: the motion, its amplitude X0 [m] and frequency f [Hz]."""

    motion: Motion
    amplitude: float
    frequency: float


def parse_motion(text: str, field: float = 0.0, control_unit: str | None = None) -> SineMotion:
    """The motion of ``"sine 10 mm 2 Hz"`` (optionally ``"... 5 cycles"``, default 3) at the constant control
    ``field`` [SI] (described in ``control_unit``), sampled at :data:`SAMPLES_PER_CYCLE` per cycle.

    >>> m = parse_motion("sine 10 mm 2 Hz")
    >>> m.amplitude, m.frequency, round(float(m.motion.time[-1]), 3)
    (0.01, 2.0, 1.5)
    """
    from ..units import to_si

    match = _SINE.match(str(text))
    if match is None:
        raise ErdesignError(
            f'motion: expected "sine AMPLITUDE FREQUENCY [N cycles]" with units, e.g. "sine 10 mm 2 Hz", got {text!r}'
        )
    amplitude = float(to_si(match["amp"], "m", "motion amplitude"))
    frequency = float(to_si(match["freq"], "Hz", "motion frequency"))
    cycles = float(match["cycles"]) if match["cycles"] else 3.0
    if not (cycles >= 1 and cycles == int(cycles) and cycles <= 1000):
        raise ErdesignError(f"motion: the number of cycles must be a whole number from 1 to 1000, got {cycles:g}")
    motion = sine(
        amplitude, frequency, field, cycles=cycles, rate=SAMPLES_PER_CYCLE * frequency, control_unit=control_unit
    )
    return SineMotion(motion, amplitude, frequency)


@dataclass
class MotionRun:
    """The record of the generated motion with the model's force, and the figures of its last whole cycle: energy
    per cycle U [J], C_eqv [N s/m], and U per unit active fluid volume [J/m^3] (None when the volume is unknown)."""

    record: Measurement
    amplitude: float
    frequency: float
    energy_per_cycle: float
    equivalent_damping: float
    active_volume: float | None
    energy_per_active_volume: float | None
    peak_force: float


def run_on_motion(
    model: Model,
    values,
    sine_motion: SineMotion,
    *,
    control_kind: str | None = None,
    active_volume: float | None = None,
) -> MotionRun:
    """Run ``model`` with SI ``values`` on the generated sine (from rest) and compute the figures of its last
    cycle; ``active_volume`` [m^3] (the physics damper's is its geometry's) gives the energy per unit active fluid
    volume.

    Examples
    --------
    >>> from erdesign.models.registry import get_model
    >>> run = run_on_motion(get_model("bingham"), {"c0": 1000.0, "f_c": 0.0}, parse_motion("sine 10 mm 1 Hz"))
    >>> round(run.equivalent_damping)        # a dashpot: C_eqv = c0 (Kamath and Wereley 1997, eq 2)
    1000
    """
    motion = sine_motion.motion
    record = motion.record(control_kind, velocity_noise=0.0)
    force = model.simulate(record, values)
    if not np.all(np.isfinite(force)):
        raise ErdesignError(f"{model.name}: the parameters give non-finite forces on {motion.description}")
    X0, f = sine_motion.amplitude, sine_motion.frequency
    last = motion.time >= motion.time[-1] - 1.0 / f - 1e-12
    U = energy_per_cycle(motion.time[last], motion.displacement[last], force[last], frequency=f)
    Ceq = equivalent_damping(U, 2 * np.pi * f, X0)
    if active_volume is not None and not (np.isfinite(active_volume) and active_volume > 0):
        raise ErdesignError(f"active_volume: must be a positive volume, got {active_volume!r} m^3")
    per_volume = None if active_volume is None else U / active_volume
    return MotionRun(
        record.with_force(force), X0, f, float(U), float(Ceq), active_volume, per_volume, float(np.max(np.abs(force)))
    )
