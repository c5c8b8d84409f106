r"""Quarter vehicle with a controllable damper (Butz and von Stryk 2002, section 4).

.. math::
    m_1\ddot u_1 = K(u_0 - u_1) + C(\dot u_0 - \dot u_1) + k(u_2 - u_1) + F, \qquad
    m_2\ddot u_2 = -k(u_2 - u_1) - F

(eqs 31-32; axle m1, body m2, road u0).  The damper force F is that of any registered model
(:mod:`erdesign.models.registry`) or of the physics damper of a damper file, driven by the relative motion
x = u2 - u1 and a control (field, current or voltage) held constant (passive) or set at every step by a control law
(:mod:`erdesign.simulation.control`) through the damper's inverse model.

The coupling is a fixed-step co-simulation, because the models map a whole motion record to a force (the form in
which they are identified).  The scheme it solves is explicit: the force F_i of the damper model on the relative
motion up to t_i (from rest at t = 0), with the control the law chooses at t_i, is held over the step while the linear
vehicle is advanced by a classical Runge-Kutta step.  It is solved window by window (50 ms) by waveform relaxation:
guess the forces of the window, advance the vehicle, run the model once on the window (a memoryless model) or on the
whole history (a model with internal states), repeat until the forces the vehicle used are the model's, to 1 mN.
The damper's linear part (its slope c between 0.05 and 0.1 m/s, then a secant slope per sample) is carried in the
vehicle step, F = F_guess + c (v - v_guess), so that a window settles in a few passes; a window that does not settle
in 5 passes is redone in windows an eighth as long (a single step settles at once: the relaxation is causal), and the
window then doubles at each step up to 50 ms.  The error is first order in the step (the held force): for the
Butz-von Stryk step the body motion stays within 0.05 mm (0.25 ms step) and 0.2 mm (1 ms) of an adaptive
``solve_ivp`` solution of the same equations with a viscous damper, and each control law's ride figures within 4e-4
of a ``solve_ivp`` solution that holds only the control between samples (tests/test_vehicle.py).  A model with internal
states costs O(n^2) sample evaluations for n steps (about 4 s for 3 s of the modified Bouc-Wen model at the 1 ms
default).

Simulations return a :class:`VehicleResponse`; :meth:`VehicleResponse.ride` gives the figures an engineer reads.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field, fields
from typing import Mapping

import numpy as np

from ..data.measurement import Measurement
from ..errors import ErdesignError, ErdesignWarning
from ..limits import check_sample_count
from ..models.base import ControlAffineModel, Model
from .control import VehicleState, get_controller
from .ride import rms, weighted_rms
from .roads import Road

__all__ = [
    "QUARTER_CAR",
    "CONVENTIONAL_DAMPING",
    "QuarterCar",
    "VehicleDamper",
    "VehicleResponse",
    "simulate_vehicle",
    "settling_time",
    "default_gain",
    "write_history",
]

#: Butz and von Stryk (2002) section 4.1: axle and body mass [kg], tyre stiffness [N/m] and damping [N s/m],
#: suspension stiffness [N/m].
QUARTER_CAR = {"m1": 250.0, "m2": 1300.0, "K": 650e3, "C": 800.0, "k": 110e3}
#: Damping constant of their conventional damper, eq 33 [N s/m].
CONVENTIONAL_DAMPING = 6000.0
GRAVITY = 9.80665


@dataclass(frozen=True)
class QuarterCar:
    """Axle mass m1 [kg], body mass m2 [kg], tyre stiffness K [N/m] and damping C [N s/m], suspension spring k
    [N/m]; defaults of Butz and von Stryk (2002) section 4.1."""

    m1: float = QUARTER_CAR["m1"]
    m2: float = QUARTER_CAR["m2"]
    K: float = QUARTER_CAR["K"]
    C: float = QUARTER_CAR["C"]
    k: float = QUARTER_CAR["k"]

    def __post_init__(self):
        for f in fields(self):
            v = getattr(self, f.name)
            if not (np.isfinite(v) and (v > 0 or (f.name == "C" and v == 0))):
                raise ErdesignError(f"vehicle.{f.name}: must be a finite positive number, got {v!r}")

    @property
    def static_tyre_load(self) -> float:
        """(m1 + m2) g [N]."""
        return (self.m1 + self.m2) * GRAVITY


def default_gain(car: QuarterCar) -> float:
    """Skyhook / groundhook gain when none is given: the critical damping of the body on the suspension spring,
    2 sqrt(k m2) [N s/m] (23.9 kN s/m for the Butz-von Stryk vehicle)."""
    return 2.0 * float(np.sqrt(car.k * car.m2))


@dataclass
class VehicleDamper:
    """A damper in the vehicle: a model with its SI parameter values, the kind of its control and the reachable
    control range [SI], and the control a passive damper holds."""

    model: Model
    values: Mapping[str, float]
    control_kind: str | None = None
    control_range: tuple[float, float] = (0.0, 0.0)
    passive_control: float = 0.0
    label: str = ""
    notes: list[str] = field(default_factory=list)
    """Warnings of the parameter resolution (e.g. a published set for another kind of control)."""

    def __post_init__(self):
        self.values = self.model.check_values(self.values)
        lo, hi = (float(c) for c in self.control_range)
        if not (np.isfinite(lo) and np.isfinite(hi) and 0.0 <= lo <= hi):
            raise ErdesignError(f"control_range: expected 0 <= low <= high, got {self.control_range!r}")
        self.control_range = (lo, hi)
        self.label = self.label or self.model.name

    @property
    def memoryless(self) -> bool:
        """True when the force at a sample depends on that sample alone (the model declares it; the physics damper
        without effects is quasi-steady)."""
        if self.model.name == "physics":
            return not getattr(self.model, "effect_names", ())
        return bool(getattr(self.model, "memoryless", False))


@dataclass
class VehicleResponse:
    """Time [s]; road u0, axle u1 and body u2 displacement [m]; v1, v2 [m/s]; body acceleration a2 [m/s^2]; damper
    force [N]; control [SI of ``control_kind``]; dynamic tyre load K(u0 - u1) + C(du0 - v1) [N]; and where a
    continuous law's desired force was out of the damper's reach (``unreachable``)."""

    time: np.ndarray
    u0: np.ndarray
    u1: np.ndarray
    u2: np.ndarray
    v1: np.ndarray
    v2: np.ndarray
    a2: np.ndarray
    force: np.ndarray
    control: np.ndarray
    tyre_load: np.ndarray
    unreachable: np.ndarray
    car: QuarterCar
    road: Road
    controller: str
    damper: str
    control_kind: str | None = None
    gain: float | None = None
    notes: list[str] = field(default_factory=list)

    @property
    def travel(self) -> np.ndarray:
        """Suspension travel u2 - u1 [m] (positive: extension)."""
        return self.u2 - self.u1

    def ride(self) -> dict[str, float | None]:
        """The ride figures (SI, keys of ``erdesign vehicle --json``): RMS and ISO 2631-1 W_k-weighted RMS body
        acceleration, RMS and peak suspension travel, RMS and peak dynamic tyre load (and the RMS relative to the
        static load), peak damper force, mean control, and for a step or bump the settling time of the body."""
        out = {
            "body_acceleration_rms_m_per_s2": rms(self.a2),
            "body_acceleration_weighted_rms_m_per_s2": weighted_rms(self.time, self.a2),
            "suspension_travel_rms_m": rms(self.travel),
            "suspension_travel_peak_m": float(np.max(np.abs(self.travel))),
            "tyre_load_rms_N": rms(self.tyre_load),
            "tyre_load_peak_N": float(np.max(np.abs(self.tyre_load))),
            "tyre_load_rms_relative": rms(self.tyre_load) / self.car.static_tyre_load,
            "damper_force_peak_N": float(np.max(np.abs(self.force))),
            "control_mean": float(np.mean(self.control)),
            "unreachable_fraction": float(np.mean(self.unreachable)),
            "settling_time_s": None,
        }
        if self.road.settles_to is not None:
            band = 0.1 * max(abs(float(np.max(self.u0))), abs(float(np.min(self.u0))))
            out["settling_time_s"] = settling_time(self.time, self.u2, self.road.settles_to, band)
        return out

    def history(self) -> dict[str, tuple[np.ndarray, str]]:
        """Columns of the history file: name -> (values, unit)."""
        return {
            "time": (self.time, "s"),
            "road": (self.u0, "m"),
            "axle_displacement": (self.u1, "m"),
            "body_displacement": (self.u2, "m"),
            "axle_velocity": (self.v1, "m/s"),
            "body_velocity": (self.v2, "m/s"),
            "body_acceleration": (self.a2, "m/s^2"),
            "suspension_travel": (self.travel, "m"),
            "damper_force": (self.force, "N"),
            "tyre_load": (self.tyre_load, "N"),
            "control": (self.control, "SI"),
        }


def simulate_vehicle(
    damper: VehicleDamper,
    road: Road,
    control: str = "passive",
    *,
    gain: float | None = None,
    car: QuarterCar | None = None,
    duration: float = 3.0,
    dt: float | None = None,
) -> VehicleResponse:
    """Simulate the quarter vehicle over ``road`` with ``damper`` under the control law ``control``.

    Parameters
    ----------
    damper : VehicleDamper
        The damper model, its parameters and control range.
    road : Road
        Road input (:mod:`erdesign.simulation.roads`).
    control : str
        ``"passive"``, ``"skyhook"``, ``"groundhook"`` or ``"clipped-optimal"``.
    gain : float, optional
        Skyhook / groundhook damping c [N s/m]; default :func:`default_gain`.  The other laws take none.
    car : QuarterCar, optional
        Vehicle; default Butz and von Stryk (2002) section 4.1.
    duration : float
        Simulated time [s].
    dt : float, optional
        Step [s]; default 0.25 ms for a memoryless damper, 1 ms for one with internal states.

    Returns
    -------
    VehicleResponse

    Examples
    --------
    >>> from erdesign.models.registry import get_model
    >>> from erdesign.simulation.roads import step_road
    >>> d = VehicleDamper(get_model("bingham"), {"c0": 6000.0, "f_c": 0.0})
    >>> r = simulate_vehicle(d, step_road(0.1), duration=1.0)
    >>> round(float(r.v1[0]), 3)          # tyre-damper impulse of the step: C h / m1 [m/s]
    0.32
    """
    car = car or QuarterCar()
    law = get_controller(control)
    if dt is None:
        dt = 2.5e-4 if damper.memoryless else 1e-3
    if not (np.isfinite(duration) and duration > 0 and np.isfinite(dt) and 0 < dt <= duration / 10):
        raise ErdesignError(f"duration, dt: need 0 < dt <= duration / 10, got duration {duration!r} s, dt {dt!r} s")
    if dt > 2e-3:
        raise ErdesignError(f"dt: at most 2 ms (the tyre mode near 9 Hz and the damper need it), got {dt!r} s")
    if gain is not None and not law.uses_gain:
        raise ErdesignError(
            f"gain: applies to skyhook and groundhook; {law.name} has no gain"
            + (
                " (its desired force is the LQR force of the vehicle, docs/vehicle.md)"
                if law.primary is not None
                else ""
            )
        )
    gain = default_gain(car) if gain is None else float(gain)
    desired = None
    if law.primary is not None:
        if not (np.isfinite(gain) and gain > 0):
            raise ErdesignError(f"gain: must be a finite positive damping [N s/m], got {gain!r}")
        _check_controllable(damper, needs_inverse=not law.on_off)
        desired = law.primary(car, gain)
    n = check_sample_count(round(duration / dt) + 1, "duration, dt", "shorten the duration or take a larger dt")
    if n > _LONG_HISTORY and not damper.memoryless:
        warnings.warn(
            f"{damper.label}: {n} steps of a model with internal states: each window runs the model on "
            "the whole history, so this run takes long (minutes); a shorter duration or a larger dt is "
            "quicker",
            ErdesignWarning,
            stacklevel=2,
        )
    run = _CoSimulation(damper, road, car, np.arange(n) * dt, desired, law.on_off)
    run.solve()
    u1, v1, u2, v2 = run.S.T
    a2 = (-car.k * (u2 - u1) - run.F) / car.m2
    tyre = car.K * (run.u0 - u1) + car.C * (run.du0 - v1)
    return VehicleResponse(
        run.t,
        run.u0,
        u1,
        u2,
        v1,
        v2,
        a2,
        run.F,
        run.u,
        tyre,
        run.unreachable,
        car,
        road,
        law.name,
        damper.label,
        damper.control_kind,
        gain if law.uses_gain else None,
        list(damper.notes),
    )


class _CoSimulation:
    """The vehicle and the damper model stepped together (module notes): state S = (u1, v1, u2, v2) per sample, the
    relative motion x, v, a and control u the model sees, and the force F it gives."""

    def __init__(self, damper: VehicleDamper, road: Road, car: QuarterCar, t: np.ndarray, desired, on_off: bool):
        self.damper, self.car, self.t, self.desired, self.on_off = damper, car, t, desired, on_off
        n, dt = t.size, t[1] - t[0]
        self.u0, self.du0 = road.profile(t), road.rate(t)
        self.A, self.B, self.R = _discrete_vehicle(
            car, dt, self.u0, self.du0, road.profile(t + dt / 2), road.rate(t + dt / 2)
        )
        self.BE = np.outer(self.B, _REL_VELOCITY)
        self.c_limit = 0.5 / (dt * (1 / car.m1 + 1 / car.m2))  # explicit step stays stable below this damping
        self.c = _slope(damper, self.c_limit)
        self.x, self.v, self.a, self.u, self.F = (np.zeros(n) for _ in range(5))
        self.unreachable = np.zeros(n, bool)
        self.S = np.zeros((n, 4))
        self.S[0, 1] = car.C * road.step / car.m1  # the step's tyre-damper impulse
        self.w_max = max(1, int(round(_WINDOW / dt)))

    def record(self, i0: int, i1: int) -> Measurement:
        """What the model sees for samples i0..i1-1: those samples (memoryless) or the history up to them, with an
        exact velocity (no noise band for the sign of a yield force: velocity_noise 0)."""
        sl = slice(i0, i1) if self.damper.memoryless else slice(0, i1)
        return Measurement(
            self.t[sl],
            self.x[sl],
            None,
            self.v[sl],
            self.a[sl],
            self.u[sl],
            self.damper.control_kind,
            velocity_noise=0.0,
        )

    def sweep(self, i0: int, i1: int, g: np.ndarray, cj: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Advance the vehicle over samples i0..i1-1 with the force g + cj (v2 - v1) held over each step; return the
        state after the last step and the forces used."""
        S, n = self.S, self.t.size
        s = S[i0].copy()
        for j in range(i0, i1):
            S[j] = s
            if j + 1 < n:
                s = (self.A + cj[j - i0] * self.BE) @ s + self.B * g[j - i0] + self.R[j]
        u1, v1, u2, v2 = S[i0:i1].T
        self.x[i0:i1], self.v[i0:i1] = u2 - u1, v2 - v1
        F_used = g + cj * self.v[i0:i1]
        car = self.car
        a1 = (car.K * (self.u0[i0:i1] - u1) + car.C * (self.du0[i0:i1] - v1) + car.k * (u2 - u1) + F_used) / car.m1
        self.a[i0:i1] = (-car.k * (u2 - u1) - F_used) / car.m2 - a1
        return s, F_used

    def choose_control(self, i0: int, i1: int, F_used: np.ndarray, F_last: float) -> None:
        """The control of samples i0..i1-1: held (passive), switched by Dyke's rule, or from the inverse model."""
        d = self.damper
        if self.desired is None:
            self.u[i0:i1] = d.passive_control
            return
        u1, v1, u2, v2 = self.S[i0:i1].T
        F_prev = np.concatenate(([F_last], F_used[:-1]))
        Fd = self.desired(VehicleState(self.u0[i0:i1], u1, u2, v1, v2, F_prev))
        if self.on_off:
            lo, hi = d.control_range
            self.u[i0:i1] = np.where((Fd - F_prev) * F_prev > 0, hi, lo)
        else:
            self.u[i0:i1], self.unreachable[i0:i1] = _realise(d, self.record(i0, i1), Fd, d.control_kind)

    def solve(self) -> None:
        """Window by window, by waveform relaxation (module notes)."""
        n = self.t.size
        d = self.damper
        w, i0, F_last = self.w_max, 0, 0.0
        while i0 < n:
            i1 = min(n, i0 + w)
            m = i1 - i0
            Fg, vg = np.full(m, F_last), np.full(m, self.S[i0, 3] - self.S[i0, 1])
            cj = np.full(m, self.c)
            F_model = None
            for _ in range(_MAX_ITERATIONS):
                s, F_used = self.sweep(i0, i1, Fg - cj * vg, cj)
                self.choose_control(i0, i1, F_used, F_last)
                F_new = np.asarray(d.model.force(self.record(i0, i1), d.values), dtype=float)[-m:]
                if not np.all(np.isfinite(F_new)):
                    raise ErdesignError(
                        f"{d.label}: the damper force is not finite near t = {self.t[i0]:.4g} s "
                        "(the parameters or the step dt make the model unstable)"
                    )
                if m == 1:  # one step: the force follows from the known state (explicit step)
                    if i1 < n:
                        s = self.A @ self.S[i0] + self.B * F_new[0] + self.R[i0]
                    break
                if np.max(np.abs(F_new - F_used)) <= 1e-3 + 1e-7 * np.max(np.abs(F_new)):
                    break
                if F_model is not None:  # secant slope of the model in the relative velocity, per sample
                    dv = self.v[i0:i1] - vg
                    moved = np.abs(dv) > 1e-9
                    cj[moved] = np.clip((F_new - F_model)[moved] / dv[moved], 0.0, self.c_limit)
                F_model, Fg, vg = F_new, F_new, self.v[i0:i1].copy()
            else:
                w = max(1, w // 8)  # not settled: a smaller window (one step always settles)
                continue
            self.F[i0:i1] = F_new
            if i1 < n:
                self.S[i1] = s
            F_last, i0, w = float(F_new[-1]), i1, min(self.w_max, 2 * w)


#: Steps beyond which a run of a model with internal states warns of its cost.
_LONG_HISTORY = 20000
#: Relaxation window [s], iterations per window, and the selector of the relative velocity v2 - v1 in (u1, v1, u2, v2).
_WINDOW = 0.05
_MAX_ITERATIONS = 5
_REL_VELOCITY = np.array([0.0, -1.0, 0.0, 1.0])


def _discrete_vehicle(car: QuarterCar, dt: float, r0, dr0, rh, drh):
    """The classical Runge-Kutta step of the linear vehicle as s' = A s + B F + R_j (exact superposition: the step
    is linear in the state, the held force and the road samples at t_j, t_j + dt/2, t_j + dt)."""
    m1, m2, K, C, k = car.m1, car.m2, car.K, car.C, car.k

    def f(s, F, r, dr):
        u1, v1, u2, v2 = np.moveaxis(s, -1, 0)
        a1 = (K * (r - u1) + C * (dr - v1) + k * (u2 - u1) + F) / m1
        return np.stack([v1, a1, v2, (-k * (u2 - u1) - F) / m2], axis=-1)

    def step(s, F, ra, dra, rb, drb, rc, drc):
        k1 = f(s, F, ra, dra)
        k2 = f(s + dt / 2 * k1, F, rb, drb)
        k3 = f(s + dt / 2 * k2, F, rb, drb)
        k4 = f(s + dt * k3, F, rc, drc)
        return s + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)

    A = np.stack([step(e, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0) for e in np.eye(4)], axis=1)
    B = step(np.zeros(4), 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    z = np.zeros((r0.size - 1, 4))
    R = step(z, 0.0, r0[:-1], dr0[:-1], rh[:-1], drh[:-1], r0[1:], dr0[1:])
    return A, B, R


def _slope(damper: VehicleDamper, limit: float) -> float:
    """Damping [N s/m] of the damper between 0.05 and 0.1 m/s at its passive control (mid-range when controlled):
    the linear part the relaxation carries implicitly, which makes it settle in a few iterations."""
    lo, hi = damper.control_range
    level = damper.passive_control if hi <= lo else 0.5 * (lo + hi)
    t = np.linspace(0.0, 0.2, 41)
    forces = []
    for speed in (0.05, 0.1):
        rec = Measurement(
            t,
            speed * t,
            None,
            np.full(t.size, speed),
            np.zeros(t.size),
            np.full(t.size, level),
            damper.control_kind,
            velocity_noise=0.0,
        )
        forces.append(float(damper.model.force(rec, damper.values)[-1]))
    c = (forces[1] - forces[0]) / 0.05
    return float(np.clip(c, 0.0, limit)) if np.isfinite(c) else 0.0


def _realise(damper: VehicleDamper, rec: Measurement, Fd, kind: str | None) -> tuple[np.ndarray, np.ndarray]:
    """Control for the desired forces ``Fd`` at the last ``len(Fd)`` samples of ``rec`` (the inverse model), and
    where they were out of reach."""
    from ..identification.inverse import inverse_control

    m = np.size(Fd)
    desired = np.zeros(len(rec))
    desired[-m:] = Fd
    r = inverse_control(
        damper.model, rec, desired, damper.values, control_range=damper.control_range, control_kind=kind or "current"
    )
    return r.control[-m:], r.unreachable[-m:]


def _check_controllable(damper: VehicleDamper, *, needs_inverse: bool) -> None:
    """Refuse, with a message naming the way out, a damper whose force the control cannot change or that has no
    inverse for a law that needs one."""
    from ..models.friction import LuGreModified

    model, name = damper.model, damper.label
    lo, hi = damper.control_range
    if not model.uses_control or hi <= lo:
        raise ErdesignError(
            f"{name}: semi-active control needs a damper whose force depends on the control and a "
            f"control range (max_field above 0); got range {damper.control_range}"
        )
    if damper.control_kind is None:
        raise ErdesignError(f"{name}: semi-active control needs the kind of control (give max_field with its unit)")
    probe_t = np.linspace(0.0, 0.02, 21)
    forces = []
    for c in (lo, hi):
        rec = Measurement(
            probe_t,
            0.1 * probe_t,
            None,
            np.full(21, 0.1),
            np.zeros(21),
            np.full(21, c),
            damper.control_kind,
            velocity_noise=0.0,
        )
        forces.append(float(model.force(rec, damper.values)[-1]))
    if not abs(forces[1] - forces[0]) > 1e-9 * max(1.0, abs(forces[0])):
        raise ErdesignError(
            f"{name}: with these parameters the force does not change with the control (its "
            "control coefficients are zero), so there is nothing to control; use passive"
        )
    if needs_inverse:
        affine = isinstance(model, ControlAffineModel) and not isinstance(model, LuGreModified)
        if not (damper.memoryless or affine):
            raise ErdesignError(
                f"{name}: this control law needs the damper's inverse model and {model.name} has "
                "none usable step by step (memoryless models, the physics damper without effects, "
                "kwok_tanh, magic_formula, bouc_wen_normalized, dahl_viscous, weng_arctan have); "
                "use clipped-optimal, which switches the control without an inverse"
            )


def settling_time(t, u, final, band):
    """Last time |u - final| exceeds ``band`` [s] (0 if never)."""
    outside = np.flatnonzero(np.abs(np.asarray(u) - final) > band)
    return float(t[outside[-1]]) if outside.size else 0.0


def write_history(path, response: VehicleResponse, *, overwrite: bool = False, option: str = "path") -> None:
    """Write the time history of a run as CSV (units in the header, as the measurement files) through the one
    writer of output files (:func:`erdesign.output.open_output`: atomic, never over an existing file unless
    ``overwrite``)."""
    import csv

    from ..fluid import CONTROL_UNITS
    from ..output import open_output

    columns = response.history()
    control_unit = CONTROL_UNITS.get(response.control_kind, "1")
    header = [f"{name} [{control_unit if unit == 'SI' else unit}]" for name, (_, unit) in columns.items()]
    data = np.column_stack([values for values, _ in columns.values()])
    with open_output(path, overwrite=overwrite, option=option, newline="") as fh:
        fh.write(f"# erdesign vehicle: {response.damper}, {response.controller}, {response.road.description}\n")
        w = csv.writer(fh)
        w.writerow(header)
        w.writerows([[f"{v:.10g}" for v in row] for row in data])
