r"""Viscoelastic-plastic models of the MR-model review (section 6): Li's viscoelastic-plastic model, the continuous
viscoelastic-plastic (VEP) model, its nonlinear-stiffness form (nkVEP) and the stiffness-viscosity-elasto-slide
(SVES) model.

The pre-yield Zener element of Li's model is the exact first-order lag of :mod:`erdesign.models._kernels`; the
series visco-plastic element of VEP / nkVEP is integrated by implicit-midpoint sub-steps
(:func:`erdesign.models._kernels.series_viscoplastic`); the elasto-slide element of SVES is a stop operator, exact for
a displacement linear between samples.
"""

from __future__ import annotations

import numpy as np

from ._guess import force_scales
from ._kernels import first_order_lag, series_viscoplastic, stop_operator
from .base import FORCE_OFFSET, Model, Parameter

__all__ = ["SVES", "ContinuousVEP", "LiViscoelasticPlastic", "NonlinearStiffnessVEP", "zener_force"]


def zener_force(t, x, k1, c1, k2):
    r"""Force [N] of a spring k2 in series with a Kelvin-Voigt element (k1, c1), from rest at the first sample:
    :math:`F = k_2(x - y)`, :math:`c_1\dot y + k_1 y = k_2(x - y)`, i.e. y is the exact first-order lag of
    :math:`k_2 x/(k_1 + k_2)` with time constant :math:`c_1/(k_1 + k_2)`.

    At steady harmonic motion the complex stiffness is :math:`k_2(k_1 + i\omega c_1)/(k_1 + k_2 + i\omega c_1)`.
    """
    x = np.asarray(x, dtype=float)
    x_rel = x - x[0]
    y = first_order_lag(t, k2 * x_rel / (k1 + k2), c1 / (k1 + k2))
    return k2 * (x_rel - y)


class LiViscoelasticPlastic(Model):
    r"""Li's viscoelastic-plastic model: a Zener solid with seal stiction before yield, Bingham with inertia after.

    .. math::
        F = \begin{cases} F_{ve} + F_s & |F_{ve} + F_s| \le F_c \\
        F_c\operatorname{sgn}(\dot x) + c_v\dot x + R\ddot x & \text{otherwise}\end{cases},
        \qquad F_c = F_{c,0} + F_{c,u}u

    with :math:`F_{ve} = k_2(x - y)`, :math:`c_1\dot y + k_1 y = k_2(x - y)` (a spring k2 in series with a
    Kelvin-Voigt element k1, c1: the review's "rigid three-parameter model").

    Parameters (SI): ``k1``, ``k2`` [N/m], ``c1``, ``c_v`` [N s/m], ``R`` [kg], ``F_c``, ``F_c_u``, ``F_s`` [N].

    Notes
    -----
    The review gives the two regimes (eqs 76-79) and the switch :math:`|F| \le F_c`; the pre-yield element is
    tested before the switch, so the force is the pre-yield force while it stays below the yield force.  The seal
    stiction :math:`F_s` is taken as a constant force.  The yield force depends on the control (the source's current);
    in the post-yield regime the force is affine in it, which is why the review marks the model invertible:
    :func:`erdesign.identification.inverse.inverse_control` solves the post-yield equation for the control (a desired
    force inside the pre-yield band is reached at any control large enough, and reported unreachable otherwise).

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 2001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = LiViscoelasticPlastic().simulate(rec, {"F_c": 0.0, "F_s": 0.0, "R": 0.0})   # no yield force: a dashpot
    >>> bool(np.allclose(F[1:], 2000.0 * rec.velocity[1:]))
    True

    References
    ----------
    Review (the MR-model review) eqs 76-79, section 6.3 (Li et al.), Table 1: invertible.
    """

    name = "li_viscoelastic_plastic"
    title = "viscoelastic-plastic model (Li)"
    source = "the MR-model review eqs 76-79 (Table 1: eqs 73-74, invertible)"
    uses_control = True
    control_parameters = ("F_c_u",)
    parameters = (
        Parameter("k1", "N/m", 2e5, 1.0, 1e11, "Kelvin-Voigt spring (pre-yield)", log_scale=True),
        Parameter("c1", "N*s/m", 2e4, 1.0, 1e9, "Kelvin-Voigt dashpot (pre-yield)", log_scale=True),
        Parameter("k2", "N/m", 5e5, 1.0, 1e11, "series spring (pre-yield)", log_scale=True),
        Parameter("F_c", "N", 500.0, 0.0, 1e7, "yield force"),
        Parameter("c_v", "N*s/m", 2000.0, 0.0, 1e8, "post-yield viscous damping"),
        Parameter("R", "kg", 0.0, -1e5, 1e5, "post-yield inertial mass"),
        Parameter("F_s", "N", 0.0, -1e7, 1e7, "seal stiction force (pre-yield)"),
        Parameter("F_c_u", "N", 0.0, -1e7, 1e7, "yield force per unit control"),
    )

    def _yield(self, record, values):
        return values["F_c"] + values["F_c_u"] * self.control(record)

    def pre_yield(self, record, values):
        """The pre-yield force F_ve + F_s [N]."""
        return zener_force(record.time, record.displacement, values["k1"], values["c1"], values["k2"]) + values["F_s"]

    def control_affine(self, record, values):
        """(P, Q) of the post-yield force P + Q u (the inverse model; the pre-yield force does not depend on u)."""
        v, a = record.velocity, record.acceleration
        s = np.sign(v)
        return values["F_c"] * s + values["c_v"] * v + values["R"] * a, values["F_c_u"] * s

    def force(self, record, values):
        pre = self.pre_yield(record, values)
        Fc = self._yield(record, values)
        P, Q = self.control_affine(record, values)
        return np.where(np.abs(pre) <= Fc, pre, P + Q * self.control(record))

    def guess_from_force(self, record):
        fy, c, f0, X, vmax = force_scales(record, min_damping=1.0)
        return dict(F_c=fy, c_v=c, F_s=f0, k2=10.0 * fy / X, k1=fy / X, c1=fy / vmax)


