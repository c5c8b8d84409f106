r"""The physics damper as a :class:`~erdesign.models.base.Model`: calibrated quasi-steady baseline plus effects.

Baseline: the quasi-steady force of the damper's configuration (valve: Bingham flow through the annular ducts,
Makris eqs 5-7 and 14; mixed: Couette-Poiseuille Bingham flow, Kamath and Wereley (1997)) with the fluid of the
damper file scaled
by two calibration factors, because nominal fluid properties are uncertain by tens of percent:

.. math::
    \eta = k_\eta\,\eta(E), \qquad \tau_y = k_\tau\,\tau_y(E), \qquad
    F = \Delta p\,A_p + F_\text{shear} + F_s\operatorname{sgn}(v)

(the seal friction :math:`F_s` of the damper file is held fixed unless ``seal_friction`` is among the effects).

Effects (:mod:`erdesign.effects`) carry their own composition: each declares the *stage* of this chain at which it
acts and overrides that stage's hook (:class:`erdesign.effects.base.Effect`).  :meth:`PhysicsDamper.components`
runs the stages in this order, calling the hook of each stage on the effects that declare it, and names no effect:

1. *state of the control* (:meth:`~erdesign.effects.base.Effect.fluid_control`) - the control the fluid sees,
   e.g. ``field_lag`` (a first-order lag);
2. *constitutive* (:meth:`~erdesign.effects.base.Effect.gap_law`) - the law of the gap flow,
   :class:`~erdesign.effects.base.GapLaw`, e.g. ``shear_thinning`` (Herschel-Bulkley instead of Bingham);
3. *parallel* (:meth:`~erdesign.effects.base.Effect.split_flow`) - the flow splits between the ducts and another
   path, e.g. ``leakage`` (a laminar bypass, vectorised root per sample);
4. *thermal* (:meth:`~erdesign.effects.base.Effect.viscosity_factor`) - the viscosity follows the dissipated
   power, e.g. ``viscous_heating`` (fixed-point passes over the record, at most :data:`HEATING_PASSES`);
5. *series* (:meth:`~erdesign.effects.base.Effect.series_forces`) - an element between the piston and
   the ducts replaces the pressure force (and on a moving-electrode head the shear drag of the gap's flow), e.g.
   ``compressibility`` (the fluid column as a spring in series with the nonlinear duct law, implicit integration
   of the stiff ODE);
6. *constitutive in time* (:meth:`~erdesign.effects.base.Effect.filter_fluid_force`) - the fluid force through a
   law in time, e.g. ``preyield_elasticity`` (Makris eq 8 at the damper level, exact-step scan);
7. *additive* (:meth:`~erdesign.effects.base.Effect.additive_forces`) - named force components, e.g.
   ``seal_friction`` (which replaces the damper file's seal friction), ``fluid_inertia``, ``gas_spring``.

The parallel and series stages take one effect at a time (:data:`SINGLE_STAGES`).  A new effect is one module of
:mod:`erdesign.effects` plus its :func:`~erdesign.effects.register_effect` line; this module does not change.

The break-away jump of the rigid-plastic gap flow at a reversal (from minus to plus the yield force) and the sign of
the seal friction are evaluated at the derived velocity, whose sign is uncertain within its noise band: the model
uses the expected sign :math:`\operatorname{erf}(v/\sqrt2\sigma_v)` (:func:`erdesign.effects.base.sign_expectation`),
with the velocity noise :math:`\sigma_v` estimated from the record (:func:`erdesign.data.noise.velocity_noise`).  On a
record without noise that is the sharp sign of Makris eq 14, and at a sample with v = 0 exactly the expected force is
the mean of the two break-away forces, 0 (the kernels' value there, the break-away force signed by the sign bit, is
one side of the jump); no fixed smoothing floor is left in the baseline
(an effect whose :attr:`~erdesign.effects.base.Effect.continuous_at_reversal` is set, e.g. ``leakage``,
``compressibility`` or ``preyield_elasticity``, makes the force continuous through the reversal and needs none).

Everything is vectorised over the samples; the linear time-varying recurrences use the exact-step prefix scan of
:func:`erdesign.effects.base.relaxation_filter`.  The record's control is a command held over each sample interval
(a zero-order hold, as the truth rig drives it): the laws in time (compressibility, pre-yield elasticity) see a step
of the control at the sample where it happens.  The internal states start settled (quasi-steady) at the first
sample.  A parallel path re-solves the gap flow with the damper's own gap law
(:func:`erdesign.damper.quasi_steady.valve_pressure_drop`: thin gap or exact annulus; the mixed head through
:class:`erdesign.damper.quasi_steady.MixedGapTable`); a flow index other than 1 uses the thin-gap
Herschel-Bulkley law of :mod:`erdesign.flow.herschel_bulkley`.
"""

