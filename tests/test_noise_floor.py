"""The noise floor a record supports (erdesign.data.noise_floor; issue 23).

Records come from the truth rig (erdesign.simulation.truthrig), which shares no code with the fitted model: the
force noise is known exactly (the noisy force minus the rig's noise-free force), and so is what the motion channel
costs an exact model (the rig's own force fed the measured motion).  The real records (../shared/data) are
reported and bounded; those tests skip when the folder is absent.
"""

import dataclasses
import math
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from scipy.signal import butter, sosfiltfilt

from erdesign.damper.files import load_example
from erdesign.data.measurement import Measurement, read_measurement
from erdesign.data.noise import force_noise, sign_known
from erdesign.data.noise_floor import (
    METHODS,
    NoiseFloor,
    estimate_noise_floor,
    force_noise_from_cycles,
    force_noise_from_still_segment,
    motion_noise,
    quantisation_step,
)
from erdesign.errors import ErdesignError
from erdesign.simulation.rig import Motion, earthquake_motion, random_motion, sine
from erdesign.simulation.truthrig import TruthDamper, simulate_truth
from erdesign.units import Q_

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT.parent / "shared" / "data"
SPECTRUM, CYCLES, STILL = "spectrum above the excited band", "repeated cycles", "still segment"


def _true_sigma(rec, noise):
    # simulate_truth's load cell: white noise of `noise` times the RMS of the true force
    return noise * math.sqrt(float(np.mean(rec.true_force**2)))


# ------------------------------------------------------------------------------- white load-cell noise, 1 % and 3 %
CASES = [("makris", {}, 3e6), ("mr_valve", {"compliance": {}}, 2e5), ("mr_mixed", {}, 2e5)]
MOTIONS = {
    "sine": (lambda E: sine(0.005, 2.0, E, cycles=4, rate=1000), CYCLES),
    "random": (lambda E: random_motion(0.003, (0.5, 5.0), E, duration=4.0, rate=1000, seed=1), SPECTRUM),
    "earthquake": (lambda E: earthquake_motion(0.008, E, duration=6.0, rate=1000, seed=2), SPECTRUM),
}


@pytest.mark.parametrize("noise", [0.01, 0.03])
@pytest.mark.parametrize("motion", list(MOTIONS))
@pytest.mark.parametrize("damper,mechanisms,field", CASES, ids=[c[0] for c in CASES])
def test_white_force_noise_within_20_percent(damper, mechanisms, field, motion, noise):
    make, method = MOTIONS[motion]
    rec = simulate_truth(TruthDamper(load_example(damper), mechanisms), make(field), force_noise=noise, seed=3)
    floor = estimate_noise_floor(rec.measured)
    truth = _true_sigma(rec, noise)
    # the brief's tolerance: 20 % (a plateau's level from a few hundred spectral bins is good to about 5 %)
    assert 0.8 < floor.sigma_force / truth < 1.2, (floor.sigma_force / truth, floor.note)
    assert floor.method == method, floor.note
    # the ESR is the force noise's variance over the force's, on all samples
    F = rec.measured.force
    assert floor.esr == pytest.approx(F.size * floor.sigma_force**2 / np.sum((F - F.mean()) ** 2), rel=1e-12)
    assert floor.motion_esr == 0.0 and floor.total() == floor.esr


def test_rigid_yield_jumps_do_not_inflate_the_spectrum():
    """A rigid MR valve on random motion: force jumps at every reversal hide the noise at every frequency of the
    raw spectrum (their harmonics fall as 1/f^2, 80 times the 1 % noise at the Nyquist frequency); with them taken
    out the plateau is the noise's."""
    from scipy.signal import welch

    rec = simulate_truth(
        TruthDamper(load_example("mr_valve"), {}),
        random_motion(0.003, (0.5, 5.0), 2e5, duration=4.0, rate=1000, seed=1),
        force_noise=0.01,
        seed=3,
    )
    truth = _true_sigma(rec, 0.01)
    f, P = welch(rec.measured.force, fs=1000.0, nperseg=512)
    raw_top = math.sqrt(float(np.median(P[f > 300])) * 500.0)  # white at the raw spectrum's top level
    assert raw_top > 2.5 * truth
    floor = estimate_noise_floor(rec.measured)
    assert floor.method == SPECTRUM and 0.85 < floor.sigma_force / truth < 1.15


