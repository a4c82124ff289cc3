"""Reading an input without trusting its size: at most the limit and one byte more.

A file's ``st_size`` says nothing about a device (``/dev/zero``), a FIFO or standard
input, which may never end: every byte stream a user names is read here, in chunks,
and refused with a one-line InputError once it passes ``MCAR_MAX_INPUT_MB``. Regular
files may be read whole where a command promises no limit (``mcar check``): they end.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from ..errors import InputError
from .inputs import MAX_INPUT_MB_ENV, check_size, display_path, input_limit_mb

_CHUNK = 1 << 20


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
    """The bytes of a user-named file; OSError when it cannot be opened. See read_open."""
    with open(path, "rb") as handle:
        return read_open(handle, shown or display_path(path), limit_regular)


def read_open(handle, shown: str, limit_regular: bool = True) -> bytes:
    """The rest of an open binary file or stream. A device, FIFO, socket or pipe is
    always read within the limit; a regular file too unless ``limit_regular`` is false
    (then it is read whole: it ends, and its size is the caller's choice)."""
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
    """The first ``size`` bytes of a file (fewer if it is shorter); OSError if unreadable."""
    with open(Path(path), "rb") as handle:
        return handle.read(size)
