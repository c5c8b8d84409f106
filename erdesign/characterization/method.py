r"""The characterization-and-customization method of Vivas-López et al. (n.d.) as one workflow, :func:`characterize`.

1. Characterization (section 3): pool the records, split the force into passive and semi-active parts (eq 1,
   :mod:`~erdesign.characterization.split`) and read each characteristic of Table 2 from its diagram
   (:mod:`~erdesign.characterization.detectors`).
2. Customization (section 4): the general model (eqs 2-5) keeps the terms the characteristics found call for
   (Table 2), with coefficients for extension and compression when the damper is asymmetric
   (:class:`~erdesign.models.semiactive.SemiactiveCustomized`; eq 6 and its 20 parameters when the characteristics
   are the paper's).
3. Identification and validation (sections 5-6): the customized model identified on each record and scored on every
   other (Table 4, with the paper's average: the mean of each identification column over all validation records,
   its own included), and the same for the Eyring-plastic model (eq 8, section 7, Table 6).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import partial

import numpy as np

from ..errors import ErdesignError
from ..identification.identify import CrossValidation, cross_validation, identify
from ..models.registry import get_model
from ..models.semiactive import TERMS, SemiactiveCustomized
from .detectors import THRESHOLD, Finding, control_exponent, detect
from .split import Samples, robust_peak

__all__ = [
    "DEMO_MECHANISMS",
    "Characterization",
    "CharacterizationError",
    "characterize",
    "customized_terms",
    "demo_records",
]

#: The truth-rig damper of :func:`demo_records`: Stribeck seal friction, a gas accumulator and a single-ended rod
#: (friction, stiffness and asymmetry to find) on the ``mr_valve_current`` example.
DEMO_MECHANISMS = {
    "stribeck_friction": {"coulomb_force": 150.0, "static_force": 220.0},
    "accumulator": {"charge_pressure": 3e6, "gas_volume": 2e-5},
    "single_rod": {},
}


class CharacterizationError(ErdesignError):
    """Records the method cannot read (none, no force, too few samples); the message names the record."""


def _finite(a) -> list:
    """A nested list of the array's values, None where not finite (a fit that diverged on another record)."""
    return [_finite(x) for x in a] if np.ndim(a) else (float(a) if np.isfinite(a) else None)


