"""The package laid out by pipeline stage (issue 13): the flat layout's module paths are deprecated aliases.

Each old path (erdesign/_deprecated.py, ``MOVED``) still imports, warns once with a :class:`DeprecationWarning`
naming the new path, and gives the very objects of the new modules; nothing in the repository imports one of them.
"""

import ast
import importlib
import json
import re
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

import erdesign
from erdesign._deprecated import MOVED, MOVED_SUBMODULES

ROOT = Path(__file__).resolve().parents[1]


def _is_deprecated(module: str) -> bool:
    return any(module == old or module.startswith(old + ".") for old in MOVED)


def _deprecation_warnings(seen) -> list[str]:
    return [
        str(w.message)
        for w in seen
        if issubclass(w.category, DeprecationWarning) and " is deprecated; import from erdesign." in str(w.message)
    ]


@pytest.fixture
def restored(request):
    """Put back what importing an old path again changes: sys.modules and the parent package's attribute (the
    import system binds ``erdesign.diagnose`` to the alias module, which the rest of the session must not see)."""
    old = request.node.callspec.params["old"]
    parent, _, attr = old.rpartition(".")
    names = (old, *(f"{old}.{sub}" for sub in MOVED_SUBMODULES.get(old, ())))
    saved = {name: sys.modules.get(name) for name in names}
    namespace = vars(sys.modules[parent])
    had, value = attr in namespace, namespace.get(attr)
    yield
    for name, module in saved.items():
        if module is None:
            sys.modules.pop(name, None)
        else:
            sys.modules[name] = module
    if had:
        namespace[attr] = value
    else:
        namespace.pop(attr, None)


@pytest.mark.parametrize("old", sorted(MOVED))
@pytest.mark.usefixtures("restored")
def test_old_path_warns_once_and_gives_the_same_objects(old):
    assert not (ROOT / (old.replace(".", "/") + ".py")).exists()  # no file: the move stays a rename for git
    new = [importlib.import_module(name) for name in MOVED[old]]
    for name in (old, *(f"{old}.{sub}" for sub in MOVED_SUBMODULES.get(old, ()))):
        sys.modules.pop(name, None)
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        shim = importlib.import_module(old)
        assert importlib.import_module(old) is shim
    messages = _deprecation_warnings(seen)
    assert len(messages) == 1, messages
    assert messages[0].startswith(f"{old} is deprecated; import from {MOVED[old][0]}")
    assert shim.__all__ and set(dir(shim)) >= set(shim.__all__)
    for name in shim.__all__:
        value = getattr(shim, name)
        assert any(getattr(module, name, None) is value for module in new), f"{old}.{name} is not the new object"
    with pytest.raises(AttributeError, match="has no attribute 'no_such_name'"):
        shim.no_such_name  # noqa: B018
    for sub in MOVED_SUBMODULES.get(old, ()):
        moved = importlib.import_module(f"{MOVED[old][0]}.{sub}")
        assert importlib.import_module(f"{old}.{sub}") is moved and getattr(shim, sub) is moved


def test_the_old_paths_work_as_scripts_wrote_them():
    """Fresh interpreter: the forms users wrote, the warning attributed to their line, the namespace unchanged."""
    code = """
import json, warnings
warnings.simplefilter("always")
with warnings.catch_warnings(record=True) as seen:
    warnings.simplefilter("always")
    import erdesign.truthrig.cases
    from erdesign.field_laws.laws import PowerLaw
    import erdesign.fit
    from erdesign.rig import sweep
import erdesign
from erdesign.simulation.truthrig import cases
from erdesign.fluid.field_laws import laws
from erdesign.identification.fit import fit
from erdesign.simulation import rig
print(json.dumps({
    "warnings": [(str(w.message), w.filename, w.lineno) for w in seen if w.category is DeprecationWarning],
    "cases": erdesign.truthrig.cases is cases, "law": PowerLaw is laws.PowerLaw,
    "fit": erdesign.fit is fit, "sweep": sweep is rig.sweep}))
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=ROOT)
    result = json.loads(out.stdout.strip().splitlines()[-1])
    assert result.pop("warnings") == [
        ["erdesign.truthrig is deprecated; import from erdesign.simulation.truthrig", "<string>", 6],
        ["erdesign.field_laws is deprecated; import from erdesign.fluid.field_laws", "<string>", 7],
        ["erdesign.fit is deprecated; import from erdesign.identification.fit", "<string>", 8],
        ["erdesign.rig is deprecated; import from erdesign.simulation.rig", "<string>", 9],
    ]
    assert all(result.values()), result


def test_the_curated_namespace_and_the_packages_give_no_warning():
    code = """
import json, warnings
with warnings.catch_warnings(record=True) as seen:
    warnings.simplefilter("always")
    from erdesign import *
    import erdesign
    from erdesign.damper import Damper, QuasiSteadyState, CRITICAL_REYNOLDS
    from erdesign.fluid import Fluid, CONTROL_UNITS
    from erdesign.report import velocity_sweep, VelocitySweep
    modules = {name: getattr(erdesign, name).__name__ for name in ("diagnose", "identify", "plots", "field_laws")}
    fit = erdesign.fit
