r"""Tolerance studies: the spread of a damper's design point under manufacturing and material tolerances.

A study varies some values of a damper file (``geometry.gap``, ``fluid.viscosity``, ...: :data:`VARIABLES`), each
with its own distribution (:class:`Variation`: normal with the tolerance as one standard deviation, or uniform with
it as the half-width), and evaluates the quasi-steady design point of every sample at one piston velocity and
control with the kernel every other part of erdesign uses (:func:`erdesign.damper.quasi_steady.quasi_steady_state`
and :func:`~erdesign.damper.quasi_steady.damping_constant`, vectorised over the samples).  It gives

* the quantiles (1, 5, 50, 95, 99 %) of the outputs (:data:`OUTPUTS`), exact: every output of every sample is kept
  (float64; 32 bytes per sample for the four outputs, 320 MB for 1e7 samples) and :func:`numpy.quantile` (linear
  interpolation) is taken over them;
* first-order and total Sobol indices of each output for each input (Sobol 2001; the estimators of Saltelli et al.
  2010 as implemented by SALib, Herman and Usher 2017), with bootstrap 95 % confidence half-widths.

Reproducibility: the Monte-Carlo samples are drawn in chunks of :data:`CHUNK` samples, chunk ``k`` from its own
stream ``numpy.random.default_rng([seed, k])``, so the numbers do not depend on the executor
(:mod:`erdesign.executor`) or on the number of workers.  The Sobol design (a scrambled Sobol sequence, seeded) is
built in the calling process and evaluated on the executor in chunks too.

Non-physical draws (a gap <= 0, a rod as thick as the piston, ...: :func:`physical`) are rejected and drawn again
from the chunk's stream (so the distributions are truncated to the physical region); the study reports how many.

The field law is the file's: with a ``[coil]``, the yield stress at the current is that of the file's magnetic
circuit, so a varied gap changes the flow but not the gap's flux density (the circuit is not re-solved per sample).
See docs/tolerance.md for the method and how many samples give which confidence.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from ..damper.damper import Damper, exact_annulus_for
from ..damper.quasi_steady import damping_constant, quasi_steady_state
from ..errors import ErdesignError, did_you_mean
from ..limits import size_text
from ..executor import Executor, chunks, executor_for
from ..fluid.fluid import plastic_viscosity
from ..units import Q_, dimension_name, parse_quantity

__all__ = [
    "CHUNK",
    "HISTOGRAM_BINS",
    "OUTPUTS",
    "QUANTILES",
    "SAMPLE_FORMATS",
    "SOBOL_BASE_MAX",
    "VARIABLES",
    "ToleranceError",
    "ToleranceResult",
    "ToleranceStudy",
    "Variable",
    "Variation",
    "evaluate_samples",
    "parse_variation",
    "physical",
    "sobol_base_samples",
    "tolerance_study",
    "write_samples",
]

#: Samples per chunk: the unit of work and of random streams (changing it changes the numbers, not their law).
CHUNK = 65536
#: Quantiles reported, in percent (the JSON keys are these as text: "1", "5", ...).
QUANTILES = (1, 5, 50, 95, 99)
#: Outputs of every sample, SI: the keys of ``erdesign size --json`` they match.
OUTPUTS = ("force_N", "zero_field_force_N", "dynamic_range", "damping_constant_N_s_per_m")
#: Bins of the histograms a study keeps of each output.
HISTOGRAM_BINS = 60
#: A chunk may reject at most this fraction of its draws before the study is refused (tolerances far too wide).
MAX_REJECTED_FRACTION = 0.5
#: Most Monte-Carlo samples of one study: the outputs take 32 bytes a sample (540 MB at the limit), the kept inputs
#: more; 1e9 samples filled the memory until the system killed the process.  docs/tolerance.md says how many samples
#: give which confidence (far fewer).
MAX_SAMPLES = 2**24


class ToleranceError(ErdesignError):
    """A tolerance study cannot run as asked (a bad ``--vary``, tolerances that leave no physical damper)."""


class Variable(NamedTuple):
    """A value of the damper file a study may vary."""

    si_unit: str
    nominal: Callable[[Damper], float]
    """The damper's value, SI."""
    lower: float
    """Smallest physical value (SI)."""
    inclusive: bool
    """``lower`` itself is physical (a yield stress of 0), or not (a gap of 0)."""


