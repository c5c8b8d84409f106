r"""The general dynamic models of the MR-model review (its section 11): Zhao's dead-zone model, Zhao and Xu's
corrected sigmoid model, Yuan's tanh-exponential model, Yu's hysteresis-division model and He's mechanism-based
unified model.  Bui's quasi-static magic-formula model (eq 112) is not here: the review does not give its
quasi-static force :math:`F_{QS} = F_\eta + F_\tau + F_f`.
"""

from __future__ import annotations

import numpy as np

from ._guess import force_scales
from .base import FORCE_OFFSET, Model, Parameter
from .bingham import extended_bingham_force

__all__ = ["ZhaoDeadZone", "ZhaoXuSigmoid", "YuanTanh", "YuDivision", "HeUnified"]


class ZhaoDeadZone(Model):
    r"""Zhao's dynamic hysteretic model: an integrator with a dead-zone feedback, driven by the velocity.

    .. math::
        \dot\eta = k_i[\dot x - \Delta(\eta)],\qquad F = \eta - a\dot x + b,\qquad
        \Delta(\eta) = k\,\operatorname{sgn}(\eta)\max(|\eta| - x_0, 0)

    Parameters (SI): ``k_i`` [N/m] (integration gain), ``x0`` [N] (half width of the dead zone), ``k``
    [m/(N s)] (dead-zone slope), ``a`` [N s/m] (feedforward gain), ``b`` [N] (bias).

    Notes
    -----
    With the velocity as the model input U, :math:`\eta` is exactly the force of Zhou's modified Bingham model
    (``bingham_modified``) with spring :math:`k_1 = k_i`, yield force :math:`f_c = x_0` and damping
    :math:`c_0 = 1/k`: in that model :math:`\dot F = k_1(\dot x - \dot x_1)` with
    :math:`c_0\dot x_1 = \operatorname{sgn}(F)\max(|F| - f_c, 0)`.  It is solved by the same backward-Euler
    dead-zone step.  x0 and k_i set the width and the height of the loop, as the review says.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 1, 1001); rec = Measurement.from_arrays(t, 0.05 * t)   # 50 mm/s
    >>> round(float(ZhaoDeadZone().simulate(rec, {"k": 1 / 4000.0, "x0": 300.0, "k_i": 1e6, "a": 0.0})[-1]), 3)
    500.0

    References
    ----------
    Review (the MR-model review) eq 107, section 11 (Zhao et al. 2018).
    """

    name = "zhao_dead_zone"
    title = "dead-zone dynamic hysteretic model (Zhao)"
    source = "the MR-model review eq 107 (Table 1: eqs 101-106; Zhao et al.)"
    linear_parameters = ("a", "b")
    parameters = (
        Parameter("k_i", "N/m", 2e5, 1.0, 1e11, "integration gain", log_scale=True),
        Parameter("x0", "N", 500.0, 0.0, 1e7, "half width of the dead zone"),
        Parameter("k", "m/(N*s)", 2e-4, 1e-12, 1e3, "slope of the dead zone", log_scale=True),
        Parameter("a", "N*s/m", 0.0, -1e8, 1e8, "feedforward gain"),
        Parameter("b", "N", 0.0, -1e7, 1e7, "bias"),
    )

    def force(self, record, values):
        eta = extended_bingham_force(
            record.time, record.displacement, 1.0 / values["k"], values["x0"], 1e300, 1.0, values["k_i"]
        )
        return eta - values["a"] * record.velocity + values["b"]

    def guess_from_force(self, record):
        fy, c, f0, X, _ = force_scales(record)
        return dict(x0=fy, k=1.0 / max(c, 1.0), b=f0, k_i=20.0 * fy / X)