# ------------------------------------------------------------------------------------------ a band-limited channel
@pytest.fixture(scope="module")
def fast_record():
    """20 s at 3 kHz (60,000 samples): a compliant MR valve on random motion to 15 Hz, 1 % load-cell noise."""
    truth = TruthDamper(load_example("mr_valve"), {"compliance": {"bulk_modulus": 5e7}})
    return simulate_truth(
        truth, random_motion(0.003, (0.5, 15.0), 2e5, duration=20.0, rate=3000.0, seed=4), force_noise=0.01, seed=5
    )


def _low_passed(rec, cutoff):
    """The record with its noisy force low-passed at ``cutoff`` [Hz] (Butterworth, order 4, zero phase) as an
    anti-aliased channel would be, and the standard deviation of the noise it then holds."""
    sos = butter(4, cutoff, fs=3000.0, output="sos")
    measured = sosfiltfilt(sos, rec.measured.force)
    noise = measured - sosfiltfilt(sos, rec.true_force)
    return rec.measured.with_force(measured), float(np.std(noise[100:-100]))


@pytest.fixture(scope="module")
def band_limited(fast_record):
    return _low_passed(fast_record, 1000.0)


def test_band_limited_3khz_floor_is_the_noise_not_the_fast_force(band_limited):
    record, truth = band_limited
    floor = estimate_noise_floor(record)
    # the brief's tolerance: a factor 1.5; measured 1.01
    assert floor.method == SPECTRUM and "roll-off" in floor.note
    assert 1 / 1.5 < floor.sigma_force / truth < 1.5, floor.note
    # the old estimate, fourth differences: on the full record the filter has removed the noise they see (0.38 of
    # the truth); on the copy a diagnosis thins to 4000 samples the fast force counts as noise (4.0 times it)
    full = force_noise(record)
    thinned = force_noise(record.select(slice(None, None, math.ceil(len(record) / 4000))))
    print(
        f"\nband-limited 3 kHz: truth {truth:.2f} N; floor {floor.sigma_force:.2f} N ({floor.method}); fourth "
        f"differences {full:.2f} N on the full record, {thinned:.2f} N on the thinned copy"
    )
    assert full < 0.5 * truth and thinned > 2.5 * truth


def test_low_passed_channel_without_a_plateau_gives_an_upper_bound(fast_record):
    """Low-passed at 500 Hz the fast force stays above the noise up to the filter's knee: no plateau.  The noise
    is then at most white at the pass band's lowest level - an upper bound, close to it, while the fourth
    differences see 4 % of the noise."""
    record, truth = _low_passed(fast_record, 500.0)
    floor = estimate_noise_floor(record)
    assert floor.method == SPECTRUM and "upper bound" in floor.note and "no flat plateau" in floor.note
    assert 1.0 < floor.sigma_force / truth < 1.6  # measured 1.20
    assert force_noise(record) < 0.1 * truth


def test_floor_is_cheap_on_60k_samples(band_limited):
    record, _ = band_limited
    estimate_noise_floor(record)  # scipy.signal imported
    start = time.perf_counter()
    estimate_noise_floor(record)
    # the brief asks < 0.3 s (measured 0.1-0.2 s); 1 s leaves room for a machine shared by several jobs
    assert time.perf_counter() - start < 1.0


