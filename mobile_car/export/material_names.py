"""The names an OBJ and its ``.mtl`` give the files they pull in, rewritten in an export's
copy so that the folder names only what it holds.

An export copies an OBJ with the ``.mtl`` and maps mcar's scan found beside it
(:func:`~mobile_car.load.mesh_scan.find_beside`: below the mesh's real folder). Copied as
they are, an ``mtllib /home/ci/.ssh/id_rsa`` or ``map_Kd /etc/shadow`` line would still
name files outside every allowed folder, and the next tool to read the folder (the USD
converter mcar runs on it, an engine on another machine) would read them. So each name is
replaced by the relative name of the copy it found, and a name that found nothing copied
becomes a comment.
"""

from __future__ import annotations

import re
from pathlib import Path

from ..load.mesh_scan import find_beside

_MTLLIB = re.compile(rb"^([ \t]*mtllib[ \t]+)([^\r\n]*)", re.M)
_MAP = re.compile(rb"^([ \t]*(?:map_\w+|bump|disp|decal|refl|norm)[ \t]+)([^\r\n]*)",
                  re.M | re.I)
LEFT_OUT = b"# left out by mcar export: names no file copied beside the mesh"


def portable_names(data: bytes, suffix: str, folder: Path, copied: set[Path]) -> bytes:
    """``data`` of an ``.obj`` or ``.mtl`` file whose names are looked up beside the mesh
    in ``folder`` (as the scan looked them up), each replaced by the name of the file it
    finds relative to that folder when it is in ``copied`` (real paths), else the line
    left out; other files unchanged."""
    pattern = {".obj": _MTLLIB, ".mtl": _MAP}.get(suffix.lower())
    if pattern is None:
        return data
    root = Path(folder).resolve()

    def named(text: str) -> str | None:
        found = find_beside(root, text)
        return found.relative_to(root).as_posix() if found in copied else None

    def rewrite(match: re.Match) -> bytes:
        rest = match.group(2).decode("utf-8", "replace").strip()
        whole = named(rest)
        if whole is not None:
            return match.group(1) + whole.encode()
        words = rest.split()
        last = named(words[-1]) if words else None
        if last is not None:  # options before the name: map_Kd -s 1 1 1 tex.png
            return match.group(1) + " ".join([*words[:-1], last]).encode()
        return LEFT_OUT

    return pattern.sub(rewrite, data)
