r"""Bingham-type damper models: Stanway's Bingham model and Gamota-Filisko's extended Bingham model.

Bingham (Butz and von Stryk 2002, eq 2; the MR-model review eq 2 with the accumulator offset :math:`f_0`):

.. math:: F = f_c\,\operatorname{sgn}(\dot x) + c_0\dot x + f_0

Extended Bingham (Gamota and Filisko; Butz and von Stryk (2002) eq 3): a Bingham element (c0, f_c) in series with a
Kelvin-Voigt
element (k1, c1) and a spring k2.  See :class:`BinghamExtended` for how it is integrated.
"""

from __future__ import annotations

import numpy as np

from ._guess import sign_viscous_fit, stroke
from .base import FORCE_OFFSET, Model, Parameter

__all__ = [
    "Bingham",
    "BinghamExtended",
    "extended_bingham_force",
    "BinghamModified",
    "BinghamImproved",
    "BinghamRegularized",
    "BinghamHysteretic",
]


class Bingham(Model):
    r"""Stanway's Bingham model: Coulomb friction in parallel with a dashpot.

    .. math:: F = (f_c + f_{c,u} u)\,\operatorname{sgn}(\dot x) + (c_0 + c_{0,u} u)\,\dot x + f_0

    Parameters (SI): ``c0`` [N s/m], ``f_c`` [N], ``f0`` [N]; control slopes ``f_c_u`` [N], ``c0_u`` [N s/m] per unit
    of the dimensionless control u (the MR-model review eq 7: yield force linear in the coil current).

    Notes
    -----
    sgn(0) = 0.  Rigid below yield: the model has no pre-yield branch, so it cannot show the roll-off of measured
    force-velocity loops (Butz and von Stryk 2002, section 3.1.1).

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 1, 201); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = Bingham().simulate(rec, {"c0": 5000.0, "f_c": 670.0})   # Butz and von Stryk (2002) section 4.2
    >>> bool(abs(F.max() - (670 + 5000 * 0.02 * np.pi)) < 1.0)   # f_c + c0 v_max
    True

    References
    ----------
    Butz and von Stryk (2002) eq 2 and section 4.2; review (the MR-model review) eqs 2 and 7.
    """

    name = "bingham"
    memoryless = True
    title = "Bingham (Stanway)"
    source = "Butz and von Stryk (2002) eq 2 (Stanway); the MR-model review eqs 2, 7"
    uses_control = True
    control_parameters = ("f_c_u", "c0_u")
    linear_parameters = ("c0", "f_c", "f0", "f_c_u", "c0_u")
    parameters = (
        Parameter("c0", "N*s/m", 5000.0, 0.0, 1e8, "viscous damping (post-yield)"),
        Parameter("f_c", "N", 670.0, 0.0, 1e7, "friction (yield) force"),
        Parameter("f0", "N", 0.0, -1e7, 1e7, "force offset (accumulator)"),
        Parameter("f_c_u", "N", 0.0, -1e7, 1e7, "yield force per unit control"),
        Parameter("c0_u", "N*s/m", 0.0, -1e8, 1e8, "damping per unit control"),
    )

    def force(self, record, values):
        u = self.control(record)
        v = record.velocity
        return (
            (values["f_c"] + values["f_c_u"] * u) * np.sign(v) + (values["c0"] + values["c0_u"] * u) * v + values["f0"]
        )

    def linear_terms(self, record, values):
        u, v = self.control(record), record.velocity
        s = np.sign(v)
        return {"c0": v, "f_c": s, "f0": np.ones_like(v), "f_c_u": u * s, "c0_u": u * v}, np.zeros_like(v)

    def guess_from_force(self, record):
        fc, c0, f0 = sign_viscous_fit(record)
        return dict(f_c=max(fc, 0.0), c0=max(c0, 0.0), f0=f0)


