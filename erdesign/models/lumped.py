r"""Models with an internal mass: Sims' lumped-parameter model of the fluid flow and Bass's hyperbolic-tangent
model (the MR-model review sections 5.4 and 8.1).

Both move an internal mass through springs and dampers driven by the piston; the equations of motion are solved by
implicit-midpoint sub-steps (:func:`erdesign.models._kernels.mass_on_damper`, compiled), which stay stable however
stiff the damper (a small fluid mass or a steep pre-yield branch).
"""

from __future__ import annotations

import numpy as np

from ._guess import force_scales
from ._kernels import mass_on_damper
from .base import FORCE_OFFSET, Model, Parameter

__all__ = ["SimsLumped", "Bass"]


class SimsLumped(Model):
    r"""Sims' lumped-parameter model of the fluid flow: fluid inertia and compressibility in series with a
    quasi-steady biviscous valve, current laws in tanh.

    .. math::
        m_1\ddot x_1 = k(x - x_1) - \psi(\dot x_1, u),\qquad F = k(x - x_1) + m_2\ddot x + f_0,

        \psi = \operatorname{sgn}(\dot x_1)\min(C_{pre}|\dot x_1|,\ C_{post}|\dot x_1| + F_y),\quad
        C_{pre} = C_{pre,a} + C_{pre,b}\tanh(C_{pre,c}u)

    and the same tanh laws for :math:`C_{post}` and :math:`F_y`.

    Parameters (SI): ``k`` [N/m] (fluid compressibility), ``m1`` [kg] (fluid inertia), ``m2`` [kg] (piston and
    fittings), ``C_pre_a``, ``C_pre_b``, ``C_post_a``, ``C_post_b`` [N s/m], ``F_y_a``, ``F_y_b``, ``f0`` [N],
    ``C_pre_c``, ``C_post_c``, ``F_y_c`` [-].

    Notes
    -----
    Eq 64 switches branches at :math:`\dot x = F_y/C_{pre}`, where the pre-yield force :math:`F_y` and the
    post-yield force :math:`C_{post}F_y/C_{pre} + F_y` differ: a jump.  The continuous biviscous law of eq 60
    (switch at :math:`F_y/(C_{pre} - C_{post})`, the min form above) is used.  Eq 63 writes the input as the force;
    the damper is driven by its displacement here (the force is the output).  With :math:`m_1 = 0` and a stiff
    spring the force is the quasi-steady biviscous law :math:`\psi(\dot x)`.

    References
    ----------
    Review (the MR-model review) eqs 63-65, section 5.4 (Sims et al.).
    """

    name = "sims_lumped"
    title = "lumped-parameter fluid-flow model (Sims)"
    source = "the MR-model review eqs 63-65 (Table 1: eq 59; Sims et al.)"
    uses_control = True
    control_parameters = ("C_pre_b", "C_pre_c", "C_post_b", "C_post_c", "F_y_b", "F_y_c")
    linear_parameters = ("m2", "f0")
    parameters = (
        Parameter("k", "N/m", 5e6, 1.0, 1e12, "fluid compressibility stiffness", log_scale=True),
        Parameter("m1", "kg", 0.0, 0.0, 1e5, "fluid inertia"),
        Parameter("m2", "kg", 0.0, -1e5, 1e5, "piston and fittings mass"),
        Parameter("C_pre_a", "N*s/m", 1e6, 1.0, 1e10, "pre-yield damping at zero control", log_scale=True),
        Parameter("C_post_a", "N*s/m", 5000.0, 0.0, 1e9, "post-yield damping at zero control"),
        Parameter("F_y_a", "N", 500.0, 0.0, 1e7, "yield force at zero control"),
        FORCE_OFFSET,
        Parameter("C_pre_b", "N*s/m", 0.0, -1e10, 1e10, "saturating change of the pre-yield damping"),
        Parameter("C_pre_c", "", 1.0, 0.0, 1e3, "rate of the pre-yield damping law"),
        Parameter("C_post_b", "N*s/m", 0.0, -1e9, 1e9, "saturating change of the post-yield damping"),
        Parameter("C_post_c", "", 1.0, 0.0, 1e3, "rate of the post-yield damping law"),
        Parameter("F_y_b", "N", 0.0, -1e7, 1e7, "saturating change of the yield force"),
        Parameter("F_y_c", "", 1.0, 0.0, 1e3, "rate of the yield force law"),
    )

    def laws(self, record, values):
        """(C_pre, C_post, F_y) per sample (eq 65)."""
        u = self.control(record)

        def law(p):
            return values[f"{p}_a"] + values[f"{p}_b"] * np.tanh(values[f"{p}_c"] * u)

        C_post = np.maximum(law("C_post"), 0.0)
        return np.maximum(law("C_pre"), C_post + 1e-9), C_post, np.maximum(law("F_y"), 0.0)

    def linear_terms(self, record, values):
        C_pre, C_post, F_y = self.laws(record, values)
        x = record.displacement - record.displacement[0]
        x1, _ = mass_on_damper(record.time, x, m=values["m1"], k1=values["k"], C_pre=C_pre, C_post=C_post, F_y=F_y)
        return {"m2": record.acceleration, "f0": np.ones_like(x)}, values["k"] * (x - x1)

    def force(self, record, values):
        cols, rest = self.linear_terms(record, values)
        return rest + values["m2"] * cols["m2"] + values["f0"]

    def guess_from_force(self, record):
        fy, c, f0, X, vmax = force_scales(record, min_damping=1.0)
        return dict(F_y_a=fy, C_post_a=c, f0=f0, C_pre_a=fy / (0.05 * vmax) + c, k=50.0 * fy / X)


