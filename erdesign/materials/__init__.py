"""The materials database: one TOML file per fluid in this folder, each value with its source.

This folder is installed as the package ``erdesign.materials``.  A damper file's ``[fluid]`` table may name a
material (``material = "makris-zeolite-silicone"``) and override any of its values.

File layout (``<name>.toml``)::

    name = "..."                 # must equal the file name
    description = "..."
    [fluid]                      # the keys of a damper file's [fluid] table, values with units
    viscosity = "7 Pa*s"
    ...
    [sources]                    # for each value of [fluid]: where it comes from
    viscosity = "Makris et al. (seed 004), section 3: 0.001 psi s"
"""

from __future__ import annotations

import sys
from importlib import resources
from typing import Any

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

from ..errors import ErdesignError

__all__ = ["names", "load", "fluid_values"]


def names() -> list[str]:
    """Names of the materials in the database."""
    return sorted(p.name[:-5] for p in resources.files(__name__).iterdir() if p.name.endswith(".toml"))


def load(name: str) -> dict[str, Any]:
    """The whole record of a material (its TOML file as a dictionary)."""
    if name not in names():
        raise ErdesignError(f"unknown material {name!r}; known materials: {', '.join(names())}")
    with resources.as_file(resources.files(__name__) / f"{name}.toml") as path, open(path, "rb") as fh:
        return tomllib.load(fh)


def fluid_values(name: str) -> dict[str, Any]:
    """The ``[fluid]`` values of a material, as a damper file would give them."""
    return dict(load(name).get("fluid", {}))
