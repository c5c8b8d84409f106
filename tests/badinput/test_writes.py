"""Writes that cannot lose data (issue 27): exclusive creation decided at the moment of creation, symbolic links
refused, interrupts and races leave the old file or the complete new one, and never a temporary file.

Every writer of the command line, the report and the API goes through :mod:`erdesign.output`; these tests drive the
helper directly (in this process and in child processes that are signalled or raced) and through the writers and
commands that use it.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

from erdesign._util import check_output_path
from erdesign.campaign.batch import read_table, write_table
from erdesign.cli import main
from erdesign.data.measurement import Measurement, read_measurement, write_measurement
from erdesign.errors import OutputPathError
from erdesign.output import SIGTERM_EXIT, atomic_output, open_output, write_output

ROOT = Path(__file__).resolve().parents[2]
MAKRIS = str(ROOT / "erdesign" / "examples" / "makris.toml")


def leftovers(folder: Path) -> list[str]:
    """Temporary files of the helper left in ``folder`` (there must be none)."""
    return sorted(p.name for p in folder.iterdir() if p.name.endswith(".tmp"))


# ------------------------------------------------------------------------------------------ exclusive creation
def test_an_existing_file_is_refused_and_left_as_it_was(tmp_path):
    target = tmp_path / "out.csv"
    target.write_text("old")
    with pytest.raises(OutputPathError, match=r"^path .*out\.csv: exists; pass overwrite=True"):
        write_output(target, "new")
    with pytest.raises(OutputPathError, match=r"^--out .*out\.csv: exists; give --force"):
        write_output(target, "new", option="--out")
    assert target.read_text() == "old"
    assert leftovers(tmp_path) == []


def test_a_file_made_after_the_check_is_not_overwritten(tmp_path):
    """The check before a long run passes; another program makes the file meanwhile; the write refuses it."""
    target = tmp_path / "report.html"
    check_output_path(target)  # the early check: nothing there yet
    with pytest.raises(OutputPathError, match="exists"), atomic_output(target, option="--out") as tmp:
        tmp.write_text("mine, complete")
        target.write_text("someone else's")  # made while this write ran
    assert target.read_text() == "someone else's"
    assert leftovers(tmp_path) == []


def test_overwrite_replaces_the_file_whole_and_keeps_its_permissions(tmp_path):
    target = tmp_path / "out.txt"
    target.write_text("old")
    target.chmod(0o640)
    write_output(target, "new", overwrite=True)
    assert target.read_text() == "new"
    assert (target.stat().st_mode & 0o777) == 0o640
    assert leftovers(tmp_path) == []


def test_a_new_file_gets_the_usual_permissions_not_those_of_a_private_temporary_file(tmp_path):
    umask = os.umask(0o022)
    try:
        write_output(tmp_path / "a.txt", "x")
    finally:
        os.umask(umask)
    assert ((tmp_path / "a.txt").stat().st_mode & 0o777) == 0o644  # 0o666 less the umask, not mkstemp's 0o600


def test_an_error_while_writing_leaves_nothing(tmp_path):
    target = tmp_path / "out.csv"
    with pytest.raises(RuntimeError, match="the writer failed"), open_output(target) as fh:
        fh.write("half")
        raise RuntimeError("the writer failed")
    assert not target.exists() and leftovers(tmp_path) == []


def test_keyboard_interrupt_while_writing_keeps_the_old_file(tmp_path):
    target = tmp_path / "out.csv"
    target.write_text("old, complete")
    with pytest.raises(KeyboardInterrupt), open_output(target, overwrite=True) as fh:
        fh.write("new, half")
        raise KeyboardInterrupt
    assert target.read_text() == "old, complete" and leftovers(tmp_path) == []


@pytest.mark.parametrize(
    "where, message",
    [
        ("missing/out.csv", "the folder .*missing does not exist"),
        ("", "empty file name"),
    ],
)
def test_bad_places_are_one_line_errors(tmp_path, where, message):
    target = (tmp_path / where) if where else ""
    with pytest.raises(OutputPathError, match=message) as info:
        write_output(target, "x", option="--out")
    assert "\n" not in str(info.value)


def test_a_folder_is_refused(tmp_path):
    with pytest.raises(OutputPathError, match="is a folder"):
        write_output(tmp_path, "x", overwrite=True)


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes in read-only folders")
def test_a_read_only_folder_is_named(tmp_path):
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o500)
    try:
        with pytest.raises(OutputPathError, match="cannot write in the folder .*permission denied"):
            write_output(folder / "a.txt", "x")
    finally:
        folder.chmod(0o700)


# ------------------------------------------------------------------------------------------------ symbolic links
def _links(tmp_path: Path) -> dict[str, tuple[Path, Path | None]]:
    """A dangling link, a loop, and a link to a file elsewhere: (link, the file it points to or None)."""
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    victim = elsewhere / "precious.txt"
    victim.write_text("precious")
    dangling = tmp_path / "dangling.csv"
    dangling.symlink_to(elsewhere / "not-yet.csv")
    loop = tmp_path / "loop.csv"
    loop.symlink_to(tmp_path / "loop2.csv")
    (tmp_path / "loop2.csv").symlink_to(loop)
    pointing = tmp_path / "pointing.csv"
    pointing.symlink_to(victim)
    return {"dangling": (dangling, elsewhere / "not-yet.csv"), "loop": (loop, None), "pointing": (pointing, victim)}


@pytest.mark.parametrize("kind", ["dangling", "loop", "pointing"])
def test_a_symbolic_link_at_the_output_is_refused_without_force(tmp_path, kind):
    link, target = _links(tmp_path)[kind]
    before = None if target is None or not target.exists() else target.read_text()
    with pytest.raises(OutputPathError, match=r"^--out .*: is a symbolic link \(to .*\).*give --force"):
        check_output_path(link)  # the early check of every command
    with pytest.raises(OutputPathError, match="is a symbolic link"):
        write_output(link, "written through the link?", option="--out")
    assert link.is_symlink()
    if target is not None:  # nothing written where the link points
        assert (target.read_text() if target.exists() else None) == before
    assert leftovers(tmp_path) == [] and leftovers(tmp_path / "elsewhere") == []


@pytest.mark.parametrize("kind", ["dangling", "loop", "pointing"])
def test_force_replaces_the_link_itself_and_leaves_its_target_alone(tmp_path, kind):
    link, target = _links(tmp_path)[kind]
    check_output_path(link, force=True)
    write_output(link, "new file", overwrite=True)
    assert not link.is_symlink() and link.read_text() == "new file"
    if kind == "pointing":
        assert target.read_text() == "precious"
    if kind == "dangling":
        assert not target.exists()


def test_a_command_refuses_an_output_through_a_dangling_link(tmp_path, capsys):
    out = tmp_path / "report.md"
    out.symlink_to(tmp_path / "somewhere" / "else.md")
    code = main(["report", MAKRIS, "--format", "md", "--out", str(out)])
    err = capsys.readouterr().err
    assert code != 0 and err.count("\n") == 1 and "is a symbolic link" in err and "Traceback" not in err
    assert out.is_symlink() and not (tmp_path / "somewhere").exists()


# ------------------------------------------------------------------------------- interrupts in another process
WRITER = textwrap.dedent("""
    import sys, time
    from erdesign.output import open_output
    target, overwrite = sys.argv[1], sys.argv[2] == "1"
    with open_output(target, overwrite=overwrite) as fh:
        fh.write("new row\\n" * 1000)
        fh.flush()
        print("writing", flush=True)
        for _ in range(600):                 # a long write: the parent interrupts it
            fh.write("new row\\n" * 1000)
            time.sleep(0.05)
    print("done", flush=True)
