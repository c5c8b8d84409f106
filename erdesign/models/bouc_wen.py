r"""Bouc-Wen family: Bouc-Wen (Spencer), modified Bouc-Wen (Spencer 1997) and the normalised Bouc-Wen model.

The hysteretic variable obeys (Butz and von Stryk 2002, eq 9)

.. math:: \dot z = -\gamma|\dot q| z|z|^{n-1} - \beta\dot q|z|^n + \delta\dot q

for an input q (the piston displacement, or for the modified model the displacement of the Bouc-Wen element).
On each sample step it is solved exactly for the step's travel (closed-form Riccati solution for n = 2, RK4
sub-steps in the travelled distance otherwise; :mod:`erdesign.models._kernels`), so the stiff saturation of z does
not limit the step.

Redundancy: :math:`(\alpha, \beta, \gamma, \delta) \to (\alpha/s, \beta/s^n, \gamma/s^n, \delta s)` gives the same
force for any s > 0, so delta is held at its value (``fitted=False``) when identifying; the normalised model
removes the redundancy by construction.
"""

from __future__ import annotations

import numpy as np

from ._guess import sign_viscous_fit, stroke
from ._kernels import bouc_wen_state, modified_bouc_wen
from .base import FORCE_OFFSET, ControlAffineModel, Model, Parameter

__all__ = ["BoucWen", "BoucWenModified", "BoucWenNormalized", "SPENCER_PASSIVE"]

#: Modified Bouc-Wen parameters of the passive MR damper simulated by Butz and von Stryk (2002, section 4.3),
#: from Spencer et al.: SI units.
SPENCER_PASSIVE = {
    "c0a": 5300.0,
    "c1a": 93000.0,
    "k0": 1400.0,
    "k1": 540.0,
    "alpha_a": 96300.0,
    "beta": 2.0e6,
    "gamma": 2.0e6,
    "n": 2.0,
    "delta": 207.0,
    "x0": 0.0,
}


def _hysteresis_parameters(beta=2e6, gamma=2e6, delta=207.0, n=2.0):
    return (
        Parameter("beta", "1/m^2", beta, -1e12, 1e12, "Bouc-Wen shape parameter beta (units 1/m^n; shown for n = 2)"),
        Parameter("gamma", "1/m^2", gamma, -1e12, 1e12, "Bouc-Wen shape parameter gamma (units 1/m^n)"),
        Parameter("delta", "", delta, 1e-6, 1e9, "Bouc-Wen scale A (redundant with alpha: held fixed)", fitted=False),
        Parameter("n", "", n, 1.0, 10.0, "Bouc-Wen exponent (held fixed by default)", fitted=False),
    )


def _bouc_wen_scales(record, delta):
    """The Bouc-Wen family's starting scales: the damping c0 [N s/m] of the fit F - mean F = f_y sgn v + c0 v, and
    the hysteretic ``alpha_a``, ``beta``, ``gamma`` that make z saturate at about a tenth of the stroke (so that the
    loop is yielded over most of it) with the force f_y."""
    v = record.velocity
    A = np.column_stack([np.sign(v), v])
    (fy, c0), *_ = np.linalg.lstsq(A, record.force - record.force.mean(), rcond=None)
    zs = stroke(record) / 10.0
    return float(c0), {"alpha_a": float(max(fy, 1.0) / zs), "beta": 0.5 * delta / zs**2, "gamma": 0.5 * delta / zs**2}


def _polynomial(coefficients, u):
    """c_0 + c_1 u + c_2 u^2 + ... (coefficients constant first), by Horner's rule."""
    *lower, value = coefficients
    for c in reversed(lower):
        value = c + value * u
    return value


