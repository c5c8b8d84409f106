r"""Maxwell-type damper models (Makris et al. 1996): Maxwell, BingMax and the Maxwell + neural-network hybrid.

The Maxwell element (spring K in series with dashpot C, relaxation time :math:`\lambda = C/K`),

.. math:: F_M + \lambda\dot F_M = C\dot x \quad\Longleftrightarrow\quad
          F_M(t) = K\int_0^t e^{-(t-\tau)/\lambda}\dot x(\tau)\,d\tau ,

is computed as an exact discrete-time filter of the sampled velocity (first-order hold, :func:`scipy.signal.lfilter`;
:func:`erdesign.models._kernels.first_order_lag`), never by stepping an ODE.
"""

from __future__ import annotations

import numpy as np

from ..errors import ErdesignError
from ._guess import sign_viscous_fit, viscous_slope
from ._kernels import first_order_lag
from .base import FORCE_OFFSET, Model, Parameter

__all__ = ["Maxwell", "BingMax", "MaxwellNeural", "maxwell_force"]


def maxwell_force(t, v, C, K):
    r"""Force of a Maxwell element for a velocity history, [N].

    .. math:: F_M + \frac{C}{K}\dot F_M = C v, \qquad F_M(0) = 0

    Parameters
    ----------
    t : array
        Time, [s].
    v : array
        Velocity, [m/s], taken linear between samples.
    C : float
        Dashpot constant, [N s/m].
    K : float
        Spring stiffness, [N/m].

    Returns
    -------
    array
        F_M, [N].

    Examples
    --------
    A constant velocity V relaxes towards C V with time constant C/K:

    >>> import numpy as np
    >>> t = np.linspace(0, 1, 1001); F = maxwell_force(t, np.full(t.size, 0.01), C=1e5, K=1e6)
    >>> [round(float(F[k] / (1e3 * (1 - np.exp(-t[k] / 0.1)))), 9) for k in (10, 100, 1000)]
    [1.0, 1.0, 1.0]

    References
    ----------
    Makris et al. (1996) eq 13 and the Maxwell part of eq 16.
    """
    v = np.asarray(v, dtype=float)
    lam = C / K
    # the exact response to the step v(0) at t = 0 from rest: F(0) = 0, so filter the input minus its start value,
    # then add the response to the constant v(0), C v0 (1 - exp(-t/lam))
    t = np.asarray(t, dtype=float)
    return first_order_lag(t, C * (v - v[0]), lam) + C * v[0] * (1.0 - np.exp(-(t - t[0]) / lam))


class Maxwell(Model):
    r"""Linear Maxwell model of the damper: spring K in series with dashpot C.

    .. math:: F + \frac{C}{K}\dot F = (C + C_u u)\,\dot x, \qquad + f_0

    Parameters (SI): ``C`` [N s/m], ``K`` [N/m], ``f0`` [N]; ``C_u`` [N s/m] per unit control.

    Notes
    -----
    Exact discrete-time filter (first-order hold of the velocity); starts from rest.  Makris report for the
    El Centro record at 3 kV/mm a difference signal with PV = 257 lb and RMS = 56 lb.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 2001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = Maxwell().simulate(rec, {"C": 1.2e5, "K": 1e9})   # stiff spring: a dashpot
    >>> # F(0) = 0 (from rest), then it lags C v by lambda = C/K = 0.12 ms: about 6 N here
    >>> bool(np.max(np.abs(F - 1.2e5 * rec.velocity)[1:]) < 10.0)
    True

    References
    ----------
    Makris et al. (1996) eq 13 and section 4.1.
    """

    name = "maxwell"
    title = "Maxwell"
    source = "Makris et al. (1996) eq 13, section 4.1 (Makris)"
    uses_control = True
    control_parameters = ("C_u",)
    # C is not linear: it sets the relaxation time C / K as well; C_u only scales the filter's (linear) input
    linear_parameters = ("C_u", "f0")
    parameters = (
        Parameter("C", "N*s/m", 1.2e5, 1.0, 1e9, "dashpot constant", log_scale=True),
        Parameter("K", "N/m", 1e7, 1.0, 1e12, "series spring stiffness", log_scale=True),
        FORCE_OFFSET,
        Parameter("C_u", "N*s/m", 0.0, -1e9, 1e9, "dashpot constant per unit control"),
    )

    def force(self, record, values):
        C = values["C"] + values["C_u"] * self.control(record)
        # C may vary with the control: filter C v (the dashpot force) through the spring's relaxation
        return _maxwell_of(record.time, C * record.velocity, values["C"] / values["K"]) + values["f0"]

    def guess_from_force(self, record):
        C = viscous_slope(record)
        # relaxation time well below the period of 20 Hz
        return {"C": C, "K": C * 2 * np.pi * 20} if C > 1.0 else {}


