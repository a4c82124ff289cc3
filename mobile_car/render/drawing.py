"""Draw in a child process, so that Ctrl-C and SIGTERM end mcar also in the middle of a draw.

A draw is one C call: llvmpipe filling 1.5 million full-screen triangles, or Embree
tracing rays through them, takes many minutes, and Python runs signal handlers only
between bytecodes. So the renderer lives in a drawing process
(:mod:`mobile_car.render.draw_child`), one per renderer kind, started once and kept for
every picture of the process (the GL probe's process becomes it: its context is made while
mcar imports numpy and expands xacro). Here mcar only waits in ``select``, which a signal
interrupts: the handler's KeyboardInterrupt or Terminated unwinds through
:meth:`DrawingProcess.talk`, which kills the child with SIGKILL on the way out.

What comes back is data, checked by :mod:`.wire`: a small JSON header and exactly the
width x height x 4 bytes of the picture that was asked for, nothing else is read. A child
that dies, hangs past a deadline or answers out of turn is killed, and the picture fails
with a located error; the next picture starts a new child.
"""

from __future__ import annotations

import math
import os
import select
import signal
import subprocess
import sys
import threading
import time
import weakref
from pathlib import Path

from ..held_signals import hold_signals, release_signals
from . import wire

# The child's start. Python puts the working folder first on the path of `python -c`
# (and -m): a package under test holding a numpy.py or moderngl.py would run it. So that
# entry goes before any import, and the folder that holds this copy of mobile_car comes
# last, for a mcar run from a source tree.
_START = """
import sys
if sys.path and sys.path[0] in ("", "."):
    del sys.path[0]
sys.path.append(sys.argv[1])
from mobile_car.render.draw_child import main
main()
"""
_PACKAGE_ROOT = Path(__file__).resolve().parents[2]
READ_CHUNK = 1 << 20
STDERR_KEPT = 4096
# Seconds a child that closed its answers gets to exit before it is killed.
EXIT_GRACE = 2.0


class DrawingFailed(Exception):
    """A picture was not drawn: the drawing process's error, or why it ended."""


class _Reply:
    """One answer being read: prefix, header, then the body whose size the header must
    state and ``body_size(header)`` must agree with."""

    def __init__(self, body_size):
        self._body_size = body_size
        self._buffer = bytearray()
        self._need = wire.PREFIX.size
        self._stage = "prefix"
        self._body_length = 0
        self.header: dict | None = None
        self.body: bytearray | None = None

    def wanted(self) -> int:
        return self._need - len(self._buffer)

    def feed(self, data: bytes) -> None:
        self._buffer += data
        while self.body is None and len(self._buffer) >= self._need:
            self._advance()

    def _advance(self) -> None:
        data, self._buffer = self._buffer, bytearray()
        if self._stage == "prefix":
            header_length, self._body_length = wire.PREFIX.unpack(data)
            if header_length > wire.HEADER_LIMIT:
                raise wire.WireError(f"an answer with a header of {header_length} bytes")
            self._stage, self._need = "header", header_length
        elif self._stage == "header":
            self.header = wire.read_reply_header(bytes(data))
            expected = self._body_size(self.header)
            if self._body_length != expected:
                raise wire.WireError(f"an answer of {self._body_length} bytes where "
                                     f"{expected} were expected")
            self._stage, self._need = "body", expected
        else:
            self.body = data


def _kill(popen: subprocess.Popen) -> None:
    if popen.poll() is None:
        try:
            popen.kill()
        except ProcessLookupError:
            pass
    popen.wait()
    for stream in (popen.stdin, popen.stdout, popen.stderr):
        if stream is not None:
            stream.close()