from __future__ import annotations

from typing import Mapping, Sequence

import math

import numpy as np

from ..damper import Damper
from . import EFFECTS, EffectError, parse_effect_names
from .base import STAGES, DuctLaw, GapLaw, sign_expectation
from ..errors import ErdesignError
from ..flow.herschel_bulkley import herschel_bulkley_pressure_drop
from ..fluid import CONTROL_UNITS
from ..data.measurement import Measurement
from ..models.base import Model, Parameter
from ..data.noise import velocity_noise
from ..damper.quasi_steady import damper_state, mixed_gap_table, valve_pressure_drop

__all__ = ["PhysicsDamper", "BASE_PARAMETERS", "check_control", "HEATING_PASSES", "SINGLE_STAGES"]

#: Calibration factors of the baseline.
BASE_PARAMETERS = (
    Parameter("viscosity_factor", "", 1.0, 0.05, 20.0, "plastic viscosity over its nominal value", log_scale=True),
    Parameter("yield_stress_factor", "", 1.0, 0.0, 20.0, "yield stress over its nominal value"),
)


#: Stages that take one effect at a time: two bypasses or two series elements would have to be solved together.
SINGLE_STAGES = ("parallel", "series")

#: Most fixed-point passes of the heating coupling (the error falls by alpha*dT per pass; they stop when the
#: viscosity factor changes by less than 1e-9).
HEATING_PASSES = 12


def check_control(damper: Damper, record: Measurement) -> None:
    """Raise a one-line error when the record's control column does not match the damper's reference field."""
    kind = record.control_kind
    if kind is not None and kind != damper.fluid.control:
        raise ErdesignError(
            f"{record.name or 'measurement'}: its control column is {_article(kind)} {kind} ({CONTROL_UNITS[kind]}) "
            f"but "
            f"the damper file's reference_field is {_article(damper.fluid.control)} {damper.fluid.control} "
            f"({damper.fluid.field_unit}); the control column must have the dimension of the fluid's reference_field "
            f"(e.g. kV/mm data need an ER fluid with reference_field in kV/mm)"
        )


def _article(word: str) -> str:
    return "an" if word[0] in "aeiou" else "a"


