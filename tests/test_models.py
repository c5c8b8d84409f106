"""The model library: every registered model on edge-case records, round trips, reference solutions, bad input."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from erdesign.data.measurement import Measurement
from erdesign.identification.fit import fit
from erdesign.models.base import ModelInputError, ParameterError
from erdesign.models.bingham import extended_bingham_force
from erdesign.models.bouc_wen import SPENCER_PASSIVE
from erdesign.models.kamath_wereley import KAMATH_WERELEY_TABLE1
from erdesign.models.registry import describe_models, get_model, model_names
from erdesign.units import Q_

NAMES = [n for n in model_names() if n != "physics"]


def sine(amplitude=0.01, f_hz=1.0, cycles=2, n_per_cycle=1000, control=None, kind="current"):
    t = np.linspace(0, cycles / f_hz, cycles * n_per_cycle + 1)
    x = amplitude * np.sin(2 * np.pi * f_hz * t)
    if control is None:
        return Measurement.from_arrays(t, x)
    return Measurement.from_arrays(t, x, control=np.broadcast_to(control, t.shape), control_kind=kind)


def edge_records():
    rng = np.random.default_rng(0)
    t = np.linspace(0, 1, 501)
    yield "at rest", Measurement.from_arrays(t, np.zeros_like(t), control=np.zeros_like(t), control_kind="current")
    yield "1 nm", sine(1e-9, control=1.0)
    yield "fast and large", sine(0.1, f_hz=20.0, control=2.0)
    walk = np.cumsum(rng.standard_normal(t.size)) * 1e-4
    yield "random walk", Measurement.from_arrays(t, walk, control=rng.uniform(0, 1, t.size), control_kind="voltage")
    tu = np.sort(np.r_[0.0, rng.uniform(0, 1, 400), 1.0])
    yield (
        "uneven steps",
        Measurement.from_arrays(tu, 0.01 * np.sin(2 * np.pi * tu), control=0.5, control_kind="current"),
    )


@pytest.mark.parametrize("name", NAMES)
def test_every_model_gives_finite_forces_on_edge_cases(name):
    model = get_model(name)
    for label, rec in edge_records():
        F = model.simulate(rec)
        assert F.shape == rec.time.shape, label
        assert np.all(np.isfinite(F)), f"{name}: non-finite force on the '{label}' record"


def test_registry_entries_follow_the_contract():
    entries = describe_models()
    assert [e["name"] for e in entries] == model_names()
    contract = {
        "bingham",
        "bingham_extended",
        "powell",
        "bingmax",
        "maxwell",
        "bouc_wen",
        "bouc_wen_modified",
        "bouc_wen_normalized",
        "kamath_wereley_4",
        "kamath_wereley_6",
        "biviscous",
        "biviscous_hysteretic",
        "eyring_plastic",
        "semiactive_general",
        "dahl",
        "dahl_viscous",
        "lugre",
        "lugre_modified",
        "weng_arctan",
        "kwok_tanh",
        "magic_formula",
        "chebyshev",
        "maxwell_neural",
        "physics",
    }
    assert contract <= set(model_names())
    for e in entries:
        assert e["source"], e["name"]
        for p in e["parameters"]:
            Q_(p["default"], p["unit"])  # every unit parses
    with pytest.raises(ValueError, match="unknown model 'nope'"):
        get_model("nope")


def test_bad_input_is_named():
    short = Measurement.from_arrays(np.linspace(0, 1, 5), np.linspace(0, 1e-3, 5))
    model = get_model("kamath_wereley_6")
    model.min_samples = 10
    with pytest.raises(ModelInputError, match="5 samples; this model needs at least 10"):
        model.simulate(short)
    with pytest.raises(ModelInputError, match="no control column"):
        get_model("lugre_modified").simulate(sine())
    with pytest.raises(ParameterError, match="c0 = -1.0 N\\*s/m is outside its bounds"):
        get_model("bingham").simulate(sine(), {"c0": -1.0})
    uneven = Measurement.from_arrays(np.r_[0, np.cumsum(np.linspace(1e-3, 3e-3, 200))], np.zeros(201))
    strict = get_model("maxwell")
    strict.needs_uniform_time = True
    with pytest.raises(ModelInputError, match="evenly spaced time samples"):
        strict.simulate(uneven)


def test_extended_bingham_matches_a_tight_radau_solution():
    """Butz and von Stryk (2002) calls the model extremely stiff; backward Euler on the dead-zone form must converge
    to the exact
    solution.  Reference: the same dead-zone ODE by Radau (rtol 1e-10) on the analytic sine."""
    c0, fc, k1, c1, k2 = 2000.0, 500.0, 1e5, 2e4, 5e5
    X, w = 0.01, 2 * np.pi

    def rhs(t, s):
        x1, e = s
        F = k2 * (X * math.sin(w * t) - x1 - e)
        d = math.copysign(max(abs(F) - fc, 0.0), F)
        return [d / c0, (F - k1 * e) / c1]

    t = np.linspace(0, 2, 2001)
    ref = solve_ivp(rhs, (0, 2), [0.0, 0.0], method="Radau", t_eval=t, rtol=1e-10, atol=1e-13, max_step=1e-3)
    F_ref = k2 * (X * np.sin(w * t) - ref.y[0] - ref.y[1])
    F = extended_bingham_force(t, X * np.sin(w * t), c0, fc, k1, c1, k2)
    err = np.sqrt(np.mean((F - F_ref) ** 2)) / np.std(F_ref)
    # first order in the step: the default 64 sub-steps of 1/64 ms give 5e-5 relative RMS (issue 12 asks 1e-4)
    assert err < 1e-4
    # convergence, not luck: halving the step from 4 to 8 sub-steps halves the error (measured 5.5e-4 -> 2.8e-4)
    F4 = extended_bingham_force(t, X * np.sin(w * t), c0, fc, k1, c1, k2, substeps=4)
    err4 = np.sqrt(np.mean((F4 - F_ref) ** 2)) / np.std(F_ref)
    F8 = extended_bingham_force(t, X * np.sin(w * t), c0, fc, k1, c1, k2, substeps=8)
    err8 = np.sqrt(np.mean((F8 - F_ref) ** 2)) / np.std(F_ref)
    assert 0.4 < err8 / err4 < 0.6


#: Spencer, Dyke, Sain and Carlson (1997), Table 1 (as in shared/data/README.md), SI: N, m, s, V.
SPENCER_1997 = dict(
    c0a=2100.0,
    c0b=350.0,
    k0=4690.0,
    c1a=28300.0,
    c1b=295.0,
    k1=500.0,
    x0=0.143,
    alpha_a=14000.0,
    alpha_b=69500.0,
    alpha_c=0.0,
    gamma=3.63e6,
    beta=3.63e6,
    delta=301.0,
    n=2.0,
    eta=190.0,
)


def _piecewise_linear_reference(t, x, u, p):
    """(u_f, w, z) of the modified Bouc-Wen model for x and u linear between samples, by LSODA at rtol 1e-11 on
    each sample interval (the input's slope is discontinuous at the samples, so each interval is one smooth ODE)."""
    state = np.array([u[0], 0.0, 0.0])
    out = [state]
    for i in range(t.size - 1):
        h = t[i + 1] - t[i]
        xd, r = (x[i + 1] - x[i]) / h, (u[i + 1] - u[i]) / h

        def rhs(s, y, i=i, xd=xd, r=r):
            uf, w, z = y
            al = p["alpha_a"] + p["alpha_b"] * uf
            c0, c1 = p["c0a"] + p["c0b"] * uf, p["c1a"] + p["c1b"] * uf
            wd = (c1 * xd - al * z - p["k0"] * w) / (c0 + c1)
            zd = -p["gamma"] * abs(wd) * z * abs(z) - p["beta"] * wd * z * z + p["delta"] * wd
            return [-p["eta"] * (uf - u[i] - r * s), wd, zd]

        state = solve_ivp(rhs, (0.0, h), state, method="LSODA", rtol=1e-11, atol=1e-15).y[:, -1]
        out.append(state)
    return np.array(out).T


def test_modified_bouc_wen_matches_solve_ivp_at_3_khz_with_a_random_voltage():
    """Spencer et al. (1997) parameters with their voltage filter; band-limited random displacement (to 1.1 cm,
    like Dyke's ransim records) and a command voltage switched at random between 0 and 2.25 V every 20 ms, sampled
    at 3 kHz.  Reference: LSODA at rtol 1e-11 for the same piecewise-linear inputs (independent of the compiled
    kernel's RK4 / exact-Riccati scheme).  Required: 1e-4 of the force range (issue 12; measured 4e-6)."""
    p = SPENCER_1997
    rng = np.random.default_rng(0)
    t = np.arange(0.0, 0.5, 1 / 3000.0)
    f, phase = rng.uniform(0.5, 15.0, 12), rng.uniform(0, 2 * np.pi, 12)
    x = np.sum(np.sin(2 * np.pi * f[:, None] * t + phase[:, None]), axis=0)
    x *= 0.011 / np.max(np.abs(x))
    u = np.repeat(rng.uniform(0.0, 2.25, 26), 60)[: t.size]
    v = np.gradient(x, t)
    rec = Measurement.from_arrays(t, x, control=u, control_kind="voltage", velocity=v)
    model = get_model("bouc_wen_modified")
    F = model.simulate(rec, p)
    uf, w, z = _piecewise_linear_reference(t, x, u, p)
    al, c0, c1 = p["alpha_a"] + p["alpha_b"] * uf, p["c0a"] + p["c0b"] * uf, p["c1a"] + p["c1b"] * uf
    F_ref = c1 * (al * z + c0 * v + p["k0"] * w) / (c0 + c1) + p["k1"] * (x - p["x0"])
    assert np.max(np.abs(F - F_ref)) < 1e-4 * np.ptp(F_ref)


def test_modified_bouc_wen_matches_solve_ivp_with_spencer_parameters():
    """Butz and von Stryk (2002) section 4.3 parameters (passive); reference: LSODA at rtol 1e-10 on the analytic
    sine velocity.
    At 3 kHz the piecewise-linear reading of the sampled sine differs from the sine by (omega h)^2 / 24 ~ 2e-7 of
    the velocity, so the kernel must agree to 1e-4 of the force range (measured 3e-5)."""
    p = SPENCER_PASSIVE
    rec = sine(0.01, 1.0, cycles=2, n_per_cycle=3000)
    F = get_model("bouc_wen_modified").simulate(rec, p)

    def rhs(t, s):
        w, z = s
        xd = 0.01 * 2 * np.pi * math.cos(2 * np.pi * t)
        wd = (p["c1a"] * xd - p["alpha_a"] * z - p["k0"] * w) / (p["c0a"] + p["c1a"])
        return [wd, wd * p["delta"] - p["gamma"] * abs(wd) * z * abs(z) - p["beta"] * wd * z * z]

    ref = solve_ivp(rhs, (0, 2), [0.0, 0.0], t_eval=rec.time, method="LSODA", rtol=1e-10, atol=1e-14)
    w, z = ref.y
    wd = (p["c1a"] * rec.velocity - p["alpha_a"] * z - p["k0"] * w) / (p["c0a"] + p["c1a"])
    F_ref = p["c1a"] * (rec.velocity - wd) + p["k1"] * rec.displacement
    assert np.max(np.abs(F - F_ref)) < 1e-4 * np.ptp(F_ref)


@pytest.mark.parametrize(
    "beta,gamma,delta,n",
    [
        (2e6, 2e6, 207.0, 2.0),  # Spencer's passive damper (n = 2)
        (-1e6, 3e6, 207.0, 2.0),  # beta < 0: the tan branch
        (0.0, 1500.0, 1500.0, 1.0),  # normalised form, sigma = 1, n = 1
        (2e8, 2e8, 207.0, 3.0),
    ],
)  # n = 3: RK4 in the travel
def test_bouc_wen_state_matches_radau(beta, gamma, delta, n):
    """The Bouc-Wen variable (Butz and von Stryk 2002, eq 9) on a 1 Hz, 1 cm sine sampled at 3 kHz against Radau at
    rtol 1e-10
    on the analytic velocity.  The kernel is exact for n = 1, 2 (closed form) given the piecewise-linear input,
    which differs from the sine by ~2e-7: 1e-4 of the range of z is required (issue 12)."""
    from erdesign.models._kernels import bouc_wen_state

    t = np.linspace(0, 2, 6001)
    x = 0.01 * np.sin(2 * np.pi * t)
    z = bouc_wen_state(x, beta, gamma, delta, n)

    def rhs(tt, s):
        xd = 0.01 * 2 * np.pi * math.cos(2 * np.pi * tt)
        q = s[0]
        return [-gamma * abs(xd) * q * abs(q) ** (n - 1) - beta * xd * abs(q) ** n + delta * xd]

    ref = solve_ivp(rhs, (0, 2), [0.0], t_eval=t, method="Radau", rtol=1e-10, atol=1e-14, max_step=1e-3).y[0]
    assert np.max(np.abs(z - ref)) < 1e-4 * np.ptp(ref)
    if n == 2.0 and beta == gamma:
        # saturation (delta / (beta + gamma))^(1/n), Bouc-Wen's bound
        assert np.max(np.abs(z)) == pytest.approx(math.sqrt(delta / (beta + gamma)), rel=1e-6)


def _round_trip(name, true, record, *, free=None, fixed=None, noise_frac=0.01, starts=1, tol=0.05, seed=1):
    model = get_model(name)
    clean = model.simulate(record, true)
    noise = noise_frac * np.std(clean)
    rng = np.random.default_rng(seed)
    rec = record.with_force(clean + noise * rng.standard_normal(len(record)))
    r = fit(model, rec, free=free, fixed=fixed, starts=starts)
    floor = noise**2 / np.var(rec.force)
    # ESR at the noise floor: the fitted model explains all but the noise (within 25 % for some 2000 samples)
    assert r.esr == pytest.approx(floor, rel=0.25), name
    for k in r.free:
        if k in true:
            # within the stated relative tolerance, or 4 standard errors for values near zero (offsets)
            allowed = max(tol * abs(true[k]), 4 * r.stderr[k])
            assert abs(r.values[k] - true[k]) <= allowed, (name, k, r.values[k], true[k])
    return r


ROUND_TRIPS = {
    # name: (true values, record options, free, tolerance)
    "bingham": ({"c0": 5000.0, "f_c": 670.0, "f0": 20.0}, {}, None, 0.01),
    "kwok_tanh": ({"k": 2000.0, "c": 3000.0, "alpha": 600.0, "beta": 300.0, "delta": 0.3, "f0": 10.0}, {}, None, 0.03),
    "dahl": ({"k0": 1000.0, "c0": 2500.0, "f_d": 500.0, "rho": 2000.0, "f0": 5.0}, {}, None, 0.03),
    "lugre": (
        {"sigma0": 5e5, "sigma1": 0.0, "sigma2": 2500.0, "a0": 2e-3, "f0": 0.0},
        {},
        ["sigma0", "sigma2", "a0", "f0"],
        0.03,
    ),
    "biviscous": ({"C_pre": 1e5, "C_post": 3000.0, "F_y": 600.0, "f0": 0.0}, {}, None, 0.03),
    "weng_arctan": (
        {"f_y": 500.0, "c_b": 2000.0, "k": 300.0, "v0": 0.004, "m": 0.0, "f0": 0.0},
        {},
        ["f_y", "c_b", "k", "v0", "f0"],
        0.03,
    ),
    "kamath_wereley_6": (
        {**KAMATH_WERELEY_TABLE1},
        {"amplitude": 1e-3, "f_hz": 10.0, "cycles": 3, "n_per_cycle": 600},
        None,
        0.1,
    ),
    "maxwell": ({"C": 1.2e5, "K": 2e6, "f0": 0.0}, {}, None, 0.02),
    "bingham_extended": ({"c0": 3000.0, "f_c": 400.0, "k1": 5e4, "c1": 3e4, "k2": 3e5, "f0": 0.0}, {}, None, 0.03),
    "bingmax": ({"C": 8e4, "K": 5e6, "F_y": 700.0, "f0": 0.0}, {}, None, 0.02),
    "bouc_wen": (
        {"c0a": 4000.0, "k0": 1000.0, "x0": 0.0, "alpha_a": 7e4, "beta": 1.5e6, "gamma": 2.5e6},
        {},
        ["c0a", "k0", "alpha_a", "beta", "gamma"],
        0.06,
    ),
    "kamath_wereley_4": (
        {"C1": 12000.0, "C2": 9000.0, "K1": 1.2e5, "Cv": 2500.0, "f0": 0.0},
        {"amplitude": 1e-3, "f_hz": 10.0, "cycles": 3, "n_per_cycle": 600},
        None,
        0.03,
    ),
    "biviscous_hysteretic": ({"C_pre": 2e5, "C_post": 4000.0, "F_y": 600.0, "v0": 0.004, "f0": 0.0}, {}, None, 0.03),
    # the general model of Vivas-López et al. (n.d.): its passive part (asymmetric damping, stiffness, friction);
    # the hysteresis terms
    # held at zero
    "semiactive_general": (
        {"c_p_pos": 3000.0, "c_p_neg": 2000.0, "k_p": 500.0, "f_f": 400.0, "v_f": 60.0, "f0": 0.0},
        {},
        ["c_p_pos", "c_p_neg", "k_p", "f_f", "v_f", "f0"],
        0.05,
    ),
    # Powell: the shape factor e of the smoothed sign and the softening spring held at their true values
    "powell": (
        {"f_cs": 300.0, "f_cd": 200.0, "a": 40.0, "b": 60.0, "e": 400.0, "c": 2500.0, "k": 0.0, "d": 100.0, "f0": 0.0},
        {},
        ["f_cs", "f_cd", "a", "b", "c"],
        0.05,
    ),
}


@pytest.mark.parametrize("name", sorted(ROUND_TRIPS))
def test_round_trip_recovers_parameters(name):
    true, opts, free, tol = ROUND_TRIPS[name]
    # parameters not fitted are held at their true values (a round trip tests the fit, not a guess of them)
    fixed = (
        {}
        if free is None
        else {
            k: v
            for k, v in {**get_model(name).defaults(), **true}.items()
            if k not in free and get_model(name).parameter(k).fitted
        }
    )
    _round_trip(name, true, sine(**opts), free=free, fixed=fixed, tol=tol)


def test_round_trip_modified_lugre_with_a_switched_control():
    """Sakai's modified LuGre (the MR-model review eqs 58-59) needs a control; a control switched between 0 and 1 separates
    the control-proportional stiffness sigma0 from the constant sigma_a."""
    t = np.linspace(0, 2, 2001)
    u = 0.5 + 0.5 * np.sign(np.sin(np.pi * t + 0.3))
    rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t), control=u, control_kind="voltage")
    true = {
        "sigma0": 8e5,
        "sigma1": 0.0,
        "sigma2": 2500.0,
        "sigma_a": 2e5,
        "sigma_b": 1500.0,
        "a0": 2e-3,
        "a1": 0.0,
        "f0": 0.0,
    }
    _round_trip(
        "lugre_modified",
        true,
        rec,
        free=["sigma0", "sigma2", "sigma_a", "sigma_b", "a0", "f0"],
        fixed={"sigma1": 0.0, "a1": 0.0},
        tol=0.03,
    )


