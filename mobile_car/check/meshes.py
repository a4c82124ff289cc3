"""Mesh rules W207 (every ``<mesh filename>`` must exist and load), W210 (a mesh over
a size or face limit is not read, and is drawn as a marker) and W215 (a mesh or texture
outside the folders a robot may name files in is never read:
:mod:`~mobile_car.packages.asset_roots`).

``package://PKG/...`` is resolved by the same :class:`~mobile_car.packages.search.PackageSearch` as
``mcar build``; ``file://`` and relative paths against the folder of the checked file.
What check needs of a mesh (that it loads, its bounding box, the files it reads) comes
from :func:`mobile_car.load.mesh_facts.mesh_facts`: measured first without reading it whole
(:mod:`mobile_car.load.mesh_limits`), read once (numpy for a binary STL, trimesh for the
rest, imported only then), and kept in the user's cache, sealed, so that the next check of
the same files reads none of them. Formats trimesh cannot read on this machine are only
checked for existence, not reported as broken.
"""

from __future__ import annotations

import os
from pathlib import Path

from ..errors import InputError, PackageNotFoundError
from ..load.bounded import not_regular
from ..load.inputs import display_path
from ..load.mesh_facts import mesh_facts
from ..packages.asset_roots import OutsideRootsError
from ..packages.search import PackageSearch
from ..values import Value
from .context import Reporter, has_xacro_expression

# What stands for a mesh that is not read (say it where the pictures do: docs/render.md).
PLACEHOLDER = "drawn as a magenta box"


# Values (values.py), not NamedTuples: a class made with typing.NamedTuple compiles its
# __new__ on every run that imports it.


class _Outcome(Value):
    _fields = __slots__ = ("problem", "over_limit", "reads", "bounds")
    problem: str | None  # why it cannot be loaded (W207)
    over_limit: str | None  # the limit it passes (W210)
    reads: tuple[Path, ...]  # the other files it reads
    bounds: tuple | None  # its box in metres (mesh frame, no URDF scale), if known

    def __init__(self, problem: str | None, over_limit: str | None, reads: tuple[Path, ...],
                 bounds: tuple | None = None):
        self._set(problem, over_limit, reads, bounds)


_loaded: dict[Path, _Outcome] = {}


class MeshFile(Value):
    """A ``<mesh>`` of the robot: ``kind`` visual or collision, its file (None when its
    package is unknown) and whether it loads."""

    _fields = __slots__ = ("kind", "path", "sound", "over_limit", "reads", "element", "bounds")
    kind: str
    path: Path | None
    sound: bool  # found, and loads or is over a limit (then drawn as a marker: over_limit)
    over_limit: str | None  # why it is not read: the limit it passes
    reads: tuple[Path, ...]  # the files it pulls in: materials, textures
    element: object  # the <mesh> element
    bounds: tuple | None  # ((x, y, z) min, max) in metres, the URDF scale not applied

    def __init__(self, kind: str, path: Path | None, sound: bool, over_limit: str | None = None,
                 reads: tuple[Path, ...] = (), element: object = None,
                 bounds: tuple | None = None):
        self._set(kind, path, sound, over_limit, reads, element, bounds)


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
        except OutsideRootsError as error:
            report.add("W215", mesh, f"mesh {error.message}; not read, {PLACEHOLDER}")
            found.append(MeshFile(kind, None, False, element=mesh))
            continue
        except (InputError, PackageNotFoundError) as error:
            report.add("W207", mesh, f"mesh '{filename}': {error.message}")
            found.append(MeshFile(kind, None, False, element=mesh))
            continue
        special = not_regular(path)  # a FIFO would block the loader for ever
        if special:
            report.add("W207", mesh, f"mesh '{filename}' {special}")
            found.append(MeshFile(kind, path, False, element=mesh))
            continue
        if not path.is_file():
            report.add("W207", mesh, f"mesh '{filename}' not found at {os.path.abspath(path)}"
                       f"{_where_looked(filename, search)}")
            found.append(MeshFile(kind, path, False, element=mesh))
            continue
        outcome = inspect_mesh(path)
        if outcome.problem:
            report.add("W207", mesh, f"mesh '{filename}' cannot be loaded: {outcome.problem}")
        elif outcome.over_limit:
            report.add("W210", mesh, f"mesh '{filename}' not read: {outcome.over_limit}; "
                       f"{PLACEHOLDER}")
        found.append(MeshFile(kind, path, not outcome.problem, outcome.over_limit,
                              outcome.reads, mesh, outcome.bounds))
    check_textures(root, base, search, report)
    return found


def check_textures(root, base: Path, search: PackageSearch, report: Reporter) -> None:
    """W215 for each ``<material><texture filename>`` outside the allowed folders (an
    export would copy it into its folder). Whether a texture exists is not checked: URDF
    tools load them lazily, and a missing one costs only its picture."""
    for texture in root.iter("texture"):
        filename = texture.get("filename")
        if not filename or has_xacro_expression(filename):
            continue
        try:
            search.resolve_uri(filename, base)
        except OutsideRootsError as error:
            report.add("W215", texture, f"texture {error.message}; not read")
        except (InputError, PackageNotFoundError):
            continue  # not found: said by nothing today, as before


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
    try:
        facts = mesh_facts(path, display_path(path))
    except InputError as error:
        return _Outcome(error.message, None, ())
    except OSError as error:
        return _Outcome(error.strerror or str(error), None, ())
    return _Outcome(facts.problem, facts.over_limit, facts.reads, facts.bounds)
