"""The effect library: physical mechanisms the quasi-steady damper leaves out, one module per effect.

:data:`EFFECTS` maps each registered name to its :class:`Effect`; :func:`register_effect` adds one.  A new effect is
one module (a subclass of :class:`Effect` that declares its stage and overrides that stage's hook,
:mod:`erdesign.effects.base`) plus its registration line below; the force chain (:mod:`erdesign.effects.chain`) needs no
change.  :func:`get_effect` and :func:`parse_effect_names` turn user input into effects with one-line errors.

>>> EFFECT_NAMES == tuple(EFFECTS)
True
"""

from __future__ import annotations

from ..errors import did_you_mean
from .base import STAGES, Effect, EffectError, relaxation_filter
from .compressibility import Compressibility
from .field_lag import FieldLag
from .fluid_inertia import FluidInertia
from .gas_spring import GasSpring
from .leakage import Leakage
from .preyield_elasticity import PreyieldElasticity
from .seal_friction import SealFriction
from .shear_thinning import ShearThinning
from .viscous_heating import ViscousHeating

__all__ = [
    "Effect",
    "EffectError",
    "EFFECTS",
    "EFFECT_NAMES",
    "get_effect",
    "parse_effect_names",
    "register_effect",
    "unregister_effect",
    "relaxation_filter",
]

#: name -> Effect (the registry).
EFFECTS: dict[str, Effect] = {}


def register_effect(effect: Effect) -> Effect:
    """Add ``effect`` to the registry under its name; returns it.

    The name must be new and the stage one of :data:`~erdesign.effects.base.STAGES` (a one-line
    :class:`EffectError` otherwise).
    """
    if not isinstance(effect, Effect):
        raise EffectError(f"register_effect: needs an Effect instance, got {effect!r}")
    if not effect.name or effect.name in EFFECTS:
        raise EffectError(f"register_effect: the name {effect.name!r} is empty or already registered")
    if effect.stage not in STAGES:
        raise EffectError(
            f"register_effect: {effect.name}: stage must be one of {', '.join(STAGES)}, got {effect.stage!r}"
        )
    EFFECTS[effect.name] = effect
    return effect


# The library's effects, in the order of the contract (docs/cli.md).
register_effect(SealFriction())
register_effect(FluidInertia())
register_effect(Compressibility())
register_effect(Leakage())
register_effect(ViscousHeating())
register_effect(FieldLag())
register_effect(ShearThinning())
register_effect(GasSpring())
register_effect(PreyieldElasticity())

#: The library's effect names, in the contract's order (docs/cli.md); effects registered later (a user's, a test's)
#: are in :data:`EFFECTS` only, so diagnosis does not try them unasked.
EFFECT_NAMES = tuple(EFFECTS)


def unregister_effect(name: str) -> Effect:
    """Remove an effect added with :func:`register_effect` (not one of the library's); returns it."""
    if name in EFFECT_NAMES:
        raise EffectError(f"unregister_effect: {name} is one of the library's effects")
    try:
        return EFFECTS.pop(name)
    except KeyError:
        raise EffectError(f"unregister_effect: no effect {name!r} is registered") from None


def get_effect(name: str) -> Effect:
    """The effect called ``name``; an unknown name is an :class:`EffectError` listing the known ones."""
    try:
        return EFFECTS[name]
    except KeyError:
        raise EffectError(
            f"unknown effect {name!r}{did_you_mean(name, EFFECTS)}; known effects: {', '.join(EFFECTS)}"
        ) from None


def parse_effect_names(text) -> tuple[str, ...]:
    """Effect names from ``"a,b"`` (command line) or a sequence; checked, duplicates removed, order kept.

    >>> parse_effect_names("seal_friction, fluid_inertia")
    ('seal_friction', 'fluid_inertia')
    """
    if text is None:
        return ()
    if isinstance(text, str):
        items = text.split(",")
    elif isinstance(text, (bytes, bytearray, dict)) or not hasattr(text, "__iter__"):  # True: "not iterable"
        raise EffectError(
            f"effects: expected effect names ('seal_friction,fluid_inertia' or a list of names), got "
            f"{type(text).__name__} {' '.join(repr(text).split())[:60]}"
        )
    else:
        items = list(text)
    names: list[str] = []
    for item in items:
        name = str(item).strip()
        if not name:
            continue
        get_effect(name)
        if name not in names:
            names.append(name)
    return tuple(names)
