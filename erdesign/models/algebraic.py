r"""Algebraic (memoryless) hysteresis models: Eyring-plastic, Weng arctan, Kwok tanh and the magic formula.

Each maps the present displacement, velocity and acceleration (and control) to a force with no internal state, so
they are vectorised outright and their inverses (control for a desired force) are explicit where the control enters
linearly (the MR-model review Table 1 marks Kwok and the magic formula invertible;
:mod:`erdesign.identification.inverse`).
"""

from __future__ import annotations

import numpy as np

from ._guess import force_scales
from .base import FORCE_OFFSET, ControlAffineModel, Model, Parameter

__all__ = [
    "EyringPlastic",
    "WengArctan",
    "KwokTanh",
    "MagicFormula",
    "ChengTanh",
    "YangArctan",
    "YangExponential",
    "Metered",
    "Balamurugan",
]


def _control_law(values, p, u):
    """p + p_u u + p_u2 u^2: the coefficient ``p`` at the dimensionless control u (Yang's linear or quadratic laws
    in the current)."""
    return values[p] + (values[f"{p}_u"] + values[f"{p}_u2"] * u) * u


def _control_law_slopes(laws):
    """The parameters p_u, p_u2 of :func:`_control_law` for the coefficients ``laws``, (name, unit) pairs."""
    return tuple(
        Parameter(f"{p}_u{s}", unit, 0.0, -1e10, 1e10, f"{p} per unit control{' squared' if s else ''}")
        for p, unit in laws
        for s in ("", "2")
    )


class EyringPlastic(Model):
    r"""Eyring-plastic model (Bitman et al.; Vivas-López et al. (n.d.) eq 8).

    .. math:: F = F_\alpha\operatorname{arcsinh}(\lambda_1\dot z - \lambda_2 z)\,(1 + \beta_1 e^{-\beta_2|\dot z|})
              + c_1\dot z + c_3\dot z^3 + f_0, \qquad F_\alpha = F_{\alpha,0} + F_{\alpha,u}u

    Parameters (SI): ``F_alpha``, ``F_alpha_u``, ``f0`` [N], ``lambda1`` [s/m], ``lambda2`` [1/m], ``beta1`` [-],
    ``beta2`` [s/m], ``c1`` [N s/m], ``c3`` [N s^3/m^3].

    Notes
    -----
    The source makes every parameter an undefined function of the actuation and frequency; here only the yield
    amplitude depends (linearly) on the control.  The offset f0 is added (the source's data were centred).
    The post-yield coefficients are bounded below by zero, c1 >= 0 and c3 >= 0: the source has them "model the
    damping in the post-yield region", and a damper's post-yield damping dissipates (the general model's c_p >= 0,
    :mod:`erdesign.models.semiactive`, is bounded alike).  Unbounded, a fit on a slow record can trade a negative
    c1 against a large c3 that holds on its speeds only: on the truth-rig road profile E3 of docs/characterize.md
    (speeds to 0.066 m/s) it ended at F_alpha = 0, c1 = -2.5e4 N s/m, c3 = 4.8e6 N s^3/m^3, ESR 0.009 on its
    record and 4.5-5.0 on the records that reach 0.21 m/s; bounded, 0.010 and 0.006-0.009.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 401); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> bool(np.all(np.isfinite(EyringPlastic().simulate(rec))))
    True

    References
    ----------
    Vivas-López et al. eq 8 and Table 6 (ESR 0.08-0.20 on its ER damper).
    """

    name = "eyring_plastic"
    title = "Eyring-plastic (Bitman)"
    source = "Vivas-López et al. (n.d.) eq 8"
    uses_control = True
    memoryless = True
    control_parameters = ("F_alpha_u",)
    linear_parameters = ("F_alpha", "F_alpha_u", "c1", "c3", "f0")
    parameters = (
        Parameter("F_alpha", "N", 300.0, 0.0, 1e7, "yield force amplitude"),
        Parameter("lambda1", "s/m", 200.0, 0.0, 1e7, "pre-yield slope"),
        Parameter("lambda2", "1/m", 0.0, -1e7, 1e7, "pre-yield hysteresis"),
        Parameter("beta1", "", 0.0, -0.99, 100.0, "yield force correction"),
        Parameter("beta2", "s/m", 10.0, 0.0, 1e6, "yield force correction rate"),
        Parameter("c1", "N*s/m", 1000.0, 0.0, 1e8, "post-yield damping (dissipative: not negative)"),
        Parameter("c3", "N*s^3/m^3", 0.0, 0.0, 1e12, "cubic post-yield damping (not negative)"),
        FORCE_OFFSET,
        Parameter("F_alpha_u", "N", 0.0, -1e7, 1e7, "yield amplitude per unit control"),
    )

    def force(self, record, values):
        v, x = record.velocity, record.displacement
        Fa = values["F_alpha"] + values["F_alpha_u"] * self.control(record)
        return (
            Fa
            * np.arcsinh(values["lambda1"] * v - values["lambda2"] * x)
            * (1.0 + values["beta1"] * np.exp(-values["beta2"] * np.abs(v)))
            + values["c1"] * v
            + values["c3"] * v**3
            + values["f0"]
        )

    def guess_from_force(self, record):
        fy, c, f0, _, vmax = force_scales(record)
        return dict(F_alpha=fy / 3.0, lambda1=100.0 / vmax, c1=c, f0=f0, beta2=1.0 / vmax)