class ZhaoXuSigmoid(Model):
    r"""Zhao and Xu's corrected sigmoid model (Stribeck effect at low velocity).

    .. math::
        F = F_{ys}\frac{1 - e^{-\delta(\dot x - \dot x_n\operatorname{sgn}\ddot x)}}
                       {1 + e^{-\delta(\dot x - \dot x_n\operatorname{sgn}\ddot x)}}
            + \operatorname{sgn}(\dot x)F_{sc}\left(1 - e^{-|\dot x/\dot x_s|}\right) + k_0x + c_0\dot x + f_0

    with :math:`F_{ys} = F_{ys,0} + F_{ys,u}u`.

    Parameters (SI): ``F_ys``, ``F_ys_u``, ``F_sc``, ``f0`` [N], ``delta`` [s/m], ``v_n``, ``v_s`` [m/s], ``k0``
    [N/m], ``c0`` [N s/m].

    Notes
    -----
    :math:`(1 - e^{-s})/(1 + e^{-s}) = \tanh(s/2)`.  Departure from the source: eq 108 prints the shift as a
    constant :math:`\dot x_n`, which only moves the curve along the velocity axis and leaves no loop but that of
    :math:`k_0x`; the force hysteresis the model is said to describe needs the shift to follow the direction of
    the acceleration, as in Weng's model (eq 88).  :math:`F_{sc}` is the Stribeck (static) correction at low
    velocity.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 2001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = ZhaoXuSigmoid().simulate(rec, {"F_sc": 0.0, "k0": 0.0, "c0": 0.0, "delta": 1e5, "v_n": 0.0})
    >>> round(float(F.max()), 3)
    500.0

    References
    ----------
    Review (the MR-model review) eq 108, section 11 (Zhao and Xu 2018).
    """

    name = "zhao_xu_sigmoid"
    title = "corrected sigmoid model (Zhao-Xu)"
    source = "the MR-model review eq 108 (Table 1: eqs 101-106; Zhao and Xu)"
    uses_control = True
    memoryless = True
    control_parameters = ("F_ys_u",)
    linear_parameters = ("F_ys", "F_sc", "k0", "c0", "f0", "F_ys_u")
    parameters = (
        Parameter("F_ys", "N", 500.0, 0.0, 1e7, "yield force of the sigmoid"),
        Parameter("delta", "s/m", 200.0, 0.0, 1e7, "steepness of the sigmoid"),
        Parameter("v_n", "m/s", 0.002, -10.0, 10.0, "hysteretic velocity shift"),
        Parameter("F_sc", "N", 0.0, -1e7, 1e7, "Stribeck correction force"),
        Parameter("v_s", "m/s", 0.005, 1e-7, 10.0, "Stribeck velocity", log_scale=True),
        Parameter("k0", "N/m", 0.0, 0.0, 1e8, "stiffness (a spring: not negative)"),
        Parameter("c0", "N*s/m", 2000.0, 0.0, 1e8, "viscous damping"),
        FORCE_OFFSET,
        Parameter("F_ys_u", "N", 0.0, -1e7, 1e7, "sigmoid yield force per unit control"),
    )

    def force(self, record, values):
        v = record.velocity
        s = values["delta"] * (v - values["v_n"] * np.sign(record.acceleration))
        Fys = values["F_ys"] + values["F_ys_u"] * self.control(record)
        return (
            Fys * np.tanh(0.5 * s)
            + np.sign(v) * values["F_sc"] * (1.0 - np.exp(-np.abs(v / values["v_s"])))
            + values["k0"] * record.displacement
            + values["c0"] * v
            + values["f0"]
        )

    def guess_from_force(self, record):
        fy, c, f0, _, vmax = force_scales(record)
        return dict(F_ys=fy, c0=c, f0=f0, delta=40.0 / vmax, v_n=0.0, F_sc=0.0, v_s=vmax / 20.0)