def extended_bingham_force(t, x, c0, f_c, k1, c1, k2, substeps=64):
    r"""Force of the extended Bingham model for a displacement history, by backward Euler on its dead-zone form.

    The Bingham element, :math:`F = c_0\dot x_1 + f_c\operatorname{sgn}\dot x_1` with :math:`|F| \le f_c` when
    stuck, inverts to a continuous dead zone, :math:`\dot x_1 = D(F)/c_0`, :math:`D(F) = \operatorname{sgn}(F)
    \max(|F| - f_c, 0)`.  With the Kelvin elongation :math:`e = x_2 - x_1` and :math:`F = k_2(x - x_2)`:

    .. math:: \dot x_1 = D(F)/c_0, \qquad c_1\dot e = F - k_1 e .

    Backward Euler on a step h gives one monotone piecewise-linear equation for the new force,
    :math:`A F + B D(F) = R` with :math:`q = 1 + h k_1/c_1`, :math:`A = 1 + k_2 h/(c_1 q)`, :math:`B = k_2 h/c_0`,
    :math:`R = k_2(x_{n+1} - x_{1,n} - e_n/q)`, solved in closed form (stuck when :math:`|R| \le A f_c`).  The
    scheme is L-stable, so the stiffness of a small c0 (rate k2/c0) does not limit the step; it is first order, so
    ``substeps`` sub-steps per sample (displacement interpolated linearly) keep the error small: 64 (the default)
    bring it below 1e-4 of the force spread at 1 ms samples (tests/test_models.py).  The loop is compiled
    (:func:`erdesign.models._compiled.extended_bingham_force`): some 10 ns per sub-step.
    """
    from . import _compiled

    return _compiled.extended_bingham_force(
        np.ascontiguousarray(t, dtype=float),
        np.ascontiguousarray(x, dtype=float),
        float(c0),
        float(f_c),
        float(k1),
        float(c1),
        float(k2),
        int(substeps),
    )


class BinghamExtended(Model):
    r"""Gamota-Filisko extended Bingham model (viscoelastic-plastic): Bingham element in series with a Zener solid.

    .. math::
        F = k_2(x - x_2) = k_1(x_2 - x_1) + c_1(\dot x_2 - \dot x_1) =
        \begin{cases} c_0\dot x_1 + f_c\operatorname{sgn}\dot x_1 & |F| > f_c\\ \dot x_1 = 0 & |F| \le f_c\end{cases}

    plus the offset :math:`f_0`.

    Parameters (SI): ``c0`` [N s/m], ``f_c`` [N], ``k1`` [N/m], ``c1`` [N s/m], ``k2`` [N/m], ``f0`` [N].

    Notes
    -----
    The system is stiff and switches between stuck and sliding (Butz and von Stryk 2002: "extremely stiff").  It is
    integrated by backward Euler on the equivalent dead-zone form with the force solved in closed form on each step
    (:func:`extended_bingham_force`, 64 sub-steps per sample), not by regularising the sign function;
    tests/test_models.py checks it against a Radau solution with a tight tolerance.  Starts from rest.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 2001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = BinghamExtended().simulate(rec)
    >>> bool(np.all(np.isfinite(F)))
    True

    References
    ----------
    Butz and von Stryk (2002) eq 3; review (the MR-model review) eq 3 (with f0).
    """

    name = "bingham_extended"
    title = "extended Bingham (Gamota-Filisko)"
    source = "Butz and von Stryk (2002) eq 3 (Gamota and Filisko); the MR-model review eq 3"
    parameters = (
        Parameter("c0", "N*s/m", 5000.0, 1.0, 1e8, "post-yield damping of the Bingham element", log_scale=True),
        Parameter("f_c", "N", 670.0, 0.0, 1e7, "friction (yield) force"),
        Parameter("k1", "N/m", 1e5, 1.0, 1e10, "Kelvin spring (pre-yield)", log_scale=True),
        Parameter("c1", "N*s/m", 2e4, 1.0, 1e9, "Kelvin dashpot (pre-yield)", log_scale=True),
        Parameter("k2", "N/m", 2e5, 1.0, 1e10, "series spring", log_scale=True),
        Parameter("f0", "N", 0.0, -1e7, 1e7, "force offset (accumulator)"),
    )
    linear_parameters = ("f0",)

    def linear_terms(self, record, values):
        rest = self.force(record, {**values, "f0": 0.0})
        return {"f0": np.ones_like(rest)}, rest

    def force(self, record, values):
        F = extended_bingham_force(
            record.time, record.displacement, values["c0"], values["f_c"], values["k1"], values["c1"], values["k2"]
        )
        return F + values["f0"]