class WengArctan(ControlAffineModel):
    r"""Weng's arctangent model, with the inertia term of Cesmeci and Engin.

    .. math:: F = f_0 + c_b\dot x + \frac{2}{\pi}f_y\arctan\{k[\dot x - \dot x_0\operatorname{sgn}(\ddot x)]\}
              + m\ddot x, \qquad f_y = f_{y,0} + f_{y,u} u,\ c_b = c_{b,0} + c_{b,u} u

    Parameters (SI): ``f0``, ``f_y``, ``f_y_u`` [N], ``c_b``, ``c_b_u`` [N s/m], ``k`` [s/m], ``v0`` [m/s],
    ``m`` [kg] (m = 0 is Weng's eq 88; the MR-model review eq 89 adds it).

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 401); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = WengArctan().simulate(rec, {"f_y": 500.0, "c_b": 0.0, "k": 1e6, "v0": 0.0})
    >>> round(float(F.max()), 0)
    500.0

    References
    ----------
    Review (the MR-model review) eqs 88-89 (Weng et al.; Cesmeci and Engin).
    """

    name = "weng_arctan"
    title = "Weng arctangent (with inertia)"
    source = "the MR-model review eqs 88-89"
    uses_control = True
    memoryless = True
    control_parameters = ("f_y_u", "c_b_u")
    linear_parameters = ("f0", "c_b", "f_y", "m", "c_b_u", "f_y_u")
    parameters = (
        Parameter("f_y", "N", 500.0, 0.0, 1e7, "yield force"),
        Parameter("c_b", "N*s/m", 2000.0, 0.0, 1e8, "viscous damping"),
        Parameter("k", "s/m", 200.0, 0.0, 1e7, "shape (slope) coefficient"),
        Parameter("v0", "m/s", 0.002, -10.0, 10.0, "hysteretic velocity"),
        Parameter("m", "kg", 0.0, -1e5, 1e5, "virtual (fluid) mass"),
        Parameter("f0", "N", 0.0, -1e7, 1e7, "preload (accumulator)"),
        Parameter("f_y_u", "N", 0.0, -1e7, 1e7, "yield force per unit control"),
        Parameter("c_b_u", "N*s/m", 0.0, -1e8, 1e8, "damping per unit control"),
    )

    def control_affine(self, record, values):
        v, a = record.velocity, record.acceleration
        shape = 2.0 / np.pi * np.arctan(values["k"] * (v - values["v0"] * np.sign(a)))
        P = values["f0"] + values["c_b"] * v + values["f_y"] * shape + values["m"] * a
        Q = values["c_b_u"] * v + values["f_y_u"] * shape
        return P, Q

    def guess_from_force(self, record):
        fy, c, f0, _, vmax = force_scales(record)
        return dict(f_y=fy, c_b=c, f0=f0, k=20.0 / vmax, v0=0.0)


