r"""What every physical effect of the effect library is, and the exact discrete filter they share.

An :class:`Effect` is a physical mechanism that the quasi-steady damper (:mod:`erdesign.damper`) leaves out.  It
says, in words, what the mechanism is and what it does to the residual of the quasi-steady model (its *signature*,
in the spirit of Vivas-López et al. (n.d.) Table 2), lists its parameters with units and physical bounds
(:class:`~erdesign.models.base.Parameter`), computes a prior from the geometry and fluid where one exists, and
tells whether a record can show it at all (:meth:`Effect.check`).  It also carries its own composition: it declares
the *stage* of the force chain at which it acts (:data:`STAGES`) and overrides that stage's hook; the chain
(:meth:`erdesign.effects.chain.PhysicsDamper.components`) runs the stages in order and names no effect.  The kernels of
each mechanism live in the effect's own module.

The stages and their hooks (the base class's hooks are neutral):

* ``state`` - :meth:`Effect.fluid_control`: the control the fluid sees;
* ``constitutive`` - :meth:`Effect.gap_law`: options of the gap flow law, a :class:`GapLaw` (Bingham);
* ``parallel`` - :meth:`Effect.split_flow`: the pressure drop when part of the flow bypasses the ducts, with
  :meth:`Effect.bypass_conductance`: what the bypass passes at a pressure;
* ``thermal`` - :meth:`Effect.viscosity_factor`: the viscosity factor after the dissipated power;
* ``series`` - :meth:`Effect.series_pressure_force`: the pressure force behind an element in series
  (:meth:`Effect.series_forces`: with the moving head's shear drag);
* ``constitutive-in-time`` - :meth:`Effect.filter_fluid_force`: the fluid force through a law in time;
* ``additive`` - :meth:`Effect.additive_forces`: named force components added to the fluid force.

:attr:`Effect.continuous_at_reversal` says that the effect makes the force continuous through a reversal of the
motion (so the chain resolves no break-away jump with the expected sign of the velocity).

The state-dependent effects (compressibility, pre-yield elasticity, field lag, viscous heating) are first-order
relaxations :math:`\dot y = r(t)\,(u(t) - y)`.  :func:`relaxation_filter` solves them exactly between samples
(rate held over the step, target linear between samples) with a vectorised prefix scan, so no Python loop over
time is needed.
"""

from __future__ import annotations

import math
from typing import Callable, Mapping, NamedTuple

import numpy as np
from scipy.special import erf

from ..damper import Damper
from ..data.measurement import Measurement
from ..errors import ErdesignError
from ..numerics import affine_recurrence
from ..parameters import Parameter

__all__ = [
    "DuctLaw",
    "Effect",
    "EffectError",
    "GapLaw",
    "STAGES",
    "relaxation_filter",
    "reversal_count",
    "sign_expectation",
]

#: The stages of the force chain, in the order the chain runs them (:mod:`erdesign.effects.chain`).
STAGES = ("state", "constitutive", "parallel", "thermal", "series", "constitutive-in-time", "additive")


class EffectError(ErdesignError):
    """Unknown effect name, or a record that cannot show an effect (the message says which and why)."""


class GapLaw(NamedTuple):
    r"""The constitutive law of the gap flow, as the constitutive stage leaves it: Herschel-Bulkley,

    .. math:: \tau = \tau_y + K\,\dot\gamma^{m}, \qquad K = \eta\,\dot\gamma_\text{ref}^{\,1-m},

    Bingham (``flow_index`` 1, the default) unless an effect of the constitutive stage says otherwise.

    Attributes
    ----------
    flow_index : float
        m, [-] (1: Bingham).
    reference_shear_rate : float
        Shear rate at which the consistency K meets the plastic viscosity eta, [1/s] (no effect when m = 1).
    """

    flow_index: float = 1.0
    reference_shear_rate: float = 1.0

    def consistency(self, eta):
        """K = eta * rate_ref ** (1 - m), [Pa s^m] (eta itself for Bingham)."""
        return eta * self.reference_shear_rate ** (1.0 - self.flow_index)


