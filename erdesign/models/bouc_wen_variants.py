r"""The Bouc-Wen variants of the MR-model review's catalogue (its section 3): shear mode, mass element and
shear-thinning damping, amplitude dependence, the current-dependent models of Dominguez et al., the asymmetric
sigmoid current function of Ma et al., Kwok's nonsymmetrical operator, the normalised phenomenological and
restructured models of Bai et al. and the normalised model of Dominguez et al.

All use the kernels of :mod:`erdesign.models._kernels` (the exact Bouc-Wen step and Spencer's modified Bouc-Wen
loop) or are explicit (Dominguez's tanh solution).
"""

from __future__ import annotations

import numpy as np

from ._guess import force_scales
from ._kernels import bouc_wen_state, bouc_wen_state_varying, modified_bouc_wen
from .base import FORCE_OFFSET, LinearTermsModel, Model, Parameter
from .bouc_wen import BoucWen, BoucWenModified, _hysteresis_parameters
from .excitation import record_amplitude, record_frequency

__all__ = [
    "BoucWenAmplitude",
    "BoucWenAsymmetricSigmoid",
    "BoucWenDominguez",
    "BoucWenDominguezCFA",
    "BoucWenMass",
    "BoucWenModifiedMass",
    "BoucWenModifiedNormalized",
    "BoucWenNonsymmetric",
    "BoucWenNormalizedII",
    "BoucWenRestructured",
    "BoucWenShear",
    "sigmoid_gain",
    "sign_time_integral",
]


def sigmoid_gain(u, k2, a2, I0):
    r"""The asymmetric sigmoid current function of Ma et al. (the MR-model review eq 35; Balamurgan's voltage
    function, eq 92): :math:`1 + k_2/(1 + e^{-a_2(u + I_0)}) - k_2/(1 + e^{-a_2 I_0})`, 1 at u = 0, rising to
    :math:`1 + k_2 - k_2/(1 + e^{-a_2 I_0})` for large u.

    >>> round(float(sigmoid_gain(0.0, 2.0, 3.0, -1.0)), 12)
    1.0
    """
    u = np.asarray(u, dtype=float)
    return 1.0 + k2 / (1.0 + np.exp(-a2 * (u + I0))) - k2 / (1.0 + np.exp(-a2 * I0))


def sign_time_integral(t, x):
    r""":math:`\int_{t_0}^{t}\operatorname{sgn}x\,dt` at the samples, exact for x linear between samples.

    >>> import numpy as np
    >>> sign_time_integral(np.array([0.0, 1.0, 2.0]), np.array([-1.0, 1.0, 1.0])).tolist()
    [0.0, 0.0, 1.0]
    """
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    h = np.diff(t)
    s0, s1 = np.sign(x[:-1]), np.sign(x[1:])
    with np.errstate(divide="ignore", invalid="ignore"):
        frac = np.where(s0 * s1 < 0, x[:-1] / (x[:-1] - x[1:]), 0.5)
    step = np.where(s0 == s1, s0 * h, np.where(s0 * s1 < 0, (s0 * frac + s1 * (1.0 - frac)) * h, 0.5 * (s0 + s1) * h))
    return np.concatenate([[0.0], np.cumsum(step)])


class BoucWenShear(BoucWen):
    r"""Bouc-Wen model of a shear-mode damper (Yi et al.): a dashpot and a Bouc-Wen element, no spring.

    .. math:: F = c_0\dot x + \alpha z, \qquad \dot z = -\gamma|\dot x|z|z|^{n-1} - \beta\dot x|z|^n + A\dot x

    with :math:`\alpha = \alpha_a + \alpha_b u`, :math:`c_0 = c_{0a} + c_{0b}u`.

    Notes
    -----
    The standard Bouc-Wen model (``bouc_wen``) without the accumulator spring (k0 = 0, x0 = 0).

    References
    ----------
    Review (the MR-model review) eqs 15 and 22, section 3.3 (Yi et al.).
    """

    name = "bouc_wen_shear"
    title = "Bouc-Wen, shear-mode damper (Yi)"
    source = "the MR-model review eqs 15, 22 (Yi et al.)"
    linear_parameters = ("c0a", "alpha_a", "c0b", "alpha_b")
    parameters = tuple(p for p in BoucWen.parameters if p.name not in ("k0", "x0"))

    def force(self, record, values):
        return super().force(record, {**values, "k0": 0.0, "x0": 0.0})

    def linear_terms(self, record, values):
        cols, rest = super().linear_terms(record, {**values, "k0": 0.0, "x0": 0.0})
        return {k: cols[k] for k in self.linear_parameters}, rest