class BoucWen(Model):
    r"""Bouc-Wen damper model (Spencer): dashpot, spring and a Bouc-Wen hysteretic element in parallel.

    .. math::
        F = c_0\dot x + k_0(x - x_0) + \alpha z, \qquad
        \dot z = -\gamma|\dot x| z|z|^{n-1} - \beta\dot x|z|^n + \delta\dot x ,

    with :math:`\alpha = \alpha_a + \alpha_b u` and :math:`c_0 = c_{0a} + c_{0b} u` (Spencer's linear control law).

    Parameters (SI): ``c0a``, ``c0b`` [N s/m], ``k0`` [N/m], ``x0`` [m], ``alpha_a``, ``alpha_b`` [N/m],
    ``beta``, ``gamma`` [1/m^n], ``delta`` [-], ``n`` [-].

    Notes
    -----
    z starts at 0 with the record.  The displacement is taken linear between samples; each step of z is exact.
    Spencer found the model misses the roll-off of the force-velocity loop near zero velocity.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 2001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = BoucWen().simulate(rec)
    >>> z_max = (207 / 4e6) ** 0.5   # saturation of z: (delta / (beta + gamma))^(1/n)
    >>> bool(abs(F[-1] - (5300 * rec.velocity[-1] + 1400 * rec.displacement[-1])) < 96300 * z_max * 1.001)
    True

    References
    ----------
    Butz and von Stryk (2002) eqs 8-9 and 13-15; review (the MR-model review) eqs 15-16.
    """

    name = "bouc_wen"
    title = "Bouc-Wen (Spencer)"
    source = "Butz and von Stryk (2002) eqs 8-9, 13-15; the MR-model review eqs 15-16"
    uses_control = True
    control_parameters = ("c0b", "alpha_b")
    # x0 is not linear: it enters as the product k0 x0
    linear_parameters = ("c0a", "k0", "alpha_a", "c0b", "alpha_b")
    #: Identification does not project by default: with alpha solved at every point, the fit from the guess runs
    #: into the region beta + gamma < 0 (z unbounded, alpha -> 0) on measured records (Quiroz 10 mm 1 Hz 0.5 A:
    #: RSS 2.6 x the plain fit's; docs/identification.md); ``identify(..., projection=True)`` still offers it.
    projection_default = False
    parameters = (
        Parameter("c0a", "N*s/m", 5300.0, 0.0, 1e8, "viscous damping"),
        Parameter("k0", "N/m", 1400.0, 0.0, 1e8, "stiffness of the accumulator (a spring: not negative)"),
        Parameter("x0", "m", 0.0, -1.0, 1.0, "initial displacement of the spring"),
        Parameter("alpha_a", "N/m", 96300.0, 0.0, 1e10, "scale of the hysteretic force"),
        *_hysteresis_parameters(),
        Parameter("c0b", "N*s/m", 0.0, -1e8, 1e8, "viscous damping per unit control"),
        Parameter("alpha_b", "N/m", 0.0, -1e10, 1e10, "hysteretic scale per unit control"),
    )

    def force(self, record, values):
        u = self.control(record)
        z = bouc_wen_state(record.displacement, values["beta"], values["gamma"], values["delta"], values["n"])
        return (
            (values["c0a"] + values["c0b"] * u) * record.velocity
            + values["k0"] * (record.displacement - values["x0"])
            + (values["alpha_a"] + values["alpha_b"] * u) * z
        )

    def linear_terms(self, record, values):
        u, v = self.control(record), record.velocity
        z = bouc_wen_state(record.displacement, values["beta"], values["gamma"], values["delta"], values["n"])
        return {
            "c0a": v,
            "k0": record.displacement - values["x0"],
            "alpha_a": z,
            "c0b": u * v,
            "alpha_b": u * z,
        }, np.zeros_like(v)

    def guess_from_force(self, record):
        c0, hysteresis = _bouc_wen_scales(record, self.parameter("delta").default)
        return {"c0a": max(c0, 0.0), **hysteresis}


