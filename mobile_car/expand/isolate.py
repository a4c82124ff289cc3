"""Run a function in a forked child with a time and memory limit.

xacro evaluates ``${...}`` with Python's ``eval``: ``${9**9**9}`` computes for ever inside one
C call that no signal interrupts, and a runaway document can eat all memory. A forked child
(cheap on Linux: nothing is re-imported) runs the work under ``RLIMIT_AS``; the parent waits
at most ``timeout`` seconds, then kills it. The result, or the exception, comes back pickled
through a pipe. The child is confined first (:mod:`.sandbox`): a xacro is code.

The child forks even while other threads run (render finishes pictures on a worker
thread): it touches no lock those threads take (it only evaluates xacro and writes a
pipe), and were it ever to hang on one, the timeout still ends it. Only where fork does
not exist does the function run in this process, unguarded and unconfined.
"""

from __future__ import annotations

import gc
import os
import pickle
import resource
import select
import signal
import time
from pathlib import Path

from ..held_signals import hold_signals, release_signals

TIMEOUT_ENV = "MCAR_XACRO_TIMEOUT"
MEMORY_ENV = "MCAR_XACRO_MEMORY_MB"
DEFAULT_TIMEOUT = 60.0
DEFAULT_MEMORY_MB = 4096


class Timeout(Exception):
    """The child ran out of time; ``seconds`` is the limit."""

    def __init__(self, seconds: float):
        super().__init__(seconds)
        self.seconds = seconds


class OutOfMemory(Exception):
    def __init__(self, megabytes: int):
        super().__init__(megabytes)
        self.megabytes = megabytes



def run_isolated(func, *args, read_roots: list[Path] = ()):
    """func(*args) in a guarded child that may read only below ``read_roots`` (where the
    kernel can enforce it); raises what func raised, Timeout or OutOfMemory."""
    from . import sandbox

    if not hasattr(os, "fork"):
        sandbox.note_unconfined("no fork() on this system")
        return func(*args)
    from ..settings import env_number

    timeout = env_number(TIMEOUT_ENV, DEFAULT_TIMEOUT, 0.1, 86400, "seconds")
    memory_mb = int(env_number(MEMORY_ENV, DEFAULT_MEMORY_MB, 64, 1e7, "MB"))
    confined_roots = sandbox.prepare(list(read_roots))
    read_fd, write_fd = os.pipe()
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
        status = 0
        try:
            limit = memory_mb * 1024 * 1024
            # Under a lower hard limit (prlimit, a CI runner's ulimit) keep that one:
            # raising it is refused, and the child would die without a word.
            hard = resource.getrlimit(resource.RLIMIT_AS)[1]
            if hard != resource.RLIM_INFINITY:
                limit = min(limit, hard)
            resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
            try:
                if confined_roots is not None:
                    sandbox.confine(confined_roots, keep_fd=write_fd)
                payload = (True, func(*args))
            except MemoryError:
                payload = (False, OutOfMemory(memory_mb))
            except BaseException as error:  # noqa: BLE001 - everything goes to the parent
                payload = (False, error)
            try:
                data = pickle.dumps(payload)
            except Exception as error:  # an unpicklable exception: send its text
                data = pickle.dumps((False, RuntimeError(f"{type(error).__name__}: {error}")))
            view = memoryview(data)  # os.write: the sandbox refuses opening a file to write
            while view:
                view = view[os.write(write_fd, view):]
        except BaseException:
            status = 1
        finally:
            os._exit(status)
    os.close(write_fd)
    chunks = []
    deadline = time.monotonic() + timeout
    try:
        release_signals(held)  # a signal held over the fork lands here, and kills the child
        with os.fdopen(read_fd, "rb") as pipe:
            while True:
                left = deadline - time.monotonic()
                if left <= 0 or not select.select([pipe], [], [], left)[0]:
                    raise Timeout(timeout)
                chunk = os.read(pipe.fileno(), 1 << 20)
                if not chunk:
                    break
                chunks.append(chunk)
    except BaseException:
        _kill(pid)  # a timeout, or Ctrl-C in the parent: the child must not outlive us
        raise
    _reap(pid)
    if not chunks:  # the child died without a word: most likely the memory limit
        raise OutOfMemory(memory_mb)
    ok, value = pickle.loads(b"".join(chunks))
    if ok:
        return value
    raise value


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
