r"""Dynamic friction models of the MR damper: Dahl (modified), viscous Dahl, LuGre and Sakai's modified LuGre.

Their internal states obey equations linear in the state for a given motion, so on a step where the displacement
changes linearly they have exact solutions, and the whole record is one affine recurrence solved by a prefix scan
(:func:`erdesign.models._kernels.dahl_state`, :func:`lugre_state`): no loop per sample.
"""

from __future__ import annotations

import numpy as np

from ..numerics import affine_recurrence
from ._guess import force_scales
from ._kernels import dahl_state
from .base import FORCE_OFFSET, ControlAffineModel, Model, Parameter

__all__ = ["Dahl", "DahlViscous", "LuGre", "LuGreModified", "lugre_state", "DahlAsymmetric"]


def lugre_state(x, kappa, z0=0.0):
    r"""Bristle deflection of the LuGre model, :math:`\dot z = \dot x - \kappa|\dot x| z`, [m].

    On a step with direction s and travel :math:`|\Delta x|` (``kappa`` [1/m] one value per step or a scalar),

    .. math:: z_{n+1} = z_n e^{-\kappa|\Delta x|} + s\,\frac{1 - e^{-\kappa|\Delta x|}}{\kappa}

    exactly (the second term tends to :math:`\Delta x` as :math:`\kappa \to 0`).

    Examples
    --------
    The deflection saturates at 1/kappa:

    >>> import numpy as np
    >>> round(float(lugre_state(np.linspace(0, 1, 101), 100.0)[-1]), 9)
    0.01
    """
    dx = np.diff(np.asarray(x, dtype=float))
    kappa = np.broadcast_to(np.asarray(kappa, dtype=float), dx.shape)
    L = np.abs(dx)
    e = np.exp(-kappa * L)
    with np.errstate(invalid="ignore", divide="ignore"):
        gain = np.where(kappa * L > 1e-12, -np.expm1(-kappa * L) / np.where(kappa == 0, 1.0, kappa), L)
    return affine_recurrence(e, np.sign(dx) * gain, z0)


class Dahl(Model):
    r"""Modified Dahl model (Zhou et al.): spring, dashpot and a Dahl friction element in parallel.

    .. math:: F = k_0 x + c_0\dot x + f_d z + f_0, \qquad \dot z = \rho(\dot x - |\dot x| z),
              \qquad f_d = f_{d,0} + f_{d,u}u

    Parameters (SI): ``k0`` [N/m], ``c0`` [N s/m], ``f_d``, ``f_d_u``, ``f0`` [N], ``rho`` [1/m].

    Notes
    -----
    z is dimensionless and bounded by 1; its step is exact (:func:`~erdesign.models._kernels.dahl_state`).  The
    source writes :math:`- f_0`; the sign is absorbed in f0.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 401); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = Dahl().simulate(rec, {"k0": 0.0, "c0": 0.0, "f_d": 500.0, "rho": 1e4})
    >>> round(float(F.max()), 3)
    500.0

    References
    ----------
    Review (the MR-model review) eqs 103-104 (Dahl; modified Dahl of Zhou et al.).
    """

    name = "dahl"
    title = "modified Dahl (Zhou)"
    source = "the MR-model review eqs 103-104"
    uses_control = True
    control_parameters = ("f_d_u",)
    linear_parameters = ("k0", "c0", "f_d", "f0", "f_d_u")
    parameters = (
        Parameter("k0", "N/m", 0.0, 0.0, 1e8, "stiffness (a spring: not negative)"),
        Parameter("c0", "N*s/m", 2000.0, 0.0, 1e8, "viscous damping"),
        Parameter("f_d", "N", 500.0, 0.0, 1e7, "Coulomb (Dahl) force"),
        Parameter("rho", "1/m", 1000.0, 1e-2, 1e8, "Dahl rate (1 / pre-sliding displacement)", log_scale=True),
        Parameter("f0", "N", 0.0, -1e7, 1e7, "force offset (seals, bias)"),
        Parameter("f_d_u", "N", 0.0, -1e7, 1e7, "Coulomb force per unit control"),
    )

    def force(self, record, values):
        z = dahl_state(record.displacement, values["rho"])
        fd = values["f_d"] + values["f_d_u"] * self.control(record)
        return values["k0"] * record.displacement + values["c0"] * record.velocity + fd * z + values["f0"]

    def linear_terms(self, record, values):
        z = dahl_state(record.displacement, values["rho"])
        v = record.velocity
        return {
            "k0": record.displacement,
            "c0": v,
            "f_d": z,
            "f0": np.ones_like(v),
            "f_d_u": self.control(record) * z,
        }, np.zeros_like(v)

    def guess_from_force(self, record):
        fy, c, f0, X, _ = force_scales(record)
        return dict(f_d=fy, c0=c, f0=f0, rho=20.0 / X)


