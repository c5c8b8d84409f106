"""Fitting holds no hidden state: the kernels' step settings are per thread (context variables), the sub-step plans
of two records of one length are kept apart, and two fits running at once in threads give the serial results."""

import concurrent.futures

import numpy as np
import pytest

from erdesign.data.measurement import Measurement
from erdesign.identification.identify import identify
from erdesign.models._kernels import coarse_steps, frozen_substeps, step_settings
from erdesign.models.registry import get_model

TRUE = {
    "alpha_a": 1.2e5,
    "alpha_b": 4e5,
    "c0a": 900.0,
    "c0b": 3000.0,
    "c1a": 3e4,
    "c1b": 1e5,
    "k0": 50.0,
    "k1": 0.0,
    "x0": 0.0,
    "beta": 3e5,
    "gamma": 3e5,
    "delta": 1.0,
    "n": 2.0,
    "eta": 190.0,
}


def _record(seed: int) -> Measurement:
    """A 2 s random-motion record at 1 kHz (both records have 2000 samples) with a voltage that steps; the force is
    the modified Bouc-Wen model's plus 1 % noise."""
    rng = np.random.default_rng(seed)
    t = np.arange(2000) / 1000.0
    x = np.convolve(rng.standard_normal(t.size), np.ones(80) / 80, "same") * 0.08
    u = np.where(np.sin(2 * np.pi * (1.5 + seed) * t) > 0, 1.0, 0.25)
    rec = Measurement.from_arrays(t, x, control=u, control_kind="voltage", name=f"random {seed}")
    model = get_model("bouc_wen_modified")
    values = {k: v for k, v in {**model.defaults(), **TRUE}.items() if k in model.defaults()}
    F = model.force(rec, values)
    return rec.with_force(F + 0.01 * np.std(F) * rng.standard_normal(t.size))


def test_step_settings_are_per_thread():
    """A ``coarse_steps`` block in one thread does not change the steps another thread sees."""
    default = step_settings()
    seen = {}

    def inside_block():
        with coarse_steps(theta=2.0, max_substeps=8):
            seen["block"] = step_settings()
            barrier.wait()  # hold the block open while the other thread looks
            barrier.wait()

    def outside_block():
        barrier.wait()
        seen["other"] = step_settings()
        barrier.wait()

    import threading

    barrier = threading.Barrier(2)
    threads = [threading.Thread(target=inside_block), threading.Thread(target=outside_block)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    assert seen["block"].theta == 2.0 and seen["block"].max_substeps == 8
    assert seen["other"] == default and step_settings() == default


def test_two_records_of_one_length_keep_their_own_substep_plans():
    """Frozen sub-step counts belong to the record simulated first; a second record of the same length must get
    its own plan (when plans were keyed by length, it reused the first record's counts)."""
    a, b = _record(1), _record(2)
    model = get_model("bouc_wen_modified")
    values = {**model.defaults(), **{k: v for k, v in TRUE.items() if k in model.defaults()}}
    Fb_alone = model.force(b, values)
    with frozen_substeps() as plans:
        model.force(a, values)
        Fb_after_a = model.force(b, values)
    assert len(plans) == 2
    assert np.max(np.abs(Fb_after_a - Fb_alone)) < 1e-9 * np.max(np.abs(Fb_alone))


@pytest.mark.slow
def test_two_fits_in_threads_give_the_serial_results():
    """The Done-when of issue 24: two records of one length identified concurrently in threads give exactly the
    serial results, and the caller's model object is not changed by fitting."""
    records = [_record(1), _record(2)]
    model = get_model("bouc_wen_modified")
    before = dict(vars(model))
    options = dict(starts=1, max_time=60.0)
    serial = [identify(model, rec, **options) for rec in records]
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        threaded = list(pool.map(lambda rec: identify(model, rec, **options), records))
    for s, t in zip(serial, threaded):
        assert s.values == t.values
        assert s.esr == t.esr
    assert dict(vars(model)) == before