class BinghamModified(Model):
    r"""Zhou's modified Bingham model: a Bingham element in series with a spring.

    .. math:: F = c_0\dot x_1 + f_c\operatorname{sgn}(\dot x_1) + f_0 = k_1(x - x_1) + f_0

    Parameters (SI): ``c0`` [N s/m], ``f_c`` [N], ``k1`` [N/m], ``f0`` [N].

    Notes
    -----
    The extended Bingham model with a rigid Kelvin element: integrated by the same backward-Euler dead-zone step
    (:func:`extended_bingham_force`, the Kelvin spring set to 1e300 N/m).  Below the yield force the element is
    stuck and the force is the spring's, :math:`k_1(x - x_1)`; at constant velocity V the force settles at
    :math:`c_0 V + f_c\operatorname{sgn}V`, reached with the time constant :math:`c_0/k_1`.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 1, 1001); rec = Measurement.from_arrays(t, 0.05 * t)   # 50 mm/s
    >>> round(float(BinghamModified().simulate(rec, {"c0": 4000.0, "f_c": 300.0, "k1": 1e6})[-1]), 3)
    500.0

    References
    ----------
    Review (the MR-model review) eq 6, section 2.4 (Zhou).
    """

    name = "bingham_modified"
    title = "modified Bingham (Zhou)"
    source = "the MR-model review eq 6 (Zhou)"
    linear_parameters = ("f0",)
    parameters = (
        Parameter("c0", "N*s/m", 5000.0, 1.0, 1e8, "post-yield damping", log_scale=True),
        Parameter("f_c", "N", 670.0, 0.0, 1e7, "friction (yield) force"),
        Parameter("k1", "N/m", 2e5, 1.0, 1e10, "series spring", log_scale=True),
        Parameter("f0", "N", 0.0, -1e7, 1e7, "force offset (accumulator)"),
    )

    def force(self, record, values):
        return (
            extended_bingham_force(
                record.time, record.displacement, values["c0"], values["f_c"], 1e300, 1.0, values["k1"]
            )
            + values["f0"]
        )

    def guess_from_force(self, record):
        g = Bingham().guess_from_force(record)
        return dict(c0=max(g["c0"], 1.0), f_c=g["f_c"], f0=g["f0"], k1=20.0 * max(g["f_c"], 1.0) / stroke(record))


class BinghamImproved(Model):
    r"""Occhiuzzi's improved Bingham model: a power-law viscous term and a yield force linear in the current.

    .. math:: F = c\,|\dot x|^{a}\operatorname{sgn}(\dot x) + (F_{y,min} + F_{y,u}u)\operatorname{sgn}(\dot x) + f_0,
              \qquad c = c_0 + c_u u,\ a = a_0 + a_u u

    Parameters (SI): ``c`` [N (s/m)^a; shown for a = 1], ``a`` [-], ``F_y_min``, ``F_y_u``, ``f0`` [N],
    ``c_u``, ``a_u``.

    Notes
    -----
    The review's eq 9 writes the yield force as :math:`F_{y,min} + (F_{y,max} - F_{y,min})i/i_{max}`: with the
    dimensionless control u = i / i_ref, :math:`F_{y,u} = (F_{y,max} - F_{y,min}) i_{ref}/i_{max}`.  It names c(i)
    and a(i) current dependent without giving the law; linear laws are used.  a = 1 is the Bingham model.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 401); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = BinghamImproved().simulate(rec, {"c": 5000.0, "a": 1.0, "F_y_min": 670.0})
    >>> from erdesign.models.bingham import Bingham
    >>> bool(np.allclose(F, Bingham().simulate(rec)))
    True

    References
    ----------
    Review (the MR-model review) eqs 7-9, section 2.5 (Occhiuzzi et al.).
    """

    name = "bingham_improved"
    title = "improved Bingham (Occhiuzzi)"
    source = "the MR-model review eqs 7-9 (Occhiuzzi et al.)"
    uses_control = True
    memoryless = True
    control_parameters = ("F_y_u", "c_u", "a_u")
    parameters = (
        Parameter("c", "N*s/m", 5000.0, 0.0, 1e9, "viscous coefficient of the power law"),
        Parameter("a", "", 1.0, 0.05, 3.0, "velocity exponent of the power law"),
        Parameter("F_y_min", "N", 500.0, 0.0, 1e7, "yield force at zero current"),
        FORCE_OFFSET,
        Parameter("F_y_u", "N", 0.0, -1e7, 1e7, "yield force per unit control ((F_y_max - F_y_min) / i_max)"),
        Parameter("c_u", "N*s/m", 0.0, -1e9, 1e9, "viscous coefficient per unit control"),
        Parameter("a_u", "", 0.0, -2.0, 2.0, "exponent per unit control"),
    )

    def force(self, record, values):
        u = self.control(record)
        v = record.velocity
        a = np.clip(values["a"] + values["a_u"] * u, 0.05, 3.0)
        return ((values["c"] + values["c_u"] * u) * np.abs(v) ** a + values["F_y_min"] + values["F_y_u"] * u) * np.sign(
            v
        ) + values["f0"]

    def guess_from_force(self, record):
        g = Bingham().guess_from_force(record)
        return {"c": g["c0"], "F_y_min": g["f_c"], "f0": g["f0"]}