print(json.dumps({"modules": modules, "fit": f"{fit.__module__}.{fit.__name__}",
                  "warnings": [str(w.message) for w in seen if " is deprecated; import from erdesign." in str(w.message)]}))
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=ROOT)
    result = json.loads(out.stdout.strip().splitlines()[-1])
    assert result == {
        "modules": {
            "diagnose": "erdesign.diagnosis.diagnose",
            "identify": "erdesign.identification.identify",
            "plots": "erdesign.report.plots",
            "field_laws": "erdesign.fluid.field_laws",
        },
        "fit": "erdesign.identification.fit.fit",
        "warnings": [],
    }


def _sources() -> list[Path]:
    files = [
        *(ROOT / "erdesign").rglob("*.py"),
        *(ROOT / "tests").rglob("*.py"),
        *(ROOT / "benchmarks").rglob("*.py"),
        *(ROOT / "docs").rglob("*.py"),
        ROOT / "app.py",
        ROOT / "conftest.py",
    ]
    return sorted(p for p in files if "__pycache__" not in p.parts)


def _imported(node: ast.ImportFrom | ast.Import, path: Path) -> list[str]:
    """Absolute names of the modules (or module attributes) an import statement asks for."""
    if isinstance(node, ast.Import):
        return [alias.name for alias in node.names]
    base = node.module or ""
    if node.level:
        parts = list(path.relative_to(ROOT).with_suffix("").parts)
        package = parts[:-1] if parts[-1] != "__init__" else parts[:-1]
        package = package[: len(package) - (node.level - 1)]
        base = ".".join(package + ([node.module] if node.module else []))
    lazy = set(erdesign._LAZY) | set(erdesign._SUBMODULES)  # attributes of the curated namespace: not the shims
    return [base] + [f"{base}.{alias.name}" for alias in node.names if not (base == "erdesign" and alias.name in lazy)]


def test_nothing_imports_a_deprecated_path():
    found = []
    for path in _sources():
        text = path.read_text()
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                found += [
                    f"{path.relative_to(ROOT)}:{node.lineno}: {name}"
                    for name in _imported(node, path)
                    if _is_deprecated(name)
                ]
    # doctests and the code blocks of the docs: import lines in text
    line = re.compile(r"^\s*(?:>>>|\.\.\.)?\s*(?:from|import)\s+(erdesign(?:\.\w+)+)", re.M)
    for path in [*_sources(), *(ROOT / "docs").rglob("*.md"), ROOT / "README.md"]:
        if path == Path(__file__):  # its scripts import the old paths on purpose, in strings
            continue
        for match in line.finditer(path.read_text()):
            if _is_deprecated(match.group(1)):
                found.append(f"{path.relative_to(ROOT)}: {match.group(0).strip()}")
    assert not found, "imports of deprecated module paths:\n" + "\n".join(found)


def test_the_three_sweeps_have_names_that_say_what_they_are():
    """design.search.sweep sampled the design space, report.velocity_sweep made force-velocity curves, rig.sweep a
    motion: each old name is a deprecated alias that warns and gives what the new name gives."""
    import numpy as np

    from erdesign import design, report
    from erdesign.damper import curves
    from erdesign.damper.files import load_example
    from erdesign.design import search
    from erdesign.simulation import rig

    req = design.load_example_requirements("makris_requirements")
    damper = load_example("makris")
    v, E = np.linspace(0.0, 0.05, 6), np.array([0.0, 3e6])
    cases = [
        (search.sweep, search.sample_designs, (req,), {"samples": 256, "seed": 1}, "erdesign.design.search.sweep"),
        (report.velocity_sweep, curves.force_velocity_curves, (damper, v, E), {}, "erdesign.report.velocity_sweep"),
        (rig.sweep, rig.stepped_sine, ([0.004, 0.008], [1.0, 2.0], [0.0, 3e6]), {"rate": 200}, "erdesign.rig.sweep"),
    ]
    for old, new, args, kwargs, name in cases:
        with pytest.warns(DeprecationWarning, match=f"^{name} is deprecated; use {new.__module__}.{new.__name__}$"):
            got = old(*args, **kwargs)
        expected = new(*args, **kwargs)
        for field in ("force", "displacement"):
            if hasattr(expected, field):
                assert np.array_equal(getattr(got, field), getattr(expected, field))
        assert old.__wrapped__ is new
    assert report.VelocitySweep is curves.ForceVelocityCurves is report.ForceVelocityCurves
    assert design.sweep is search.sweep and "sample_designs" in design.__all__
    assert "sweep" not in rig.__all__ and "stepped_sine" in rig.__all__
    # several segments still describe themselves as the record files say ("sine sweep"); one segment is a "sine"
    assert rig.stepped_sine([0.005, 0.01], [2.0], [0.0], rate=200).description.startswith("sine sweep (2 cycles each)")
    assert rig.stepped_sine([0.005], [2.0], [0.0], rate=200).description.startswith("sine (2 cycles)")
