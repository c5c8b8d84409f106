"""The one quasi-steady force kernel (erdesign/damper/quasi_steady.py): vectorised over geometry, it is Damper.state."""

import warnings

import numpy as np
import pytest

from erdesign import Damper, Fluid, Geometry
from erdesign.damper.quasi_steady import (
    QuasiSteadyState,
    mixed_gap_table,
    mixed_state,
    quasi_steady_state,
    valve_pressure_drop,
    valve_state,
)
from erdesign.flow.mixed_mode import mixed_mode_yield_force
from erdesign.flow.newtonian import slit_pressure_drop

FLUID = Fluid.create(
    viscosity="0.3 Pa*s",
    yield_stress="3 kPa",
    reference_field="3 kV/mm",
    yield_exponent=2.0,
    density="1200 kg/m^3",
    viscosity_at_reference_field="0.5 Pa*s",
)
V = np.array([0.0, -0.0, 1e-9, -1e-9, 1e-4, 0.02, -0.02, 0.3, -1.5])
E = np.array([0.0, 0.4e6, 3e6, -2e6])
SEAL = 25.0

# (h, L, d, Dp, dr, n) per damper; the valve ones are thin (h/d <= 0.06) for "thin_gap" and wide (h/d >= 0.12)
# for "annulus", so that flow_model="auto" would pick the same model
THIN = [
    (0.8e-3, 0.05, 0.0143, 0.0334, 0.01125, 1),
    (1.0e-3, 0.04, 0.03, 0.04, 0.012, 2),
    (0.5e-3, 0.09, 0.02, 0.06, 0.02, 4),
]
WIDE = [
    (2.0e-3, 0.05, 0.0143, 0.0334, 0.01125, 1),
    (4.0e-3, 0.04, 0.03, 0.04, 0.012, 3),
    (3.0e-3, 0.03, 0.012, 0.025, 0.008, 1),
]
MIXED = [
    (1.0e-3, 0.02, None, 0.03, 0.01, 1),
    (2.54e-3, 0.05, None, 0.038, 0.0127, 1),
    (0.6e-3, 0.08, None, 0.05, 0.02, 1),
]
CASES = {"thin_gap": ("valve", THIN), "annulus": ("valve", WIDE), "mixed": ("mixed", MIXED)}


def _damper(configuration, row, flow_model):
    h, L, d, Dp, dr, n = row
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the wide gaps warn that the exact annulus is used
        g = Geometry.create(
            configuration=configuration,
            gap=f"{h} m",
            duct_length=f"{L} m",
            duct_mean_diameter=None if d is None else f"{d} m",
            piston_diameter=f"{Dp} m",
            rod_diameter=f"{dr} m",
            ducts=n,
        )
    return Damper(geometry=g, fluid=FLUID, seal_friction=SEAL, flow_model=flow_model)


@pytest.mark.parametrize("case", CASES)
def test_kernel_over_geometries_is_damper_state_one_by_one(case):
    # The kernel is called once on arrays of shape (dampers, fields, velocities); each damper built on its own
    # and asked through Damper.state must give the same state.  Both routes run the same operations element by
    # element, so they agree to rounding: 1e-13 relative (the annulus root is converged to ~1e-15, element-wise).
    configuration, rows = CASES[case]
    flow_model = "auto" if case == "mixed" else case
    dampers = [_damper(configuration, row, flow_model) for row in rows]
    geo = [
        np.array([getattr(dm.geometry, k) for dm in dampers], dtype=float)[:, None, None]
        for k in ("gap", "duct_length", "duct_mean_diameter", "piston_diameter", "rod_diameter", "ducts")
    ]
    exact = np.array([dm.uses_exact_annulus for dm in dampers])[:, None, None]
    assert exact.all() == (case == "annulus") and exact.any() == (case == "annulus")
    tau_y = FLUID.yield_stress_at(E)[None, :, None]
    eta = FLUID.viscosity_at(E)[None, :, None]
    s = quasi_steady_state(configuration, V[None, None, :], tau_y, eta, FLUID.density, SEAL, *geo, exact_annulus=exact)
    for i, dm in enumerate(dampers):
        one = dm.state(V[None, :], E[:, None])
        for name in QuasiSteadyState._fields:
            got = np.broadcast_to(getattr(s, name), (len(dampers), E.size, V.size))[i]
            want = np.broadcast_to(getattr(one, name), (E.size, V.size))
            np.testing.assert_allclose(got, want, rtol=1e-13, atol=0.0, err_msg=f"{case}: {name}, damper {i}")


