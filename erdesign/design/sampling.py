r"""Candidate geometries that fill the bounds of a requirements set, chunk by chunk (bounded memory).

The free variables (bounds with low < high) are sampled in the unit hypercube and mapped to their ranges:
continuous lengths log-uniformly, :math:`x = x_\text{lo}(x_\text{hi}/x_\text{lo})^u`, because the gap enters the
pressure drop as :math:`h^{-1}` to :math:`h^{-3}` and a ratio of 4 in a bound matters as much at its low end as at
its high end; the number of ducts uniformly over the whole numbers of its range.  Fixed variables keep their value.

Two samplers of :mod:`scipy.stats.qmc`: a scrambled Sobol' sequence (default), drawn chunk after chunk so that the
first :math:`2^m` points of any run are a balanced design whatever the chunk size; or Latin hypercubes, one per
chunk.  Both are reproducible from ``design.search.seed``.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterator
from typing import TYPE_CHECKING

import numpy as np
from scipy.stats import qmc

if TYPE_CHECKING:  # pragma: no cover
    from .requirements import Requirements

__all__ = ["map_unit_to_bounds", "candidate_chunks", "variables_of"]


def map_unit_to_bounds(u, bounds, free):
    r"""Map points of the unit hypercube to candidate geometries.

    .. math:: x = x_\text{lo}\left(\frac{x_\text{hi}}{x_\text{lo}}\right)^u \;\text{(lengths)}, \qquad
              n = n_\text{lo} + \lfloor u\,(n_\text{hi} - n_\text{lo} + 1) \rfloor \;\text{(ducts)}

    Parameters
    ----------
    u : array, shape (N, k)
        Points in [0, 1), one column per name in ``free``.
    bounds : mapping
        Name -> (low, high) in SI for every variable (None for a variable the configuration does not have).
    free : sequence of str
        Names of the sampled variables, in the order of the columns of ``u``.

    Returns
    -------
    dict of str -> array
        One array of N values per variable (fixed variables repeated; None stays None).

    Examples
    --------
    >>> import numpy as np
    >>> x = map_unit_to_bounds(np.array([[0.0, 0.5], [0.5, 0.99]]), {"gap": (1e-3, 4e-3), "ducts": (1, 3)},
    ...                        ["gap", "ducts"])
    >>> x["gap"].tolist(), x["ducts"].tolist()
    ([0.001, 0.002], [2.0, 3.0])
    """
    u = np.asarray(u, dtype=float)
    n = u.shape[0]
    out = {}
    for name, b in bounds.items():
        if b is None:
            out[name] = None
            continue
        lo, hi = b
        if name not in free:
            out[name] = np.full(n, float(lo))
            continue
        col = u[:, list(free).index(name)]
        if name == "ducts":
            out[name] = np.minimum(lo + np.floor(col * (hi - lo + 1)), hi)
        else:
            out[name] = lo * np.exp(col * np.log(hi / lo))
    return out


def variables_of(req: "Requirements", n: int = 1) -> dict:
    """The variables of ``req`` at the low end of every bound, N copies (a template for the fixed ones)."""
    return map_unit_to_bounds(np.zeros((n, len(req.free_variables))), req.bounds, req.free_variables)


def candidate_chunks(req: "Requirements", samples: int | None = None, chunk: int | None = None,
                     seed: int | None = None, sampling: str | None = None) -> Iterator[dict]:
    """Yield candidate geometries (dicts of arrays, see :func:`map_unit_to_bounds`) in chunks.

    Parameters
    ----------
    req : Requirements
        Bounds and search settings.
    samples, chunk, seed, sampling : optional
        Override ``req.search``.

    Yields
    ------
    dict of str -> array
        At most ``chunk`` candidates; ``samples`` in total (one when no variable is free).
    """
    s = req.search
    samples = s.samples if samples is None else samples
    chunk = s.chunk if chunk is None else chunk
    seed = s.seed if seed is None else seed
    sampling = s.sampling if sampling is None else sampling
    free = req.free_variables
    if not free:
        yield variables_of(req, 1)
        return
    rng = np.random.default_rng(seed)
    sobol = qmc.Sobol(len(free), scramble=True, seed=rng) if sampling == "sobol" else None
    done = 0
    while done < samples:
        m = min(chunk, samples - done)
        with warnings.catch_warnings():
            # Sobol' balance holds for the power-of-2 prefixes of the whole run, not for each chunk.
            warnings.filterwarnings("ignore", message=".*balance properties of Sobol.*")
            u = sobol.random(m) if sobol is not None else qmc.LatinHypercube(len(free), seed=rng).random(m)
        done += m
        yield map_unit_to_bounds(u, req.bounds, free)