class DuctLaw(NamedTuple):
    """What the ducts pass at a pressure, per sample (SI): the inverse of the quasi-steady pressure force, which
    the series stage integrates (:mod:`erdesign.effects.compressibility`).

    ``kind`` 0: thin annular slits (``ducts`` of them, length L, mean diameter d, gap h), Herschel-Bulkley with
    yield stress ``tau_y``, consistency ``K`` [Pa s^m] and flow index ``m`` (1: Bingham, K the plastic viscosity);
    ``kind`` 1: the moving-electrode gap of a mixed damper (plastic viscosity ``K``, m = 1; ``d`` = Dp + h, the
    head's speed is the piston's), whose flow :func:`erdesign.effects.compressibility.moving_wall_gap_flow` gives
    from the pressure gradient and the head's speed.  ``bypass`` is 1/C_l [m/(N s)] (0: none).  ``w`` and ``G``
    are no longer read (kept so that existing callers' tuples still build)."""

    kind: int
    tau_y: np.ndarray
    K: np.ndarray
    m: float
    L: float
    d: float
    h: float
    Ap: float
    ducts: int
    bypass: float = 0.0
    w: np.ndarray = np.zeros(2)
    G: np.ndarray = np.ones(2)


class Effect:
    """Base class of a physical effect.  Subclasses set the class attributes, :meth:`parameters` and the hook of
    their :attr:`stage`.

    Attributes
    ----------
    name : str
        Contract name (docs/cli.md, effect names).
    title : str
        Human name.
    mechanism : str
        The physics in one or two sentences.
    signature : str
        What the effect leaves in the residual of a model that lacks it.
    stage : str
        Where it enters the damper force, one of :data:`STAGES` (module table; :mod:`erdesign.effects.chain`).
    continuous_at_reversal : bool
        True when the effect makes the force continuous through a reversal of the motion (a bypass, a compliant
        column, an elastic solid below yield): the chain then resolves no break-away jump.
    source : str
        Seed paper and equation.
    """

    name: str = ""
    title: str = ""
    mechanism: str = ""
    signature: str = ""
    stage: str = ""
    continuous_at_reversal: bool = False
    source: str = ""

    @property
    def composition(self) -> str:
        """The former name of :attr:`stage`."""
        return self.stage

    def parameters(self, damper: Damper) -> tuple[Parameter, ...]:
        """Parameters (SI units, physical bounds; defaults from the prior where there is one)."""
        raise NotImplementedError

    def prior(self, damper: Damper) -> dict[str, float]:
        """Values expected from the geometry and fluid alone, SI (empty when none can be computed)."""
        return {}

    def start(self, damper: Damper, record: Measurement) -> dict[str, float]:
        """Starting values for a fit: the defaults of :meth:`parameters` (override for a guess from the data)."""
        return {p.name: p.default for p in self.parameters(damper)}

    #: parameter -> "lower" or "upper": the bound at which the effect vanishes (a second start for a fit that went
    #: astray; e.g. an infinitely stiff fluid column has no compressibility).
    neutral: dict = {}

    def neutral_values(self, damper: Damper) -> dict[str, float]:
        """Parameter values (near) where the effect vanishes: the model is then the one without it."""
        out = {}
        for p in self.parameters(damper):
            side = self.neutral.get(p.name, "lower")
            if side in ("lower", "upper"):
                out[p.name] = p.lower if side == "lower" else p.upper
            else:
                out[p.name] = float(side)
        return out

    def check(self, record: Measurement, damper: Damper) -> str | None:
        """Why ``record`` cannot show this effect (a sentence), or None when it can."""
        return None

    #: parameter -> (low, high): the fitted value over its prior that still counts as plausible.  Priors come from
    #: nominal geometry and handbook properties, good to a factor of a few; an effect may widen the window where
    #: the physics allows it (entrained air softens a fluid column by tens of times, never stiffens it).
    plausible_ratio: dict = {}
    #: default window for parameters not in :attr:`plausible_ratio`.
    PLAUSIBLE_RATIO = (0.2, 5.0)

    def implausible(self, damper: Damper, values: Mapping[str, float]) -> list[str]:
        """What is implausible about fitted ``values`` against the prior (empty list: nothing)."""
        notes = []
        for name, p in self.prior(damper).items():
            window = self.plausible_ratio.get(name, self.PLAUSIBLE_RATIO)
            v = values.get(name)
            if v is None or p == 0 or window is None:
                continue
            ratio = v / p
            if not (window[0] <= ratio <= window[1]):
                notes.append(f"{name} is {ratio:.3g} x its prior (plausible: {window[0]:g} to {window[1]:g} x)")
        return notes

    def plausibility(self, damper: Damper, values: Mapping[str, float]) -> str:
        """A short judgement of fitted values against the prior: ``"plausible"``, ``"implausible (...)"`` or
        ``"no prior"`` (window per parameter: :attr:`plausible_ratio`, default 0.2 to 5 x the prior)."""
        if not self.prior(damper):
            return "no prior"
        notes = self.implausible(damper, values)
        return "plausible" if not notes else "implausible (" + "; ".join(notes) + ")"

    # ---------------------------------------------------------------- how it applies: one hook per stage
    # Each hook is neutral here; an effect overrides the hook of its stage.  ``values`` are the model's parameter
    # values (SI, by name); arrays have one entry per sample of the record.

    def fluid_control(self, t, control, values: Mapping[str, float]):
        """State: the control the fluid sees, from the control applied (same SI unit), [V/m, A/m, A or V]."""
        return control

    def gap_law(self, law: GapLaw, values: Mapping[str, float]) -> GapLaw:
        """Constitutive: the law of the gap flow, from the law so far (a :class:`GapLaw`)."""
        return law

    def split_flow(
        self,
        v,
        gap_pressure_drop: Callable,
        args: tuple,
        quasi_steady_drop,
        damper: Damper,
        values: Mapping[str, float],
    ):
        """Parallel: ``(dp, u)`` when part of the displaced flow bypasses the ducts.

        ``gap_pressure_drop(u, *args)`` is the ducts' pressure drop [Pa] for the flow of a piston at ``u`` [m/s]
        (elementwise; ``quasi_steady_drop`` its value at ``v``); ``dp`` is the pressure drop across the piston
        [Pa] and ``u`` the piston speed whose flow the ducts pass [m/s].  Neutral: all the flow through the ducts.
        """
        return quasi_steady_drop, v

    def bypass_conductance(self, values: Mapping[str, float]) -> float:
        """Parallel: piston speed per unit pressure force that the bypass passes, [m/(N s)] (0: none).  The inverse
        side of :meth:`split_flow`, for a series element that needs the ducts' flow at a pressure."""
        return 0.0

    def viscosity_factor(self, t, power, values: Mapping[str, float]):
        """Thermal: the plastic viscosity over its unheated value after the dissipated ``power`` [W] history,
        [-].  The chain resolves the coupling by fixed-point passes over the record."""
        return 1.0

    def series_pressure_force(self, t, v, pressure_force, duct_law, values: Mapping[str, float]):
        """Series: the pressure force [N] when an element in series stands between the piston and the ducts
        (``pressure_force`` is the quasi-steady one, ``duct_law`` the ducts' flow at a pressure,
        :class:`~erdesign.effects.compressibility.DuctLaw`)."""
        return pressure_force

    def series_forces(self, t, v, pressure_force, shear_force, duct_law, values: Mapping[str, float]):
        """Series: the pressure force and the moving head's shear drag [N] behind an element in series; by default
        :meth:`series_pressure_force` with the shear drag unchanged.  An element that changes the gap's flow on a
        moving-electrode head (a compliant column) changes its drag too, and overrides this."""
        return self.series_pressure_force(t, v, pressure_force, duct_law, values), shear_force

    def filter_fluid_force(self, t, v, fluid_force, damper: Damper, values: Mapping[str, float], held_force=None):
        """Constitutive in time: the fluid force [N] through a law in time, from the quasi-steady one
        (``held_force``: the quasi-steady force at each sample's speed with the previous sample's control, for a
        control held over each interval; None where it equals ``fluid_force``)."""
        return fluid_force

    def additive_forces(
        self, record: Measurement, sign, damper: Damper, values: Mapping[str, float]
    ) -> dict[str, np.ndarray]:
        """Additive: named force components [N] added to the fluid force; ``sign`` is the expected sign of the
        velocity over its noise band (:func:`sign_expectation`).  A name the baseline already has (``friction``:
        the damper file's seal friction) replaces the baseline's component."""
        return {}

    def describe(self) -> dict:
        return {
            "name": self.name,
            "title": self.title,
            "mechanism": self.mechanism,
            "signature": self.signature,
            "stage": self.stage,
            "composition": self.stage,
            "source": self.source,
        }

    def __repr__(self) -> str:
        return f"<Effect {self.name!r}>"