# ---------------------------------------------------------------------------- what the motion channel adds, 100 Hz
def test_quantised_displacement_at_100_hz_sets_the_floor_through_the_velocity():
    """An MR valve at 100 Hz with a displacement digitised in 5 um steps and a noise-free load cell.

    Independent of any fitted model: the rig's own force fed the derivatives of the digitised displacement, minus
    the same fed the derivatives of the exact displacement, is what the digitisation costs an exact model (the
    derivative rule's own bias on the exact displacement is left out: it is not noise).  The sensitivities are
    central differences of the rig's force in v and a."""
    q = 5e-6
    truth = TruthDamper(load_example("mr_valve"), {"slug_inertia": {}})
    motion = earthquake_motion(0.01, 0.0, duration=30.0, rate=100.0, seed=7)
    exact = simulate_truth(truth, motion, force_noise=0.0, displacement_noise=0.0)
    xq = np.round(motion.displacement / q) * q
    record = Measurement.from_arrays(
        motion.time, xq, exact.true_force, control=motion.control, control_kind=exact.measured.control_kind
    )
    clean = Measurement.from_arrays(motion.time, motion.displacement, exact.true_force)

    def rig(v, a):
        return simulate_truth(
            truth, replace(motion, velocity=v, acceleration=a), force_noise=0.0, displacement_noise=0.0
        ).true_force

    cost = rig(record.velocity, record.acceleration) - rig(clean.velocity, clean.acceleration)
    dv, da = 1e-4 * np.ptp(motion.velocity), 1e-3 * np.ptp(motion.acceleration)
    s_v = (rig(motion.velocity + dv, motion.acceleration) - rig(motion.velocity - dv, motion.acceleration)) / (2 * dv)
    s_a = (rig(motion.velocity, motion.acceleration + da) - rig(motion.velocity, motion.acceleration - da)) / (2 * da)
    known = sign_known(record)
    F = exact.true_force[known]
    true_esr = float(np.sum(cost[known] ** 2) / np.sum((F - F.mean()) ** 2))
    floor = estimate_noise_floor(record, known, sensitivity=(s_v, s_a))
    assert quantisation_step(xq) == pytest.approx(q, rel=1e-9)
    assert floor.sigma_displacement == pytest.approx(q / math.sqrt(12), rel=1e-9)  # uniform error of one step
    # first-order propagation of a white noise: measured 1.10 here, 0.76-1.19 for peaks of 4 to 20 mm (a digitisation
    # error is white only while the motion crosses several steps a sample, and the derivative's adaptive cut-off
    # moves with the noise): within a factor 1.4
    print(
        f"\n100 Hz, 5 um steps: motion_esr {floor.motion_esr:.3g}, the digitisation costs an exact model "
        f"{true_esr:.3g}; load cell {floor.esr:.3g}"
    )
    assert 1 / 1.4 < floor.motion_esr / true_esr < 1.4, (floor.motion_esr, true_esr)
    assert floor.total() == pytest.approx(floor.esr + floor.motion_esr)
    assert floor.total() > floor.esr


def test_motion_noise_of_a_digitised_sine_matches_its_propagation():
    # a record digitised in 5 um steps at 100 Hz: the fourth differences would read 1.25 q/sqrt(12) (the
    # digitisation error is uniform, lighter-tailed than a Gaussian); its known variance q^2/12 is taken
    t = np.arange(3000) / 100.0
    x = np.round(5e-3 * np.sin(2 * np.pi * 0.7 * t) / 5e-6) * 5e-6
    sx, sv, sa = motion_noise(Measurement.from_arrays(t, x))
    assert sx == pytest.approx(5e-6 / math.sqrt(12), rel=1e-9)
    assert 0 < sv < 2 * math.pi * 0.7 * sx * 10 and sa > 0


# --------------------------------------------------------------------------------------------- the other methods
@pytest.mark.parametrize("value", ["5 N", Q_(5.0, "N"), 5.0, "0.005 kN", 5])
def test_given_force_noise(value):
    t = np.arange(2000) / 500.0
    rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t), 1000 * np.cos(2 * np.pi * t))
    floor = estimate_noise_floor(rec, force_noise=value)
    assert floor.method == "given" and floor.sigma_force == pytest.approx(5.0)
    # ESR of a 5 N noise against a 1000 N amplitude cosine: 25 / (1000^2 / 2) over whole cycles
    assert floor.esr == pytest.approx(5.0e-5, rel=1e-3)


@pytest.mark.parametrize(
    "value,match", [("5 m", "force_noise"), (-1.0, "force_noise"), (True, "force_noise"), (float("nan"), "force_noise")]
)
def test_given_force_noise_errors_name_the_argument(value, match):
    t = np.arange(100) / 100.0
    rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t), np.cos(2 * np.pi * t))
    with pytest.raises(ErdesignError, match=match):
        estimate_noise_floor(rec, force_noise=value)


