"""The Eyring-plastic model (Vivas-López et al. (n.d.) eq 8) fitted the way ``erdesign characterize`` fits it (one
trust-region start from its guess, linear parameters projected): on a record of its own form the parameters come back,
and on the truth rig's slow road profile it predicts the faster records (the baseline of the characterize
comparison, docs/characterize.md)."""

import numpy as np
import pytest

from erdesign.data.measurement import Measurement
from erdesign.identification.fit import esr
from erdesign.identification.identify import identify
from erdesign.models.registry import get_model
from erdesign.simulation.programmes import programme

#: Every term of eq 8 active, the yield amplitude rising with the control (u = current / 1 A).
TRUE = {
    "F_alpha": 150.0,
    "F_alpha_u": 500.0,
    "lambda1": 300.0,
    "lambda2": 3000.0,
    "beta1": 0.5,
    "beta2": 40.0,
    "c1": 2000.0,
    "c3": 5e4,
    "f0": 100.0,
}


def _own_form(noise=10.0, seed=4):
    """E5 (DSFS + PRBS, control 0 to 1 A, 250 Hz) with the force of eq 8 at TRUE plus white noise [N]."""
    m = programme("E5", control_range=(0.0, 1.0), rate=250.0)
    rec = Measurement.from_arrays(
        m.time, m.displacement, control=m.control, control_kind="current", velocity=m.velocity, name="e5"
    )
    clean = get_model("eyring_plastic").simulate(rec, TRUE)
    return rec.with_force(clean + np.random.default_rng(seed).normal(0.0, noise, clean.size)), noise


def test_round_trip_of_its_own_form():
    rec, noise = _own_form()
    r = identify(get_model("eyring_plastic"), rec, starts=1)
    assert r.model.control_reference == 1.0  # u is the current in A, as TRUE is written
    # ESR at the noise floor (noise variance over force variance; 4,673 samples: within 10 %)
    assert r.esr == pytest.approx(noise**2 / np.var(rec.force), rel=0.1)
    assert r.success and not r.poor_fit and not r.not_identifiable
    for k, true in TRUE.items():
        # 1 % (measured: within 0.4 %, c1 the loosest; the standard errors are 0.03-0.3 %)
        assert r.values[k] == pytest.approx(true, rel=0.01), k


@pytest.mark.slow
def test_fit_on_the_truth_rig_road_profile_predicts_the_faster_record():
    # The truth rig (shares no code with eq 8) on the records of docs/characterize.md: E3 (road profile, 1-8 mm,
    # speeds to 0.066 m/s) identifies, E5 (DSFS, speeds to 0.21 m/s) validates.  With c1 and c3 unbounded the fit
    # ended at c1 = -2.5e4 N s/m, c3 = 4.8e6 N s^3/m^3 (ESR 0.009 on E3) and predicted E5 with ESR 4.5; bounded
    # (measured 2026-11-26) it fits E3 to 0.0103 and predicts E5 to 0.0087.
    from erdesign.characterization.method import demo_records

    e3, e5 = demo_records(names=("e3", "e5"))
    r = identify(get_model("eyring_plastic"), e3, starts=1)
    assert r.success and not r.poor_fit
    assert r.esr == pytest.approx(0.0103, abs=0.002)
    assert esr(e5.force, r.model.simulate(e5, r.values)) == pytest.approx(0.0087, abs=0.002)
    # the reference Bingham fit of identify (c0 v + f_c sgn v + f0) leaves 20 times more
    assert r.esr < 0.1 * r.baseline_esr


def test_global_search_ends_with_the_best_point_when_the_evolution_stalls():
    # identify(global_search=True) runs differential evolution through the tracked residual, whose stall rule
    # (meant for a local optimiser) fired inside the evolution on E3 and escaped as an internal exception; now the
    # best point it met is a start, and the fit ends where the local one does (ESR 0.0103, measured 2026-11-26)
    from erdesign.characterization.method import demo_records

    (e3,) = demo_records(names=("e3",))
    r = identify(get_model("eyring_plastic"), e3, starts=1, global_search=True)
    assert r.success
    assert r.esr == pytest.approx(0.0103, abs=0.002)