class BoucWenMass(LinearTermsModel):
    r"""Bouc-Wen model with a mass element and shear-thinning post-yield damping (Yang et al.).

    .. math::
        F = m\ddot x + c_0(\dot x)\dot x + k x + \alpha z + f_0, \qquad
        c_0(\dot x) = a_1 e^{-(a_2|\dot x|)^p},

    z from the Bouc-Wen equation (eq 15); :math:`\alpha = \alpha_a + \alpha_u u`, :math:`a_1 = a_{1} + a_{1,u}u`.

    Parameters (SI): ``m`` [kg], ``a1``, ``a1_u`` [N s/m], ``a2`` [s/m], ``p`` [-], ``k`` [N/m], ``alpha``,
    ``alpha_u`` [N/m], the Bouc-Wen shape ``beta``, ``gamma`` [1/m^n], ``delta`` (A), ``n`` [-], ``f0`` [N].

    Notes
    -----
    :math:`a_2 = 0` makes the damping constant: the standard Bouc-Wen model with a mass element (eq 25).  The
    post-yield damping coefficient decreases monotonically with the speed (shear thinning), which gives the roll-off
    of the force at low velocity the source describes.  The mass and the damping enter linearly.

    References
    ----------
    Review (the MR-model review) eqs 23-25, section 3.4 (Yang et al.).
    """

    name = "bouc_wen_mass"
    title = "Bouc-Wen with mass and shear-thinning damping (Yang)"
    source = "the MR-model review eqs 23-25 (Yang et al.)"
    uses_control = True
    control_parameters = ("alpha_u", "a1_u")
    linear_parameters = ("m", "k", "alpha", "f0", "alpha_u")
    parameters = (
        Parameter("m", "kg", 0.0, -1e5, 1e5, "equivalent mass (stiction and fluid inertia)"),
        Parameter("a1", "N*s/m", 5000.0, 0.0, 1e8, "post-yield damping at zero speed"),
        Parameter("a2", "s/m", 10.0, 0.0, 1e6, "shear-thinning rate (0: constant damping, eq 25)"),
        Parameter("p", "", 1.0, 0.1, 5.0, "shear-thinning exponent"),
        Parameter("k", "N/m", 0.0, 0.0, 1e8, "accumulator stiffness (a spring: not negative)"),
        Parameter("alpha", "N/m", 96300.0, 0.0, 1e10, "scale of the hysteretic force"),
        *_hysteresis_parameters(),
        Parameter("f0", "N", 0.0, -1e7, 1e7, "friction of the seals and bias"),
        Parameter("alpha_u", "N/m", 0.0, -1e10, 1e10, "hysteretic scale per unit control"),
        Parameter("a1_u", "N*s/m", 0.0, -1e8, 1e8, "damping per unit control"),
    )

    def damping(self, record, values):
        """The shear-thinning damping coefficient c0(v) [N s/m] per sample (eq 24)."""
        a1 = values["a1"] + values["a1_u"] * self.control(record)
        return a1 * np.exp(-((values["a2"] * np.abs(record.velocity)) ** values["p"]))

    def linear_terms(self, record, values):
        z = bouc_wen_state(record.displacement, values["beta"], values["gamma"], values["delta"], values["n"])
        u = self.control(record)
        rest = self.damping(record, values) * record.velocity
        return {
            "m": record.acceleration,
            "k": record.displacement,
            "alpha": z,
            "f0": np.ones_like(z),
            "alpha_u": u * z,
        }, rest

    def guess_from_force(self, record):
        fy, c0, f0, X, _ = force_scales(record)
        zs = X / 10.0
        d = self.parameter("delta").default
        return dict(a1=c0, a2=0.0, f0=f0, alpha=fy / zs, beta=0.5 * d / zs**2, gamma=0.5 * d / zs**2)


class BoucWenModifiedMass(BoucWenModified):
    r"""Modified Bouc-Wen model (Spencer) with a mass element (Yang et al.).

    .. math:: F = m\ddot x + c_1\dot y + k_1(x - x_0)

    with y and z of Spencer's model (eq 17) and its control laws.

    Notes
    -----
    ``bouc_wen_modified`` plus the inertia term :math:`m\ddot x`; m = 0 is Spencer's model.

    References
    ----------
    Review (the MR-model review) eq 26, section 3.4 (Yang et al.).
    """

    name = "bouc_wen_modified_mass"
    title = "modified Bouc-Wen with mass element (Yang)"
    source = "the MR-model review eq 26 (Yang et al.)"
    linear_parameters = ("k1", "m")
    parameters = BoucWenModified.parameters + (Parameter("m", "kg", 0.0, -1e5, 1e5, "equivalent mass (fluid inertia)"),)

    def force(self, record, values):
        return super().force(record, values) + values["m"] * record.acceleration

    def linear_terms(self, record, values):
        rest = super().force(record, {**values, "k1": 0.0})
        return {"k1": record.displacement - values["x0"], "m": record.acceleration}, rest


class BoucWenNonsymmetric(LinearTermsModel):
    r"""Kwok's nonsymmetrical Bouc-Wen model: the Bouc-Wen operator driven by a shifted velocity.

    .. math::
        F = c_0\dot x + k_0 x + \alpha z + f_0, \qquad
        \dot z = [\delta - (\beta + \gamma\operatorname{sgn}(z\dot x_s))|z|^n]\,\dot x_s, \qquad
        \dot x_s = \dot x - \mu\operatorname{sgn}(x)

    with :math:`\alpha = \alpha_a + \alpha_u u` and :math:`c_0 = c_{0a} + c_{0u}u`.

    Parameters (SI): ``c0``, ``c0_u`` [N s/m], ``k0`` [N/m], ``alpha``, ``alpha_u`` [N/m], ``beta``, ``gamma``
    [1/m^n], ``delta``, ``n`` [-], ``mu`` [m/s], ``f0`` [N].

    Notes
    -----
    :math:`[\delta - (\beta + \gamma\operatorname{sgn}(z v))|z|^n]v = -\gamma|v|z|z|^{n-1} - \beta v|z|^n +
    \delta v`: eq 36 is the Bouc-Wen equation (15) in Kwok's notation (its :math:`|z|^m` is :math:`|z|^n`), and
    eq 37 substitutes the shifted velocity; the printed eq 37 misplaces its brackets.  The operator is driven by
    :math:`x_s = x - \mu\int\operatorname{sgn}x\,dt` (exact for a displacement linear between samples), so z
    turns where :math:`\dot x = \mu\operatorname{sgn}x`, not at zero velocity: the switching of the loop moves
    near zero velocity while the rest of the loop keeps its form (the review, section 3.9).  mu = 0 is the standard
    Bouc-Wen model with :math:`x_0 = 0`.

    References
    ----------
    Review (the MR-model review) eqs 36-38, section 3.9 (Kwok et al.).
    """

    name = "bouc_wen_nonsymmetric"
    title = "nonsymmetrical Bouc-Wen (Kwok)"
    source = "the MR-model review eqs 36-38 (Table 1: eqs 35-36; Kwok et al.)"
    uses_control = True
    control_parameters = ("c0_u", "alpha_u")
    linear_parameters = ("c0", "k0", "alpha", "f0", "c0_u", "alpha_u")
    projection_default = False
    parameters = (
        Parameter("c0", "N*s/m", 5300.0, 0.0, 1e8, "viscous damping"),
        Parameter("k0", "N/m", 0.0, 0.0, 1e8, "stiffness (a spring: not negative)"),
        Parameter("alpha", "N/m", 96300.0, 0.0, 1e10, "scale of the hysteretic force"),
        *_hysteresis_parameters(),
        Parameter("mu", "m/s", 0.0, -10.0, 10.0, "velocity shift of the hysteresis switching"),
        FORCE_OFFSET,
        Parameter("c0_u", "N*s/m", 0.0, -1e8, 1e8, "viscous damping per unit control"),
        Parameter("alpha_u", "N/m", 0.0, -1e10, 1e10, "hysteretic scale per unit control"),
    )

    def hysteretic_state(self, record, values):
        """z driven by the shifted input x - mu int sgn(x) dt."""
        xs = record.displacement - values["mu"] * sign_time_integral(record.time, record.displacement)
        return bouc_wen_state(xs, values["beta"], values["gamma"], values["delta"], values["n"])

    def linear_terms(self, record, values):
        z = self.hysteretic_state(record, values)
        u, v = self.control(record), record.velocity
        return {
            "c0": v,
            "k0": record.displacement,
            "alpha": z,
            "f0": np.ones_like(v),
            "c0_u": u * v,
            "alpha_u": u * z,
        }, np.zeros_like(v)

    def guess_from_force(self, record):
        g = BoucWen().guess_from_force(record)
        return {"c0": g["c0a"], "alpha": g["alpha_a"], "beta": g["beta"], "gamma": g["gamma"]}


