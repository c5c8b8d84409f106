"""Start-up of the package and the command line: lazy imports (issue 12), with the public names unchanged.

Timing is measured by benchmarks/bench_startup.py, never asserted here; these tests check what the laziness rests
on: which modules a bare import and ``erdesign --help`` load, and that the lazy names are the real ones.
"""

import json
import subprocess
import sys

import click
import pytest

import erdesign
from erdesign.cli import main
from erdesign.cli.main import COMMANDS, cli

HEAVY = ("scipy", "pint", "numba", "plotly", "pandas", "erdesign.identification.fit", "erdesign.models")


def _modules_after(code):
    out = subprocess.run(
        [sys.executable, "-c", code + "\nimport sys, json; print(json.dumps(sorted(sys.modules)))"],
        capture_output=True,
        text=True,
        check=True,
    )
    return set(json.loads(out.stdout.strip().splitlines()[-1]))


@pytest.mark.parametrize(
    "code",
    [
        "import erdesign",
        "from erdesign.cli import main\ntry:\n    main(['--help'])\nexcept SystemExit:\n    pass",
    ],
)
def test_bare_import_and_help_load_no_heavy_dependency(code):
    loaded = _modules_after(code)
    assert not [m for m in loaded if m.split(".")[0] in HEAVY or m in HEAVY]


def test_size_command_does_not_load_scipy_subpackages():
    """`erdesign size` needs pint and the damper, not scipy's solvers (only the exact annulus or a tabulated law
    would; pint itself imports the bare ``scipy`` package to probe for it)."""
    loaded = _modules_after(
        "import pathlib, erdesign\nfrom erdesign.cli import main\n"
        "main(['size', str(pathlib.Path(erdesign.__file__).parent / 'examples' / 'makris.toml'), "
        "'--velocity', '0.0254', '--json'])"
    )
    assert "erdesign.damper" in loaded
    solvers = ("scipy.optimize", "scipy.stats", "scipy.special", "scipy.integrate", "scipy.interpolate")
    assert not [m for m in loaded if m.startswith(solvers)]


def test_every_public_name_resolves_to_its_defining_module():
    from erdesign import fit as fit_function
    from erdesign.identification.fit import fit as real_fit
    from erdesign.units import Q_

    for name in erdesign.__all__:
        assert getattr(erdesign, name) is not None, name
    assert fit_function is real_fit and erdesign.fit is real_fit  # the function, not the deprecated module erdesign.fit
    assert erdesign.Q_ is Q_
    assert erdesign.flow.slit_pressure_drop(1e-6, 7.0, 0.0546, 0.0143, 0.0008) == pytest.approx(
        erdesign.slit_pressure_drop("1 mL/s", "7 Pa*s", "54.6 mm", "14.3 mm", "0.8 mm").to("Pa").magnitude
    )
    assert erdesign.materials.__name__ == "erdesign.materials"  # any submodule, as an attribute
    with pytest.raises(AttributeError, match="no attribute 'no_such_name'"):
        erdesign.no_such_name  # noqa: B018


def test_command_table_matches_the_commands_own_help():
    """The --help list comes from COMMANDS without importing the commands; it must say what each command says."""
    for name, (module, text) in COMMANDS.items():
        command = cli.get_command(click.Context(cli), name)
        assert command is not None and command.name == name and module == name
        for limit in (45, 65, 300):
            # click's own shortening of the table's text (a bare command with that help; click 8.5 deprecates the
            # helper make_default_short_help it uses)
            assert command.get_short_help_str(limit) == click.Command(name, help=text).get_short_help_str(limit), name


def test_help_lists_every_command(capsys):
    assert main(["--help"]) == 0
    out = capsys.readouterr().out
    for name in COMMANDS:
        assert f"\n  {name} " in out


def test_unknown_command_is_one_line_usage_error(capsys):
    assert main(["no-such-command"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "no-such-command" in err