class KwokTanh(ControlAffineModel):
    r"""Kwok's hyperbolic-tangent model.

    .. math:: F = k x + c\dot x + \alpha\tanh(\beta\dot x + \delta\operatorname{sgn}x) + f_0,
              \qquad \alpha = \alpha_0 + \alpha_u u,\ c = c_0 + c_u u

    Parameters (SI): ``k`` [N/m], ``c``, ``c_u`` [N s/m], ``alpha``, ``alpha_u``, ``f0`` [N], ``beta`` [s/m],
    ``delta`` [-].

    Notes
    -----
    The force is affine in the control, so the inverse model is explicit (the MR-model review: invertible).

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 401); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = KwokTanh().simulate(rec, {"k": 0.0, "c": 0.0, "alpha": 700.0, "beta": 1e4, "delta": 0.0})
    >>> round(float(F.max()), 0)
    700.0

    References
    ----------
    Review (the MR-model review) eq 95 (Kwok et al.), section 8.2.
    """

    name = "kwok_tanh"
    title = "Kwok hyperbolic tangent"
    source = "the MR-model review eq 95 (Table 1: eq 89)"
    uses_control = True
    memoryless = True
    control_parameters = ("alpha_u", "c_u")
    linear_parameters = ("k", "c", "alpha", "f0", "c_u", "alpha_u")
    parameters = (
        Parameter("k", "N/m", 0.0, 0.0, 1e8, "stiffness (a spring: not negative)"),
        Parameter("c", "N*s/m", 2000.0, 0.0, 1e8, "viscous damping"),
        Parameter("alpha", "N", 600.0, 0.0, 1e7, "hysteresis scale (height of the loop)"),
        Parameter("beta", "s/m", 200.0, 0.0, 1e7, "slope of the loop"),
        Parameter("delta", "", 0.2, -10.0, 10.0, "width of the loop"),
        FORCE_OFFSET,
        Parameter("alpha_u", "N", 0.0, -1e7, 1e7, "hysteresis scale per unit control"),
        Parameter("c_u", "N*s/m", 0.0, -1e8, 1e8, "damping per unit control"),
    )

    def control_affine(self, record, values):
        v, x = record.velocity, record.displacement
        z = np.tanh(values["beta"] * v + values["delta"] * np.sign(x))
        P = values["k"] * x + values["c"] * v + values["alpha"] * z + values["f0"]
        Q = values["c_u"] * v + values["alpha_u"] * z
        return P, Q

    def guess_from_force(self, record):
        fy, c, f0, _, vmax = force_scales(record)
        return dict(alpha=fy, c=c, f0=f0, beta=10.0 / vmax, delta=0.0)