def _geo(name: str) -> Callable[[Damper], float]:
    return lambda d: float(getattr(d.geometry, name))


def _fluid(name: str) -> Callable[[Damper], float]:
    return lambda d: float(getattr(d.fluid, name))


def _eta_ref(d: Damper) -> float:
    f = d.fluid
    return float(f.viscosity if f.viscosity_at_reference_field is None else f.viscosity_at_reference_field)


#: Key (as in the damper file, docs/file_formats.md) -> how to read it and its physical bound.  The yield stress
#: is varied as a factor on the fluid's whole law tau_y(E) (``fluid.yield_stress`` is the law's value at the
#: reference field); ``fluid.viscosity_at_reference_field`` of a fluid that has none is the zero-field viscosity.
VARIABLES: dict[str, Variable] = {
    "geometry.gap": Variable("m", _geo("gap"), 0.0, False),
    "geometry.duct_length": Variable("m", _geo("duct_length"), 0.0, False),
    "geometry.duct_mean_diameter": Variable("m", _geo("duct_mean_diameter"), 0.0, False),
    "geometry.piston_diameter": Variable("m", _geo("piston_diameter"), 0.0, False),
    "geometry.rod_diameter": Variable("m", _geo("rod_diameter"), 0.0, True),
    "fluid.viscosity": Variable("Pa*s", _fluid("viscosity"), 0.0, False),
    "fluid.viscosity_at_reference_field": Variable("Pa*s", _eta_ref, 0.0, False),
    "fluid.yield_stress": Variable("Pa", _fluid("yield_stress"), 0.0, True),
    "fluid.density": Variable("kg/m^3", _fluid("density"), 0.0, False),
    "fluid.seal_friction": Variable("N", lambda d: float(d.seal_friction), 0.0, True),
}


@dataclass(frozen=True)
class Variation:
    """One varied value: ``nominal`` (SI, the damper file's) and ``delta`` (SI: one standard deviation of a normal
    distribution, or the half-width of a uniform one)."""

    key: str
    nominal: float
    delta: float
    distribution: str = "normal"
    spec: str = ""
    """The ``--vary`` text it came from, for messages."""

    def ppf(self, u: np.ndarray) -> np.ndarray:
        """The value at cumulative probability ``u`` (the inverse CDF), untruncated."""
        if self.distribution == "uniform":
            return self.nominal + self.delta * (2.0 * u - 1.0)
        from scipy.special import ndtri

        return self.nominal + self.delta * ndtri(u)

    def draw(self, rng: np.random.Generator, n: int) -> np.ndarray:
        if self.distribution == "uniform":
            return rng.uniform(self.nominal - self.delta, self.nominal + self.delta, n)
        return rng.normal(self.nominal, self.delta, n)

    def describe(self) -> str:
        """``"geometry.gap = 0.8 mm +- 0.02 mm (sd)"``, in the unit that reads best."""
        from ..formatting import pick_unit

        si_unit = VARIABLES[self.key].si_unit
        unit = pick_unit(Q_(self.nominal or self.delta, si_unit), _KINDS[si_unit])
        nominal, delta = (Q_(x, si_unit).to(unit).magnitude for x in (self.nominal, self.delta))
        kind = "sd" if self.distribution == "normal" else "uniform half-width"
        shown = f"{Q_(1.0, unit).units:~P}"
        return f"{self.key} = {nominal:.6g} {shown} +- {delta:.4g} {shown} ({kind})"


#: The kind of unit (erdesign.formatting.UNIT_CHOICES) of each variable's SI unit, for display.
_KINDS = {"m": "length", "Pa*s": "viscosity", "Pa": "pressure", "kg/m^3": "density", "N": "force"}


_SPEC = re.compile(
    r"^\s*(?P<uniform>uniform:)?\s*(?P<key>[A-Za-z_.]+)\s*=\s*(?P<value>.*?)\s*(\+-|±|\+/-)"
    r"\s*(?P<delta>.+?)\s*$"
)


