"""The diagnosis benchmark (benchmarks/bench_diagnosis_accuracy.py, docs/diagnosis_benchmark.md).

A fast unit test holds the catalogue of :func:`erdesign.simulation.truthrig.cases.benchmark_cases` to its coverage
rules; a slow end-to-end test diagnoses the fast subset (records of the independent truth rig, written to CSV and read
back with the reader users use) and requires every verdict to be right and no exception.
"""

import importlib.util
from itertools import combinations
from pathlib import Path

import pytest

from erdesign.effects import EFFECT_NAMES
from erdesign.simulation.truthrig import MECHANISMS
from erdesign.simulation.truthrig.cases import (DAMPERS, EXCITATIONS, LIBRARY_MECHANISMS, NOISES, NOT_VISIBLE_ON,
                                                OUT_OF_LIBRARY, EXCITATIONS_OF, STEP_PERIOD, benchmark_cases, supported,
                                                unsupported_pairs)

BENCH = Path(__file__).resolve().parent.parent / "benchmarks" / "bench_diagnosis_accuracy.py"


@pytest.fixture(scope="module")
def catalogue():
    return benchmark_cases("full")


def _bench():
    spec = importlib.util.spec_from_file_location("bench_diagnosis_accuracy", BENCH)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_mechanism_map_agrees_with_the_truth_rig():
    # the catalogue's effect -> mechanism map is the truth rig's own, read backwards
    assert sorted(LIBRARY_MECHANISMS) == sorted(EFFECT_NAMES)
    for effect, mech in LIBRARY_MECHANISMS.items():
        assert MECHANISMS[mech].library_effect == effect
    for mech in OUT_OF_LIBRARY:
        assert MECHANISMS[mech].library_effect is None


def test_catalogue_meets_the_coverage_rules(catalogue):
    names = [c.name for c in catalogue]
    assert len(catalogue) >= 150
    assert len(set(names)) == len(names)
    kinds = [c.kind for c in catalogue]
    assert kinds.count("clean") >= 10 and kinds.count("out_of_library") >= 10
    assert {c.excitation for c in catalogue} == set(EXCITATIONS)
    assert {c.noise for c in catalogue} == set(NOISES)
    assert {c.damper for c in catalogue} >= {"makris", "mr_valve", "mr_valve_current"}
    assert any(c.load_damper().geometry.configuration == "mixed" for c in catalogue)
    assert {m for c in catalogue if c.kind == "out_of_library" for m in c.mechanisms} == set(OUT_OF_LIBRARY)
    for effect in EFFECT_NAMES:
        singles = [c for c in catalogue if c.kind == "single" and c.expected == effect]
        for size in ("moderate", "large"):
            at_size = [c for c in singles if c.size == size]
            # on every damper, valve and mixed mode, except where it cannot be seen at a physical size; four at least
            mech = LIBRARY_MECHANISMS[effect]
            possible = {d for d in DAMPERS if d not in NOT_VISIBLE_ON.get(mech, ())}
            assert all(supported({mech}, d) for d in DAMPERS), effect
            assert {c.damper for c in at_size} == possible and len(possible) >= 4, (effect, size)
            assert any(c.load_damper().geometry.configuration == "mixed" for c in at_size), (effect, size)
        assert {c.excitation for c in singles} == set(EXCITATIONS_OF.get(mech, EXCITATIONS)), effect
        assert {c.noise for c in singles} == set(NOISES), effect
    pairs = {frozenset(c.accepted) for c in catalogue if c.kind == "pair"}
    assert unsupported_pairs() == []
    assert pairs == {frozenset(p) for p in combinations(EFFECT_NAMES, 2)}
    for c in catalogue:
        assert supported(c.mechanisms, c.damper), c.name
        if c.kind in ("single", "pair"):
            assert c.expected in c.accepted and c.accepted <= set(EFFECT_NAMES)
            assert {MECHANISMS[m].library_effect for m in c.mechanisms} == set(c.accepted)
        else:
            assert not c.accepted
        assert 3.0 <= c.duration <= 20.0 and 500.0 <= c.rate <= 1000.0


def test_catalogue_is_deterministic(catalogue):
    again = benchmark_cases("full")
    assert [(c.name, c.seed, c.mechanisms) for c in again] == [(c.name, c.seed, c.mechanisms) for c in catalogue]


def test_the_control_changes_at_speed_and_is_on_part_of_the_record(catalogue):
    for c in [c for c in catalogue if c.kind == "single"][::9]:
        damper = c.load_damper()
        m = c.motion(damper)
        on = m.control > 0
        assert 0.3 < on.mean() < 0.9, c.name
        steps = (m.control[1:] != m.control[:-1]).nonzero()[0] + 1
        assert len(steps) >= 3
        # every step falls on the speed peak within a third of a step period of its nominal time
        speed, t = abs(m.velocity), m.time
        for k, i in enumerate(steps, start=1):
            near = abs(t - (t[0] + k * STEP_PERIOD)) <= STEP_PERIOD / 3
            assert near[i] and speed[i] >= speed[near].max() * (1 - 1e-9), (c.name, t[i])


def test_fast_subset_covers_the_classes():
    fast = benchmark_cases("fast")
    assert 6 <= len(fast) <= 8
    kinds = [c.kind for c in fast]
    assert "clean" in kinds and "out_of_library" in kinds and 4 <= kinds.count("single") <= 6
    assert len({c.damper for c in fast if c.kind == "single"}) >= 4


def test_unknown_subset_is_an_error():
    with pytest.raises(ValueError, match="subset"):
        benchmark_cases("everything")


@pytest.mark.slow
@pytest.mark.parametrize("case", benchmark_cases("fast"), ids=lambda c: c.name)
def test_fast_subset_is_diagnosed_right(case):
    # the same path as the benchmark: truth rig -> CSV -> read_measurement -> diagnose; an exception is a failure
    row = _bench().run_case(case, detectability=False)
    assert row["error"] is None, row["error"]
    assert row["correct"], (f"{case.name}: expected {case.expected} ({', '.join(sorted(case.accepted)) or '-'}), "
                            f"diagnose said {row['verdict']} {row['missing_effect'] or ''}; "
                            f"top of the ranking {row['ranking']}")