class ContinuousVEP(Model):
    r"""Continuous viscoelastic-plastic (VEP) model of Li et al.: a spring in series with a dashpot and a smoothed
    Coulomb element.

    .. math::
        F = k(x - y) = c\dot y + A\tanh(\alpha\dot y) + \ldots,\qquad
        k = k_a\tanh(b u) + k_b,\ c = c_a u + c_b,\ A = A_a u + A_b,\ \alpha = \alpha_a u + \alpha_b

    Parameters (SI): ``k_b``, ``k_a`` [N/m], ``b`` [-], ``c_b``, ``c_a`` [N s/m], ``A_b``, ``A_a`` [N], ``alpha_b``,
    ``alpha_a`` [s/m], ``f0`` [N].

    Notes
    -----
    The review prints eqs 80 and 82 as :math:`F = kx - y`; the spring force :math:`k(x - y)` is meant (the Maxwell
    element of its Figure 23).  The current laws are those the review gives for nkVEP (eq 85), here used with the
    continuous model too (zero slopes: constants).  For large k the element is rigid and the force tends to the
    algebraic :math:`c\dot x + A\tanh(\alpha\dot x)`; at constant velocity V it settles at
    :math:`cV + A\tanh(\alpha V)`.  Implicit-midpoint sub-steps (second order), the sub-step's rate by a bracketed root (Illinois false position).

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 1, 2001); rec = Measurement.from_arrays(t, 0.05 * t)   # 50 mm/s constant
    >>> F = ContinuousVEP().simulate(rec, {"k_b": 1e6, "c_b": 2000.0, "A_b": 400.0, "alpha_b": 200.0})
    >>> round(float(F[-1]), 1)   # c V + A tanh(alpha V) = 100 + 400 tanh(10)
    500.0

    References
    ----------
    Review (the MR-model review) eqs 80-82 and 85, section 6.4 (Li et al.).
    """

    name = "vep_continuous"
    title = "continuous viscoelastic-plastic model (VEP, Li)"
    source = "the MR-model review eqs 80-82 (Table 1: eq 77), current laws eq 85"
    uses_control = True
    control_parameters = ("k_a", "b", "c_a", "A_a", "alpha_a")
    parameters = (
        Parameter("k_b", "N/m", 2e5, 1.0, 1e11, "pre-yield stiffness", log_scale=True),
        Parameter("c_b", "N*s/m", 2000.0, 0.0, 1e8, "post-yield viscous damping"),
        Parameter("A_b", "N", 500.0, 0.0, 1e7, "yield force"),
        Parameter("alpha_b", "s/m", 200.0, 0.0, 1e7, "restoring factor (sharpness of yield)"),
        FORCE_OFFSET,
        Parameter("k_a", "N/m", 0.0, -1e11, 1e11, "stiffness change at saturating control"),
        Parameter("b", "", 1.0, 0.0, 1e3, "saturation rate of the stiffness with control"),
        Parameter("c_a", "N*s/m", 0.0, -1e8, 1e8, "damping per unit control"),
        Parameter("A_a", "N", 0.0, -1e7, 1e7, "yield force per unit control"),
        Parameter("alpha_a", "s/m", 0.0, -1e7, 1e7, "restoring factor per unit control"),
    )

    def laws(self, record, values):
        """(k, c, A, alpha) per sample (eq 85), clipped to k > 0 and c, A, alpha >= 0."""
        u = self.control(record)
        k = np.maximum(values["k_a"] * np.tanh(values["b"] * u) + values["k_b"], 1e-6)
        c = np.maximum(values["c_a"] * u + values["c_b"], 0.0)
        A = np.maximum(values["A_a"] * u + values["A_b"], 0.0)
        alpha = np.maximum(values["alpha_a"] * u + values["alpha_b"], 0.0)
        return k, c, A, alpha

    def _element(self, record, values, k, c, A, alpha):
        return series_viscoplastic(record.time, record.displacement - record.displacement[0], k, c, A, alpha)

    def force(self, record, values):
        k, c, A, alpha = self.laws(record, values)
        y, _ = self._element(record, values, k, c, A, alpha)
        return k * (record.displacement - record.displacement[0] - y) + values["f0"]

    def guess_from_force(self, record):
        fy, c, f0, X, vmax = force_scales(record, min_damping=1.0)
        return dict(A_b=fy, c_b=c, f0=f0, k_b=20.0 * fy / X, alpha_b=20.0 / vmax)


