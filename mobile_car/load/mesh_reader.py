"""The one way mcar reads a mesh file with trimesh: measured first, within every limit.

:func:`load_mesh` checks the file with :func:`~.mesh_limits.scan_mesh` (size, declared
counts), decompresses compressed and zipped formats itself within ``MCAR_MAX_MESH_MB``
(counting each member again), and hands trimesh the bytes with a resolver that opens only
regular files below the mesh's folder, each within the same size cap, and notes every
file it opens: a texture or ``.mtl`` is an input of the run like the mesh.

Imports trimesh: only the commands that read meshes import this module.
"""

from __future__ import annotations

import io
import logging
import os
import stat
import zipfile
from pathlib import Path

from PIL import Image

from ..errors import InputError
from ..held_signals import import_held
from ..packages.asset_roots import in_vcs_folder
from . import mesh_cache
from .collada import readable_collada
from .compressed import ZIP_FORMATS, compressed_kind, decompressed_members, max_mesh_bytes
from .mesh_limits import MeshOverLimit, scan_bytes, scan_mesh, suffix_of

trimesh = import_held("trimesh")  # see import_held: a signal in its start aborts
# trimesh logs what it recovers from (a sparse product cut by Ctrl-C, a bad texture) with
# a traceback, and with no handler logging's last resort prints it on stderr: a library
# must not print, and a signal trimesh swallowed is raised again by mcar's command line.
logging.getLogger("trimesh").addHandler(logging.NullHandler())
logging.getLogger("trimesh").propagate = False

_IMAGES = (".png", ".jpg", ".jpeg", ".bmp", ".tga", ".tif", ".tiff", ".gif", ".webp")


class BoundedResolver(trimesh.resolvers.FilePathResolver):
    """trimesh's resolver for the files a mesh names (materials, textures, buffers): in
    the mesh's folder or below, regular files within the mesh size cap, and textures
    within PIL's own pixel limit (a small PNG can stand for gigabytes of pixels), never in
    a version-control folder; what it opened is in ``read``. A file it refuses is one
    trimesh does without (its colour); ``textures`` False refuses every image, for a
    reader of the geometry alone."""

    def __init__(self, mesh: Path, read: list[Path], textures: bool = True):
        super().__init__(str(mesh))
        self.read = read
        self.textures = textures

    def namespaced(self, namespace: str) -> BoundedResolver:
        # A namespace is a folder below this one: one that climbs out (``..``, a link
        # leading away) leaves the resolver where it is.
        here = Path(os.path.realpath(self.parent))
        inner = Path(os.path.realpath(here / namespace))
        return BoundedResolver((inner if inner.is_relative_to(here) else here) / "_",
                               self.read, self.textures)

    def get(self, name: str) -> bytes:
        if not self.textures and Path(name.strip()).suffix.lower() in _IMAGES:
            raise FileNotFoundError(name)
        for candidate in (name.strip(), name.strip().lstrip("/"), os.path.split(name)[-1]):
            try:
                path = self.absolute(candidate)
            except ValueError:
                continue
            # never the checkout's .git (a glTF at a repository's root naming .git/config
            # as its buffer: its bytes became the vertices of an exported STL)
            if path.exists() and not in_vcs_folder(path.relative_to(self._root())):
                return self._read(path)
        raise FileNotFoundError(name)

    def _root(self) -> Path:
        return Path(self.parent).resolve()

    def _read(self, path: Path) -> bytes:
        with open(path, "rb", opener=_no_blocking) as handle:
            info = os.fstat(handle.fileno())
            if not stat.S_ISREG(info.st_mode):
                raise OSError(f"{path}: not a regular file")
            if info.st_size > max_mesh_bytes():
                raise OSError(f"{path}: over the mesh size limit")
            self.read.append(path)
            data = handle.read(max_mesh_bytes() + 1)
        if path.suffix.lower() in _IMAGES:
            with Image.open(io.BytesIO(data)) as image:  # reads the header only
                width, height = image.size
            if width * height > (Image.MAX_IMAGE_PIXELS or 1 << 62):
                raise OSError(f"{path}: {width}x{height} pixels, too many for a texture")
        return data

    def write(self, name, data):
        raise OSError("mcar writes no file next to a mesh")


def _no_blocking(path, flags):
    """Open without waiting for a FIFO's writer (it is refused just after)."""
    return os.open(path, flags | os.O_NONBLOCK)