class BoucWenAmplitude(BoucWen):
    r"""Amplitude-dependent Bouc-Wen model (Ali and Ramaswamy): the coefficients of the standard model depend on
    the current and, quadratically, on the stroke amplitude :math:`x_a`.

    .. math::
        F = c_0\dot x + k_0 x + \alpha z,\qquad
        c_0 = (c_1 + c_2x_a + c_3x_a^2) + (c_4 + c_5x_a + c_6x_a^2)u

    and the same laws for :math:`k_0` (k1-k6) and :math:`\alpha` (alpha1-alpha6); z from eq 15.

    Parameters (SI): ``c1``-``c6`` [N s/m per m^j], ``k1``-``k6`` [N/m per m^j], ``alpha1``-``alpha6`` [N/m per
    m^j], the Bouc-Wen shape, and ``x_a`` [m], the stroke amplitude.

    Notes
    -----
    The stroke amplitude is an explicit parameter held a priori (:mod:`erdesign.models.excitation`): a simulation
    uses the amplitude given, and identification starts from the record's half peak-to-peak displacement and
    reports it; on a record of several amplitudes, split it (one amplitude per test, as the source).  At a given
    amplitude the model is the standard Bouc-Wen model with :math:`c_{0a} = c_1 + c_2x_a + c_3x_a^2`,
    :math:`c_{0b} = c_4 + c_5x_a + c_6x_a^2`, and so on.

    References
    ----------
    Review (the MR-model review) eqs 16 and 27, section 3.5 (Ali and Ramaswamy).
    """

    name = "bouc_wen_amplitude"
    title = "amplitude-dependent Bouc-Wen (Ali-Ramaswamy)"
    source = "the MR-model review eqs 16, 27 (Ali and Ramaswamy)"
    control_parameters = ("c4", "c5", "c6", "k4", "k5", "k6", "alpha4", "alpha5", "alpha6")
    linear_parameters = ("c1", "c2", "c3", "k1", "k2", "k3", "alpha1", "alpha2", "alpha3") + control_parameters
    parameters = (
        *(
            Parameter(f"c{j}", "N*s/m", 5300.0 if j == 1 else 0.0, -1e12, 1e12, f"viscous damping law, coefficient {j}")
            for j in range(1, 7)
        ),
        *(Parameter(f"k{j}", "N/m", 0.0, -1e12, 1e12, f"stiffness law, coefficient {j}") for j in range(1, 7)),
        *(
            Parameter(
                f"alpha{j}", "N/m", 96300.0 if j == 1 else 0.0, -1e14, 1e14, f"hysteretic scale law, coefficient {j}"
            )
            for j in range(1, 7)
        ),
        *_hysteresis_parameters(),
        Parameter("x_a", "m", 0.01, 0.0, 10.0, "stroke amplitude of the test (a priori: the record's)", fitted=False),
    )

    @staticmethod
    def _law(values, p, j0):
        """p_j0 + p_(j0+1) x_a + p_(j0+2) x_a^2: a coefficient of the standard model at the amplitude x_a."""
        xa = values["x_a"]
        return values[f"{p}{j0}"] + values[f"{p}{j0 + 1}"] * xa + values[f"{p}{j0 + 2}"] * xa**2

    def standard(self, values):
        """The standard Bouc-Wen parameters at the amplitude x_a."""
        return {
            "c0a": self._law(values, "c", 1),
            "c0b": self._law(values, "c", 4),
            "k0": self._law(values, "k", 1),
            "alpha_a": self._law(values, "alpha", 1),
            "alpha_b": self._law(values, "alpha", 4),
            "x0": 0.0,
            **{k: values[k] for k in ("beta", "gamma", "delta", "n")},
        }

    def force(self, record, values):
        k0b = self._law(values, "k", 4)  # the stiffness per unit control, which the standard model does not have
        return super().force(record, self.standard(values)) + k0b * self.control(record) * record.displacement

    def linear_terms(self, record, values):
        u, v, x = self.control(record), record.velocity, record.displacement
        z = bouc_wen_state(x, values["beta"], values["gamma"], values["delta"], values["n"])
        xa = values["x_a"]
        cols = {}
        for p, base in (("c", v), ("k", x), ("alpha", z)):
            for j in range(3):
                cols[f"{p}{j + 1}"] = base * xa**j
                cols[f"{p}{j + 4}"] = base * u * xa**j
        return cols, np.zeros_like(v)

    def initial_guess(self, record):
        return {**super().initial_guess(record), "x_a": record_amplitude(record)}

    def guess_from_force(self, record):
        g = super().guess_from_force(record)
        return {"beta": g["beta"], "gamma": g["gamma"], "c1": g["c0a"], "alpha1": g["alpha_a"]}


def _saturating(a1, a2, a3, u):
    """a1 + a2 (1 - exp(-a3 u)) (Dominguez et al.'s exponential current law, eq 31)."""
    return a1 + a2 * (1.0 - np.exp(-a3 * u))