def test_mask_and_sensitivity_errors_name_the_argument():
    t = np.arange(100) / 100.0
    rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t), np.cos(2 * np.pi * t))
    with pytest.raises(ErdesignError, match="mask"):
        estimate_noise_floor(rec, np.ones(50, dtype=bool), force_noise=1.0)
    with pytest.raises(ErdesignError, match="sensitivity"):
        estimate_noise_floor(rec, force_noise=1.0, sensitivity=(np.ones(50), None))
    with pytest.raises(ErdesignError, match="record"):
        estimate_noise_floor("rec.csv")


def test_still_segment_before_the_motion():
    """An MR valve held still for 1.5 s, then driven at 2 Hz: the force's spread at rest is the load cell's."""
    rate, rest = 1000.0, 1500
    m = sine(0.005, 2.0, 2e5, cycles=3, rate=rate)
    motion = Motion(
        np.arange(rest + m.time.size) / rate,
        np.concatenate([np.zeros(rest), m.displacement]),
        np.concatenate([np.zeros(rest), m.velocity]),
        np.concatenate([np.zeros(rest), m.acceleration]),
        np.concatenate([np.full(rest, 2e5), m.control]),
        "rest, then a sine",
    )
    rec = simulate_truth(TruthDamper(load_example("mr_valve"), {"accumulator": {}}), motion, force_noise=0.01, seed=8)
    truth = _true_sigma(rec, 0.01)
    assert np.ptp(rec.true_force[:rest]) < 1e-9 * np.ptp(rec.true_force)  # the gas preload: constant at rest
    floor = estimate_noise_floor(rec.measured)
    assert floor.method == STILL, floor.note
    # 1500 samples: the spread is known to about 2 %; 10 %
    assert 0.9 < floor.sigma_force / truth < 1.1
    assert force_noise_from_still_segment(rec.measured.select(slice(rest, None))) is None  # no rest, no segment


def test_repeated_cycles_with_heating_and_a_period_of_no_whole_number_of_samples():
    """An MR valve heating over 12 cycles (its force falls as the fluid warms) at 1.3 Hz sampled at 500 Hz
    (384.6 samples a period): adjacent cycles cancel the drift and the interpolation's effect is divided out."""
    truth = TruthDamper(load_example("mr_valve"), {"thermal": {"heat_capacity": 20.0}})  # warms 77 K
    rec = simulate_truth(truth, sine(0.008, 1.3, 2e5, cycles=12, rate=500), force_noise=0.01, seed=9)
    F = rec.true_force
    period = int(round(500 / 1.3))
    drift = abs(np.max(F[period : 2 * period]) - np.max(F[-2 * period : -period]))
    noise = _true_sigma(rec, 0.01)
    assert drift > 3 * noise  # the heating is there, above the noise
    found = force_noise_from_cycles(rec.measured)
    assert found is not None
    assert 0.85 < found[0] / noise < 1.15
    assert estimate_noise_floor(rec.measured).method == CYCLES


def test_methods_constant_and_result_type():
    assert METHODS == ("given", STILL, CYCLES, SPECTRUM, "fourth differences")
    nf = NoiseFloor(2.0, "given", 0.01, 0.02)
    assert nf.total() == pytest.approx(0.03)
    with pytest.raises(dataclasses.FrozenInstanceError):
        nf.esr = 0.0


# ------------------------------------------------------------------------------------------------------ real data
needs_dyke = pytest.mark.skipif(
    not (DATA / "dyke_nees" / "ransim_u.csv").is_file(),
    reason="../shared/data/dyke_nees/ransim_u.csv is absent (the measured MR-damper data "
    "are not part of the repository)",
)
needs_quiroz = pytest.mark.skipif(
    not (DATA / "quiroz2022_utfsm_mr").is_dir(),
    reason="../shared/data/quiroz2022_utfsm_mr is absent (the measured MR-damper data are not part of the repository)",
)


