"""Mesh rule W207: every ``<mesh filename>`` must exist and load.

``package://PKG/...`` is resolved by the same :class:`~mobile_car.packages.search.PackageSearch` as
``mcar build``; ``file://`` and relative paths against the folder of the checked file.
A mesh is loaded with trimesh (imported only when a mesh file exists), once per process
however many links use it. Formats trimesh cannot read on this machine are only checked
for existence, not reported as broken. Compressed meshes are decompressed by mcar within
``MCAR_MAX_MESH_MB`` (:mod:`mobile_car.load.compressed`), then handed to trimesh.
"""

from __future__ import annotations

import io
import os
from pathlib import Path
from typing import NamedTuple

from ..errors import InputError, McarError
from ..load.bounded import not_regular
from ..load.compressed import broken_errors, compressed_kind, decompressed_members, suffix_of
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
        special = not_regular(path)  # a FIFO would block the loader for ever
        if special:
            report.add("W207", mesh, f"mesh '{filename}' {special}")
            found.append(MeshFile(kind, path, False))
            continue
        if not path.is_file():
            report.add("W207", mesh, f"mesh '{filename}' not found at {os.path.abspath(path)}"
                       f"{_where_looked(filename, search)}")
            found.append(MeshFile(kind, path, False))
            continue
        problem = load_problem(path)
        if problem:
            report.add("W207", mesh, f"mesh '{filename}' cannot be loaded: {problem}")
        found.append(MeshFile(kind, path, not problem))
    return found


def _where_looked(filename: str, search: PackageSearch) -> str:
    """Why that path: the package a package:// URI named, found first of the search places
    (ROS, too, looks only in the first package of a name); the input's folder for a
    relative filename."""
    if filename.startswith("package://"):
        name = filename[len("package://"):].partition("/")[0]
        return (f" (package '{name}' found first in {search.found_in(name)}; search order: "
                + "; ".join(search.where_looked()) + ")")
    if filename.startswith("file://") or os.path.isabs(filename):
        return ""
    return " (a relative filename starts at the input's folder)"


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

    if compressed_kind(path) is not None:
        return _compressed_problem(path, trimesh)
    suffix = path.suffix.lower().lstrip(".")
    if suffix not in trimesh.available_formats():
        return None
    return _geometry_problem(trimesh, str(path))


def _geometry_problem(trimesh, source, **kwargs) -> str | None:
    try:
        loaded = trimesh.load(source, force="mesh", **kwargs)
    except Exception as exc:  # trimesh raises anything from ValueError to struct.error
        return _short(exc)
    if getattr(loaded, "vertices", None) is None or len(loaded.vertices) == 0:
        return "it holds no geometry"
    return None


def _compressed_problem(path: Path, trimesh) -> str | None:
    """Decompressed by mcar within MCAR_MAX_MESH_MB (trimesh would decompress a bomb
    whole); sound when a member of a format trimesh reads holds geometry."""
    try:
        members = decompressed_members(path)
    except InputError as error:
        return error.message
    except broken_errors() as exc:
        return _short(exc)
    readable = [(name, data) for name, data in members
                if suffix_of(name) in trimesh.available_formats()]
    problem = None
    for name, data in readable:
        problem = _geometry_problem(trimesh, io.BytesIO(data), file_type=suffix_of(name))
        if problem is None:
            return None
    return problem


def _short(exc: BaseException) -> str:
    return " ".join(str(exc).split())[:200] or type(exc).__name__
