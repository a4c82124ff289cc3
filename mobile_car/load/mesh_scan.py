"""What a mesh scan finds (:class:`MeshScan`), the error for a file whose own counts
contradict it (:class:`MeshBroken`), and the two small readings every format's scan shares:
a count the file declares, and the file beside the mesh that trimesh's resolver would open.
"""

from __future__ import annotations

import os
from pathlib import Path

from ..errors import InputError
from ..packages.asset_roots import in_vcs_folder
from ..values import Value


class MeshBroken(InputError):
    """A mesh file whose own counts contradict it (a binary STL claiming more triangles
    than it holds): not read, reported like a mesh trimesh cannot load."""


class MeshScan(Value):
    """What a mesh file declares: ``faces`` and ``vertices`` (None: not known before
    decompressing or parsing it) and the other files it reads, that exist."""

    _fields = __slots__ = ("faces", "vertices", "reads", "partial")
    faces: int | None
    vertices: int | None
    reads: tuple[Path, ...]
    partial: bool  # counting stopped once over the limit: at least these

    def __init__(self, faces: int | None = None, vertices: int | None = None,
                 reads: tuple[Path, ...] = (), partial: bool = False):
        self._set(faces, vertices, reads, partial)


def find_beside(folder: Path, name: str) -> Path | None:
    """The regular file trimesh's resolver would open for ``name`` in ``folder``: the
    name, without a leading slash, or its base name; below the folder only, and never in a
    version-control folder (an OBJ at a repository's root naming ``.git/config``)."""
    name = name.strip()
    if not name or "\0" in name:
        return None
    root = Path(folder).resolve()
    for candidate in (name, name.lstrip("/"), os.path.split(name)[-1]):
        if not candidate:
            continue
        try:
            path = (root / candidate).resolve()
            if path.is_relative_to(root) and not in_vcs_folder(path.relative_to(root)) \
                    and path.is_file():
                return path
        except (OSError, ValueError, RuntimeError):
            continue
    return None


def declared_count(word: str, shown: str) -> int:
    """A count as a file declares it (a header word, a ``count`` attribute): digits only,
    at most 19 of them; MeshBroken naming the word otherwise."""
    if not word.isdigit() or len(word) > 19:
        raise MeshBroken(f"its header gives the count {word[:30]!r}", file=shown)
    return int(word)
