r"""Candidate geometries that fill the bounds of a requirements set, chunk by chunk (bounded memory).

The free variables (bounds with low < high) are sampled in the unit hypercube and mapped to their ranges:
continuous lengths log-uniformly, :math:`x = x_\text{lo}(x_\text{hi}/x_\text{lo})^u`, because the gap enters the
pressure drop as :math:`h^{-1}` to :math:`h^{-3}` and a ratio of 4 in a bound matters as much at its low end as at
its high end; the number of ducts uniformly over the whole numbers of its range.  Fixed variables keep their value.

Two samplers of :mod:`scipy.stats.qmc`: a scrambled Sobol' sequence (default), one sequence cut into chunks so
that the first :math:`2^m` points of any run are a balanced design whatever the chunk size; or Latin hypercubes,
one per chunk.  Both are reproducible from ``design.search.seed``, and any chunk is made from the seed and its
index alone (:func:`candidate_chunk`), so the chunks of a sweep can be made on the workers that evaluate them.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterator
from typing import TYPE_CHECKING

import numpy as np
from scipy.stats import qmc

if TYPE_CHECKING:  # pragma: no cover
    from .requirements import Requirements

__all__ = ["map_unit_to_bounds", "candidate_chunks", "candidate_chunk", "chunk_count", "sobol_from", "variables_of"]


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


def chunk_count(req: "Requirements", samples: int | None = None, chunk: int | None = None) -> int:
    """How many chunks :func:`candidate_chunks` yields: ``ceil(samples / chunk)`` (one when no variable is free)."""
    s = req.search
    samples = s.samples if samples is None else samples
    chunk = s.chunk if chunk is None else chunk
    return 1 if not req.free_variables else -(-samples // chunk)


def candidate_chunk(
    req: "Requirements",
    index: int,
    samples: int | None = None,
    chunk: int | None = None,
    seed: int | None = None,
    sampling: str | None = None,
) -> dict:
    """Chunk ``index`` of :func:`candidate_chunks`, made from the seed and the index alone (no earlier chunk).

    So a worker of a parallel sweep makes its own chunk and only the index travels.  Sobol': the scrambled
    sequence of the seed, from point ``index * chunk`` on (:func:`sobol_from`, the same points as drawing the
    chunks one after the other).  Latin hypercube: one per chunk, from the random stream of the seed and the
    chunk index (``SeedSequence(seed, spawn_key=(index,))``, independent streams).

    Examples
    --------
    >>> from erdesign.design import load_example_requirements
    >>> req = load_example_requirements("makris_requirements")
    >>> whole = candidate_chunk(req, 0, samples=4096, chunk=4096)
    >>> second = candidate_chunk(req, 1, samples=4096, chunk=2048)
    >>> bool((second["gap"] == whole["gap"][2048:]).all())
    True
    """
    s = req.search
    samples = s.samples if samples is None else samples
    chunk = s.chunk if chunk is None else chunk
    seed = s.seed if seed is None else seed
    sampling = s.sampling if sampling is None else sampling
    free = req.free_variables
    if not free:
        return variables_of(req, 1)
    start = index * chunk
    if not 0 <= start < samples:
        raise ValueError(f"chunk {index} is outside the {chunk_count(req, samples, chunk)} chunks of the sweep")
    m = min(chunk, samples - start)
    with warnings.catch_warnings():
        # Sobol' balance holds for the power-of-2 prefixes of the whole run, not for each chunk.
        warnings.filterwarnings("ignore", message=".*balance properties of Sobol.*")
        if sampling == "sobol":
            u = sobol_from(len(free), seed, start).random(m)
        else:
            rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(index,)))
            u = qmc.LatinHypercube(len(free), seed=rng).random(m)
    return map_unit_to_bounds(u, req.bounds, free)


def sobol_from(d: int, seed: int, start: int) -> qmc.Sobol:
    r"""The scrambled Sobol' engine of ``seed`` in ``d`` dimensions, positioned at point ``start``.

    Point :math:`k` of the sequence, in the Gray-code order scipy draws in (Antonov and Saleev 1979), is the
    scrambling shift XOR the scrambled direction numbers of the bits set in :math:`g(k) = k \oplus \lfloor k/2
    \rfloor`, so the engine is positioned by XOR-ing at most 30 direction numbers, where
    :meth:`scipy.stats.qmc.Sobol.fast_forward` steps through the ``start`` points one by one (5 s for 10^9 points:
    more than evaluating a far chunk).  The state set is scipy's (``_shift``, ``_sv``, ``_quasi``); a scipy
    without it gets ``fast_forward``.  tests/test_design_executor.py checks the points against a sequential draw.

    References
    ----------
    Antonov, I. A. and Saleev, V. M. (1979), An economic method of computing LP_tau-sequences, USSR Computational
    Mathematics and Mathematical Physics 19(1), 252-256.

    Examples
    --------
    >>> a = qmc.Sobol(3, scramble=True, seed=np.random.default_rng(7))
    >>> _ = a.random(1024)
    >>> bool((sobol_from(3, 7, 1024).random(24) == a.random(24)).all())
    True
    """
    sobol = qmc.Sobol(d, scramble=True, seed=np.random.default_rng(seed))
    if start == 0:
        return sobol
    if not all(hasattr(sobol, a) for a in ("_shift", "_sv", "_quasi")):  # pragma: no cover - another scipy
        return sobol.fast_forward(start)
    k = start - 1  # the engine holds the last point drawn
    gray = k ^ (k >> 1)
    quasi = sobol._shift.copy()
    for bit in range(int(gray).bit_length()):
        if gray >> bit & 1:
            quasi ^= sobol._sv[:, bit]
    sobol._quasi = quasi
    sobol.num_generated = start
    return sobol


def candidate_chunks(
    req: "Requirements",
    samples: int | None = None,
    chunk: int | None = None,
    seed: int | None = None,
    sampling: str | None = None,
) -> Iterator[dict]:
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
        At most ``chunk`` candidates; ``samples`` in total (one when no variable is free): the chunks of
        :func:`candidate_chunk`, in order.
    """
    for index in range(chunk_count(req, samples, chunk)):
        yield candidate_chunk(req, index, samples, chunk, seed, sampling)