def test_round_trip_spencer_modified_bouc_wen():
    """Butz and von Stryk (2002) section 4.3 (Spencer's damper): simulate, add 1 % noise, identify the nine free
    parameters
    (delta and n held, they are redundant / a priori) from a neutral start, recover them within 10 %."""
    true = dict(SPENCER_PASSIVE)
    rec = sine(0.01, 1.5, cycles=2, n_per_cycle=800)
    free = ["c0a", "c1a", "k0", "k1", "alpha_a", "beta", "gamma"]
    start = {"c0a": 4000.0, "c1a": 7e4, "k0": 1000.0, "k1": 400.0, "alpha_a": 8e4, "beta": 1.5e6, "gamma": 1.5e6}
    model = get_model("bouc_wen_modified")
    clean = model.simulate(rec, true)
    noise = 0.01 * np.std(clean)
    data = rec.with_force(clean + noise * np.random.default_rng(3).standard_normal(len(rec)))
    r = fit(model, data, free=free, start=start)
    assert r.esr == pytest.approx(noise**2 / np.var(data.force), rel=0.25)
    for k in ("c0a", "alpha_a", "beta", "gamma"):
        assert r.values[k] == pytest.approx(true[k], rel=0.10), k


@pytest.mark.slow
@pytest.mark.parametrize(
    "name,true",
    [
        (
            "magic_formula",
            {"D": 600.0, "C": 1.2, "B": 150.0, "E": -0.5, "A": 3.0, "k_c": 2000.0, "k": 1000.0, "f0": 0.0},
        ),
        ("bouc_wen_normalized", {"k_x": 1000.0, "k_v": 3000.0, "k_w": 500.0, "rho": 800.0, "sigma": 1.5, "f0": 0.0}),
        ("dahl_viscous", {"k_x": 3000.0, "k_w": 500.0, "rho": 1500.0, "f0": 0.0}),
        (
            "eyring_plastic",
            {
                "F_alpha": 200.0,
                "lambda1": 300.0,
                "lambda2": 0.0,
                "beta1": 0.0,
                "beta2": 10.0,
                "c1": 2000.0,
                "c3": 0.0,
                "f0": 0.0,
            },
        ),
    ],
)
def test_round_trip_more_models(name, true):
    # Held at their true values: the Eyring correction terms (zero here) and the magic formula's shape and
    # curvature factors C and E, which trade off against D and B on one sinusoid (correlation > 0.99).
    held = {"eyring_plastic": ("lambda2", "beta1", "beta2", "c3"), "magic_formula": ("C", "E")}.get(name, ())
    free = [k for k in true if k not in held]
    _round_trip(name, true, sine(), free=free, fixed={k: true[k] for k in held}, tol=0.05, starts=8)


