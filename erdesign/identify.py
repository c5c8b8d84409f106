r"""Identification workflows on top of :func:`erdesign.fit.fit`: one record, several records jointly (e.g. one
sinusoid per coil current with the current-dependent parameters shared), and cross-validation tables in the style
of seed 002 Table 4 (identify on one experiment, score the ESR on every other).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np
from scipy.optimize import least_squares

from .fit import FitError, FitResult, fit
from .measurement import Measurement
from .metrics import esr
from .models.base import Model

__all__ = ["identify", "identify_joint", "cross_validation", "CrossValidation", "JointResult",
           "choose_control_reference"]


def choose_control_reference(model: Model, records: Sequence[Measurement]) -> float:
    """Power of ten near the largest |control| of the records (1 when they have none), so that the model's
    dimensionless control u = control / reference is of order one and its per-unit parameters stay readable."""
    peak = max((float(np.max(np.abs(r.control))) for r in records if r.control_kind is not None), default=0.0)
    ref = 10.0 ** math.floor(math.log10(peak)) if peak > 0 else 1.0
    model.control_reference = ref
    return ref


def identify(model: Model, record: Measurement, *, starts: int = 4, global_search: bool = False,
             **options) -> FitResult:
    """Identify ``model`` on ``record``: choose the control reference, fit (multi-start), and train the network
    of a hybrid model (``maxwell_neural``) on the residual of its parametric part."""
    choose_control_reference(model, [record])
    if record.control_kind is not None and not np.any(record.control):
        # a control column of zeros shows no more of the control dependence than none: hold the slopes too
        free = options.get("free")
        held = {k: model.parameter(k).default for k in model.control_parameters if free is None or k not in free}
        options["fixed"] = {**held, **dict(options.get("fixed") or {})}
    result = fit(model, record, starts=starts, global_search=global_search, **options)
    if hasattr(model, "train"):
        model.train(record, result.values)
        result.force = model.simulate(record, result.values)
        result.residual = record.require_force() - result.force
        result.esr = esr(record.require_force(), result.force)
    return result


@dataclass
class JointResult:
    """Parameters shared by several records and the ESR on each."""

    model: Model
    values: dict[str, float]
    esr: list[float]
    names: list[str]
    success: bool


def identify_joint(model: Model, records: Sequence[Measurement], *, free: Sequence[str] | None = None,
                   fixed: Mapping[str, float] | None = None, start: Mapping[str, float] | None = None,
                   max_nfev: int | None = None) -> JointResult:
    """One parameter set for several records (each simulated from rest), by least squares on all residuals.

    Each record's residual is weighted by 1 / its force standard deviation, so that a record with small forces
    (zero current) counts as much as one with large forces.
    """
    if not records:
        raise FitError("identify_joint: no records")
    for r in records:
        model.check_record(r)
        r.require_force()
    choose_control_reference(model, records)
    fixed = dict(fixed or {})
    if all(r.control_kind is None for r in records):
        fixed = {**model.fixed_for(records[0]), **fixed}
    else:
        fixed = {**{p.name: p.default for p in model.parameters if not p.fitted}, **fixed}
    names = [n for n in (free or model.parameter_names) if n not in fixed]
    if not names:
        raise FitError(f"{model.name}: no free parameter to fit")
    total = sum(len(r) for r in records)
    if total <= len(names):
        raise FitError(f"identify_joint: {total} samples cannot determine {len(names)} parameters")
    base = model.check_values({**model.initial_guess(records[0]), **(start or {}), **fixed})
    params = [model.parameter(n) for n in names]
    log = np.array([p.log_scale for p in params])
    lo = np.array([math.log(p.lower) if p.log_scale else p.lower for p in params])
    hi = np.array([math.log(p.upper) if p.log_scale else p.upper for p in params])
    z0 = np.clip([math.log(base[n]) if p.log_scale else base[n] for n, p in zip(names, params)], lo, hi)
    forces = [r.require_force() for r in records]
    weights = [1.0 / max(float(np.std(F)), 1e-12) for F in forces]

    def values(z):
        v = dict(base)
        v.update({n: float(math.exp(q) if lg else q) for n, q, lg in zip(names, z, log)})
        return v

    def residual(z):
        v = values(z)
        parts = [w * (model.force(r, v) - F) for r, F, w in zip(records, forces, weights)]
        out = np.concatenate(parts)
        return np.where(np.isfinite(out), out, 1e6)

    res = least_squares(residual, z0, bounds=(lo, hi), x_scale="jac", max_nfev=max_nfev)
    v = values(res.x)
    return JointResult(model, v, [esr(F, model.force(r, v)) for r, F in zip(records, forces)],
                       [r.name for r in records], bool(res.success))


@dataclass
class CrossValidation:
    """ESR table: ``table[i][j]`` is the ESR on record i of the model identified on record j (seed 002 Table 4)."""

    names: list[str]
    table: np.ndarray

    @property
    def average(self) -> np.ndarray:
        """Mean ESR of each identification record over all validation records (the table's last row)."""
        return self.table.mean(axis=0)

    def markdown(self) -> str:
        head = "| validation \\ identification | " + " | ".join(self.names) + " |"
        rule = "|---" * (len(self.names) + 1) + "|"
        rows = [f"| {n} | " + " | ".join(f"{x:.4f}" for x in row) + " |" for n, row in zip(self.names, self.table)]
        rows.append("| average | " + " | ".join(f"{x:.4f}" for x in self.average) + " |")
        return "\n".join([head, rule, *rows])


def cross_validation(model_factory, records: Sequence[Measurement], **fit_options) -> CrossValidation:
    """Identify a fresh model (``model_factory()``) on each record and score it on every record."""
    n = len(records)
    table = np.empty((n, n))
    for j, rec in enumerate(records):
        model = model_factory()
        r = identify(model, rec, **fit_options)
        for i, other in enumerate(records):
            table[i, j] = r.esr if i == j else esr(other.require_force(), model.simulate(other, r.values))
    return CrossValidation([r.name or f"record {k}" for k, r in enumerate(records)], table)


# ------------------------------------------------------------------------------------------------ real-data study
#: Coil currents of the Quiroz (2022) UTFSM sinusoids [A] and of the columns 2-6 of its validation record.
QUIROZ_CURRENTS = (0.0, 0.25, 0.5, 0.75, 1.0)
QUIROZ_VALIDATION_CURRENTS = (0.2, 0.4, 0.6, 0.8, 1.0)
#: The six sinusoids: amplitude [mm] and frequency [Hz] as in the file names ('x' is the decimal point).
QUIROZ_TESTS = (("10mm1Hz", 1.0), ("25mm0x1Hz", 0.1), ("25mm0x25Hz", 0.25), ("25mm0x5Hz", 0.5), ("2mm5Hz", 5.0),
                ("5mm3Hz", 3.0))


def quiroz_folder(repository_root=None):
    """The folder ``../shared/data/quiroz2022_utfsm_mr`` next to the repository (None when it is absent)."""
    from pathlib import Path
    root = Path(repository_root) if repository_root else Path(__file__).resolve().parents[1]
    folder = root.parent / "shared" / "data" / "quiroz2022_utfsm_mr"
    return folder if folder.is_dir() else None


def _current_label(i: float) -> str:
    return f"{i:g}".replace(".", "x") + "A"


def read_quiroz_sinusoid(folder, test: str, current: float, *, cycles: float = 2.5,
                         samples_per_cycle: int = 200) -> Measurement:
    r"""One preprocessed sinusoid of the Quiroz (2022) MR damper, cropped and resampled for identification.

    The file holds t [s], x [mm], v [mm/s], F [N] (see shared/data/README.md).  The last ``cycles`` periods are
    kept (the start of each test is a transient of the press) and resampled by linear interpolation to
    ``samples_per_cycle`` per period (the 5 Hz test is stored at only 40 per period; the models take the motion as
    linear between samples, so interpolation adds no information but keeps their time steps short).  The velocity
    is derived from x (Savitzky-Golay), not taken from the file's finite difference.

    Notes
    -----
    The source smoothed x and F alike with a causal moving average over a tenth of a period: both carry the same
    lag (about 1/20 of a period), so the phase between them is kept, but sharp force changes at reversals are
    rounded over that window - a floor on the ESR any model can reach.
    """
    from pathlib import Path
    freq = dict(QUIROZ_TESTS)[test]
    a = np.loadtxt(Path(folder) / "preprocessed" / f"{test}{_current_label(current)}.txt")
    period = 1.0 / freq
    keep = a[:, 0] >= a[-1, 0] - cycles * period
    t0 = a[keep, 0][0]
    t = np.linspace(0.0, a[-1, 0] - t0, int(round((a[-1, 0] - t0) / period * samples_per_cycle)) + 1)
    x = np.interp(t + t0, a[:, 0], a[:, 1]) * 1e-3
    F = np.interp(t + t0, a[:, 0], a[:, 3])
    return Measurement.from_arrays(t, x - x.mean(), F, control=current, control_kind="current",
                                   name=f"{test} {current:g} A")


def read_quiroz_validation(folder, *, step: int = 1) -> list[Measurement]:
    """The earthquake-type validation record (validation/validacion.mat, 1 kHz): one record per current
    (0.2 to 1.0 A), every ``step``-th sample."""
    from pathlib import Path
    from scipy.io import loadmat
    data = loadmat(str(Path(folder) / "validation" / "validacion.mat"))["data"][::step]
    t = np.arange(data.shape[0]) * 1e-3 * step
    x = data[:, 0] * 1e-3
    return [Measurement.from_arrays(t, x, data[:, k + 1], control=i, control_kind="current",
                                    name=f"earthquake {i:g} A")
            for k, i in enumerate(QUIROZ_VALIDATION_CURRENTS)]


def quiroz_source_values(folder, current: float, *, A: float = 1.0, beta_ratio: float = 1.0) -> dict[str, float]:
    r"""The source's own current-dependent modified Bouc-Wen parameters (parametros_ajuste2.mat) at one current,
    in SI, as values of :class:`~erdesign.models.bouc_wen.BoucWenModified` with the control slopes at zero.

    The source works in mm and N: k0, k1 [N/mm], x0 [mm], :math:`\alpha = p_4 i^2 + p_5 i + p_6` [N/mm],
    :math:`\gamma = p_7 e^{p_8 i}` [1/mm^2], :math:`c_0 = p_9 i + p_{10}`, :math:`c_1 = p_{11} i + p_{12}` [N s/mm].
    Its beta, A and n sit in a binary Simulink file that is not in the data set: n = 2 is assumed, A (``A``, the
    Bouc-Wen delta) and :math:`\beta = ` ``beta_ratio`` :math:`\gamma` are given here (:func:`quiroz_hidden_constants`
    estimates them from the data).
    """
    from pathlib import Path
    from scipy.io import loadmat
    p = loadmat(str(Path(folder) / "parametros_ajuste2.mat"))["parametros"].ravel()
    i = float(current)
    gamma = p[6] * math.exp(p[7] * i) * 1e6
    out = {"k0": p[0] * 1e3, "k1": p[1] * 1e3, "x0": p[2] * 1e-3,
            "alpha_a": (p[3] * i**2 + p[4] * i + p[5]) * 1e3, "gamma": gamma,
            "beta": beta_ratio * gamma, "delta": A, "n": 2.0,
            "c0a": (p[8] * i + p[9]) * 1e3, "c1a": (p[10] * i + p[11]) * 1e3,
            "c0b": 0.0, "c1b": 0.0, "alpha_b": 0.0, "alpha_c": 0.0}
    return {k: float(v) for k, v in out.items()}


#: Models of the real-data study, with what is held fixed: the control filter rate (every record has a constant
#: current, so it cannot be seen) and the redundant Bouc-Wen scale (A = 1, n = 2 as in the source).
QUIROZ_STUDY_MODELS = {
    "bouc_wen_modified": {"eta": 190.0, "delta": 1.0, "n": 2.0},
    "bingham": {},
    "kwok_tanh": {},
}


def _quiroz_start(name: str, folder) -> dict[str, float]:
    """Starting values: for the modified Bouc-Wen, the source's own fit (its c0, c1, alpha laws in SI)."""
    if name != "bouc_wen_modified":
        return {}
    s0, s1 = quiroz_source_values(folder, 0.0), quiroz_source_values(folder, 1.0)
    mid = quiroz_source_values(folder, 0.5)["gamma"]
    return {"c0a": s0["c0a"], "c0b": s1["c0a"] - s0["c0a"], "c1a": s0["c1a"], "c1b": s1["c1a"] - s0["c1a"],
            "k0": 1.0, "k1": s0["k1"], "x0": 0.0, "alpha_a": s0["alpha_a"],
            "alpha_b": (s1["alpha_a"] - s0["alpha_a"]) * 2.0, "alpha_c": -(s1["alpha_a"] - s0["alpha_a"]),
            "beta": mid, "gamma": mid, "delta": 1.0}


def real_data_study(folder, *, models: Sequence[str] = tuple(QUIROZ_STUDY_MODELS), validation_step: int = 2,
                    records=None, validation=None) -> dict:
    """Identify current-dependent models on all 30 Quiroz sinusoids jointly, score them on the earthquake record.

    Returns a JSON-ready dict: per model the identified values (SI), the ESR on every training record and on the
    validation record at each current, the run time; and the source's own modified Bouc-Wen parameters scored the
    same way (under the assumptions of :func:`quiroz_source_values`).  ``docs/make_real_data.py`` writes it to
    docs/real_data.md.
    """
    import time as _time
    from .models.registry import get_model
    records = records if records is not None else [read_quiroz_sinusoid(folder, test, i) for test, _ in QUIROZ_TESTS
                                                   for i in QUIROZ_CURRENTS]
    validation = validation if validation is not None else read_quiroz_validation(folder, step=validation_step)
    out = {"training": [r.name for r in records], "validation": [r.name for r in validation], "models": {}}
    for name in models:
        model = get_model(name)
        t0 = _time.perf_counter()
        res = identify_joint(model, records, fixed=QUIROZ_STUDY_MODELS.get(name, {}), start=_quiroz_start(name, folder))
        seconds = _time.perf_counter() - t0
        out["models"][name] = {
            "values": res.values, "success": res.success, "seconds": seconds,
            "training_esr": dict(zip(res.names, res.esr)),
            "validation_esr": {r.name: esr(r.require_force(), model.simulate(r, res.values)) for r in validation}}
    model = get_model("bouc_wen_modified")
    A, ratio = quiroz_hidden_constants(folder, records)
    source = {}
    for label, kw in (("A = 1, beta = gamma", {}), (f"A = {A:.4g}, beta = {ratio:.4g} gamma", {"A": A,
                                                                                          "beta_ratio": ratio})):
        def score(r):
            return esr(r.require_force(), model.simulate(r, quiroz_source_values(folder, float(r.control[0]), **kw)))
        source[label] = {"A": kw.get("A", 1.0), "beta_ratio": kw.get("beta_ratio", 1.0),
                         "training_esr": {r.name: score(r) for r in records},
                         "validation_esr": {r.name: score(r) for r in validation}}
    out["source"] = source
    return out


def quiroz_hidden_constants(folder, records: Sequence[Measurement]) -> tuple[float, float]:
    """The two constants the source's Simulink model hides, A and beta / gamma (n = 2), by least squares on
    ``records`` with all of the source's published parameters held: (A, beta_ratio)."""
    from .models.registry import get_model
    model = get_model("bouc_wen_modified")
    base = [{**model.defaults(), **quiroz_source_values(folder, float(r.control[0]))} for r in records]
    scale = [1.0 / max(float(np.std(r.require_force())), 1e-12) for r in records]

    def residual(z):
        parts = [w * (model.force(r, {**v, "delta": math.exp(z[0]), "beta": z[1] * v["gamma"]}) - r.force)
                 for r, v, w in zip(records, base, scale)]
        out = np.concatenate(parts)
        return np.where(np.isfinite(out), out, 1e6)

    # a few starts: the loss has several basins in (A, beta/gamma)
    best = min((least_squares(residual, [math.log(a0), r0], bounds=([-10.0, -0.99], [15.0, 50.0]), max_nfev=60)
                for a0 in (1.0, 10.0, 100.0) for r0 in (1.0, 0.0, -0.5)), key=lambda res: res.cost)
    return float(math.exp(best.x[0])), float(best.x[1])
