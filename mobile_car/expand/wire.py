"""What the sandboxed xacro child may send back: data only, in one checked frame.

The child runs a xacro, and a xacro is code: whatever it evaluates can find the result pipe
(an open descriptor in the child) and write anything to it. So nothing read from that pipe
may construct an object or call a function in the parent (``pickle`` would do both: a
forged pickle runs any command, outside every sandbox layer). A frame is::

    MAGIC | header length (4 bytes, big-endian) | body length (8 bytes) | header | body

The header is a small JSON object checked against a fixed schema (``ok``, and either the
result's lists of strings or an error of an allowed kind with message, file, line and
details); the body is the URDF as UTF-8 bytes, never parsed here. Every length is bounded
before it is trusted, and the frame must end exactly where the pipe does. Anything else is
a :class:`MalformedResult` whose text says what was wrong; nothing of it is used.

A genuine child and a forged one look alike when the frame is well-formed: that is fine,
as the xacro could have produced that URDF anyway. What a forged frame must never do is
run code, take memory without bound, or name files the child was not allowed to read
(the caller checks the ``deps`` against the sandbox's roots, see :mod:`.xacro_build`).
"""

from __future__ import annotations

import json
import struct

from ..errors import BuildError, InputError, McarError, PackageNotFoundError, UsageError

MAGIC = b"MCAR-XACRO-RESULT/1\n"
_LENGTHS = struct.Struct(">IQ")
PREFIX_SIZE = len(MAGIC) + _LENGTHS.size
MAX_HEADER_BYTES = 8 * 1024 * 1024  # 100,000 included files with long paths fit
MAX_STRING_CHARS = 64 * 1024  # a path, a warning, a message or a stack line
MAX_LIST_ITEMS = 100_000

# The only errors the child can raise in the parent, by name: never a class it names.
ERROR_KINDS: dict[str, type[McarError]] = {
    cls.__name__: cls for cls in (BuildError, UsageError, InputError, PackageNotFoundError)}
OUT_OF_MEMORY = "out_of_memory"
CRASHED = "crashed"  # any other exception: a bug of ours, sent as its type's name and text


class MalformedResult(Exception):
    """The child's frame broke the format; ``reason`` says how (never a traceback)."""

    def __init__(self, reason: str):
        super().__init__(reason)
        self.reason = reason


class ChildOutOfMemory(Exception):
    """The child reported a MemoryError."""


class ChildCrashed(RuntimeError):
    """An exception the child could only report by name (a bug, not a bad input)."""


# -- the child's side ---------------------------------------------------------------------

def frame(header: dict, body: bytes = b"") -> bytes:
    data = json.dumps(header, ensure_ascii=True, allow_nan=False).encode("ascii")
    return MAGIC + _LENGTHS.pack(len(data), len(body)) + data + body


def error_frame(error: BaseException) -> bytes:
    """The frame for an exception raised in the child."""
    if isinstance(error, MemoryError):
        return frame({"ok": False, "error": {"kind": OUT_OF_MEMORY}})
    if type(error).__name__ in ERROR_KINDS and isinstance(error, McarError):
        kind = type(error).__name__
    elif isinstance(error, McarError):  # a subclass: sent as its nearest allowed kind
        kind = next((name for name, cls in ERROR_KINDS.items() if isinstance(error, cls)),
                    CRASHED)
    else:
        kind = CRASHED
    if kind == CRASHED:
        return frame({"ok": False, "error": {
            "kind": CRASHED, "type": _clip(type(error).__name__),
            "message": _clip(str(error))}})
    return frame({"ok": False, "error": {
        "kind": kind, "message": _clip(error.message),
        "file": None if error.file is None else _clip(str(error.file)),
        "line": error.line if isinstance(error.line, int) and error.line > 0 else None,
        "details": [_clip(str(d)) for d in error.details[:MAX_LIST_ITEMS]]}})


def _clip(text: str) -> str:
    return text if len(text) <= MAX_STRING_CHARS else text[:MAX_STRING_CHARS - 3] + "..."


# -- the parent's side --------------------------------------------------------------------

