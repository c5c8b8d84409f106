r"""The general semi-active damper model of Vivas-López et al. (n.d.) (passive + semi-active force, asymmetric
coefficients)."""

from __future__ import annotations

import numpy as np

from .base import Model, Parameter

__all__ = ["SemiactiveGeneral", "sigmoid_ratio"]


def sigmoid_ratio(s):
    r"""The saturating function of Vivas-López et al. (n.d.) eqs 5a-5e, :math:`s/(1 + |s|)` (odd, bounded by 1).

    >>> sigmoid_ratio([-1.0, 0.0, 3.0]).tolist()
    [-0.5, 0.0, 0.75]
    """
    s = np.asarray(s, dtype=float)
    return s / (1.0 + np.abs(s))


class SemiactiveGeneral(Model):
    r"""General semi-active model of Vivas-López et al. (n.d.) (eqs 2-5) with coefficients that differ in
    extension and compression.

    .. math::
        F_D = F_P + F_{SA}, \qquad
        F_P = f_0 + c_p\dot z + k_p z + m_D\ddot z + f_{fr} + f_{h,z} + f_{h,\dot z},

        F_{SA} = V c_{SA}\,[f_{pre\text{-}y,\dot z,V} + f_{pre\text{-}y,z}],

        f_{fr} = f_f\,S(v_f\dot z + x_f z),\quad
        f_{h,z} = F_{hz}\,S(v_{hz}\dot z + x_{hz}\operatorname{sgn} z),\quad
        f_{h,\dot z} = F_{hv}\,S(v_{hv}\dot z + x_{hv}\operatorname{sgn}\dot z),

        f_{pre\text{-}y,\dot z,V} = S(v_{py}\dot z V),\quad f_{pre\text{-}y,z} = S(x_{py} z),\qquad S(s) = s/(1 + |s|)

    where :math:`c_p` and :math:`c_{SA}` take their ``_pos`` value for :math:`\dot z \ge 0` (extension) and ``_neg``
    otherwise ("the SA damper has an asymmetric behavior", Vivas-López et al. section 4); V is the dimensionless control u.

    Parameters (SI): ``f0``, ``f_f``, ``F_hz``, ``F_hv`` [N]; ``c_p_pos``, ``c_p_neg`` [N s/m]; ``k_p`` [N/m];
    ``m_D`` [kg]; ``v_f``, ``v_hz``, ``v_hv``, ``v_py`` [s/m]; ``x_f``, ``x_py`` [1/m]; ``x_hz``, ``x_hv`` [-];
    ``c_sa_pos``, ``c_sa_neg`` [N].

    Notes
    -----
    Vivas-López et al. uses :math:`f_{h,z}` both for the term and its amplitude; the amplitudes are named ``F_hz`` and ``F_hv``
    here.  Without a control column the semi-active part is zero and its parameters are held fixed.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 401); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> bool(np.all(np.isfinite(SemiactiveGeneral().simulate(rec))))
    True

    References
    ----------
    Vivas-López et al. eqs 2-6, Table 2 (which diagram shows which term), Tables 3-4 (ESR 0.06-0.16, cross-validation).
    """

    name = "semiactive_general"
    title = "general semi-active model (Vivas-López et al.)"
    source = "Vivas-López et al. (n.d.) eqs 2-5"
    uses_control = True
    control_parameters = ("c_sa_pos", "c_sa_neg", "v_py", "x_py")
    linear_parameters = ("f0", "c_p_pos", "c_p_neg", "k_p", "m_D", "f_f", "F_hz", "F_hv", "c_sa_pos", "c_sa_neg")
    parameters = (
        Parameter("f0", "N", 0.0, -1e7, 1e7, "accumulator force"),
        Parameter("c_p_pos", "N*s/m", 2000.0, 0.0, 1e8, "viscous damping, extension"),
        Parameter("c_p_neg", "N*s/m", 2000.0, 0.0, 1e8, "viscous damping, compression"),
        Parameter("k_p", "N/m", 0.0, 0.0, 1e8, "stiffness (a spring: not negative)"),
        Parameter("m_D", "kg", 0.0, -1e5, 1e5, "virtual damper mass"),
        Parameter("f_f", "N", 300.0, -1e7, 1e7, "friction amplitude"),
        Parameter("v_f", "s/m", 100.0, 0.0, 1e7, "friction velocity gain"),
        Parameter("x_f", "1/m", 0.0, -1e7, 1e7, "friction displacement gain"),
        Parameter("F_hz", "N", 0.0, -1e7, 1e7, "displacement-hysteresis amplitude"),
        Parameter("v_hz", "s/m", 100.0, 0.0, 1e7, "displacement-hysteresis velocity gain"),
        Parameter("x_hz", "", 0.0, -1e3, 1e3, "displacement-hysteresis offset"),
        Parameter("F_hv", "N", 0.0, -1e7, 1e7, "velocity-hysteresis amplitude"),
        Parameter("v_hv", "s/m", 100.0, 0.0, 1e7, "velocity-hysteresis velocity gain"),
        Parameter("x_hv", "", 0.0, -1e3, 1e3, "velocity-hysteresis offset"),
        Parameter("c_sa_pos", "N", 0.0, -1e7, 1e7, "force gain of the control, extension"),
        Parameter("c_sa_neg", "N", 0.0, -1e7, 1e7, "force gain of the control, compression"),
        Parameter("v_py", "s/m", 100.0, 0.0, 1e7, "pre-yield velocity gain"),
        Parameter("x_py", "1/m", 0.0, -1e7, 1e7, "pre-yield displacement gain"),
    )

    def control_affine(self, record, values):
        z, v, a = record.displacement, record.velocity, record.acceleration
        ext = v >= 0
        S = sigmoid_ratio
        P = (values["f0"] + np.where(ext, values["c_p_pos"], values["c_p_neg"]) * v + values["k_p"] * z
             + values["m_D"] * a + values["f_f"] * S(values["v_f"] * v + values["x_f"] * z)
             + values["F_hz"] * S(values["v_hz"] * v + values["x_hz"] * np.sign(z))
             + values["F_hv"] * S(values["v_hv"] * v + values["x_hv"] * np.sign(v)))
        return P, ext

    def force(self, record, values):
        P, ext = self.control_affine(record, values)
        u = self.control(record)
        c_sa = np.where(ext, values["c_sa_pos"], values["c_sa_neg"])
        F_sa = u * c_sa * (sigmoid_ratio(values["v_py"] * record.velocity * u)
                           + sigmoid_ratio(values["x_py"] * record.displacement))
        return P + F_sa

    def initial_guess(self, record):
        g = self.defaults()
        if record.force is not None:
            v, F = record.velocity, record.force
            vmax = float(np.max(np.abs(v))) or 1.0
            A = np.column_stack([np.sign(v), v, np.ones_like(v)])
            (fy, c, f0), *_ = np.linalg.lstsq(A, F, rcond=None)
            g.update(f_f=float(fy), c_p_pos=float(max(c, 0.0)), c_p_neg=float(max(c, 0.0)), f0=float(f0),
                     v_f=20.0 / vmax, v_hz=20.0 / vmax, v_hv=20.0 / vmax, v_py=20.0 / vmax)
        return g