class BoucWenDominguez(Model):
    r"""Current-dependent Bouc-Wen model of Dominguez et al.: the Bouc-Wen equation with A = 1, beta = 0, n = 2,
    solved explicitly on the two branches of the loop.

    .. math::
        F = c_0(u)\dot x + k_0(u)x + \alpha(u)z,\qquad
        z = \frac{1}{\sqrt{\gamma}}\tanh\!\left[\sqrt{\gamma}\,x + \operatorname{sgn}(\dot x)
            \operatorname{artanh}\frac{F_{z0}\sqrt{\gamma}}{\alpha}\right],

        \gamma = \gamma_1 + \gamma_2u,\ k_0 = k_1 + k_2u,\ c_0 = c_1 + c_2(1 - e^{-c_3u}),\
        \alpha = \alpha_1 + \alpha_2(1 - e^{-\alpha_3u}),\ F_{z0} = F_{z01} + F_{z02}(1 - e^{-F_{z03}u})

    Parameters (SI): ``c1``, ``c2`` [N s/m], ``c3`` [-], ``k1``, ``k2`` [N/m], ``alpha1``, ``alpha2`` [N/m],
    ``alpha3`` [-], ``gamma1``, ``gamma2`` [1/m^2], ``F_z01``, ``F_z02`` [N], ``F_z03`` [-] (rates per unit control).

    Notes
    -----
    :math:`F_{z0}` is the hysteretic force :math:`\alpha z` at zero displacement: :math:`+F_{z0}` on the branch of
    increasing displacement, :math:`-F_{z0}` on the other; far from zero displacement z saturates at
    :math:`\pm 1/\sqrt{\gamma}`.  Corrections to the printed text: eq 30 writes the tanh argument with
    :math:`\dot x` and chooses the branch by the sign of x; the explicit solution of :math:`dz/dx = 1 - \gamma z^2`
    is in the displacement, and the branch follows the direction of motion.  Eq 29 prints :math:`+\gamma|\dot x|
    z|z|^{n-1}`; the tanh solution it leads to needs the minus sign of eq 15.  Eq 31 writes
    :math:`\gamma = -\gamma_1 + \gamma_2I`; the sign is absorbed in :math:`\gamma_1` here (:math:`\gamma > 0` is
    needed, and is enforced).  The model is explicit (no state), so the inverse is a bracketed root in the control.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 2001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> m = BoucWenDominguez(); F = m.simulate(rec, {"c1": 0.0, "k1": 0.0})
    >>> round(float(F[500]), 6)   # x = 0 at t = 0.5 s, moving down: -F_z01
    -300.0

    References
    ----------
    Review (the MR-model review) eqs 28-31, section 3.6 (Dominguez et al.).
    """

    name = "bouc_wen_dominguez"
    title = "current-dependent Bouc-Wen (Dominguez)"
    source = "the MR-model review eqs 28-31 (Dominguez et al.)"
    uses_control = True
    memoryless = True
    control_parameters = ("c2", "c3", "k2", "alpha2", "alpha3", "gamma2", "F_z02", "F_z03")
    parameters = (
        Parameter("c1", "N*s/m", 3000.0, 0.0, 1e8, "viscous damping at zero control"),
        Parameter("k1", "N/m", 0.0, -1e8, 1e8, "stiffness at zero control"),
        Parameter("alpha1", "N/m", 1e5, 1e-3, 1e10, "hysteretic scale at zero control", log_scale=True),
        Parameter("gamma1", "1/m^2", 1e5, 1e-3, 1e12, "Bouc-Wen gamma at zero control", log_scale=True),
        Parameter("F_z01", "N", 300.0, 0.0, 1e7, "hysteretic force at zero displacement, zero control"),
        Parameter("c2", "N*s/m", 0.0, -1e8, 1e8, "saturating damping increase with control"),
        Parameter("c3", "", 1.0, 0.0, 1e3, "rate of the damping law"),
        Parameter("k2", "N/m", 0.0, -1e8, 1e8, "stiffness per unit control"),
        Parameter("alpha2", "N/m", 0.0, -1e10, 1e10, "saturating increase of alpha with control"),
        Parameter("alpha3", "", 1.0, 0.0, 1e3, "rate of the alpha law"),
        Parameter("gamma2", "1/m^2", 0.0, -1e12, 1e12, "gamma per unit control"),
        Parameter("F_z02", "N", 0.0, -1e7, 1e7, "saturating increase of F_z0 with control"),
        Parameter("F_z03", "", 1.0, 0.0, 1e3, "rate of the F_z0 law"),
    )

    def laws(self, record, values):
        """(c0, k0, alpha, gamma, F_z0) per sample (eq 31)."""
        u = self.control(record)
        c0 = _saturating(values["c1"], values["c2"], values["c3"], u)
        k0 = values["k1"] + values["k2"] * u
        al = np.maximum(_saturating(values["alpha1"], values["alpha2"], values["alpha3"], u), 1e-12)
        ga = np.maximum(values["gamma1"] + values["gamma2"] * u, 1e-12)
        Fz0 = _saturating(values["F_z01"], values["F_z02"], values["F_z03"], u)
        return c0, k0, al, ga, Fz0

    def hysteretic_force(self, x, v, al, ga, Fz0):
        """alpha z [N] of the explicit branches (eq 30, corrected)."""
        r = np.sqrt(ga)
        ratio = np.clip(Fz0 * r / al, -1.0 + 1e-12, 1.0 - 1e-12)
        direction = np.where(v >= 0, 1.0, -1.0)
        return al / r * np.tanh(r * x + direction * np.arctanh(ratio))

    def force(self, record, values):
        c0, k0, al, ga, Fz0 = self.laws(record, values)
        x, v = record.displacement, record.velocity
        return c0 * v + k0 * x + self.hysteretic_force(x, v, al, ga, Fz0)

    def guess_from_force(self, record):
        fy, c0, _f0, X, _ = force_scales(record)
        zs = X / 10.0
        return dict(c1=c0, gamma1=1.0 / zs**2, alpha1=fy / zs, F_z01=0.9 * fy)