class NonlinearStiffnessVEP(ContinuousVEP):
    r"""Viscoelastic-plastic model with nonlinear stiffness (nkVEP, Li et al.).

    .. math::
        F = k(x, y)(x - y) = c\dot y + A\tanh(\alpha\dot y),\qquad
        k(x, y) = q\,|(x - y) - \tanh(\rho(\dot x - \dot y))\,d_{opf}|^n + k_0

    with the current laws of eq 85 (:math:`k_0 = k_a\tanh(bu) + k_b`, c, A and alpha linear in u).

    Parameters (SI): those of ``vep_continuous`` (``k_b``, ``k_a`` are the reference stiffness k0 and its change)
    plus ``q`` [N/m^(1+n)], ``n`` [-], ``rho`` [s/m], ``d_opf`` [m].

    Notes
    -----
    q = 0 is the continuous VEP model.  The stiffness rises away from :math:`\pm d_{opf}` (the "sudden change point"
    of the stiffness): with :math:`\rho` large, :math:`\tanh(\rho(\dot x - \dot y))` is the sign of the element's
    relative motion, so the stiffness is lowest where the spring's deflection equals :math:`\pm d_{opf}`.  The
    stiffness depends on the rate :math:`\dot y` too, so each sub-step's rate is found by a bracketed root of the full
    nonlinear equation, grown from the previous rate.  The rate is unique only while the stiffness changes slowly
    with it, roughly :math:`q\rho d_{opf}|x - y|^n < c + A\alpha\,\mathrm{sech}^2(\alpha\dot y)`; beyond that the
    equation has several rates and the printed model chatters between them (a property of eqs 83-84, not of the
    integration): keep :math:`q\rho d_{opf}` moderate.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 2001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> m = NonlinearStiffnessVEP()
    >>> bool(np.allclose(m.simulate(rec, {"q": 0.0}), ContinuousVEP().simulate(rec)))
    True

    References
    ----------
    Review (the MR-model review) eqs 83-85, section 6.5 (Li et al.).
    """

    name = "vep_nonlinear_stiffness"
    title = "nonlinear-stiffness viscoelastic-plastic model (nkVEP, Li)"
    source = "the MR-model review eqs 83-85 (Table 1: eqs 78-79)"
    parameters = ContinuousVEP.parameters + (
        Parameter("q", "N/m^2", 1e6, 0.0, 1e15, "nonlinear stiffness coefficient (units N/m^(1+n); shown for n = 1)"),
        Parameter("n", "", 1.0, 0.1, 5.0, "nonlinear stiffness exponent", fitted=False),
        Parameter("rho", "s/m", 50.0, 0.0, 1e7, "amplification coefficient"),
        Parameter("d_opf", "m", 0.001, 0.0, 1.0, "position of the sudden change of stiffness"),
    )

    def _element(self, record, values, k, c, A, alpha):
        return series_viscoplastic(
            record.time,
            record.displacement - record.displacement[0],
            k,
            c,
            A,
            alpha,
            q=values["q"],
            n=values["n"],
            rho=values["rho"],
            d=values["d_opf"],
        )

    def force(self, record, values):
        k0, c, A, alpha = self.laws(record, values)
        y, yd = self._element(record, values, k0, c, A, alpha)
        w = record.displacement - record.displacement[0] - y
        k = (
            values["q"] * np.abs(w - np.tanh(values["rho"] * (record.velocity - yd)) * values["d_opf"]) ** values["n"]
            + k0
        )
        return k * w + values["f0"]


