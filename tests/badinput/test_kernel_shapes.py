"""Issue 27: the SI flow kernels name the arguments whose array shapes do not broadcast together, as the unit-aware
API does, instead of numpy's "operands could not be broadcast" (which names neither).

Every function of :mod:`erdesign.flow` is walked: two of its arguments are given 3 and 4 values, and the message
must name both.  A kernel added to ``erdesign.flow.__all__`` is walked too (or must be listed as taking scalars).
"""

import inspect

import numpy as np
import pytest

import erdesign.flow as flow
from erdesign.errors import ErdesignError, one_line

#: A plausible SI value of every argument name the kernels use (Makris-sized duct, an MR mixed-mode head).
VALUES = dict(
    Q=1e-5,
    dp=1e6,
    tau_y=1e3,
    eta=1.0,
    K=1.0,
    m=1.0,
    L=0.05,
    d=0.014,
    h=8e-4,
    r=0.0071,
    U=0.1,
    q=-1e-5,
    y=1e-4,
    v=0.1,
    Dp=0.05,
    dr=0.01,
    plug_fraction=0.5,
    h_over_d=0.05,
    bingham_number=3.0,
)
#: Functions of scalars only (a grid size; a solver of one case), not walked.
SCALAR_ONLY = {"gap_grid", "solve_gap_flow"}

KERNELS = sorted(
    name
    for name in flow.__all__
    if inspect.isfunction(getattr(flow, name))
    and name not in SCALAR_ONLY
    and len(inspect.signature(getattr(flow, name)).parameters) >= 2
)


def _pairs(name):
    params = list(inspect.signature(getattr(flow, name)).parameters)
    return [(params[0], params[1]), (params[-2], params[-1]), (params[0], params[-1])]


@pytest.mark.parametrize("name", KERNELS)
def test_mismatched_shapes_are_named(name):
    kernel = getattr(flow, name)
    params = list(inspect.signature(kernel).parameters)
    for a, b in _pairs(name):
        args = {p: VALUES[p] for p in params}
        args[a], args[b] = np.full(3, VALUES[a]), np.full(4, VALUES[b])
        with pytest.raises(ErdesignError) as info:
            kernel(**args)
        message = str(info.value)
        assert f"{a} and {b}: shapes (3,) and (4,) do not match" in message, (name, message)
        assert message == one_line(message)


def test_every_kernel_is_walked():
    assert len(KERNELS) >= 20  # 26 when written; a rename must not empty the walk
    for name in KERNELS:
        assert set(inspect.signature(getattr(flow, name)).parameters) <= set(VALUES), name


def test_shapes_that_broadcast_still_do():
    """A column of flows against a row of yield stresses is a table, as numpy broadcasts it."""
    Q = np.array([[1e-6], [1e-5], [3e-5]])
    tau_y = np.array([0.0, 1e3, 2e3, 4e3])
    dp = flow.bingham_pressure_drop(Q, tau_y, 1.0, 0.05, 0.014, 8e-4)
    assert dp.shape == (3, 4) and np.all(np.diff(dp, axis=0) > 0) and np.all(np.diff(dp, axis=1) > 0)
    F = flow.mixed_mode_damper_force(Q[:, :1].ravel() * 1e4, tau_y[:, None], 1.0, 0.05, 0.05, 0.01, 8e-4).force
    assert np.shape(F) == (4, 3)
