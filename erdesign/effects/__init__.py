"""The effect library: physical mechanisms the quasi-steady damper leaves out, one module per effect.

:data:`EFFECTS` maps each contract name (docs/cli.md) to its :class:`Effect`;
:func:`get_effect` and :func:`parse_effect_names` turn user input into effects with one-line errors.
How the effects enter the damper force is :mod:`erdesign.physics`.

>>> sorted(EFFECTS) == sorted(EFFECT_NAMES)
True
"""

from __future__ import annotations

from .base import Effect, EffectError, relaxation_filter
from .compressibility import Compressibility
from .field_lag import FieldLag
from .fluid_inertia import FluidInertia
from .gas_spring import GasSpring
from .leakage import Leakage
from .preyield_elasticity import PreyieldElasticity
from .seal_friction import SealFriction
from .shear_thinning import ShearThinning
from .viscous_heating import ViscousHeating

__all__ = ["Effect", "EffectError", "EFFECTS", "EFFECT_NAMES", "get_effect", "parse_effect_names",
           "relaxation_filter"]

#: The contract's effect names, in the contract's order.
EFFECT_NAMES = ("seal_friction", "fluid_inertia", "compressibility", "leakage", "viscous_heating", "field_lag",
                "shear_thinning", "gas_spring", "preyield_elasticity")

#: name -> Effect (the registry).
EFFECTS: dict[str, Effect] = {e.name: e for e in (
    SealFriction(), FluidInertia(), Compressibility(), Leakage(), ViscousHeating(), FieldLag(), ShearThinning(),
    GasSpring(), PreyieldElasticity())}


def get_effect(name: str) -> Effect:
    """The effect called ``name``; an unknown name is an :class:`EffectError` listing the known ones."""
    try:
        return EFFECTS[name]
    except KeyError:
        raise EffectError(f"unknown effect {name!r}; known effects: {', '.join(EFFECT_NAMES)}") from None


def parse_effect_names(text) -> tuple[str, ...]:
    """Effect names from ``"a,b"`` (command line) or a sequence; checked, duplicates removed, order kept.

    >>> parse_effect_names("seal_friction, fluid_inertia")
    ('seal_friction', 'fluid_inertia')
    """
    if text is None:
        return ()
    items = text.split(",") if isinstance(text, str) else list(text)
    names: list[str] = []
    for item in items:
        name = str(item).strip()
        if not name:
            continue
        get_effect(name)
        if name not in names:
            names.append(name)
    return tuple(names)