def relaxation_filter(t, target, rate, y0=None):
    r"""Exact solution at the samples of the first-order relaxation :math:`\dot y = r(t)\,(u(t) - y)`.

    Over each step the rate is held at its value at the start of the step, :math:`r_n`, and the target is linear
    between the samples; then, with :math:`a_n = e^{-r_n \Delta t_n}`,

    .. math::
        y_{n+1} = a_n y_n + u_{n+1} - a_n u_n - (u_{n+1} - u_n)\,\frac{1 - a_n}{r_n \Delta t_n},

    an affine recurrence evaluated with a vectorised prefix scan (:mod:`erdesign.constitutive.makris`).

    Parameters
    ----------
    t : array, shape (N,)
        Time, strictly increasing, [s].
    target : array, shape (N,)
        u, the value y relaxes towards, [any unit].
    rate : float or array, shape (N,)
        r >= 0, [1/s]; ``inf`` makes y follow the target.
    y0 : float, optional
        y at ``t[0]``; default ``target[0]`` (settled).

    Returns
    -------
    array, shape (N,)
        y at the samples, in the unit of ``target``.

    Notes
    -----
    Exact for a piecewise-linear target and piecewise-constant rate at any step size (no stability limit: every
    step is a convex combination); for smooth inputs the error is second order in the step.  With a constant rate
    it is the first-order-hold discretisation of a first-order low-pass filter.

    Examples
    --------
    A step held at 1 from t = 0 relaxes as 1 - exp(-r t):

    >>> import numpy as np
    >>> t = np.linspace(0.0, 1.0, 11)
    >>> y = relaxation_filter(t, np.ones(11), 2.0, y0=0.0)
    >>> bool(abs(y[-1] - (1 - np.exp(-2.0))) < 1e-12)
    True

    References
    ----------
    Butz and von Stryk (2002) (Butz and von Stryk), eq 16 (first-order filter); Makris et al. (1996), eqs 9-10 (the same
    linear first-order form with a time-varying rate).
    """
    t = np.asarray(t, dtype=float)
    u = np.asarray(target, dtype=float)
    r = np.broadcast_to(np.asarray(rate, dtype=float), u.shape)[:-1]
    dt = np.diff(t)
    x = r * dt
    with np.errstate(invalid="ignore", over="ignore"):
        a = np.exp(-x)
        one_minus_a = -np.expm1(-x)
        # (1 - a)/x -> 1 as x -> 0 and -> 0 as x -> inf
        phi = np.where(x > 1e-12, one_minus_a / np.where(x > 1e-12, x, 1.0), 1.0 - 0.5 * x)
        phi = np.where(np.isinf(x), 0.0, phi)
        a = np.where(np.isinf(x), 0.0, a)
    du = np.diff(u)
    d = u[1:] - a * u[:-1] - du * phi
    y0 = u[0] if y0 is None else float(y0)
    return affine_recurrence(a, d, y0)