class BoucWenDominguezCFA(BoucWenDominguez):
    r"""Current-frequency-amplitude-dependent Bouc-Wen model of Dominguez et al.

    .. math::
        F = (d_1\omega^{d_2})(d_3x_{max}^{d_4})\,[c_0(u)\dot x + k_0(u)x + \alpha(u)z]

    with z as in ``bouc_wen_dominguez`` and, above the border control :math:`u_c`, the exponential laws
    :math:`c_0 = c_1 + c_2(1 - e^{-c_3(u - u_c)})` (the same for :math:`\alpha` and :math:`F_{z0}`), below it the
    linear laws :math:`c_0 = c_4 + (c_1 - c_4)u/u_c`; :math:`\gamma = \gamma_1 + \gamma_2u`, :math:`k_0 = k_1 +
    k_2u`.

    Parameters (SI): those of ``bouc_wen_dominguez`` plus ``c4`` [N s/m], ``alpha4`` [N/m], ``F_z04`` [N], ``u_c``
    [-], ``d1``-``d4`` [-]; the excitation ``frequency`` [Hz] (:math:`\omega = 2\pi f`) and amplitude ``x_max`` [m]
    are explicit, held a priori (identification starts from the record's).

    Notes
    -----
    Correction: eq 33 prints the low-current laws as :math:`c_4 + (c_4 - c_1)I/I_c`, which is :math:`2c_4 - c_1`
    at :math:`I_c` where the high-current law gives :math:`c_1`; the law continuous at :math:`I_c`,
    :math:`c_4 + (c_1 - c_4)I/I_c`, is used (and likewise for alpha and F_z0).  :math:`d_3` only rescales
    :math:`d_1` and is held at 1.  With :math:`d_2 = d_4 = 0`, :math:`d_1 = 1` and :math:`u > u_c` it is the
    current-dependent model with the control shifted by :math:`u_c`.

    References
    ----------
    Review (the MR-model review) eqs 32-33, section 3.7 (Dominguez et al.).
    """

    name = "bouc_wen_dominguez_cfa"
    title = "current-frequency-amplitude-dependent Bouc-Wen (Dominguez)"
    source = "the MR-model review eqs 32-33 (Table 1: eq 31; Dominguez et al.)"
    control_parameters = BoucWenDominguez.control_parameters + ("c4", "alpha4", "F_z04", "u_c")
    parameters = BoucWenDominguez.parameters + (
        Parameter("c4", "N*s/m", 3000.0, 0.0, 1e8, "viscous damping at zero control (low-current law)"),
        Parameter("alpha4", "N/m", 1e5, 1e-3, 1e10, "alpha at zero control (low-current law)"),
        Parameter("F_z04", "N", 300.0, 0.0, 1e7, "F_z0 at zero control (low-current law)"),
        Parameter("u_c", "", 0.25, 1e-6, 1e3, "border control between the low and high laws"),
        Parameter("d1", "", 1.0, 1e-9, 1e9, "frequency factor", log_scale=True),
        Parameter("d2", "", 0.0, -5.0, 5.0, "frequency exponent"),
        Parameter("d3", "", 1.0, 1e-9, 1e9, "amplitude factor (redundant with d1: held)", fitted=False),
        Parameter("d4", "", 0.0, -5.0, 5.0, "amplitude exponent"),
        Parameter("frequency", "Hz", 1.0, 1e-6, 1e4, "excitation frequency (a priori: the record's)", fitted=False),
        Parameter("x_max", "m", 0.01, 1e-9, 10.0, "excitation amplitude (a priori: the record's)", fitted=False),
    )

    def laws(self, record, values):
        u = self.control(record)
        uc = values["u_c"]
        high = u > uc

        def piecewise(p):
            lo = values[f"{p}4"] + (values[f"{p}1"] - values[f"{p}4"]) * u / uc
            hi = _saturating(values[f"{p}1"], values[f"{p}2"], values[f"{p}3"], u - uc)
            return np.where(high, hi, lo)

        c0 = piecewise("c")
        al = np.maximum(piecewise("alpha"), 1e-12)
        Fz0 = values["F_z04"] + (values["F_z01"] - values["F_z04"]) * u / uc
        Fz0 = np.where(high, _saturating(values["F_z01"], values["F_z02"], values["F_z03"], u - uc), Fz0)
        ga = np.maximum(values["gamma1"] + values["gamma2"] * u, 1e-12)
        return c0, values["k1"] + values["k2"] * u, al, ga, Fz0

    def force(self, record, values):
        scale = (
            values["d1"]
            * (2 * np.pi * values["frequency"]) ** values["d2"]
            * values["d3"]
            * values["x_max"] ** values["d4"]
        )
        return scale * super().force(record, values)

    def initial_guess(self, record):
        g = super().initial_guess(record)
        g.update(
            c4=g["c1"],
            alpha4=g["alpha1"],
            F_z04=g["F_z01"],
            frequency=max(record_frequency(record), 1e-6),
            x_max=max(record_amplitude(record), 1e-9),
        )
        return g


class BoucWenAsymmetricSigmoid(BoucWenModified):
    r"""Modified Bouc-Wen model with the asymmetric sigmoid current function of Ma et al.

    .. math::
        F = f_i(u)\,f_h(x, \dot x, \ddot x), \qquad
        f_i(u) = 1 + \frac{k_2}{1 + e^{-a_2(u + I_0)}} - \frac{k_2}{1 + e^{-a_2I_0}}

    where :math:`f_h` is Spencer's modified Bouc-Wen model (eq 17) with constant (zero-current) parameters.

    Parameters (SI): those of ``bouc_wen_modified`` without the control laws, plus ``k2``, ``a2``, ``I0`` [-].

    Notes
    -----
    :math:`f_i(0) = 1`, so :math:`f_h` is the zero-current force; the gain saturates at
    :math:`1 + k_2 - k_2/(1 + e^{-a_2I_0})` for large current.  u is the dimensionless control (the source's
    current in A when the control reference is 1 A).

    References
    ----------
    Review (the MR-model review) eqs 17, 34-35, section 3.8 (Ma et al.).
    """

    name = "bouc_wen_asymmetric_sigmoid"
    title = "asymmetric sigmoid modified Bouc-Wen (Ma)"
    source = "the MR-model review eqs 17, 34-35 (Table 1: eqs 17, 33; Ma et al.)"
    control_parameters = ("k2", "a2", "I0")
    linear_parameters = ()
    parameters = tuple(
        p for p in BoucWenModified.parameters if p.name not in ("c0b", "c1b", "alpha_b", "alpha_c", "eta")
    ) + (
        Parameter("k2", "", 0.0, 0.0, 1e4, "gain of the sigmoid current function"),
        Parameter("a2", "", 1.0, 1e-6, 1e4, "slope of the sigmoid current function"),
        Parameter("I0", "", 0.0, -1e3, 1e3, "bias of the sigmoid current function"),
    )

    def force(self, record, values):
        passive = {**values, "c0b": 0.0, "c1b": 0.0, "alpha_b": 0.0, "alpha_c": 0.0, "eta": 190.0}
        gain = sigmoid_gain(self.control(record), values["k2"], values["a2"], values["I0"])
        return gain * super().force(record, passive)

    def linear_terms(self, record, values):  # no linear parameters: the gain multiplies the whole force
        return {}, self.force(record, values)


