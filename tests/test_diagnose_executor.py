"""The diagnosis's candidate and pair fits are independent tasks: on a process pool and on a Dask LocalCluster the
diagnosis is the same as in this process, number for number."""

import pytest

from erdesign import load_example
from erdesign.diagnosis.diagnose import diagnose
from erdesign.executor import PoolExecutor
from erdesign.simulation.rig import run_rig, stepped_sine


@pytest.fixture(scope="module")
def friction_record():
    """Makris's damper with seal friction the file does not know (the doctest of ``improve``)."""
    motion = stepped_sine([0.005], [2.0], [0.0, 3e6], cycles=2, rate=200)
    rig = run_rig(
        load_example("makris"),
        motion,
        hidden={"seal_friction": {"friction_force": 400.0}},
        viscosity_factor=1.2,
        seed=2,
    )
    return rig.record


def _summary(d):
    return (
        d.verdict,
        d.missing_effects,
        d.baseline_esr,
        [(c.effect, c.esr, c.delta_bic, c.significant) for c in d.ranking],
    )


@pytest.mark.slow
def test_candidates_on_a_pool_and_on_dask_give_the_serial_diagnosis(friction_record, dask_client):
    damper = load_example("makris")
    serial = diagnose(damper, friction_record)
    assert serial.verdict == "missing_effect" and serial.missing_effect == "seal_friction"
    with PoolExecutor(2) as pool:
        pooled = diagnose(damper, friction_record, executor=pool)
        assert pool._pool is not None  # a pool the caller gave is left open for its next use
    on_dask = diagnose(damper, friction_record, scheduler=dask_client.scheduler.address)
    assert _summary(pooled) == _summary(serial)
    assert _summary(on_dask) == _summary(serial)