def parse_variation(spec: str, damper: Damper) -> Variation:
    """A :class:`Variation` from a ``--vary`` text: ``"KEY=VALUE +- DELTA"``, ``"KEY=+-P %"``, ``"KEY=VALUE +- P %"``,
    each optionally prefixed ``uniform:``.  VALUE, when given, must agree with the damper file (to 1e-6).

    >>> from erdesign import load_example
    >>> v = parse_variation("geometry.gap=0.8 mm +- 20 um", load_example("makris"))
    >>> v.nominal, round(v.delta, 9), v.distribution
    (0.0008, 2e-05, 'normal')
    >>> parse_variation("uniform:fluid.viscosity=+-10 %", load_example("makris")).delta
    0.7
    """
    where = f"--vary {spec!r}"
    m = _SPEC.match(spec or "")
    if m is None:
        raise ToleranceError(
            f'{where}: expected "KEY=VALUE +- DELTA" or "KEY=+-P %" (prefix "uniform:" for a '
            'uniform spread), e.g. "geometry.gap=0.8 mm +- 0.02 mm"'
        )
    key = m["key"]
    if key not in VARIABLES:
        raise ToleranceError(
            f"{where}: {key!r} is not a value a study can vary{did_you_mean(key, VARIABLES)}; keys: {', '.join(VARIABLES)}"
        )
    var = VARIABLES[key]
    if key == "geometry.duct_mean_diameter" and damper.geometry.configuration == "mixed":
        raise ToleranceError(f"{where}: a mixed damper's duct_mean_diameter is piston_diameter + gap; vary those")
    nominal = var.nominal(damper)
    unit_text = f"{Q_(1.0, var.si_unit).units:~P}"
    if m["value"]:
        value = _si(m["value"], var.si_unit, where, "VALUE")
        if not math.isclose(value, nominal, rel_tol=1e-6, abs_tol=0.0):
            given = Q_(m["value"]).units
            raise ToleranceError(
                f"{where}: VALUE {m['value']} disagrees with the damper file, which gives "
                f"{key} = {Q_(nominal, var.si_unit).to(given).magnitude:.6g} {given:~P}; give the "
                f'file\'s value or leave it out ("{key}=+-5 %")'
            )
    delta_text = m["delta"]
    pm = re.fullmatch(r"([-+0-9.eE]+)\s*%", delta_text)
    if pm:
        try:
            delta = abs(nominal) * float(pm[1]) / 100.0
        except ValueError:
            raise ToleranceError(f"{where}: cannot read the percentage {delta_text!r}") from None
        if nominal == 0:
            raise ToleranceError(
                f"{where}: {key} is 0 in the damper file, so a tolerance in % is 0; give it with "
                f'a unit, e.g. "{key}=+-1 {unit_text}"'
            )
    else:
        delta = _si(delta_text, var.si_unit, where, "DELTA")
    if not (math.isfinite(delta) and delta > 0):
        raise ToleranceError(f"{where}: the tolerance must be a positive amount, got {delta_text!r}")
    if key == "fluid.yield_stress" and nominal == 0:
        raise ToleranceError(
            f"{where}: the fluid's yield stress is 0; a tolerance on it scales the yield curve, which has none"
        )
    return Variation(key, nominal, float(delta), "uniform" if m["uniform"] else "normal", spec)


def _si(text: str, si_unit: str, where: str, part: str) -> float:
    """A quantity of the text in SI; a bare number is refused (a tolerance without its unit is ambiguous)."""
    try:
        q = parse_quantity(text, part)
    except ErdesignError as exc:
        raise ToleranceError(f"{where}: cannot read {part} {text!r}: {str(exc).removeprefix(part + ': ')}") from None
    if not hasattr(q, "units") or q.dimensionless:
        raise ToleranceError(
            f'{where}: {part} {text!r} has no unit; give one, e.g. "{text} '
            f'{Q_(1.0, si_unit).units:~P}"' + (", or a percentage" if part == "DELTA" else "")
        )
    try:
        value = float(q.to(si_unit).magnitude)
    except Exception:  # noqa: BLE001 - pint's DimensionalityError
        raise ToleranceError(
            f"{where}: {part} {text!r} is {dimension_name(q.dimensionality)}, expected "
            f"{dimension_name(Q_(1.0, si_unit).dimensionality)}"
        ) from None
    if not math.isfinite(value):
        raise ToleranceError(f"{where}: {part} {text!r} is not a finite number")
    return value