def sign_expectation(v, sigma):
    r"""Expected sign of the true velocity given a measured one with Gaussian noise of standard deviation sigma.

    .. math:: \operatorname{E}[\operatorname{sgn} v_\text{true} \mid v] = \operatorname{erf}\!\left(\frac{v}{\sqrt2\,\sigma}\right)

    A force that jumps with the sign of the velocity (the yield force of a rigid-plastic fluid, Coulomb friction) is
    predicted best, in the least-squares sense, by its expectation over the velocity noise; with ``sigma = 0`` it is
    the sharp sign.  The width comes from the record (:func:`erdesign.data.noise.velocity_noise`), not from a fixed
    fraction of the peak speed.

    Parameters
    ----------
    v : float or array
        Measured (derived) velocity, [m/s].
    sigma : float
        Standard deviation of its noise, [m/s], >= 0.

    Returns
    -------
    float or array
        In [-1, 1].

    Examples
    --------
    >>> float(sign_expectation(0.0, 0.01)), round(float(sign_expectation(0.02, 0.01)), 4)
    (0.0, 0.9545)
    """
    v = np.asarray(v, dtype=float)
    if not sigma > 0:
        return np.sign(v)
    return erf(v / (math.sqrt(2.0) * sigma))


def reversal_count(v) -> int:
    """Number of sign changes of the velocity (two per cycle of a periodic stroke), ignoring the noise band
    below 5 % of the peak speed."""
    v = np.asarray(v, dtype=float)
    peak = np.max(np.abs(v)) if v.size else 0.0
    if peak == 0:
        return 0
    s = np.sign(v[np.abs(v) > 0.05 * peak])
    return int(np.count_nonzero(np.diff(s) != 0))


def geometric_damping(damper: Damper) -> float:
    """Damping constant per unit plastic viscosity, C / eta_0, [m^3] (valve: 12 L Ap^2 / (n pi d h^3))."""
    return damper.damping_constant_si() / damper.fluid.viscosity


def peak_speed(record: Measurement) -> float:
    """Robust peak speed of a record, the 99th percentile of |v|, [m/s]."""
    return float(np.percentile(np.abs(record.velocity), 99.0)) if len(record) else 0.0


def is_finite_positive(x: float) -> bool:
    return bool(math.isfinite(x) and x > 0)