def _maxwell_of(t, Fd, lam):
    """Maxwell filter of a dashpot-force history Fd (from rest, F(0) = 0)."""
    t = np.asarray(t, dtype=float)
    return first_order_lag(t, Fd - Fd[0], lam) + Fd[0] * (1.0 - np.exp(-(t - t[0]) / lam))


class BingMax(Model):
    r"""BingMax model (Makris eq 16): a Maxwell element in parallel with Coulomb friction.

    .. math:: F(t) = K\int_0^t e^{-(t-\tau)/\lambda}\dot x(\tau)\,d\tau + F_y\operatorname{sgn}\dot x(t) + f_0,
              \qquad \lambda = C/K ,

    with :math:`F_y = F_{y,0} + F_{y,u} u` (the friction is the field-dependent part).

    Parameters (SI): ``C`` [N s/m], ``K`` [N/m], ``F_y`` [N], ``f0`` [N]; ``F_y_u`` [N] per unit control.

    Notes
    -----
    Butz and von Stryk (2002) writes the model as eq 7, :math:`F + \lambda\dot F = C\dot u +
    F_y\operatorname{sgn}\dot u`, which
    would also low-pass the friction; that disagrees with its own eq 6 and with Makris eq 16 (friction in parallel,
    unfiltered), which is implemented here.  Makris report PV = 109 lb and RMS = 31 lb on El Centro at 3 kV/mm.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 2001); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> F = BingMax().simulate(rec, {"C": 1e4, "K": 1e9, "F_y": 500.0})
    >>> bool(np.max(np.abs(F - 1e4 * rec.velocity - 500 * np.sign(rec.velocity))[1:]) < 0.1)
    True

    References
    ----------
    Makris et al. (1996) eq 16; Butz and von Stryk (2002) eqs 6-7.
    """

    name = "bingmax"
    title = "BingMax (Makris)"
    source = "Makris et al. (1996) eq 16 (Makris); Butz and von Stryk (2002) eqs 6-7"
    uses_control = True
    control_parameters = ("F_y_u",)
    linear_parameters = ("F_y", "f0", "F_y_u")
    parameters = (
        Parameter("C", "N*s/m", 1.2e5, 1.0, 1e9, "dashpot constant", log_scale=True),
        Parameter("K", "N/m", 1e7, 1.0, 1e12, "series spring stiffness", log_scale=True),
        Parameter("F_y", "N", 500.0, 0.0, 1e7, "friction (yield) force"),
        FORCE_OFFSET,
        Parameter("F_y_u", "N", 0.0, -1e7, 1e7, "friction force per unit control"),
    )

    def force(self, record, values):
        v = record.velocity
        Fy = values["F_y"] + values["F_y_u"] * self.control(record)
        return maxwell_force(record.time, v, values["C"], values["K"]) + Fy * np.sign(v) + values["f0"]

    def guess_from_force(self, record):
        fy, c, f0 = sign_viscous_fit(record)
        g = {"F_y": max(fy, 0.0), "f0": f0}
        if c > 1.0:
            g.update(C=c, K=c * 2 * np.pi * 20)
        return g


