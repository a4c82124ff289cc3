"""An export's folder, written whole or not at all.

The files are written into a hidden staging folder beside the target (same file system)
and renamed into place in one step once everything is written (and verified, with
``--verify``); a failure or a signal removes the staging folder and leaves the target as
it was. A target that exists is replaced only when it is empty or an earlier export (it
holds :data:`MANIFEST`): ``-o ~/Documents`` must never empty a folder of the user's. The
old export is moved aside, the new one renamed in, then the old one removed, with signals
held over the two renames so that the target is never missing.

An export never replaces a folder that holds a file the run reads (the robot, an include,
a mesh): replacing it would delete the input.
"""

from __future__ import annotations

import contextlib
import os
import secrets
import shutil
from collections.abc import Iterable, Iterator
from pathlib import Path

from ..errors import InputError, UsageError
from ..held_signals import hold_signals, release_signals
from ..load.inputs import display_path
from ..scaffold.placing import make_parents, remove_made, require_makeable

MANIFEST = "mcar-export.json"


def refuse_replacing(target: Path, protected: Iterable[Path | None]) -> None:
    """UsageError when ``target`` is not a folder an export may replace, or holds (or is)
    one of the ``protected`` files."""
    require_makeable(target, [], "give -o another folder")
    key = Path(os.path.realpath(target))
    for path in protected:
        if path is None:
            continue
        real = Path(os.path.realpath(path))
        if real == key or key in real.parents:
            raise UsageError(f"holds {display_path(path)}, a file this run reads; export "
                             "into another folder", file=display_path(target))
    if os.path.lexists(target):
        if not target.is_dir() or target.is_symlink():
            raise UsageError("exists and is not a folder; give -o a new folder",
                             file=display_path(target))
        if any(target.iterdir()) and not (target / MANIFEST).is_file():
            raise UsageError(f"is a folder mcar did not export into (no {MANIFEST}): it is "
                             "not replaced; give -o a new or empty folder",
                             file=display_path(target))


@contextlib.contextmanager
def staged_folder(target: Path, protected: Iterable[Path | None]) -> Iterator[Path]:
    """Yield an empty staging folder; when the block ends without an error, it becomes
    ``target``. InputError (exit 2) when the file system refuses."""
    from ..load.default_outputs import placed

    target = Path(os.path.abspath(placed(target)[0]))  # below build/: resolved, kept inside
    refuse_replacing(target, protected)
    made = make_parents(target.parent)
    staging = target.parent / f".{target.name[:200]}.mcar-export-{secrets.token_hex(4)}"
    try:
        os.mkdir(staging)
        yield staging
        _swap_in(staging, target)
        made = []
    except OSError as exc:
        where = exc.filename if exc.filename and ".mcar-export-" not in str(exc.filename) \
            else target
        raise InputError(f"cannot write: {exc.strerror or exc}; nothing was written",
                         file=display_path(where)) from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)
        remove_made(made)


def _swap_in(staging: Path, target: Path) -> None:
    old = None
    held = hold_signals()
    try:
        if os.path.lexists(target):
            old = target.parent / f".{target.name[:200]}.mcar-old-{secrets.token_hex(4)}"
            os.rename(target, old)
        try:
            os.rename(staging, target)
        except OSError:
            if old is not None:
                os.rename(old, target)
                old = None
            raise
    finally:
        release_signals(held)
        if old is not None:
            shutil.rmtree(old, ignore_errors=True)
