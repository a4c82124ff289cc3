"""Writing to stdout and stderr when they can fail: a full disk, a closed pipe, a bad fd.

Every write to stdout goes through :func:`stdout_writes`, which turns a failure into one
``mcar: error: cannot write <stdout>: REASON`` line (exit 2), or, when the reader of a pipe
has gone (``mcar tree | head -1``), into :class:`ReaderGone`: the reader wanted no more, so
the run ends quietly with exit 0. stderr has no one left to tell: a failure there ends the
run with exit 2 and no word. :func:`exit_quietly` then makes sure that the interpreter's
final flush cannot fail again and print "Exception ignored ... BrokenPipeError".
A text too large to hold (a deep tree's: hundreds of megabytes of indentation) is written
as it is made, by :func:`write_lines`, and fails the same way wherever it stops.
"""

from __future__ import annotations

import contextlib
import errno
import os
import sys

from mobile_car.errors import InputError


class ReaderGone(Exception):
    """stdout is a pipe whose reader has closed it: stop writing, exit 0."""


@contextlib.contextmanager
def stdout_writes():
    """Around code that writes to stdout: a failed write becomes a one-line error."""
    try:
        yield
    except BrokenPipeError:
        raise ReaderGone() from None
    except OSError as exc:
        raise InputError(f"cannot write <stdout>: {exc.strerror or exc}") from None


def write(data: bytes) -> None:
    """Bytes to stdout, flushed, so that a failure shows here and not at exit."""
    with stdout_writes():
        _refuse_closed_stdout()
        sys.stdout.buffer.write(data)
        sys.stdout.buffer.flush()


# What one gathered write takes at most: Linux refuses more than 1,024 buffers in one
# os.writev (IOV_MAX), and a chunk's lines are held until written, so bytes are capped too.
CHUNK_LINES = 1024
CHUNK_BYTES = 1 << 20


def write_lines(lines) -> None:
    """Bytes to stdout as they come from the iterable ``lines`` (each usually one line of
    a text too large to hold: a deep tree's), gathered into chunks of at most
    :data:`CHUNK_LINES` lines or about :data:`CHUNK_BYTES`, each one ``os.writev`` straight
    to the file descriptor (no copy joins them), else joined per chunk. What came before
    on ``sys.stdout`` is flushed first, so the order holds."""
    with stdout_writes():
        _refuse_closed_stdout()
        sys.stdout.flush()  # its text layer too: what was printed comes first
        out = sys.stdout.buffer
        try:
            fd = out.fileno()
        except (AttributeError, OSError, ValueError):  # io.UnsupportedOperation: CliRunner
            fd = None
        chunk, size = [], 0
        for line in lines:
            chunk.append(line)
            size += len(line)
            if len(chunk) >= CHUNK_LINES or size >= CHUNK_BYTES:
                _write_chunk(out, fd, chunk)
                chunk, size = [], 0
        if chunk:
            _write_chunk(out, fd, chunk)
        out.flush()


def _write_chunk(out, fd: int | None, chunk: list) -> None:
    if fd is None or not hasattr(os, "writev"):
        out.write(b"".join(chunk))
        return
    while chunk:
        written = os.writev(fd, chunk)
        done = 0
        while done < len(chunk) and written >= len(chunk[done]):
            written -= len(chunk[done])
            done += 1
        chunk = chunk[done:]
        if chunk and written:  # a partial write stopped inside this buffer
            chunk[0] = memoryview(chunk[0])[written:]


def echo(text: str = "", nl: bool = True) -> None:
    """A line of text to stdout (click.echo: the locale's encoding, flushed)."""
    import click

    with stdout_writes():
        _refuse_closed_stdout()
        click.echo(text, nl=nl)


def flush() -> None:
    """Whatever is still buffered for stdout, written now while it can be reported."""
    with stdout_writes():
        if sys.stdout is not None:
            sys.stdout.flush()


def say(text: str) -> None:
    """One line on stderr, if stderr can still take it."""
    import click

    try:
        click.echo(text, err=True)
    except OSError:  # stderr full or closed: there is nowhere left to say it
        pass


def _refuse_closed_stdout() -> None:
    if sys.stdout is None:  # mcar was started with fd 1 closed (`>&-`)
        raise OSError(errno.EBADF, os.strerror(errno.EBADF))


def open_closed_standard_fds() -> None:
    """Put /dev/null on fds 0, 1 and 2 when mcar was started with one closed (`2>&-`):
    else the first file mcar opens would get that number, and a message meant for stderr
    would land in an output. Messages for a closed stderr are dropped (the exit code still
    tells); output for a closed stdout is refused (see write)."""
    for fd in (0, 1, 2):
        try:
            os.fstat(fd)
        except OSError:
            devnull = os.open(os.devnull, os.O_RDWR)
            if devnull != fd:
                os.dup2(devnull, fd)
                os.close(devnull)
    if sys.stderr is None:
        sys.stderr = open(2, "w", closefd=False)  # noqa: SIM115 - lives as long as mcar


def exit_quietly(code: int):
    """sys.exit(code), after pointing a stream that cannot be flushed at /dev/null so
    that the interpreter's last flush neither fails nor prints a complaint."""
    for stream in (sys.stdout, sys.stderr):
        try:
            if stream is not None:
                stream.flush()
        except (OSError, ValueError):
            _point_at_devnull(stream)
    sys.exit(code)


def _point_at_devnull(stream) -> None:
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, stream.fileno())
        os.close(devnull)
    except (OSError, ValueError):  # no fd behind the stream: nothing to point anywhere
        pass