def load_mesh(path: str | os.PathLike, shown: str | None = None, textures: bool = True,
              **kwargs):
    """``trimesh.load(path, **kwargs)`` within every limit, in metres, and the files it
    read besides the mesh. COLLADA is read as RViz reads it (:mod:`.collada`: recovered
    XML, repaired colours, ``<unit>`` applied). ``textures`` False: the image files it
    names are not read (a reader of its geometry alone: bounds, inertia, MuJoCo's copy;
    trimesh made one texture atlas of Curiosity's textured COLLADA parts, most of the
    time of mcar check, sim and specs on it). MeshOverLimit over a limit; MeshBroken,
    InputError or one of compressed.broken_errors() for a file that cannot be measured;
    trimesh's own exceptions for one it cannot parse. Within :func:`.mesh_cache.kept`, a
    file asked for as a scene or a mesh is parsed once while its stamp holds (once with
    its textures, once without): what
    ``trimesh.load`` makes of ``force`` (the scene, or its meshes concatenated) is made of
    the kept scene, a copy each time."""
    path = Path(path)
    shown = shown or str(path)
    force = kwargs.get("force")
    key = None
    if force in ("scene", "mesh"):
        key = mesh_cache.key_of(path, _read_alike(path, {
            **{k: v for k, v in kwargs.items() if k != "force"}, "textures": textures}))
    if key is None:
        loaded, unit, read = _read(path, shown, kwargs, textures)
        return in_metres(loaded, unit), read
    kept = mesh_cache.get(key)
    if kept is None:
        kept = _read(path, shown, {**kwargs, "force": "scene"}, textures)
        mesh_cache.put(key, kept)
    scene, unit, read = kept
    if force == "mesh":  # what trimesh.load(force="mesh") makes of the same scene
        return in_metres(scene.to_mesh(), unit), list(read)
    # (scaled is a copy already)
    return in_metres(scene.copy() if unit == 1.0 else scene, unit), list(read)


def _read_alike(path: Path, options: dict) -> dict:
    """``options`` without those that change nothing trimesh reads from this file: its
    COLLADA reader ignores ``skip_materials`` and ignores broken parts unless told not to
    (render asks for both, sim for neither: they share one read)."""
    if suffix_of(path.name) != "dae":
        return options
    return {k: v for k, v in options.items()
            if k != "skip_materials" and (k, v) != ("ignore_broken", True)}


def _read(path: Path, shown: str, kwargs: dict, textures: bool):
    """(what trimesh.load gives for ``kwargs``, the file's unit in metres, the files it
    read besides the mesh; ``textures``: as :func:`load_mesh`)."""
    read: list[Path] = []
    scan_mesh(path, shown)
    kind = compressed_kind(path)
    # Anchored at the real file: what it names is taken below the folder it really lies
    # in (trimesh then follows every link of a name and keeps it below that folder).
    resolver = BoundedResolver(Path(os.path.realpath(path)), read, textures)
    if kind is None:
        with open(path, "rb", opener=_no_blocking) as handle:
            data = handle.read(max_mesh_bytes() + 1)
        if len(data) > max_mesh_bytes():  # it grew since it was measured
            raise MeshOverLimit("grew past the mesh size limit while read", file=shown)
        return (*_load_bytes(path.name, data, shown, resolver, kwargs), read)
    members = decompressed_members(path, shown)
    for name, data in members:
        scan_bytes(name, data, f"{shown} ({name})")
    if not members:
        raise InputError("an archive with no file in it", file=shown)
    if kind in ("bz2", "gz"):
        name, data = members[0]
        return (*_load_bytes(name, data, shown, resolver, kwargs), read)
    # An archive again, its members stored as they are: trimesh reads what was measured;
    # a COLLADA member as RViz reads it, its unit applied once loaded.
    unit = 1.0
    stored = io.BytesIO()
    with zipfile.ZipFile(stored, "w", zipfile.ZIP_STORED) as archive:
        for name, data in members:
            if suffix_of(name) == "dae":
                document = readable_collada(data, f"{shown} ({name})")
                data, unit = document.data, document.unit
            archive.writestr(name, data)
    del members
    stored.seek(0)
    file_type = kind if kind in ZIP_FORMATS else "zip"
    return trimesh.load(stored, file_type=file_type, **kwargs), unit, read


def _load_bytes(name: str, data: bytes, shown: str, resolver, kwargs: dict):
    """(what trimesh.load gives, the unit in metres)."""
    file_type = suffix_of(name)
    unit = 1.0
    if file_type == "dae":
        document = readable_collada(data, shown)
        data, unit = document.data, document.unit
    return trimesh.load(io.BytesIO(data), file_type=file_type, resolver=resolver,
                        **kwargs), unit


def in_metres(loaded, unit: float):
    """A loaded Trimesh or Scene scaled by ``unit`` (metres per file unit)."""
    if unit == 1.0:
        return loaded
    if isinstance(loaded, trimesh.Scene):
        loaded = loaded.scaled(unit)
    else:
        loaded.apply_scale(unit)
    loaded.units = "meters"  # trimesh noted the file's unit: it is applied now
    return loaded