class DahlViscous(ControlAffineModel):
    r"""Viscous Dahl model (Ikhouane et al.): viscous term plus a Dahl state, gains linear in the control.

    .. math:: F = (k_x + k_{x,u}u)\,\dot x + (k_w + k_{w,u}u)\,w + f_0, \qquad \dot w = \rho(\dot x - |\dot x| w)

    Parameters (SI): ``k_x``, ``k_x_u`` [N s/m], ``k_w``, ``k_w_u``, ``f0`` [N], ``rho`` [1/m].

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 401); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> bool(np.all(np.isfinite(DahlViscous().simulate(rec))))
    True

    References
    ----------
    Review (the MR-model review) eq 105 with the Dahl state of eq 103 (Ikhouane and Dyke; Table 1: "viscous Dahl, voltage").
    """

    name = "dahl_viscous"
    title = "viscous Dahl (Ikhouane)"
    source = "the MR-model review eqs 103, 105"
    uses_control = True
    control_parameters = ("k_x_u", "k_w_u")
    linear_parameters = ("k_x", "k_w", "f0", "k_x_u", "k_w_u")
    parameters = (
        Parameter("k_x", "N*s/m", 2000.0, 0.0, 1e8, "viscous coefficient"),
        Parameter("k_w", "N", 500.0, 0.0, 1e7, "friction coefficient"),
        Parameter("rho", "1/m", 1000.0, 1e-2, 1e8, "Dahl rate", log_scale=True),
        FORCE_OFFSET,
        Parameter("k_x_u", "N*s/m", 0.0, -1e8, 1e8, "viscous coefficient per unit control"),
        Parameter("k_w_u", "N", 0.0, -1e7, 1e7, "friction coefficient per unit control"),
    )

    def control_affine(self, record, values):
        w = dahl_state(record.displacement, values["rho"])
        v = record.velocity
        return values["k_x"] * v + values["k_w"] * w + values["f0"], values["k_x_u"] * v + values["k_w_u"] * w

    def guess_from_force(self, record):
        fy, c, f0, X, _ = force_scales(record)
        return dict(k_w=fy, k_x=c, f0=f0, rho=20.0 / X)


class LuGre(Model):
    r"""LuGre dynamic friction model (Canudas de Wit et al.) of the MR damper.

    .. math:: F = \sigma_0 z + \sigma_1\dot z + \sigma_2\dot x + f_0, \qquad \dot z = \dot x - \sigma_0 a_0|\dot x| z

    Parameters (SI): ``sigma0`` [N/m], ``sigma1``, ``sigma2`` [N s/m], ``a0`` [1/N], ``f0`` [N].

    Notes
    -----
    :math:`1/a_0` is the sliding friction force (z saturates at :math:`1/(\sigma_0 a_0)`).  Exact steps
    (:func:`lugre_state`); :math:`\dot z` at the samples from the state equation.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 2001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = LuGre().simulate(rec, {"sigma0": 1e7, "sigma1": 0.0, "sigma2": 0.0, "a0": 1 / 500})
    >>> round(float(F.max()), 2)
    500.0

    References
    ----------
    Review (the MR-model review) eq 57 (section 4).
    """

    name = "lugre"
    title = "LuGre"
    source = "the MR-model review eq 57"
    # sigma0 is not linear: it sets the state's rate kappa = sigma0 a0 as well
    linear_parameters = ("sigma1", "sigma2", "f0")
    parameters = (
        Parameter("sigma0", "N/m", 1e6, 1.0, 1e11, "bristle stiffness", log_scale=True),
        Parameter("sigma1", "N*s/m", 0.0, 0.0, 1e8, "bristle damping"),
        Parameter("sigma2", "N*s/m", 2000.0, 0.0, 1e8, "viscous damping"),
        Parameter("a0", "1/N", 2e-3, 1e-9, 1.0, "inverse of the sliding friction force", log_scale=True),
        FORCE_OFFSET,
    )

    def force(self, record, values):
        kappa = values["sigma0"] * values["a0"]
        z = lugre_state(record.displacement, kappa)
        v = record.velocity
        zd = v - kappa * np.abs(v) * z
        return values["sigma0"] * z + values["sigma1"] * zd + values["sigma2"] * v + values["f0"]

    def linear_terms(self, record, values):
        kappa = values["sigma0"] * values["a0"]
        z = lugre_state(record.displacement, kappa)
        v = record.velocity
        return ({"sigma1": v - kappa * np.abs(v) * z, "sigma2": v, "f0": np.ones_like(v)}, values["sigma0"] * z)

    def guess_from_force(self, record):
        fy, c, f0, X, _ = force_scales(record)
        return dict(a0=1.0 / fy, sigma2=c, f0=f0, sigma0=fy * 20.0 / X)


