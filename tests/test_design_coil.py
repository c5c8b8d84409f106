"""Design with the coil (``[design.coil]``, issue 16): the returned designs meet the force at the stated current
when re-evaluated independently through a damper file and its magnetic circuit; conflicts and file errors."""

import numpy as np
import pytest

from erdesign.damper.files import damper_from_dict
from erdesign.design import design, load_example_requirements, requirements_from_dict
from erdesign.design.requirements import RequirementsError
from erdesign.magnetics import circuit_from_damper_dict, load_magnetic_circuit
from erdesign.magnetics.circuit import HeadBatch, MagneticCircuit


@pytest.fixture(scope="module")
def req():
    return load_example_requirements("mr_coil_requirements").with_search(samples=1024, designs=3)


@pytest.fixture(scope="module")
def result(req):
    return design(req)


def damper_dict(rec):
    """The damper file of a returned design: its [geometry] and [coil] tables as printed, the fluid by name."""
    return {
        "name": "designed",
        "geometry": rec["geometry"],
        "coil": rec["coil"],
        "fluid": {"material": "lord-mrf-132dg", "reference_field": "2 A", "seal_friction": "40 N"},
    }


def test_designs_meet_the_force_at_the_current_through_the_circuit(result):
    assert result.feasible and result.conflicts == []
    for rec in result.designs:
        d = damper_from_dict(damper_dict(rec))
        r = d.size(velocity="0.1 m/s", field="2 A")
        # independent path: the scalar head of the damper file, its root find, the coil law and Damper.size
        assert r.force.m_as("N") >= 2000.0
        assert r.force.m_as("N") == pytest.approx(rec["force_N"], rel=1e-4)
        assert r.dynamic_range >= 5.0
        c = circuit_from_damper_dict(damper_dict(rec)).at("2 A")
        m, p = rec["magnetics"], rec["points"][0]
        assert c.coil_resistance.m_as("ohm") == pytest.approx(m["coil_resistance_ohm"], rel=1e-12)
        assert c.power.m_as("W") == pytest.approx(m["power_W"], rel=1e-12)
        # batch regula falsi and the scalar bracketed root agree to their tolerances
        assert c.time_constant.m_as("s") == pytest.approx(m["time_constant_s"], rel=1e-8)
        assert c.gap_flux_density.m_as("T") == pytest.approx(p["gap_flux_density_T"], rel=1e-8)
        assert c.voltage.m_as("V") <= 12.0 and not c.saturated
        assert rec["coil"]["supply_voltage"] == "12 V" and isinstance(rec["coil"]["turns"], int)


def test_min_coil_power_ranks_by_power(result):
    powers = [rec["magnetics"]["power_W"] for rec in result.designs]
    assert powers == sorted(powers)


def test_batch_of_heads_equals_one_head_at_a_time():
    one = load_magnetic_circuit("erdesign/examples/mr_coil.toml")
    h = one.head
    rng = np.random.default_rng(3)
    k = 6
    scale = {
        "gap": rng.uniform(0.6, 1.4, k),
        "pole_length": rng.uniform(0.6, 1.4, k),
        "turns": rng.integers(100, 500, k) / h.turns,
        "core_radius": rng.uniform(0.7, 1.1, k),
    }
    heads = [
        dict(
            core_radius=h.core_radius * scale["core_radius"][i],
            pole_radius=h.pole_radius,
            gap=h.gap * scale["gap"][i],
            housing_outer_radius=h.housing_outer_radius,
            pole_length=h.pole_length * scale["pole_length"][i],
            coil_length=h.coil_length,
            turns=round(h.turns * scale["turns"][i]),
            wire_diameter=h.wire_diameter,
        )
        for i in range(k)
    ]
    batch = MagneticCircuit(
        HeadBatch(**{key: np.array([hd[key] for hd in heads], dtype=float) for key in heads[0]}),
        one.steel,
        one.fluid,
        one.yield_law,
    )
    I = np.linspace(0.3, 4.0, k)
    st = batch.state(I)
    for i, hd in enumerate(heads):
        from erdesign.magnetics.circuit import PistonHead

        single = MagneticCircuit(PistonHead(**hd), one.steel, one.fluid, one.yield_law).state(I[i])
        assert st.gap_field[i] == pytest.approx(float(single.gap_field[0]), rel=1e-9)
        assert st.flux_linkage[i] == pytest.approx(float(single.flux_linkage[0]), rel=1e-9)


def _coil_requirements(**coil_changes):
    data = {
        "fluid": {"material": "lord-mrf-132dg", "seal_friction": "40 N"},
        "design": {
            "configuration": "mixed",
            "objective": "min_coil_power",
            "point": [{"velocity": "0.1 m/s", "field": "2 A", "min_force": "2 kN"}],
            "bounds": {
                "gap": ["0.5 mm", "1.5 mm"],
                "duct_length": ["20 mm", "60 mm"],
                "piston_diameter": ["25 mm", "50 mm"],
                "rod_diameter": "12 mm",
            },
            "coil": {
                "turns": [50, 800],
                "wire_diameter": ["0.2 mm", "1.0 mm"],
                "core_diameter": ["10 mm", "35 mm"],
                "pole_length": ["3 mm", "15 mm"],
                "housing_outer_diameter": ["35 mm", "60 mm"],
                "supply_voltage": "12 V",
            },
            "search": {"samples": 512, "designs": 2, "refine": False},
        },
    }
    data["design"]["coil"].update(coil_changes)
    return data


def test_a_supply_too_weak_is_a_conflict_that_names_it():
    r = design(requirements_from_dict(_coil_requirements(supply_voltage="0.01 V")))
    assert not r.feasible
    assert any("coil.supply_voltage (point 1)" in c for c in r.conflicts)


def test_saturation_is_a_conflict_unless_allowed():
    # a thin core (4 mm) saturates long before the gap carries the flux 2 kN needs
    data = _coil_requirements(core_diameter="4 mm", turns=[400, 800])
    r = design(requirements_from_dict(data))
    assert not r.feasible and any("coil.saturation" in c for c in r.conflicts)


@pytest.mark.parametrize(
    "change, message",
    [
        (lambda d: d["design"].pop("coil"), "design.objective: 'min_coil_power' needs a [design.coil] table"),
        (lambda d: d["fluid"].update(yield_stress="40 kPa"), "fluid.yield_stress: not allowed with [design.coil]"),
        (lambda d: d["design"]["coil"].update(turns=[50.5, 800]), "design.coil.turns: expected [low, high] whole"),
        (lambda d: d["design"]["coil"].update(colour="red"), "design.coil.colour: unknown key"),
        (lambda d: d["design"]["coil"].pop("pole_length"), "design.coil.pole_length: missing"),
        (lambda d: d["fluid"].update(material="makris-zeolite-silicone"), "fluid.material:"),
    ],
)
def test_requirement_errors_name_the_field(change, message):
    data = _coil_requirements()
    change(data)
    with pytest.raises(RequirementsError, match=message.replace("[", r"\[").replace("(", r"\(")):
        requirements_from_dict(data)
