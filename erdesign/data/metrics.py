r"""Figures of merit computed from a force record: energy per cycle, equivalent damping, ESR.

Energy dissipated per cycle (Kamath and Wereley 1997, Kamath and Wereley, eq 1) and equivalent viscous damping (eq 2):

.. math::
    U = \oint F\,dx = \int_0^{2\pi/\Omega} F v\,dt, \qquad C_\text{eqv} = \frac{U}{\pi \Omega X_0^2}

Equivalent-error measure ESR (Vivas-López et al. (n.d.), eq 7; docs/file_formats.md, ESR):

.. math:: \mathrm{ESR} = \frac{\sum (F - F_\text{model})^2}{\sum (F - \bar F)^2}
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy import trapezoid

from .._util import broadcast_named, scalar_or_array, si_array
from ..errors import ErdesignError

__all__ = ["energy_per_cycle", "equivalent_damping", "esr", "objective_j", "difference_signal", "loops", "Loops"]


def energy_per_cycle(t, x, F, frequency):
    r"""Energy dissipated per cycle, the area of the force-displacement loop averaged over the record, [J].

    .. math:: U = \frac{1}{N_c}\oint F\,dx, \qquad N_c = f\,(t_\text{end} - t_0)

    Parameters
    ----------
    t : array
        Time, [s]; the record should span a whole number of cycles.
    x : array
        Displacement, [m].
    F : array
        Force the damper resists with (same sign as the velocity when dissipating), [N].
    frequency : float
        Excitation frequency f, [Hz].

    Returns
    -------
    float
        U, [J].

    Notes
    -----
    Trapezoidal integration of F dx, which for a sampled sine converges as the square of the step.

    Examples
    --------
    A linear dashpot F = C v dissipates pi C Omega X0^2 per cycle:

    >>> import numpy as np
    >>> t = np.linspace(0, 1, 4001); x = 0.01 * np.sin(2 * np.pi * t); F = 1000 * np.gradient(x, t, edge_order=2)
    >>> round(energy_per_cycle(t, x, F, frequency=1.0) / (np.pi * 1000 * 2 * np.pi * 0.01**2), 5)
    1.0

    References
    ----------
    Kamath and Wereley (1997), eq 1.
    """
    # texts, quantities and NaN were read by numpy (or "can't multiply sequence by non-int" for frequency="1 Hz")
    t, x, F = (si_array(a, name) for a, name in ((t, "t"), (x, "x"), (F, "F")))
    if not (t.shape == x.shape == F.shape and t.ndim == 1 and t.size >= 3):
        raise ErdesignError("energy_per_cycle: t, x and F must be 1-D arrays of the same length (at least 3)")
    frequency = si_array(frequency, "frequency")
    if frequency.ndim or not frequency > 0:
        raise ErdesignError(f"frequency: expected one positive frequency [Hz], got {frequency}")
    n_cycles = float(frequency) * (t[-1] - t[0])
    if n_cycles <= 0:
        raise ErdesignError("energy_per_cycle: the record must span a positive time")
    return float(trapezoid(F, x) / n_cycles)


def equivalent_damping(energy, omega, amplitude):
    r"""Equivalent viscous damping constant of a cycle, C_eqv = U / (pi Omega X0^2), [N s/m].

    Parameters
    ----------
    energy : float
        Energy per cycle U, [J].
    omega : float
        Angular frequency Omega, [rad/s].
    amplitude : float
        Displacement amplitude X0, [m].

    Arguments are SI numbers or arrays (of shapes that broadcast); text, quantities, NaN, a frequency or amplitude
    that is not positive are an :class:`~erdesign.errors.ErdesignError` naming the argument (``"1 J"`` was a raw
    ``TypeError``, a zero frequency an infinite constant).

    >>> round(equivalent_damping(2.0, 2 * math.pi, 0.01), 3)
    1013.212

    References
    ----------
    Kamath and Wereley (1997), eq 2.
    """
    U, w, X = si_array(energy, "energy"), si_array(omega, "omega"), si_array(amplitude, "amplitude")
    for arr, name in ((w, "omega"), (X, "amplitude")):
        if not np.all(arr > 0):
            raise ErdesignError(f"{name}: must be positive, got {float(np.min(arr)):g} (SI)")
    broadcast_named(energy=U, omega=w, amplitude=X)
    return scalar_or_array(U / (math.pi * w * X**2))


def esr(F_measured, F_model):
    """Equivalent-error ratio: residual sum of squares over the variance sum of the measurement, [-].

    0 is a perfect fit, 1 predicts no better than the mean (Vivas-López et al. (n.d.), eq 7).

    >>> esr([1.0, 2.0, 3.0], [1.0, 2.0, 3.0]), esr([1.0, 2.0, 3.0], [2.0, 2.0, 2.0])
    (0.0, 1.0)
    """
    F, M = si_array(F_measured, "F_measured"), si_array(F_model, "F_model")
    if F.shape != M.shape:
        raise ErdesignError(
            f"F_measured and F_model: {F.size} and {M.size} samples (shapes {F.shape} and "
            f"{M.shape}); give one model force per measured force"
        )
    if F.size < 2:
        raise ErdesignError(f"F_measured: {F.size} sample{'s' if F.size != 1 else ''}; the ESR needs at least 2")
    scale = float(np.max(np.abs(F)))
    if scale > 0:  # the ratio is scale-free: scaled, sums of squares of huge forces stay finite
        F, M = F / scale, M / scale
    spread = np.sum((F - F.mean()) ** 2)
    if spread == 0:
        raise ErdesignError("esr: the measured force is constant, so the ESR is undefined")
    return float(np.sum((F - M) ** 2) / spread)


def objective_j(F_measured, F_model):
    r"""Identification objective of Kamath and Wereley, the sum of squared force errors, [N^2].

    .. math:: J = \sum_{i=1}^{N} (F_i - F_{m,i})^2

    >>> objective_j([1.0, 2.0], [1.5, 2.0])
    0.25

    References
    ----------
    Kamath and Wereley (1997), eq 13.
    """
    F = np.asarray(F_measured, dtype=float)
    M = np.asarray(F_model, dtype=float)
    return float(np.sum((F - M) ** 2))


def difference_signal(F_measured, F_model):
    """Peak value and root mean square of the difference signal F - F_model, [N] (Makris's PV and RMS).

    >>> difference_signal([0.0, 3.0, -4.0], [0.0, 0.0, 0.0])
    (4.0, 2.886751345948129)

    References
    ----------
    Makris et al. (1996), section 4.1: Maxwell PV = 257 lb, RMS = 56 lb; BingMax PV = 109 lb, RMS = 31 lb.
    """
    d = np.asarray(F_measured, dtype=float) - np.asarray(F_model, dtype=float)
    return float(np.max(np.abs(d))), float(np.sqrt(np.mean(d**2)))


class Loops(NamedTuple):
    """Force-displacement and force-velocity loops as plain arrays, for plots (SI)."""

    displacement: np.ndarray
    velocity: np.ndarray
    force_measured: np.ndarray | None
    force_model: np.ndarray | None


def loops(record, force_model=None, *, last_cycles: float | None = None, frequency: float | None = None) -> Loops:
    """The loops of a record (and a model's force on it), optionally only the last ``last_cycles`` cycles of
    the excitation at ``frequency`` [Hz].

    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 201); r = Measurement.from_arrays(t, np.sin(2 * np.pi * t), np.cos(2 * np.pi * t))
    >>> len(loops(r, last_cycles=1, frequency=1.0).displacement)
    101
    """
    keep = slice(None)
    if last_cycles is not None:
        if not frequency or frequency <= 0:
            raise ErdesignError("loops: last_cycles needs the excitation frequency [Hz]")
        keep = record.time >= record.time[-1] - last_cycles / frequency - 1e-12

    def pick(a):
        return None if a is None else np.asarray(a, dtype=float)[keep]

    return Loops(record.displacement[keep], record.velocity[keep], pick(record.force), pick(force_model))