class LuGreModified(ControlAffineModel):
    r"""Sakai's modified LuGre model: field-dependent and invertible.

    .. math::
        F = \sigma_0 z u + \sigma_1\dot z + \sigma_2\dot x + \sigma_a z + \sigma_b\dot x u + f_0, \qquad
        \dot z = \dot x - \sigma_0 a_0|\dot x| z(1 + a_1 u)

    Parameters (SI): ``sigma0``, ``sigma_a`` [N/m], ``sigma1``, ``sigma2``, ``sigma_b`` [N s/m], ``a0`` [1/N],
    ``a1`` [-], ``f0`` [N]; u is the dimensionless control.

    Notes
    -----
    Needs a control column (the hysteretic force is proportional to it).  At each step the force is affine in u
    (:meth:`control_affine`), which gives the inverse model used by :mod:`erdesign.identification.inverse`.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 401)
    >>> rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t), control=1.0, control_kind="voltage")
    >>> bool(np.all(np.isfinite(LuGreModified().simulate(rec))))
    True

    References
    ----------
    Review (the MR-model review) eqs 58-59 (Alvarez and Jimenez; Sakai et al.), Table 1: invertible.
    """

    name = "lugre_modified"
    title = "modified LuGre (Sakai)"
    source = "the MR-model review eqs 58-59"
    uses_control = True
    requires_control = True
    linear_parameters = ("sigma1", "sigma2", "sigma_a", "sigma_b", "f0")
    parameters = (
        Parameter("sigma0", "N/m", 1e6, 1.0, 1e11, "bristle stiffness (per unit control in the force)", log_scale=True),
        Parameter("sigma1", "N*s/m", 0.0, 0.0, 1e8, "bristle damping"),
        Parameter("sigma2", "N*s/m", 2000.0, 0.0, 1e8, "viscous damping"),
        Parameter("sigma_a", "N/m", 0.0, -1e11, 1e11, "control-independent bristle stiffness"),
        Parameter("sigma_b", "N*s/m", 0.0, -1e8, 1e8, "viscous damping per unit control"),
        Parameter("a0", "1/N", 2e-3, 1e-9, 1.0, "inverse friction force scale", log_scale=True),
        Parameter("a1", "", 0.0, -0.99, 1e3, "control dependence of the saturation"),
        FORCE_OFFSET,
    )

    def state(self, record, values, u=None):
        u = self.control(record) if u is None else u
        kappa = values["sigma0"] * values["a0"] * (1.0 + values["a1"] * u)
        return lugre_state(record.displacement, np.maximum(kappa[:-1], 0.0)), kappa

    def control_affine(self, record, values, z):
        """(P, Q) with F = P + Q u at each sample, for the state z (the inverse model steps z itself)."""
        v = record.velocity
        k0 = values["sigma0"] * values["a0"]
        P = values["sigma1"] * (v - k0 * np.abs(v) * z) + values["sigma2"] * v + values["sigma_a"] * z + values["f0"]
        Q = values["sigma0"] * z + values["sigma_b"] * v - values["sigma1"] * k0 * values["a1"] * np.abs(v) * z
        return P, Q

    def force(self, record, values):
        u = self.control(record)
        z, _ = self.state(record, values, u)
        P, Q = self.control_affine(record, values, z)
        return P + Q * u

    def guess_from_force(self, record):
        fy, c, f0, X, _ = force_scales(record)
        umax = float(np.max(np.abs(self.control(record)))) or 1.0
        return dict(a0=1.0 / fy, sigma2=c, f0=f0, sigma0=fy * 20.0 / X / umax)


