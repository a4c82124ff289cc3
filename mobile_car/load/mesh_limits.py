"""How big a mesh file is, told before it is read: file size, and the vertex and face
counts the format declares, plus the other files it pulls in (materials, textures).

trimesh reads a mesh whole and believes its counts: a 2 GB sparse STL is read into
memory, an OBJ of 12 MB naming 1.5 million faces (of 3 vertices) keeps the renderer busy
for minutes. Here a mesh is measured without trimesh, numpy or parsing its geometry:

* every file: ``stat`` against ``MCAR_MAX_MESH_MB`` (compressed files are capped again
  as they are decompressed, :mod:`.compressed`);
* binary STL: the triangle count at byte 80, which must fit in the file; ASCII STL,
  OBJ: ``vertex`` / ``v`` / ``f`` lines counted in a bytes scan (an OBJ polygon of n
  corners is n - 2 triangles); PLY, OFF: the header; COLLADA: the ``count`` attributes
  of its primitives, times the times each geometry is instanced (nodes may instance nodes:
  counted through the graph, never expanded); glTF: its accessors and nodes (both in
  :mod:`.scene_counts`);
* the counts against ``MCAR_MAX_MESH_FACES`` (and three vertices a face).

The same scan notes the files the mesh would read (an OBJ's ``mtllib``, the textures its
``.mtl`` maps, COLLADA ``<init_from>`` images, glTF buffers and images): they are inputs
of the run, kept from being overwritten and stamped for freshness. Found as trimesh's
resolver finds them: in the mesh's folder (or below), by name, else by base name.
"""

from __future__ import annotations

import io
import os
import re
import stat
from pathlib import Path

from ..errors import InputError
from .bounded import open_regular
from .compressed import (  # noqa: F401 (MeshOverLimit: one name for every limit)
    MAX_MESH_MB_ENV,
    MeshOverLimit,
    compressed_kind,
    max_mesh_bytes,
    suffix_of,
)
from .mesh_scan import MeshBroken, MeshScan, declared_count, find_beside  # noqa: F401 (MeshBroken)

MAX_MESH_FACES_ENV = "MCAR_MAX_MESH_FACES"
# Per mesh file. Measured by scan_mesh over the 58 meshes of the released TurtleBot3,
# Husky, Jackal and Clearpath packages (shared/real-robots) and tests/real_packages: the
# largest is TurtleBot3 waffle_pi's base, 63,200 triangles (Husky's wheel.dae 25,104),
# fifteen times under the default; 1.5 million coincident faces kept llvmpipe busy for
# minutes (issue 32). A CAD export or a scan can be larger: raise it then.
DEFAULT_MAX_MESH_FACES = 1_000_000
VERTICES_PER_FACE = 3  # a triangle soup (STL, unshared OBJ corners) has three a face
_CHUNK = 4 << 20
_HEADER_LIMIT = 64 << 10  # PLY and OFF headers are a few lines; more is not a mesh


def max_mesh_faces() -> int:
    from ..settings import env_number

    return int(env_number(MAX_MESH_FACES_ENV, DEFAULT_MAX_MESH_FACES, 1, 1e10, "faces"))


_scanned: dict[tuple, MeshScan | InputError] = {}


def scan_mesh(path: str | os.PathLike, shown: str | None = None) -> MeshScan:
    """The counts and files of the mesh at ``path`` after checking its size; MeshOverLimit
    over a limit, MeshBroken for a self-contradicting file, InputError for what is not a
    regular file, OSError when it cannot be read. Remembered per file and stat."""
    path = Path(path)
    shown = shown or str(path)
    info = os.stat(path)
    if not stat.S_ISREG(info.st_mode):
        raise InputError("not a regular file (a device, FIFO or socket is no mesh)", file=shown)
    cap = max_mesh_bytes()
    if info.st_size > cap:
        raise MeshOverLimit(f"{_mb(info.st_size)} MB, over the limit of {_mb(cap)} MB for "
                            f"a mesh file; set {MAX_MESH_MB_ENV} to raise it", file=shown)
    key = (str(path.resolve()), info.st_size, info.st_mtime_ns, info.st_ino,
           cap, max_mesh_faces())
    if key not in _scanned:
        try:
            if compressed_kind(path) is not None:  # counted as decompressed (mesh_reader.py)
                _scanned[key] = MeshScan()
            else:
                with open_regular(path, shown) as handle:  # swapped for a FIFO: no wait
                    # The folder the mesh really is in: a mesh reached through a link
                    # finds its .mtl and maps beside its target, never beside the link.
                    _scanned[key] = scan_stream(suffix_of(path.name), handle, info.st_size,
                                                shown, Path(os.path.realpath(path)).parent)
        except InputError as error:  # check and render both ask: scanned once
            _scanned[key] = error
    if isinstance(_scanned[key], InputError):
        raise _scanned[key]
    return _scanned[key]


def scan_stream(kind: str, handle, size: int, shown: str, folder: Path | None) -> MeshScan:
    """Counts of a mesh of format ``kind`` (``stl``, ``obj``, ...) read from ``handle``,
    checked against the face limit; ``folder`` None: its other files are not on disk."""
    scanner = _SCANNERS.get(kind)
    if scanner is None:
        return MeshScan()
    scan = scanner(handle, size, shown, folder)
    limit = max_mesh_faces()
    if scan.faces is not None and scan.faces > limit:
        at_least = "at least " if scan.partial else ""
        raise MeshOverLimit(f"{at_least}{scan.faces} faces, over the limit of {limit} for a "
                            f"mesh; set {MAX_MESH_FACES_ENV} to raise it", file=shown)
    if scan.vertices is not None and scan.vertices > VERTICES_PER_FACE * limit:
        raise MeshOverLimit(f"{'at least ' if scan.partial else ''}{scan.vertices} "
                            f"vertices, over the limit of "
                            f"{VERTICES_PER_FACE * limit} for a mesh (three a face); "
                            f"set {MAX_MESH_FACES_ENV} to raise it", file=shown)
    return scan