class BinghamRegularized(Model):
    r"""Hysteresis-regularised Bingham model (Soltane et al.): an exponential regularisation of the Bingham law with
    a hysteretic velocity shift.

    .. math:: F = F_0 + c_v\dot x_e + F_y\left[1 - e^{-|\dot x_e|/\dot x_0}\right]\operatorname{sgn}(\dot x_e),
              \qquad \dot x_e = \dot x - \dot x_h\operatorname{sgn}(\ddot x),\ F_y = F_{y,0} + F_{y,u}u

    Parameters (SI): ``c_v`` [N s/m], ``F_y``, ``F_y_u``, ``F0`` [N], ``v_0``, ``v_h`` [m/s].

    Notes
    -----
    Departure from the source: eq 13 selects the branch :math:`\dot x_d \pm \dot x_h` by the sign of the velocity.
    A branch chosen by the velocity is a single-valued curve with a jump at zero velocity, not the loop whose width
    :math:`\dot x_h` is said to set; the branch is chosen by the sign of the acceleration, as in Weng's model (eq
    88), with the force lagging the velocity.  :math:`\dot x_h = 0` is eq 12.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 2001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = BinghamRegularized().simulate(rec, {"c_v": 0.0, "F_y": 500.0, "v_0": 1e-6, "v_h": 0.0})
    >>> round(float(F.max()), 6)   # a sharp regularisation is the Bingham yield force
    500.0

    References
    ----------
    Review (the MR-model review) eqs 12-13, section 2.7 (Soltane et al.).
    """

    name = "bingham_regularized"
    title = "hysteresis-regularised Bingham (Soltane)"
    source = "the MR-model review eqs 12-13 (Soltane et al.)"
    uses_control = True
    memoryless = True
    control_parameters = ("F_y_u",)
    linear_parameters = ("c_v", "F_y", "F0", "F_y_u")
    parameters = (
        Parameter("c_v", "N*s/m", 3000.0, 0.0, 1e8, "viscous damping"),
        Parameter("F_y", "N", 500.0, 0.0, 1e7, "yield force"),
        Parameter("v_0", "m/s", 0.005, 1e-7, 10.0, "regularisation velocity", log_scale=True),
        Parameter("v_h", "m/s", 0.002, -10.0, 10.0, "hysteretic velocity (half width of the loop)"),
        Parameter("F0", "N", 0.0, -1e7, 1e7, "force offset"),
        Parameter("F_y_u", "N", 0.0, -1e7, 1e7, "yield force per unit control"),
    )

    def force(self, record, values):
        ve = record.velocity - values["v_h"] * np.sign(record.acceleration)
        Fy = values["F_y"] + values["F_y_u"] * self.control(record)
        return values["F0"] + values["c_v"] * ve + Fy * (1.0 - np.exp(-np.abs(ve) / values["v_0"])) * np.sign(ve)

    def guess_from_force(self, record):
        g = Bingham().guess_from_force(record)
        v_0 = max(float(np.max(np.abs(record.velocity))) / 20.0, 1e-7)
        return {"c_v": g["c0"], "F_y": g["f_c"], "F0": g["f0"], "v_0": v_0, "v_h": 0.0}