class DrawingProcess:
    """A started drawing process of ``mode`` (gl or raycast); raises OSError if it cannot
    be started. Killed when garbage-collected, at exit, and on any failure or signal."""

    def __init__(self, mode: str):
        self.mode = mode
        self.description: str | None = None
        self._stderr = bytearray()
        env = dict(os.environ)
        env.setdefault("EGL_LOG_LEVEL", "fatal")  # Mesa's own chatter is not our message
        held = hold_signals()  # a signal now would leave a child nobody knows about
        try:
            self._popen = subprocess.Popen(
                [sys.executable, "-c", _START, str(_PACKAGE_ROOT), mode],
                stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                env=env)
        except BaseException:
            release_signals(held)
            raise
        self._finalizer = weakref.finalize(self, _kill, self._popen)
        try:
            release_signals(held)
        except BaseException:
            self.kill()
            raise
        os.set_blocking(self._popen.stdin.fileno(), False)
        os.set_blocking(self._popen.stderr.fileno(), False)
        self._err: int | None = self._popen.stderr.fileno()

    @property
    def alive(self) -> bool:
        return self._finalizer.alive

    def kill(self) -> None:
        self._finalizer()

    def first_answer(self, timeout: float) -> dict:
        """The child's word once its renderer is made: ``{"ok": True, "description": ...}``
        or ``{"ok": False, "error": ..., "kind": "import" | "other"}`` (it has then ended).
        Raises TimeoutError (the child is killed) or DrawingFailed (it died)."""
        header, _body = self.talk([], timeout=timeout)
        if header["ok"]:
            self.description = header.get("description") or self.mode
        else:
            self.kill()
        return header

    def talk(self, outgoing: list, body_size=lambda header: 0,
             timeout: float | None = None) -> tuple[dict, bytearray]:
        """Send ``outgoing`` (bytes-like objects), read one answer. The child is killed on
        anything but a well-formed answer: a signal here, a timeout, its death, a protocol
        error (raised as DrawingFailed)."""
        if not self.alive:
            raise DrawingFailed("the drawing process has ended")
        pending = [memoryview(chunk).cast("B") for chunk in outgoing if len(chunk)]
        reply = _Reply(body_size)
        deadline = None if timeout is None else time.monotonic() + timeout
        try:
            while reply.body is None:
                self._step(pending, reply, deadline)
            if pending:  # an answer to a question not yet asked: out of step for good
                raise wire.WireError("an answer before it had read the request")
        except wire.WireError as error:
            self.kill()
            raise DrawingFailed(f"the drawing process sent {error}") from None
        except BaseException:  # a signal, a timeout, the child's end: it must not outlive this
            self.kill()
            raise
        return reply.header, reply.body

    def _step(self, pending: list, reply: _Reply, deadline: float | None) -> None:
        """Wait for the child (a signal interrupts the wait), then move what can move:
        its stderr, the request, the answer. poll, not select: mcar may hold fds past 1024."""
        answers, requests = self._popen.stdout.fileno(), self._popen.stdin.fileno()
        poller = select.poll()
        poller.register(answers, select.POLLIN)
        if self._err is not None:
            poller.register(self._err, select.POLLIN)
        if pending:
            poller.register(requests, select.POLLOUT)
        wait = None if deadline is None else max(0, math.ceil(
            (deadline - time.monotonic()) * 1000))
        ready = dict(poller.poll(wait))
        if not ready:
            raise TimeoutError
        if self._err is not None and self._err in ready:
            self._drain_stderr()
        if requests in ready and pending:
            try:
                sent = os.write(requests, pending[0][:READ_CHUNK])
            except BlockingIOError:
                sent = 0
            except (BrokenPipeError, ConnectionResetError):
                raise DrawingFailed(self._end_reason()) from None
            pending[0] = pending[0][sent:]
            if not pending[0]:
                pending.pop(0)
        if answers in ready:
            data = os.read(answers, min(reply.wanted(), READ_CHUNK))
            if not data:
                raise DrawingFailed(self._end_reason())
            reply.feed(data)

    def _drain_stderr(self) -> None:
        """Keep the last STDERR_KEPT bytes the child wrote to stderr; None once it closed."""
        try:
            data = os.read(self._err, READ_CHUNK)
        except BlockingIOError:
            return
        if not data:
            self._err = None
            return
        self._stderr = (self._stderr + data)[-STDERR_KEPT:]

    def _end_reason(self) -> str:
        """Why the child stopped answering: its exit status and last line on stderr."""
        try:
            code = self._popen.wait(timeout=EXIT_GRACE)
        except subprocess.TimeoutExpired:  # it closed its answers and lives on: no more
            self._popen.kill()
            code = self._popen.wait()
        for _ in range(STDERR_KEPT // 512 + 1):  # what it said last, without waiting
            if self._err is None:
                break
            self._drain_stderr()
        if code is not None and code < 0:
            try:
                how = f"killed by {signal.Signals(-code).name}"
            except ValueError:
                how = f"killed by signal {-code}"
        else:
            how = f"exit status {code}"
        lines = [line.strip() for line in self._stderr.decode("utf-8", "replace").splitlines()
                 if line.strip()]
        said = f": {wire.printable(lines[-1])}" if lines else ""
        return f"the drawing process ended unexpectedly ({how}){said}"


class RemoteRenderer:
    """The renderer interface (``name``, ``description``, ``draw``) over a drawing
    process. A scene is sent once for all the views drawn of it; a process killed by a
    signal or a failure is replaced by a new one at the next picture."""

    def __init__(self, process: DrawingProcess, start_timeout: float):
        self.name = process.mode
        self.description = process.description
        self._process = process
        self._start_timeout = start_timeout
        self._sent = None  # a weak reference to the scene the child holds
        self._turn = threading.Lock()  # one conversation at a time: answers come in order

    def _running(self) -> DrawingProcess:
        if not self._process.alive:
            self._sent = None
            try:
                process = DrawingProcess(self.name)
            except OSError as exc:
                raise DrawingFailed(f"cannot start a drawing process: {exc}") from None
            try:
                answer = process.first_answer(self._start_timeout)
            except TimeoutError:
                raise DrawingFailed("a new drawing process did not start within "
                                    f"{self._start_timeout:g} s") from None
            if not answer["ok"]:
                raise DrawingFailed(f"a new drawing process failed: {answer.get('error')}")
            self._process = process
        return self._process

    def draw(self, scene, camera):
        """The model alone, (H, W, 4) uint8, colour premultiplied by coverage."""
        with self._turn:
            return self._draw(scene, camera)

    def _draw(self, scene, camera):
        import numpy as np

        process = self._running()
        outgoing = []
        if self._sent is None or self._sent() is not scene:
            self._sent = None
            arrays = [np.ascontiguousarray(values, dtype=np.float32)
                      for values in (scene.positions, scene.normals, scene.colors)]
            outgoing += [wire.message({"op": "scene", "corners": len(arrays[0])},
                                      sum(array.nbytes for array in arrays)), *arrays]
        outgoing.append(wire.message({"op": "draw", "camera": wire.camera_data(camera)}))
        expected = (camera.width, camera.height)

        def body_size(header: dict) -> int:
            if not header["ok"]:
                return 0
            if wire.picture_size(header) != expected:
                raise wire.WireError(f"a picture of {wire.picture_size(header)} pixels "
                                     f"where {expected} were asked for")
            return camera.width * camera.height * 4

        try:
            header, body = process.talk(outgoing, body_size)
        except TimeoutError:  # (no deadline is given: cannot happen)
            raise DrawingFailed("the drawing process did not answer") from None
        try:
            self._sent = weakref.ref(scene)
        except TypeError:  # a scene-like object without weak references: sent every time
            self._sent = None
        if not header["ok"]:
            raise DrawingFailed(header.get("error") or "the drawing process failed")
        return np.frombuffer(body, dtype=np.uint8).reshape(camera.height, camera.width, 4)

    def close(self) -> None:
        self._process.kill()
