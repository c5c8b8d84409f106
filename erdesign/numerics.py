r"""Exact recurrences shared by the kernels, the models and the effects (plain numpy, SI-free).

* :func:`affine_recurrence` - :math:`y_{n+1} = c_n y_n + d_n` for all n at once, by a parallel prefix scan: the
  exact-step solution of every linear first-order law in time (the Makris law, :mod:`erdesign.constitutive`; the
  Dahl and LuGre friction states and the first-order filters of :mod:`erdesign.models`; the relaxation filters of
  :mod:`erdesign.effects`).
"""

from __future__ import annotations

import numpy as np

__all__ = ["affine_recurrence", "find_root"]


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


def find_root(f, a, b, *, args=(), xatol: float, xrtol: float, maxiter: int = 100) -> np.ndarray:
    """Roots of an elementwise function ``f(x, *args)`` bracketed by ``a`` and ``b`` (arrays of one shape, ``args``
    too), by Chandrupatla's method: the iterates and the stopping rules of :func:`scipy.optimize.elementwise.find_root`
    with ``tolerances={"xatol": xatol, "xrtol": xrtol}`` (function tolerance the smallest normal float), whose result
    ``x`` it returns, element for element the same (tests/test_numerics_find_root.py); NaN where the bracket does not
    hold a sign change.  Without scipy's array-API framework, whose bookkeeping per step costs several times the
    function itself on a few thousand elements (the bracketed root of a damper with a bypass,
    :func:`erdesign.effects.leakage.leaky_pressure_drop`, evaluated at every sample in every step of a fit)."""
    shape = np.broadcast_shapes(np.shape(a), np.shape(b), *(np.shape(v) for v in args))
    x1 = np.array(np.broadcast_to(np.asarray(a, dtype=float), shape)).ravel()
    x2 = np.array(np.broadcast_to(np.asarray(b, dtype=float), shape)).ravel()
    args = [np.broadcast_to(np.asarray(v, dtype=float), shape).ravel() for v in args]
    f1 = np.asarray(f(x1, *args), dtype=float)
    f2 = np.asarray(f(x2, *args), dtype=float)
    fatol = np.finfo(float).smallest_normal
    with np.errstate(invalid="ignore"):
        frtol = 0.0 * np.minimum(np.abs(f1), np.abs(f2))  # scipy's frtol = 0 times the ends' values (NaN at inf)
    out = np.empty(x1.size)
    active = np.arange(x1.size)
    x3 = f3 = None
    t: float | np.ndarray = 0.5
    nit = 0
    with np.errstate(divide="ignore", invalid="ignore"):
        while True:
            # termination, as scipy's check_termination: the better end, then every test in its order
            better = np.abs(f1) < np.abs(f2)
            xmin = np.where(better, x1, x2)
            fmin = np.where(better, f1, f2)
            stop = np.abs(fmin) <= fatol + frtol
            lost = (np.sign(f1) == np.sign(f2)) & ~stop
            invalid = (~(np.isfinite(x1) & np.isfinite(x2)) | (np.isnan(f1) & np.isnan(f2))) & ~stop & ~lost
            xmin[lost | invalid] = np.nan
            stop |= lost | invalid
            dx = np.abs(x2 - x1)
            tol = np.abs(xmin) * xrtol + xatol
            stop |= dx < tol
            if np.any(stop):
                out[active[stop]] = xmin[stop]
                keep = ~stop
                active = active[keep]
                x1, f1, x2, f2, frtol, dx, tol = (v[keep] for v in (x1, f1, x2, f2, frtol, dx, tol))
                if x3 is not None:
                    x3, f3 = x3[keep], f3[keep]
                if np.ndim(t):
                    t = t[keep]
                args = [v[keep] for v in args]
            if active.size == 0:
                break
            if nit >= maxiter:
                out[active] = xmin[~stop]
                break
            if nit:  # the next point's position in the bracket: inverse quadratic interpolation when it is safe
                xi1 = (x1 - x2) / (x3 - x2)
                phi1 = (f1 - f2) / (f3 - f2)
                alpha = (x3 - x1) / (x2 - x1)
                j = ((1 - np.sqrt(1 - xi1)) < phi1) & (phi1 < np.sqrt(xi1))
                f1j, f2j, f3j, alphaj = f1[j], f2[j], f3[j], alpha[j]
                t = np.full_like(alpha, 0.5)
                t[j] = f1j / (f1j - f2j) * f3j / (f3j - f2j) - alphaj * f1j / (f3j - f1j) * f2j / (f2j - f3j)
                tl = 0.5 * tol / dx
                t = np.clip(t, tl, 1 - tl)
            x = x1 + t * (x2 - x1)
            fx = np.asarray(f(x, *args), dtype=float)
            x3, f3 = x2.copy(), f2.copy()
            j = np.sign(fx) == np.sign(f1)
            x3[j], f3[j] = x1[j], f1[j]
            x2[~j], f2[~j] = x1[~j], f1[~j]
            x1, f1 = x, fx
            nit += 1
    return out.reshape(shape)
