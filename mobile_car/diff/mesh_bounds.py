"""The box around a mesh file's vertices, in the mesh's own frame.

A binary STL (the common case, and the bundled car's) is read with ``struct``: importing
numpy and trimesh would cost more than comparing two whole robots. Other formats go
through trimesh, imported only then. Every mesh is measured first (size, declared counts:
:mod:`mobile_car.load.mesh_limits`); one over a limit has no bounds, and says why.
"""

from __future__ import annotations

import struct
from pathlib import Path

from ..errors import InputError, McarError
from ..load.mesh_limits import scan_mesh

_cache: dict[Path, tuple | str] = {}


def mesh_bounds(filename: str, base: Path, search) -> tuple | str:
    """((xmin, ymin, zmin), (xmax, ymax, zmax)), or a message saying why there is none."""
    try:
        path = search.resolve_uri(filename, base).resolve()
    except McarError as error:
        return error.message
    if path not in _cache:
        _cache[path] = _bounds(path)
    return _cache[path]


def _bounds(path: Path) -> tuple | str:
    if not path.is_file():
        return f"no file at {path}"
    try:
        scan_mesh(path, str(path))
    except InputError as error:
        return f"{path} not read: {error.message}"
    except OSError as error:
        return f"cannot read {path}: {error.strerror or error}"
    try:
        binary = _binary_stl(path)
    except OSError as error:
        return f"cannot read {path}: {error.strerror or error}"
    if binary is not None:
        return binary
    try:
        from ..load.mesh_reader import load_mesh

        mesh, _ = load_mesh(path, str(path), textures=False, force="mesh")
        low, high = mesh.bounds
    except Exception as error:  # trimesh raises anything on a file it cannot read
        return f"cannot load {path}: {type(error).__name__}: {error}"
    return tuple(map(float, low)), tuple(map(float, high))


def _binary_stl(path: Path) -> tuple | None:
    """Bounds of a binary STL whose size matches its triangle count, else None."""
    if path.suffix.lower() != ".stl":
        return None
    data = path.read_bytes()
    if len(data) < 84:
        return None
    count = struct.unpack_from("<I", data, 80)[0]
    if count == 0 or len(data) != 84 + 50 * count:
        return None
    low = [float("inf")] * 3
    high = [float("-inf")] * 3
    for record in struct.iter_unpack("<12fH", data[84:]):
        for vertex in (record[3:6], record[6:9], record[9:12]):
            for i in range(3):
                if vertex[i] < low[i]:
                    low[i] = vertex[i]
                if vertex[i] > high[i]:
                    high[i] = vertex[i]
    return tuple(low), tuple(high)