class PhysicsDamper(Model):
    """The damper of a damper file, calibrated, with any subset of the effect library.

    Parameters
    ----------
    damper : Damper
        Geometry and nominal fluid (and known seal friction).
    effects : sequence of str or str
        Effect names (docs/cli.md), e.g. ``("seal_friction", "fluid_inertia")`` or ``"a,b"``.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign import load_example
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 1, 501); x = 0.005 * np.sin(2 * np.pi * 2 * t)
    >>> rec = Measurement.from_arrays(t, x, control=3e6, control_kind="electric field")
    >>> model = PhysicsDamper(load_example("makris"), ["seal_friction"])
    >>> model.parameter_names
    ('viscosity_factor', 'yield_stress_factor', 'friction_force')
    >>> F = model.simulate(rec)
    >>> round(float(F.max()) / 1e3, 2)           # kN at the peak speed 63 mm/s and 3 kV/mm
    14.44
    """

    name = "physics"
    source = "Makris et al. (1996) eqs 5-7, 14; Kamath and Wereley (1997); erdesign.effects"
    uses_control = True

    def __init__(self, damper: Damper, effects: Sequence[str] | str = ()):
        self.damper = damper
        self.effect_names = parse_effect_names(effects)
        self.effects = tuple(EFFECTS[n] for n in self.effect_names)
        #: stage -> the effects that act there, in the order named
        self.stages = {s: tuple(e for e in self.effects if e.stage == s) for s in STAGES}
        for s in SINGLE_STAGES:
            if len(self.stages[s]) > 1:
                raise EffectError(
                    f"{', '.join(e.name for e in self.stages[s])}: the physics damper takes one "
                    f"effect of the {s} stage at a time"
                )
        params = list(BASE_PARAMETERS)
        for e in self.effects:
            params.extend(e.parameters(damper))
        self.parameters = tuple(params)
        self.title = "physics damper" + (f" + {', '.join(self.effect_names)}" if self.effect_names else " (baseline)")

    def has(self, name: str) -> bool:
        """True when the effect ``name`` is among this model's effects."""
        return name in self.effect_names

    def with_effects(self, effects: Sequence[str]) -> "PhysicsDamper":
        """Another physics damper with the same damper and the given effects."""
        return PhysicsDamper(self.damper, effects)

    def initial_guess(self, record: Measurement) -> dict[str, float]:
        guess = {"viscosity_factor": 1.0, "yield_stress_factor": 1.0}
        for e in self.effects:
            guess.update(e.start(self.damper, record))
        return guess

    # ------------------------------------------------------------------ the gap flow
    def _gap_pressure_drop(self, u, v_wall, tau_y, eta, law: GapLaw):
        """Pressure drop [Pa] of the gap passing the flow of a piston at speed u (wall speed v_wall, mixed)."""
        g = self.damper.geometry
        if g.configuration == "valve":
            Q = u * g.piston_area / g.ducts
            m = law.flow_index
            if m != 1.0:
                K = law.consistency(eta)
                return herschel_bulkley_pressure_drop(Q, tau_y, K, m, g.duct_length, g.duct_mean_diameter, g.gap)
            return valve_pressure_drop(
                Q, tau_y, eta, g.duct_length, g.duct_mean_diameter, g.gap, self.damper.uses_exact_annulus
            )
        return self._mixed(u, v_wall, tau_y, eta, law, shear=False)[0]

    def _mixed(self, u, v_wall, tau_y, eta, law: GapLaw, *, shear: bool = True):
        """Pressure drop [Pa] and shear drag [N] of the moving-electrode gap.

        The flow q = -u A_p / (pi d) and the wall speed are taken equal (u = v_wall, as without a bypass): the
        solution then depends on the Bingham number alone and is read from the head's
        :class:`~erdesign.damper.quasi_steady.MixedGapTable` (relative error below 1e-5).  With a bypass
        (u < v_wall) the shear drag is taken at the flow speed too, which is good when the pressure drag dominates (by about
        D_p / 2h).  A flow index m != 1 enters as the apparent viscosity at the apparent shear rate
        (:mod:`erdesign.effects.shear_thinning`).  ``shear=False``: the drag is None (not computed)."""
        g = self.damper.geometry
        h = g.gap
        m, rate_ref = law
        if m != 1.0:
            q = u * g.piston_area / (np.pi * (g.piston_diameter + h))
            rate = 6 * np.abs(q) / h**2 + np.abs(v_wall) / h
            rate = np.maximum(rate, 1e-3 * rate_ref)
            eta = eta * (rate / rate_ref) ** (m - 1.0)
        return self._mixed_table().forces(u, tau_y, eta, g.duct_length, shear=shear)

    def _mixed_table(self):
        g = self.damper.geometry
        return mixed_gap_table(g.gap, g.piston_diameter, g.rod_diameter)

    def _duct_law(self, tau_y, eta, law: GapLaw, bypass: float) -> DuctLaw:
        """The ducts' flow at a pressure (per-sample yield stress and viscosity; ``bypass`` [m/(N s)] the piston
        speed per unit pressure force of a parallel path) for an element in series."""
        g = self.damper.geometry
        n = np.size(eta)
        tau_y = np.broadcast_to(np.asarray(tau_y, dtype=float), (n,))
        if g.configuration == "valve":
            K = law.consistency(eta)
            return DuctLaw(
                0, tau_y, K, law.flow_index, g.duct_length, g.duct_mean_diameter, g.gap, g.piston_area, g.ducts, bypass
            )
        # mixed gap: the flow from the pressure and the head's speed (the piston's), the Couette-Poiseuille law of
        # the compiled loop; a flow index (if any) is left at Bingham with the plastic viscosity here (a series
        # element only needs the gap law near its yield point)
        return DuctLaw(1, tau_y, eta, 1.0, g.duct_length, g.duct_mean_diameter, g.gap, g.piston_area, 1, bypass)

    def _fluid_forces(self, v, tau_y, eta, law: GapLaw, values):
        """Pressure force and shear drag [N] of the gap flow at piston speed v, with the gap law of the
        constitutive stage and the flow split of the parallel stage."""
        g = self.damper.geometry
        m = law.flow_index
        valve = g.configuration == "valve"
        parallel = self.stages["parallel"]
        if valve and m == 1.0 and not parallel:
            # the quasi-steady kernels of Damper.state, called with per-sample tau_y and eta
            return self._valve_state(v, tau_y, eta), np.zeros_like(v)
        tau_y = np.broadcast_to(tau_y, v.shape)
        eta = np.broadcast_to(eta, v.shape)
        if not parallel:
            # no bypass: the gap passes the piston's flow (one evaluation gives the pressure drop and the drag)
            if valve:
                dp = self._gap_pressure_drop(v, v, tau_y, eta, law)
                return dp * g.piston_area, np.zeros_like(v)
            dp, shear = self._mixed(v, v, tau_y, eta, law)
            return dp * g.piston_area, shear

        gap = _GapDrop(self, law)
        dp0 = gap(v, v, tau_y, eta)
        dp, u = parallel[0].split_flow(v, gap, (v, tau_y, eta), dp0, self.damper, values)
        if valve:
            return dp * g.piston_area, np.zeros_like(v)
        # the pressure drop is the root (on the break-away jump when creeping); the shear drag at the duct flow
        return dp * g.piston_area, self._mixed(u, v, tau_y, eta, law)[1]

    def _held_fluid_force(self, record, v, fluid, heat, law: GapLaw, vals):
        """The quasi-steady fluid force at each sample's speed with the previous sample's control, [N] (None when
        the control never changes): the record's control is a command held over each sample interval (zero-order
        hold), so a law in time sees a control step at the sample where it happens, not ramped over the interval
        before it.  Not with an effect of the state stage (a lagged control is continuous) or of the series stage."""
        E = np.asarray(record.control, dtype=float)
        if self.stages["state"] or self.stages["series"] or E.size < 2:
            return None
        changed = np.flatnonzero(E[1:] != E[:-1]) + 1
        if not changed.size:
            return None
        fl = self.damper.fluid
        Ep = E[changed - 1]
        tau_y = vals["yield_stress_factor"] * np.asarray(fl.yield_stress_at(Ep), dtype=float) * np.ones(changed.size)
        eta = vals["viscosity_factor"] * np.asarray(fl.viscosity_at(Ep), dtype=float) * np.ones(changed.size)
        eta = eta * np.broadcast_to(heat, v.shape)[changed]
        P, S = self._fluid_forces(v[changed], tau_y, eta, law, vals)
        held = np.array(fluid, dtype=float, copy=True)
        held[changed] = P + S
        return held

    def _valve_state(self, v, tau_y, eta):
        return np.asarray(damper_state(self.damper, v, tau_y, eta).pressure_force, dtype=float)

    # ------------------------------------------------------------------ the force
    def components(self, record: Measurement, values: Mapping[str, float]) -> dict[str, np.ndarray]:
        """The force and its parts, [N]: ``fluid``, ``friction``, ``inertia``, ``gas_spring`` (and any other
        component an additive effect names), ``force``, and the ``yield_force`` of the calibrated fluid at the
        control the fluid sees (for residual analysis).

        The stages of the chain (module notes) run in order; each calls the hook of its stage on the effects that
        declare it (:mod:`erdesign.effects.base`)."""
        vals = dict(values)
        d, fl, stages = self.damper, self.damper.fluid, self.stages
        t, v = record.time, np.asarray(record.velocity, dtype=float)
        # 1. state: the control the fluid sees
        E = np.asarray(record.control, dtype=float)
        for e in stages["state"]:
            E = e.fluid_control(t, E, vals)
        # 2. constitutive: the law of the gap flow
        law = GapLaw()
        for e in stages["constitutive"]:
            law = e.gap_law(law, vals)
        k_eta, k_tau = vals["viscosity_factor"], vals["yield_stress_factor"]
        tau_y = k_tau * np.asarray(fl.yield_stress_at(E), dtype=float) * np.ones_like(v)
        eta_nominal = k_eta * np.asarray(fl.viscosity_at(E), dtype=float) * np.ones_like(v)
        heat = 1.0
        passes = HEATING_PASSES if stages["thermal"] else 1
        # the velocity's noise band: a force that jumps with the sign of v is predicted by its expectation there
        # (diagnosis scales the record's velocity_noise to the width that fits the record best)
        sigma_v = velocity_noise(record)
        sign = sign_expectation(v, sigma_v)
        g = d.geometry
        yield_pressure = k_tau * np.asarray(fl.yield_stress_at(E), dtype=float) * 2 * g.duct_length / g.gap
        # (a bypass makes the piston creep below yield, a compliant column or pre-yield elasticity makes the force
        # continuous: no jump to resolve, and the elastic law must relax onto the sharp rigid-plastic force)
        exact_jump = any(e.continuous_at_reversal for e in self.effects)
        # the gap kernels give the break-away force at v = 0 (signed by the sign bit, +-F_y): the expected force
        # there is the mean of the two sides, 0, as at any sample whose sign is unknown (copysign, not sign)
        smooth = 0.0 if exact_jump else sign - np.copysign(1.0, v)
        jump_P = yield_pressure * g.piston_area * smooth
        jump_S = tau_y * g.shear_area * smooth
        # 3. parallel (inside the gap flow) and 4. thermal: fixed-point passes on the viscosity
        for _ in range(passes):
            eta = eta_nominal * heat
            P, S = self._fluid_forces(v, tau_y, eta, law, vals)
            P, S = P + jump_P, S + jump_S
            if stages["thermal"]:
                new = math.prod(e.viscosity_factor(t, (P + S) * v, vals) for e in stages["thermal"])
                converged = np.max(np.abs(new - heat)) < 1e-9
                heat = new
                if converged:
                    break
        # 5. series: an element between the piston and the ducts replaces the pressure force
        if stages["series"]:
            bypass = stages["parallel"][0].bypass_conductance(vals) if stages["parallel"] else 0.0
            duct_law = self._duct_law(tau_y, eta, law, bypass)
            for e in stages["series"]:
                P, S = e.series_forces(t, v, P, S, duct_law, vals)
        fluid = P + S
        # 6. constitutive in time
        if stages["constitutive-in-time"]:
            held = self._held_fluid_force(record, v, fluid, heat, law, vals)
            for e in stages["constitutive-in-time"]:
                fluid = e.filter_fluid_force(t, v, fluid, d, vals, held_force=held)
        # 7. additive: the damper file's seal friction unless an effect replaces it
        parts = {"friction": d.seal_friction * sign, "inertia": np.zeros_like(v), "gas_spring": np.zeros_like(v)}
        for e in stages["additive"]:
            parts.update(e.additive_forces(record, sign, d, vals))
        force = fluid
        for part in parts.values():
            force = force + part
        yield_force = k_tau * np.asarray(d.yield_force_si(E), dtype=float) * np.ones_like(v)
        return {"fluid": fluid, **parts, "force": force, "yield_force": yield_force}

    def force(self, record: Measurement, values: Mapping[str, float]) -> np.ndarray:
        # extreme trial values of an optimiser (a bypass 1e6 x the ducts) overflow harmlessly to inf; the fit
        # treats non-finite forces as a huge residual
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            return self.components(record, values)["force"]

    def check_record(self, record: Measurement) -> None:
        """Raise a one-line error when the record cannot drive this damper (control of the wrong kind)."""
        base_check = getattr(super(), "check_record", None)
        if base_check is not None:
            base_check(record)
        check_control(self.damper, record)

    def check_effects(self, record: Measurement) -> None:
        """Raise when an effect of the model cannot be seen in ``record`` (says which and why)."""
        self.check_record(record)
        for e in self.effects:
            why = e.check(record, self.damper)
            if why:
                raise EffectError(f"{e.name}: cannot be judged from {record.name or 'this record'}: {why}")


