"""Dyke's NEES record ``ransim_u`` of the Spencer et al. (1997) prototype MR damper with the bundled equivalent
damper file ``examples/spencer1997.toml`` (docs/equivalent_damper.md).

The record lives in ../shared/data/dyke_nees (present in CI, absent in a fresh clone: then every test here skips).
The numbers pinned here were measured on the full-rate record (60,096 samples at 3004.8 Hz); the tolerances leave
room for the optimiser, not for a different answer.

Two things about the record matter to every fit:

* 217 force samples sit at +4545 N: a clipped load-cell channel (``clipped_samples``);
* from 19.53 s to 19.91 s the displacement sits at 10.5-11.0 mm (beyond its largest value anywhere else in the
  record, 8.4 mm; two short excursions apart) while the force swings from -2.7 kN to the +4.5 kN clip.  Whether the
  channel saturated or the piston reached a stop, the force does not follow the displacement there: those 834
  unclipped samples (1.4 % of the record) carry about 55 % of the residual of the physics models fitted here.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from erdesign.damper.files import load_example
from erdesign.data.measurement import clipped_samples, read_measurement
from erdesign.data.metrics import esr
from erdesign.diagnosis.diagnose import _fit
from erdesign.effects.chain import PhysicsDamper

ROOT = Path(__file__).resolve().parents[1]
RECORD = ROOT.parent / "shared" / "data" / "dyke_nees" / "ransim_u.csv"
pytestmark = pytest.mark.skipif(
    not RECORD.is_file(),
    reason="../shared/data/dyke_nees/ransim_u.csv is absent (the "
    "measured MR-damper data are not part of the repository)",
)


def held_at_extreme(t, x, *, fraction=0.05, min_duration=0.05, bridge=0.02, guard=0.005):
    """Samples in stretches of at least ``min_duration`` [s] where the displacement stays within ``fraction`` of its
    range from its largest (or smallest) value (gaps shorter than ``bridge`` [s] bridged), widened by ``guard``."""
    t, x = np.asarray(t, float), np.asarray(x, float)
    dt = (t[-1] - t[0]) / (t.size - 1)
    out = np.zeros(x.size, dtype=bool)
    span = np.ptp(x)
    for near in (x >= x.max() - fraction * span, x <= x.min() + fraction * span):
        idx = np.flatnonzero(near)
        breaks = np.flatnonzero(np.diff(idx) * dt > bridge)
        for a, b in zip(np.r_[idx[0], idx[breaks + 1]], np.r_[idx[breaks], idx[-1]]):
            if t[b] - t[a] >= min_duration:
                g = int(round(guard / dt))
                out[max(a - g, 0) : b + g + 1] = True
    return out


@pytest.fixture(scope="module")
def record():
    return read_measurement(RECORD)


@pytest.fixture(scope="module")
def masks(record):
    unclipped = ~clipped_samples(record.force)
    return unclipped, unclipped & ~held_at_extreme(record.time, record.displacement)


def test_the_record_has_a_clipped_force_and_a_held_displacement(record, masks):
    unclipped, kept = masks
    assert (~unclipped).sum() == 217  # shared/data/README.md: about 220 at +4545 N
    held = unclipped & ~kept
    t = record.time[held]
    assert 800 <= held.sum() <= 870  # 834 measured
    assert t.min() == pytest.approx(19.53, abs=0.01) and t.max() == pytest.approx(19.91, abs=0.01)
    assert np.median(record.displacement[held]) > 0.0105  # m: the channel sits at 10.5-11.0 mm ...
    assert record.displacement[~held & unclipped].max() < 0.0085  # ... beyond its largest value elsewhere (8.4 mm)
    assert np.ptp(record.force[held]) > 6000.0  # N: while the force swings by 6-7 kN


def test_field_lag_and_accumulator_on_ransim_u(record, masks):
    """Baseline + field_lag + gas_spring, 5 free parameters: ESR 0.068 on the kept samples (0.149 on all
    unclipped ones); fitted on the first half it predicts the second within 1.31 x its own ESR.  The accumulator of
    the file bounds the gas stiffness to 0.2-5 x its 500 N/m; the fit ends at the upper bound."""
    unclipped, kept = masks
    model = PhysicsDamper(load_example("spencer1997"), ["field_lag", "gas_spring"])
    fit = _fit(model, record, None, kept)
    force = model.simulate(record, fit.values)
    assert fit.k == 5
    assert esr(record.force[kept], force[kept]) == pytest.approx(0.0684, abs=0.004)
    assert esr(record.force[unclipped], force[unclipped]) == pytest.approx(0.1486, abs=0.006)
    v = fit.values
    # the field follows the command voltage with 8.2 ms (Spencer et al. 1997: eta = 190 1/s, i.e. 5.3 ms)
    assert 0.006 < v["field_time_constant"] < 0.011
    # the accumulator's force at rest: -140 N in the rig's sign convention (Spencer's k1 x0 = 71.5 N in 1997)
    assert -160.0 < v["gas_preload"] < -115.0
    assert v["gas_stiffness"] == pytest.approx(2503.0, rel=1e-3)  # at 5 x the accumulator's k
    assert 1.3 < v["viscosity_factor"] < 1.65 and 0.68 < v["yield_stress_factor"] < 0.85

    first = np.arange(len(record)) < len(record) // 2
    half = _fit(model, record, fit.values, kept & first)
    predicted = model.simulate(record, half.values)
    own = esr(record.force[kept & first], predicted[kept & first])
    ahead = esr(record.force[kept & ~first], predicted[kept & ~first])
    assert own == pytest.approx(0.0621, abs=0.004)
    assert ahead / own < 1.45  # measured 1.31


def test_without_field_lag_the_yield_factor_reads_low(record, masks):
    """docs/equivalent_damper.md: the baseline alone reads a yield-stress factor of 0.42, field_lag lifts it to 0.79."""
    _, kept = masks
    base = _fit(PhysicsDamper(load_example("spencer1997"), []), record, None, kept)
    assert base.values["viscosity_factor"] == pytest.approx(2.06, abs=0.1)
    assert base.values["yield_stress_factor"] == pytest.approx(0.42, abs=0.04)
    lag = _fit(PhysicsDamper(load_example("spencer1997"), ["field_lag"]), record, None, kept)
    assert lag.values["yield_stress_factor"] == pytest.approx(0.79, abs=0.05)
    assert lag.values["viscosity_factor"] == pytest.approx(1.43, abs=0.1)


@pytest.mark.slow
def test_seven_parameter_physics_model_on_ransim_u(record):
    """The best combination of the effect library found on ransim_u (docs/equivalent_damper.md): field lag, the
    accumulator, a low-speed bypass and pre-yield elasticity, 7 free parameters.  On every 2nd sample (1502 Hz, to
    halve the time; the full record gives the same to 0.001): ESR 0.021 on the kept samples and 0.0994 on all unclipped
    ones (published Spencer set: 0.055 and 0.134; Bouc-Wen identified on the unclipped samples: 0.013 and 0.092);
    fitted on the first half it predicts the second within 1.19 x its own ESR.  The test takes about 15 s on
    two shared cores."""
    thin = record.select(slice(None, None, 2))
    unclipped = ~clipped_samples(thin.force)
    kept = unclipped & ~held_at_extreme(thin.time, thin.displacement)
    model = PhysicsDamper(load_example("spencer1997"), ["field_lag", "gas_spring", "leakage", "preyield_elasticity"])
    fit = _fit(model, thin, None, kept)
    force = model.simulate(thin, fit.values)
    assert fit.k == 7
    assert esr(thin.force[kept], force[kept]) == pytest.approx(0.0214, abs=0.003)
    assert esr(thin.force[unclipped], force[unclipped]) == pytest.approx(0.0994, abs=0.004)
    v = fit.values
    assert v["viscosity_factor"] == pytest.approx(0.93, abs=0.07)  # near the file's zero-field slope
    assert v["yield_stress_factor"] == pytest.approx(1.30, abs=0.08)
    assert 18e3 < v["bypass_damping"] < 30e3  # N s/m (Spencer's c1a: 28.3 kN s/m)
    assert 0.007 < v["field_time_constant"] < 0.0105

    first = np.arange(len(thin)) < len(thin) // 2
    half = _fit(model, thin, fit.values, kept & first)
    predicted = model.simulate(thin, half.values)
    own = esr(thin.force[kept & first], predicted[kept & first])
    ahead = esr(thin.force[kept & ~first], predicted[kept & ~first])
    assert ahead / own < 1.3


@pytest.mark.slow
def test_round_two_names_preyield_elasticity_where_it_acts(record):
    """Following the tool's verdicts (docs/case_studies/dyke.md): after field_lag and the pair gas_spring + leakage,
    no effect explains a fifth of the excess on the samples where the sign of the velocity is known (seal friction
    13 %, pre-yield elasticity 6 %); judged with the samples near reversals too, where a compliance below yield
    acts, pre-yield elasticity removes 35 % of the excess and 37 % of the held-out error, and is named.  The next
    round ends ``unexplained`` (seal friction 20 %), so the loop's model has 7 free parameters: ESR 0.0994 on all
    unclipped samples (test_seven_parameter_physics_model_on_ransim_u).  About a minute on two shared cores."""
    from erdesign.diagnosis.diagnose import diagnose

    d = diagnose(load_example("spencer1997"), record, ["field_lag", "gas_spring", "leakage"])
    assert d.verdict == "missing_effect", d.reason
    assert d.missing_effects == ["preyield_elasticity"]
    assert d.baseline_esr == pytest.approx(0.0187, abs=0.001)  # on the judged samples, as before
    (pre,) = [c for c in d.ranking if c.effect == "preyield_elasticity"]
    assert pre.significant and "near reversals" in pre.note
    assert pre.explained < 0.2  # on the judged samples alone it would not be named
    assert "judged where it acts" in d.reason