def declared_size(prefix: bytes) -> int | None:
    """The whole frame's size, from its first PREFIX_SIZE bytes (None: too few yet);
    MalformedResult when the prefix is not one or declares a header over its bound."""
    if len(prefix) < PREFIX_SIZE:
        if not MAGIC.startswith(prefix[:len(MAGIC)]):
            raise MalformedResult("it does not start as a result does")
        return None
    if not prefix.startswith(MAGIC):
        raise MalformedResult("it does not start as a result does")
    header_size, body_size = _LENGTHS.unpack_from(prefix, len(MAGIC))
    if header_size > MAX_HEADER_BYTES:
        raise MalformedResult(f"its header claims {header_size} bytes "
                              f"(at most {MAX_HEADER_BYTES})")
    return PREFIX_SIZE + header_size + body_size


def unframe(data: bytes) -> tuple[dict, bytes]:
    """The checked header and the body of one complete frame."""
    total = declared_size(data)
    if total is None or len(data) < total:
        raise MalformedResult("it ended before the length it declared")
    if len(data) > total:
        raise MalformedResult("more bytes followed the result")
    header_size = _LENGTHS.unpack_from(data, len(MAGIC))[0]
    raw = data[PREFIX_SIZE:PREFIX_SIZE + header_size]
    try:
        header = strict_json(raw.decode("ascii"))
    except (UnicodeDecodeError, ValueError, RecursionError) as error:
        raise MalformedResult(f"its header is not JSON ({type(error).__name__})") from None
    if not isinstance(header, dict) or not isinstance(header.get("ok"), bool):
        raise MalformedResult("its header is not a result")
    return header, data[PREFIX_SIZE + header_size:]


def strict_json(text: str):
    """JSON as a boundary reads it: NaN, Infinity and a key given twice are ValueErrors
    (the Gazebo helper's answer is read through this too)."""
    return json.loads(text, parse_constant=_refuse_constant, object_pairs_hook=_unique_keys)


def _refuse_constant(name: str):
    raise ValueError(f"{name} is not a number")


def _unique_keys(pairs: list) -> dict:
    keys = [key for key, _ in pairs]
    if len(set(keys)) != len(keys):
        raise ValueError("a key given twice")
    return dict(pairs)


def expect_fields(obj: dict, where: str, **kinds) -> dict:
    """``obj`` with exactly the keys of ``kinds``, each value of its kind: ``str``,
    ``str?`` (or None), ``line`` (a positive int or None), ``[str]`` (a bounded list of
    strings), ``bool``, ``dict``."""
    if set(obj) != set(kinds):
        extra = sorted(set(obj) ^ set(kinds))
        raise MalformedResult(f"its {where} has the wrong fields ({', '.join(extra)})")
    for key, kind in kinds.items():
        value = obj[key]
        if not _is_kind(value, kind):
            raise MalformedResult(f"its {where} field '{key}' is not {kind}")
    return obj


def _is_kind(value, kind: str) -> bool:
    if kind == "bool":
        return isinstance(value, bool)
    if kind == "dict":
        return isinstance(value, dict)
    if kind == "json":
        return True  # any JSON value: nothing in JSON can call or construct anything
    if kind == "str":
        return _is_text(value)
    if kind == "str?":
        return value is None or _is_text(value)
    if kind == "line":
        return value is None or (type(value) is int and 0 < value < 1 << 31)
    if kind == "[str]":
        return (isinstance(value, list) and len(value) <= MAX_LIST_ITEMS
                and all(_is_text(item) for item in value))
    raise ValueError(kind)


def _is_text(value) -> bool:
    return isinstance(value, str) and len(value) <= MAX_STRING_CHARS and "\0" not in value


def raise_error(header: dict) -> None:
    """Raise the error an ``ok: false`` header reports."""
    expect_fields(header, "header", ok="bool", error="dict")
    error = header["error"]
    if not isinstance(error, dict) or not isinstance(error.get("kind"), str):
        raise MalformedResult("its error has no kind")
    kind = error["kind"]
    if kind == OUT_OF_MEMORY:
        expect_fields(error, "error", kind="str")
        raise ChildOutOfMemory()
    if kind == CRASHED:
        expect_fields(error, "error", kind="str", type="str", message="str")
        raise ChildCrashed(f"{error['type']}: {error['message']}")
    cls = ERROR_KINDS.get(kind)
    if cls is None:
        raise MalformedResult(f"its error is of no known kind ({kind[:40]!r})")
    expect_fields(error, "error", kind="str", message="str", file="str?", line="line",
                  details="[str]")
    raise cls(error["message"], file=error["file"], line=error["line"],
              details=error["details"])

