"""Collision meshes as MuJoCo can read them, with the geometry ``mcar render`` draws.

MuJoCo reads binary STL (up to 200,000 triangles), OBJ and its own ``.msh``, and knows
nothing of COLLADA's ``<unit>``. A collision mesh it can read as it is goes to it as it is;
any other (COLLADA, PLY, glTF, an ASCII STL, a compressed file, a bigger STL) is read by
mcar's reader (:func:`mobile_car.load.mesh_reader.load_mesh`: within the mesh limits, in
metres, COLLADA as RViz reads it) and written for MuJoCo as a binary STL (an OBJ past
MuJoCo's STL limit) in the user's cache folder, ``mujoco-meshes/``, named by the source's
bytes. The file is written again on every run, never trusted from an earlier one: the
MJCF ``mcar build --format mjcf`` writes names it, so it stays where it is.
"""

from __future__ import annotations

import hashlib
import os
import tempfile
from pathlib import Path

from ..atomic import atomic_write
from ..errors import InputError
from ..file_memo import FileMemo
from ..load.mesh_facts import binary_stl_triangles
from ..load.mesh_limits import scan_mesh
from ..record_seal import cache_dir

AS_IT_IS = (".obj", ".msh")
MUJOCO_STL_FACES = 200_000  # MuJoCo's STL reader refuses more ("between 1 and 200000")
_FOLDER = "mujoco-meshes"
CONVERTER_VERSION = 1  # in the file names: bump when the same source converts differently
_fallback: list[Path] = []  # a temporary folder, where the cache folder cannot be written


def mujoco_mesh(path: Path) -> Path:
    """The file MuJoCo should read for the collision mesh at ``path``: itself, or a
    converted copy. InputError (MeshOverLimit, MeshBroken) or OSError with the reason
    when it cannot be read. Each file is measured and converted once in a process while
    its stamp holds (:data:`_converted`), however many ``<mesh>`` elements name it."""
    return _converted.get(path, lambda: _mujoco_mesh(path), still_good=os.path.isfile)


# what mujoco_mesh gave for each file: Unitree Go1 names calf.dae four times, and sim's
# model and specs' ray scenes read the same visuals
_converted = FileMemo(1024)


def _mujoco_mesh(path: Path) -> Path:
    scan_mesh(path, str(path))
    suffix = path.suffix.lower()
    if suffix in AS_IT_IS:
        return path
    if suffix == ".stl" and binary_stl_triangles(path) in range(1, MUJOCO_STL_FACES + 1):
        return path
    from ..load.mesh_reader import load_mesh

    try:
        mesh, _ = load_mesh(path, str(path), textures=False, force="mesh")
    except (InputError, OSError):
        raise
    except Exception as exc:  # trimesh raises anything on a file it cannot parse
        raise InputError(f"cannot be read: {' '.join(str(exc).split())[:200]}",
                         file=str(path)) from None
    if getattr(mesh, "faces", None) is None or not len(mesh.faces):
        raise InputError("holds no triangles", file=str(path))
    kind = "stl" if len(mesh.faces) <= MUJOCO_STL_FACES else "obj"
    data = mesh.export(file_type=kind)
    data = data.encode() if isinstance(data, str) else data
    name = f"{_digest(path)}.{kind}"
    return atomic_write(_folder() / name, data)


def _digest(path: Path) -> str:
    digest = hashlib.sha256(f"{CONVERTER_VERSION}\0".encode())
    with open(path, "rb") as handle:
        digest.update(hashlib.file_digest(handle, "sha256").digest())
    return digest.hexdigest()[:32]


def _folder() -> Path:
    folder = cache_dir() / _FOLDER
    try:
        folder.mkdir(parents=True, exist_ok=True, mode=0o700)
        if os.access(folder, os.W_OK):
            return folder
    except OSError:
        pass
    if not _fallback:
        import atexit
        import shutil

        _fallback.append(Path(tempfile.mkdtemp(prefix="mcar-mujoco-meshes-")))
        atexit.register(shutil.rmtree, _fallback[0], ignore_errors=True)
    return _fallback[0]