def scan_bytes(name: str, data: bytes, shown: str) -> MeshScan:
    """Counts of one decompressed member (``name`` gives its format)."""
    return scan_stream(suffix_of(name), io.BytesIO(data), len(data), shown, None)


def _mb(size: int) -> str:
    return f"{size / 1024 / 1024:.6g}"


def _chunks(handle):
    """The stream in pieces of whole lines (the last may lack its newline)."""
    rest = b""
    while True:
        block = handle.read(_CHUNK)
        if not block:
            if rest:
                yield rest
            return
        block = rest + block
        cut = block.rfind(b"\n") + 1
        if cut == 0:  # one line longer than a chunk: it is bounded by the file size
            rest = block
            continue
        rest = block[cut:]
        yield block[:cut]


def _stl(handle, size: int, shown: str, folder) -> MeshScan:
    head = handle.read(84)
    triangles = int.from_bytes(head[80:84], "little") if len(head) == 84 else None
    if triangles is not None and 84 + 50 * triangles == size:
        return MeshScan(triangles, 3 * triangles)
    if head.lstrip().lower().startswith(b"solid"):  # ASCII, as trimesh reads it then
        handle.seek(0)
        corners = sum(chunk.count(b"vertex") for chunk in _chunks(handle))
        return MeshScan(corners // 3, corners)
    if triangles is not None and 84 + 50 * triangles > size:
        raise MeshBroken(f"its binary STL header says {triangles} triangles, and the file "
                         f"of {size} bytes holds at most {max(size - 84, 0) // 50}",
                         file=shown)
    return MeshScan(triangles, None if triangles is None else 3 * triangles)


# Patterns, compiled by re at their first use (and kept in its cache): a run that reads
# no OBJ does not pay for compiling them.
_OBJ_FACE = rb"(?m)^[ \t]*f[ \t]+([^\n]*)"
_OBJ_VERTEX = rb"(?m)^[ \t]*v[ \t]"
_OBJ_MTLLIB = rb"(?m)^[ \t]*mtllib[ \t]+([^\r\n]*)"
_MTL_MAP = rb"(?mi)^[ \t]*(?:map_\w+|bump|disp|decal|refl|norm)[ \t]+([^\r\n]*)"


def _obj(handle, size: int, shown: str, folder) -> MeshScan:
    faces = vertices = 0
    limit = max_mesh_faces()
    libraries = []
    partial = False
    for chunk in _chunks(handle):
        lines = re.findall(_OBJ_FACE, chunk)
        # an n-gon is n - 2 triangles: corners (tokens) less two a line
        faces += len(b" ".join(lines).split()) - 2 * len(lines)
        vertices += len(re.findall(_OBJ_VERTEX, chunk))
        libraries += [m.decode("utf-8", "replace").strip()
                      for m in re.findall(_OBJ_MTLLIB, chunk)]
        if faces > limit or vertices > VERTICES_PER_FACE * limit:
            partial = True
            break  # over already: no need to read the rest
    reads = []
    if folder is not None:
        for library in dict.fromkeys(libraries):
            found = find_beside(folder, library)
            if found is not None:
                reads.append(found)
                reads += _mtl_maps(found, folder)
    return MeshScan(faces, vertices, tuple(dict.fromkeys(reads)), partial)


def _mtl_maps(mtl: Path, folder: Path) -> list[Path]:
    """The textures a .mtl maps (trimesh looks for them beside the OBJ); the whole rest
    of the line, and its last word (``map_Kd -s 1 1 1 tex.png``)."""
    try:
        if mtl.stat().st_size > max_mesh_bytes():
            return []
        text = mtl.read_bytes()
    except OSError:
        return []
    found = []
    for rest in re.findall(_MTL_MAP, text):
        name = rest.decode("utf-8", "replace").strip()
        for candidate in (name, *name.split()[-1:]):
            texture = find_beside(folder, candidate)
            if texture is not None:
                found.append(texture)
    return found


def _header(handle) -> list[str]:
    return handle.read(_HEADER_LIMIT).decode("latin-1").splitlines()


def _ply(handle, size: int, shown: str, folder) -> MeshScan:
    counts: dict[str, int] = {}
    for line in _header(handle):
        words = line.split()
        if words[:1] == ["end_header"]:
            break
        if words[:1] == ["element"] and len(words) >= 3:
            counts[words[1]] = counts.get(words[1], 0) + declared_count(words[2], shown)
    else:
        raise MeshBroken(f"no end_header in its first {_HEADER_LIMIT // 1024} KB", file=shown)
    return MeshScan(counts.get("face", 0) + counts.get("tristrips", 0), counts.get("vertex", 0))


def _off(handle, size: int, shown: str, folder) -> MeshScan:
    words = []
    for line in _header(handle):
        line = line.partition("#")[0]
        words += line.split()
        if len(words) >= 4:
            break
    if len(words) >= 3 and words[0].upper().endswith("OFF"):
        return MeshScan(declared_count(words[2], shown), declared_count(words[1], shown))
    return MeshScan()


def _scene(kind: str):
    """The scene_counts reader of ``kind``, imported when a COLLADA or glTF file is met
    (it brings urllib.parse and the XML reader; a robot of STL meshes needs neither)."""
    def scan(*args):
        from . import scene_counts

        return getattr(scene_counts, kind)(*args)
    return scan


_SCANNERS = {"stl": _stl, "obj": _obj, "ply": _ply, "off": _off, "dae": _scene("dae"),
             "gltf": _scene("gltf"), "glb": _scene("glb")}
