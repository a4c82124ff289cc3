"""Mesh rules W207 (every ``<mesh filename>`` must exist and load) and W210 (a mesh over
a size or face limit is not read, and is drawn as a marker).

``package://PKG/...`` is resolved by the same :class:`~mobile_car.packages.search.PackageSearch` as
``mcar build``; ``file://`` and relative paths against the folder of the checked file.
Every mesh is measured first without reading it whole (:mod:`mobile_car.load.mesh_limits`:
file size, declared vertex and face counts); one within the limits is loaded with trimesh
(imported only then) through :func:`mobile_car.load.mesh_reader.load_mesh`, once per
process however many links use it. Formats trimesh cannot read on this machine are only
checked for existence, not reported as broken.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import NamedTuple

from ..errors import InputError, McarError
from ..load.bounded import not_regular
from ..load.compressed import broken_errors, compressed_kind, suffix_of
from ..load.inputs import display_path
from ..load.mesh_limits import MeshOverLimit, scan_mesh
from ..packages.search import PackageSearch
from .context import Reporter, has_xacro_expression

# What stands for a mesh that is not read (say it where the pictures do: README).
PLACEHOLDER = "drawn as a magenta box"


class _Outcome(NamedTuple):
    problem: str | None  # why it cannot be loaded (W207)
    over_limit: str | None  # the limit it passes (W210)
    reads: tuple[Path, ...]  # the other files it reads


_loaded: dict[Path, _Outcome] = {}


class MeshFile(NamedTuple):
    """A ``<mesh>`` of the robot: ``kind`` visual or collision, its file (None when its
    package is unknown) and whether it loads."""

    kind: str
    path: Path | None
    sound: bool  # found, and loads or is over a limit (then drawn as a marker: over_limit)
    over_limit: str | None = None  # why it is not read: the limit it passes
    reads: tuple[Path, ...] = ()  # the files it pulls in: materials, textures


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
        outcome = inspect_mesh(path)
        if outcome.problem:
            report.add("W207", mesh, f"mesh '{filename}' cannot be loaded: {outcome.problem}")
        elif outcome.over_limit:
            report.add("W210", mesh, f"mesh '{filename}' not read: {outcome.over_limit}; "
                       f"{PLACEHOLDER}")
        found.append(MeshFile(kind, path, not outcome.problem, outcome.over_limit,
                              outcome.reads))
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
    """None if trimesh loads a non-empty mesh from ``path`` (or cannot read the format, or
    it is over a limit: see inspect_mesh), else why not."""
    return inspect_mesh(path).problem


def inspect_mesh(path: Path) -> _Outcome:
    """Whether the mesh at ``path`` loads, passes a limit, and what else it reads."""
    key = path.resolve()
    if key not in _loaded:
        _loaded[key] = _inspect(key)
    return _loaded[key]


def _inspect(path: Path) -> _Outcome:
    if not os.access(path, os.R_OK):
        return _Outcome("permission denied", None, ())
    shown = display_path(path)
    try:
        scan = scan_mesh(path, shown)
    except MeshOverLimit as error:
        return _Outcome(None, error.message, ())
    except InputError as error:
        return _Outcome(error.message, None, ())
    except OSError as error:
        return _Outcome(error.strerror or str(error), None, ())
    if _sound_binary_stl(path):
        return _Outcome(None, None, scan.reads)
    try:
        problem, reads = _try_load(path, shown)
    except MeshOverLimit as error:  # a member of an archive, counted once decompressed
        return _Outcome(None, error.message, ())
    return _Outcome(problem, None, tuple(dict.fromkeys([*scan.reads, *reads])))


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


def _try_load(path: Path, shown: str) -> tuple[str | None, list[Path]]:
    from ..held_signals import import_held

    # heavy (numpy): only for meshes the cheap test above cannot vouch for
    trimesh = import_held("trimesh")

    from ..load.mesh_reader import load_mesh

    if compressed_kind(path) is None and suffix_of(path.name) not in trimesh.available_formats():
        return None, []
    try:
        loaded, reads = load_mesh(path, shown, force="mesh")
    except MeshOverLimit:
        raise
    except McarError as error:
        return error.message, []
    except broken_errors() as exc:
        return _short(exc), []
    except Exception as exc:  # trimesh raises anything from ValueError to struct.error
        return _short(exc), []
    if getattr(loaded, "vertices", None) is None or len(loaded.vertices) == 0:
        return "it holds no geometry", reads
    return None, reads


def _short(exc: BaseException) -> str:
    return " ".join(str(exc).split())[:200] or type(exc).__name__
