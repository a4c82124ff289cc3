"""Run a function in a forked child with a time and memory limit.

xacro evaluates ``${...}`` with Python's ``eval``: ``${9**9**9}`` computes for ever inside one
C call that no signal interrupts, and a runaway document can eat all memory. A forked child
(cheap on Linux: nothing is re-imported) runs the work under ``RLIMIT_AS``; the parent waits
at most ``timeout`` seconds, then kills it. The child is confined first (:mod:`.sandbox`): a
xacro is code. Its result, or its error, comes back through a pipe as data only, in the
checked frame of :mod:`.wire` (never a pickle: the xacro can write to that pipe itself);
the parent reads at most the frame's bound and kills a child that sends more.

The child forks even while other threads run (render finishes pictures on a worker
thread): it touches no lock those threads take (it only evaluates xacro and writes a
pipe), and were it ever to hang on one, the timeout still ends it. Only where fork does
not exist does the function run in this process, unguarded and unconfined.
"""

from __future__ import annotations

import gc
import os
import resource
import select
import signal
import time
from collections.abc import Callable
from pathlib import Path

from ..held_signals import hold_signals, release_signals
from ..values import Value
from . import wire

TIMEOUT_ENV = "MCAR_XACRO_TIMEOUT"
MEMORY_ENV = "MCAR_XACRO_MEMORY_MB"
OUTPUT_ENV = "MCAR_XACRO_OUTPUT_MB"
DEFAULT_TIMEOUT = 60.0
DEFAULT_MEMORY_MB = 4096
DEFAULT_OUTPUT_MB = 256  # PR2, the largest robot we know, expands to about 1 MB


class Codec(Value):
    """How a value crosses the pipe: ``pack`` (in the child) makes its frame, ``unpack``
    (in the parent) makes the value again from the header and body of a well-formed
    ``ok`` frame, checking every field, or raises :class:`wire.MalformedResult`."""

    _fields = __slots__ = ("pack", "unpack")
    pack: Callable[[object], bytes]
    unpack: Callable[[dict, bytes], object]

    def __init__(self, pack: Callable[[object], bytes], unpack: Callable[[dict, bytes], object]):
        self._set(pack, unpack)


def _unpack_json(header: dict, body: bytes):
    wire.expect_fields(header, "header", ok="bool", value="json")
    if body:
        raise wire.MalformedResult("a plain value came with a body")
    return header["value"]


# Plain JSON data (numbers, strings, lists, objects): for small helpers and tests.
JSON_VALUE = Codec(lambda value: wire.frame({"ok": True, "value": value}), _unpack_json)


class Timeout(Exception):
    """The child ran out of time; ``seconds`` is the limit."""

    def __init__(self, seconds: float):
        super().__init__(seconds)
        self.seconds = seconds


class OutOfMemory(Exception):
    def __init__(self, megabytes: int):
        super().__init__(megabytes)
        self.megabytes = megabytes


class Ended(Exception):
    """The child ended before sending a result, not by the memory limit: ``how`` says
    ("it was ended by SIGTERM", "it exited with status 0")."""

    def __init__(self, how: str):
        super().__init__(how)
        self.how = how


def run_isolated(func, *args, read_roots: list[Path] = (), codec: Codec = JSON_VALUE):
    """func(*args) in a guarded child that may read only below ``read_roots`` (where the
    kernel can enforce it), its value sent back through ``codec``. Raises the McarError
    func raised (of the kinds :data:`wire.ERROR_KINDS` allows), wire.ChildCrashed for any
    other exception, Timeout (the child has neither sent its result nor exited within
    ``MCAR_XACRO_TIMEOUT``), OutOfMemory, Ended (it died without a word, not of memory),
    or wire.MalformedResult when what came back is not a well-formed result within
    ``MCAR_XACRO_OUTPUT_MB``."""
    from . import sandbox

    if not hasattr(os, "fork"):
        sandbox.note_unconfined("no fork() on this system")
        return func(*args)
    from ..settings import env_number

    timeout = env_number(TIMEOUT_ENV, DEFAULT_TIMEOUT, 0.1, 86400, "seconds")
    memory_mb = int(env_number(MEMORY_ENV, DEFAULT_MEMORY_MB, 64, 1e7, "MB"))
    output_mb = env_number(OUTPUT_ENV, DEFAULT_OUTPUT_MB, 0.001, 1e6, "MB")
    most = wire.PREFIX_SIZE + wire.MAX_HEADER_BYTES + int(output_mb * 1024 * 1024)
    confined_roots = sandbox.prepare(list(read_roots))
    read_fd, write_fd = os.pipe()
    parent = os.getpid()  # the child must not outlive it: see sandbox.die_with_parent
    held = hold_signals()  # not inside fork's after-fork callbacks: see held_signals
    try:
        pid = os.fork()
    except BaseException:
        release_signals(held)
        raise
    if pid == 0:  # the child: do the work, send (ok, value), leave without cleanup
        release_signals(held)
        os.close(read_fd)
        # The embedding program's garbage-collector hooks are not the child's: a Dask
        # worker's reads memory through psutil at each collection, which the sandbox
        # refuses, and Python prints that failure into the stderr xacro's warnings are
        # read from (a --strict check then fails a good robot).
        gc.callbacks.clear()
        # The child lives for one expansion, whose DOM is made of young objects by the
        # hundred thousand that stay alive to the end: Python's default, a collection
        # every 700 new objects, runs hundreds of passes that free next to nothing (a
        # tenth of PR2's expansion). Every 100,000: garbage is still collected, within
        # RLIMIT_AS as before.
        gc.set_threshold(100_000, 10, 10)
        status = 0
        try:
            # The limit is on what xacro adds: a fork shares the parent's address space,
            # which in a large program (a Dask worker, the viewer, a test run with USD,
            # MuJoCo and their thread pools loaded) may itself exceed any fixed bound.
            limit = _address_space() + memory_mb * 1024 * 1024
            # Under a lower hard limit (prlimit, a CI runner's ulimit) keep that one:
            # raising it is refused, and the child would die without a word.
            hard = resource.getrlimit(resource.RLIMIT_AS)[1]
            if hard != resource.RLIM_INFINITY:
                limit = min(limit, hard)
            resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
            try:
                if confined_roots is not None:
                    sandbox.confine(confined_roots, keep_fd=write_fd, parent=parent)
                data = codec.pack(func(*args))
            except BaseException as error:  # noqa: BLE001 - everything goes to the parent
                data = wire.error_frame(error)
            view = memoryview(data)  # os.write: the sandbox refuses opening a file to write
            while view:
                view = view[os.write(write_fd, view):]
        except BaseException:
            status = 1
        finally:
            os._exit(status)
    os.close(write_fd)
    deadline = time.monotonic() + timeout
    try:
        release_signals(held)  # a signal held over the fork lands here, and kills the child
        data = _read_result(read_fd, deadline, timeout, most, output_mb)
        # The pipe's end is not the child's: it may have closed the pipe itself, then
        # stopped (SIGSTOP) or spun; the time limit covers its exit too.
        status = _exit_status(pid, deadline)
        if status is None:
            raise Timeout(timeout)
    except BaseException:
        _kill(pid)  # a timeout, a bad frame, Ctrl-C: the child must not outlive us
        raise
    if not data:
        raise _without_a_word(status, memory_mb)
    header, body = wire.unframe(data)
    if not header["ok"]:
        try:
            wire.raise_error(header)
        except wire.ChildOutOfMemory:
            raise OutOfMemory(memory_mb) from None
    return codec.unpack(header, body)