def _normalized_shape(values):
    """(beta, gamma, delta) of the Bouc-Wen equation for the normalised form rho (1 - sigma), rho sigma, rho."""
    rho, sigma = values["rho"], values["sigma"]
    return rho * (1.0 - sigma), rho * sigma, rho


_NORMALIZED_SHAPE = (
    Parameter("rho", "1/m", 1000.0, 1e-3, 1e7, "rate of the normalised state", log_scale=True),
    Parameter("sigma", "", 1.0, 0.5, 50.0, "shape of the loop (>= 1/2)"),
    Parameter("n", "", 1.0, 1.0, 10.0, "exponent (held fixed by default)", fitted=False),
)


class BoucWenModifiedNormalized(BoucWenModified):
    r"""Normalised phenomenological model (Bai et al.): Spencer's modified Bouc-Wen model with the normalised
    Bouc-Wen operator.

    .. math::
        F = c_1\dot y + k_1(x - x_0),\quad \dot y = \frac{\alpha z + c_0\dot x + k_0(x - y)}{c_0 + c_1},\quad
        \dot z = \rho\left(-\sigma|\dot w|z|z|^{n-1} - (1 - \sigma)\dot w|z|^n + \dot w\right),\ w = x - y

    Notes
    -----
    The modified Bouc-Wen kernel with :math:`\beta = \rho(1 - \sigma)`, :math:`\gamma = \rho\sigma`,
    :math:`\delta = \rho`: z stays within [-1, 1] for :math:`\sigma \ge 1/2`, and the redundant scale of the
    Bouc-Wen operator is gone (one parameter fewer).  Spencer's control laws are kept.

    References
    ----------
    Review (the MR-model review) eqs 17 and 55, section 3.12 (Bai et al.).
    """

    name = "bouc_wen_modified_normalized"
    title = "normalised phenomenological model (Bai)"
    source = "the MR-model review eqs 17, 55 (Table 1: eqs 17, 51; Bai et al.)"
    parameters = (
        tuple(p for p in BoucWenModified.parameters if p.name not in ("beta", "gamma", "delta", "n"))
        + _NORMALIZED_SHAPE
    )

    def states(self, record, values):
        beta, gamma, delta = _normalized_shape(values)
        return super().states(record, {**values, "beta": beta, "gamma": gamma, "delta": delta})

    def guess_from_force(self, record):
        fy, c0, _, X, _ = force_scales(record)
        # z saturates at 1 after a travel of about X / 10
        return dict(c0a=max(c0, 10.0), c1a=15.0 * max(c0, 10.0), alpha_a=fy, rho=10.0 / X, sigma=1.0, k0=0.0, k1=0.0)


class BoucWenRestructured(LinearTermsModel):
    r"""Restructured model of Bai et al.: a spring, a dashpot and a normalised Bouc-Wen element whose input is
    relieved by a dashpot c1 in series.

    .. math::
        F = k_1x + c_0\dot x + \alpha z + f_0,\qquad \dot y = \frac{\alpha z}{c_1},\qquad
        \dot z = \rho\left(-\sigma|\dot w|z|z|^{n-1} - (1 - \sigma)\dot w|z|^n + \dot w\right),\ w = x - y

    with :math:`\alpha = \alpha_a + \alpha_u u`, :math:`c_0 = c_{0} + c_{0,u}u`.

    Notes
    -----
    The review's eq 56 drops :math:`\sigma` from the first term of the z equation; eq 55, which it restructures,
    has it, and without it the operator is not the normalised one.  Solved by the modified Bouc-Wen kernel with
    :math:`c_0 = k_0 = 0` in its y equation (:math:`\dot w = \dot x - \alpha z/c_1`).  For large c1 the series
    dashpot is rigid and the model is the normalised Bouc-Wen model :math:`k_1x + c_0\dot x + \alpha z(x)`.

    References
    ----------
    Review (the MR-model review) eq 56, section 3.13 (Bai et al.).
    """

    name = "bouc_wen_restructured"
    title = "restructured model (Bai)"
    source = "the MR-model review eq 56 (Table 1: eq 52; Bai et al.)"
    uses_control = True
    control_parameters = ("alpha_u", "c0_u", "eta")
    linear_parameters = ("k1", "c0", "f0", "c0_u")
    parameters = (
        Parameter("k1", "N/m", 0.0, 0.0, 1e8, "stiffness (a spring: not negative)"),
        Parameter("c0", "N*s/m", 3000.0, 0.0, 1e8, "viscous damping"),
        Parameter("alpha", "N", 500.0, 0.0, 1e7, "hysteretic force amplitude"),
        Parameter("c1", "N*s/m", 1e5, 1.0, 1e10, "series dashpot of the hysteretic element", log_scale=True),
        *_NORMALIZED_SHAPE,
        FORCE_OFFSET,
        Parameter("alpha_u", "N", 0.0, -1e7, 1e7, "hysteretic amplitude per unit control"),
        Parameter("c0_u", "N*s/m", 0.0, -1e8, 1e8, "viscous damping per unit control"),
        Parameter("eta", "1/s", 1e6, 1e-3, 1e9, "rate of the first-order control filter (fast: none)", log_scale=True),
    )

    def states(self, record, values):
        beta, gamma, delta = _normalized_shape(values)
        return modified_bouc_wen(
            record.time,
            record.displacement,
            self.control(record),
            values["eta"],
            (values["alpha"], values["alpha_u"], 0.0),
            (0.0, 0.0),
            (values["c1"], 0.0),
            0.0,
            beta,
            gamma,
            delta,
            values["n"],
        )

    def linear_terms(self, record, values):
        uf, _w, z = self.states(record, values)
        v = record.velocity
        rest = (values["alpha"] + values["alpha_u"] * uf) * z
        return {"k1": record.displacement, "c0": v, "f0": np.ones_like(v), "c0_u": self.control(record) * v}, rest

    def guess_from_force(self, record):
        fy, c0, f0, X, _ = force_scales(record)
        return dict(c0=c0, alpha=fy, f0=f0, rho=10.0 / X, c1=100.0 * max(c0, 1.0))


