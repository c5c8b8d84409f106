r"""The general semi-active damper model of Vivas-López et al. (n.d.) (passive + semi-active force, asymmetric
coefficients)."""

from __future__ import annotations

import numpy as np

from ._guess import peak_speed, sign_viscous_fit
from .base import Model, Parameter, ParameterError

__all__ = ["PAPER_TERMS", "TERMS", "SemiactiveCustomized", "SemiactiveGeneral", "general_force", "sigmoid_ratio"]


def sigmoid_ratio(s):
    r"""The saturating function of Vivas-López et al. (n.d.) eqs 5a-5e, :math:`s/(1 + |s|)` (odd, bounded by 1).

    >>> sigmoid_ratio([-1.0, 0.0, 3.0]).tolist()
    [-0.5, 0.0, 0.75]
    """
    s = np.asarray(s, dtype=float)
    return s / (1.0 + np.abs(s))


def _guess(defaults: dict, record) -> dict:
    """Starting values of the general model's parameters (``defaults`` updated): offset, friction and damping of a
    Bingham fit F = f_0 + f_f sgn v + c_p v of the record, saturation gains of 20 over its peak speed; a coefficient
    with ``_pos`` / ``_neg`` values gets the guess of its base name on both sides."""
    g = dict(defaults)
    if record.force is None:
        return g
    vmax = peak_speed(record)
    fy, c, f0 = sign_viscous_fit(record)
    guess = {
        "f_f": fy,
        "c_p": max(c, 0.0),
        "f0": f0,
        "v_f": 20.0 / vmax,
        "v_hz": 20.0 / vmax,
        "v_hv": 20.0 / vmax,
        "v_py": 20.0 / vmax,
    }
    for name in g:
        key = name.removesuffix("_pos").removesuffix("_neg")
        if key in guess:
            g[name] = guess[key]
    return g


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

    def force(self, record, values):
        return general_force(record, values, TERMS, self.control(record))

    def initial_guess(self, record):
        return _guess(self.defaults(), record)


#: The terms of the general model (Vivas-López et al. eqs 3-5) -> their coefficients, in the order of eq 3 and 4;
#: each is a model term of the paper's Table 2.
TERMS: dict[str, tuple[str, ...]] = {
    "offset": ("f0",),
    "viscous": ("c_p",),
    "stiffness": ("k_p",),
    "inertia": ("m_D",),
    "friction": ("f_f", "v_f", "x_f"),
    "hysteresis_z": ("F_hz", "v_hz", "x_hz"),
    "hysteresis_v": ("F_hv", "v_hv", "x_hv"),
    "gain": ("c_sa",),
    "preyield": ("v_py", "x_py"),
}
#: The customized model of Vivas-López et al. eq 6: every term but the two hysteresis terms.
PAPER_TERMS = ("offset", "viscous", "stiffness", "inertia", "friction", "gain", "preyield")
_LINEAR = ("f0", "c_p", "k_p", "m_D", "f_f", "F_hz", "F_hv", "c_sa")
_CONTROL = ("c_sa", "v_py", "x_py")


def _bounded(p: Parameter, scales) -> Parameter:
    """``p`` with bounds from the records' peak force, speed and stroke (:class:`SemiactiveCustomized`)."""
    import dataclasses

    limit = {
        "N": 10.0 * scales["force"],
        "s/m": 1000.0 / scales["speed"],
        "1/m": 100.0 / scales["stroke"],
        "N*s/m": 100.0 * scales["force"] / scales["speed"],
        "N/m": 100.0 * scales["force"] / scales["stroke"],
    }.get(p.unit)
    if limit is None:
        return p
    lower, upper = max(p.lower, -limit), min(p.upper, limit)
    return dataclasses.replace(p, lower=lower, upper=upper, default=min(max(p.default, lower), upper))


def general_force(record, values, terms, u):
    r"""The force of the general semi-active model (Vivas-López et al. eqs 2-5) with the ``terms`` of :data:`TERMS`
    given, [N].

    A coefficient ``name`` is read from ``values[name]``, or, when it is asymmetric, from ``values[name + "_pos"]``
    for :math:`\dot z \ge 0` (extension) and ``values[name + "_neg"]`` otherwise.  With the ``gain`` term but
    without ``preyield`` the bracket of eq 4 is :math:`\operatorname{sgn}\dot z` (the post-yield limit
    :math:`v_{pre-y} \to \infty`).  ``u`` is the dimensionless control V.
    """
    z, v, a = record.displacement, record.velocity, record.acceleration
    ext = v >= 0
    S = sigmoid_ratio

    def c(name):
        if name in values:
            return values[name]
        return np.where(ext, values[name + "_pos"], values[name + "_neg"])

    F = np.zeros_like(v)
    if "offset" in terms:
        F = F + c("f0")
    if "viscous" in terms:
        F = F + c("c_p") * v
    if "stiffness" in terms:
        F = F + c("k_p") * z
    if "inertia" in terms:
        F = F + c("m_D") * a
    if "friction" in terms:
        F = F + c("f_f") * S(c("v_f") * v + c("x_f") * z)
    if "hysteresis_z" in terms:
        F = F + c("F_hz") * S(c("v_hz") * v + c("x_hz") * np.sign(z))
    if "hysteresis_v" in terms:
        F = F + c("F_hv") * S(c("v_hv") * v + c("x_hv") * np.sign(v))
    if "gain" in terms:
        bracket = (S(c("v_py") * v * u) + S(c("x_py") * z)) if "preyield" in terms else np.sign(v)
        F = F + u * c("c_sa") * bracket
    return F


