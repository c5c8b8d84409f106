"""The design sweep on the executor (erdesign/design/search.py): the serial search, a local pool of 2 processes and
a Dask LocalCluster give the same DesignResult bit for bit; chunks made from their index are those of the
sequential sampler; merging chunk summaries does not depend on how the chunks are grouped."""

import itertools
import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.stats import qmc

from erdesign.design import design, load_example_requirements
from erdesign.design.evaluate import constraints_for
from erdesign.design.sampling import (
    candidate_chunk,
    candidate_chunks,
    chunk_count,
    sobol_from,
)
from erdesign.design.search import _chunk_summary, _evaluate, _Summary
from erdesign.executor import PoolExecutor, SerialExecutor

# Small sweeps (a few chunks each) so that every executor runs in a few seconds: a valve damper with refinement,
# an infeasible one (nearest design and conflicts) and a mixed-mode MR damper with a coil.
CASES = {
    "makris_requirements": {"samples": 5 * 1024 + 300, "chunk": 1024},
    "infeasible_requirements": {"samples": 4 * 1024, "chunk": 1024},
    "mr_coil_requirements": {"samples": 2048, "chunk": 1024},
}


def _req(name):
    return load_example_requirements(name).with_search(**CASES[name])


def _as_text(result) -> str:
    """Every number of the result (ranked designs with their geometry strings, Pareto set, counts, conflicts) in
    one string: equal strings are equal results, bit for bit (floats are written with repr's 17 digits)."""
    return json.dumps(result.as_json(), sort_keys=True)


@pytest.fixture(scope="module")
def serial():
    return {name: design(_req(name)) for name in CASES}


def _check_same(result, reference):
    assert _as_text(result) == _as_text(reference)
    assert result.evaluated == reference.evaluated and result.feasible_count == reference.feasible_count
    assert [d["geometry"] for d in result.designs] == [d["geometry"] for d in reference.designs]
    assert [d["geometry"] for d in result.pareto] == [d["geometry"] for d in reference.pareto]


def test_serial_sweep_is_the_search_of_the_examples(serial):
    """Guards that the cases exercise what they should: feasible designs with a front, and the conflicts path."""
    r = serial["makris_requirements"]
    assert r.feasible and len(r.designs) == r.requirements.search.designs and r.pareto
    assert r.evaluated == 5 * 1024 + 300
    assert not serial["infeasible_requirements"].feasible and serial["infeasible_requirements"].conflicts
    assert serial["mr_coil_requirements"].requirements.configuration == "mixed"


def test_pool_of_two_gives_the_serial_result(serial):
    seen = []
    with PoolExecutor(2) as pool:
        for name in CASES:
            _check_same(design(_req(name), executor=pool), serial[name])
        _check_same(
            design(_req("makris_requirements"), executor=pool, progress=lambda *a: seen.append(a)),
            serial["makris_requirements"],
        )
    # progress: one call per chunk, the last one with every candidate
    assert len(seen) == 6 and seen[-1][0] == seen[-1][1] == 5 * 1024 + 300
    assert seen[-1][2] == serial["makris_requirements"].feasible_count


def test_thinned_front_is_the_same_on_a_pool(monkeypatch):
    """Beyond FRONT_STORE the stored front is thinned after each merge: the merges run in the caller, in chunk
    order, so the thinned front is still the serial one (about 170 front designs per chunk here, 64 kept)."""
    from erdesign.design import search

    monkeypatch.setattr(search, "FRONT_STORE", 64)
    req = load_example_requirements("mr_requirements").with_search(samples=4096, chunk=1024, refine=False)
    reference = design(req)
    assert 0 < len(reference.pareto) <= 64
    with PoolExecutor(2) as pool:
        _check_same(design(req, executor=pool), reference)


def test_jobs_argument_opens_and_closes_its_own_pool(serial):
    _check_same(design(_req("makris_requirements"), jobs=2), serial["makris_requirements"])


@pytest.mark.slow
def test_dask_local_cluster_gives_the_serial_result(serial, dask_client):
    for name in CASES:
        _check_same(design(_req(name), scheduler=dask_client), serial[name])


# ---------------------------------------------------------------------------------------------- chunks by index
def test_chunks_by_index_are_the_sequential_sobol_points():
    """A chunk made from its index alone holds the points of the one scrambled sequence drawn from the start."""
    req = load_example_requirements("mr_coil_requirements")
    d = len(req.free_variables)
    whole = np.vstack([candidate_chunk(req, 0, samples=3000, chunk=3000)["gap"]])
    parts = np.concatenate([x["gap"] for x in candidate_chunks(req, samples=3000, chunk=1024)])
    assert np.array_equal(whole, parts[None, :])
    reference = qmc.Sobol(d, scramble=True, seed=np.random.default_rng(req.search.seed))
    points = reference.random(4096)
    for start in (1, 2, 3, 1023, 1024, 1025, 2047, 4000):
        assert np.array_equal(sobol_from(d, req.search.seed, start).random(4096 - start), points[start:]), start
    assert chunk_count(req, samples=3000, chunk=1024) == 3


def test_latin_hypercube_chunks_are_independent_streams():
    req = load_example_requirements("makris_requirements").with_search(sampling="lhs")
    a = candidate_chunk(req, 1, samples=4096, chunk=1024)
    assert np.array_equal(a["gap"], candidate_chunk(req, 1, samples=4096, chunk=1024)["gap"])
    b = candidate_chunk(req, 2, samples=4096, chunk=1024)
    assert not np.array_equal(a["gap"], b["gap"])
    # a Latin hypercube per chunk: each free variable has one point in each of the 1024 strata of its range
    lo, hi = req.bounds["gap"]
    u = np.log(a["gap"] / lo) / np.log(hi / lo)
    assert np.array_equal(np.sort(np.floor(u * 1024)), np.arange(1024))


