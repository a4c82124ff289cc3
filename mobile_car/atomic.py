"""Atomic file output: write to a temporary file beside the target, then rename.

A reader never sees a half-written file, and a failure (an exception, a full disk, Ctrl-C)
leaves whatever was at the target before untouched. A target that exists and is not a
regular file (``/dev/null``, ``/dev/stdout``, a named pipe) is written to in place: renaming
over it would replace the device or pipe with a file (as root, ``/dev/null`` itself).

A rebuilt file keeps its permission bits (0600 stays private, 0755 executable). A read-only
output (0444) is replaced and stays 0444, as ``make`` would: the rename replaces the
folder's entry, which needs a writable folder, not a writable file; read-only guards the
file against editors, not against the tool that generates it.

A default output (below ``build/`` or ``renders/``, :mod:`.load.default_outputs`) is
written beneath its folder as resolved once, and never through a link leading out of the
output root; a file there that is not a regular file is replaced, not written into.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from .errors import InputError
from .held_signals import hold_signals, release_signals


def atomic_write(path: str | os.PathLike, data: bytes | str) -> Path:
    """Write ``data`` to ``path`` atomically, creating parent directories; returns the path."""
    from .load.default_outputs import placed

    target, confined = placed(path)
    payload = data.encode("utf-8") if isinstance(data, str) else data
    if not confined and _is_special(target):
        try:
            with open(target, "wb") as handle:
                handle.write(payload)
        except OSError as exc:
            raise InputError(f"cannot write: {exc.strerror or exc}", file=str(target)) from None
        return target
    import tempfile  # shutil, random, bz2, lzma: start-up time, only when writing a file

    # A signal between creating the temporary file and the try below would leave it
    # behind: hold signals until the cleanup is in place, then let them in.
    held = hold_signals()
    try:
        try:
            target.parent.mkdir(parents=True, exist_ok=True)
        except (FileExistsError, NotADirectoryError):  # a file where a folder should be
            raise InputError(f"cannot write: {_blocking_file(target)} is a file, not a folder",
                             file=str(target)) from None
        if target.is_dir():
            raise InputError("is a directory, cannot write a file there", file=str(target))
        # The temporary name adds 14 bytes: a long target name (up to NAME_MAX, 255) is cut.
        stem = target.name if len(os.fsencode(target.name)) <= 200 else target.name[:40]
        fd, tmp = tempfile.mkstemp(prefix=f".{stem}.", suffix=".tmp", dir=target.parent)
    except InputError:
        release_signals(held)
        raise
    except OSError as exc:
        release_signals(held)
        raise InputError(f"cannot write: {exc.strerror or exc}", file=str(target)) from None
    try:
        release_signals(held)
        with os.fdopen(fd, "wb") as handle:
            handle.write(payload)
            handle.flush()
            os.fsync(handle.fileno())
        # mkstemp creates 0600: give the output the mode it had, or a plain write's.
        os.chmod(tmp, _mode_for(target))
        os.replace(tmp, target)
    except BaseException as exc:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        if isinstance(exc, OSError):
            raise InputError(f"cannot write: {exc.strerror or exc}", file=str(target)) from None
        raise
    return target


def _mode_for(target: Path) -> int:
    """The permission bits of the file at ``target``, else 0666 less the umask."""
    try:
        return stat.S_IMODE(target.stat().st_mode)
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


def _blocking_file(target: Path) -> str:
    """The first folder of ``target``'s path that is a file (for the message)."""
    for parent in reversed(target.parents):
        if parent.exists() and not parent.is_dir():
            return str(parent)
    return str(target.parent)


def _is_special(target: Path) -> bool:
    """True for an existing target that is neither a regular file nor a folder."""
    try:
        mode = target.stat().st_mode
    except OSError:
        return False
    return not (stat.S_ISREG(mode) or stat.S_ISDIR(mode))