class MagicFormula(ControlAffineModel):
    r"""Magic-formula damper model (Pacejka's tyre formula applied to the MR damper).

    .. math::
        F = D\sin\{C\arctan[B(1 - E)s + E\arctan(Bs)]\} + k_c\dot x + k x + f_0,
        \qquad s = \dot x + A x,\quad D = D_0 + D_u u

    Parameters (SI): ``D``, ``D_u``, ``f0`` [N], ``C``, ``E`` [-], ``B`` [s/m], ``A`` [1/s], ``k_c`` [N s/m],
    ``k`` [N/m].

    Notes
    -----
    Departure from the source: the MR-model review eq 100 prints the argument as :math:`\dot x + A|x|` (and a misplaced
    bracket).  With :math:`|x|` the two branches of a sinusoidal cycle have the same :math:`|x|` at the same
    velocity, so the term cannot open the force-velocity loop that A is said to set ("the half-width of the
    hysteresis curve"); :math:`\dot x + A x` opens it by :math:`A X_0` in velocity, as described.  The bracket follows
    the standard magic formula (eq 99).  D enters linearly: invertible in the control (the MR-model review Table 1).

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 401); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = MagicFormula().simulate(rec, {"D": 800.0, "C": 1.0, "E": 0.0, "B": 1e5, "A": 0.0, "k_c": 0.0})
    >>> round(float(F.max()), 1)
    800.0

    References
    ----------
    Review (the MR-model review) eqs 99-100, section 9.
    """

    name = "magic_formula"
    title = "magic formula (Pacejka form)"
    source = "the MR-model review eqs 99-100"
    uses_control = True
    memoryless = True
    control_parameters = ("D_u",)
    linear_parameters = ("D", "k_c", "k", "f0", "D_u")
    parameters = (
        Parameter("D", "N", 600.0, 0.0, 1e7, "peak factor (saturation force)"),
        Parameter("C", "", 1.0, 0.1, 2.0, "shape factor"),
        Parameter("B", "s/m", 200.0, 0.0, 1e7, "stiffness factor"),
        Parameter("E", "", 0.0, -10.0, 1.0, "curvature factor"),
        Parameter("A", "1/s", 1.0, -1e4, 1e4, "hysteretic factor"),
        Parameter("k_c", "N*s/m", 2000.0, -1e8, 1e8, "viscous damping"),
        Parameter("k", "N/m", 0.0, 0.0, 1e8, "stiffness (a spring: not negative)"),
        FORCE_OFFSET,
        Parameter("D_u", "N", 0.0, -1e7, 1e7, "peak factor per unit control"),
    )

    def control_affine(self, record, values):
        v, x = record.velocity, record.displacement
        s = v + values["A"] * x
        B, E = values["B"], values["E"]
        shape = np.sin(values["C"] * np.arctan(B * (1.0 - E) * s + E * np.arctan(B * s)))
        P = values["D"] * shape + values["k_c"] * v + values["k"] * x + values["f0"]
        Q = values["D_u"] * shape
        return P, Q

    def guess_from_force(self, record):
        fy, c, f0, _, vmax = force_scales(record)
        return dict(D=fy, k_c=c, f0=f0, B=10.0 / vmax, A=0.0)


class ChengTanh(ControlAffineModel):
    r"""Cheng's modified hyperbolic-tangent model: a dashpot and a tanh hysteresis term, no spring.

    .. math:: F = c\,\dot x + \alpha z, \qquad z = \tanh(\beta\dot x + \delta\operatorname{sgn}x),
              \qquad c = c_0 + c_u u,\ \alpha = \alpha_0 + \alpha_u u

    Parameters (SI): ``c``, ``c_u`` [N s/m], ``alpha``, ``alpha_u`` [N], ``beta`` [s/m], ``delta`` [-].

    Notes
    -----
    The source makes c and beta functions of the current and of the excitation amplitude and frequency, and alpha
    a function of the current, without the review giving the functions; here c and alpha are linear in the control
    and beta is a constant (identified per test condition).  With beta independent of the control the force is
    affine in it, so the inverse is explicit (the review: invertible).

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 401); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = ChengTanh().simulate(rec, {"c": 0.0, "alpha": 700.0, "beta": 1e5, "delta": 0.0})
    >>> round(float(F.max()), 3)
    700.0

    References
    ----------
    Review (the MR-model review) eq 98, section 8.4 (Cheng et al.), Table 1: invertible.
    """

    name = "cheng_tanh"
    title = "Cheng hyperbolic tangent"
    source = "the MR-model review eq 98 (Table 1: eq 92, invertible; Cheng et al.)"
    uses_control = True
    memoryless = True
    control_parameters = ("alpha_u", "c_u")
    linear_parameters = ("c", "alpha", "c_u", "alpha_u")
    parameters = (
        Parameter("c", "N*s/m", 2000.0, 0.0, 1e8, "viscous damping"),
        Parameter("alpha", "N", 600.0, 0.0, 1e7, "hysteresis scale (height of the loop)"),
        Parameter("beta", "s/m", 200.0, 0.0, 1e7, "slope of the loop"),
        Parameter("delta", "", 0.2, -10.0, 10.0, "width of the loop (delta_c)"),
        Parameter("alpha_u", "N", 0.0, -1e7, 1e7, "hysteresis scale per unit control"),
        Parameter("c_u", "N*s/m", 0.0, -1e8, 1e8, "damping per unit control"),
    )

    def control_affine(self, record, values):
        v, x = record.velocity, record.displacement
        z = np.tanh(values["beta"] * v + values["delta"] * np.sign(x))
        return values["c"] * v + values["alpha"] * z, values["c_u"] * v + values["alpha_u"] * z

    def guess_from_force(self, record):
        fy, c, f0, _, vmax = force_scales(record)
        return dict(alpha=fy, c=c, beta=10.0 / vmax, delta=0.0)