class SemiactiveCustomized(Model):
    r"""The customized semi-active model of Vivas-López et al. (n.d.): the general model (eqs 2-5) with only the
    terms the characterization calls for (Table 2), each coefficient asymmetric (one value in extension, one in
    compression) when the damper is.

    .. math::
        F_D = f_0 + c_p\dot z + k_p z + m_D\ddot z + f_f S(v_f\dot z + x_f z)
              + V c_{SA}\,[S(v_{pre-y}\dot z V) + S(x_{pre-y} z)] \quad (\text{eq 6, the default terms})

    Parameters
    ----------
    terms : sequence of str
        Keys of :data:`TERMS`; default :data:`PAPER_TERMS` (eq 6).
    asymmetric : bool or sequence of str
        True: every coefficient has a ``_pos`` (extension) and a ``_neg`` (compression) value, the paper's choice
        ("the SA damper has an asymmetric behavior ... different coefficients for positive and negative
        velocities"), 20 parameters for eq 6 (its Table 5); False: one value each; or the coefficient names that
        are asymmetric.
    scales : mapping, optional
        ``force`` [N], ``speed`` [m/s] and ``stroke`` [m] of the records the model is for (their peaks).  Given,
        they bound the parameters to what such records can tell: forces within 10 x ``force``, the gains of the
        saturations :math:`S` below 1000 / ``speed`` (a transition narrower than 0.1 % of the peak speed is a step
        no sample resolves) and 100 / ``stroke``.  Without bounds a friction term with a gain at its limit becomes
        a sign function of a line in (z, ż) whose amplitude an opposite offset cancels: a fit that holds on its
        record and fails on every other (seen on truth-rig road-profile records).
    control_exponent : float
        n > 0: the manipulation V of eqs 4-5d is the dimensionless control to the power n, V = u^n (default 1, the
        paper's linear force gain).  The characterization reads n from the FM diagram when the force gain is not
        linear in the control (:mod:`erdesign.characterization.detectors`, ``nonlinear_gain``), as the yield stress
        of an ER fluid grows as E^n with n = 1.2-2.5 (Butz and von Stryk 2002) and an MR valve's as a power of the
        coil current.  It is structure, not a fitted parameter: a record with two control levels (PRBS) cannot
        tell it.

    Examples
    --------
    >>> len(SemiactiveCustomized().parameters), len(SemiactiveCustomized(asymmetric=False).parameters)
    (20, 10)

    References
    ----------
    Vivas-López et al. eqs 2-6, Table 2 (characteristic -> model term), Table 5 (20 parameters).
    """

    name = "semiactive_customized"
    title = "customized semi-active model (Vivas-López et al.)"
    source = "Vivas-López et al. (n.d.) eqs 2-6"
    uses_control = True

    def __init__(self, terms=PAPER_TERMS, asymmetric=True, scales=None, control_exponent=1.0):
        if not (isinstance(control_exponent, (int, float)) and np.isfinite(control_exponent) and control_exponent > 0):
            raise ParameterError(f"control_exponent: must be a finite number > 0, got {control_exponent!r}")
        self.control_exponent = float(control_exponent)
        unknown = [t for t in terms if t not in TERMS]
        if unknown:
            raise ParameterError(f"terms: unknown {unknown[0]!r}; terms: {', '.join(TERMS)}")
        self.terms = tuple(t for t in TERMS if t in terms)
        names = [n for t in self.terms for n in TERMS[t]]
        if asymmetric is True:
            self.asymmetric = tuple(names)
        elif asymmetric is False:
            self.asymmetric = ()
        else:
            bad = [n for n in asymmetric if n not in names]
            if bad:
                raise ParameterError(
                    f"asymmetric: {bad[0]!r} is not a coefficient of the terms {', '.join(self.terms)}"
                )
            self.asymmetric = tuple(asymmetric)
        base = {p.name.removesuffix("_pos"): p for p in SemiactiveGeneral.parameters if not p.name.endswith("_neg")}
        if scales is not None:
            base = {n: _bounded(p, scales) for n, p in base.items()}
        self.scales = None if scales is None else dict(scales)
        params = []
        for n in names:
            p = base[n]
            if n in self.asymmetric:
                for side, word in (("_pos", "extension"), ("_neg", "compression")):
                    what = p.description.removesuffix(", extension")
                    params.append(Parameter(n + side, p.unit, p.default, p.lower, p.upper, f"{what}, {word}"))
            else:
                params.append(
                    Parameter(n, p.unit, p.default, p.lower, p.upper, p.description.removesuffix(", extension"))
                )
        self.parameters = tuple(params)

        def base_name(n):
            return n.removesuffix("_pos").removesuffix("_neg")

        self.linear_parameters = tuple(p.name for p in params if base_name(p.name) in _LINEAR)
        self.control_parameters = tuple(p.name for p in params if base_name(p.name) in _CONTROL)

    def control(self, record):
        """The manipulation V = u^n of eqs 4-5d (u the dimensionless control, n :attr:`control_exponent`)."""
        u = super().control(record)
        if self.control_exponent == 1.0:
            return u
        if np.any(u < 0):
            raise ParameterError(
                f"{record.name or 'record'}: control below zero; a control exponent "
                f"{self.control_exponent:g} needs a control that is not negative"
            )
        return u**self.control_exponent

    def force(self, record, values):
        return general_force(record, values, self.terms, self.control(record))

    def initial_guess(self, record):
        g = _guess(self.defaults(), record)
        return {n: min(max(x, self.parameter(n).lower), self.parameter(n).upper) for n, x in g.items()}

    def describe(self) -> dict:
        return {**super().describe(), "terms": list(self.terms), "control_exponent": self.control_exponent}