""")


def _default_signals() -> None:
    """In the child before it starts: Ctrl-C and SIGTERM at their defaults and not blocked.  Both are inherited
    through exec: a shell that starts the suite in the background (``cmd &``) gives it SIGINT ignored, and a library
    of an earlier test may leave it blocked; either way the child's Python never raises KeyboardInterrupt and the
    test sends a Ctrl-C nobody hears (seen in a full clean-clone run: the child wrote on and exited 0)."""
    signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT, signal.SIGTERM})
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _child(*args: str, script: str = WRITER) -> subprocess.Popen:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.Popen(
        [sys.executable, "-c", script, *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
        preexec_fn=_default_signals,
    )


@pytest.mark.parametrize("sig, code", [(signal.SIGTERM, SIGTERM_EXIT), (signal.SIGINT, -signal.SIGINT)])
@pytest.mark.parametrize("existing", [True, False])
def test_an_interrupt_mid_write_leaves_the_old_file_or_none_and_no_temporary(tmp_path, sig, code, existing):
    target = tmp_path / "forces.csv"
    if existing:
        target.write_text("old, complete\n")
    child = _child(str(target), "1" if existing else "0")
    assert child.stdout.readline().strip() == "writing"
    assert leftovers(tmp_path), "the child writes a temporary file beside the target"
    child.send_signal(sig)
    _, err = child.communicate(timeout=60)
    assert child.returncode == code, err
    if existing:
        assert target.read_text() == "old, complete\n"
    else:
        assert not target.exists()
    assert leftovers(tmp_path) == []


# ------------------------------------------------------------------------------------------ two writers at once
RACER = textwrap.dedent("""
    import sys, time, pathlib
    from erdesign.errors import OutputPathError
    from erdesign.output import open_output
    target, me, go = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3])
    try:
        with open_output(target, option="--out") as fh:
            fh.write(me * 10000)
            pathlib.Path(go.with_suffix("." + me)).touch()     # ready: my file is written, not yet named
            while not go.exists():
                time.sleep(0.01)
    except OutputPathError as exc:
        print(exc, file=sys.stderr)
        sys.exit(1)