class YangArctan(Model):
    r"""Yang's algebraic hysteretic model with an arctangent (friction-lag) term.

    .. math:: F = kx + c\dot x + \alpha z + f_0,\qquad z = \arctan(\beta\dot x) + \delta\operatorname{sgn}(x),

    with :math:`p = p_0 + p_1u + p_2u^2` for p = k, c, alpha, beta, delta (the source's linear or quadratic laws in
    the current).

    Parameters (SI): ``k`` [N/m], ``c`` [N s/m], ``alpha`` [N], ``beta`` [s/m], ``delta`` [-], ``f0`` [N], and
    their control slopes ``*_u``, ``*_u2``.

    Notes
    -----
    The :math:`\delta\operatorname{sgn}x` term is outside the arctangent (as printed): it shifts the force by
    :math:`\pm\alpha\delta` with the sign of the displacement, which opens the loop by :math:`2\alpha\delta` at
    zero velocity.  Memoryless: the inverse is a bracketed root in the control.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 2001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = YangArctan().simulate(rec, {"k": 0.0, "c": 0.0, "alpha": 400.0, "beta": 1e6, "delta": 0.0})
    >>> round(float(F.max()) / (np.pi / 2), 1)
    400.0

    References
    ----------
    Review (the MR-model review) eq 96, section 8.3 (Yang et al.).
    """

    name = "yang_arctan"
    title = "Yang arctangent model"
    source = "the MR-model review eq 96 (Table 1: eq 90; Yang et al.)"
    uses_control = True
    memoryless = True
    _slopes = _control_law_slopes((("k", "N/m"), ("c", "N*s/m"), ("alpha", "N"), ("beta", "s/m"), ("delta", "")))
    control_parameters = tuple(p.name for p in _slopes)
    linear_parameters = ("k", "c", "alpha", "f0", "k_u", "k_u2", "c_u", "c_u2", "alpha_u", "alpha_u2")
    parameters = (
        Parameter("k", "N/m", 0.0, 0.0, 1e8, "stiffness (a spring: not negative)"),
        Parameter("c", "N*s/m", 2000.0, 0.0, 1e8, "viscous damping"),
        Parameter("alpha", "N", 400.0, 0.0, 1e7, "hysteretic factor"),
        Parameter("beta", "s/m", 200.0, 0.0, 1e7, "slope of the loop"),
        Parameter("delta", "", 0.2, -10.0, 10.0, "width of the loop"),
        FORCE_OFFSET,
        *_slopes,
    )

    def _shape(self, record, values, u):
        beta, delta = _control_law(values, "beta", u), _control_law(values, "delta", u)
        return np.arctan(beta * record.velocity) + delta * np.sign(record.displacement)

    def force(self, record, values):
        u = self.control(record)
        return (
            _control_law(values, "k", u) * record.displacement
            + _control_law(values, "c", u) * record.velocity
            + _control_law(values, "alpha", u) * self._shape(record, values, u)
            + values["f0"]
        )

    def guess_from_force(self, record):
        fy, c, f0, _, vmax = force_scales(record)
        return dict(alpha=fy / 1.5, c=c, f0=f0, beta=10.0 / vmax, delta=0.0)