def _finite_tree(obj):
    """``obj`` with every non-finite float replaced by None (the JSON of the command holds no NaN)."""
    if isinstance(obj, dict):
        return {k: _finite_tree(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_finite_tree(v) for v in obj]
    if isinstance(obj, float) and not np.isfinite(obj):
        return None
    return obj


def mean_esr_reduction(customized, reference) -> float:
    """The mean over records of the relative reduction of the ESR, (reference - customized) / reference: the
    paper's "on average 28.4 % less ESR than the Eyring-plastic model" from its Table 6.

    >>> round(mean_esr_reduction([0.0714, 0.0642, 0.1284], [0.0996, 0.0816, 0.1996]), 3)   # Vivas-López Table 6
    0.284
    """
    c, r = np.asarray(customized, dtype=float), np.asarray(reference, dtype=float)
    return float(np.mean(np.where(r > 0, (r - c) / np.where(r > 0, r, 1.0), 0.0)))


def customized_terms(findings: Sequence[Finding]) -> tuple[tuple[str, ...], bool]:
    """The terms of the customized model (keys of :data:`~erdesign.models.semiactive.TERMS`, the offset f_0 always)
    and whether its coefficients are asymmetric, from the findings (Table 2).  A pre-yield zone needs the control's
    force gain c_SA that multiplies it (eq 4), so it brings the gain along."""
    terms = {"offset"}
    for f in findings:
        if f.found:
            terms.update(f.characteristic.terms)
    if "preyield" in terms:
        terms.add("gain")
    asymmetric = any(f.found and f.characteristic.asymmetric for f in findings)
    return tuple(t for t in TERMS if t in terms), asymmetric


@dataclass
class Characterization:
    """What :func:`characterize` found and built.

    Attributes
    ----------
    records : list of Measurement
    findings : list of Finding
        One per characteristic of :data:`~erdesign.characterization.detectors.CHARACTERISTICS`.
    passive_force : list of ndarray
        F_P [N] of each record the characteristics were read from (:attr:`read_from`; eq 1): the semi-active force
        is the record's force minus it.
    passive : list of ndarray
        Mask of the samples at the passive control (the lowest) of each of those records.
    terms, asymmetric, scales
        The customized model's terms, whether its coefficients differ in extension and compression, and the peak
        force, speed and stroke of the records that bound its parameters.
    control_exponent : float
        The exponent n of its manipulation V = u^n (the FM diagram's; 1 when the force gain is linear).
    customized, eyring
        Cross-validation tables (Table 4) of the customized and of the Eyring-plastic model (None with one record).
    fits : dict
        Model name -> the identification on the record with the best average (the one the figures show).
    """

    records: list
    findings: list
    passive_force: list
    passive: list
    passive_control: float | None
    terms: tuple[str, ...]
    asymmetric: bool
    scales: dict
    customized: CrossValidation
    eyring: CrossValidation
    fits: dict = field(default_factory=dict)
    identified_on: int = 0
    characterized: list = field(default_factory=list)
    """The records the characteristics were read from (the paper's E1; by default the records themselves)."""
    control_exponent: float = 1.0

    @property
    def read_from(self) -> list:
        return self.characterized or self.records

    @property
    def model(self) -> SemiactiveCustomized:
        return SemiactiveCustomized(self.terms, self.asymmetric, self.scales, self.control_exponent)

    def comparison(self) -> dict:
        """The customized model against the Eyring-plastic model.

        ``identification`` compares the ESR of each on the record it was identified on (the diagonals; the paper's
        Table 6) and ``esr_reduction`` is the mean over the records of the relative reduction (the paper's "28.4 %
        less ESR": the mean of 28.3, 21.3 and 35.7 % of its Table 6); ``cross_validation`` compares the means of
        the whole tables (Table 4); ``customized_better`` is the verdict of the cross-validation (a model that
        predicts the records it was not identified on)."""
        c_diag, e_diag = np.diag(self.customized.table), np.diag(self.eyring.table)
        c, e = float(np.mean(self.customized.table)), float(np.mean(self.eyring.table))
        return {
            "identification": {
                "customized": c_diag.tolist(),
                "eyring_plastic": e_diag.tolist(),
                "esr_reduction": mean_esr_reduction(c_diag, e_diag),
            },
            "cross_validation": {
                "customized_mean_esr": c,
                "eyring_plastic_mean_esr": e,
                "esr_reduction": (e - c) / e if e > 0 else 0.0,
            },
            "customized_better": bool(c < e),
        }

    def split(self) -> dict:
        """The passive / semi-active split (eq 1) over all samples: the RMS of F_P and of F_SA = F_D - F_P [N], and
        the force gain the FM diagram shows: the mean of F_SA sgn(ż) at each control level (up to 8 bins of the
        control span) with the slope and R^2 of a straight line through them (the paper: "the average force gain
        ... has a linear pattern")."""
        F_P = np.concatenate(self.passive_force)
        F = np.concatenate([r.force for r in self.read_from])
        F_SA = F - F_P
        out = {
            "passive_force_rms_N": float(np.sqrt(np.mean((F_P - F_P.mean()) ** 2))),
            "semiactive_force_rms_N": float(np.sqrt(np.mean(F_SA**2))),
            "force_gain": None,
        }
        u = np.concatenate([r.control for r in self.read_from])
        sv = np.sign(np.concatenate([r.velocity for r in self.read_from]))
        if self.passive_control is None or np.ptp(u) == 0:
            return out
        edges = np.linspace(u.min(), u.max(), 9)
        k = np.clip(np.searchsorted(edges, u, side="right") - 1, 0, 7)
        levels = [b for b in range(8) if np.sum(k == b) >= 10]
        x = np.array([np.mean(u[k == b]) for b in levels])
        y = np.array([np.mean(F_SA[k == b] * sv[k == b]) for b in levels])
        if x.size < 2:
            return out
        slope, intercept = np.polyfit(x, y, 1)
        resid = y - (slope * x + intercept)
        r2 = 1.0 - float(np.sum(resid**2) / np.sum((y - y.mean()) ** 2)) if np.ptp(y) > 0 else 1.0
        out["force_gain"] = {
            "control": x.tolist(),
            "force_N": y.tolist(),
            "slope_N_per_control_unit": float(slope),
            "r_squared": r2,
        }
        return out

    def model_force(self, name: str, k: int) -> np.ndarray:
        """The force [N] of model ``name`` (``"customized"`` or ``"eyring_plastic"``), as identified on the record
        with the best average, on record ``k``."""
        fit = self.fits[name]
        return fit.model.simulate(self.records[k], fit.values)

    def to_dict(self) -> dict:
        """The JSON of ``erdesign characterize --json`` (keys in docs/cli.md)."""
        model = self.model
        fit = self.fits["customized"]

        def cv(t):
            return {"table": _finite(t.table), "average": _finite(t.average)}

        return _finite_tree(
            {
                "records": [
                    {
                        "name": r.name,
                        "samples": len(r),
                        "control_kind": r.control_kind,
                        "force_variance_N2": float(np.var(r.force)),
                    }
                    for r in self.records
                ],
                "characterized_on": [
                    {"name": r.name, "samples": len(r), "passive_samples": int(np.sum(self.passive[k]))}
                    for k, r in enumerate(self.read_from)
                ],
                "passive_control": self.passive_control,
                "split": self.split(),
                "characteristics": [f.to_dict() for f in self.findings],
                "found": [f.characteristic.name for f in self.findings if f.found],
                "model": {
                    "terms": list(self.terms),
                    "asymmetric": self.asymmetric,
                    "control_exponent": self.control_exponent,
                    "parameter_count": len(model.parameters),
                    "model_terms": [f.characteristic.model_term for f in self.findings if f.found],
                    "identified_on": self.records[self.identified_on].name,
                    "esr": float(fit.esr),
                    "parameters": {n: model.parameter(n).format(v) for n, v in fit.values.items()},
                    "parameters_si": {n: float(v) for n, v in fit.values.items()},
                    "control_reference": float(fit.model.control_reference),
                },
                "cross_validation": {
                    "records": self.customized.names,
                    "customized": cv(self.customized),
                    "eyring_plastic": cv(self.eyring),
                },
                "comparison": self.comparison(),
            }
        )


def characterize(
    records: Sequence,
    *,
    characterize_on: Sequence = (),
    threshold: float = THRESHOLD,
    executor=None,
    identify_options: dict | None = None,
) -> Characterization:
    """Characterize a damper from its records and build, identify and cross-validate its customized model.

    Parameters
    ----------
    records : sequence of Measurement
        Records of one damper with force (and control, for the semi-active characteristics), e.g. the experiments
        E1-E5 of :mod:`erdesign.simulation.programmes` played on a rig.
    characterize_on : sequence of Measurement, optional
        Records to read the characteristics from instead of ``records`` (the paper characterizes on E1 and
        identifies and cross-validates on E2-E5); ``records`` are then only identified and validated.
    threshold : float
        Rise of the ESR (a fraction of the force variance) a characteristic must account for to be found.
    executor
        Where the identifications run (:func:`erdesign.executor.executor_for`); the tables do not depend on it.
    identify_options : dict, optional
        Keywords of :func:`erdesign.identification.identify.identify` (``max_time``, ``decimate``, ``starts``...).
        Default one trust-region start from each model's guess (``starts=1``), the paper's nonlinear least squares:
        identify's further starts run when a fit is no better than the reference Bingham fit, which an
        Eyring-plastic fit of a nearly Bingham damper never is (50 s instead of 1 s on a 5,000-sample record).

    Returns
    -------
    Characterization

    References
    ----------
    Vivas-López et al. (n.d.), eqs 1-8, Tables 2, 4 and 6.
    """
    records, read_from = list(records), list(characterize_on) or list(records)
    if not records:
        raise CharacterizationError("records: none given")
    for r in records + read_from:
        if r.force is None:
            raise CharacterizationError(
                f"{r.name or 'record'}: has no force column (characterize reads measured "
                "forces; a test plan from 'erdesign doe' must be played on a rig first)"
            )
        if not np.ptp(r.force) > 0:
            raise CharacterizationError(
                f"{r.name or 'record'}: the force is constant ({r.force[0]:.6g} N): no "
                "diagram to read (a disconnected load cell?)"
            )
    kinds = {r.control_kind for r in records + read_from} - {None}
    if len(kinds) > 1:
        raise CharacterizationError(
            f"records: controls of different kinds ({', '.join(sorted(kinds))}); the records "
            "of one damper share one control column"
        )
    samples = Samples.pool(read_from)
    findings, F_P = detect(samples, threshold=threshold)
    terms, asymmetric = customized_terms(findings)
    exponent = control_exponent(findings)
    options = {"starts": 1, **dict(identify_options or {})}

    def every(name):
        return np.concatenate([getattr(r, name) for r in records + read_from])

    scales = {
        "force": robust_peak(every("force")),
        "speed": robust_peak(every("velocity")),
        "stroke": robust_peak(every("displacement")),
    }
    factories = {
        "customized": partial(SemiactiveCustomized, terms, asymmetric, scales, exponent),
        "eyring_plastic": partial(get_model, "eyring_plastic"),
    }
    tables = {name: cross_validation(f, records, executor=executor, **options) for name, f in factories.items()}
    best = int(np.argmin(tables["customized"].average))
    fits = {name: identify(f(), records[best], **options) for name, f in factories.items()}
    splits = np.cumsum([0] + [len(r) for r in read_from])

    def per_record(a):
        return [a[splits[k] : splits[k + 1]] for k in range(len(read_from))]

    return Characterization(
        records,
        findings,
        per_record(F_P),
        per_record(samples.passive),
        samples.u_passive,
        terms,
        asymmetric,
        scales,
        tables["customized"],
        tables["eyring_plastic"],
        fits,
        best,
        list(characterize_on),
        exponent,
    )


def demo_records(
    mechanisms=None,
    names=("e2", "e3", "e4", "e5"),
    *,
    damper: str = "mr_valve_current",
    control_range=(0.0, 0.8),
    rate: float = 250.0,
    seed: int = 2,
) -> list:
    """Records of the experiments ``names`` (:mod:`erdesign.simulation.programmes`) measured on the independent
    truth rig (:mod:`erdesign.simulation.truthrig`) with ``mechanisms`` (default :data:`DEMO_MECHANISMS`): the
    records of docs/characterize.md, the app's example and the tests' (control in A for the default damper)."""
    from ..damper.files import load_example
    from ..simulation.programmes import programme
    from ..simulation.truthrig import TruthDamper, simulate_truth

    truth = TruthDamper(load_example(damper), DEMO_MECHANISMS if mechanisms is None else mechanisms)
    return [
        simulate_truth(truth, programme(n, control_range=control_range, rate=rate), seed=seed, name=n).measured
        for n in names
    ]