class BoucWenNormalizedII(LinearTermsModel):
    r"""Normalised Bouc-Wen model II of Dominguez et al.: a normalised operator and square-root current laws.

    .. math::
        F = k_0x + c_0\dot x + \rho z,\qquad \dot z = \gamma(\dot x - |\dot x|z|z|),

        c_0 = c_1 + c_2\sqrt{|u|},\ k_0 = k_1 + k_2\sqrt{|u|},\ \rho = \rho_1 + \rho_2\sqrt{|u|} + \rho_3\sqrt{|\dot x|}

    Parameters (SI): ``c1``, ``c2`` [N s/m], ``k1``, ``k2`` [N/m], ``rho1``, ``rho2`` [N], ``rho3``
    [N (s/m)^(1/2)], ``gamma`` [1/m], ``f0`` [N].

    Notes
    -----
    Eq 49 is the Bouc-Wen equation with :math:`\beta = 0`, n = 2 and :math:`A = \gamma`; it is solved exactly
    (the Bouc-Wen kernel), and z stays in [-1, 1].  On a branch with :math:`z \ge 0`, :math:`\dot x \ge 0` the
    solution is :math:`z = \tanh(\gamma(x + \lambda))` (eq 50); the review's later forms (eqs 51 and 54, the
    integration constant replaced by :math:`-\ddot x`) are approximations of it and are not separate models here.

    References
    ----------
    Review (the MR-model review) eqs 49-53, section 3.11 (Dominguez et al.).
    """

    name = "bouc_wen_normalized_dominguez"
    title = "normalised Bouc-Wen II (Dominguez)"
    source = "the MR-model review eqs 49-53 (Table 1: eqs 49, 48 or 50; Dominguez et al.)"
    uses_control = True
    control_parameters = ("c2", "k2", "rho2")
    linear_parameters = ("c1", "c2", "k1", "k2", "rho1", "rho2", "rho3", "f0")
    parameters = (
        Parameter("c1", "N*s/m", 3000.0, -1e8, 1e8, "viscous damping at zero control"),
        Parameter("k1", "N/m", 0.0, -1e8, 1e8, "stiffness at zero control"),
        Parameter("rho1", "N", 500.0, -1e7, 1e7, "hysteretic force at zero control"),
        Parameter("rho3", "N*s^0.5/m^0.5", 0.0, -1e8, 1e8, "hysteretic force per square root of the speed"),
        Parameter("gamma", "1/m", 1000.0, 1e-3, 1e8, "rate of the normalised state", log_scale=True),
        FORCE_OFFSET,
        Parameter("c2", "N*s/m", 0.0, -1e8, 1e8, "damping per square root of the control"),
        Parameter("k2", "N/m", 0.0, -1e8, 1e8, "stiffness per square root of the control"),
        Parameter("rho2", "N", 0.0, -1e7, 1e7, "hysteretic force per square root of the control"),
    )

    def linear_terms(self, record, values):
        g = values["gamma"]
        z = bouc_wen_state(record.displacement, 0.0, g, g, 2.0)
        s = np.sqrt(np.abs(self.control(record)))
        x, v = record.displacement, record.velocity
        return {
            "c1": v,
            "c2": s * v,
            "k1": x,
            "k2": s * x,
            "rho1": z,
            "rho2": s * z,
            "rho3": np.sqrt(np.abs(v)) * z,
            "f0": np.ones_like(v),
        }, np.zeros_like(v)

    def guess_from_force(self, record):
        fy, c0, f0, X, _ = force_scales(record)
        return dict(c1=c0, rho1=fy, f0=f0, gamma=10.0 / X)


class BoucWenModifiedPolynomial(BoucWenModified):
    r"""Modified Bouc-Wen model (Spencer) with cubic current laws (Yang et al.; quadratic: Spaggiari and Dragoni).

    .. math::
        \alpha = \alpha_a + \alpha_1u_f + \alpha_2u_f^2 + \alpha_3u_f^3,\quad
        c_0 = c_{0a} + c_{0,1}u_f + c_{0,2}u_f^2 + c_{0,3}u_f^3,\quad
        c_1 = c_{1a} + c_{1,1}u_f + c_{1,2}u_f^2 + c_{1,3}u_f^3

    in Spencer's model (eq 17) with the first-order filter of the control (eq 19).

    Notes
    -----
    Eq 20 (Yang et al.) writes the laws with the highest power first (:math:`\alpha_ai^3 + \alpha_bi^2 + \alpha_ci
    + \alpha_d`); here the coefficients are named by their power.  The cubic coefficients at zero give the quadratic
    laws of Spaggiari and Dragoni (eq 21); all but the constants and linear terms at zero give Spencer's eq 18.  The
    same compiled loop as ``bouc_wen_modified`` (its coefficient polynomials are cubic).

    References
    ----------
    Review (the MR-model review) eqs 17-21, section 3.2 (Yang et al.; Spaggiari and Dragoni).
    """

    name = "bouc_wen_modified_polynomial"
    title = "modified Bouc-Wen with cubic / quadratic current laws (Yang; Spaggiari)"
    source = "the MR-model review eqs 17-21 (Yang et al.; Spaggiari and Dragoni)"
    _laws = (("alpha", "alpha_a", "N/m", 1e10), ("c0", "c0a", "N*s/m", 1e8), ("c1", "c1a", "N*s/m", 1e9))
    control_parameters = tuple(f"{p}_{j}" for p, *_ in _laws for j in (1, 2, 3)) + ("eta",)
    linear_parameters = ("k1",)
    parameters = tuple(
        p for p in BoucWenModified.parameters if p.name not in ("c0b", "c1b", "alpha_b", "alpha_c")
    ) + tuple(
        Parameter(f"{p}_{j}", unit, 0.0, -bound, bound, f"{p} per unit control to the power {j}")
        for p, _, unit, bound in _laws
        for j in (1, 2, 3)
    )

    def control_laws(self, values):
        return tuple((values[const], *(values[f"{p}_{j}"] for j in (1, 2, 3))) for p, const, *_ in self._laws)


