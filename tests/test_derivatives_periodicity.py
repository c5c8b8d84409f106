"""The cheap spectral test of periodicity in ``derivatives`` (erdesign/data/measurement.py, issue 27).

The spectral test may only reject a record that the least-squares fits would reject too (so no result changes); it
is checked against the fits themselves on periodic records (which it must never reject: sines with harmonics and
noise, from 2.5 periods on, evenly sampled) and on non-periodic ones (which the fits reject, and which it should
reject without them: sweeps, band-limited random motion, earthquake-like bursts).  The harmonic fit by normal
equations is checked against numpy's SVD least squares.
"""

import numpy as np
import pytest
from scipy.signal import butter, chirp, sosfiltfilt

from erdesign.data import measurement as m

FS = 1000.0


def _verdicts(t, x):
    """(spectral test rejects, fits accept) for one record."""
    T = t[-1] - t[0]
    spectrum = m._spectrum(t, x)
    f0 = m._dominant_frequency(t, x, spectrum)
    sigma = m._noise_level(x)
    limit = 1.5 * sigma + 1e-7 * np.ptp(x)
    assert f0 * T >= 1.5
    rejects = m._clearly_aperiodic(spectrum, f0, T, (t.size - 1) / T, limit)
    accepts = m._periodic_derivatives(t, x, f0, sigma) is not None  # the fits alone
    return rejects, accepts


@pytest.mark.parametrize("periods", [2.5, 7.3, 40.0])
@pytest.mark.parametrize("noise", [1e-3, 3e-2])
def test_periodic_records_are_never_rejected_by_the_spectral_test(periods, noise):
    rng = np.random.default_rng(int(periods * 10) + int(noise * 1e4))
    f = 1.7
    t = np.arange(int(periods / f * FS)) / FS
    w = 2 * np.pi * f * t
    # a fundamental, a few harmonics (a clipped or distorted drive), a trend line, noise
    x = 0.01 * (np.sin(w + 0.3) + 0.2 * np.cos(3 * w) + 0.05 * np.sin(7 * w - 1.0)) + 1e-4 * t
    x = x + noise * 0.01 * rng.normal(size=t.size)
    rejects, accepts = _verdicts(t, x)
    assert accepts, "the fits should accept a periodic record"
    assert not rejects


def _non_periodic(kind, rng):
    n = 30_000
    t = np.arange(n) / FS
    if kind == "sweep":
        return t, 0.01 * chirp(t, 0.3, t[-1], 8.0)
    if kind == "band-limited random":
        return t, sosfiltfilt(butter(4, [0.5, 5.0], btype="band", fs=FS, output="sos"), rng.normal(size=n))
    if kind == "low-pass random":
        return t, sosfiltfilt(butter(4, 3.0, fs=FS, output="sos"), rng.normal(size=n))
    burst = np.exp(-(((t - 12.0) / 4.0) ** 2))
    return t, burst * sosfiltfilt(butter(2, [1.0, 8.0], btype="band", fs=FS, output="sos"), rng.normal(size=n))


@pytest.mark.parametrize("kind", ["sweep", "band-limited random", "low-pass random", "earthquake-like"])
def test_non_periodic_records_are_rejected_before_any_fit(kind):
    t, x = _non_periodic(kind, np.random.default_rng(4))
    rejects, accepts = _verdicts(t, x)
    assert not accepts, "the fits reject this record"
    assert rejects, "and the spectral test should spare them"


def test_harmonic_fit_equals_svd_least_squares():
    rng = np.random.default_rng(2)
    t = np.sort(rng.uniform(0, 3.0, 4000))  # uneven sampling: any grid
    f = 1.3
    x = (
        0.01 * np.sin(2 * np.pi * f * t)
        + 0.002 * np.cos(6 * np.pi * f * t)
        + 0.003 * t
        + 1e-5 * rng.normal(size=t.size)
    )
    coef, A, r = m._harmonic_fit(t, x, f, 6)
    w = 2 * np.pi * f * (t - t[0])
    B = np.column_stack([np.ones_like(t), t - t[0]] + [g(k * w) for k in range(1, 7) for g in (np.cos, np.sin)])
    ref, *_ = np.linalg.lstsq(B, x, rcond=None)
    np.testing.assert_allclose(coef, ref, rtol=0, atol=1e-13 * np.max(np.abs(ref)))  # measured 1e-15
    np.testing.assert_allclose(A[:, 2:], B[:, 2:], rtol=0, atol=1e-13)  # angle addition: k ulp
    np.testing.assert_allclose(r, x - B @ ref, rtol=0, atol=1e-15)