class YangExponential(Model):
    r"""Yang's algebraic model with an exponential (sigmoid) hysteresis term.

    .. math:: F = kx + c_0\dot x + \frac{f_b}{e^{\alpha\dot x + \beta\operatorname{sgn}x} + \gamma} + f_0

    with :math:`p = p_0 + p_1u + p_2u^2` for p = k, c0, f_b (linear or quadratic laws in the current).

    Parameters (SI): ``k`` [N/m], ``c0`` [N s/m], ``f_b``, ``f0`` [N], ``alpha`` [s/m], ``beta``, ``gamma`` [-],
    and the control slopes ``*_u``, ``*_u2``.

    Notes
    -----
    For a positive :math:`f_b` the term falls from :math:`f_b/\gamma` at large negative velocity to 0 at large
    positive velocity when :math:`\alpha > 0`; a damper's force needs :math:`f_b < 0` (or :math:`\alpha < 0`),
    and the offset :math:`f_0` centres the step.  With :math:`\gamma = 1` the term is
    :math:`f_b[1 - \tanh((\alpha\dot x + \beta\operatorname{sgn}x)/2)]/2`.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 2001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = YangExponential().simulate(rec, {"k": 0.0, "c0": 0.0, "f_b": -800.0, "alpha": 1e4, "beta": 0.0,
    ...                                      "gamma": 1.0, "f0": 400.0})
    >>> round(float(F.max()), 3), round(float(F.min()), 3)
    (400.0, -400.0)

    References
    ----------
    Review (the MR-model review) eq 97, section 8.3 (Yang et al.).
    """

    name = "yang_exponential"
    title = "Yang exponential model"
    source = "the MR-model review eq 97 (Table 1: eq 91; Yang et al.)"
    uses_control = True
    memoryless = True
    _slopes = _control_law_slopes((("k", "N/m"), ("c0", "N*s/m"), ("f_b", "N")))
    control_parameters = tuple(p.name for p in _slopes)
    linear_parameters = ("k", "c0", "f_b", "f0") + control_parameters
    parameters = (
        Parameter("k", "N/m", 0.0, 0.0, 1e8, "stiffness (a spring: not negative)"),
        Parameter("c0", "N*s/m", 2000.0, 0.0, 1e8, "viscous damping"),
        Parameter("f_b", "N", -800.0, -1e7, 1e7, "hysteresis force"),
        Parameter("alpha", "s/m", 200.0, -1e7, 1e7, "velocity scale of the hysteresis term"),
        Parameter("beta", "", 0.5, -50.0, 50.0, "width of the loop"),
        Parameter("gamma", "", 1.0, 1e-6, 1e3, "shape of the hysteresis term", log_scale=True),
        Parameter("f0", "N", 400.0, -1e7, 1e7, "force offset"),
        *_slopes,
    )

    def force(self, record, values):
        u = self.control(record)
        e = np.exp(
            np.clip(values["alpha"] * record.velocity + values["beta"] * np.sign(record.displacement), -700.0, 700.0)
        )
        return (
            _control_law(values, "k", u) * record.displacement
            + _control_law(values, "c0", u) * record.velocity
            + _control_law(values, "f_b", u) / (e + values["gamma"])
            + values["f0"]
        )

    def guess_from_force(self, record):
        fy, c, f0, _, vmax = force_scales(record)
        return dict(f_b=-2.0 * fy, f0=f0 + fy, c0=c, alpha=20.0 / vmax, beta=0.0, gamma=1.0)