class BinghamHysteretic(Model):
    r"""Zhang and Huang's nonlinear Bingham hysteretic model: an elastic-perfectly-plastic spring (an elasto-slide
    element) with nonlinear damping, and a post-yield viscous term while it slides.

    .. math::
        F = \begin{cases} k x_1 + (c_1|\dot x| + c_2\dot x^2)\dot x + f_0 & |k x_1| < F_y \\
        F_y\operatorname{sgn}(\dot x) + (c_0 + c_1|\dot x| + c_2\dot x^2)\dot x + f_0 & |k x_1| = F_y \end{cases},
        \qquad F_y = F_{y,0} + F_{y,u}u

    where :math:`k x_1` follows the displacement with stiffness k and is bounded by :math:`\pm F_y` (a stop
    operator: eq 11 is its explicit form on a harmonic cycle, with the turning point :math:`x_{2,max}`).

    Parameters (SI): ``k`` [N/m], ``F_y``, ``F_y_u``, ``f0`` [N], ``c0`` [N s/m], ``c1`` [N s^2/m^2], ``c2``
    [N s^3/m^3].

    Notes
    -----
    The element slides where its force is at the bound and moves the same way; the c0 term acts there only.  The
    loop's elastic branches have slope k in the force-displacement plane, and on a harmonic cycle the element
    dissipates :math:`4F_y(\bar x - F_y/k)` per cycle.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 2001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = BinghamHysteretic().simulate(rec, {"c0": 0.0, "c1": 0.0, "c2": 0.0})
    >>> round(float(F.max()), 6)   # the yield force
    500.0

    References
    ----------
    Review (the MR-model review) eqs 10-11, section 2.6 (Zhang and Huang).
    """

    name = "bingham_hysteretic"
    title = "nonlinear Bingham hysteretic (Zhang-Huang)"
    source = "the MR-model review eqs 10-11 (Zhang and Huang)"
    uses_control = True
    control_parameters = ("F_y_u",)
    linear_parameters = ("c1", "c2", "f0")
    parameters = (
        Parameter("k", "N/m", 5e5, 1.0, 1e11, "stiffness of the pre-yield spring", log_scale=True),
        Parameter("F_y", "N", 500.0, 0.0, 1e7, "yield force"),
        Parameter("c0", "N*s/m", 3000.0, 0.0, 1e8, "post-yield viscous damping"),
        Parameter("c1", "N*s^2/m^2", 0.0, -1e9, 1e9, "quadratic damping"),
        Parameter("c2", "N*s^3/m^3", 0.0, -1e11, 1e11, "cubic damping"),
        Parameter("f0", "N", 0.0, -1e7, 1e7, "force offset (accumulator)"),
        Parameter("F_y_u", "N", 0.0, -1e7, 1e7, "yield force per unit control"),
    )

    def force(self, record, values):
        from ._kernels import stop_operator

        v = record.velocity
        Fy = np.maximum(values["F_y"] + values["F_y_u"] * self.control(record), 0.0)
        s = stop_operator(record.displacement, values["k"], Fy)
        sliding = (np.abs(s) >= Fy * (1.0 - 1e-12)) & (s * v > 0)
        return s + (values["c1"] * np.abs(v) + values["c2"] * v**2) * v + values["c0"] * v * sliding + values["f0"]

    def guess_from_force(self, record):
        g = Bingham().guess_from_force(record)
        return {"c0": g["c0"], "F_y": g["f_c"], "f0": g["f0"], "k": 20.0 * max(g["f_c"], 1.0) / stroke(record)}