""")


def test_two_processes_writing_one_new_file_exactly_one_wins(tmp_path):
    target, go = tmp_path / "same.html", tmp_path / "go"
    children = {me: _child(str(target), me, str(go), script=RACER) for me in ("a", "b")}
    deadline = time.monotonic() + 60
    while not all(go.with_suffix("." + me).exists() for me in children):  # both past any check, both written
        assert time.monotonic() < deadline and all(c.poll() is None for c in children.values())
        time.sleep(0.01)
    go.touch()
    results = {me: (c.wait(timeout=60), c.stderr.read()) for me, c in children.items()}
    codes = sorted(code for code, _ in results.values())
    assert codes == [0, 1], results
    winner = next(me for me, (code, _) in results.items() if code == 0)
    loser_err = next(err for code, err in results.values() if code == 1)
    assert target.read_text() == winner * 10000  # the winner's file, whole
    assert loser_err.strip().endswith("same.html: exists; give --force to replace it, or choose another name")
    assert loser_err.count("\n") == 1
    assert leftovers(tmp_path) == []


@pytest.mark.slow
def test_two_report_commands_to_one_file_exactly_one_wins(tmp_path):
    """``erdesign report --out same.html`` twice at once: one exits 0, the other with a one-line "exists"."""
    out = tmp_path / "same.html"
    script = "import sys; from erdesign.cli import main; sys.exit(main(sys.argv[1:]))"
    children = [_child("report", MAKRIS, "--out", str(out), script=script) for _ in range(2)]
    results = [(c.wait(timeout=600), c.stderr.read()) for c in children]
    assert sorted(code for code, _ in results) == [0, 1], results
    err = next(e for code, e in results if code == 1)
    assert "exists" in err and err.strip().count("\n") == 0 and "Traceback" not in err
    assert out.read_text().rstrip().endswith("</html>")
    assert leftovers(tmp_path) == []


# ------------------------------------------------------------------------------------------ the writers use it
def _record() -> Measurement:
    t = np.linspace(0.0, 1.0, 101)
    return Measurement.from_arrays(t, 0.01 * np.sin(2 * np.pi * t), 100.0 * np.cos(2 * np.pi * t))


def test_write_measurement_is_exclusive_unless_overwrite(tmp_path):
    path = tmp_path / "m.csv"
    write_measurement(path, _record())
    with pytest.raises(OutputPathError, match="m.csv: exists"):
        write_measurement(path, _record().with_force(np.zeros(101)))
    np.testing.assert_allclose(read_measurement(path).force, _record().force, rtol=1e-9, atol=1e-9)
    write_measurement(path, _record().with_force(np.zeros(101)), overwrite=True)
    assert np.all(read_measurement(path, require_force=False).force == 0.0)
    assert leftovers(tmp_path) == []


def test_the_batch_table_is_written_by_the_same_helper(tmp_path):
    path = tmp_path / "t.csv"
    rows = [{"record": "a.csv", "status": "ok", "esr": 0.25, "sha256": "0" * 64}]
    write_table(path, rows, ["record", "status", "esr", "sha256"])
    with pytest.raises(OutputPathError, match="t.csv: exists"):
        write_table(path, rows, ["record", "status", "esr", "sha256"])
    write_table(path, rows * 2, ["record", "status", "esr", "sha256"], overwrite=True)
    assert [r["esr"] for r in read_table(path)] == [0.25, 0.25]
    link = tmp_path / "link.csv"
    link.symlink_to(tmp_path / "nowhere.csv")
    with pytest.raises(OutputPathError, match="symbolic link"):
        write_table(link, rows, ["record", "status", "esr", "sha256"])
    assert leftovers(tmp_path) == []


@pytest.mark.slow
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_an_interrupt_during_simulate_out_leaves_no_half_written_csv(tmp_path, sig):
    """The issue's case: Ctrl-C (or kill) while ``erdesign simulate --out`` writes a long CSV left 3898 of 1,000,000
    rows.  The command is interrupted as soon as its temporary file appears: no forces.csv, no temporary file."""
    t = np.arange(150_000) / 10_000.0
    record = Measurement.from_arrays(t, 0.01 * np.sin(4 * np.pi * t), 500.0 * np.cos(4 * np.pi * t))
    write_measurement(tmp_path / "m.csv", record)
    script = "import sys; from erdesign.cli import main; sys.exit(main(sys.argv[1:]))"
    child = _child(
        "simulate",
        str(tmp_path / "m.csv"),
        "--model",
        "bingham",
        "--params",
        "f_c=100 N, c0=1000 N*s/m, f0=0 N",
        "--out",
        str(tmp_path / "forces.csv"),
        script=script,
    )
    deadline = time.monotonic() + 300
    while not leftovers(tmp_path):  # the write has begun
        assert child.poll() is None, child.communicate()
        assert time.monotonic() < deadline
        time.sleep(0.005)
    child.send_signal(sig)
    _, err = child.communicate(timeout=120)
    assert child.returncode != 0, err
    assert "Traceback" not in err
    assert not (tmp_path / "forces.csv").exists() and leftovers(tmp_path) == []