class BoucWenNormalizedBahar(LinearTermsModel):
    r"""Normalised Bouc-Wen model with Bahar's nonlinear voltage laws.

    .. math::
        F = k_x x + k_{\dot x}(v)\dot x + k_w(v)w + f_0,\qquad
        \dot w = \rho(v)\left(\dot x - \sigma(v)|\dot x||w|^{n(v)-1}w + (\sigma(v) - 1)\dot x|w|^{n(v)}\right),

        k_{\dot x} = k_{\dot xa} + k_{\dot xb}v,\ n = n_a + n_be^{-13v},\ \rho = \rho_a + \rho_be^{-14v},\
        \sigma = \sigma_a + \sigma_be^{-14v},

        k_w = \begin{cases} k_{w1} + k_{w2}v^{1.13} & v \le 0.3\\
        k_{w3} + k_{w4}\sin\frac{\pi(v - 0.3)}{0.8} + k_{w5}\sin\frac{3\pi(v - 0.3)}{0.8} & 0.3 \le v \le 0.7\\
        k_{w6} + k_{w7}v + k_{w8}v^3 + k_{w9}v^5 & 0.7 \le v \end{cases}

    with v the voltage in volts.

    Notes
    -----
    The constants of the laws (13 and 14 per volt, the break points 0.3 V and 0.7 V, the period 0.8 V, the
    exponent 1.13) are the source's, in volts, so the model's control is always taken in volts (its control
    reference is fixed at 1 V whatever the records).  The source writes :math:`-k_w w`; the sign is absorbed in
    :math:`k_w` (as ``bouc_wen_normalized``).  n, rho and sigma change with the voltage, so the state depends on
    the voltage history: the step of w uses the laws at the start of each sample's step (exact in w along it).
    The review gives no continuity conditions for k_w at the break points; they are not imposed.

    References
    ----------
    Review (the MR-model review) eqs 46-48, section 3.10 (Bahar et al.).
    """

    name = "bouc_wen_normalized_bahar"
    title = "normalised Bouc-Wen with Bahar's voltage laws"
    source = "the MR-model review eqs 46-48 (Bahar et al.)"
    uses_control = True
    control_parameters = ("k_v_b", "n_b", "rho_b", "sigma_b", *(f"k_w{j}" for j in range(2, 10)))
    linear_parameters = ("k_x", "k_v_a", "k_v_b", "f0", *(f"k_w{j}" for j in range(1, 10)))
    parameters = (
        Parameter("k_x", "N/m", 0.0, 0.0, 1e8, "stiffness (a spring: not negative)"),
        Parameter("k_v_a", "N*s/m", 5000.0, -1e8, 1e8, "viscous damping at 0 V"),
        Parameter("k_v_b", "N*s/m", 0.0, -1e8, 1e8, "viscous damping per volt"),
        Parameter("n_a", "", 1.0, 0.5, 10.0, "exponent at high voltage"),
        Parameter("n_b", "", 0.0, -5.0, 10.0, "exponent change at 0 V (decays as exp(-13 v))"),
        Parameter("rho_a", "1/m", 1000.0, 1e-3, 1e7, "rate at high voltage", log_scale=True),
        Parameter("rho_b", "1/m", 0.0, -1e7, 1e7, "rate change at 0 V (decays as exp(-14 v))"),
        Parameter("sigma_a", "", 1.0, 0.5, 50.0, "loop shape at high voltage"),
        Parameter("sigma_b", "", 0.0, -0.5, 50.0, "loop shape change at 0 V (decays as exp(-14 v))"),
        *(
            Parameter(f"k_w{j}", "N", 500.0 if j in (1, 3, 6) else 0.0, -1e7, 1e7, f"hysteretic force law, term {j}")
            for j in range(1, 10)
        ),
        FORCE_OFFSET,
    )

    @property
    def control_reference(self) -> float:
        """Fixed at 1 V: the laws' constants are in volts."""
        return 1.0

    @control_reference.setter
    def control_reference(self, value) -> None:  # identification sets a reference; the laws need volts
        pass

    def state(self, record, values):
        """The normalised state w (|w| <= 1 for sigma >= 1/2)."""
        v = np.maximum(self.control(record), 0.0)
        n = np.clip(values["n_a"] + values["n_b"] * np.exp(-13.0 * v), 0.5, 10.0)
        rho = np.maximum(values["rho_a"] + values["rho_b"] * np.exp(-14.0 * v), 1e-9)
        sigma = np.maximum(values["sigma_a"] + values["sigma_b"] * np.exp(-14.0 * v), 0.5)
        return bouc_wen_state_varying(record.displacement, rho * (1.0 - sigma), rho * sigma, rho, n)

    def _k_w_basis(self, v):
        low, mid, high = v <= 0.3, (v > 0.3) & (v <= 0.7), v > 0.7
        s1 = np.sin(np.pi * (v - 0.3) / 0.8)
        s3 = np.sin(3.0 * np.pi * (v - 0.3) / 0.8)
        return {
            "k_w1": 1.0 * low,
            "k_w2": low * v**1.13,
            "k_w3": 1.0 * mid,
            "k_w4": mid * s1,
            "k_w5": mid * s3,
            "k_w6": 1.0 * high,
            "k_w7": high * v,
            "k_w8": high * v**3,
            "k_w9": high * v**5,
        }

    def linear_terms(self, record, values):
        v = np.maximum(self.control(record), 0.0)
        w = self.state(record, values)
        cols = {k: b * w for k, b in self._k_w_basis(v).items()}
        xd = record.velocity
        cols.update(k_x=record.displacement, k_v_a=xd, k_v_b=v * xd, f0=np.ones_like(xd))
        return cols, np.zeros_like(xd)

    def guess_from_force(self, record):
        fy, c0, f0, X, _ = force_scales(record)
        return dict(k_v_a=c0, f0=f0, rho_a=10.0 / X, k_w1=fy, k_w3=fy, k_w6=fy)
