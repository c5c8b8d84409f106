"""The module paths of the flat layout that moved when the package was laid out by pipeline stage (issue 13).

Each old path still imports: a small module made here (no file: a file at the old path would hide the move from
git's rename detection, and edits made elsewhere to the old file would then not follow it through a merge) that
warns once, with a :class:`DeprecationWarning` naming the new path, and gives the very objects of the new modules
(attribute look-up, so that identity holds and nothing is copied).  The submodules of a moved package are the moved
modules themselves (``import erdesign.truthrig.cases``).  docs/architecture.md has the table; the old paths go in a
later release.  tests/test_layout.py checks every one, and that nothing in the repository imports one.
"""

import functools
import importlib
import importlib.machinery
import sys
import warnings

__all__ = ["MOVED", "MOVED_SUBMODULES", "RENAMED", "renamed"]

#: Old module path -> the modules its names live in now (the warning names them all; the first is the main one).
MOVED: dict[str, tuple[str, ...]] = {
    "erdesign.damper_file": ("erdesign.damper.files",),
    "erdesign.quasi_steady": ("erdesign.damper.quasi_steady",),
    "erdesign.report.sweep": ("erdesign.damper.curves",),
    "erdesign.field_laws": ("erdesign.fluid.field_laws",),
    "erdesign.physics": ("erdesign.effects.chain",),
    "erdesign.measurement": ("erdesign.data.measurement",),
    "erdesign.noise": ("erdesign.data.noise",),
    "erdesign.metrics": ("erdesign.data.metrics",),
    "erdesign.fit": ("erdesign.identification.fit",),
    "erdesign.identify": (
        "erdesign.identification.identify",
        "erdesign.data.readers",
        "erdesign.data.quiroz",
        "erdesign.case_studies.quiroz",
    ),
    "erdesign.inverse": ("erdesign.identification.inverse",),
    "erdesign.diagnose": ("erdesign.diagnosis.diagnose",),
    "erdesign.rig": ("erdesign.simulation.rig",),
    "erdesign.vehicle": ("erdesign.simulation.vehicle",),
    "erdesign.truthrig": ("erdesign.simulation.truthrig",),
    "erdesign.plots": ("erdesign.report.plots",),
}

#: Submodules of the moved packages: ``import erdesign.truthrig.cases`` gives ``erdesign.simulation.truthrig.cases``.
MOVED_SUBMODULES: dict[str, tuple[str, ...]] = {
    "erdesign.field_laws": ("fitting", "kernels", "laws", "tables"),
    "erdesign.truthrig": ("cases", "kernels", "mechanisms", "simulate", "valve"),
}

#: Names of an old path's ``__all__`` that the new modules keep only as deprecated aliases (old path -> names):
#: "sweep" named three things, now each named for what it is (docs/architecture.md).
RENAMED: dict[str, tuple[str, ...]] = {
    "erdesign.report.sweep": ("VelocitySweep", "velocity_sweep"),
    "erdesign.rig": ("sweep",),
}


def renamed(function, old: str):
    """A deprecated alias of ``function`` under its old name ``old`` (a dotted path): it warns, then calls it."""
    new = f"{function.__module__}.{function.__name__}"

    @functools.wraps(function)
    def alias(*args, **kwargs):
        warnings.warn(f"{old} is deprecated; use {new}", DeprecationWarning, stacklevel=2)
        return function(*args, **kwargs)

    alias.__name__ = alias.__qualname__ = old.rpartition(".")[2]
    alias.__doc__ = f"Deprecated alias of :func:`{new}`."
    return alias


class _OldPath:
    """Finder and loader of the old paths (on ``sys.meta_path``, first: a stale ``erdesign/truthrig/`` folder of
    byte-code left by an update must not turn the old path into an empty namespace package)."""

    @staticmethod
    def find_spec(name, path=None, target=None):
        if name not in MOVED:
            return None
        return importlib.machinery.ModuleSpec(name, _OldPath, is_package=name in MOVED_SUBMODULES)

    @staticmethod
    def create_module(spec):
        return None

    @staticmethod
    def exec_module(module):
        old = module.__name__
        new = [importlib.import_module(name) for name in MOVED[old]]

        def __getattr__(name):
            for target in new:
                try:
                    return getattr(target, name)
                except AttributeError:
                    pass
            raise AttributeError(f"module {old!r} has no attribute {name!r}")

        module.__getattr__ = __getattr__
        module.__dir__ = lambda: sorted(set().union(*(dir(target) for target in new)))
        module.__all__ = [
            *dict.fromkeys(name for target in new for name in getattr(target, "__all__", ())),
            *RENAMED.get(old, ()),
        ]
        module.__doc__ = f"Deprecated: moved to {', '.join(MOVED[old])} (docs/architecture.md, moved modules)."
        for name in MOVED_SUBMODULES.get(old, ()):
            sys.modules[f"{old}.{name}"] = importlib.import_module(f"{MOVED[old][0]}.{name}")
        where = MOVED[old][0] if len(new) == 1 else f"{', '.join(MOVED[old][:-1])} or {MOVED[old][-1]}"
        # stacklevel 2: past this function (and the import machinery, which warnings skips), the importing line
        warnings.warn(f"{old} is deprecated; import from {where}", DeprecationWarning, stacklevel=2)


if _OldPath not in sys.meta_path:
    sys.meta_path.insert(0, _OldPath)