@dataclass(frozen=True)
class ToleranceStudy:
    """Everything a chunk of a study needs (picklable: it travels to the workers)."""

    damper: Damper
    velocity: float
    """[m/s]"""
    field: float
    """Control, SI."""
    variations: tuple[Variation, ...]
    seed: int = 0

    @property
    def keys(self) -> tuple[str, ...]:
        return tuple(v.key for v in self.variations)


def _values(study: ToleranceStudy, x: np.ndarray) -> dict[str, np.ndarray | float]:
    """Every variable's value per sample (columns of ``x`` for the varied ones, the damper's for the others)."""
    out: dict[str, Any] = {key: var.nominal(study.damper) for key, var in VARIABLES.items()}
    for j, v in enumerate(study.variations):
        out[v.key] = x[:, j]
    if study.damper.geometry.configuration == "mixed":  # d = Dp + h (docs/file_formats.md)
        out["geometry.duct_mean_diameter"] = out["geometry.piston_diameter"] + out["geometry.gap"]
    return out


def physical(study: ToleranceStudy, x: np.ndarray) -> np.ndarray:
    """True for the samples (rows of ``x``, one column per variation) that describe a damper that can exist:
    every value above its bound (:data:`VARIABLES`), a rod thinner than the piston, a gap thinner than its mean
    diameter."""
    ok = np.ones(x.shape[0], dtype=bool)
    for j, v in enumerate(study.variations):
        var = VARIABLES[v.key]
        ok &= (x[:, j] >= var.lower) if var.inclusive else (x[:, j] > var.lower)
    p = _values(study, x)
    ok &= np.asarray(p["geometry.rod_diameter"] < p["geometry.piston_diameter"])
    ok &= np.asarray(p["geometry.gap"] < p["geometry.duct_mean_diameter"])
    return np.broadcast_to(ok, (x.shape[0],))


def evaluate_samples(study: ToleranceStudy, x: np.ndarray) -> dict[str, np.ndarray]:
    """The outputs (:data:`OUTPUTS`) of the samples ``x`` (rows; one column per variation, SI), vectorised.

    The kernel of :meth:`Damper.size <erdesign.damper.Damper.size>`: the damper's state at the field and at zero
    field (:func:`~erdesign.damper.quasi_steady.quasi_steady_state`) and its damping constant
    (:func:`~erdesign.damper.quasi_steady.damping_constant`), with each sample's values in place of the file's.
    """
    d, p = study.damper, _values(study, np.asarray(x, dtype=float).reshape(len(x), -1))
    f = d.fluid
    ratio = float(f.yield_law.ratio(study.field, f.reference_field))
    tau_y = p["fluid.yield_stress"] * ratio
    eta0 = p["fluid.viscosity"]
    eta = plastic_viscosity(eta0, p["fluid.viscosity_at_reference_field"], ratio)
    g = d.geometry
    h, L, dm = p["geometry.gap"], p["geometry.duct_length"], p["geometry.duct_mean_diameter"]
    Dp, dr, rho, Fs = (
        p["geometry.piston_diameter"],
        p["geometry.rod_diameter"],
        p["fluid.density"],
        p["fluid.seal_friction"],
    )
    annulus = exact_annulus_for(g.configuration, d.flow_model, np.asarray(h) / np.asarray(dm))
    n = len(x)

    def state(tau, visc):
        s = quasi_steady_state(g.configuration, study.velocity, tau, visc, rho, Fs, h, L, dm, Dp, dr, g.ducts, annulus)
        return np.broadcast_to(np.asarray(s.force, dtype=float), (n,))

    force = state(tau_y, eta)
    zero = state(0.0, eta0)
    with np.errstate(divide="ignore", invalid="ignore"):
        dynamic_range = np.where(zero != 0, force / zero, np.nan)
    C = np.broadcast_to(
        np.asarray(damping_constant(g.configuration, eta0, rho, h, L, dm, Dp, dr, g.ducts, annulus), dtype=float), (n,)
    )
    return {
        "force_N": np.array(force),
        "zero_field_force_N": np.array(zero),
        "dynamic_range": dynamic_range,
        "damping_constant_N_s_per_m": np.array(C),
    }


