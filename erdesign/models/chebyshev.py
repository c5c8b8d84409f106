r"""Chebyshev polynomial fit of the restoring force (Ehrgott and Masri; 3-D with the field, Gavin et al.).

.. math::
    F(x, \dot x, u) \approx \sum_{i,j=0}^{m}\sum_{k=0}^{m_u} C_{ijk}\,T_i(x')\,T_j(\dot x')\,T_k(u')

with x', v', u' the displacement, velocity and control mapped linearly onto [-1, 1] (Butz and von Stryk 2002,
eqs 29-30).
"""

from __future__ import annotations

import numpy as np
from numpy.polynomial import chebyshev as C

from ..errors import ErdesignError
from .base import Model, Parameter

__all__ = ["Chebyshev"]


class Chebyshev(Model):
    r"""Non-parametric Chebyshev fit of the force over displacement, velocity and (optionally) control.

    .. math:: F = \sum_{i,j=0}^{m}\sum_{k=0}^{m_u} C_{ijk}T_i(x')T_j(\dot x')T_k(u'),
              \quad x' = \frac{x - x_c}{x_s},\ \dot x' = \frac{\dot x}{v_s},\ u' = \frac{u - u_c}{u_s}

    Parameters (SI): ``C_i_j_k`` [N] for i, j <= ``degree`` and k <= ``control_degree``; the normalisation
    ``x_c``, ``x_s`` [m], ``v_s`` [m/s], ``u_c``, ``u_s`` [-], chosen from the data (not fitted).

    Notes
    -----
    ``control_degree = 0`` is the 2-D fit of Ehrgott and Masri (eq 29); ``control_degree >= 1`` the 3-D fit of
    Gavin et al. (eq 30).  The coefficients enter linearly: :meth:`initial_guess` solves the linear least-squares
    problem directly, so fitting converges at once.  Normalised arguments are clipped to [-1, 1]: outside the range
    of the data it was fitted on the model extrapolates flat, not polynomially.  Without a control column the
    k >= 1 coefficients are held at zero.

    Examples
    --------
    >>> import numpy as np
    >>> from erdesign.data.measurement import Measurement
    >>> t = np.linspace(0, 2, 801); rec = Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t))
    >>> rec = rec.with_force(3000 * rec.velocity + 2e4 * rec.displacement)
    >>> m = Chebyshev(degree=2); g = m.initial_guess(rec)
    >>> round(float(np.max(np.abs(m.simulate(rec, g) - rec.force))), 6)
    0.0

    References
    ----------
    Butz and von Stryk (2002) eqs 29-30 (Ehrgott and Masri; Gavin et al.).
    """

    name = "chebyshev"
    title = "Chebyshev polynomial fit"
    source = "Butz and von Stryk (2002) eqs 29-30 (Ehrgott and Masri; Gavin et al.)"
    uses_control = True

    def __init__(self, degree: int = 3, control_degree: int = 1):
        if int(degree) < 1 or int(control_degree) < 0:
            raise ErdesignError(
                f"Chebyshev: degree must be >= 1 and control_degree >= 0, got {degree}, {control_degree}"
            )
        self.degree = int(degree)
        self.control_degree = int(control_degree)
        coeffs = tuple(
            Parameter(f"C_{i}_{j}_{k}", "N", 0.0, -1e9, 1e9, f"coefficient of T{i}(x') T{j}(v') T{k}(u')")
            for k in range(self.control_degree + 1)
            for i in range(self.degree + 1)
            for j in range(self.degree + 1)
        )
        scales = (
            Parameter("x_c", "m", 0.0, -10.0, 10.0, "centre of the displacement range", fitted=False),
            Parameter("x_s", "m", 0.01, 1e-12, 10.0, "half range of the displacement", fitted=False),
            Parameter("v_s", "m/s", 0.1, 1e-12, 1e3, "largest velocity", fitted=False),
            Parameter("u_c", "", 0.0, -1e9, 1e9, "centre of the control range", fitted=False),
            Parameter("u_s", "", 1.0, 1e-12, 1e9, "half range of the control", fitted=False),
        )
        self.parameters = coeffs + scales
        self.control_parameters = tuple(p.name for p in coeffs if not p.name.endswith("_0"))
        self.linear_parameters = tuple(p.name for p in coeffs)

    def _basis(self, record, values):
        xn = np.clip((record.displacement - values["x_c"]) / values["x_s"], -1.0, 1.0)
        vn = np.clip(record.velocity / values["v_s"], -1.0, 1.0)
        un = np.clip((self.control(record) - values["u_c"]) / values["u_s"], -1.0, 1.0)
        Tx = C.chebvander(xn, self.degree)
        Tv = C.chebvander(vn, self.degree)
        Tu = C.chebvander(un, self.control_degree)
        # columns ordered as the parameters: k, i, j
        return (Tu[:, :, None, None] * Tx[:, None, :, None] * Tv[:, None, None, :]).reshape(len(record), -1)

    def linear_terms(self, record, values):
        B = self._basis(record, values)
        return {name: B[:, j] for j, name in enumerate(self.linear_parameters)}, np.zeros(len(record))

    def force(self, record, values):
        coeffs = np.array([values[p.name] for p in self.parameters[:-5]])
        return self._basis(record, values) @ coeffs

    def initial_guess(self, record):
        g = self.defaults()
        x, v, u = record.displacement, record.velocity, self.control(record)
        g["x_c"] = float(0.5 * (x.max() + x.min()))
        g["x_s"] = float(max(0.5 * (x.max() - x.min()), 1e-12))
        g["v_s"] = float(max(np.max(np.abs(v)), 1e-12))
        g["u_c"] = float(0.5 * (u.max() + u.min()))
        g["u_s"] = float(max(0.5 * (u.max() - u.min()), 1e-12)) if record.control_kind else 1.0
        if record.force is not None:
            B = self._basis(record, g)
            ncol = (self.degree + 1) ** 2 * (self.control_degree + 1 if record.control_kind else 1)
            sol, *_ = np.linalg.lstsq(B[:, :ncol], record.force, rcond=None)
            for p, c in zip(self.parameters[:ncol], sol):
                g[p.name] = float(np.clip(c, p.lower, p.upper))
        return g
