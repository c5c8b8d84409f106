r"""Wereley's biviscous models: the nonlinear biviscous and the nonlinear hysteretic biviscous force-velocity laws.

Both are memoryless maps of velocity (and, for the hysteretic one, the sign of the acceleration).  Written as a
clip between the two post-yield lines :math:`C_{post}\dot x \pm F_y`, they are continuous and vectorised:

.. math::
    F = \operatorname{clip}\big(C_{pre}(\dot x - \dot x_0\operatorname{sgn}\ddot x),\;
        C_{post}\dot x - F_y,\; C_{post}\dot x + F_y\big) + f_0 .

With :math:`\dot x_0 = 0` this is the biviscous model (the MR-model review eq 60); with :math:`\dot x_0 > 0` the
hysteretic biviscous model (eq 61), whose yield velocities are :math:`\dot x_{y1,2} = (F_y \mp C_{pre}\dot x_0)
/(C_{pre} - C_{post})`.
"""

from __future__ import annotations

import numpy as np

from ._guess import force_scales, peak_speed
from .base import FORCE_OFFSET, Model, Parameter

__all__ = ["Biviscous", "BiviscousHysteretic", "biviscous_force", "ArctanHysteretic"]


def biviscous_force(v, a, C_pre, C_post, F_y, v0=0.0):
    r"""Force of the (hysteretic) biviscous model, [N].

    .. math:: F = \operatorname{clip}\big(C_{pre}(v - v_0\operatorname{sgn} a),\ C_{post}v - F_y,\ C_{post}v + F_y\big)

    Parameters
    ----------
    v : array
        Velocity, [m/s].
    a : array
        Acceleration, [m/s^2] (only its sign is used).
    C_pre, C_post : float or array
        Pre- and post-yield damping, [N s/m]; ``C_pre > C_post``.
    F_y : float or array
        Yield force, [N].
    v0 : float
        Zero-force velocity offset of the pre-yield branch, [m/s] (0: no hysteresis).

    Notes
    -----
    The MR-model review prints eq 60 with :math:`C_{post} + F_y` (the velocity factor is missing) and the velocity intervals
    of eq 61 with mixed signs; the clip form is the continuous law they describe, with the printed yield velocities.

    Examples
    --------
    >>> biviscous_force([0.001, 0.1], [0.0, 0.0], C_pre=1e6, C_post=1e4, F_y=1000.0).tolist()
    [1000.0, 2000.0]

    References
    ----------
    Review (the MR-model review) eqs 60-61 (Wereley, Pang and Kamath, 1998).
    """
    v = np.asarray(v, dtype=float)
    pre = C_pre * (v - v0 * np.sign(a))
    return np.clip(pre, C_post * v - F_y, C_post * v + F_y)


class Biviscous(Model):
    r"""Nonlinear biviscous model (Stanway; Wereley et al.): two viscous slopes, yield force F_y.

    .. math:: F = \operatorname{clip}(C_{pre}\dot x,\ C_{post}\dot x - F_y,\ C_{post}\dot x + F_y) + f_0,
              \quad F_y = F_{y,0} + F_{y,u}u

    Parameters (SI): ``C_pre``, ``C_post`` [N s/m], ``F_y``, ``F_y_u``, ``f0`` [N].

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 401); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> bool(np.all(np.abs(Biviscous().simulate(rec)) <= 1000 + 5000 * 0.0629))
    True

    References
    ----------
    Review (the MR-model review) eq 60; Butz and von Stryk (2002) eqs 26-27 (bi-viscous stress law).
    """

    name = "biviscous"
    title = "nonlinear biviscous (Wereley)"
    source = "the MR-model review eq 60; Butz and von Stryk (2002) eqs 26-27"
    uses_control = True
    memoryless = True
    control_parameters = ("F_y_u",)
    linear_parameters = ("f0",)
    parameters = (
        Parameter("C_pre", "N*s/m", 1e6, 1.0, 1e10, "pre-yield damping", log_scale=True),
        Parameter("C_post", "N*s/m", 5000.0, 0.0, 1e9, "post-yield damping"),
        Parameter("F_y", "N", 1000.0, 0.0, 1e7, "yield force"),
        FORCE_OFFSET,
        Parameter("F_y_u", "N", 0.0, -1e7, 1e7, "yield force per unit control"),
    )

    def _v0(self, values):
        return 0.0

    def force(self, record, values):
        Fy = np.maximum(values["F_y"] + values["F_y_u"] * self.control(record), 0.0)
        return (
            biviscous_force(
                record.velocity, record.acceleration, values["C_pre"], values["C_post"], Fy, self._v0(values)
            )
            + values["f0"]
        )

    def guess_from_force(self, record):
        fy, c, f0, _, vmax = force_scales(record)
        return dict(F_y=fy, C_post=c, f0=f0, C_pre=fy / (0.05 * vmax) + c)