class YuanTanh(Model):
    r"""Yuan's tanh-exponential model: a shear-thinning viscous term, a tanh hysteretic term, a spring and a fixed
    force.

    .. math:: F = c\,e^{-A|\dot x|}\dot x + T\tanh(\alpha\dot x + \beta x) + Kx + F_0,\qquad T = T_0 + T_uu

    Parameters (SI): ``c`` [N s/m] (the product :math:`VS_1C\eta` of eq 109), ``A`` [s/m], ``T``, ``T_u``, ``F0``
    [N] (:math:`T(i)S_2`), ``alpha`` [s/m], ``beta`` [1/m], ``K`` [N/m].

    Notes
    -----
    The constants :math:`V`, :math:`S_1`, :math:`C`, :math:`\eta` (and :math:`S_2`) of eq 109 only multiply each
    other: one coefficient each is identifiable, so they are merged.  The review gives T(i) without its law;
    linear.

    References
    ----------
    Review (the MR-model review) eq 109, section 11 (Yuan et al. 2018).
    """

    name = "yuan_tanh"
    title = "tanh-exponential model (Yuan)"
    source = "the MR-model review eq 109 (Table 1: eqs 101-106; Yuan et al.)"
    uses_control = True
    memoryless = True
    control_parameters = ("T_u",)
    linear_parameters = ("c", "T", "K", "F0", "T_u")
    parameters = (
        Parameter("c", "N*s/m", 3000.0, 0.0, 1e8, "viscous coefficient (V S1 C eta)"),
        Parameter("A", "s/m", 0.0, 0.0, 1e5, "shear-thinning rate of the viscous term"),
        Parameter("T", "N", 500.0, 0.0, 1e7, "hysteretic force (T(i) S2)"),
        Parameter("alpha", "s/m", 200.0, 0.0, 1e7, "velocity scale of the tanh"),
        Parameter("beta", "1/m", 0.0, -1e6, 1e6, "displacement term of the tanh (loop width)"),
        Parameter("K", "N/m", 0.0, 0.0, 1e8, "stiffness (a spring: not negative)"),
        Parameter("F0", "N", 0.0, -1e7, 1e7, "fixed force"),
        Parameter("T_u", "N", 0.0, -1e7, 1e7, "hysteretic force per unit control"),
    )

    def force(self, record, values):
        v, x = record.velocity, record.displacement
        T = values["T"] + values["T_u"] * self.control(record)
        return (
            values["c"] * np.exp(-values["A"] * np.abs(v)) * v
            + T * np.tanh(values["alpha"] * v + values["beta"] * x)
            + values["K"] * x
            + values["F0"]
        )

    def guess_from_force(self, record):
        fy, c, f0, _, vmax = force_scales(record)
        return dict(T=fy, c=c, F0=f0, alpha=20.0 / vmax)


class YuDivision(Model):
    r"""Yu's hysteresis-division model: a backbone curve plus or minus a branch curve by the sign of the
    acceleration.

    .. math::
        F = F_{ba} + \operatorname{sgn}^+(\ddot x)F_{br} + f_0,\qquad
        F_{ba} = a\frac{1 - e^{-b|\dot x|}}{1 + e^{-c|\dot x|}}\operatorname{sgn}\dot x,\qquad
        F_{br} = d\exp\left[-\left(\frac{|\dot x| - e}{f}\right)^2\right]

    with :math:`\operatorname{sgn}^+(\ddot x) = 1` for :math:`\ddot x \ge 0`, -1 otherwise; :math:`a = a_0 + a_u u`.

    Parameters (SI): ``a``, ``a_u``, ``d``, ``f0`` [N], ``b``, ``c`` [s/m], ``e``, ``f`` [m/s].

    Notes
    -----
    Eq 110 prints the backbone with :math:`e^{+b\dot x\operatorname{sgn}\dot x}` and :math:`e^{+c\dot
    x\operatorname{sgn}\dot x}`, which grows or vanishes exponentially with the speed instead of saturating; the
    negative exponents give the saturating backbone of the source's Figure 37 (zero at zero velocity, a at large
    speed when b, c > 0).  The branch curve is a Gaussian bump of height d centred at the speed e.

    References
    ----------
    Review (the MR-model review) eq 110, section 11 (Yu et al.).
    """

    name = "yu_division"
    title = "hysteresis-division model (Yu)"
    source = "the MR-model review eq 110 (Table 1: eqs 101-106; Yu et al.)"
    uses_control = True
    memoryless = True
    control_parameters = ("a_u",)
    linear_parameters = ("a", "d", "f0", "a_u")
    parameters = (
        Parameter("a", "N", 800.0, -1e7, 1e7, "saturation force of the backbone"),
        Parameter("b", "s/m", 100.0, 0.0, 1e7, "rise rate of the backbone"),
        Parameter("c", "s/m", 100.0, 0.0, 1e7, "second rate of the backbone"),
        Parameter("d", "N", 100.0, -1e7, 1e7, "height of the branch curve"),
        Parameter("e", "m/s", 0.01, 0.0, 10.0, "speed at the peak of the branch curve"),
        Parameter("f", "m/s", 0.01, 1e-7, 10.0, "width of the branch curve", log_scale=True),
        FORCE_OFFSET,
        Parameter("a_u", "N", 0.0, -1e7, 1e7, "backbone saturation per unit control"),
    )

    def force(self, record, values):
        v = record.velocity
        s = np.abs(v)
        a = values["a"] + values["a_u"] * self.control(record)
        backbone = a * (1.0 - np.exp(-values["b"] * s)) / (1.0 + np.exp(-values["c"] * s)) * np.sign(v)
        branch = values["d"] * np.exp(-(((s - values["e"]) / values["f"]) ** 2))
        return backbone + np.where(record.acceleration >= 0, 1.0, -1.0) * branch + values["f0"]

    def guess_from_force(self, record):
        fy, c, f0, _, vmax = force_scales(record)
        return dict(a=fy + c * vmax, b=20.0 / vmax, c=20.0 / vmax, d=0.0, e=0.2 * vmax, f=0.2 * vmax, f0=f0)