class SVES(Model):
    r"""Stiffness-viscosity-elasto-slide (SVES) model (Wereley et al.): a spring, a dashpot and an elasto-slide
    element in parallel.

    .. math::
        F = k_1 x + c\dot x + F_{es} + f_0,\qquad
        \dot F_{es} = k_2\dot x \text{ while } |F_{es}| < N,\ N = k_2 x_s

    (a spring k2 in series with a Coulomb slider of force N: the parallelogram of eq 87 on a harmonic cycle).

    Parameters (SI): ``k1``, ``k2`` [N/m], ``c`` [N s/m], ``x_s`` [m], ``f0`` [N], ``N_u`` [N] (slider force per
    unit control: the review's parameters are "amplitude-dependent", refitted per test).

    Notes
    -----
    Eq 87 prints the decreasing branch as :math:`-N + k_2(x - \bar x)`; starting from :math:`+N` at the turning
    point :math:`x = \bar x`, the element force is :math:`N + k_2(x - \bar x)`, reaching :math:`-N` after the travel
    :math:`2x_s` as the text says.  On a harmonic cycle of amplitude :math:`\bar x > x_s` the element dissipates
    :math:`4N(\bar x - x_s)` per cycle (the area of the parallelogram).

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 2001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = SVES().simulate(rec, {"k1": 0.0, "c": 0.0, "k2": 1e5, "x_s": 0.002})
    >>> round(float(F.max()), 6)   # the slider force N = k2 x_s
    200.0

    References
    ----------
    Review (the MR-model review) eqs 86-87, section 6.6 (Wereley et al.).
    """

    name = "sves"
    title = "stiffness-viscosity-elasto-slide (SVES, Wereley)"
    source = "the MR-model review eqs 86-87 (Table 1: eqs 80-81)"
    uses_control = True
    control_parameters = ("N_u",)
    linear_parameters = ("k1", "c", "f0")
    parameters = (
        Parameter("k1", "N/m", 0.0, 0.0, 1e9, "linear stiffness (a spring: not negative)"),
        Parameter("c", "N*s/m", 2000.0, 0.0, 1e8, "linear viscous damping"),
        Parameter("k2", "N/m", 2e5, 1.0, 1e11, "elasto-slide stiffness", log_scale=True),
        Parameter("x_s", "m", 0.002, 1e-9, 1.0, "yielding displacement of the elasto-slide", log_scale=True),
        FORCE_OFFSET,
        Parameter("N_u", "N", 0.0, -1e7, 1e7, "slider force per unit control"),
    )

    def elasto_slide(self, record, values):
        """The elasto-slide force [N] (from rest)."""
        N = np.maximum(values["k2"] * values["x_s"] + values["N_u"] * self.control(record), 0.0)
        return stop_operator(record.displacement, values["k2"], N)

    def force(self, record, values):
        return (
            values["k1"] * record.displacement
            + values["c"] * record.velocity
            + self.elasto_slide(record, values)
            + values["f0"]
        )

    def guess_from_force(self, record):
        fy, c, f0, X, _vmax = force_scales(record, min_damping=1.0)
        return dict(c=c, f0=f0, x_s=X / 10.0, k2=10.0 * fy / X)