class Bass(Model):
    r"""Bass's hyperbolic-tangent model: two spring-dashpot pairs joined by a mass that slides with a smoothed
    Coulomb friction.

    .. math::
        m_0\ddot x_0 = k_1(x - x_0) + c_1(\dot x - \dot x_0) - k_0x_0 - c_0\dot x_0
                      - f_0\tanh(\dot x_0/V_{ref}),\qquad
        F = k_1(x - x_0) + c_1(\dot x - \dot x_0)

    with :math:`f_0 = f_{0} + f_{0,u}u` (the yield force; the source makes its parameters polynomials in the
    current).

    Parameters (SI): ``k0``, ``k1`` [N/m], ``c0``, ``c1`` [N s/m], ``m0`` [kg], ``f_y``, ``f_y_u`` [N] (the
    source's f0, the yield force), ``v_ref`` [m/s].

    Notes
    -----
    Eq 93 adds :math:`+f_0\tanh(\dot x_0/V_{ref})/m_0`: a friction force along the mass's velocity, which feeds
    energy in.  The review describes the mass as resisting motion through Coulomb friction, so the term opposes the
    velocity (minus sign), as used.  With :math:`f_0 = 0` the model is linear: at steady harmonic motion its
    complex stiffness is :math:`(k_1 + i\omega c_1)(k_0 - m_0\omega^2 + i\omega c_0)/(k_0 + k_1 - m_0\omega^2 +
    i\omega(c_0 + c_1))`.

    References
    ----------
    Review (the MR-model review) eqs 93-94, section 8.1 (Bass).
    """

    name = "bass"
    title = "Bass hyperbolic-tangent model"
    source = "the MR-model review eqs 93-94 (Table 1: eqs 87-88; Bass)"
    uses_control = True
    control_parameters = ("f_y_u",)
    parameters = (
        Parameter("k0", "N/m", 1e3, 0.0, 1e10, "post-yield spring (mass to body)"),
        Parameter("c0", "N*s/m", 5000.0, 0.0, 1e9, "post-yield dashpot (mass to body)"),
        Parameter("k1", "N/m", 5e5, 1.0, 1e11, "pre-yield spring (piston to mass)", log_scale=True),
        Parameter("c1", "N*s/m", 2e4, 0.0, 1e9, "pre-yield dashpot (piston to mass)"),
        Parameter("m0", "kg", 1.0, 0.0, 1e5, "inertial mass of fluid and piston"),
        Parameter("f_y", "N", 500.0, 0.0, 1e7, "yield (friction) force of the mass"),
        Parameter("v_ref", "m/s", 0.005, 1e-7, 10.0, "reference velocity of the tanh transition", log_scale=True),
        Parameter("f_y_u", "N", 0.0, -1e7, 1e7, "yield force per unit control"),
    )

    def states(self, record, values):
        """(x0, dx0/dt) of the mass [m], [m/s]."""
        u = self.control(record)
        fy = values["f_y"] + values["f_y_u"] * u
        x = record.displacement - record.displacement[0]
        return mass_on_damper(
            record.time,
            x,
            m=values["m0"],
            k1=values["k1"],
            c1=values["c1"],
            k0=values["k0"],
            c=values["c0"],
            f_t=np.maximum(fy, 0.0),
            v_ref=values["v_ref"],
        )

    def force(self, record, values):
        x0, v0 = self.states(record, values)
        x = record.displacement - record.displacement[0]
        return values["k1"] * (x - x0) + values["c1"] * (record.velocity - v0)

    def guess_from_force(self, record):
        fy, c, _, X, vmax = force_scales(record, min_damping=1.0)
        return dict(f_y=fy, c0=c, k1=20.0 * fy / X, c1=5.0 * c, v_ref=vmax / 50.0)
