"""What passes between mcar and its drawing process: plain data, framed, bounded.

Each message is a 12-byte prefix (header length, body length; network order), a header of
JSON text, and a body of raw bytes. mcar sends a scene (the float32 corner arrays, one
after the other) and cameras (numbers); the drawing process answers with the size of the
picture and exactly width x height x 4 bytes of RGBA, or with an error's text. Nothing on
either side is unpickled or evaluated: the drawing process works on an untrusted mesh in
C code (llvmpipe, Embree), so mcar takes from it only what :func:`read_reply_header`
accepts and only as many bytes as the picture it asked for.

Importing this module costs nothing: the drawing process starts with it.
"""

from __future__ import annotations

import json
import struct

PREFIX = struct.Struct("!IQ")
# A header is a few numbers or one error message; more is a broken or hostile process.
HEADER_LIMIT = 64 * 1024
# Messages mcar shows from the drawing process are cut to this many characters.
TEXT_LIMIT = 500
# Bytes per triangle corner on the wire: position (3), normal (3), colour (4), float32.
CORNER_BYTES = (3 + 3 + 4) * 4


class WireError(Exception):
    """The drawing process sent something that is not a well-formed answer."""


def message(header: dict, body_length: int = 0) -> bytes:
    """The prefix and header of a message whose body (``body_length`` bytes) follows."""
    text = json.dumps(header, separators=(",", ":")).encode()
    return PREFIX.pack(len(text), body_length) + text


def camera_data(camera) -> dict:
    """A :class:`~mobile_car.render.camera.Camera` as JSON numbers (floats round-trip)."""
    return {"rotation": [float(v) for v in camera.rotation.reshape(-1)],
            "center": [float(v) for v in camera.center.reshape(-1)],
            "half_height": float(camera.half_height), "width": int(camera.width),
            "height": int(camera.height), "depth_near": float(camera.depth_near),
            "depth_far": float(camera.depth_far)}


def printable(text: str) -> str:
    """``text`` cut to TEXT_LIMIT characters, control characters shown escaped."""
    text = text[:TEXT_LIMIT]
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in text)


def read_reply_header(raw: bytes) -> dict:
    """The header of a reply, checked: a JSON object whose ``ok`` is a bool; ``error``
    and ``description``, when there, strings (made printable)."""
    try:
        header = json.loads(raw.decode("utf-8"))
    except (UnicodeDecodeError, ValueError) as exc:
        raise WireError(f"an unreadable answer ({type(exc).__name__})") from None
    if not isinstance(header, dict) or not isinstance(header.get("ok"), bool):
        raise WireError("an answer that is not a drawing process's")
    for key in ("error", "description", "kind", "import_error"):
        if key in header:
            if not isinstance(header[key], str):
                raise WireError(f"an answer whose {key} is not text")
            header[key] = printable(header[key])
    return header


def picture_size(header: dict) -> tuple[int, int]:
    """(width, height) of a successful draw's reply, as positive ints."""
    size = header.get("width"), header.get("height")
    if not all(type(v) is int and v > 0 for v in size):
        raise WireError("an answer without a picture size")
    return size
