"""Design synthesis: from requirements to ranked damper geometries, trade-offs and conflicts (``erdesign design``).

One module per idea:

* :mod:`~erdesign.design.requirements` - the requirements file (TOML) and its checks;
* :mod:`~erdesign.design.envelope` - outer diameter, body length and fluid volumes from the geometry;
* :mod:`~erdesign.design.evaluate` - vectorised figures, non-dimensional groups and constraint margins of
  candidate geometries, straight from the flow kernels;
* :mod:`~erdesign.design.sampling` - Sobol' / Latin-hypercube candidates over the bounds, chunk by chunk;
* :mod:`~erdesign.design.pareto` - vectorised non-dominated filter;
* :mod:`~erdesign.design.scaling` - the active-volume law of the valve damper (a lower bound the search must reach);
* :mod:`~erdesign.design.search` - the workflow: chunked sampling, SLSQP refinement, ranking, conflicts;
* :mod:`~erdesign.design.result` - design records, JSON and CSV.

Example
-------
>>> from erdesign.design import design, load_example_requirements
>>> req = load_example_requirements("makris_requirements").with_search(samples=4096)
>>> result = design(req)
>>> result.feasible, sorted(result.designs[0]["geometry"])[:3]
(True, ['configuration', 'duct_length', 'duct_mean_diameter'])
"""

from .evaluate import FIGURES, OBJECTIVES, CandidateFigures, constraints_for, evaluate_candidates
from .pareto import pareto_mask
from .requirements import (
    DesignPoint,
    Envelope,
    Limits,
    Requirements,
    RequirementsError,
    SearchSettings,
    example_requirements_names,
    load_example_requirements,
    read_requirements,
    requirements_from_dict,
)
from .result import DesignResult
from .scaling import plug_fraction_at_dynamic_range, valve_minimum_active_volume
from .search import design, sample_designs, sweep

__all__ = [
    "design",
    "sample_designs",
    "sweep",
    "read_requirements",
    "requirements_from_dict",
    "load_example_requirements",
    "example_requirements_names",
    "Requirements",
    "RequirementsError",
    "DesignPoint",
    "Limits",
    "Envelope",
    "SearchSettings",
    "DesignResult",
    "CandidateFigures",
    "evaluate_candidates",
    "constraints_for",
    "pareto_mask",
    "plug_fraction_at_dynamic_range",
    "valve_minimum_active_volume",
    "FIGURES",
    "OBJECTIVES",
]