def test_exact_annulus_chosen_per_element():
    # One call with thin and wide ducts mixed, the flag per element, equals the two calls apart.
    rows = THIN + WIDE
    h, L, d, Dp, dr, n = (np.array(c, dtype=float)[:, None] for c in zip(*rows))
    exact = np.array([False] * len(THIN) + [True] * len(WIDE))[:, None]
    args = (0.05 * V[None, :] / V.max(), 2000.0, 0.4, 1200.0, SEAL)
    both = quasi_steady_state("valve", *args, h, L, d, Dp, dr, n, exact_annulus=exact)
    thin = quasi_steady_state("valve", *args, h[:3], L[:3], d[:3], Dp[:3], dr[:3], n[:3], exact_annulus=False)
    wide = quasi_steady_state("valve", *args, h[3:], L[3:], d[3:], Dp[3:], dr[3:], n[3:], exact_annulus=True)
    np.testing.assert_array_equal(both.force, np.concatenate([thin.force, wide.force]))
    np.testing.assert_array_equal(both.plug_fraction, np.concatenate([thin.plug_fraction, wide.plug_fraction]))
    # and the exact annulus does differ from the thin gap at these h/d (else the test above proves nothing)
    thin_wide = quasi_steady_state("valve", *args, h[3:], L[3:], d[3:], Dp[3:], dr[3:], n[3:])
    assert np.max(np.abs(thin_wide.pressure_drop / wide.pressure_drop - 1)[:, 4:]) > 1e-3


def test_zero_field_valve_is_makris_eq4():
    # Makris et al. (1996) eq 4: with tau_y = 0 the duct is Newtonian, dp = 12 eta L Q / (pi d h^3), no plug;
    # the kernel's thin-gap branch must give it to rounding (1e-15: one division apart at most).
    h, L, d, Dp, dr, n = (np.array(c, dtype=float) for c in zip(*THIN))
    Ap = np.pi / 4 * (Dp**2 - dr**2)
    s = quasi_steady_state("valve", 0.02, 0.0, 0.3, 1200.0, 0.0, h, L, d, Dp, dr, n)
    np.testing.assert_allclose(s.pressure_drop, slit_pressure_drop(0.02 * Ap / n, 0.3, L, d, h), rtol=1e-15)
    np.testing.assert_array_equal(s.plug_fraction, 0.0)
    np.testing.assert_allclose(s.force, s.pressure_drop * Ap, rtol=1e-15)


def test_mixed_break_away_force_is_the_yield_force_plus_friction():
    # Kamath and Wereley (1997), section II; docs/theory/mixed_mode.md: as v -> 0+ the mixed-mode force tends to
    # tau_y (2 L A_p / h + pi Dp L), and the kernel returns that limit at v = +0 (-0.0: minus it).  The shear
    # drag's limit comes out of a root, so agreement to 1e-9 relative.
    h, L, d, Dp, dr, n = (np.array(c, dtype=float) for c in zip(*MIXED))
    d = Dp + h
    s = quasi_steady_state("mixed", np.array([[0.0], [-0.0]]), 3000.0, 0.3, 1200.0, SEAL, h, L, d, Dp, dr)
    Fy = mixed_mode_yield_force(3000.0, L, Dp, dr, h)
    np.testing.assert_allclose(s.force, [Fy + SEAL, -Fy - SEAL], rtol=1e-9)


def test_bad_configuration_is_an_error():
    with pytest.raises(ValueError, match="configuration"):
        quasi_steady_state("rotary", 0.1, 0.0, 1.0, 1000.0, 0.0, 1e-3, 0.05, 0.02, 0.04, 0.01)
    with pytest.raises(ValueError, match="one gap"):
        quasi_steady_state("mixed", 0.1, 0.0, 1.0, 1000.0, 0.0, 1e-3, 0.05, 0.041, 0.04, 0.01, exact_annulus=True)


@pytest.mark.parametrize("row", MIXED)
def test_mixed_gap_table_is_mixed_state_within_its_interpolation_error(row):
    """The physics model's fast path (MixedGapTable, linear interpolation in sqrt(1 - s)) against the bracketed
    root of mixed_state at every velocity and control, from creeping flow (plug filling the gap) to Newtonian."""
    h, L, _, Dp, dr, _ = row
    table = mixed_gap_table(h, Dp, dr)
    assert mixed_gap_table(h, Dp, dr) is table  # built once per head
    v = np.concatenate([-np.geomspace(1e-5, 2.0, 40), np.geomspace(1e-5, 2.0, 40)])
    for tau_y in (0.0, 50.0, 3e3, 40e3):
        eta = 0.3
        s = mixed_state(v, tau_y, eta, 1200.0, 0.0, h, L, Dp + h, Dp, dr)
        dp, shear = table.forces(v, tau_y, eta, L)
        np.testing.assert_allclose(dp, s.pressure_drop, rtol=1e-5, atol=0)
        np.testing.assert_allclose(shear, s.shear_force, rtol=1e-5, atol=1e-12 * np.max(np.abs(s.shear_force)))


