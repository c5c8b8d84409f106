"""The one model interface: anything that predicts a damper force from a motion record.

Physics dampers (the quasi-steady damper plus effects) and the phenomenological models of the literature both
implement :class:`Model`, so that fitting (:mod:`erdesign.identification.fit`), metrics, diagnosis, plots and the app
treat them alike.  A model is a description (name, source, parameters with units and bounds) plus one function,
:meth:`Model.force`, that maps a motion record and parameter values (SI floats) to a force array (N).
"""

from __future__ import annotations

import numbers
from typing import Mapping, Sequence

import numpy as np

from ..data.measurement import Measurement
from ..errors import ErdesignError, did_you_mean
from ..parameters import Parameter, ParameterError

__all__ = [
    "ControlAffineModel",
    "FORCE_OFFSET",
    "LinearTermsModel",
    "Parameter",
    "Model",
    "ParameterError",
    "ModelInputError",
]

#: The force offset f0 [N] (seals, bias) of the models that have one, written once.
FORCE_OFFSET = Parameter("f0", "N", 0.0, -1e7, 1e7, "force offset")


class ModelInputError(ErdesignError):
    """A record a model cannot use: too few samples, uneven time steps where the model needs even ones, or no
    control column for a model whose force needs the field / current / voltage."""


class Model:
    """Base class of every damper model.

    Subclasses set :attr:`name`, :attr:`title`, :attr:`source`, :attr:`parameters` (and :attr:`uses_control` when
    parameters depend on the field / current / voltage) and implement :meth:`force`.
    """

    name: str = ""
    """Registry name, snake_case and stable (docs/cli.md, model names)."""
    title: str = ""
    """Human name (``"BingMax (Makris)"``)."""
    source: str = ""
    """Where the equations come from: paper and equation numbers."""
    parameters: tuple[Parameter, ...] = ()
    uses_control: bool = False
    """True when the force depends on the record's control (field, current or voltage)."""
    requires_control: bool = False
    """True when the model has no meaning without a control column (a record without one is an error)."""
    control_parameters: tuple[str, ...] = ()
    """Parameters that only act through the control (slopes of field-dependent coefficients, filter rates).  For a
    record without a control column they are held at their defaults (zero slopes): the field-dependent coefficients
    are then identified as constants."""
    needs_uniform_time: bool = False
    """True when the model's discrete-time filters assume an even time step."""
    min_samples: int = 5
    control_reference: float = 1.0
    """Control (SI: V/m, A/m, T, A or V) that maps to the dimensionless control u = 1 of the model's equations."""
    linear_parameters: tuple[str, ...] = ()
    r"""Parameters in which the force is affine whatever the others' values: :math:`F = r + \sum_j \theta_j b_j`
    with the rest r and the basis b_j functions of the other parameters only (a parameter that enters a state
    equation does not qualify).  Identification solves them by linear least squares inside each residual
    (variable projection, :mod:`erdesign.identification.identify`); tests/test_linear_parameters.py checks each
    declaration."""
    projection_default: bool = True
    """Whether identification projects out the :attr:`linear_parameters` unless told otherwise (False where it was
    measured to end in a worse optimum)."""

    # ------------------------------------------------------------------ to implement
    def force(self, record: Measurement, values: Mapping[str, float]) -> np.ndarray:
        """Model force [N] for the record's motion, one value per sample, from SI parameter values."""
        raise NotImplementedError

    def initial_guess(self, record: Measurement) -> dict[str, float]:
        """Starting values for fitting ``record`` (SI): the parameters' defaults, updated by
        :meth:`guess_from_force` when the record has a force."""
        g = self.defaults()
        if record.force is not None:
            g.update(self.guess_from_force(record))
        return g

    def guess_from_force(self, record: Measurement) -> dict[str, float]:
        """Starting values read from the force of ``record`` (SI; only called for a record with a force).  Default:
        none; override with a guess from the data where one exists (e.g. a damping constant from the
        force-velocity slope, :mod:`erdesign.models._guess`)."""
        return {}

    def linear_terms(
        self, record: Measurement, values: Mapping[str, float]
    ) -> tuple[dict[str, np.ndarray], np.ndarray]:
        """The basis columns b_j [N per unit of the parameter] of the :attr:`linear_parameters` and the rest r [N]
        at ``values``: the force is r + sum_j values[j] b_j.  This default simulates the model once with the
        linear parameters at zero and once per parameter at one; models whose simulation is costly override it
        with one pass."""
        zero = {**values, **{k: 0.0 for k in self.linear_parameters}}
        rest = np.asarray(self.force(record, zero), dtype=float)
        return {
            k: np.asarray(self.force(record, {**zero, k: 1.0}), dtype=float) - rest for k in self.linear_parameters
        }, rest

    # ------------------------------------------------------------------ provided
    def check_record(self, record: Measurement) -> None:
        """Raise :class:`ModelInputError` naming the problem when ``record`` cannot drive this model."""
        n = len(record)
        if n < self.min_samples:
            raise ModelInputError(
                f"{self.name}: the record {record.name or ''} has {n} samples; this model needs at "
                f"least {self.min_samples}".replace("  ", " ")
            )
        if self.requires_control and record.control_kind is None:
            raise ModelInputError(
                f"{self.name}: the force depends on the field / current / voltage, but the record "
                f"{record.name or ''} has no control column (field, current or voltage)".replace("  ", " ")
            )
        if self.needs_uniform_time:
            dt = np.diff(record.time)
            mean = (record.time[-1] - record.time[0]) / (n - 1)
            worst = float(np.max(np.abs(dt - mean)) / mean)
            if worst > 0.01:
                raise ModelInputError(
                    f"{self.name}: needs evenly spaced time samples (its filters are exact for one "
                    f"step size); the steps of {record.name or 'the record'} vary by "
                    f"{100 * worst:.3g} % - resample it first"
                )

    def control(self, record: Measurement) -> np.ndarray:
        """Dimensionless control u = control / :attr:`control_reference` (zeros when the record has none)."""
        return np.asarray(record.control, dtype=float) / self.control_reference

    def fixed_for(self, record: Measurement) -> dict[str, float]:
        """Values to hold fixed when fitting ``record``: the control parameters at their defaults if the record has
        no control column, and every parameter that is not ``fitted`` at its initial guess (its default unless the
        model guesses it from the data, like the scales of the Chebyshev fit)."""
        a_priori = [p.name for p in self.parameters if not p.fitted]
        guess = self.initial_guess(record) if a_priori else {}
        fixed = {k: guess.get(k, self.parameter(k).default) for k in a_priori}
        if record.control_kind is None:
            fixed.update({k: self.parameter(k).default for k in self.control_parameters})
        return fixed

    @property
    def parameter_names(self) -> tuple[str, ...]:
        return tuple(p.name for p in self.parameters)

    def parameter(self, name: str) -> Parameter:
        for p in self.parameters:
            if p.name == name:
                return p
        raise ParameterError(
            f"{self.name}: no parameter {name!r}{did_you_mean(name, self.parameter_names)}; parameters: "
            f"{', '.join(self.parameter_names)}"
        )

    def defaults(self) -> dict[str, float]:
        return {p.name: p.default for p in self.parameters}

    def check_values(self, values: Mapping[str, float]) -> dict[str, float]:
        """All parameter values (defaults filled in), checked: names known, finite, within bounds."""
        unknown = [k for k in values if k not in self.parameter_names]
        if unknown:
            raise ParameterError(
                f"{self.name}: unknown parameter {unknown[0]!r}; parameters: {', '.join(self.parameter_names)}"
            )
        full = {**self.defaults(), **values}
        for p in self.parameters:
            v = full[p.name]
            if isinstance(v, (bool, np.bool_)) or not isinstance(v, (numbers.Real, np.number)) or np.ndim(v):
                # '150 N' was "ufunc 'isfinite' not supported for the input types"
                raise ParameterError(f"{self.name}: {p.name}: expected one number in {p.unit} (SI), got {v!r:.60}")
            if not (np.isfinite(v) and p.lower <= v <= p.upper):
                raise ParameterError(
                    f"{self.name}: {p.name} = {v!r} {p.unit} is outside its bounds [{p.lower:g}, {p.upper:g}] {p.unit}"
                )
        return full

    def simulate(self, record: Measurement, values: Mapping[str, float] | None = None) -> np.ndarray:
        """Force [N] for ``record`` with checked parameter values (defaults where not given) and a checked record."""
        self.check_record(record)
        return np.asarray(self.force(record, self.check_values(values or {})), dtype=float)

    @property
    def invertible(self) -> bool:
        """True when :func:`erdesign.identification.inverse.inverse_control` finds the control for a desired force:
        the force depends on the control and is affine in it at each sample (``control_affine``: explicit, or step
        by step for a state that the control drives) or the model is memoryless (a bracketed root)."""
        return bool(self.uses_control and (hasattr(self, "control_affine") or getattr(self, "memoryless", False)))

    def describe(self) -> dict:
        """The registry entry of ``erdesign models --json``."""
        return {
            "name": self.name,
            "source": self.source,
            "invertible": self.invertible,
            "parameters": [{"name": p.name, "unit": p.unit, "default": p.default} for p in self.parameters],
        }

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.name!r}: {', '.join(self.parameter_names)}>"


class LinearTermsModel(Model):
    """A model written as its :meth:`~Model.linear_terms`: the force is r + sum_j values[j] b_j, computed from the
    one pass that gives the basis and the rest."""

    def force(self, record: Measurement, values: Mapping[str, float]) -> np.ndarray:
        cols, rest = self.linear_terms(record, values)
        return rest + sum(values[k] * c for k, c in cols.items())


def values_from_vector(names: Sequence[str], vector: Sequence[float]) -> dict[str, float]:
    return {n: float(v) for n, v in zip(names, vector)}


class ControlAffineModel(Model):
    """A model whose force is affine in the dimensionless control: F = P(x, v, a) + Q(x, v, a) u.

    Subclasses implement :meth:`control_affine`; the force follows, and :mod:`erdesign.identification.inverse` inverts
    it explicitly (the MR-model review calls such models invertible).
    """

    def control_affine(self, record: Measurement, values: Mapping[str, float]) -> tuple[np.ndarray, np.ndarray]:
        """The two parts (P, Q) of F = P + Q u, [N] each."""
        raise NotImplementedError

    def force(self, record: Measurement, values: Mapping[str, float]) -> np.ndarray:
        P, Q = self.control_affine(record, values)
        return P + Q * self.control(record)