class DahlAsymmetric(ControlAffineModel):
    r"""Asymmetric Dahl model (Garcia et al.): the viscous Dahl model with coefficients that differ with the sign
    of the velocity and of the Dahl state.

    .. math:: F = k_x\dot x + k_w w + f_0,\qquad
              k_x = \begin{cases}k_{x1} & \dot x \ge 0\\ k_{x2} & \dot x < 0\end{cases},\
              k_w = \begin{cases}k_{w1} & w \ge 0\\ k_{w2} & w < 0\end{cases},\qquad \dot w = \rho(\dot x - |\dot x|w)

    with the voltage laws of the viscous Dahl model added to both branches: :math:`k_x + k_{x,u}u`,
    :math:`k_w + k_{w,u}u`.

    Parameters (SI): ``k_x1``, ``k_x2``, ``k_x_u`` [N s/m], ``k_w1``, ``k_w2``, ``k_w_u``, ``f0`` [N], ``rho``
    [1/m].

    Notes
    -----
    Equal branch coefficients give the viscous Dahl model (``dahl_viscous``).  The Dahl state does not depend on
    the control, so the force is affine in it and the inverse is explicit.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 401); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> bool(np.allclose(DahlAsymmetric().simulate(rec, {"k_x2": 2000.0, "k_w2": 500.0}),
    ...                  DahlViscous().simulate(rec)))
    True

    References
    ----------
    Review (the MR-model review) eqs 105-106, section 10.3 (Garcia et al.).
    """

    name = "dahl_asymmetric"
    title = "asymmetric Dahl (Garcia)"
    source = "the MR-model review eqs 105-106 (Table 1: eqs 99-100; Garcia et al.)"
    uses_control = True
    control_parameters = ("k_x_u", "k_w_u")
    linear_parameters = ("k_x1", "k_x2", "k_w1", "k_w2", "f0", "k_x_u", "k_w_u")
    parameters = (
        Parameter("k_x1", "N*s/m", 2000.0, 0.0, 1e8, "viscous coefficient, positive velocity"),
        Parameter("k_x2", "N*s/m", 1500.0, 0.0, 1e8, "viscous coefficient, negative velocity"),
        Parameter("k_w1", "N", 500.0, 0.0, 1e7, "friction coefficient, positive state"),
        Parameter("k_w2", "N", 400.0, 0.0, 1e7, "friction coefficient, negative state"),
        Parameter("rho", "1/m", 1000.0, 1e-2, 1e8, "Dahl rate", log_scale=True),
        FORCE_OFFSET,
        Parameter("k_x_u", "N*s/m", 0.0, -1e8, 1e8, "viscous coefficient per unit control"),
        Parameter("k_w_u", "N", 0.0, -1e7, 1e7, "friction coefficient per unit control"),
    )

    def linear_terms(self, record, values):
        v = record.velocity
        w = dahl_state(record.displacement, values["rho"])
        pos_v, pos_w = v >= 0, w >= 0
        u = self.control(record)
        return {
            "k_x1": v * pos_v,
            "k_x2": v * ~pos_v,
            "k_w1": w * pos_w,
            "k_w2": w * ~pos_w,
            "f0": np.ones_like(v),
            "k_x_u": u * v,
            "k_w_u": u * w,
        }, np.zeros_like(v)

    def control_affine(self, record, values):
        cols, _ = self.linear_terms(record, values)
        P = sum(values[k] * cols[k] for k in ("k_x1", "k_x2", "k_w1", "k_w2", "f0"))
        v = record.velocity
        w = cols["k_w1"] + cols["k_w2"]
        return P, values["k_x_u"] * v + values["k_w_u"] * w

    def guess_from_force(self, record):
        g = DahlViscous().guess_from_force(record)
        return dict(k_x1=g["k_x"], k_x2=g["k_x"], k_w1=g["k_w"], k_w2=g["k_w"], rho=g["rho"], f0=g["f0"])
