"""Writing output files so that no data is lost: the one way every file erdesign writes reaches the disk.

:func:`atomic_output` is used by every writer of the command line, the report and the API (reports, measurement
and design CSV files, tolerance samples, the batch table, figure images, damper files):

1. the content goes to a temporary file in the target's folder (``.NAME.XXXXXXXX.tmp``, created exclusively);
2. the temporary file is flushed and ``fsync``-ed: it is complete on the disk before it gets the target's name;
3. the target is created **exclusively** at that moment: :func:`os.link` of the temporary file to the target fails
   if the target exists (whatever created it in the meantime: another run, another program), so "exists" is
   decided when the file is created, not by a check made earlier; with ``overwrite=True`` (``--force``)
   :func:`os.replace` puts the complete file in place of the old one in one step;
4. a symbolic link at the target (dangling, a loop, or pointing elsewhere) is refused unless ``overwrite``; with
   it, the link itself is replaced by the file (its target is left alone);
5. whatever happens before step 3 - an error, Ctrl-C (:class:`KeyboardInterrupt`), ``SIGTERM`` (turned into
   :class:`SystemExit` with code 143 while a file is written, in the main thread) - the temporary file is removed
   and the target is untouched: a reader sees the old file or the complete new one, never half of one.

Two runs writing the same new file at once: exactly one wins, the other gets an
:class:`~erdesign.errors.OutputPathError` ("exists").

Example
-------
>>> import tempfile, pathlib
>>> path = pathlib.Path(tempfile.mkdtemp()) / "a.txt"
>>> _ = write_output(path, "one\\n")
>>> try:
...     write_output(path, "two\\n")
... except OutputPathError as exc:
...     print(str(exc).endswith("a.txt: exists; pass overwrite=True to replace it, or choose another name"))
True
>>> _ = write_output(path, "two\\n", overwrite=True); path.read_text()
'two\\n'
>>> [p.name for p in path.parent.iterdir()]           # no temporary file left
['a.txt']
"""

from __future__ import annotations

import contextlib
import errno
import os
import secrets
import signal
import stat
import threading
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import IO, Any

from .errors import OutputPathError

__all__ = [
    "atomic_output",
    "exists_message",
    "open_output",
    "refuse_odd_name",
    "refuse_read_only",
    "refuse_symlink",
    "write_output",
]

#: Exit code of a process stopped by SIGTERM while writing (the shell's 128 + signal number).
SIGTERM_EXIT = 128 + signal.SIGTERM
_NAME_MAX = 255


def exists_message(path: str | Path, option: str = "path") -> str:
    """The one message for an output that exists: the command line's ``--force``, the API's ``overwrite=True``."""
    remedy = "give --force" if option.startswith("--") else "pass overwrite=True"
    return f"{option} {path}: exists; {remedy} to replace it, or choose another name"


def refuse_symlink(path: str | Path, *, overwrite: bool = False, option: str = "path") -> None:
    """An :class:`OutputPathError` when ``path`` is a symbolic link (dangling, a loop or not) and not ``overwrite``."""
    path = Path(path)
    if overwrite or not path.is_symlink():
        return
    try:
        target = os.readlink(path)
    except OSError:  # pragma: no cover - raced away
        target = "?"
    remedy = "give --force" if option.startswith("--") else "pass overwrite=True"
    raise OutputPathError(
        f"{option} {path}: is a symbolic link (to {target}); erdesign does not write through "
        f"links: {remedy} to replace the link itself by the file, or choose another name"
    )


def _tilde_hint(folder: Path) -> str:
    """A hint for a '~' the shell did not expand (in quotes, or after '='): Python does not either."""
    return (
        " ('~' is your home folder only where the shell expands it: write $HOME)" if str(folder).startswith("~") else ""
    )


def refuse_odd_name(out: str | Path, option: str) -> None:
    """An :class:`~erdesign.errors.OutputPathError` for a name that is not what the user meant to write: one
    ending in '/' (a folder; Path() drops the slash and 'new.csv/' was written as the file new.csv) or in a space
    ('x.csv ' was read as the suffix '.csv ')."""
    text = str(out)
    if text.endswith(("/", os.sep)) and text.strip("/" + os.sep):
        raise OutputPathError(f"{option} {text}: ends in '/', a folder; give a file name (e.g. {text}out.csv)")
    name = os.path.basename(text)
    if name != name.strip():
        raise OutputPathError(f"{option} {text!r}: the file name starts or ends in a space; remove it")