def test_mixed_gap_table_compiled_pass_reads_the_table_as_np_interp():
    """MixedGapTable.forces runs one compiled pass over its uniform table: the values np.interp reads there, to a few
    ulp, for every sign and size of the speed and for zero, non-finite and broadcast inputs."""
    h, Dp, dr, L = 1e-3, 0.0381, 0.0127, 0.0254
    t = mixed_gap_table(h, Dp, dr)
    rng = np.random.default_rng(7)
    u = np.concatenate([rng.normal(0, 0.3, 500), rng.normal(0, 1e-5, 500), [0.0, -0.0, np.inf, -np.inf, np.nan]])
    tau_y = np.where(np.arange(u.size) % 5 == 0, 0.0, rng.uniform(0, 50e3, u.size))
    eta = rng.uniform(0.05, 1.0, u.size)
    eta[3] = np.inf
    # the interpolation of the module notes, written out with np.interp
    scale = eta * np.abs(u) + tau_y * h
    with np.errstate(divide="ignore", invalid="ignore"):
        w = np.sqrt(np.where(scale > 0, eta * np.abs(u) / scale, 1.0))
        sign = np.copysign(1.0, u)
        dp_ref = sign * np.interp(w, t.w, t.pressure) * scale / h**2 * L
        drag_ref = -sign * np.interp(w, t.w, t.shear) * scale / h * np.pi * Dp * L
    dp, drag = t.forces(u, tau_y, eta, L)
    np.testing.assert_allclose(dp, dp_ref, rtol=1e-13, atol=0, equal_nan=True)
    np.testing.assert_allclose(drag, drag_ref, rtol=1e-13, atol=0, equal_nan=True)
    assert t.forces(u, tau_y, eta, L, shear=False)[1] is None
    # broadcasting: a scalar control and viscosity against an array of speeds, and a 2-D array
    a, _ = t.forces(u[:10], 2e3, 0.3, L)
    b, _ = t.forces(u[:10].reshape(2, 5), 2e3, 0.3, L)
    assert a.shape == (10,) and b.shape == (2, 5) and np.array_equal(a, b.ravel())


def test_valve_pressure_drop_follows_the_damper_flow_model():
    """valve_pressure_drop is the gap law of valve_state: thin gap or exact annulus, bit for bit."""
    for rows, exact in ((THIN, False), (WIDE, True)):
        for h, L, d, Dp, dr, n in rows:
            Ap = np.pi / 4 * (Dp**2 - dr**2)
            v = np.array([-0.3, -1e-4, 0.02, 0.3])
            s = valve_state(v, 3e3, 0.3, 1200.0, 0.0, h, L, d, Ap, n, exact)
            assert np.array_equal(valve_pressure_drop(v * Ap / n, 3e3, 0.3, L, d, h, exact), s.pressure_drop)


def test_wide_gap_valve_with_a_closed_bypass_is_the_exact_annulus_baseline():
    """A bypass in parallel re-solves the gap flow: on a wide gap it must use the exact annulus, as the baseline
    does (before, it fell back to the thin gap: 8e-4 off on this damper, against 4e-9 now)."""
    from erdesign.data.measurement import Measurement
    from erdesign.effects.chain import PhysicsDamper

    damper = _damper("valve", WIDE[0], "auto")
    assert damper.uses_exact_annulus
    t = np.linspace(0, 1, 401)
    rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * 2 * t), control=3e6, control_kind="electric field")
    base = PhysicsDamper(damper)
    leaky = PhysicsDamper(damper, ["leakage"])
    values = base.initial_guess(rec)
    F0 = base.components(rec, values)["fluid"]
    F1 = leaky.components(rec, {**values, "bypass_damping": 1e9 * damper.damping_constant_si()})["fluid"]
    moving = np.abs(rec.velocity) > 0.05 * np.max(np.abs(rec.velocity))
    np.testing.assert_allclose(F1[moving], F0[moving], rtol=1e-6)