class _GapDrop:
    """The gap's pressure drop at the flow of a piston moving at ``u`` (wall speed ``v_wall``), the callable the
    parallel stage solves with (:meth:`Effect.split_flow`), and, for the gap laws that have one (a mixed head,
    Bingham; thin valve slits, Bingham), the same root with a bypass in compiled code (:meth:`with_bypass`)."""

    def __init__(self, chain: "PhysicsDamper", law: GapLaw):
        self.chain, self.law = chain, law

    def __call__(self, u, v_wall, tau_y, eta):
        return self.chain._gap_pressure_drop(u, v_wall, tau_y, eta, self.law)

    def with_bypass(self, v, k, args, dp0, xatol, xrtol):
        """dp = dp_gap(v - dp k) per sample (``args`` = (v_wall, tau_y, eta), ``dp0`` the no-leak drop) by the
        compiled loop :func:`erdesign.flow._compiled.leaky_pressure_drop`, or None when this gap law has no
        compiled form (exact annulus, a flow index other than 1): the caller then solves it on whole arrays."""
        damper = self.chain.damper
        g = damper.geometry
        if self.law.flow_index != 1.0 or (g.configuration == "valve" and damper.uses_exact_annulus):
            return None
        from ..flow import _compiled

        _, tau_y, eta = (np.ascontiguousarray(a, dtype=float).ravel() for a in args)
        vv = np.ascontiguousarray(v, dtype=float).ravel()
        d0 = np.ascontiguousarray(dp0, dtype=float).ravel()
        if g.configuration == "valve":
            kind, table = _compiled.LEAKY_SLIT, _compiled._NO_TABLE
            d, per_speed = g.duct_mean_diameter, g.piston_area / g.ducts
        else:
            kind, table = _compiled.LEAKY_MIXED_HEAD, self.chain._mixed_table().pressure
            d, per_speed = 0.0, 0.0
        out = np.empty(vv.size)
        _compiled.leaky_pressure_drop(
            kind, vv, float(k), tau_y, eta, g.gap, g.duct_length, d, per_speed, table, d0, xatol, xrtol, out
        )
        return out.reshape(np.shape(v))