@needs_dyke
def test_dyke_ransim_u_floor_is_far_below_a_13_parameter_model():
    """Dyke's NEES record ransim_u (3004.8 Hz, band-limited random motion): the floor must not exceed what a
    13-parameter Bouc-Wen reaches there (ESR 0.026, issue 23); the old fourth differences on the copy a diagnosis
    thinned to 4000 samples read 62 N, an ESR of 0.006, and the loop's rounds 0.058-0.073."""
    from erdesign.data.measurement import clipped_samples

    record = read_measurement(DATA / "dyke_nees" / "ransim_u.csv")
    unclipped = ~clipped_samples(record.force)
    floor = estimate_noise_floor(record, unclipped)
    print(f"\nransim_u: {floor.sigma_force:.3g} N, ESR {floor.esr:.3g} ({floor.method}: {floor.note})")
    assert floor.method == SPECTRUM
    assert floor.esr < 0.026 / 100
    assert 0.1 < floor.sigma_force < 5.0  # measured 0.53 N; the load cell's digitisation step is 0.14 N


def _read_quiroz_raw(path, segment=0):
    """One stretch (between DAQ pauses) of a Quiroz raw file: x [mm] = 10 x CHANNEL0, F [N] = 980.665 x CHANNEL1
    (shared/data/README.md; the 3 Hz test keeps the channels in that order)."""
    rows, seg = [], 0
    with open(path) as fh:
        for i, line in enumerate(fh):
            if i < 7:
                continue
            cells = line.split(",")
            if seg == segment:
                rows.append((float(cells[2]), float(cells[3])))
            if len(cells) >= 5 and "Pause" in cells[4]:
                seg += 1
                if seg > segment:
                    break
    a = np.array(rows)
    return Measurement.from_arrays(np.arange(len(a)) * 1e-3, a[:, 0] * 1e-2, a[:, 1] * 980.665, name=path.name)


@needs_quiroz
def test_quiroz_raw_record_floor_from_its_still_start():
    record = _read_quiroz_raw(DATA / "quiroz2022_utfsm_mr" / "raw" / "ME5mm3Hz.txt", segment=0)
    floor = estimate_noise_floor(record)
    print(f"\nQuiroz raw ME5mm3Hz (0 A): {floor.sigma_force:.3g} N, ESR {floor.esr:.3g} ({floor.method}: {floor.note})")
    assert floor.method == STILL
    # the force channel's digitisation step is 0.003 V x 980.665 N/V = 2.9 N: its spread is of that order
    # (measured 2.0 N)
    assert 2.9 / math.sqrt(12) < floor.sigma_force < 3 * 2.9
    assert floor.esr < 1e-3


@needs_quiroz
def test_quiroz_preprocessed_record_floor_from_its_cycles():
    a = np.loadtxt(DATA / "quiroz2022_utfsm_mr" / "preprocessed" / "10mm1Hz0x5A.txt")
    record = Measurement.from_arrays(a[:, 0] - a[0, 0], a[:, 1] * 1e-3, a[:, 3], name="10mm1Hz0x5A")
    floor = estimate_noise_floor(record)
    print(
        f"\nQuiroz preprocessed 10mm1Hz0x5A: {floor.sigma_force:.3g} N, ESR {floor.esr:.3g} ({floor.method}: "
        f"{floor.note})"
    )
    # the file is smoothed (a causal moving average over a tenth of a period): the fourth differences see almost
    # nothing (0.017 N); what a model of one cycle cannot follow is the spread between cycles (measured 1.0 N)
    assert floor.method == CYCLES
    assert floor.sigma_force > 10 * force_noise(record)
    assert floor.esr < 1e-4


def test_one_floor_judged_on_a_thinned_copy():
    """The floor is estimated on the full record; on the copy a diagnosis thins it keeps its noise levels, and its
    ESR on the thinned samples equals the full record's (every 15th sample of a long random record)."""
    rec = simulate_truth(
        TruthDamper(load_example("makris"), {}),
        random_motion(0.003, (0.5, 5.0), 3e6, duration=8.0, rate=1000, seed=1),
        force_noise=0.01,
        seed=3,
    )
    n = len(rec.measured)
    s_v = np.full(n, 2e3)
    full = estimate_noise_floor(rec.measured, sensitivity=(s_v, None))
    thinned = full.on(rec.measured.select(slice(None, None, 15)), sensitivity=(s_v[::15], None))
    assert (thinned.sigma_force, thinned.method, thinned.sigma_velocity) == (
        full.sigma_force,
        full.method,
        full.sigma_velocity,
    )
    # the same variances over a sample of the same record: equal to within the sampling of the force's variance
    assert thinned.esr == pytest.approx(full.esr, rel=0.05)
    assert thinned.motion_esr == pytest.approx(full.motion_esr, rel=0.05)
    with pytest.raises(ErdesignError, match="mask"):
        full.on(rec.measured, np.ones(3, dtype=bool))