def test_chunk_outside_the_sweep_is_an_error():
    req = load_example_requirements("makris_requirements")
    with pytest.raises(ValueError, match="chunk 4 is outside the 4 chunks"):
        candidate_chunk(req, 4, samples=4096, chunk=1024)


# ------------------------------------------------------------------------------------------------ merge algebra
def _same_summary(a: _Summary, b: _Summary, figures_rtol: float = 0.0) -> None:
    """Same counts, same designs (their variables bit for bit) and the same figures: bit for bit, or within
    ``figures_rtol`` where the two were evaluated in chunks of different sizes (flow arrays of at least
    erdesign.flow.bingham.COMPILED_MIN_SIZE elements go through the compiled loop, smaller ones through numpy:
    the same arithmetic, equal to a few ulp)."""
    for name in ("evaluated", "valid", "feasible"):
        assert getattr(a, name) == getattr(b, name), name
    for name in ("best_X", "front_X", "near_X", "violated", "single", "pair"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    for name in ("best_key", "front_Y", "near_v"):
        assert np.allclose(getattr(a, name), getattr(b, name), rtol=figures_rtol, atol=0.0, equal_nan=True), name


def _chunk_parts(name, chunks=8, chunk=1024):
    req = load_example_requirements(name).with_search(samples=chunks * chunk, chunk=chunk)
    keep = 16
    parts = [_chunk_summary(req, keep, i) for i in range(chunks)]
    return req, keep, parts


def _fold(req, keep, parts):
    total = _Summary(len(constraints_for(req)), keep, req.variables)
    for p in parts:
        total.merge(p, req.search.pareto)
    return total


@pytest.fixture(scope="module")
def chunk_parts():
    return {name: _chunk_parts(name) for name in ("makris_requirements", "infeasible_requirements")}


def test_merged_chunk_summaries_are_the_summary_of_the_whole_sample(chunk_parts):
    """Merging the 8 chunk summaries gives the summary of the 8192 candidates taken as one chunk."""
    for req, keep, parts in chunk_parts.values():
        whole = req.with_search(chunk=len(parts) * 1024)
        one = _Summary.of_chunk(
            _evaluate(whole, candidate_chunk(whole, 0), constraints_for(req)),
            req.objective,
            req.search.pareto,
            keep,
            req.variables,
        )
        # the whole sample is one chunk of 8192 (compiled flow loop), the parts chunks of 1024 (numpy)
        _same_summary(_fold(req, keep, parts), _fold(req, keep, [one]), figures_rtol=1e-13)


@settings(max_examples=25, deadline=None)
@given(
    cuts=st.lists(st.integers(1, 7), unique=True),
    name=st.sampled_from(["makris_requirements", "infeasible_requirements"]),
)
def test_merge_is_associative_over_random_groupings(chunk_parts, cuts, name):
    """Chunks split into consecutive groups at random cuts, each group merged alone, the groups merged in order:
    the summary of the serial fold, array for array."""
    req, keep, parts = chunk_parts[name]
    bounds = [0, *sorted(cuts), len(parts)]
    groups = [_fold(req, keep, parts[a:b]) for a, b in itertools.pairwise(bounds)]
    _same_summary(_fold(req, keep, groups), _fold(req, keep, parts))


def test_ties_go_to_the_earlier_candidate():
    """The k smallest keys with ties at the k-th: the earliest of the tied candidates, in a group or after merges
    of groups (argpartition alone picks among tied keys by its own order)."""
    from erdesign.design.search import _smallest

    key = np.array([3.0, 1.0, 2.0, 1.0, 2.0, np.nan, 2.0, 0.5, 2.0])
    assert _smallest(key, 4).tolist() == [7, 1, 3, 2]
    assert _smallest(key, 20).tolist() == [7, 1, 3, 2, 4, 6, 8, 0, 5]
    rng = np.random.default_rng(1)
    for _ in range(50):
        key = rng.integers(0, 5, 40).astype(float)  # many ties
        k = int(rng.integers(1, 12))
        whole = _smallest(key, k)
        assert whole.tolist() == np.lexsort((np.arange(40), key))[:k].tolist()
        cut = int(rng.integers(1, 40))
        first = _smallest(key[:cut], k)
        second = cut + _smallest(key[cut:], k)
        both = np.concatenate([first, second])
        assert both[_smallest(key[both], k)].tolist() == whole.tolist()


def test_serial_executor_is_the_default():
    """No executor argument: the search stays in this process (a library call is serial unless asked)."""
    req = _req("makris_requirements")
    assert _as_text(design(req)) == _as_text(design(req, executor=SerialExecutor()))


# ------------------------------------------------------------------------------------------------- command line
def test_cli_jobs_gives_the_same_designs(capsys):
    from pathlib import Path

    import erdesign
    from erdesign.cli.main import main

    path = str(Path(erdesign.__file__).parent / "examples" / "requirements" / "makris_requirements.toml")
    assert main(["design", path, "--json"]) == 0
    serial = capsys.readouterr().out
    assert main(["design", path, "--json", "--jobs", "2"]) == 0
    assert capsys.readouterr().out == serial
    assert main(["design", path, "--jobs", "0"]) == 2
    err = capsys.readouterr().err
    assert "--jobs" in err and len(err.strip().splitlines()) == 1
    assert main(["design", path, "--jobs", "2", "--scheduler", "tcp://127.0.0.1:8786"]) == 2
    err = capsys.readouterr().err
    assert "give one of them" in err and len(err.strip().splitlines()) == 1
