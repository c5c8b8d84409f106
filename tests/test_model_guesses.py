"""The starting guesses of the model library: the record scales they are read from (erdesign/models/_guess.py) and
the one rule every model follows (defaults, updated from the force when the record has one)."""

import numpy as np
import pytest

from erdesign.data.measurement import Measurement
from erdesign.models._guess import force_scales, peak_speed, sign_viscous_fit, stroke, viscous_slope
from erdesign.models.registry import get_model, model_names

T = np.linspace(0.0, 2.0, 4001)
X = 0.004 + 0.01 * np.sin(2 * np.pi * T)  # 10 mm about a 4 mm offset, 1 Hz


def _record(force=None, **kw):
    return Measurement.from_arrays(T, X, force, **kw)


def test_sign_viscous_fit_recovers_a_bingham_force():
    # F = f_y sgn v + c v + f_0 lies in the span of the fit's columns: least squares returns it to rounding
    rec = _record()
    F = 300.0 * np.sign(rec.velocity) + 2000.0 * rec.velocity + 50.0
    fy, c, f0 = sign_viscous_fit(_record(F))
    assert (fy, c, f0) == pytest.approx((300.0, 2000.0, 50.0), rel=1e-9)


def test_stroke_and_peak_speed_of_a_sine():
    rec = _record()
    # the mean of two whole periods of the sine is the offset: the excursion is the amplitude, 10 mm
    assert stroke(rec) == pytest.approx(0.01, rel=1e-6)
    # peak speed 2 pi f A = 62.83 mm/s; the derived velocity of 2 kHz samples is within 1e-5 of it
    assert peak_speed(rec) == pytest.approx(2 * np.pi * 0.01, rel=1e-5)


def test_a_still_record_gives_unit_scales_not_a_division_by_zero():
    rec = Measurement.from_arrays(T, np.zeros_like(T), np.zeros_like(T))
    assert stroke(rec) == 1.0 and peak_speed(rec) == 1.0


def test_viscous_slope_and_clamped_scales():
    rec = _record()
    # the centred force on the velocity: exact for a velocity of zero mean; over two whole periods of the derived
    # velocity its mean is below 1e-3 of its peak, which moves the slope by less than 1e-6
    assert viscous_slope(_record(1500.0 * rec.velocity + 20.0)) == pytest.approx(1500.0, rel=1e-6)
    # a force that falls with the speed: the clamped damping is 0 (or the floor asked for), the friction 1 N
    s = force_scales(_record(-10.0 * rec.velocity))
    assert (s.damping, s.friction) == (0.0, 1.0)
    assert force_scales(_record(-10.0 * rec.velocity), min_damping=1.0).damping == 1.0


# chebyshev's scales (x_c, x_s, v_s, u_c, u_s) are the record's, read whether or not it has a force
@pytest.mark.parametrize("name", [n for n in model_names() if n not in ("physics", "chebyshev")])
def test_without_a_force_every_guess_is_the_defaults(name):
    # the rule of Model.initial_guess: nothing is read from a force that is not there (bouc_wen_amplitude raised a
    # KeyError here); the a priori amplitude / frequency are the record's whether or not it has a force
    model = get_model(name)
    rec = _record(control=np.ones_like(T), control_kind="voltage")
    guess = model.initial_guess(rec)
    a_priori = {"x_a", "amplitude", "frequency", "x_max", "v_ref"}
    assert list(guess) == list(model.defaults())
    assert {k: v for k, v in guess.items() if k not in a_priori} == {
        k: v for k, v in model.defaults().items() if k not in a_priori
    }
