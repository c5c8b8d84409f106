"""The model registry: contract name -> model factory, with one dispatcher (:func:`get_model`).

Names are those of docs/cli.md ("Model names").  Every factory returns a fresh :class:`Model`;
``physics`` (the physics damper of a damper file, with effects, :class:`erdesign.effects.chain.PhysicsDamper`, imported
when first asked for) needs ``damper=`` (a :class:`~erdesign.damper.Damper` or a damper-file path).
"""

from __future__ import annotations

from typing import Callable

from ..errors import ErdesignError, did_you_mean
from .algebraic import (
    Balamurugan,
    ChengTanh,
    EyringPlastic,
    KwokTanh,
    MagicFormula,
    Metered,
    WengArctan,
    YangArctan,
    YangExponential,
)
from .base import Model
from .bingham import Bingham, BinghamExtended, BinghamHysteretic, BinghamImproved, BinghamModified, BinghamRegularized
from .biviscous import ArctanHysteretic, Biviscous, BiviscousHysteretic
from .bouc_wen import BoucWen, BoucWenModified, BoucWenNormalized
from .bouc_wen_variants import (
    BoucWenAmplitude,
    BoucWenAsymmetricSigmoid,
    BoucWenDominguez,
    BoucWenDominguezCFA,
    BoucWenMass,
    BoucWenModifiedMass,
    BoucWenModifiedNormalized,
    BoucWenNonsymmetric,
    BoucWenModifiedPolynomial,
    BoucWenNormalizedBahar,
    BoucWenNormalizedII,
    BoucWenRestructured,
    BoucWenShear,
)
from .chebyshev import Chebyshev
from .friction import Dahl, DahlAsymmetric, DahlViscous, LuGre, LuGreModified
from .general import HeUnified, YuanTanh, YuDivision, ZhaoDeadZone, ZhaoXuSigmoid
from .kamath_wereley import KamathWereley4, KamathWereley6, ViscoelasticPlasticPang
from .lumped import Bass, SimsLumped
from .maxwell import BingMax, Maxwell, MaxwellNeural
from .powell import Powell
from .semiactive import SemiactiveCustomized, SemiactiveGeneral
from .viscoelastic import SVES, ContinuousVEP, LiViscoelasticPlastic, NonlinearStiffnessVEP

__all__ = ["MODELS", "get_model", "model_names", "describe_models", "UnknownModelError", "INVERTIBLE"]


class UnknownModelError(ErdesignError):
    """No model of that name in the registry (or it needs an option that was not given)."""


def _physics(damper=None, effects=(), **options) -> Model:
    """The physics damper (:class:`erdesign.effects.chain.PhysicsDamper`) of a damper file with effects, as a Model."""
    # imported here: the physics damper loads scipy's root finders and the compiled effects, which
    # `erdesign models` and the other models do not need
    from ..effects.chain import PhysicsDamper

    if damper is None:
        raise UnknownModelError("physics: needs the damper (--damper DAMPER.toml on the command line)")
    if isinstance(damper, str) or hasattr(damper, "__fspath__"):
        from ..damper.files import load_damper

        damper = load_damper(damper)
    model = PhysicsDamper(damper, effects=tuple(effects), **options)
    if "yield_stress_factor" in model.parameter_names and not model.control_parameters:
        # without a field the yield stress cannot be seen: held at its nominal value (factor 1) for such records
        model.control_parameters = ("yield_stress_factor",)
    return model