# How a child under RLIMIT_AS dies when even reporting the MemoryError fails: malloc's
# abort, a stack that cannot grow, the kernel's own out-of-memory killer.
_MEMORY_DEATHS = (signal.SIGKILL, signal.SIGSEGV, signal.SIGABRT, signal.SIGBUS)


def _without_a_word(status: int, memory_mb: int) -> Exception:
    """What a child that sent nothing died of: most likely the memory limit, unless its
    exit says otherwise (a xacro may kill itself, or leave with os._exit)."""
    if os.WIFSIGNALED(status):
        number = os.WTERMSIG(status)
        if number in _MEMORY_DEATHS:
            return OutOfMemory(memory_mb)
        try:
            name = signal.Signals(number).name
        except ValueError:
            name = f"signal {number}"
        return Ended(f"it was ended by {name}")
    return Ended(f"it exited with status {os.WEXITSTATUS(status)}")


def _address_space() -> int:
    """This process's address space in bytes, what RLIMIT_AS counts (0 where /proc
    cannot tell: the limit is then the bound alone, as it was)."""
    try:
        with open("/proc/self/statm", "rb") as statm:
            return int(statm.read().split()[0]) * resource.getpagesize()
    except (OSError, ValueError, IndexError):
        return 0


def _read_result(read_fd: int, deadline: float, timeout: float, most: int,
                 output_mb: float) -> bytes:
    """Everything the child writes until it closes the pipe, read before ``deadline``;
    stops (MalformedResult) at the first byte that cannot belong to a frame of at most
    ``most`` bytes, so a child that sends garbage or 10 GB costs no more than that."""
    data = bytearray()
    expected = None
    with os.fdopen(read_fd, "rb") as pipe:
        while True:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([pipe], [], [], left)[0]:
                raise Timeout(timeout)
            chunk = os.read(pipe.fileno(), 1 << 20)
            if not chunk:
                return bytes(data)
            data += chunk
            if expected is None:
                expected = wire.declared_size(bytes(data[:wire.PREFIX_SIZE]))
                if expected is not None and expected > most:
                    raise wire.MalformedResult(
                        f"it declares {expected / 1024 / 1024:.1f} MB, more than "
                        f"{OUTPUT_ENV}={output_mb:g}")
            if expected is not None and len(data) > expected:
                raise wire.MalformedResult("more bytes followed the result")


def _exit_status(pid: int, deadline: float) -> int | None:
    """The child's wait status once it has exited, or None when ``deadline`` passes
    first (the child is then still there, to be killed)."""
    try:
        watch = os.pidfd_open(pid)  # readable once the child has exited
    except (AttributeError, OSError):  # no pidfd (Linux < 5.3): ask every few ms
        watch = None
    try:
        pause = 0.001
        while True:
            done, status = os.waitpid(pid, os.WNOHANG)
            if done:
                return status
            left = deadline - time.monotonic()
            if left <= 0:
                return None
            if watch is not None:
                select.select([watch], [], [], left)
            else:
                time.sleep(min(pause, left))
                pause = min(pause * 2, 0.05)
    finally:
        if watch is not None:
            os.close(watch)


def _kill(pid: int) -> None:
    try:
        os.kill(pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    _reap(pid)


def _reap(pid: int) -> None:
    try:
        os.waitpid(pid, 0)
    except ChildProcessError:
        pass
