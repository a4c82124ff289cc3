"""The drawing process: one renderer (OpenGL or ray casting) drawing what mcar sends it.

Started by :mod:`mobile_car.render.drawing`, whose ``python -c`` calls :func:`main` with
the renderer's kind (gl or raycast) as the last argument. A draw is one C call (llvmpipe
rasterising, Embree tracing) that no signal interrupts, and a hostile mesh makes it last
for minutes; in this process mcar can stop it at once, with SIGKILL, while its own
process stays responsive to Ctrl-C and SIGTERM. The protocol is :mod:`.wire`: requests
on stdin, answers on the stdout it was started with; anything a library prints goes to
stderr instead.

Ctrl-C from the terminal reaches this process too: it is ignored here, because mcar
decides (and kills this process). SIGTERM and SIGHUP keep their default, death; so does
mcar's own death (``PR_SET_PDEATHSIG``).
"""

from __future__ import annotations

import io
import os
import signal
import sys
from dataclasses import dataclass

from . import wire

_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)


@dataclass
class _Corners:
    """The scene as the renderers read it: corner arrays (N*3 rows) and a triangle count."""

    positions: object
    normals: object
    colors: object

    @property
    def triangle_count(self) -> int:
        return len(self.positions) // 3


def describe(exc: BaseException) -> str:
    """An exception as the last line of its traceback would show it."""
    kind = type(exc)
    name = kind.__qualname__ if kind.__module__ == "builtins" else \
        f"{kind.__module__}.{kind.__qualname__}"
    lines = [line.strip() for line in str(exc).splitlines() if line.strip()]
    return f"{name}: {lines[-1]}" if lines else name


def _open(mode: str):
    if mode == "gl":
        from .gl import GLRenderer

        return GLRenderer()
    from .raycast import RaycastRenderer

    return RaycastRenderer()


def _read_exactly(stream, count: int) -> bytearray | None:
    """``count`` bytes from ``stream``; None at its end (mcar has gone)."""
    data = bytearray(count)
    view = memoryview(data)
    while view:
        got = stream.readinto(view)
        if not got:
            return None
        view = view[got:]
    return data


def _receive(stream):
    prefix = _read_exactly(stream, wire.PREFIX.size)
    if prefix is None:
        return None
    header_length, body_length = wire.PREFIX.unpack(prefix)
    header = _read_exactly(stream, header_length)
    body = _read_exactly(stream, body_length)
    if header is None or body is None:
        return None
    import json

    return json.loads(header.decode()), body


def _send(fd: int, header: dict, body=b"") -> None:
    view = memoryview(wire.message(header, len(body)) + bytes(body))
    while view:
        view = view[os.write(fd, view):]


def _scene(header: dict, body: bytearray) -> _Corners:
    import numpy as np

    count = int(header["corners"])
    if len(body) != count * wire.CORNER_BYTES:
        raise ValueError(f"a scene of {count} corners in {len(body)} bytes")
    values = np.frombuffer(body, dtype=np.float32)
    positions, normals, colors = np.split(values, [count * 3, count * 6])
    return _Corners(positions.reshape(count, 3), normals.reshape(count, 3),
                    colors.reshape(count, 4))


def _camera(data: dict):
    import numpy as np

    from .camera import Camera

    return Camera(rotation=np.array(data["rotation"], dtype=float).reshape(3, 3),
                  center=np.array(data["center"], dtype=float).reshape(3),
                  half_height=float(data["half_height"]), width=int(data["width"]),
                  height=int(data["height"]), depth_near=float(data["depth_near"]),
                  depth_far=float(data["depth_far"]))


def _draw(renderer, scene, header: dict) -> tuple[dict, bytes]:
    import numpy as np

    camera = _camera(header["camera"])
    if isinstance(scene, BaseException):  # the scene could not be taken in
        raise scene
    image = renderer.draw(scene, camera)
    if image.shape != (camera.height, camera.width, 4):
        raise ValueError(f"the renderer drew a picture of shape {image.shape}")
    pixels = np.ascontiguousarray(image, dtype=np.uint8)
    return {"ok": True, "width": camera.width, "height": camera.height}, pixels.tobytes()


def serve(mode: str, requests, replies: int) -> int:
    try:
        renderer = _open(mode)
    except BaseException as exc:  # noqa: BLE001 - every failure is an answer to mcar
        kind = "import" if isinstance(exc, ImportError) else "other"
        _send(replies, {"ok": False, "error": describe(exc), "kind": kind,
                        "import_error": str(exc) if kind == "import" else ""})
        return 1
    _send(replies, {"ok": True, "description": renderer.description})
    scene = None
    while True:
        request = _receive(requests)
        if request is None:
            return 0
        header, body = request
        if header.get("op") == "scene":
            try:
                scene = _scene(header, body)
            except Exception as exc:  # noqa: BLE001 - said at the next draw
                scene = exc
            continue
        try:
            answer, pixels = _draw(renderer, scene, header)
        except Exception as exc:  # noqa: BLE001 - the robot's error, not this process's end
            answer, pixels = {"ok": False, "error": describe(exc)}, b""
        _send(replies, answer, pixels)


def main() -> int:
    signal.pthread_sigmask(signal.SIG_UNBLOCK, _SIGNALS)  # mcar held them over the spawn
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    for signum in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(signum, signal.SIG_DFL)
    from ..expand.sandbox import die_with_parent

    die_with_parent()
    replies = os.dup(1)
    os.dup2(2, 1)  # what a library prints must not land among the answers
    requests = io.FileIO(0, closefd=False)
    try:
        status = serve(sys.argv[-1], requests, replies)
    except (BrokenPipeError, ConnectionResetError):
        status = 0  # mcar has gone
    sys.stderr.flush()
    os._exit(status)  # no interpreter or driver teardown: nothing here needs saving