def refuse_read_only(path: Path, option: str) -> None:
    """An :class:`~erdesign.errors.OutputPathError` for an existing file nobody may write (chmod a-w): the rename
    that replaces a file ignores its permissions, so --force would replace a file its owner protected."""
    with contextlib.suppress(OSError):
        st = os.stat(path, follow_symlinks=False)
        if stat.S_ISREG(st.st_mode) and not st.st_mode & 0o222:
            raise OutputPathError(
                f"{option} {path}: the file is read-only; --force does not replace a protected file: make it "
                f"writable (chmod u+w) or choose another name"
            )


def _temporary(path: Path, option: str, made: list) -> tuple[Path, int]:
    """A new empty file beside ``path``, created exclusively with the usual permissions (0o666 less the umask).

    Its name goes into ``made`` *before* the file is created, so that an interrupt that lands between the creation
    and the caller's ``try`` still leaves the caller a name to remove (the window the interrupt tests of
    tests/badinput/test_writes.py hit now and then on a loaded machine)."""
    folder = path.parent if str(path.parent) else Path(".")
    stem = path.name[: _NAME_MAX - 15]
    for _ in range(100):
        tmp = folder / f".{stem}.{secrets.token_hex(4)}.tmp"
        made.append(tmp)
        try:
            return tmp, os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0), 0o666)
        except FileExistsError:  # pragma: no cover - 1 in 4e9: another writer's file, not ours to remove
            made.remove(tmp)
            continue
        except FileNotFoundError:
            if folder.is_dir():  # /proc: a folder of the system that takes no new files
                raise OutputPathError(f"{option} {path}: cannot create a file in the folder {folder}") from None
            raise OutputPathError(f"{option} {path}: the folder {folder} does not exist{_tilde_hint(folder)}") from None
        except NotADirectoryError:
            raise OutputPathError(f"{option} {path}: {folder} is not a folder") from None
        except PermissionError:
            raise OutputPathError(f"{option} {path}: cannot write in the folder {folder} (permission denied)") from None
        except OSError as exc:
            raise OutputPathError(
                f"{option} {path}: cannot create a file in {folder}: {exc.strerror or type(exc).__name__}"
            ) from None
    raise OutputPathError(f"{option} {path}: cannot create a temporary file in {folder}")  # pragma: no cover


def _fsync_file(path: Path) -> None:
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _fsync_folder(folder: Path) -> None:
    # the new name is durable only once the folder is synced; not every system lets a folder be opened
    with contextlib.suppress(OSError):
        fd = os.open(folder, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)


def _link_exclusively(tmp: Path, path: Path, option: str) -> None:
    """Give the complete ``tmp`` the name ``path``, failing if ``path`` exists at this moment."""
    exists = OutputPathError(exists_message(path, option))
    try:
        os.link(tmp, path, follow_symlinks=False)
        return
    except FileExistsError:
        if path.is_symlink():
            refuse_symlink(path, option=option)
        raise exists from None
    except OSError as exc:
        if exc.errno not in (errno.EPERM, errno.ENOTSUP, errno.EOPNOTSUPP, errno.EXDEV, errno.EMLINK, errno.ENOSYS):
            raise OutputPathError(
                f"{option} {path}: cannot create the file: {exc.strerror or type(exc).__name__}"
            ) from None
    # a file system without hard links (FAT, some network shares): claim the name exclusively with an empty
    # file, then put the complete file in its place in one step
    try:
        os.close(os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666))
    except FileExistsError:
        raise exists from None
    os.replace(tmp, path)


