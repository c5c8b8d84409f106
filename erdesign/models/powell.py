r"""Powell's three-element model: viscous damper, softening spring and a smoothed static / dynamic friction."""

from __future__ import annotations

import numpy as np

from .base import FORCE_OFFSET, Model, Parameter

__all__ = ["Powell"]


class Powell(Model):
    r"""Powell's three-element model (Butz and von Stryk 2002, eqs 4-5).

    .. math::
        F = f_c + k\tanh(d z) + c\dot z, \qquad
        f_c = \begin{cases} (f_{cs} + f_{cd}e^{-a|\dot z|})\tanh(e\dot z) & \dot z\ddot z \ge 0\\
                            f_{cd}(1 - e^{-b|\dot z|})\tanh(e\dot z) & \dot z\ddot z < 0 \end{cases}

    Parameters (SI): ``f_cs``, ``f_cd``, ``k``, ``f0`` [N], ``a``, ``b``, ``e`` [s/m], ``c`` [N s/m], ``d`` [1/m].

    Notes
    -----
    :math:`f_{cs}(1 + (f_{cd}/f_{cs})e^{-a|\dot z|}) = f_{cs} + f_{cd}e^{-a|\dot z|}` as printed.  Memoryless given the
    measured velocity and acceleration; the switch on the sign of :math:`\dot z\ddot z` makes the force jump where the
    motion turns from speeding up to slowing down, as in the source.  The offset f0 is added.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 401); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> bool(np.all(np.isfinite(Powell().simulate(rec))))
    True

    References
    ----------
    Butz and von Stryk (2002) eqs 4-5 (Powell 1994).
    """

    name = "powell"
    title = "three-element model (Powell)"
    source = "Butz and von Stryk (2002) eqs 4-5"
    memoryless = True
    linear_parameters = ("f_cs", "f_cd", "k", "c", "f0")
    parameters = (
        Parameter("f_cs", "N", 400.0, 0.0, 1e7, "static friction"),
        Parameter("f_cd", "N", 300.0, 0.0, 1e7, "dynamic friction"),
        Parameter("a", "s/m", 50.0, 0.0, 1e6, "decay of the static friction with speed"),
        Parameter("b", "s/m", 50.0, 0.0, 1e6, "rise of the dynamic friction with speed"),
        Parameter("e", "s/m", 500.0, 0.0, 1e7, "smoothing of the sign function"),
        Parameter("c", "N*s/m", 2000.0, 0.0, 1e8, "viscous damping"),
        Parameter("k", "N", 0.0, -1e7, 1e7, "force of the softening spring"),
        Parameter("d", "1/m", 100.0, 0.0, 1e6, "softening of the spring"),
        FORCE_OFFSET,
    )

    def force(self, record, values):
        v, a, z = record.velocity, record.acceleration, record.displacement
        sm = np.tanh(values["e"] * v)
        speeding = v * a >= 0
        fc = np.where(
            speeding,
            (values["f_cs"] + values["f_cd"] * np.exp(-values["a"] * np.abs(v))) * sm,
            values["f_cd"] * (1.0 - np.exp(-values["b"] * np.abs(v))) * sm,
        )
        return fc + values["k"] * np.tanh(values["d"] * z) + values["c"] * v + values["f0"]