class BoucWenModified(Model):
    r"""Modified Bouc-Wen model (Spencer et al. 1997) with the control dependence and first-order filter.

    .. math::
        F = c_1\dot y + k_1(x - x_0), \qquad
        \dot y = \frac{\alpha z + c_0\dot x + k_0(x - y)}{c_0 + c_1},

        \dot z = -\gamma|\dot x - \dot y| z|z|^{n-1} - \beta(\dot x - \dot y)|z|^n + \delta(\dot x - \dot y),

        \alpha = \alpha_a + \alpha_b u_f + \alpha_c u_f^2,\quad c_1 = c_{1a} + c_{1b} u_f,\quad c_0 = c_{0a} + c_{0b} u_f,
        \qquad \dot u_f = -\eta(u_f - u).

    Parameters (SI): ``c0a``, ``c0b``, ``c1a``, ``c1b`` [N s/m], ``k0``, ``k1`` [N/m], ``x0`` [m], ``alpha_a``,
    ``alpha_b``, ``alpha_c`` [N/m], ``beta``, ``gamma`` [1/m^n], ``delta``, ``n`` [-], ``eta`` [1/s].

    Notes
    -----
    Defaults: the passive parameters of Butz and von Stryk (2002) section 4.3 (:data:`SPENCER_PASSIVE`).  The
    quadratic term
    :math:`\alpha_c u_f^2` is not in Butz and von Stryk (2002) (eq 13 is linear in u): it is the saturation of the MR
    yield force
    with coil current used by Quiroz (2022, the UTFSM data of docs/case_studies/quiroz.md); ``alpha_c = 0`` (the
    default) is Spencer's law.  Motion and control are taken linear between samples; the filter is solved exactly, w by
    RK4 sub-steps with z exact along each sub-step (:func:`~erdesign.models._kernels.modified_bouc_wen`, a compiled
    loop), which tests/test_models.py checks against :func:`scipy.integrate.solve_ivp` (LSODA, rtol 1e-10) to 1e-4
    of the force range at 3 kHz.  States start at rest (y = z = 0, u_f = u at the first sample).  Published sets
    (``spencer1997``): :mod:`erdesign.models.published`.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 4001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = BoucWenModified().simulate(rec)
    >>> 500 < float(F.max()) < 1500   # about alpha z_max + c0 v: some 1 kN for Spencer's damper at 63 mm/s
    True

    References
    ----------
    Butz and von Stryk (2002) eqs 10-16 and section 4.3; review (the MR-model review) eqs 17-19.
    """

    name = "bouc_wen_modified"
    title = "modified Bouc-Wen (Spencer 1997)"
    source = "Butz and von Stryk (2002) eqs 10-16, section 4.3 (Spencer et al. 1997); the MR-model review eqs 17-19"
    uses_control = True
    control_parameters = ("c0b", "c1b", "alpha_b", "alpha_c", "eta")
    # only k1: alpha, c0, c1 and k0 enter the state equation of y, and x0 enters as the product k1 x0
    linear_parameters = ("k1",)
    parameters = (
        Parameter("c0a", "N*s/m", 5300.0, 1.0, 1e8, "viscous damping at large velocity", log_scale=True),
        Parameter("c1a", "N*s/m", 93000.0, 1.0, 1e9, "dashpot for the roll-off at low velocity", log_scale=True),
        Parameter("k0", "N/m", 1400.0, 0.0, 1e8, "stiffness at large velocity"),
        Parameter("k1", "N/m", 540.0, 0.0, 1e8, "accumulator stiffness (a spring: not negative)"),
        Parameter("x0", "m", 0.0, -1.0, 1.0, "initial displacement of the accumulator spring"),
        Parameter("alpha_a", "N/m", 96300.0, 0.0, 1e10, "scale of the hysteretic force"),
        *_hysteresis_parameters(),
        Parameter("c0b", "N*s/m", 0.0, -1e8, 1e8, "c0 per unit control"),
        Parameter("c1b", "N*s/m", 0.0, -1e9, 1e9, "c1 per unit control"),
        Parameter("alpha_b", "N/m", 0.0, -1e10, 1e10, "alpha per unit control"),
        Parameter("alpha_c", "N/m", 0.0, -1e10, 1e10, "alpha per unit control squared (saturation; Quiroz 2022)"),
        Parameter("eta", "1/s", 190.0, 1e-3, 1e6, "rate of the first-order control filter", log_scale=True),
    )

    def control_laws(self, values):
        """The coefficients (constant first) of alpha, c0 and c1 as polynomials in the filtered control u_f."""
        return (
            (values["alpha_a"], values["alpha_b"], values["alpha_c"]),
            (values["c0a"], values["c0b"]),
            (values["c1a"], values["c1b"]),
        )

    def states(self, record, values):
        """(filtered control u_f, w = x - y, z) on the record."""
        return modified_bouc_wen(
            record.time,
            record.displacement,
            self.control(record),
            values["eta"],
            *self.control_laws(values),
            values["k0"],
            values["beta"],
            values["gamma"],
            values["delta"],
            values["n"],
        )

    def force(self, record, values):
        uf, w, z = self.states(record, values)
        al, c0, c1 = (_polynomial(coefficients, uf) for coefficients in self.control_laws(values))
        ydot = (al * z + c0 * record.velocity + values["k0"] * w) / (c0 + c1)
        return c1 * ydot + values["k1"] * (record.displacement - values["x0"])

    def linear_terms(self, record, values):
        return {"k1": record.displacement - values["x0"]}, self.force(record, {**values, "k1": 0.0})

    def guess_from_force(self, record):
        c0, hysteresis = _bouc_wen_scales(record, self.parameter("delta").default)
        c0 = max(c0, 10.0)
        return {"c0a": c0, "c1a": c0 * 15, **hysteresis, "k0": 0.0, "k1": 0.0}