def test_a_saturated_displacement_is_not_a_still_segment():
    """A displacement transducer that saturates at +2 mm during a 5 mm sine looks still at its rail while the
    piston moves on and the force keeps changing: that is not the load cell at rest."""
    rng = np.random.default_rng(4)
    t = np.arange(4000) / 1000.0
    x = 0.005 * np.sin(2 * np.pi * 1.0 * t)
    F = 2000 * np.tanh(50 * np.cos(2 * np.pi * t)) + 500 * np.sin(2 * np.pi * t) + 3.0 * rng.standard_normal(t.size)
    record = Measurement.from_arrays(t, np.minimum(x, 0.002), F)
    assert force_noise_from_still_segment(record) is None
    assert estimate_noise_floor(record).method != STILL


@pytest.mark.parametrize("level", [0.95, 0.8])
def test_clipped_samples_out_of_the_mask_do_not_lower_the_floor(level):
    """Issue 23: MR valve, 1 Hz then 2 Hz (3 cycles each) at 500 Hz, 1 % noise (true sigma 31.4 N), the force clipped
    at 95 % / 80 % of its peak and the clipped samples excluded by the mask: pairs of identical clipped values once
    entered the cycle differences (17.8 N and 9.1 N).  The brief's tolerance: 20 %."""
    from erdesign.data.findings import excluded_mask, find_data_problems
    from erdesign.simulation.rig import stepped_sine

    d = load_example("mr_valve")
    ref = d.fluid.reference_field
    tr = simulate_truth(
        TruthDamper(d, {}, viscosity_factor=1.1, yield_stress_factor=0.9),
        stepped_sine([0.01], [1.0, 2.0], [ref, 0.5 * ref], cycles=3, rate=500),
        force_noise=0.01,
        seed=4,
    )
    rec = tr.measured
    truth = float(np.std(rec.force - tr.true_force))
    clipped = rec.with_force(np.minimum(rec.force, level * rec.force.max()))
    keep = ~excluded_mask(find_data_problems(clipped), len(clipped))
    assert keep.sum() < len(clipped)
    floor = estimate_noise_floor(clipped, keep)
    assert floor.method == CYCLES
    assert 0.8 < floor.sigma_force / truth < 1.2, (floor.sigma_force / truth, floor.note)


def test_every_method_reads_only_the_masked_samples():
    """A still start held at a flat value (a channel stuck, masked out) is no still segment; the spectrum of a
    random motion with a stretch masked out is taken on the longest stretch kept and still finds the noise."""
    rng = np.random.default_rng(0)
    t = np.arange(3000) / 1000.0
    x = np.where(t < 1, 0.0, 0.005 * np.sin(2 * np.pi * (t - 1)))
    F = 2000 * np.tanh(1e3 * np.gradient(x, t)) + 3.0 * rng.standard_normal(t.size)
    rec = Measurement.from_arrays(t, x, np.where(t < 1, 0.0, F), velocity=np.gradient(x, t))
    out = t < 1
    assert force_noise_from_still_segment(rec, ~out) is None
    assert estimate_noise_floor(rec, ~out).method != STILL
    m = simulate_truth(TruthDamper(load_example("makris"), {}), MOTIONS["random"][0](3e6), force_noise=0.01, seed=3)
    keep = np.ones(len(m.measured), bool)
    keep[1500:1600] = False
    floor = estimate_noise_floor(m.measured, keep)
    assert floor.method == SPECTRUM and "longest stretch" in floor.note
    assert 0.8 < floor.sigma_force / _true_sigma(m, 0.01) < 1.2, floor.note