class BiviscousHysteretic(Biviscous):
    r"""Nonlinear hysteretic biviscous model (Wereley et al. 1998).

    .. math:: F = \operatorname{clip}\big(C_{pre}(\dot x - \dot x_0\operatorname{sgn}\ddot x),\
              C_{post}\dot x - F_y,\ C_{post}\dot x + F_y\big) + f_0

    Parameters (SI): ``C_pre``, ``C_post`` [N s/m], ``F_y``, ``F_y_u``, ``f0`` [N], ``v0`` [m/s].

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 401); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = BiviscousHysteretic().simulate(rec, {"v0": 0.005})
    >>> bool(np.all(np.isfinite(F)))
    True

    References
    ----------
    Review (the MR-model review) eq 61.
    """

    name = "biviscous_hysteretic"
    title = "nonlinear hysteretic biviscous (Wereley)"
    source = "the MR-model review eq 61"
    parameters = Biviscous.parameters + (
        Parameter("v0", "m/s", 0.002, 0.0, 10.0, "zero-force velocity of the pre-yield branch"),
    )

    def _v0(self, values):
        return values["v0"]


class ArctanHysteretic(Model):
    r"""Nonlinear hysteretic arctangent model (Wang and Liao, after Ang et al.): the hysteretic biviscous model with
    an arctangent pre-yield branch.

    .. math:: F = \operatorname{clip}\big(\alpha\arctan[\beta(\dot x - \dot x_0\operatorname{sgn}\ddot x)],\
              C_{post}\dot x - F_y,\ C_{post}\dot x + F_y\big) + f_0,\qquad F_y = F_{y,0} + F_{y,u}u

    Parameters (SI): ``alpha`` [N] (magnification), ``beta`` [s/m] (rotation), ``v0`` [m/s], ``C_post``
    [N s/m], ``F_y``, ``F_y_u``, ``f0`` [N].

    Notes
    -----
    Eq 62 prints the branches of eq 61 with the pre-yield line replaced by the arctangent; as for eq 61, the clip
    form is the continuous law (the pre-yield branch between the two post-yield lines).  The loop is point
    symmetric about the origin (the review: "a symmetric hysteresis loop around the zero point").

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 2001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = ArctanHysteretic().simulate(rec, {"C_post": 0.0, "F_y": 1e6, "v0": 0.0, "alpha": 300.0, "beta": 1e6})
    >>> round(float(F.max()) / (np.pi / 2), 1)   # never yields: the arctangent alone
    300.0

    References
    ----------
    Review (the MR-model review) eq 62, section 5.3 (Wang and Liao; Ang et al.).
    """

    name = "arctan_hysteretic"
    title = "nonlinear hysteretic arctangent (Wang-Liao)"
    source = "the MR-model review eq 62 (Table 1: eq 58; Wang and Liao)"
    uses_control = True
    memoryless = True
    control_parameters = ("F_y_u",)
    parameters = (
        Parameter("alpha", "N", 800.0, 0.0, 1e7, "magnification factor of the pre-yield arctangent"),
        Parameter("beta", "s/m", 500.0, 0.0, 1e7, "rotation factor (slope) of the pre-yield arctangent"),
        Parameter("v0", "m/s", 0.002, 0.0, 10.0, "zero-force velocity of the pre-yield branch"),
        Parameter("C_post", "N*s/m", 5000.0, 0.0, 1e9, "post-yield damping"),
        Parameter("F_y", "N", 1000.0, 0.0, 1e7, "yield force"),
        FORCE_OFFSET,
        Parameter("F_y_u", "N", 0.0, -1e7, 1e7, "yield force per unit control"),
    )

    def force(self, record, values):
        v = record.velocity
        Fy = np.maximum(values["F_y"] + values["F_y_u"] * self.control(record), 0.0)
        pre = values["alpha"] * np.arctan(values["beta"] * (v - values["v0"] * np.sign(record.acceleration)))
        return np.clip(pre, values["C_post"] * v - Fy, values["C_post"] * v + Fy) + values["f0"]

    def guess_from_force(self, record):
        g = Biviscous().guess_from_force(record)
        return dict(
            C_post=g["C_post"], F_y=g["F_y"], f0=g["f0"], alpha=g["F_y"], beta=20.0 / peak_speed(record), v0=0.0
        )