@contextlib.contextmanager
def terminate_as_exit(before_exit: Callable[[Any], bool] | None = None) -> Iterator[None]:
    """While the block runs: SIGTERM raises ``SystemExit(SIGTERM_EXIT)`` (so ``finally`` blocks run: a temporary
    file is removed, a pool shut down) instead of ending the process at once.  ``before_exit(frame)`` runs first and
    may put the exit off by returning False (the command line stops its worker processes there,
    :func:`erdesign.cli.main._stop_workers`).  Only the main thread can set a handler; elsewhere, and when the
    program has its own handler (or an outer block set this one), nothing changes."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    try:
        previous = signal.getsignal(signal.SIGTERM)
    except (ValueError, OSError, AttributeError):  # pragma: no cover
        yield
        return
    if previous not in (signal.SIG_DFL, None):
        yield
        return

    def stop(signum, frame):
        if before_exit is not None and before_exit(frame) is False:
            return
        raise SystemExit(SIGTERM_EXIT)

    signal.signal(signal.SIGTERM, stop)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


@contextlib.contextmanager
def atomic_output(path: str | Path, *, overwrite: bool = False, option: str = "path") -> Iterator[Path]:
    """Write a file that appears whole or not at all: yields the path of a temporary file beside ``path`` to write
    (by any means: ``open``, pandas, pyarrow); on leaving the block without an error it is synced and given the name
    ``path`` (module docstring).

    Parameters
    ----------
    path : str or Path
        The file to write.
    overwrite : bool
        Replace an existing file (or a symbolic link, the link itself); otherwise an existing ``path`` - even one
        created while the block ran - is an :class:`~erdesign.errors.OutputPathError` and nothing is written.
    option : str
        How messages name the output: an argument name (``path``) or the command line's ``--out``, ``--figures``
        (then the remedy named is ``--force``, else ``overwrite=True``).

    Raises
    ------
    OutputPathError
        ``path`` exists (and not ``overwrite``), is a folder or a symbolic link, or its folder is missing or not
        writable; the message is one line naming ``option`` and ``path``.
    """
    if path is not None and not isinstance(path, (str, os.PathLike)):  # a Series: "expected str, bytes or ..."
        raise OutputPathError(f"{option}: expected a file name (a str or Path), got {type(path).__name__}")
    if path is None or str(path).strip() == "":
        raise OutputPathError(f"{option}: empty file name")
    if "\x00" in str(path):  # "embedded null byte", a ValueError from the first system call
        raise OutputPathError(f"{option} {str(path)!r:.80}: the file name holds a NUL character; give a plain name")
    refuse_odd_name(path, option)
    path = Path(path)
    longest = max((len(part.encode("utf-8", "surrogateescape")) for part in path.parts), default=0)
    if longest > _NAME_MAX:  # "[Errno 36] File name too long: '<the whole path>'"
        raise OutputPathError(
            f"{option} {str(path)[:60]!r}...: a name of {longest} bytes, more than the {_NAME_MAX} a file system "
            "takes; give a shorter name"
        )
    refuse_symlink(path, overwrite=overwrite, option=option)
    if path.is_dir() and not path.is_symlink():
        raise OutputPathError(f"{option} {path}: is a folder; give a file name")
    if overwrite:
        refuse_read_only(path, option)
    with terminate_as_exit():
        made: list[Path] = []
        try:
            tmp, fd = _temporary(path, option, made)
            os.close(fd)
            yield tmp
            _fsync_file(tmp)
            if overwrite:
                with contextlib.suppress(OSError):  # a replaced file keeps its permissions
                    old = os.stat(path, follow_symlinks=False)
                    if stat.S_ISREG(old.st_mode):
                        os.chmod(tmp, stat.S_IMODE(old.st_mode))
                try:
                    os.replace(tmp, path)
                except IsADirectoryError:
                    raise OutputPathError(f"{option} {path}: is a folder; give a file name") from None
                except OSError as exc:
                    raise OutputPathError(
                        f"{option} {path}: cannot replace the file: {exc.strerror or type(exc).__name__}"
                    ) from None
            else:
                _link_exclusively(tmp, path, option)
            _fsync_folder(path.parent if str(path.parent) else Path("."))
        finally:
            for tmp in made:
                with contextlib.suppress(FileNotFoundError):
                    os.unlink(tmp)


@contextlib.contextmanager
def open_output(
    path: str | Path,
    mode: str = "w",
    *,
    overwrite: bool = False,
    option: str = "path",
    encoding: str | None = "utf-8",
    newline: str | None = None,
) -> Iterator[IO]:
    """:func:`atomic_output` as an open file: ``mode`` ``"w"`` (text, ``encoding``, ``newline``) or ``"wb"``."""
    if mode not in ("w", "wb"):
        raise ValueError(f"mode: expected 'w' or 'wb', got {mode!r}")
    with atomic_output(path, overwrite=overwrite, option=option) as tmp:
        if mode == "wb":
            with open(tmp, "wb") as fh:
                yield fh
        else:
            with open(tmp, "w", encoding=encoding, newline=newline) as fh:
                yield fh


def write_output(
    path: str | Path, data: str | bytes, *, overwrite: bool = False, option: str = "path", encoding: str = "utf-8"
) -> Path:
    """Write ``data`` (text as ``encoding``, or bytes) to ``path`` through :func:`atomic_output`; returns the path."""
    raw = data.encode(encoding) if isinstance(data, str) else bytes(data)
    with open_output(path, "wb", overwrite=overwrite, option=option) as fh:
        fh.write(raw)
    return Path(path)
