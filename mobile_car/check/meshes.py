"""Mesh rule W207: every ``<mesh filename>`` must exist and load.

``package://PKG/...`` is resolved by the same :class:`~mobile_car.packages.search.PackageSearch` as
``mcar build``; ``file://`` and relative paths against the folder of the checked file.
A mesh is loaded with trimesh (imported only when a mesh file exists), once per process
however many links use it. Formats trimesh cannot read on this machine are only checked
for existence, not reported as broken.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import NamedTuple

from ..errors import McarError
from ..packages.search import PackageSearch
from .context import Reporter, has_xacro_expression

_loaded: dict[Path, str | None] = {}


class MeshFile(NamedTuple):
    """A ``<mesh>`` of the robot: ``kind`` visual or collision, its file (None when its
    package is unknown) and whether it loads."""

    kind: str
    path: Path | None
    sound: bool


def check_meshes(root, base: Path, search: PackageSearch, report: Reporter
                 ) -> list[MeshFile]:
    """Report W207 for each mesh that is missing or broken; return every mesh file with
    the geometry it belongs to, so a consumer knows what it reads and what it lacks."""
    found: list[MeshFile] = []
    for mesh in root.iter("mesh"):
        filename = mesh.get("filename")
        if not filename or has_xacro_expression(filename):
            continue  # E112 / E105
        geometry = mesh.getparent()
        holder = geometry.getparent() if geometry is not None else None
        kind = holder.tag if holder is not None and isinstance(holder.tag, str) else ""
        try:
            path = search.resolve_uri(filename, base)
        except McarError as error:
            report.add("W207", mesh, f"mesh '{filename}': {error.message}")
            found.append(MeshFile(kind, None, False))
            continue
        if not path.is_file():
            shown = f" ({path})" if str(path) != filename else ""
            report.add("W207", mesh, f"mesh '{filename}' not found{shown}")
            found.append(MeshFile(kind, path, False))
            continue
        problem = load_problem(path)
        if problem:
            report.add("W207", mesh, f"mesh '{filename}' cannot be loaded: {problem}")
        found.append(MeshFile(kind, path, not problem))
    return found


def load_problem(path: Path) -> str | None:
    """None if trimesh loads a non-empty mesh from ``path`` (or cannot read the format)."""
    key = path.resolve()
    if key not in _loaded:
        _loaded[key] = _try_load(key)
    return _loaded[key]


def _sound_binary_stl(path: Path) -> bool:
    """True for a binary STL whose size matches its triangle count: no need for trimesh.

    Importing numpy and trimesh costs more than checking a whole robot; STL is
    the common case, and its binary form says its own length.
    """
    if path.suffix.lower() != ".stl":
        return False
    try:
        size = path.stat().st_size
        with open(path, "rb") as handle:
            header = handle.read(84)
    except OSError:
        return False
    if len(header) < 84:
        return False
    triangles = int.from_bytes(header[80:84], "little")
    return triangles > 0 and size == 84 + 50 * triangles


def _try_load(path: Path) -> str | None:
    if not os.access(path, os.R_OK):
        return "permission denied"
    if _sound_binary_stl(path):
        return None
    import trimesh  # heavy (numpy): only for meshes the cheap test above cannot vouch for

    suffix = path.suffix.lower().lstrip(".")
    if suffix not in trimesh.available_formats():
        return None
    try:
        loaded = trimesh.load(str(path), force="mesh")
    except Exception as exc:  # trimesh raises anything from ValueError to struct.error
        return " ".join(str(exc).split())[:200] or type(exc).__name__
    if getattr(loaded, "vertices", None) is None or len(loaded.vertices) == 0:
        return "it holds no geometry"
    return None
