"""Reading an input without trusting its size or its kind.

Size: at most the limit and one byte more. A file's ``st_size`` says nothing about
standard input, which may never end: it is read here in chunks and refused with a
one-line InputError once it passes ``MCAR_MAX_INPUT_MB``. Regular files may be read
whole where a command promises no limit (``mcar check``): they end.

Kind: a FIFO, socket or device named as a file (an input, an include, a config, a
mesh) is refused by :func:`open_regular` before it is read. ``open()`` of a FIFO
without a writer blocks for ever, and a device may never end, so the file is stat'ed
first, opened with O_NONBLOCK (which never blocks on a FIFO), and the opened file is
stat'ed again in case the name was swapped between the two.
"""

from __future__ import annotations

import errno
import os
import stat
from pathlib import Path

from ..errors import InputError
from .input_limit import MAX_INPUT_MB_ENV, check_size, display_path, input_limit_mb

_CHUNK = 1 << 20
_KINDS = ((stat.S_ISFIFO, "a FIFO"), (stat.S_ISSOCK, "a socket"),
          (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"))


class NotRegularFile(InputError):
    """A FIFO, socket or device where a file was expected; ``path`` is what was opened."""

    def __init__(self, kind: str, path: str | os.PathLike, shown: str):
        super().__init__(f"is {kind}, not a regular file", file=shown)
        self.path = str(path)


def special_kind(mode: int) -> str | None:
    """"a FIFO", "a socket", "a character device" or "a block device"; None for a
    regular file, a directory or a link."""
    return next((kind for test, kind in _KINDS if test(mode)), None)


def not_regular(path: str | os.PathLike) -> str | None:
    """"is a FIFO, not a regular file" (or a socket, a device) for a path that is one,
    else None: missing files, folders and regular files are the caller's usual business.
    Only stats: never opens."""
    try:
        kind = special_kind(os.stat(path).st_mode)
    except (OSError, ValueError):
        return None
    return None if kind is None else f"is {kind}, not a regular file"


def open_regular(path: str | os.PathLike, shown: str | None = None):
    """A binary file object for a regular file, opened without ever blocking; OSError
    as ``open()`` raises it (a folder: IsADirectoryError), NotRegularFile otherwise."""
    shown = shown or display_path(path)
    _refuse_special(os.stat(path).st_mode, path, shown)
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    try:
        mode = os.fstat(fd).st_mode
        _refuse_special(mode, path, shown)
        if stat.S_ISDIR(mode):
            raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), str(path))
        os.set_blocking(fd, True)
        return os.fdopen(fd, "rb")
    except BaseException:
        os.close(fd)
        raise


def _refuse_special(mode: int, path, shown: str) -> None:
    kind = special_kind(mode)
    if kind is not None:
        raise NotRegularFile(kind, path, shown)


def read_stream(stream, shown: str, limit_bytes: int | None = None) -> bytes:
    """All of a binary stream, or InputError once it passes the limit (default
    MCAR_MAX_INPUT_MB); never holds more than the limit plus one chunk."""
    if limit_bytes is None:
        limit_bytes = int(input_limit_mb() * 1024 * 1024)
    chunks: list[bytes] = []
    total = 0
    while True:
        chunk = stream.read(min(_CHUNK, limit_bytes + 1 - total))
        if not chunk:
            return b"".join(chunks)
        chunks.append(chunk)
        total += len(chunk)
        if total > limit_bytes:
            raise InputError(f"more than {limit_bytes / 1024 / 1024:g} MB, the input limit; "
                             f"set {MAX_INPUT_MB_ENV} to raise the limit", file=shown)


def read_input(path: str | os.PathLike, shown: str | None = None,
               limit_regular: bool = True) -> bytes:
    """The bytes of a user-named regular file; OSError when it cannot be opened,
    NotRegularFile for a FIFO, socket or device. See read_open."""
    with open_regular(path, shown) as handle:
        return read_open(handle, shown or display_path(path), limit_regular)


def read_open(handle, shown: str, limit_regular: bool = True) -> bytes:
    """The rest of an open binary file or stream. A device, FIFO, socket or pipe (as
    standard input may be) is always read within the limit; a regular file too unless
    ``limit_regular`` is false (then it is read whole: it ends, and its size is the
    caller's choice)."""
    try:
        mode = os.fstat(handle.fileno()).st_mode
    except (AttributeError, OSError, ValueError):  # an in-memory stream (tests): no fd
        mode = 0
    if not stat.S_ISREG(mode):
        return read_stream(handle, shown)
    if not limit_regular:
        return handle.read()
    check_size(os.fstat(handle.fileno()).st_size, shown)  # says the size, when it is known
    return read_stream(handle, shown)  # and still stops if the file grows meanwhile


def read_text_quietly(path: str | os.PathLike) -> str | None:
    """The text of a file scanned for hints (arguments, macro names, lines), or None
    when it cannot be read or is over the limit: whoever loads it reports that."""
    try:
        return read_input(path, shown=str(path)).decode("utf-8", errors="replace")
    except (OSError, InputError):
        return None


def read_head(path: str | os.PathLike, size: int) -> bytes:
    """The first ``size`` bytes of a file (fewer if it is shorter); OSError if unreadable,
    NotRegularFile if not a regular file."""
    with open_regular(Path(path)) as handle:
        return handle.read(size)