def test_chebyshev_fit_is_linear_least_squares():
    rec = sine(control=None)
    target = get_model("bingham").simulate(rec, {"c0": 3000.0, "f_c": 0.0}) + 1e4 * rec.displacement
    rec = rec.with_force(target)
    r = fit(get_model("chebyshev"), rec)
    # a plane in (x, v) is exactly representable: ESR at round-off
    assert r.esr < 1e-12


def test_maxwell_neural_reduces_the_maxwell_residual():
    rec = sine(n_per_cycle=400)
    F = 1e4 * rec.velocity + 300 * np.tanh(rec.velocity / 0.01)
    rec = rec.with_force(F)
    m = get_model("maxwell_neural", hidden=4)
    r = fit(m, rec)
    before = r.esr
    m.train(rec, r.values)
    after = float(np.sum((F - m.simulate(rec, r.values)) ** 2) / np.sum((F - F.mean()) ** 2))
    # Makris section 4.3: the network captures the nonlinearity the Maxwell model misses
    assert after < 0.2 * before


def test_models_doc_is_generated_from_the_registry():
    """docs/models.md is written by docs/make_models_doc.py from the registry; it must be current (re-run the
    script after changing a model) and cover every registered model."""
    import importlib.util
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    spec = importlib.util.spec_from_file_location("make_models_doc", root / "docs" / "make_models_doc.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    text = (root / "docs" / "models.md").read_text()
    assert text == module.render()
    for name in model_names():
        assert f"## `{name}`" in text
    assert set(module.INTEGRATION) == set(NAMES)
