"""Put a new folder of files in place all at once, or not at all.

``mcar init`` and ``mcar new part`` write several files; a failure half-way (a name too
long for the file system, a full disk, Ctrl-C) must not leave half a package behind. Every
name is first checked against the file system's limits; the files are then written into a
hidden staging folder beside the target and renamed into place in one step. When the
target folder already exists (an empty checkout, a folder the user made), each file is
moved in without replacing anything, and a failure takes back what was moved.
"""

from __future__ import annotations

import os
import secrets
import shutil
from pathlib import Path

from ..errors import InputError, UsageError
from ..load.inputs import display_path
from ..names import component_problem, shown


def short(name: str, keep: int = 40) -> str:
    """A name for a one-line message: shown, and cut in the middle when long."""
    text = shown(name)
    return text if len(text) <= keep else f"{text[:keep // 2]}…{text[-keep // 2:]}"


def require_makeable(folder: Path, relatives: list[str], why: str) -> None:
    """UsageError, before anything is written, unless ``folder`` and every file below it
    can be named on this file system (``why``: what gave the name, for the message)."""
    for relative in relatives:
        for part in relative.split("/"):
            problem = component_problem(part)
            if problem is not None:
                raise UsageError(f"cannot make the file '{short(part)}': {problem}; {why}")
    for part in Path(os.path.abspath(folder)).parts[1:]:
        problem = component_problem(part)
        if problem is not None:
            raise UsageError(f"cannot make the folder '{short(part)}': {problem}")


def refuse_present(folder: Path, files, optional: frozenset[str] = frozenset()) -> None:
    """UsageError naming the files below ``folder`` that exist (``optional`` ones aside)."""
    present = [Path(folder) / rel for rel in files
               if rel not in optional and os.path.lexists(Path(folder) / rel)]
    if present:
        raise UsageError("will not overwrite " + ", ".join(shown(p) for p in present))


def place(folder: Path, files: dict[str, str], optional: frozenset[str] = frozenset(),
          executable: frozenset[str] = frozenset()) -> list[Path]:
    """Write ``files`` (path below ``folder`` -> text) into ``folder``, all or none;
    ``optional`` ones are left out where a file exists; ``executable`` ones get the
    execute bits the umask allows. Returns the paths written."""
    folder = Path(os.path.abspath(folder))
    refuse_present(folder, files, optional)
    files = {rel: text for rel, text in files.items() if not os.path.lexists(folder / rel)}
    made_parents = make_parents(folder.parent)
    staging = folder.parent / f".mcar-new-{secrets.token_hex(4)}"
    try:
        os.mkdir(staging)  # the umask's mode, as a plain mkdir: it becomes the folder
        for rel, text in files.items():
            target = staging / rel
            target.parent.mkdir(parents=True, exist_ok=True)
            mode = 0o777 if rel in executable else 0o666  # less the umask, as open() does
            with open(target, "x", encoding="utf-8",
                      opener=lambda path, flags, mode=mode: os.open(path, flags, mode)) as handle:
                handle.write(text)
        if not os.path.lexists(folder):
            os.rename(staging, folder)  # one step: the whole folder, or nothing
        else:
            _move_in(staging, folder, list(files))
    except OSError as exc:
        remove_made(made_parents)
        where = exc.filename if exc.filename and ".mcar-new-" not in str(exc.filename) \
            else folder
        raise InputError(f"cannot write: {exc.strerror or exc}; nothing was written",
                         file=display_path(where)) from None
    except BaseException:
        remove_made(made_parents)
        raise
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return [folder / rel for rel in files]


def make_parents(parent: Path) -> list[Path]:
    """Make ``parent`` and its missing ancestors; returns those made, deepest first."""
    missing = []
    for directory in [parent, *parent.parents]:
        if os.path.lexists(directory):
            break
        missing.append(directory)
    try:
        for directory in reversed(missing):
            os.mkdir(directory)
    except OSError as exc:
        remove_made(missing)
        raise InputError(f"cannot make the folder: {exc.strerror or exc}",
                         file=str(parent)) from None
    return missing


def remove_made(folders: list[Path]) -> None:
    for directory in folders:  # deepest first; only if still empty
        try:
            os.rmdir(directory)
        except OSError:
            pass


def _move_in(staging: Path, folder: Path, relatives: list[str]) -> None:
    """Move each staged file into the existing ``folder``, replacing nothing (a file
    claimed with O_EXCL, then renamed over); on any failure, take back what was moved."""
    placed: list[Path] = []
    made: list[Path] = []
    try:
        for rel in relatives:
            target = folder / rel
            for directory in reversed([p for p in target.parents if p != folder
                                       and folder in p.parents]):
                if not os.path.lexists(directory):
                    os.mkdir(directory)
                    made.append(directory)
            os.close(os.open(target, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o600))
            placed.append(target)
            os.replace(staging / rel, target)
    except BaseException:
        for target in placed:
            try:
                os.unlink(target)
            except OSError:
                pass
        remove_made(list(reversed(made)))
        raise
