"""Property tests (hypothesis) of the flow kernels: monotone in flow rate and yield stress, odd in the flow rate,
and the Bingham -> Newtonian limit (tau_y -> 0 gives Makris eq 4).  The exact-annulus kernel's root finder takes
~0.1 s per call, so its properties run on six examples (wide gaps, where it is used)."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from erdesign.flow import bingham_pressure_drop, slit_pressure_drop

Q = st.floats(1e-9, 1e-3)  # m^3/s
TAU = st.floats(0.0, 1e5)  # Pa
ETA = st.floats(1e-2, 1e2)  # Pa s
L = st.floats(1e-3, 0.5)  # m
D = st.floats(5e-3, 0.1)  # m
RATIO = st.floats(0.005, 0.08)  # h/d, thin gap
FAST = settings(max_examples=60, deadline=None, database=None)


@FAST
@given(Q, Q, TAU, ETA, L, D, RATIO)
def test_pressure_drop_rises_with_flow_rate(q1, q2, tau, eta, length, d, ratio):
    lo, hi = sorted((q1, q2))
    h = ratio * d
    assert bingham_pressure_drop(hi, tau, eta, length, d, h) >= bingham_pressure_drop(lo, tau, eta, length, d, h) * (
        1 - 1e-12
    )


@FAST
@given(Q, TAU, TAU, ETA, L, D, RATIO)
def test_pressure_drop_rises_with_yield_stress(q, t1, t2, eta, length, d, ratio):
    lo, hi = sorted((t1, t2))
    h = ratio * d
    assert bingham_pressure_drop(q, hi, eta, length, d, h) >= bingham_pressure_drop(q, lo, eta, length, d, h) * (
        1 - 1e-12
    )


@FAST
@given(Q, TAU, ETA, L, D, RATIO)
def test_pressure_drop_is_odd_in_flow_rate(q, tau, eta, length, d, ratio):
    h = ratio * d
    plus, minus = bingham_pressure_drop(q, tau, eta, length, d, h), bingham_pressure_drop(-q, tau, eta, length, d, h)
    assert np.isfinite(plus) and plus > 0 and abs(minus + plus) <= 1e-12 * abs(plus)


@FAST
@given(Q, ETA, L, D, RATIO)
def test_bingham_tends_to_newtonian(q, eta, length, d, ratio):
    """tau_y -> 0: the Bingham slit pressure drop is the Newtonian one (Makris eq 4), to the relative size of the
    yield part (2 tau_y L / h, one part in 1e9 here)."""
    h = ratio * d
    newtonian = slit_pressure_drop(q, eta, length, d, h)
    tau = 1e-9 * newtonian * h / (2 * length)
    assert abs(bingham_pressure_drop(q, tau, eta, length, d, h) / newtonian - 1) < 1e-6
    assert (
        bingham_pressure_drop(q, 0.0, eta, length, d, h) == np.float64(newtonian)
        or abs(bingham_pressure_drop(q, 0.0, eta, length, d, h) / newtonian - 1) < 1e-12
    )


WIDE = st.floats(0.1, 0.6)  # h/d where the damper uses the exact annulus
FEW = settings(max_examples=6, deadline=None, database=None)


@FEW
@given(Q, Q, TAU, ETA, L, D, WIDE)
def test_annulus_pressure_drop_is_odd_and_rises_with_flow_rate(q1, q2, tau, eta, length, d, ratio):
    from erdesign.flow.annulus_bingham import annulus_bingham_pressure_drop

    lo, hi = sorted((q1, q2))
    h = ratio * d
    p_lo = annulus_bingham_pressure_drop(lo, tau, eta, length, d, h)
    p_hi = annulus_bingham_pressure_drop(hi, tau, eta, length, d, h)
    assert p_hi >= p_lo * (1 - 1e-9)
    assert annulus_bingham_pressure_drop(-hi, tau, eta, length, d, h) == -p_hi
