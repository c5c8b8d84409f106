"""The benchmark catalogue (erdesign/simulation/truthrig/cases.py) as the benchmark's results were measured on it:
the seeds follow the order the cases are made in, and each case's answer and size follow from its mechanisms."""

import pytest

from erdesign.simulation.truthrig.cases import LIBRARY_MECHANISMS, OUT_OF_LIBRARY, benchmark_cases

# name -> (seed, expected, accepted, size, viscosity and yield-stress factors), as in the catalogue of 2026-11-25 that
# the diagnosis benchmark (benchmarks/bench_diagnosis_accuracy.py) was measured on: a change of seed order or of an
# answer shows here
PINNED = {
    "pair-seal_friction+fluid_inertia-makris-sine-1pct": (1091, "seal_friction", {"seal_friction", "fluid_inertia"}, "large", 1.2, 1.15),
    "outside-blowoff-makris-sine-1pct": (1142, "unexplained", set(), "large", 0.85, 1.1),
    "long_field_steps-lag20ms-mr_valve-doe_sine-1pct": (5001, "field_lag", {"field_lag"}, "", 0.9, 1.2),
    "band_limited_3khz-lag15ms-mr_valve_current-filtered_gaussian-1pct": (5008, "field_lag", {"field_lag"}, "moderate", 0.9, 1.2),
    "series_springs_mixed-gas+column-mr_valve-random-3pct": (5019, "gas_spring", {"gas_spring", "compressibility"}, "large", 1.15, 0.9),
    "artefacts-gap-mr_valve_current-sine-1pct": (5044, "field_lag", {"field_lag"}, "large", 1.05, 0.95),
    "fast-gas_spring-kamath_wereley-earthquake": (106, "gas_spring", {"gas_spring"}, "large", 0.85, 1.1),
}  # fmt: skip


@pytest.fixture(scope="module")
def cases():
    return {c.name: c for c in benchmark_cases("full") + benchmark_cases("fast")}


@pytest.mark.parametrize("name", PINNED)
def test_pinned_cases(cases, name):
    c = cases[name]
    assert (c.seed, c.expected, set(c.accepted), c.size, c.viscosity_factor, c.yield_stress_factor) == PINNED[name]


def test_every_answer_names_the_effects_of_the_hidden_mechanisms(cases):
    effect_of = {m: e for e, m in LIBRARY_MECHANISMS.items()}
    for c in cases.values():
        if not c.mechanisms:
            assert (c.expected, c.accepted) == ("nothing_missing", frozenset()), c.name
        elif set(c.mechanisms) & set(OUT_OF_LIBRARY):
            assert (c.expected, c.accepted) == ("unexplained", frozenset()), c.name
        else:
            assert c.accepted == {effect_of[m] for m in c.mechanisms} and c.expected in c.accepted, c.name


def test_every_named_excitation_has_a_motion():
    from erdesign.simulation.truthrig.cases import _MOTIONS, EXCITATIONS, ISSUE23_EXCITATIONS

    assert list(_MOTIONS) == [*EXCITATIONS, *ISSUE23_EXCITATIONS]
