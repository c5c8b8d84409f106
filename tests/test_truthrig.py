"""The truth rig, each mechanism against a check the rig did not compute (closed forms, erdesign.flow, quadrature)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from erdesign.damper.files import load_example
from erdesign.errors import ErdesignError
from erdesign.flow.bingham import bingham_pressure_drop
from erdesign.flow.mixed_mode import couette_poiseuille_bingham
from erdesign.simulation.rig import Motion, sine
from erdesign.simulation.truthrig import (
    MECHANISMS,
    TruthDamper,
    bingham_valve_flow,
    herschel_bulkley_valve_flow,
    mechanism_names,
    mixed_gap_flow,
    simulate_truth,
)
from erdesign.simulation.truthrig.mechanisms import ATMOSPHERIC_PRESSURE

MAKRIS = load_example("makris")
MR = load_example("mr_valve")  # tau_y 42 kPa at 200 kA/m: a yield force of 3.8 kN
E_MAKRIS, E_MR = 3e6, 2e5

LIBRARY = {
    "compliance": "compressibility",
    "herschel_bulkley": "shear_thinning",
    "bypass": "leakage",
    "accumulator": "gas_spring",
    "stribeck_friction": "seal_friction",
    "slug_inertia": "fluid_inertia",
    "coil_lag": "field_lag",
    "thermal": "viscous_heating",
    "preyield": "preyield_elasticity",
    "blowoff": None,
    "single_rod": None,
    "cavitation": None,
    "free_play": None,
}


def run(damper, mechanisms, motion, **kw):
    return simulate_truth(TruthDamper(damper, mechanisms, **kw), motion, force_noise=0.0, displacement_noise=0.0)


def manual_motion(v, control=0.0, rate=1000.0):
    """A motion with chosen velocities at the samples (forces of the rigid rig depend on the sample values only);
    short lists are repeated to the 32 samples a record needs at least (compare the first ones)."""
    v = np.asarray(v, dtype=float)
    v = np.resize(v, max(v.size, 32))
    t = np.arange(v.size) / rate
    return Motion(t, np.cumsum(v) / rate, v, np.zeros_like(v), np.full(v.size, float(control)), "manual")


def yield_force(damper, field):
    g = damper.geometry
    return 2.0 * float(damper.fluid.yield_stress_at(field)) * g.duct_length * g.piston_area / g.gap


# ---------------------------------------------------------------------------------------------- registry, API
def test_registry_names_library_effects_and_parameters():
    assert mechanism_names() == list(LIBRARY)
    for name, mech in MECHANISMS.items():
        assert mech.name == name and mech.title and mech.description
        assert mech.library_effect == LIBRARY[name]
        defaults = mech.parameters(MAKRIS)
        assert set(defaults) == set(mech.units)
        assert all(math.isfinite(v) and v >= 0 for v in defaults.values())


@pytest.mark.parametrize(
    "mechanisms, message",
    [
        ({"viscous_heating": {}}, "unknown mechanism 'viscous_heating'"),
        ({"coil_lag": {"tau": 1.0}}, "unknown parameter 'tau'"),
        ({"compliance": {"bulk_modulus": -1.0}}, "bulk_modulus: must be finite and > 0"),
        (["compliance", "preyield", "slug_inertia"], "compliance and preyield and slug_inertia cannot be combined"),
        (["free_play", "accumulator"], "accumulator and free_play cannot be combined"),
    ],
)
def test_bad_settings_are_clear_errors(mechanisms, message):
    with pytest.raises(ErdesignError, match=message):
        TruthDamper(MAKRIS, mechanisms)


def test_mixed_damper_refuses_valve_mechanisms():
    with pytest.raises(ErdesignError, match="blowoff need the valve's chambers"):
        TruthDamper(load_example("mr_mixed"), ["blowoff", "coil_lag"])
    with pytest.raises(ErdesignError, match="compliance and preyield cannot be combined on the mixed-mode"):
        TruthDamper(load_example("mr_mixed"), ["compliance", "preyield"])


def test_every_library_mechanism_runs_alone_and_deterministically():
    motion = sine(0.005, 2.0, E_MAKRIS, cycles=1, rate=400)
    for name in MECHANISMS:
        truth = TruthDamper(MAKRIS, [name])
        a = simulate_truth(truth, motion, seed=3)
        b = simulate_truth(truth, motion, seed=3)
        assert np.all(np.isfinite(a.true_force)), name
        np.testing.assert_array_equal(a.measured.force, b.measured.force)


# ---------------------------------------------------------------------------------------------- valve laws
def test_rigid_bingham_force_equals_erdesign_flow_bingham():
    # The rig inverts Q(dp) by a root; erdesign.flow.bingham solves the Makris cubic in closed form: 1e-10 is
    # round-off of the cubic's closed form well above the rig's root tolerance (1e-14).
    motion = sine(0.008, 1.5, E_MAKRIS, cycles=1, rate=500)
    rec = run(MAKRIS, {}, motion, viscosity_factor=1.2, yield_stress_factor=0.8)
    g, f = MAKRIS.geometry, MAKRIS.fluid
    v = motion.velocity
    dp = bingham_pressure_drop(
        v * g.piston_area / g.ducts,
        0.8 * f.yield_stress_at(E_MAKRIS),
        1.2 * f.viscosity_at(E_MAKRIS),
        g.duct_length,
        g.duct_mean_diameter,
        g.gap,
    )
    np.testing.assert_allclose(rec.components["fluid"], dp * g.piston_area, rtol=1e-10)
    np.testing.assert_array_equal(rec.components["friction"], 112.0 * np.sign(v))  # Makris eq 14, P_y = 112 N


def test_force_jumps_by_twice_the_yield_force_at_a_reversal():
    v = np.array([1e-12, -1e-12])
    rec = run(MR, {}, manual_motion(v, E_MR))
    Fy = yield_force(MR, E_MR)  # 2 tau_y L Ap / h: the blocked-gap force (MR has no seal friction)
    np.testing.assert_allclose(rec.true_force[:2], [Fy, -Fy], rtol=1e-6)


def test_bingham_flow_newtonian_limit():
    # tau_y -> 0: Q = pi d h^3 dp / (12 eta L) (Makris eq 4)
    dp = np.array([1e3, 1e5, 3e6])
    q = bingham_valve_flow(dp, 0.0, 7.0, 0.0546, 0.0143, 0.8e-3)
    np.testing.assert_allclose(q, math.pi * 0.0143 * 0.8e-3**3 * dp / (12 * 7.0 * 0.0546), rtol=1e-14)


def test_herschel_bulkley_with_unit_index_is_bingham():
    dp = np.linspace(0.0, 5e6, 41)
    np.testing.assert_array_equal(
        herschel_bulkley_valve_flow(dp, 42e3, 0.11, 1.0, 0.04, 0.03, 1e-3),
        bingham_valve_flow(dp, 42e3, 0.11, 0.04, 0.03, 1e-3),
    )


@pytest.mark.parametrize("m", [0.4, 0.7, 1.3])
def test_herschel_bulkley_flow_equals_quadrature_of_the_velocity_profile(m):
    # Independent route: velocity u(y) = integral of the shear rate from y to the wall, then Q = pi d * 2 int u dy;
    # quad converges to ~1e-12 on these smooth integrands, so 1e-8 leaves room for the nested quadrature.
    tau_y, eta, L, d, h, dp = 5e3, 0.2, 0.04, 0.03, 1e-3, 1.2e6
    K = eta * 1000.0 ** (1 - m)
    G, H = dp / L, h / 2
    y0 = tau_y / G

    def rate(y):
        return ((G * y - tau_y) / K) ** (1 / m) if y > y0 else 0.0

    def u(y):
        return quad(rate, max(y, y0), H, epsabs=0, epsrel=1e-13)[0]

    q = 2 * math.pi * d * (u(0.0) * y0 + quad(u, y0, H, epsabs=0, epsrel=1e-12)[0])
    assert herschel_bulkley_valve_flow(dp, tau_y, eta, m, L, d, h) == pytest.approx(q, rel=1e-8)


# ---------------------------------------------------------------------------------------------- compliance
def test_compliance_at_zero_field_is_a_maxwell_element():
    # Newtonian duct (E = 0) + compressible column: F + (C/k) F' = C v, so for x = X0 sin wt the steady force is
    # C X0 w / sqrt(1 + (w lam)^2) cos(wt - phi), tan phi = w lam, lam = C/k (Makris eq 13 at the damper level).
    g = MAKRIS.geometry
    beta, V = 6.4e7, g.piston_area * g.piston_diameter
    k = 2 * beta * g.piston_area**2 / V
    C = 12 * 7.0 * g.duct_length * g.piston_area**2 / (math.pi * g.duct_mean_diameter * g.gap**3)
    lam, f, X0 = C / k, 2.0, 0.004
    w = 2 * math.pi * f
    motion = sine(X0, f, 0.0, cycles=6, rate=1000)
    rec = run(MAKRIS, {"compliance": {"bulk_modulus": beta}}, motion)
    last = motion.time >= 5 / f  # transients decay as exp(-t/lam), lam = 0.04 s: gone by 2.5 s
    t, F = motion.time[last], rec.components["fluid"][last]
    basis = np.column_stack([np.cos(w * t), np.sin(w * t)])
    (ca, sa), *_ = np.linalg.lstsq(basis, F, rcond=None)
    # backward Euler on h = 1e-4 s: amplitude and phase errors O(h/lam, w h) ~ 2.5e-3 at most
    assert math.hypot(ca, sa) == pytest.approx(C * X0 * w / math.sqrt(1 + (w * lam) ** 2), rel=3e-3)
    assert math.atan2(sa, ca) == pytest.approx(math.atan(w * lam), abs=3e-3)


def test_compliance_force_ramps_as_a_spring_after_a_reversal():
    # After the top of the stroke the valve passes flow until the force has relaxed to F_y, then closes: from +F_y
    # to -F_y no fluid passes the duct, dF/dx = k_c exactly (the rig integrates the exact stroke increment), over
    # 2 F_y / k_c of stroke, and the valve yields again past -F_y.
    beta = 2e7
    g = MR.geometry
    kc = 2 * beta * g.piston_area**2 / (g.piston_area * g.piston_diameter)
    motion = sine(0.01, 1.0, E_MR, cycles=1.5, rate=2000)
    rec = run(MR, {"compliance": {"bulk_modulus": beta}}, motion)
    Fy, F, x = yield_force(MR, E_MR), rec.components["fluid"], motion.displacement
    after = np.arange(np.argmax(x), x.size)  # from the reversal at the top of the stroke
    closed = after[np.abs(F[after]) < Fy]
    closed = closed[: np.argmax(np.diff(closed) > 1) + 1] if np.any(np.diff(closed) > 1) else closed
    slope = np.diff(F[closed]) / np.diff(x[closed])
    np.testing.assert_allclose(slope, kc, rtol=1e-9)  # round-off of the sums of substep increments

    def crossing(level):  # stroke where F first falls through ``level``
        k = after[np.argmax(F[after] < level)]
        return np.interp(level, [F[k], F[k - 1]], [x[k], x[k - 1]])

    dx = np.abs(np.diff(x[closed[0] - 1 : closed[-1] + 2])).max()
    assert crossing(Fy) - crossing(-Fy) == pytest.approx(2 * Fy / kc, abs=2 * dx)  # one sample at each end
    assert 2 * Fy / kc > 100 * dx
    beyond = closed[-1] + 2
    assert (F[beyond] - F[beyond - 1]) / (x[beyond] - x[beyond - 1]) < 0.99 * kc  # yielding again


# ---------------------------------------------------------------------------------------------- paths in parallel
def test_bypass_creep_below_yield():
    Cl = 2e5
    speeds = np.linspace(-0.015, 0.015, 31)  # C_l |v| <= 3 kN < F_y = 3.8 kN: the duct is closed
    rec = run(MR, {"bypass": {"bypass_damping": Cl}}, manual_motion(speeds, E_MR))
    np.testing.assert_allclose(rec.components["fluid"][:31], Cl * speeds, rtol=1e-12, atol=1e-9)


def test_blowoff_caps_rebound_and_leaves_compression_alone():
    Fc, Cb = 4000.0, 2e4
    speeds = np.concatenate([-np.geomspace(1e-3, 0.5, 30), np.geomspace(1e-3, 0.5, 30)])
    motion = manual_motion(speeds, E_MR)
    plain = run(MR, {}, motion).components["fluid"]
    rec = run(MR, {"blowoff": {"cracking_force": Fc, "blowoff_damping": Cb}}, motion).components["fluid"]
    comp = speeds > 0
    np.testing.assert_array_equal(rec[comp], plain[comp])
    reb = ~comp
    slack = 1e-12 * np.abs(plain[reb])  # the two roots may differ in the last bits
    assert np.all(rec[reb] >= plain[reb] - slack) and np.all(-rec[reb] <= Fc + Cb * -speeds[reb] + slack)
    # where the valve is open, the duct carries v - (|F| - F_c) / C_b and erdesign.flow.bingham gives back |F|
    open_ = reb & (-rec > Fc)
    assert open_.sum() > 10
    g, tau, eta = MR.geometry, MR.fluid.yield_stress_at(E_MR), MR.fluid.viscosity_at(E_MR)
    v_duct = -speeds[open_] - (-rec[open_] - Fc) / Cb
    dp = bingham_pressure_drop(v_duct * g.piston_area, tau, eta, g.duct_length, g.duct_mean_diameter, g.gap)
    np.testing.assert_allclose(dp * g.piston_area, -rec[open_], rtol=1e-9)


def test_single_rod_compression_over_rebound_from_the_areas():
    g = MR.geometry
    Ac, Ar = math.pi / 4 * g.piston_diameter**2, g.piston_area
    v = np.array([0.2, -0.2])
    newtonian = run(MR, ["single_rod"], manual_motion(v, 0.0)).components["fluid"][:2]  # F = C' (A v) A ~ A^2
    assert -newtonian[0] / newtonian[1] == pytest.approx((Ac / Ar) ** 2, rel=1e-12)
    v = np.array([1e-9, -1e-9])
    blocked = run(MR, ["single_rod"], manual_motion(v, E_MR)).components["fluid"][:2]  # F -> dp_y A ~ A
    assert -blocked[0] / blocked[1] == pytest.approx(Ac / Ar, rel=1e-6)


def test_cavitation_caps_rebound_force():
    p_charge, p_vap = 3e6, 5e3
    cap = (p_charge - p_vap) * MR.geometry.piston_area
    motion = sine(0.02, 2.0, E_MR, cycles=1, rate=500)
    plain = run(MR, {}, motion).components["fluid"]
    rec = run(MR, {"cavitation": {"charge_pressure": p_charge, "vapour_pressure": p_vap}}, motion).components["fluid"]
    assert plain.min() < -1.2 * cap  # the cap is active
    assert rec.min() == pytest.approx(-cap, rel=1e-15)
    np.testing.assert_array_equal(rec[plain > -cap], plain[plain > -cap])


# ---------------------------------------------------------------------------------------------- additive forces
def test_accumulator_obeys_boyle_mariotte_for_isothermal_gas():
    # n = 1: p V = p0 Vg for the gas volume Vg - A_rod x (Boyle-Mariotte), force (p - p_atm) A_rod
    p0, Vg = 2e6, 5e-5
    motion = sine(0.02, 1.0, 0.0, cycles=1, rate=200)
    rec = run(MR, {"accumulator": {"charge_pressure": p0, "gas_volume": Vg, "polytropic_index": 1.0}}, motion)
    A_rod = math.pi / 4 * MR.geometry.rod_diameter**2
    p = rec.components["gas_spring"] / A_rod + ATMOSPHERIC_PRESSURE
    np.testing.assert_allclose(p * (Vg - A_rod * motion.displacement), p0 * Vg, rtol=1e-12)


def test_stribeck_curve_values():
    Fc, Fs, vs, cv = 80.0, 150.0, 0.01, 200.0
    v = np.array([1e-9, vs, -vs, 0.5, 0.0])
    rec = run(
        MR,
        {"stribeck_friction": {"coulomb_force": Fc, "static_force": Fs, "stribeck_speed": vs, "viscous_friction": cv}},
        manual_motion(v),
    )
    expected = [
        Fs + cv * 1e-9,
        Fc + (Fs - Fc) / math.e + cv * vs,
        -(Fc + (Fs - Fc) / math.e + cv * vs),
        Fc + cv * 0.5,
        0.0,
    ]
    np.testing.assert_allclose(rec.components["friction"][:5], expected, rtol=1e-9, atol=1e-12)


def test_slug_inertia_force_is_the_kinetic_energy_mass_times_acceleration():
    # the fluid moves at U = Ap v / (n pi d h) in the ducts: 1/2 rho (n pi d h L) U^2 = 1/2 m v^2
    g, rho = MAKRIS.geometry, MAKRIS.fluid.density
    U_per_v = g.piston_area / (g.ducts * math.pi * g.duct_mean_diameter * g.gap)
    m = rho * g.ducts * math.pi * g.duct_mean_diameter * g.gap * g.duct_length * U_per_v**2
    assert MECHANISMS["slug_inertia"].parameters(MAKRIS)["slug_mass"] == pytest.approx(m, rel=1e-12)
    X0, f = 0.005, 5.0
    motion = sine(X0, f, 0.0, cycles=1, rate=1000)
    rec = run(MAKRIS, ["slug_inertia"], motion)
    w = 2 * math.pi * f
    # the rig's sine has exact kinematics to ~1e-5 (fine-grid differences): m a = -m X0 w^2 sin(wt)
    inner = slice(1, -1)  # the end points carry one-sided differences
    np.testing.assert_allclose(
        rec.components["inertia"][inner], -m * X0 * w**2 * np.sin(w * motion.time[inner]), atol=1e-4 * m * X0 * w**2
    )


def test_coil_lag_step_response():
    T, E = 0.03, E_MAKRIS
    base = sine(0.005, 2.0, 0.0, cycles=1, rate=1000)
    t0 = base.time[100]
    motion = dataclasses.replace(base, control=np.where(base.time >= t0, E, 0.0))
    for mechanisms in (
        {"coil_lag": {"time_constant": T}},
        {"coil_lag": {"time_constant": T}, "thermal": {}},
    ):  # rigid and substepped paths
        seen = run(MAKRIS, mechanisms, motion).states["control_seen"]
        after = motion.time >= t0
        np.testing.assert_allclose(
            seen[after], E * (1 - np.exp(-(motion.time[after] - t0) / T)), rtol=1e-12, atol=1e-9 * E
        )
        assert np.all(seen[~after] == 0.0)


def test_two_stage_coil_lag_step_response():
    # two first-order stages in cascade (T1 = 15 ms, T2 = 8 ms): the step response of the product of the two
    # transfer functions, 1 - (T1 exp(-t/T1) - T2 exp(-t/T2)) / (T1 - T2); equal stages: 1 - (1 + t/T) exp(-t/T)
    base = sine(0.005, 2.0, 0.0, cycles=1, rate=1000)
    t0 = base.time[100]
    motion = dataclasses.replace(base, control=np.where(base.time >= t0, E_MAKRIS, 0.0))
    after = motion.time >= t0
    s = motion.time[after] - t0
    for T1, T2, expected in (
        (0.015, 0.008, 1 - (0.015 * np.exp(-s / 0.015) - 0.008 * np.exp(-s / 0.008)) / 0.007),
        (0.01, 0.01, 1 - (1 + s / 0.01) * np.exp(-s / 0.01)),
    ):
        for extra in ({}, {"thermal": {}}):  # rigid and substepped paths
            seen = run(MAKRIS, {"coil_lag": {"time_constant": T1, "second_time_constant": T2}, **extra}, motion).states[
                "control_seen"
            ]
            np.testing.assert_allclose(seen[after], E_MAKRIS * expected, rtol=1e-9, atol=1e-9 * E_MAKRIS)
            assert np.all(seen[~after] == 0.0)
    # 10 ms after the step the cascade has reached 23 % of the command, a single 15 ms stage 49 %
    i = np.searchsorted(motion.time, t0 + 0.010)
    two = run(MAKRIS, {"coil_lag": {"time_constant": 0.015, "second_time_constant": 0.008}}, motion)
    assert two.states["control_seen"][i] / E_MAKRIS == pytest.approx(
        1 - (0.015 * np.exp(-0.010 / 0.015) - 0.008 * np.exp(-0.010 / 0.008)) / 0.007, rel=1e-9
    )


# ---------------------------------------------------------------------------------------------- states in time
def test_thermal_energy_balance_and_thinning():
    C, tau = 50.0, 2.0
    motion = sine(0.008, 3.0, E_MAKRIS, cycles=12, rate=1000)
    rec = run(MAKRIS, {"thermal": {"heat_capacity": C, "cooling_time": tau, "temperature_coefficient": 0.02}}, motion)
    t, theta = motion.time, rec.states["temperature_rise"]
    work = np.trapezoid(rec.components["fluid"] * motion.velocity, t)
    heat = C * theta[-1] + np.trapezoid(C * theta / tau, t)
    # the rig balances every substep exactly; the difference is the trapezoid on the samples (O((w dt)^2) ~ 1e-4)
    assert heat == pytest.approx(work, rel=1e-3)
    assert theta[-1] > 5.0
    first, last = rec.components["fluid"][:334], rec.components["fluid"][-334:]
    assert last.max() < 0.95 * first.max()  # the oil thins as it warms: eta0 exp(-alpha T)


def test_preyield_small_amplitude_is_a_spring_and_large_amplitude_bingham():
    g, G = MR.geometry, 5e5
    Kpre = 12 * G * g.duct_length * g.piston_area**2 / (math.pi * g.duct_mean_diameter * g.gap**3)
    Fy = yield_force(MR, E_MR)
    X0 = 0.01 * Fy / Kpre  # K X0 = F_y / 100: eq 8 gives dF/dx = K (1 - F/F_y), within 1 %
    motion = sine(X0, 1.0, E_MR, cycles=1, rate=1000)
    F = run(MR, {"preyield": {"shear_modulus": G}}, motion).components["fluid"]
    slope = np.polyfit(motion.displacement, F, 1)[0]
    assert slope == pytest.approx(Kpre, rel=0.02)
    big = sine(0.02, 2.0, E_MR, cycles=2, rate=1000)
    F = run(MR, {"preyield": {"shear_modulus": G}}, big).components["fluid"]
    rigid = run(MR, {}, big).components["fluid"]
    fast = (big.time > 0.5) & (np.abs(big.velocity) > 0.5 * np.abs(big.velocity).max())
    # relaxation time F_r / (K v) ~ 1e-4 s at these speeds: the stress sits on the Bingham force to ~0.1 %
    np.testing.assert_allclose(F[fast], rigid[fast], rtol=5e-3)


def test_free_play_zero_force_in_the_gap():
    delta = 1e-3
    motion = sine(0.005, 2.0, E_MR, cycles=1.25, rate=2000)
    rec = run(MR, {"free_play": {"half_width": delta}}, motion)
    x, xp = motion.displacement, rec.states["piston_displacement"]
    assert np.all(np.abs(x - xp) <= delta + 1e-15)  # the play operator's width
    i_top = np.argmax(x)
    after = np.arange(i_top, x.size)
    gap = after[(rec.true_force[after] == 0.0)]
    gap = gap[gap < gap[0] + np.argmax(np.diff(gap) > 1) + 1] if np.any(np.diff(gap) > 1) else gap
    crossed = x[gap[0]] - x[gap[-1]]
    dx = np.abs(np.diff(x[gap[0] - 1 : gap[-1] + 2])).max()
    assert crossed == pytest.approx(2 * delta, abs=dx)  # within one sample of stroke
    assert rec.true_force[gap[-1] + 1] < -yield_force(MR, E_MR)  # engaged again in rebound


# ---------------------------------------------------------------------------------------------- mixed mode, files
def test_mixed_mode_rigid_force_equals_damper_state():
    # erdesign.damper calls the mixed-mode solver through its own wrapper (mixed_mode_damper_force); same speeds
    damper = load_example("mr_mixed")
    motion = sine(0.01, 2.0, 2e5, cycles=1, rate=400)
    rec = run(damper, {}, motion)
    moving = motion.velocity != 0
    ref = damper.state(motion.velocity, motion.control).force
    np.testing.assert_allclose(rec.true_force[moving], ref[moving], rtol=1e-12)


MIXED, KW = load_example("mr_mixed"), load_example("kamath_wereley")


@pytest.mark.parametrize(
    "U, q, tau_y, eta",
    [
        (0.05, -1e-3, 2000.0, 0.1),  # floating plug (the damper's regime)
        (0.2, -5e-3, 75e3, 0.25),
        (-0.2, 5e-3, 75e3, 0.25),  # rebound: all signs reverse
        (0.01, -1e-5, 75e3, 0.25),  # creeping head, nearly blocked gap
        (0.1, 2e-5, 100.0, 0.3),  # forward flow, plug at a wall
        (0.1, 7e-5, 500.0, 0.2),  # fully yielded
        (0.1, -2e-4, 0.0, 0.2),  # Newtonian
    ],
)
def test_mixed_gap_flow_inverts_the_couette_poiseuille_solver(U, q, tau_y, eta):
    # Two independent routes: erdesign.flow solves for the pressure gradient from the flow (scipy find_root on its
    # own regime equations), the rig for the flow from the pressure drop (Newton on the wall stress): they agree to
    # round-off of the nested roots.
    h, L, d = 1e-3, 0.025, 0.041
    ref = couette_poiseuille_bingham(U, q, tau_y, eta, h)
    Q, tau = mixed_gap_flow(ref.pressure_gradient * L, U, tau_y, eta, 1.0, L, d, h)
    assert Q == pytest.approx(math.pi * d * q, rel=1e-10, abs=1e-16)
    assert tau == pytest.approx(-ref.wall_stress_moving, rel=1e-10)  # the traction on the head is -tau


@pytest.mark.parametrize("m", [0.5, 0.7])
def test_mixed_gap_flow_herschel_bulkley_equals_quadrature(m):
    # The profile from the returned wall stress: tau(y) = tau_h - g (h - y), rate from the law, u(0) = 0; its
    # integral must reach the head's speed at y = h and carry the returned flow (quad, breakpoints at the yield
    # surfaces).
    tau_y, eta, L, d, h, dp, U = 3e3, 0.3, 0.03, 0.04, 1e-3, 4e5, 0.15
    Q, tau_h = mixed_gap_flow(dp, U, tau_y, eta, m, L, d, h)
    K, g = eta * 1000.0 ** (1 - m), dp / L

    def rate(y):
        tau = tau_h - g * (h - y)
        return math.copysign((max(abs(tau) - tau_y, 0.0) / K) ** (1 / m), tau)

    kinks = [y for y in ((tau_h - g * h - s) / -g for s in (tau_y, -tau_y)) if 0 < y < h]

    def u(y):
        return quad(rate, 0.0, y, points=[k for k in kinks if k < y] or None, epsabs=0, epsrel=1e-11)[0]

    assert u(h) == pytest.approx(U, rel=1e-9)
    assert quad(u, 0.0, h, points=kinks or None, epsrel=1e-11)[0] * math.pi * d == pytest.approx(Q, rel=1e-8)


def _newtonian_mixed_force(damper, v, eta, bypass_damping=math.inf):
    # plane Couette-Poiseuille flow of a Newtonian fluid: Q_gap = b (v h / 2 - h^3 dp / (12 eta L)), the bypass
    # passes A_p^2 dp / C_l, together A_p v; the head feels dp A_p plus (eta v / h + dp h / (2 L)) on its wall
    g = damper.geometry
    Ap, b, h, L = g.piston_area, math.pi * g.duct_mean_diameter, g.gap, g.duct_length
    dp = (Ap * v + b * v * h / 2) / (b * h**3 / (12 * eta * L) + Ap**2 / bypass_damping)
    return dp * Ap + (eta * v / h + dp * h / (2 * L)) * math.pi * g.piston_diameter * L


def test_mixed_newtonian_head_with_bypass_is_the_closed_form():
    Cl = 400.0
    motion = manual_motion(np.linspace(-0.3, 0.3, 41), control=0.0)
    rec = run(KW, {"bypass": {"bypass_damping": Cl}}, motion)
    eta = float(KW.fluid.viscosity_at(0.0))
    np.testing.assert_allclose(
        rec.components["fluid"], _newtonian_mixed_force(KW, motion.velocity, eta, Cl), rtol=1e-11, atol=1e-12
    )


def test_mixed_preyield_stiffness_and_limits():
    G = 4e5
    truth = TruthDamper(MIXED, {"preyield": {"shear_modulus": G}})
    assert truth.preyield_stiffness == pytest.approx(_newtonian_mixed_force(MIXED, 1.0, G), rel=1e-12)
    Kpre, Fy = truth.preyield_stiffness, abs(float(run(MIXED, {}, manual_motion([1e-6], 2e5)).true_force[0]))
    X0 = 0.01 * Fy / Kpre  # small amplitude: a spring of stiffness K within 1 %
    F = run(MIXED, {"preyield": {"shear_modulus": G}}, sine(X0, 1.0, 2e5, cycles=1, rate=1000)).components["fluid"]
    assert np.polyfit(sine(X0, 1.0, 2e5, cycles=1, rate=1000).displacement, F, 1)[0] == pytest.approx(Kpre, rel=0.02)
    big = sine(0.02, 2.0, 2e5, cycles=2, rate=1000)
    F = run(MIXED, {"preyield": {"shear_modulus": G}}, big).components["fluid"]
    fast = (big.time > 0.5) & (np.abs(big.velocity) > 0.5 * np.abs(big.velocity).max())
    np.testing.assert_allclose(F[fast], run(MIXED, {}, big).components["fluid"][fast], rtol=5e-3)


def test_mixed_compliance_at_zero_field_follows_its_linear_ode():
    # Newtonian fluid: P' = k_c (v + Q(P/A_p, v) / A_p) is linear in P; solve_ivp at tight tolerance is the
    # independent route.  Backward Euler on substeps of 0.1 ms takes the head's drag term at the step's end: an
    # error O(w h / 2) ~ 1e-3 of the force, after the start-up transient (time constant C / k_c = 0.28 ms).
    g = KW.geometry
    Ap, b, h, L = g.piston_area, math.pi * g.duct_mean_diameter, g.gap, g.duct_length
    beta, eta = 5e6, float(KW.fluid.viscosity_at(0.0))
    motion = sine(0.004, 3.0, 0.0, cycles=3, rate=1000)
    truth = TruthDamper(KW, {"compliance": {"bulk_modulus": beta}})
    kc = truth.compliance_stiffness
    rec = simulate_truth(truth, motion, force_noise=0.0, displacement_noise=0.0)
    X0, w = 0.004, 2 * math.pi * 3.0

    def rhs(t, P):
        v = X0 * w * math.cos(w * t)
        return kc * (v + b * (v * h / 2 - h**3 * P / (Ap * 12 * eta * L)) / Ap)

    t = motion.time
    P = solve_ivp(rhs, (0, t[-1]), [0.0], t_eval=t, rtol=1e-11, atol=1e-9, method="LSODA").y[0]
    v = motion.velocity
    F = P + (eta * v / h + P / Ap * h / (2 * L)) * math.pi * g.piston_diameter * L
    scale = np.abs(F).max()
    assert np.abs(rec.components["fluid"] - F)[5:].max() < 2e-3 * scale
    assert np.abs(F - _newtonian_mixed_force(KW, v, eta)).max() > 0.2 * scale  # the column matters here


def test_mixed_compliance_energy_balance():
    # work done on the head = energy dissipated in the gap + energy stored in the column, to the quadrature error
    beta = 3e7
    motion = sine(0.01, 2.0, 2e5, cycles=2, rate=1000)
    truth = TruthDamper(MIXED, {"compliance": {"bulk_modulus": beta}})
    rec = simulate_truth(truth, motion, force_noise=0.0, displacement_noise=0.0)
    work = np.trapezoid(rec.components["fluid"] * motion.velocity, motion.time)
    P = rec.states["valve_force"]
    stored = P[-1] ** 2 / (2 * truth.compliance_stiffness)
    assert np.sum(rec.states["dissipated"]) + stored == pytest.approx(work, rel=2e-3)


def test_compliance_in_series_with_preyield_limits_and_stiffness():
    # one force through the column (k_c) and the elastic fluid (K): a stiff column gives the pre-yield element
    # alone, a stiff fluid the column alone, and at small amplitude the series spring 1 / (1/k_c + 1/K)
    # (a soft fluid, G = 1 kPa, so that both springs matter: K = 2.3 k_c; a real MR fluid is 100-1000 x stiffer)
    motion = sine(0.01, 1.0, E_MR, cycles=1.5, rate=1000)
    G, beta = 1e3, 5e7
    both = run(MR, {"compliance": {"bulk_modulus": beta}, "preyield": {"shear_modulus": G}}, motion).true_force
    pre = run(MR, {"preyield": {"shear_modulus": G}}, motion).true_force
    col = run(MR, {"compliance": {"bulk_modulus": beta}}, motion).true_force
    stiff_col = run(MR, {"compliance": {"bulk_modulus": 1e14}, "preyield": {"shear_modulus": G}}, motion).true_force
    stiff_fluid = run(
        MR, {"compliance": {"bulk_modulus": beta}, "preyield": {"shear_modulus": 1e12}}, motion
    ).true_force
    scale = np.abs(pre).max()
    assert np.abs(stiff_col - pre).max() < 1e-3 * scale
    assert np.abs(stiff_fluid - col).max() < 1e-2 * scale
    assert np.abs(both - pre).max() > 0.05 * scale and np.abs(both - col).max() > 0.05 * scale
    truth = TruthDamper(MR, {"compliance": {"bulk_modulus": beta}, "preyield": {"shear_modulus": G}})
    k = 1 / (1 / truth.compliance_stiffness + 1 / truth.preyield_stiffness)
    X0 = 0.01 * yield_force(MR, E_MR) / k
    small = sine(X0, 1.0, E_MR, cycles=1, rate=1000)
    F = run(MR, {"compliance": {"bulk_modulus": beta}, "preyield": {"shear_modulus": G}}, small).true_force
    assert np.polyfit(small.displacement, F - rec_friction(small), 1)[0] == pytest.approx(k, rel=0.02)


def rec_friction(motion):
    return MR.seal_friction * np.sign(motion.velocity)


def test_record_round_trip_through_the_csv_reader(tmp_path):
    truth = TruthDamper(MAKRIS, {"compliance": {"bulk_modulus": 2e8}, "coil_lag": {}}, viscosity_factor=1.1)
    rec = simulate_truth(truth, sine(0.005, 2.0, E_MAKRIS, cycles=1, rate=300), seed=4, name="case-001")
    path = rec.write(tmp_path / "case.csv")
    text = path.read_text().splitlines()
    assert text[0].startswith("# truth rig: makris-1996") and "bulk_modulus = 2e+08 Pa" in text[0]
    assert "displacement [mm]" in text[1] and "[kV/mm]" in text[1]
    back = rec.read_back(path)
    for name in ("time", "displacement", "force", "control"):  # 10 significant digits in the file
        np.testing.assert_allclose(getattr(back, name), getattr(rec.measured, name), rtol=1e-9, atol=1e-15)
    with pytest.raises(ErdesignError, match="does not overwrite"):
        rec.write(path)