class BoucWenNormalized(ControlAffineModel):
    r"""Normalised Bouc-Wen model (Ikhouane-Rodellar form) with control-dependent gains.

    .. math::
        F = k_x x + (k_v + k_{v,u} u)\,\dot x + (k_w + k_{w,u} u)\,w + f_0, \qquad
        \dot w = \rho\left(\dot x - \sigma|\dot x||w|^{n-1}w + (\sigma - 1)\dot x|w|^n\right)

    where w stays in [-1, 1] and the parameters are not redundant (the MR-model review eqs 41-47).

    Parameters (SI): ``k_x`` [N/m], ``k_v``, ``k_v_u`` [N s/m], ``k_w``, ``k_w_u`` [N], ``rho`` [1/m],
    ``sigma`` [-] (>= 1/2 for a bounded, dissipative w), ``n`` [-], ``f0`` [N].

    Notes
    -----
    The force law combines eq 46 (Bahar: elastic, viscous and hysteretic terms) with the linear voltage law of
    Tsouroukdissian / Bahar (eq 47) for :math:`k_{\dot x}` and :math:`k_w`; the source writes :math:`-k_w w`, here
    the sign is absorbed in :math:`k_w` (positive :math:`k_w` dissipates).  The hysteretic state does not depend
    on the control, so the force is affine in u: the model is invertible in closed form (the MR-model review Table 1,
    "modified normalized Bouc-Wen: invertible"; :mod:`erdesign.identification.inverse`).  Solved with the Bouc-Wen
    kernel with
    :math:`\beta = \rho(1-\sigma)`, :math:`\gamma = \rho\sigma`, :math:`\delta = \rho` (in w).

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 2001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> m = BoucWenNormalized(); w = m.hysteretic_state(rec, m.defaults())
    >>> bool(np.max(np.abs(w)) <= 1.0 + 1e-9)
    True

    References
    ----------
    Review (the MR-model review) eqs 41-47 (Ikhouane and Rodellar; Tsouroukdissian; Bahar).
    """

    name = "bouc_wen_normalized"
    title = "normalised Bouc-Wen (Ikhouane-Rodellar)"
    source = "the MR-model review eqs 41-47"
    uses_control = True
    control_parameters = ("k_v_u", "k_w_u")
    linear_parameters = ("k_x", "k_v", "k_w", "f0", "k_v_u", "k_w_u")
    parameters = (
        Parameter("k_x", "N/m", 0.0, 0.0, 1e8, "stiffness (a spring: not negative)"),
        Parameter("k_v", "N*s/m", 5000.0, 0.0, 1e8, "viscous damping"),
        Parameter("k_w", "N", 500.0, 0.0, 1e7, "hysteretic force amplitude"),
        Parameter("rho", "1/m", 1000.0, 1e-3, 1e7, "rate of the normalised state", log_scale=True),
        Parameter("sigma", "", 1.0, 0.5, 50.0, "shape of the loop (>= 1/2)"),
        Parameter("n", "", 1.0, 1.0, 10.0, "exponent (held fixed by default)", fitted=False),
        FORCE_OFFSET,
        Parameter("k_v_u", "N*s/m", 0.0, -1e8, 1e8, "viscous damping per unit control"),
        Parameter("k_w_u", "N", 0.0, -1e7, 1e7, "hysteretic amplitude per unit control"),
    )

    def hysteretic_state(self, record, values):
        """The normalised state w on the record (|w| <= 1)."""
        rho, sigma = values["rho"], values["sigma"]
        return bouc_wen_state(record.displacement, rho * (1.0 - sigma), rho * sigma, rho, values["n"])

    def control_affine(self, record, values):
        """(P, Q) with F = P + Q u at every sample (the inverse model uses it)."""
        w = self.hysteretic_state(record, values)
        v = record.velocity
        P = values["k_x"] * record.displacement + values["k_v"] * v + values["k_w"] * w + values["f0"]
        Q = values["k_v_u"] * v + values["k_w_u"] * w
        return P, Q

    def linear_terms(self, record, values):
        w = self.hysteretic_state(record, values)
        u, v = self.control(record), record.velocity
        return {
            "k_x": record.displacement,
            "k_v": v,
            "k_w": w,
            "f0": np.ones_like(v),
            "k_v_u": u * v,
            "k_w_u": u * w,
        }, np.zeros_like(v)

    def guess_from_force(self, record):
        fy, c0, f0 = sign_viscous_fit(record)
        return {"k_v": max(c0, 0.0), "k_w": max(fy, 0.0), "f0": f0, "rho": 10.0 / stroke(record)}