class HeUnified(Model):
    r"""He's mechanism-based unified model: friction, elasticity, viscosity, inertia and a magic-formula shear
    force.

    .. math::
        F = A\operatorname{sgn}^+(\ddot x) + k(x - x_0) + c\dot x + n\ddot x
            + D_b\sin\{C_b\arctan[B_b(1 - E_b)\dot x + E_b\arctan(B_b\dot x)]\}

    with :math:`\operatorname{sgn}^+(\ddot x) = 1` for :math:`\ddot x > 0`, -1 otherwise, and
    :math:`D_b = D_{b,0} + D_{b,u}u`.

    Parameters (SI): ``A``, ``D_b``, ``D_b_u`` [N], ``k`` [N/m], ``x0`` [m], ``c`` [N s/m], ``n`` [kg], ``B_b``
    [s/m], ``C_b``, ``E_b`` [-].

    Notes
    -----
    :math:`B_b[(1 - E_b)\dot x + (E_b/B_b)\arctan(B_b\dot x)]` of eq 111 is the standard magic-formula argument
    written above.  The review defines :math:`C_b = 1 \pm (1 - \frac{2}{\pi}\arcsin(Y_m/D_b))` without saying which
    sign or what :math:`Y_m` is; :math:`C_b` is identified directly.  The shear force's current law is not given;
    :math:`D_b` is linear in the control.

    References
    ----------
    Review (the MR-model review) eq 111, section 11 (He et al. 2019).
    """

    name = "he_unified"
    title = "mechanism-based unified model (He)"
    source = "the MR-model review eq 111 (Table 1: eqs 101-106; He et al.)"
    uses_control = True
    memoryless = True
    control_parameters = ("D_b_u",)
    linear_parameters = ("A", "k", "c", "n", "D_b", "D_b_u")
    parameters = (
        Parameter("A", "N", 50.0, -1e7, 1e7, "friction force (sign of the acceleration)"),
        Parameter("k", "N/m", 0.0, 0.0, 1e8, "stiffness (a spring: not negative)"),
        Parameter("x0", "m", 0.0, -1.0, 1.0, "initial displacement of the spring"),
        Parameter("c", "N*s/m", 2000.0, -1e8, 1e8, "viscous damping"),
        Parameter("n", "kg", 0.0, -1e5, 1e5, "inertia coefficient"),
        Parameter("D_b", "N", 600.0, 0.0, 1e7, "peak of the shear force"),
        Parameter("C_b", "", 1.0, 0.1, 2.0, "shape factor of the shear force"),
        Parameter("B_b", "s/m", 200.0, 0.0, 1e7, "stiffness factor of the shear force"),
        Parameter("E_b", "", 0.0, -10.0, 1.0, "curvature factor of the shear force"),
        Parameter("D_b_u", "N", 0.0, -1e7, 1e7, "peak of the shear force per unit control"),
    )

    def force(self, record, values):
        v = record.velocity
        B, E = values["B_b"], values["E_b"]
        Db = values["D_b"] + values["D_b_u"] * self.control(record)
        shear = Db * np.sin(values["C_b"] * np.arctan(B * (1.0 - E) * v + E * np.arctan(B * v)))
        return (
            values["A"] * np.where(record.acceleration > 0, 1.0, -1.0)
            + values["k"] * (record.displacement - values["x0"])
            + values["c"] * v
            + values["n"] * record.acceleration
            + shear
        )

    def guess_from_force(self, record):
        fy, c, _, _, vmax = force_scales(record)
        return dict(D_b=fy, c=c, B_b=10.0 / vmax, A=0.0)