class _Chunk(NamedTuple):
    inputs: np.ndarray
    outputs: dict[str, np.ndarray]
    rejected: int


def _monte_carlo_chunk(task: tuple[ToleranceStudy, int, int, bool]) -> _Chunk:
    """Samples ``size`` of chunk ``index``: drawn from the stream ``default_rng([seed, index])``, non-physical
    draws rejected and drawn again from the same stream."""
    study, index, size, keep_inputs = task
    rng = np.random.default_rng([study.seed, index])
    rows: list[np.ndarray] = []
    have = rejected = 0
    while have < size:
        need = size - have
        x = np.column_stack([v.draw(rng, need) for v in study.variations])
        ok = physical(study, x)
        bad = int(need - ok.sum())
        rejected += bad
        if rejected > MAX_REJECTED_FRACTION * size + 64:
            raise ToleranceError(_too_wide(study, x[~ok]))
        rows.append(x[ok])
        have += need - bad
    x = np.concatenate(rows)
    return _Chunk(x if keep_inputs else np.empty((0, x.shape[1])), evaluate_samples(study, x), rejected)


def _too_wide(study: ToleranceStudy, bad: np.ndarray) -> str:
    """The message for draws that give no damper: the --vary whose own bound most draws cross, else all of them
    (the draws cross a bound between two values: a rod as thick as the piston)."""
    culprits = [
        v for j, v in enumerate(study.variations) if len(bad) and np.mean(bad[:, j] <= VARIABLES[v.key].lower) > 0.5
    ]
    named = culprits[:1] or study.variations
    where = ", ".join(f"--vary {v.spec or v.key!r}" for v in named)
    return (
        f"{where}: more than {MAX_REJECTED_FRACTION:.0%} of the draws give no physical damper (a value at or "
        "below 0, a rod as thick as the piston, a gap as wide as its duct); the tolerances are far too wide for "
        "this damper"
    )


def _sobol_chunk(task: tuple[ToleranceStudy, np.ndarray]) -> dict[str, np.ndarray]:
    study, x = task
    return evaluate_samples(study, x)


#: Largest default base of the Sobol design: 2^14 gives indices to about +-0.02 (95 %), and SALib's bootstrap of
#: the confidence intervals grows faster than linearly beyond it (1.6 s at 2^14, 36 s at 2^17 for four outputs).
SOBOL_BASE_MAX = 2**14