class Metered(WengArctan):
    r"""Metered's model: Weng's arctangent model with the yield term scaled by the excitation amplitude and
    frequency.

    .. math:: F = f_0 + c_b\dot x + \frac{2}{\pi}f_y\arctan\{k[\dot x - \dot x_0\operatorname{sgn}(\ddot x)]\}
              (A_1a + A_2)(F_1f + F_2)

    Parameters (SI): those of ``weng_arctan`` plus ``A1`` [1/m], ``A2`` [-], ``F1`` [1/Hz], ``F2`` [-], and the
    excitation ``amplitude`` [m] and ``frequency`` [Hz], explicit and held a priori (identification starts from the
    record's).

    Notes
    -----
    As printed, the amplitude and frequency factors multiply the yield term only.  :math:`A_2` and :math:`F_2`
    only rescale :math:`f_y` and are held at 1.  With :math:`A_1 = F_1 = 0` it is Weng's model.

    References
    ----------
    Review (the MR-model review) eq 90, section 7.3 (Metered et al.).
    """

    name = "metered"
    title = "Metered amplitude-frequency arctangent model"
    source = "the MR-model review eq 90 (Table 1: eq 84; Metered et al.)"
    parameters = WengArctan.parameters + (
        Parameter("A1", "1/m", 0.0, -1e6, 1e6, "amplitude factor of the yield term"),
        Parameter("A2", "", 1.0, -1e3, 1e3, "amplitude offset (redundant with f_y: held)", fitted=False),
        Parameter("F1", "1/Hz", 0.0, -1e3, 1e3, "frequency factor of the yield term"),
        Parameter("F2", "", 1.0, -1e3, 1e3, "frequency offset (redundant with f_y: held)", fitted=False),
        Parameter("amplitude", "m", 0.01, 0.0, 10.0, "excitation amplitude (a priori: the record's)", fitted=False),
        Parameter("frequency", "Hz", 1.0, 0.0, 1e4, "excitation frequency (a priori: the record's)", fitted=False),
    )

    def _scale(self, values):
        return (values["A1"] * values["amplitude"] + values["A2"]) * (values["F1"] * values["frequency"] + values["F2"])

    def control_affine(self, record, values):
        s = self._scale(values)
        return super().control_affine(record, {**values, "f_y": values["f_y"] * s, "f_y_u": values["f_y_u"] * s})

    def initial_guess(self, record):
        from .excitation import record_amplitude, record_frequency

        return {
            **super().initial_guess(record),
            "amplitude": record_amplitude(record),
            "frequency": record_frequency(record),
        }


class Balamurugan(Model):
    r"""Balamurgan's model: Weng's arctangent hysteretic function times an asymmetric sigmoid function of the
    voltage.

    .. math:: F = \left[f_0 + c_b\dot x + \frac{2}{\pi}f_y\arctan\{k[\dot x - \dot x_0\operatorname{sgn}(\ddot x)]\}
              \right]\left(1 + \frac{k_2}{1 + e^{-a_2(u/v_0 + I_0)}} - \frac{k_2}{1 + e^{-a_2I_0}}\right)

    Parameters (SI): ``f0``, ``f_y`` [N], ``c_b`` [N s/m], ``k`` [s/m], ``v0`` [m/s] (the hysteretic velocity), and
    the voltage function's ``k2``, ``a2``, ``I0``, ``u0`` [-] (the source's :math:`v_0`, in units of the control).

    Notes
    -----
    The review prints the voltage as :math:`\sigma`; it is the control u (the voltage).  The gain is 1 at zero
    voltage and monotone in it, so the inverse is a bracketed root in the control (the gain equation has a closed
    form too).

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 401)
    >>> rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t), control=np.zeros(401), control_kind="voltage")
    >>> bool(np.allclose(Balamurugan().simulate(rec), WengArctan().simulate(rec)))
    True

    References
    ----------
    Review (the MR-model review) eqs 91-92, section 7.4 (Balamurgan et al.).
    """

    name = "balamurugan"
    title = "Balamurgan voltage-gain arctangent model"
    source = "the MR-model review eqs 91-92 (Table 1: eq 86; Balamurgan et al.)"
    uses_control = True
    memoryless = True
    control_parameters = ("k2", "a2", "I0", "u0")
    parameters = tuple(p for p in WengArctan.parameters if p.name in ("f_y", "c_b", "k", "v0", "f0")) + (
        Parameter("k2", "", 0.0, 0.0, 1e4, "gain of the voltage function"),
        Parameter("a2", "", 1.0, 1e-6, 1e4, "slope of the voltage function"),
        Parameter("I0", "", 0.0, -1e3, 1e3, "bias of the voltage function"),
        Parameter("u0", "", 1.0, 1e-6, 1e6, "voltage scale of the voltage function (the source's v0)"),
    )

    def force(self, record, values):
        from .bouc_wen_variants import sigmoid_gain

        hyst = WengArctan().force(record, {**values, "m": 0.0, "f_y_u": 0.0, "c_b_u": 0.0})
        return hyst * sigmoid_gain(self.control(record) / values["u0"], values["k2"], values["a2"], values["I0"])

    def guess_from_force(self, record):
        return WengArctan().guess_from_force(record)
