r"""Exact recurrences shared by the kernels, the models and the effects (plain numpy, SI-free).

* :func:`affine_recurrence` - :math:`y_{n+1} = c_n y_n + d_n` for all n at once, by a parallel prefix scan: the
  exact-step solution of every linear first-order law in time (the Makris law, :mod:`erdesign.constitutive`; the
  Dahl and LuGre friction states and the first-order filters of :mod:`erdesign.models`; the relaxation filters of
  :mod:`erdesign.effects`).
"""

from __future__ import annotations

import numpy as np

__all__ = ["affine_recurrence"]


def affine_recurrence(c, d, y0):
    r"""Solve :math:`y_{n+1} = c_n y_n + d_n` along axis 0 for all n, by a parallel prefix scan.

    ``c`` and ``d`` have shape (N - 1, ...), ``y0`` broadcasts to ``c.shape[1:]``; returns shape (N, ...).
    The affine maps :math:`y \mapsto c y + d` compose associatively, so log2(N) vectorised passes (Hillis-Steele
    scan) replace the Python loop over time steps.  With :math:`0 \le c_n \le 1` every partial product is
    bounded by 1, so the scan is as stable as the loop (no division by a product of decays, which underflows).
    """
    C = np.array(c, dtype=float, copy=True)
    D = np.array(d, dtype=float, copy=True)
    shift = 1
    while shift < C.shape[0]:
        # map[k] <- map[k] o map[k - shift]: (C_k, D_k) o (C_j, D_j) = (C_k C_j, C_k D_j + D_k)
        D[shift:] = C[shift:] * D[:-shift] + D[shift:]
        C[shift:] = C[shift:] * C[:-shift]
        shift *= 2
    y0 = np.broadcast_to(np.asarray(y0, dtype=float), C.shape[1:])
    return np.concatenate([y0[np.newaxis], C * y0 + D], axis=0)
