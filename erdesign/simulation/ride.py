r"""Ride figures of a vehicle simulation: RMS and ISO 2631-1 frequency-weighted body acceleration.

ISO 2631-1 (1997) Annex A weights vertical whole-body acceleration with W_k, the product of a band limit (high pass
at f1 = 0.4 Hz, low pass at f2 = 100 Hz, both Butterworth, Q = 1/sqrt 2), an acceleration-velocity transition
(f3 = f4 = 12.5 Hz, Q4 = 0.63) and an upward step (f5 = 2.37 Hz, Q5 = 0.91, f6 = 3.35 Hz, Q6 = 0.91):

.. math::
    H_h = \frac{s^2}{s^2 + \omega_1 s/Q_1 + \omega_1^2},\quad
    H_l = \frac{\omega_2^2}{s^2 + \omega_2 s/Q_2 + \omega_2^2},\quad
    H_t = \frac{1 + s/\omega_3}{1 + s/(Q_4\omega_4) + s^2/\omega_4^2},\quad
    H_s = \frac{1 + s/(Q_5\omega_5) + s^2/\omega_5^2}{1 + s/(Q_6\omega_6) + s^2/\omega_6^2}
          \left(\frac{\omega_5}{\omega_6}\right)^2.

The weighted RMS is computed in the frequency domain (the record's FFT times W_k(j 2 pi f)).
"""

from __future__ import annotations

import numpy as np

__all__ = ["wk_weighting", "weighted_rms", "rms"]

_F1, _F2, _F3, _F4, _Q4, _F5, _Q5, _F6, _Q6 = 0.4, 100.0, 12.5, 12.5, 0.63, 2.37, 0.91, 3.35, 0.91
_Q12 = 1 / np.sqrt(2)


def wk_weighting(f) -> np.ndarray:
    """Complex ISO 2631-1 W_k weighting (vertical, seated) at frequencies ``f`` [Hz] (dimensionless).

    Examples
    --------
    >>> round(float(abs(wk_weighting(1.0))), 3)   # ISO 2631-1 Table 3: 0.482 at 1 Hz
    0.482
    """
    s = 2j * np.pi * np.asarray(f, dtype=float)
    w1, w2, w3, w4, w5, w6 = (2 * np.pi * f for f in (_F1, _F2, _F3, _F4, _F5, _F6))
    hh = s**2 / (s**2 + w1 * s / _Q12 + w1**2)
    hl = w2**2 / (s**2 + w2 * s / _Q12 + w2**2)
    ht = (1 + s / w3) / (1 + s / (_Q4 * w4) + s**2 / w4**2)
    hs = (1 + s / (_Q5 * w5) + s**2 / w5**2) / (1 + s / (_Q6 * w6) + s**2 / w6**2) * (w5 / w6) ** 2
    return hh * hl * ht * hs


def rms(x) -> float:
    """Root mean square of ``x``."""
    x = np.asarray(x, dtype=float)
    return float(np.sqrt(np.mean(x**2)))


def weighted_rms(time, acceleration) -> float:
    """ISO 2631-1 W_k frequency-weighted RMS [m/s^2] of a body acceleration [m/s^2] sampled evenly at ``time`` [s].

    The mean is removed with the weighting (W_k(0) = 0).  Parseval: the RMS of the weighted signal is the square
    root of the weighted one-sided power sum of the FFT.
    """
    t = np.asarray(time, dtype=float)
    a = np.asarray(acceleration, dtype=float)
    n = a.size
    dt = (t[-1] - t[0]) / (n - 1)
    spectrum = np.fft.rfft(a)
    f = np.fft.rfftfreq(n, dt)
    weighted = np.fft.irfft(spectrum * wk_weighting(f), n)
    return rms(weighted)
