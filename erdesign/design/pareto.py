r"""Non-dominated (Pareto) filter for two or three figures of merit, vectorised.

A design dominates another when it is no worse in every figure and better in at least one.  The Pareto front is
the set of designs that no other design dominates: along it one figure can only be improved by giving up another
(controllable force against dynamic range against fluid volume, say).

All figures are minimised here; pass ``-x`` for a figure to be maximised (:func:`pareto_mask` takes ``maximize``).
"""

from __future__ import annotations

import numpy as np

__all__ = ["pareto_mask"]


def pareto_mask(values, maximize=None):
    r"""Mask of the non-dominated rows of ``values`` (each row a design, each column a figure).

    Row :math:`i` is dominated when some row :math:`j` has :math:`y_j \le y_i` in every column and
    :math:`y_j < y_i` in at least one (after negating the maximised columns).

    Parameters
    ----------
    values : array, shape (N, k)
        Figures of N designs, k >= 1 columns.
    maximize : sequence of bool, optional
        Per column: True to maximise it (default: minimise every column).

    Returns
    -------
    numpy.ndarray of bool, shape (N,)
        True for the designs on the Pareto front.  Of several identical rows on the front only the first is kept;
        rows with a NaN are never on it.

    Notes
    -----
    Two columns: a sort by the first figure and a running minimum of the second, O(N log N) with no loop.
    Three columns: a lexicographic sort, then blocks of 256 rows, each checked against the staircase of the
    earlier blocks (binary search) and against itself (pairwise): O(N log N) when the staircase is short, at most
    O(N^2 / 256) operations otherwise (256 rather than 1024: 2-2.5 x faster on the fronts of 2,000-4,500 designs of
    a mixed-mode sweep, benchmarks/bench_kernels_speed.py).  More columns: each surviving row in turn removes every
    row it dominates with one vectorised comparison (a loop over the front).  tests/test_design.py compares all
    three with the O(N^2) definition.

    Examples
    --------
    >>> pareto_mask([[1.0, 5.0], [2.0, 3.0], [3.0, 4.0], [4.0, 1.0], [2.0, 3.0]]).tolist()
    [True, True, False, True, False]
    >>> pareto_mask([[1.0, 5.0], [2.0, 3.0]], maximize=[True, False]).tolist()
    [False, True]
    """
    y = np.array(values, dtype=float, ndmin=2)
    if y.ndim != 2:
        raise ValueError(f"values: expected shape (N, k), got {np.shape(values)}")
    n, k = y.shape
    if maximize is not None:
        if len(maximize) != k:
            raise ValueError(f"maximize: expected {k} flags, got {len(maximize)}")
        y = np.where(np.asarray(maximize, dtype=bool), -y, y)
    mask = np.zeros(n, dtype=bool)
    finite = np.flatnonzero(np.all(np.isfinite(y), axis=1))
    if finite.size == 0:
        return mask
    yf = y[finite]
    if k == 1:
        mask[finite[np.argmin(yf[:, 0])]] = True
        return mask
    if k == 2:
        # Sort by the first figure, ties by the second, then by position; a row is on the front when its second
        # figure is below every earlier row's (the earlier rows are those no worse in the first figure).
        order = np.lexsort((np.arange(yf.shape[0]), yf[:, 1], yf[:, 0]))
        second = yf[order, 1]
        best_before = np.concatenate(([np.inf], np.minimum.accumulate(second)[:-1]))
        mask[finite[order[second < best_before]]] = True
        return mask
    if k == 3:
        mask[finite[_front3(yf)]] = True
        return mask
    ranks = np.argsort(np.argsort(yf, axis=0, kind="stable"), axis=0, kind="stable").sum(axis=1)
    order = np.lexsort((np.arange(yf.shape[0]), ranks))
    pts, idx = yf[order], finite[order]
    i = 0
    while i < pts.shape[0]:
        p = pts[i]
        # keep rows better than p somewhere (not dominated by p, not a copy of it) and p itself
        keep = np.any(pts < p, axis=1)
        keep[i] = True
        pts, idx = pts[keep], idx[keep]
        i = int(np.count_nonzero(keep[:i])) + 1
    mask[idx] = True
    return mask


def _front3(y, block=256):
    """Indices of the non-dominated rows of a finite (N, 3) array (minimised), first copy of duplicates only.

    In lexicographic order a row is dominated (or a later copy) exactly when an earlier row is no worse in the
    second and third figures.  The rows are taken in blocks: each block is compared with the staircase (the 2-D
    front in figures 2 and 3) of all earlier blocks by a binary search, and with itself pairwise.
    """
    n = y.shape[0]
    order = np.lexsort((np.arange(n), y[:, 2], y[:, 1], y[:, 0]))
    a, b = y[order, 1], y[order, 2]
    on_front = np.ones(n, dtype=bool)
    stair_a = np.empty(0)  # staircase: a ascending, b strictly descending
    stair_b = np.empty(0)
    for start in range(0, n, block):
        sa, sb = a[start : start + block], b[start : start + block]
        pos = np.searchsorted(stair_a, sa, side="right") - 1
        dominated = (pos >= 0) & (stair_b[np.maximum(pos, 0)] <= sb if stair_b.size else False)
        m = sa.size
        earlier = np.tri(m, m, -1, dtype=bool)  # [i, j]: j comes before i
        dominated |= np.any(earlier & (sa[None, :] <= sa[:, None]) & (sb[None, :] <= sb[:, None]), axis=1)
        on_front[start : start + m] = ~dominated
        ma, mb = np.concatenate([stair_a, sa]), np.concatenate([stair_b, sb])
        o = np.lexsort((mb, ma))
        ma, mb = ma[o], mb[o]
        best_before = np.concatenate(([np.inf], np.minimum.accumulate(mb)[:-1]))
        step = mb < best_before
        stair_a, stair_b = ma[step], mb[step]
    return order[on_front]