class MaxwellNeural(Maxwell):
    r"""Makris's hybrid: a Maxwell model plus a small neural network trained on its residual (difference signal).

    .. math:: F = F_M + \mathrm{NN}(x, \dot x, \ddot x, u), \qquad
              \mathrm{NN}(q) = \sum_j w_j \tanh\Big(\sum_i W_{ji} \hat q_i + b_j\Big) + b_0

    with :math:`\hat q` the inputs scaled to unit standard deviation.

    The Maxwell parameters are this model's parameters; the network weights are trained state, set by
    :meth:`train` (the identification workflow calls it after fitting the Maxwell part).  Untrained, the network
    outputs zero and the model is the Maxwell model.

    Notes
    -----
    Departure from the source: Makris built a single-hidden-layer network of 99 neurons with six input delays by the
    Dependence Identification Algorithm; here a network of ``hidden`` tanh neurons (default 8) on the present
    displacement, velocity, acceleration and control is fitted by regularised least squares
    (:func:`scipy.optimize.least_squares`).  Makris found the network converged on the Maxwell residual but not on
    the BingMax residual (nearly white).

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 801); x = 0.01 * np.sin(2 * np.pi * t)
    >>> rec = Measurement.from_arrays(t, x); v = rec.velocity
    >>> rec = rec.with_force(1e4 * v + 300 * np.tanh(v / 0.01))
    >>> m = MaxwellNeural(hidden=4); vals = {"C": 1e4, "K": 1e9}
    >>> before = np.std(rec.force - m.simulate(rec, vals)); _ = m.train(rec, vals)
    >>> bool(np.std(rec.force - m.simulate(rec, vals)) < 0.2 * before)
    True

    References
    ----------
    Makris et al. (1996) section 4.3; Butz and von Stryk (2002) section 3.2.2.
    """

    name = "maxwell_neural"
    title = "Maxwell + neural network (Makris hybrid)"
    source = "Makris et al. (1996) section 4.3 (Makris); Butz and von Stryk (2002) section 3.2.2"

    def __init__(self, hidden: int = 8):
        if int(hidden) < 1:
            raise ErdesignError(f"hidden: the network needs at least one neuron, got {hidden}")
        self.hidden = int(hidden)
        self.weights: np.ndarray | None = None
        self._scale: np.ndarray | None = None

    def _inputs(self, record):
        return np.column_stack([record.displacement, record.velocity, record.acceleration, self.control(record)])

    def network(self, record) -> np.ndarray:
        """Network output [N] on the record (zeros when untrained)."""
        if self.weights is None:
            return np.zeros(len(record))
        return _mlp(self.weights, self._inputs(record) / self._scale, self.hidden)

    def force(self, record, values):
        return super().force(record, values) + self.network(record)

    def train(self, record, values, *, seed: int = 0, regularisation: float = 1e-3):
        """Fit the network to the residual of the Maxwell part on ``record``; returns the final RMS residual [N]."""
        F = record.require_force()
        values = self.check_values(values)
        q = self._inputs(record)
        scale = q.std(axis=0)
        scale[scale == 0] = 1.0
        self._scale = scale
        qs = q / scale
        target = F - Maxwell.force(self, record, values)
        norm = max(float(np.std(target)), 1e-12)
        k = q.shape[1]
        size = self.hidden * (k + 2) + 1
        rng = np.random.default_rng(seed)
        w0 = 0.5 * rng.standard_normal(size)

        def resid(w):
            r = _mlp(w, qs, self.hidden) - target / norm
            return np.concatenate([r, regularisation * w])

        def jac(w):
            return np.vstack([_mlp_jacobian(w, qs, self.hidden), regularisation * np.eye(size)])

        from scipy.optimize import least_squares  # imported on use: not at start-up

        res = least_squares(resid, w0, jac=jac, method="lm", max_nfev=200)  # MINPACK QR: no SVD per step
        self.weights = res.x * np.r_[np.ones(size - self.hidden - 1), np.full(self.hidden + 1, norm)]
        return float(np.sqrt(np.mean((target - self.network(record)) ** 2)))


def _mlp(w, q, hidden):
    """Single hidden layer tanh network; w = [W (hidden x k), b (hidden), out (hidden), out_bias]."""
    k = q.shape[1]
    W = w[: hidden * k].reshape(hidden, k)
    b = w[hidden * k : hidden * (k + 1)]
    out = w[hidden * (k + 1) : hidden * (k + 2)]
    return np.tanh(q @ W.T + b) @ out + w[-1]


def _mlp_jacobian(w, q, hidden):
    """d output / d weights of :func:`_mlp`, shape (samples, weights)."""
    n, k = q.shape
    W = w[: hidden * k].reshape(hidden, k)
    b = w[hidden * k : hidden * (k + 1)]
    out = w[hidden * (k + 1) : hidden * (k + 2)]
    h = np.tanh(q @ W.T + b)
    g = (1.0 - h**2) * out  # d output / d pre-activation
    dW = (g[:, :, None] * q[:, None, :]).reshape(n, hidden * k)
    return np.hstack([dW, g, h, np.ones((n, 1))])