def sobol_base_samples(samples: int, inputs: int) -> int:
    """Base samples N of the Sobol design for a study of ``samples``: the largest power of two with
    N (D + 2) <= samples (SALib's design without second-order indices has N (D + 2) rows), at least 16 and at most
    :data:`SOBOL_BASE_MAX`.

    >>> sobol_base_samples(20000, 3), sobol_base_samples(10**7, 3), sobol_base_samples(10, 2)
    (2048, 16384, 16)
    """
    return min(SOBOL_BASE_MAX, max(16, 2 ** math.floor(math.log2(max(1, samples // (inputs + 2))))))


@dataclass(frozen=True)
class ToleranceResult:
    """Result of :func:`tolerance_study`.

    ``samples`` holds the inputs (one column per variation, SI) and outputs of every Monte-Carlo sample when the
    study was asked to keep them (``keep_samples``), else None."""

    study: ToleranceStudy
    count: int
    rejected: int
    quantiles: dict[str, dict[str, float]]
    """output -> {"1", "5", "50", "95", "99"} -> value, SI."""
    mean: dict[str, float]
    std: dict[str, float]
    nominal: dict[str, float]
    """The outputs of the damper file's own values."""
    sensitivity: dict[str, dict[str, dict[str, float | None]]]
    """output -> input -> {"first", "total", "first_conf", "total_conf"}; None where the output does not vary."""
    sobol_base: int
    sobol_evaluations: int
    executor: str
    seconds: float
    histograms: dict[str, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict, repr=False)
    """output -> (bin edges, counts): :data:`HISTOGRAM_BINS` bins between the 0.1 and 99.9 % quantiles (the
    samples outside fall in the end bins), for the figures of a study too large to keep its samples."""
    samples: dict[str, np.ndarray] | None = field(default=None, repr=False)

    def as_json(self) -> dict:
        """The JSON object of ``erdesign tolerance --json`` (docs/cli.md)."""
        return {
            "samples": self.count,
            "rejected": self.rejected,
            "seed": self.study.seed,
            "velocity_m_per_s": self.study.velocity,
            "field": self.study.field,
            "vary": [
                {
                    "key": v.key,
                    "nominal": v.nominal,
                    "delta": v.delta,
                    "distribution": v.distribution,
                    "unit": VARIABLES[v.key].si_unit,
                }
                for v in self.study.variations
            ],
            "nominal": self.nominal,
            "mean": self.mean,
            "std": self.std,
            "quantiles": self.quantiles,
            "sensitivity": self.sensitivity,
            "sobol_base_samples": self.sobol_base,
            "sobol_evaluations": self.sobol_evaluations,
            "executor": self.executor,
            "seconds": self.seconds,
        }


def tolerance_study(
    damper: Damper,
    variations,
    *,
    velocity: float,
    field: float = 0.0,
    samples: int = 10000,
    seed: int = 0,
    sobol_base: int | None = None,
    sensitivity: bool = True,
    keep_samples: bool = False,
    executor: Executor | Any | None = None,
    jobs: int | None = None,
    scheduler: Any = None,
    progress: Callable[[int, int], None] | None = None,
) -> ToleranceResult:
    """Monte-Carlo quantiles and Sobol indices of the design point of ``damper`` under tolerances.

    Parameters
    ----------
    damper : Damper
    variations : sequence of Variation or str
        The varied values (``--vary`` texts are parsed with :func:`parse_variation`); each key at most once.
    velocity : float
        Piston velocity, [m/s], > 0.
    field : float
        Control, SI (V/m, A/m, T, A or V as the fluid's), default 0.
    samples : int
        Monte-Carlo samples, >= 1.
    seed : int
        Seed of every random stream: same seed, same numbers on any executor.
    sobol_base : int, optional
        Base samples N of the Sobol design (a power of two); default :func:`sobol_base_samples`.
    sensitivity : bool
        Compute the Sobol indices (N (D + 2) more evaluations).
    keep_samples : bool
        Keep the inputs and outputs of every sample in the result (for :func:`write_samples`).
    executor, jobs, scheduler
        Where the chunks run (:func:`erdesign.executor.executor_for`); default serial.
    progress : callable, optional
        ``progress(done, total)`` after each chunk.

    Returns
    -------
    ToleranceResult

    Examples
    --------
    >>> from erdesign import load_example
    >>> r = tolerance_study(load_example("makris"), ["geometry.gap=+-2.5 %"], velocity=0.0254, field=3e6,
    ...                     samples=20000, seed=1)
    >>> round(r.quantiles["force_N"]["50"] / r.nominal["force_N"], 2)
    1.0
    >>> round(r.sensitivity["force_N"]["geometry.gap"]["first"], 1)
    1.0
    """
    import time

    t0 = time.perf_counter()
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or samples < 1:
        raise ToleranceError(f"samples: must be a whole number >= 1, got {samples!r}")
    if samples > MAX_SAMPLES:
        raise ToleranceError(
            f"samples: {samples:,} is more than the {MAX_SAMPLES:,} one study takes (its outputs alone would take "
            f"{size_text(32 * int(samples))}); docs/tolerance.md says how many samples give which confidence"
        )
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ToleranceError(f"seed: must be a whole number >= 0, got {seed!r}")
    if isinstance(velocity, bool) or not (
        isinstance(velocity, (int, float)) and math.isfinite(velocity) and velocity > 0
    ):
        raise ToleranceError(f"velocity: must be a positive speed, got {velocity!r} m/s")
    variations = tuple(v if isinstance(v, Variation) else parse_variation(v, damper) for v in variations)
    if not variations:
        raise ToleranceError('--vary: give at least one tolerance, e.g. --vary "geometry.gap=+-2.5 %"')
    keys = [v.key for v in variations]
    twice = sorted({k for k in keys if keys.count(k) > 1})
    if twice:
        raise ToleranceError(f"--vary: {twice[0]} is varied twice; give each key once")
    study = ToleranceStudy(damper, float(velocity), float(field), variations, int(seed))
    D = len(variations)
    pieces = chunks(int(samples), CHUNK)
    base = sobol_base if sobol_base is not None else sobol_base_samples(int(samples), D)
    sobol_x = _sobol_design(study, base) if sensitivity else None
    sobol_pieces = chunks(len(sobol_x), CHUNK) if sobol_x is not None else []
    total = len(pieces) + len(sobol_pieces)
    outputs = {k: np.empty(int(samples)) for k in OUTPUTS}
    inputs = np.empty((int(samples), D)) if keep_samples else None
    rejected = 0
    owned = not isinstance(executor, Executor)
    ex = executor_for(executor, jobs=jobs, scheduler=scheduler)
    try:
        done = 0
        tasks = [(study, k, b - a, keep_samples) for k, (a, b) in enumerate(pieces)]
        for k, chunk in ex.imap(_monte_carlo_chunk, tasks):
            a, b = pieces[k]
            for key in OUTPUTS:
                outputs[key][a:b] = chunk.outputs[key]
            if inputs is not None:
                inputs[a:b] = chunk.inputs
            rejected += chunk.rejected
            done += 1
            if progress is not None:
                progress(done, total)
        sobol_y = None
        if sobol_x is not None:
            sobol_y = {key: np.empty(len(sobol_x)) for key in OUTPUTS}
            for k, y in ex.imap(_sobol_chunk, [(study, sobol_x[a:b]) for a, b in sobol_pieces]):
                a, b = sobol_pieces[k]
                for key in OUTPUTS:
                    sobol_y[key][a:b] = y[key]
                done += 1
                if progress is not None:
                    progress(done, total)
        description = ex.description
    finally:
        if owned:
            ex.close()
    quantiles = {
        key: {str(q): float(v) for q, v in zip(QUANTILES, np.quantile(outputs[key], [q / 100 for q in QUANTILES]))}
        for key in OUTPUTS
    }
    nominal_y = evaluate_samples(study, np.array([[v.nominal for v in variations]]))
    histograms = {key: _histogram(outputs[key]) for key in OUTPUTS}
    sens = _sobol_indices(study, base, sobol_y) if sobol_y is not None else {}
    kept = None
    if keep_samples:
        kept = {v.key: inputs[:, j] for j, v in enumerate(variations)} | outputs
    return ToleranceResult(
        study=study,
        count=int(samples),
        rejected=rejected,
        quantiles=quantiles,
        mean={k: float(np.mean(outputs[k])) for k in OUTPUTS},
        std={k: float(np.std(outputs[k])) for k in OUTPUTS},
        nominal={k: float(nominal_y[k][0]) for k in OUTPUTS},
        sensitivity=sens,
        sobol_base=base,
        sobol_evaluations=0 if sobol_x is None else len(sobol_x),
        executor=description,
        seconds=time.perf_counter() - t0,
        histograms=histograms,
        samples=kept,
    )


def _histogram(values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    finite = values[np.isfinite(values)]
    if finite.size == 0:
        return np.array([0.0, 1.0]), np.array([0])
    lo, hi = np.quantile(finite, [0.001, 0.999])
    if not hi > lo:
        lo, hi = lo - 0.5 * max(abs(lo), 1e-12), hi + 0.5 * max(abs(hi), 1e-12)
    counts, edges = np.histogram(np.clip(finite, lo, hi), bins=HISTOGRAM_BINS, range=(lo, hi))
    return edges, counts


def _problem(study: ToleranceStudy) -> dict:
    return {"num_vars": len(study.variations), "names": list(study.keys), "bounds": [[0.0, 1.0]] * len(study.keys)}


def _sobol_design(study: ToleranceStudy, base: int) -> np.ndarray:
    """SALib's Saltelli design (scrambled Sobol sequence, seeded; no second-order indices) on the unit cube, taken
    through each input's inverse CDF truncated to its physical range, so that the design's inputs follow the
    Monte-Carlo distributions.  A design point that is still not physical (a rod as thick as the piston) is an
    error: it cannot be left out of the estimator."""
    import warnings

    from SALib.sample import sobol as sobol_sample

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # SALib's note on N not a power of two: the caller's choice
        u = sobol_sample.sample(_problem(study), int(base), calc_second_order=False, seed=study.seed)
    x = np.empty_like(u)
    for j, v in enumerate(study.variations):
        var = VARIABLES[v.key]
        lo = _cdf(v, var.lower)  # mass below the physical bound, rejected by the Monte Carlo
        x[:, j] = v.ppf(lo + (1.0 - lo) * u[:, j])
        if not var.inclusive:
            x[:, j] = np.maximum(x[:, j], np.nextafter(var.lower, np.inf))
    ok = physical(study, x)
    if not np.all(ok):
        raise ToleranceError(
            _too_wide(study, x[~ok]).replace(
                f"more than {MAX_REJECTED_FRACTION:.0%} of the draws", "some points of the Sobol design"
            )
        )
    return x


def _cdf(v: Variation, value: float) -> float:
    if v.distribution == "uniform":
        return float(np.clip((value - (v.nominal - v.delta)) / (2 * v.delta), 0.0, 1.0))
    from scipy.special import ndtr

    return float(ndtr((value - v.nominal) / v.delta))


def _sobol_indices(study: ToleranceStudy, base: int, y: dict[str, np.ndarray]) -> dict:
    """First-order and total indices (SALib ``analyze.sobol``; Saltelli et al. 2010 estimators, 95 % bootstrap
    confidence half-widths, seeded) of every output; None for an output that does not vary."""
    import warnings

    from SALib.analyze import sobol as sobol_analyze

    out: dict = {}
    for key in OUTPUTS:
        values = y[key]
        if not np.all(np.isfinite(values)) or np.ptp(values) <= 1e-12 * max(1.0, float(np.max(np.abs(values)))):
            out[key] = {
                name: {"first": None, "total": None, "first_conf": None, "total_conf": None} for name in study.keys
            }
            continue
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            s = sobol_analyze.analyze(_problem(study), values, calc_second_order=False, seed=study.seed)
        out[key] = {
            name: {
                "first": _num(s["S1"][j]),
                "total": _num(s["ST"][j]),
                "first_conf": _num(s["S1_conf"][j]),
                "total_conf": _num(s["ST_conf"][j]),
            }
            for j, name in enumerate(study.keys)
        }
    return out


def _num(x) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None


SAMPLE_FORMATS = {".parquet": "parquet", ".csv": "csv"}


def write_samples(
    result: ToleranceResult, path: str | Path, fmt: str, *, overwrite: bool = False, option: str = "path"
) -> None:
    """Write the samples of a study kept with ``keep_samples`` (one row per sample: the varied inputs, then the
    outputs, SI; column names carry the unit), whole or not at all; an existing ``path`` only with ``overwrite``
    (:mod:`erdesign.output`)."""
    if result.samples is None:
        raise ToleranceError("write_samples: the study did not keep its samples (keep_samples=True)")
    import pandas as pd

    units = {v.key: VARIABLES[v.key].si_unit for v in result.study.variations}
    frame = pd.DataFrame({(f"{k} [{units[k]}]" if k in units else k): v for k, v in result.samples.items()})
    from ..output import atomic_output

    with atomic_output(path, overwrite=overwrite, option=option) as tmp:
        if fmt == "parquet":
            frame.to_parquet(tmp, index=False)
        else:
            frame.to_csv(tmp, index=False)
