r"""Design synthesis: sweep the design space in chunks, refine the best designs, rank them, explain infeasibility.

:func:`design` is the workflow behind ``erdesign design``:

1. **Sweep.**  Candidate geometries fill the bounds (:mod:`~erdesign.design.sampling`) and are evaluated chunk by
   chunk with :func:`~erdesign.design.evaluate.evaluate_candidates`; only running summaries are kept between
   chunks (the best feasible designs, the Pareto front, the designs nearest to feasibility, and counts of which
   constraints the candidates violate), so memory is proportional to a chunk, not to the sweep.  The chunks are
   the tasks of an executor (``jobs=``, ``scheduler=``): each worker makes its chunk from the seed and the chunk
   index and returns its summary, and the summaries are merged in chunk order, so that the result is the same on
   any executor.
2. **Refine.**  From the best feasible samples, :func:`scipy.optimize.minimize` (SLSQP) improves the objective in
   the logarithms of the free continuous variables (the number of ducts stays fixed), subject to every constraint
   margin being at least :data:`SAFETY` and to the bounds.  Gradients are forward differences computed in one
   vectorised call of the evaluator.
3. **Round and re-check.**  Each design is rounded to a manufacturing grid (``gap_tolerance``, default 0.01 mm,
   and ``length_tolerance``, default 0.1 mm, of ``[design.search]``): the nearest grid point if it meets every
   constraint, else the best of the neighbouring grid points (each dimension rounded down or up) that does.  It is
   written as a damper-file ``[geometry]`` table with the decimals of the grid and evaluated again from those
   strings, so the figures reported are those of the geometry printed, and a design is returned only if that
   geometry meets every constraint and the bounds.  (With a tolerance of 0: six significant figures, more if
   needed.)
4. **Rank.**  By the objective; designs whose objective lies within :data:`TIE` of each other are ranked by the
   secondary objective (:data:`SECONDARY`, or ``secondary`` of ``[design.search]``), so that designs equal to the
   figures shown are not ordered by noise.
5. **Explain.**  With no feasible sample, the designs with the smallest sum of squared relative violations are
   refined the same way (minimising that sum), and the conflicts are written out: what the nearest design misses
   and by how much, which constraints every sample violates, and which constraints, relaxed alone or in pairs,
   would admit sampled designs.

:func:`sample_designs` evaluates a whole sample at once and returns the arrays, for plots and studies (it was
``sweep``, a deprecated alias now: "sweep" also named the force-velocity curves and a motion).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.optimize import minimize

from .._deprecated import renamed
from ..executor import Executor, executor_for
from ..geometry import mixed_mean_diameter
from .evaluate import FIGURES, OBJECTIVES, CandidateFigures, Constraint, constraints_for, evaluate_candidates
from .pareto import pareto_mask
from .requirements import COIL_VARIABLES, VARIABLES, Requirements
from .result import DesignResult, design_record
from .sampling import candidate_chunk, candidate_chunks, chunk_count

__all__ = [
    "design",
    "sample_designs",
    "sweep",
    "SAFETY",
    "PARETO_LIMIT",
    "FRONT_STORE",
    "SECONDARY",
    "TIE",
    "secondary_objective",
]

#: The objective that breaks ties of each objective: a compact damper first, then a small fluid volume.
SECONDARY = {
    "min_fluid_volume": "min_outer_diameter",
    "max_dynamic_range": "min_fluid_volume",
    "min_zero_field_force": "min_fluid_volume",
    "min_total_fluid_volume": "min_outer_diameter",
    "min_outer_diameter": "min_length",
    "min_length": "min_outer_diameter",
    "min_coil_power": "min_time_constant",
    "min_time_constant": "min_coil_power",
}
#: Designs whose objective differs by less than this (relative) tie: the secondary objective ranks them.  The
#: figures are printed to four significant figures, so a difference below 0.1 % is not one a reader can see.
TIE = 1e-3


def secondary_objective(req: Requirements) -> str:
    """The objective that breaks ties: ``[design.search] secondary`` or :data:`SECONDARY` of the objective."""
    return req.search.secondary or SECONDARY[req.objective]


#: Margin every refined design keeps on each constraint (relative): 1e-4, so that rounding the geometry to six
#: significant figures (a relative change of at most 5e-6 in each dimension, up to about 4e-5 in a force) cannot
#: push a design over a limit.
SAFETY = 1e-4

#: Largest number of Pareto designs reported (thinned evenly along the first figure beyond it).
PARETO_LIMIT = 100

#: Largest number of Pareto designs kept between chunks.  Beyond it the stored front is thinned to one design per
#: cell of a logarithmic grid of its figures (cells of 0.1 %, doubled until the front fits): an epsilon-Pareto
#: archive, so that memory stays bounded even when every feasible design is non-dominated.
FRONT_STORE = 8192

_KEEP_FACTOR = 4  # keep this many times ``designs`` best samples as refinement starts
_NEAREST = 4  # samples kept as starts for the nearest infeasible design
_MAX_STARTS = 8  # SLSQP runs at most (fewer for mixed, whose evaluation is slower)


def sample_designs(req: Requirements, samples: int | None = None, seed: int | None = None) -> CandidateFigures:
    """Evaluate ``samples`` candidate geometries of ``req`` at once and return every figure as arrays.

    Memory grows with ``samples`` (about 40 (P + C) + 100 bytes per candidate for P design points and C
    constraints); :func:`design` uses chunks instead.

    Examples
    --------
    >>> from erdesign.design import load_example_requirements
    >>> s = sample_designs(load_example_requirements("makris_requirements"), samples=4096)
    >>> len(s), s.force.shape, bool(s.feasible.any())
    (4096, (1, 4096), True)
    """
    n = req.search.samples if samples is None else samples
    (x,) = list(candidate_chunks(req, samples=n, chunk=max(n, 1024), seed=seed))
    return _evaluate(req, x)


sweep = renamed(sample_designs, "erdesign.design.search.sweep")


def _evaluate(req: Requirements, x: dict, constraints=None) -> CandidateFigures:
    coil = {k: x[k] for k in COIL_VARIABLES} if req.coil is not None else None
    return evaluate_candidates(
        req,
        x["gap"],
        x["duct_length"],
        x["duct_mean_diameter"],
        x["piston_diameter"],
        x["rod_diameter"],
        x["ducts"],
        constraints=constraints,
        coil=coil,
    )


# ------------------------------------------------------------------------------------------- running summaries
def _stack(fig: CandidateFigures, index=slice(None), variables=VARIABLES) -> np.ndarray:
    """(N, k) array of the variables (rows ``index``) in the order of ``variables`` (mixed: the derived d)."""
    return np.column_stack([getattr(fig, k)[index] for k in variables])


def _unstack(X: np.ndarray, req: Requirements) -> dict:
    x = {k: X[:, j] for j, k in enumerate(req.variables)}
    if req.configuration == "mixed":
        x["duct_mean_diameter"] = None
    return x


def _objective_key(fig: CandidateFigures, objective: str) -> np.ndarray:
    name = OBJECTIVES[objective]
    value = fig.figure(name)
    return value if FIGURES[name].better == "min" else -value


def _violation(margins: np.ndarray) -> np.ndarray:
    """Sum of squared relative violations, per candidate (NaN margins: invalid geometry, infinite)."""
    v = np.sum(np.minimum(margins, 0.0) ** 2, axis=0)
    return np.where(np.isnan(v), np.inf, v)


@dataclass
class _Summary:
    """What the sweep keeps of the candidates seen: of one chunk (:meth:`of_chunk`, on a worker), or of many
    (:meth:`merge`, in the caller).

    Merging the summaries of the chunks in chunk order gives the same summary whatever ran the chunks: the counts
    add, the best designs are the ``keep`` smallest objective keys of the union, the front is the Pareto set of the
    union and the nearest designs the smallest violations of the union, ties always going to the earlier candidate
    (the rows of each summary stay in the order of the candidates).  The merge is associative as long as the
    stored front fits :data:`FRONT_STORE`; beyond it the front is thinned after each merge, so the order of the
    merges matters and the sweep always merges chunk after chunk.
    """

    n_constraints: int
    keep: int
    variables: tuple = VARIABLES
    evaluated: int = 0
    valid: int = 0
    feasible: int = 0
    best_X: np.ndarray = field(default_factory=lambda: np.empty((0, 6)))
    best_key: np.ndarray = field(default_factory=lambda: np.empty(0))
    front_X: np.ndarray = field(default_factory=lambda: np.empty((0, 6)))
    front_Y: np.ndarray = field(default_factory=lambda: np.empty((0, 0)))
    near_X: np.ndarray = field(default_factory=lambda: np.empty((0, 6)))
    near_v: np.ndarray = field(default_factory=lambda: np.empty(0))
    """Nearest designs and their violations: kept only while no candidate is feasible (they explain an infeasible
    search)."""
    violated: np.ndarray = field(init=False)
    """Per constraint: valid candidates that violate it."""
    single: np.ndarray = field(init=False)
    """Per constraint: valid candidates that violate it and nothing else."""
    pair: np.ndarray = field(init=False)
    """[i, j], i < j: valid candidates that violate exactly constraints i and j."""

    def __post_init__(self) -> None:
        k = len(self.variables)
        self.best_X, self.front_X, self.near_X = np.empty((0, k)), np.empty((0, k)), np.empty((0, k))
        c = self.n_constraints
        self.violated = np.zeros(c, dtype=np.int64)
        self.single = np.zeros(c, dtype=np.int64)
        self.pair = np.zeros((c, c), dtype=np.int64)

    @classmethod
    def of_chunk(
        cls, fig: CandidateFigures, objective: str, pareto: tuple[str, ...], keep: int, variables: tuple
    ) -> _Summary:
        """The summary of the candidates of one chunk (its whole Pareto front: the merge thins it)."""
        self = cls(fig.margins.shape[0], keep, variables)
        self.evaluated = len(fig)
        valid = fig.valid
        self.valid = int(np.count_nonzero(valid))
        margins = fig.margins
        broken = margins < 0.0  # NaN (invalid) compares False
        feasible = valid & ~np.any(broken, axis=0)
        self.feasible = int(np.count_nonzero(feasible))
        if self.feasible:
            idx = np.flatnonzero(feasible)
            key = _objective_key(fig, objective)[idx]
            best = _smallest(key, keep)
            self.best_X, self.best_key = _stack(fig, idx[best], variables), key[best]
            Y = np.column_stack([fig.figure(name)[idx] for name in pareto])
            on = pareto_mask(Y, [FIGURES[name].better == "max" for name in pareto])
            self.front_X, self.front_Y = _stack(fig, idx[on], variables), Y[on]
        else:
            v = _violation(margins)
            few = _smallest(v, _NEAREST)
            self.near_X, self.near_v = _stack(fig, few, variables), v[few]
        nv = np.count_nonzero(broken, axis=0)
        self.violated += np.count_nonzero(broken & valid, axis=1)
        one = valid & (nv == 1)
        if one.any():
            self.single += np.bincount(np.argmax(broken[:, one], axis=0), minlength=self.n_constraints)
        two = valid & (nv == 2)
        if two.any():
            b = broken[:, two]
            first, last = np.argmax(b, axis=0), b.shape[0] - 1 - np.argmax(b[::-1], axis=0)
            np.add.at(self.pair, (first, last), 1)
        return self

    def merge(self, later: _Summary, pareto: tuple[str, ...]) -> None:
        """Adds the summary of ``later`` candidates (all after those of this one) to this one."""
        self.evaluated += later.evaluated
        self.valid += later.valid
        self.feasible += later.feasible
        for name in ("violated", "single", "pair"):
            setattr(self, name, getattr(self, name) + getattr(later, name))
        if later.best_key.size:
            X, key = np.vstack([self.best_X, later.best_X]), np.concatenate([self.best_key, later.best_key])
            best = _smallest(key, self.keep)
            self.best_X, self.best_key = X[best], key[best]
        if len(later.front_X):
            X = np.vstack([self.front_X, later.front_X])
            Y = np.vstack([self.front_Y.reshape(-1, len(pareto)), later.front_Y])
            on = pareto_mask(Y, [FIGURES[name].better == "max" for name in pareto])
            self.front_X, self.front_Y = _thin(X[on], Y[on], FRONT_STORE)
        if self.feasible:
            self.near_X, self.near_v = self.near_X[:0], self.near_v[:0]
        else:
            X, v = np.vstack([self.near_X, later.near_X]), np.concatenate([self.near_v, later.near_v])
            near = _smallest(v, _NEAREST)
            self.near_X, self.near_v = X[near], v[near]


def _chunk_summary(req: Requirements, keep: int, index: int) -> _Summary:
    """Makes chunk ``index`` of the sweep, evaluates it and summarises it: one task of the executor."""
    x = candidate_chunk(req, index)
    fig = _evaluate(req, x, constraints_for(req))
    return _Summary.of_chunk(fig, req.objective, req.search.pareto, keep, req.variables)


def _thin(X: np.ndarray, Y: np.ndarray, limit: int) -> tuple[np.ndarray, np.ndarray]:
    """At most ``limit`` rows: one per cell of a logarithmic grid of the figures, coarsened until they fit."""
    eps = 1e-3
    logs = np.log(np.abs(Y) + 1e-300)
    while len(X) > limit:
        _, first = np.unique(np.floor(logs / eps).astype(np.int64), axis=0, return_index=True)
        first.sort()
        X, Y, logs = X[first], Y[first], logs[first]
        eps *= 2.0
    return X, Y


def _smallest(key: np.ndarray, k: int) -> np.ndarray:
    """Indices of the ``k`` smallest keys, by key and ties by position (NaN last): the same candidates whatever
    groups the keys were split into and merged from, when each group keeps its rows in order."""
    if key.size > k:
        kth = np.partition(key, k - 1)[k - 1]
        candidates = np.flatnonzero(~(key > kth))  # those tied with the k-th too, and NaN
        return candidates[np.argsort(key[candidates], kind="stable")[:k]]
    return np.argsort(key, kind="stable")


# ------------------------------------------------------------------------------------------------- refinement
class _LocalProblem:
    """Objective and constraints of one design in the logs of its free continuous variables, for SLSQP.

    One vectorised evaluation at z and at z + step e_i gives values and forward-difference derivatives together.
    """

    STEP = 1e-7

    def __init__(self, req, constraints, x0: np.ndarray, free: list[int], mode: str, objective: str):
        self.req, self.constraints, self.x0, self.free = req, constraints, x0, free
        self.mode, self.objective = mode, objective
        self._z = None

    def point(self, z: np.ndarray) -> np.ndarray:
        x = self.x0.copy()
        x[self.free] = np.exp(z)
        if self.req.configuration == "mixed":
            x[2] = x[3] + x[0]
        return x

    def _values(self, X: np.ndarray):
        fig = _evaluate(self.req, _unstack(X, self.req), self.constraints)
        margins = np.where(np.isnan(fig.margins), -1.0, fig.margins)
        # keep the rod thinner than the piston (the geometry stays valid between constraint evaluations)
        rod = 1.0 - 1e-3 - X[:, 4] / X[:, 3]
        if self.mode == "objective":
            key = _objective_key(fig, self.objective)
            with np.errstate(invalid="ignore", divide="ignore"):
                f = np.log(np.abs(key))
            f = np.where(fig.valid & np.isfinite(f), f, 1e3)
            cons = np.vstack([margins - SAFETY, rod])
        else:
            f = _violation(margins)
            f = np.where(np.isfinite(f), f, 1e3)
            cons = rod[None, :]
        return f, cons

    def _update(self, z: np.ndarray) -> None:
        if self._z is not None and np.array_equal(z, self._z):
            return
        k = z.size
        Z = np.tile(z, (k + 1, 1)) + np.vstack([np.zeros(k), np.eye(k) * self.STEP])
        X = np.array([self.point(zi) for zi in Z])
        f, cons = self._values(X)
        self._z = z.copy()
        self.f, self.c = f[0], cons[:, 0]
        self.df = (f[1:] - f[0]) / self.STEP
        self.dc = (cons[:, 1:] - cons[:, :1]) / self.STEP

    def fun(self, z):
        self._update(z)
        return self.f, self.df

    def cons(self, z):
        self._update(z)
        return self.c

    def cons_jac(self, z):
        self._update(z)
        return self.dc


def _refine(req, constraints, x0: np.ndarray, mode: str) -> np.ndarray:
    """SLSQP from x0; returns the improved point, or x0 when the optimiser ends somewhere worse or infeasible."""
    free = [req.variables.index(k) for k in req.free_variables if k != "ducts"]
    if not free:
        return x0
    prob = _LocalProblem(req, constraints, x0, free, mode, req.objective)
    lo = np.log([req.bounds[req.variables[j]][0] for j in free])
    hi = np.log([req.bounds[req.variables[j]][1] for j in free])
    z0 = np.clip(np.log(x0[free]), lo, hi)
    res = minimize(
        prob.fun,
        z0,
        jac=True,
        method="SLSQP",
        bounds=list(zip(lo, hi)),
        constraints=[{"type": "ineq", "fun": prob.cons, "jac": prob.cons_jac}],
        options={"maxiter": 100, "ftol": 1e-9},
    )
    x1 = prob.point(np.clip(res.x, lo, hi))
    f0, _ = prob._values(x0[None, :])
    f1, c1 = prob._values(x1[None, :])
    if mode == "objective":
        fig = _evaluate(req, _unstack(x1[None, :], req), constraints)
        if fig.feasible[0] and f1[0] <= f0[0]:
            return x1
        return x0
    return x1 if f1[0] <= f0[0] and c1[-1, 0] >= 0 else x0


def _refine_task(req: Requirements, mode: str, x0: np.ndarray) -> np.ndarray:
    """:func:`_refine` as a task of the executor (the constraints are made where it runs: they hold functions)."""
    return _refine(req, constraints_for(req), x0, mode)


# ------------------------------------------------------------------------------------------- rounding/re-check
def _geometry_table(req: Requirements, x: np.ndarray, digits: int | None = None) -> dict:
    """The [geometry] table of design ``x``: ``digits`` significant figures, or (None) the decimals of the grid."""
    s = req.search

    def mm(v: float, grid: float) -> str:
        if digits is not None:
            return f"{v * 1e3:.{digits}g} mm"
        decimals = max(0, int(np.ceil(-np.log10(grid * 1e3) - 1e-9)))
        return f"{v * 1e3:.{decimals}f} mm"

    g, L = s.gap_tolerance, s.length_tolerance
    table: dict[str, Any] = {"configuration": req.configuration, "duct_length": mm(x[1], L)}
    if req.configuration == "valve":
        table["duct_mean_diameter"] = mm(x[2], L)
    table.update(gap=mm(x[0], g), piston_diameter=mm(x[3], L), rod_diameter=mm(x[4], L))
    if req.configuration == "valve":
        table["ducts"] = round(x[5])
    if req.coil is not None:
        coil = {"turns": int(round(x[6])), "wire_diameter": mm(x[7], g)}
        coil.update(
            core_diameter=mm(x[8], L),
            pole_length=mm(x[9], L),
            housing_outer_diameter=mm(x[10], L),
            steel=req.coil.steel,
        )
        if req.coil.supply_voltage is not None:
            coil["supply_voltage"] = f"{req.coil.supply_voltage:.6g} V"
        table["coil"] = coil
    return table


def _metres(text: str) -> float:
    """SI value of a length written by :func:`_geometry_table` ("54.6 mm"): the product pint forms, value x 1e-3."""
    return float(text.removesuffix(" mm")) * 1e-3


def _parse_geometry(req: Requirements, table: dict) -> np.ndarray:
    h = _metres(table["gap"])
    Dp = _metres(table["piston_diameter"])
    d = _metres(table["duct_mean_diameter"]) if "duct_mean_diameter" in table else mixed_mean_diameter(Dp, h)
    row = [h, _metres(table["duct_length"]), d, Dp, _metres(table["rod_diameter"]), float(table.get("ducts", 1))]
    if "coil" in table:
        c = table["coil"]
        row += [float(c["turns"])] + [_metres(c[k]) for k in COIL_VARIABLES[1:]]
    return np.array(row)


def _within_bounds(req: Requirements, R: np.ndarray) -> np.ndarray:
    ok = np.ones(len(R), dtype=bool)
    for j, name in enumerate(req.variables):
        b = req.bounds.get(name)
        if b is None or name not in req.free_variables:
            continue
        lo, hi = b
        ok &= (R[:, j] >= lo * (1 - 1e-9)) & (R[:, j] <= hi * (1 + 1e-9))
    return ok


def _rounded(req, constraints, X: np.ndarray, need_feasible: bool):
    """Round every design to the grid (module notes, step 3) and re-evaluate it from the strings; drop those that
    fail (unless ``need_feasible`` is False: then the nearest grid point is kept)."""
    s = req.search
    if s.gap_tolerance == 0 or s.length_tolerance == 0:
        return _rounded_digits(req, constraints, X, need_feasible)
    grid = np.array([s.gap_tolerance, s.length_tolerance, s.length_tolerance, s.length_tolerance, s.length_tolerance])
    mixed = req.configuration == "mixed"
    free = [0, 1, 3, 4] if mixed else [0, 1, 2, 3, 4]  # mixed: d = Dp + h follows
    rounded = list(range(5))  # columns on a grid (ducts are whole already)
    if req.coil is not None:  # turns whole, the wire on the gap's grid, the other coil lengths on the length grid
        grid = np.concatenate([grid, [0.0, 1.0, s.gap_tolerance] + [s.length_tolerance] * 3])
        free = free + [6, 7, 8, 9, 10]
        rounded = rounded + [6, 7, 8, 9, 10]
        # only the coil's own columns and the flow columns that are free vary (fewer corners to try)
        free = [j for j in free if req.variables[j] in req.free_variables]
    grid_full = np.ones(len(req.variables))
    grid_full[rounded] = grid[rounded]
    corners = np.array(np.meshgrid(*[[0, 1]] * len(free), indexing="ij")).reshape(len(free), -1).T

    def on_grid(rows: np.ndarray):
        """Rows through the strings of their tables (the figures are those of the table printed), and whether
        each meets every constraint and bound."""
        if mixed:
            rows[:, 2] = rows[:, 3] + rows[:, 0]
        tables = [_geometry_table(req, r) for r in rows]
        R = np.array([_parse_geometry(req, t) for t in tables])
        fig = _evaluate(req, _unstack(R, req), constraints)
        ok = fig.feasible & _within_bounds(req, R) & np.all(R[:, :5] > 0, axis=1)
        return tables, R, ok, _objective_key(fig, req.objective)

    X = np.asarray(X, dtype=float)
    near = X.copy()
    near[:, rounded] = np.round(X[:, rounded] / grid_full[rounded]) * grid_full[rounded]
    tables, R, ok, _ = on_grid(near)
    keep_tables, keep_rows = [], []
    for i, x in enumerate(X):
        if ok[i]:
            keep_tables.append(tables[i])
            keep_rows.append(R[i])
            continue
        # the nearest grid point fails: the best neighbour that meets every constraint (one design at a time, so
        # that memory stays that of a few dozen candidates)
        lo = x.copy()
        hi = x.copy()
        lo[rounded] = np.floor(x[rounded] / grid_full[rounded] + 1e-9) * grid_full[rounded]
        hi[rounded] = np.ceil(x[rounded] / grid_full[rounded] - 1e-9) * grid_full[rounded]
        rows = np.repeat(x[None, :], len(corners), axis=0)
        for k, c in enumerate(corners):
            rows[k, free] = np.where(c == 1, hi[free], lo[free])
        t_n, R_n, ok_n, key_n = on_grid(rows)
        if ok_n.any():
            j = int(np.flatnonzero(ok_n)[np.argmin(key_n[ok_n])])
            keep_tables.append(t_n[j])
            keep_rows.append(R_n[j])
        elif not need_feasible:
            keep_tables.append(tables[i])
            keep_rows.append(R[i])
    if not keep_tables:
        return [], None
    return keep_tables, _evaluate(req, _unstack(np.array(keep_rows), req), constraints)


def _rounded_digits(req, constraints, X: np.ndarray, need_feasible: bool):
    """Round every design to a [geometry] table and re-evaluate it from the strings; drop those that fail.

    Six significant figures first; a design that fails only because of the rounding is tried with more.
    """
    tables: list = [None] * len(X)
    rows = np.array(X, dtype=float, copy=True)
    pending = np.arange(len(X))
    for digits in (6, 8, 10, 12, 15):
        if pending.size == 0:
            break
        tabs = [_geometry_table(req, X[i], digits) for i in pending]
        R = np.array([_parse_geometry(req, t) for t in tabs])
        ok = _evaluate(req, _unstack(R, req), constraints).feasible | (not need_feasible)
        for j in np.flatnonzero(ok):
            tables[pending[j]], rows[pending[j]] = tabs[j], R[j]
        pending = pending[~ok]
    keep = [i for i in range(len(X)) if tables[i] is not None]
    if not keep:
        return [], None
    return [tables[i] for i in keep], _evaluate(req, _unstack(rows[keep], req), constraints)


def _ranked(req: Requirements, fig: CandidateFigures) -> np.ndarray:
    """Order of the designs of ``fig``: by the objective, ties (within :data:`TIE`) by the secondary objective."""
    key = _objective_key(fig, req.objective)
    second = _objective_key(fig, secondary_objective(req))
    order = np.argsort(key, kind="stable")
    groups, current, start = np.empty(len(key), dtype=int), 0, None
    for rank, i in enumerate(order):
        if start is None or abs(key[i] - start) > TIE * max(abs(start), 1e-300):
            current, start = rank, key[i]
        groups[i] = current
    return np.lexsort((second, groups))


# ----------------------------------------------------------------------------------------------------- design
def design(req: Requirements, progress=None, *, executor=None, jobs: int | None = None, scheduler=None) -> DesignResult:
    """Feasible designs ranked by the objective, the Pareto front, or the conflicts when nothing is feasible.

    Parameters
    ----------
    req : Requirements
        From :func:`~erdesign.design.read_requirements`; ``req.search`` sets the sample size, seed, chunk size,
        refinement, number of designs and Pareto figures (``req.with_search(samples=...)`` changes them).
    progress : callable, optional
        Called as chunks of the sweep finish as ``progress(evaluated, total, feasible)`` (the command line prints
        it on long searches).
    executor, jobs, scheduler : optional
        Where the chunks of the sweep and the refinements run (:func:`erdesign.executor.executor_for`): serial by
        default, ``jobs=N`` a local pool of N processes, ``scheduler`` a Dask cluster.  Each worker makes its
        chunks from the seed and the chunk index and returns their summaries, which are merged here in chunk
        order: the result is the same, number for number, on any executor.

    Returns
    -------
    DesignResult
        ``designs`` best first (each a record whose ``geometry`` is a damper-file [geometry] table), ``pareto``,
        ``conflicts`` and ``nearest`` (when infeasible); :meth:`DesignResult.as_json` is the ``--json`` output.

    Examples
    --------
    >>> from erdesign.design import load_example_requirements
    >>> r = design(load_example_requirements("makris_requirements").with_search(samples=4096))
    >>> r.feasible, r.designs[0]["force_N"] >= 5700.0, r.conflicts
    (True, True, [])
    """
    ex = executor_for(executor, jobs=jobs, scheduler=scheduler)
    try:
        return _design(req, ex, progress)
    finally:
        if ex is not executor:  # ours, not the caller's
            ex.close()


def _sweep(req: Requirements, ex: Executor, keep: int, progress=None) -> _Summary:
    """The summary of every chunk of the sweep, merged in chunk order (chunks that finish early wait)."""
    s = req.search
    summary = _Summary(len(constraints_for(req)), keep, req.variables)
    waiting: dict[int, _Summary] = {}
    evaluated = feasible = merged = 0
    for index, part in ex.imap(functools.partial(_chunk_summary, req, keep), range(chunk_count(req))):
        waiting[index] = part
        evaluated, feasible = evaluated + part.evaluated, feasible + part.feasible
        while merged in waiting:
            summary.merge(waiting.pop(merged), s.pareto)
            merged += 1
        if progress is not None:
            progress(evaluated, s.samples, feasible)
    return summary


def _design(req: Requirements, ex: Executor, progress) -> DesignResult:
    constraints = constraints_for(req)
    s = req.search
    summary = _sweep(req, ex, max(_KEEP_FACTOR * s.designs, _MAX_STARTS), progress)
    tol = s.active_tolerance
    result = DesignResult(
        requirements=req, constraints=constraints, evaluated=summary.evaluated, feasible_count=summary.feasible
    )
    if summary.feasible:
        X = summary.best_X
        if s.refine:
            starts = min(len(X), _MAX_STARTS if req.configuration == "valve" else 3, max(s.designs, 3))
            refined = np.array(ex.map(functools.partial(_refine_task, req, "objective"), list(X[:starts])))
            X = np.vstack([refined, X])
            origin = ["refined"] * starts + ["sampled"] * len(summary.best_X)
        else:
            origin = ["sampled"] * len(X)
        tables, fig = _rounded(req, constraints, X, need_feasible=True)
        seen, records = set(), []
        if fig is not None:
            for i in _ranked(req, fig):
                ident = repr(sorted(tables[i].items()))
                if ident in seen:
                    continue
                seen.add(ident)
                records.append(design_record(req, constraints, fig.take([i]), tables[i], tol, origin[i]))
                if len(records) == s.designs:
                    break
        for rank, rec in enumerate(records, start=1):
            rec["rank"] = rank
        result.designs = records
        result.pareto = _pareto_records(req, constraints, summary, tol)
    else:
        result.nearest, result.conflicts = _explain(req, constraints, summary, tol, ex)
    result.feasible = bool(result.designs)
    if not result.feasible and not result.conflicts:  # pragma: no cover - feasible samples that fail rounding
        result.conflicts = ["feasible samples were found but none survived rounding to a geometry table"]
    return result


def _pareto_records(req, constraints, summary: _Summary, tol: float) -> list[dict]:
    X, Y = summary.front_X, summary.front_Y
    if len(X) == 0:
        return []
    order = np.argsort(Y[:, 0], kind="stable")
    if len(order) > PARETO_LIMIT:
        order = order[np.unique(np.linspace(0, len(order) - 1, PARETO_LIMIT).round().astype(int))]
    tables, fig = _rounded(req, constraints, X[order], need_feasible=True)
    if fig is None:
        return []
    return [design_record(req, constraints, fig.take([i]), tables[i], tol, "sampled") for i in range(len(tables))]


def _explain(req, constraints, summary: _Summary, tol: float, ex: Executor):
    """Nearest design and the list of conflicts, for a sweep with no feasible sample."""
    conflicts: list[str] = []
    if summary.valid == 0:
        return None, [
            (
                "no sampled geometry is buildable: check that rod_diameter < piston_diameter and gap < "
                "duct_mean_diameter can hold within design.bounds"
            )
        ]
    X = summary.near_X[np.isfinite(summary.near_v)]
    if req.search.refine:
        X = np.vstack([np.array(ex.map(functools.partial(_refine_task, req, "violation"), list(X[:3]))), X])
    fig = _evaluate(req, _unstack(X, req), constraints)
    best = int(np.argmin(_violation(fig.margins)))
    tables, near = _rounded(req, constraints, X[[best]], need_feasible=False)
    record = design_record(req, constraints, near, tables[0], tol, "nearest")
    margins = near.margins[:, 0]
    for j in np.flatnonzero(margins < 0):
        conflicts.append(_shortfall_text(constraints[j], near, margins[j]))
    always = [c.name for j, c in enumerate(constraints) if summary.violated[j] == summary.valid]
    if always:
        conflicts.append("violated by every sampled design: " + ", ".join(always))
    singles = [(int(summary.single[j]), constraints[j].name) for j in np.flatnonzero(summary.single)]
    if singles:
        for count, name in sorted(singles, reverse=True)[:3]:
            conflicts.append(f"relaxing {name} alone would admit {count} of {summary.evaluated} sampled designs")
    else:
        i, j = np.nonzero(summary.pair)
        pairs = sorted(
            ((int(summary.pair[a, b]), constraints[a].name, constraints[b].name) for a, b in zip(i, j)), reverse=True
        )
        for count, a, b in pairs[:3]:
            conflicts.append(
                f"relaxing {a} and {b} together would admit {count} of {summary.evaluated} sampled designs"
            )
        if not pairs:
            conflicts.append("every sampled design violates three or more constraints")
    record["violations"] = {constraints[j].name: float(-margins[j]) for j in np.flatnonzero(margins < 0)}
    return record, conflicts


def _shortfall_text(c: Constraint, fig: CandidateFigures, margin: float) -> str:
    value = float(c.value(fig)[0])
    sign = "<=" if c.upper else ">="
    unit = f" {c.unit}" if c.unit else ""

    def show(x: float) -> str:
        return f"{x / c.scale:.4g}{unit}"

    return (
        f"{c.name}: the nearest design reaches {show(value)}, the requirement is {sign} {show(c.limit)} "
        f"(off by {100 * abs(margin):.3g} % of the limit)"
    )