#: name -> factory (a class or a function returning a Model).
MODELS: dict[str, Callable[..., Model]] = {
    "bingham": Bingham,
    "bingham_extended": BinghamExtended,
    "powell": Powell,
    "bingmax": BingMax,
    "maxwell": Maxwell,
    "bouc_wen": BoucWen,
    "bouc_wen_modified": BoucWenModified,
    "bouc_wen_normalized": BoucWenNormalized,
    "kamath_wereley_4": KamathWereley4,
    "kamath_wereley_6": KamathWereley6,
    "biviscous": Biviscous,
    "biviscous_hysteretic": BiviscousHysteretic,
    "eyring_plastic": EyringPlastic,
    "semiactive_general": SemiactiveGeneral,
    "semiactive_customized": SemiactiveCustomized,
    "dahl": Dahl,
    "dahl_viscous": DahlViscous,
    "lugre": LuGre,
    "lugre_modified": LuGreModified,
    "weng_arctan": WengArctan,
    "kwok_tanh": KwokTanh,
    "magic_formula": MagicFormula,
    "chebyshev": Chebyshev,
    "maxwell_neural": MaxwellNeural,
    # the rest of the MR-model review's catalogue (its Table 1; docs/models.md maps every row)
    "bingham_modified": BinghamModified,
    "bingham_improved": BinghamImproved,
    "bingham_hysteretic": BinghamHysteretic,
    "bingham_regularized": BinghamRegularized,
    "bouc_wen_modified_polynomial": BoucWenModifiedPolynomial,
    "bouc_wen_shear": BoucWenShear,
    "bouc_wen_mass": BoucWenMass,
    "bouc_wen_modified_mass": BoucWenModifiedMass,
    "bouc_wen_amplitude": BoucWenAmplitude,
    "bouc_wen_dominguez": BoucWenDominguez,
    "bouc_wen_dominguez_cfa": BoucWenDominguezCFA,
    "bouc_wen_asymmetric_sigmoid": BoucWenAsymmetricSigmoid,
    "bouc_wen_nonsymmetric": BoucWenNonsymmetric,
    "bouc_wen_modified_normalized": BoucWenModifiedNormalized,
    "bouc_wen_restructured": BoucWenRestructured,
    "bouc_wen_normalized_dominguez": BoucWenNormalizedII,
    "bouc_wen_normalized_bahar": BoucWenNormalizedBahar,
    "viscoelastic_plastic_pang": ViscoelasticPlasticPang,
    "li_viscoelastic_plastic": LiViscoelasticPlastic,
    "vep_continuous": ContinuousVEP,
    "vep_nonlinear_stiffness": NonlinearStiffnessVEP,
    "sves": SVES,
    "arctan_hysteretic": ArctanHysteretic,
    "sims_lumped": SimsLumped,
    "metered": Metered,
    "balamurugan": Balamurugan,
    "bass": Bass,
    "yang_arctan": YangArctan,
    "yang_exponential": YangExponential,
    "cheng_tanh": ChengTanh,
    "dahl_asymmetric": DahlAsymmetric,
    "zhao_dead_zone": ZhaoDeadZone,
    "zhao_xu_sigmoid": ZhaoXuSigmoid,
    "yuan_tanh": YuanTanh,
    "yu_division": YuDivision,
    "he_unified": HeUnified,
    "physics": _physics,
}

#: The models the MR-model review's Table 1 marks invertible (Kwok, the magic formula, the modified LuGre, the modified
#: normalised Bouc-Wen, Li's viscoelastic-plastic and Cheng's models), plus the physics damper.  Which models
#: :mod:`erdesign.identification.inverse` inverts is :attr:`erdesign.models.base.Model.invertible` (a superset:
#: every memoryless model with a control is inverted by a bracketed root).
INVERTIBLE = (
    "kwok_tanh",
    "magic_formula",
    "lugre_modified",
    "bouc_wen_normalized",
    "li_viscoelastic_plastic",
    "cheng_tanh",
    "physics",
)


def model_names() -> list[str]:
    """Registry names, in the order of the contract."""
    return list(MODELS)


def get_model(name: str, **options) -> Model:
    """A fresh model by registry name; ``options`` go to its factory (``damper=`` for ``physics``,
    ``degree=`` for ``chebyshev``, ``hidden=`` for ``maxwell_neural``)."""
    if not isinstance(name, str):  # a list was "TypeError: unhashable type: 'list'"
        raise UnknownModelError(f"name: expected a model's name (text), got {type(name).__name__} {name!r:.60}")
    try:
        factory = MODELS[name]
    except KeyError:
        raise UnknownModelError(
            f"unknown model {name!r}{did_you_mean(name, MODELS)}; known: {', '.join(MODELS)}"
        ) from None
    try:
        return factory(**options)
    except TypeError as exc:
        raise UnknownModelError(f"{name}: {exc}") from None


def describe_models(include_physics: bool = True) -> list[dict]:
    """Registry entries for ``erdesign models --json``.  ``physics`` is described without a damper (its
    parameters depend on the damper and effects, so the list is empty)."""
    out = []
    for name in MODELS:
        if name == "physics":
            if include_physics:
                out.append(
                    {
                        "name": "physics",
                        "source": "the damper of a damper file with effects "
                        "(erdesign.effects.chain; Makris eqs 1-16, Kamath-Wereley mixed mode)",
                        "invertible": True,
                        "parameters": [],
                    }
                )
            continue
        out.append(get_model(name).describe())
    return out
