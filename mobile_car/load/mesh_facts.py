"""What ``mcar check`` needs of a mesh file, without reading its triangles on every run:
whether it loads, its bounding box, its counts and the other files it reads.

The box is in metres, in the mesh's own frame, the file's unit applied (COLLADA
``<unit>``) and the URDF's ``scale`` not. Working it out means reading the mesh: a
binary STL's triangles with numpy (its size says how many), any other format through
mcar's reader (:mod:`.mesh_reader`, trimesh). Every file is measured first, within the
mesh limits (:mod:`.mesh_limits`), as before any read.

What was found is kept in the user's cache folder (``mesh-facts/`` in
:func:`~mobile_car.record_seal.cache_dir`), two ways:

* **by path**, with the file's identity (device, inode, size, modification and change
  times: what git's index trusts) and that of every file it reads: the next run on the
  same checkout stats the files and reads nothing else;
* **by content** (SHA-256 of the bytes), for formats that cost more to read than to
  hash (all but binary STL): a fresh clone, or a CI job that keeps the cache folder,
  hashes each mesh and skips trimesh.

A small binary STL (the first 10,000 triangles a run meets) is neither looked up nor
kept: reading it costs less than believing a record, which needs the seal keeper's
process, so a robot whose meshes are all small starts no process to be checked.

The cache is an input like the robot: a record planted there (by a CI cache shared with
a pull request's jobs, say) could make a broken mesh look sound or a mesh look any size.
So every record is sealed with this user's record key (:mod:`mobile_car.record_seal`, as
the render manifest and the ci record are) and read within a size bound; a record that is
damaged, unsealed, of another version, or not a regular file is ignored, and the mesh
read again. Where no key can be kept, nothing is cached. A record lost to a crash costs
one more read: they are written by rename, without the fsync outputs get.
"""

from __future__ import annotations

import math
import os
import stat
import sys
from pathlib import Path

from ..errors import InputError
from ..values import Value
from .bounded import open_regular
from .compressed import compressed_kind, max_mesh_bytes
from .mesh_limits import MeshOverLimit, max_mesh_faces, scan_mesh

FACTS_VERSION = 1  # bump when the same file gives other facts (a reader change)
_FOLDER = "mesh-facts"
_RECORD_LIMIT = 1 << 16  # a record is a few hundred bytes; more was not written by mcar
_PATH_SECTION, _CONTENT_SECTION = "mesh-path", "mesh-content"


class MeshFacts(Value):
    """``problem``: why it cannot be loaded (None: it loads); ``over_limit``: the mesh
    limit it passes (then it is not read, and nothing else is known); ``bounds``:
    ((xmin, ymin, zmin), (xmax, ymax, zmax)) in metres, None when unknown; ``reads``:
    the other files it reads (materials, textures, buffers), that exist."""

    _fields = __slots__ = ("problem", "over_limit", "bounds", "faces", "vertices", "reads")
    problem: str | None
    over_limit: str | None
    bounds: tuple | None
    faces: int | None
    vertices: int | None
    reads: tuple[Path, ...]

    def __init__(self, problem: str | None = None, over_limit: str | None = None,
                 bounds: tuple | None = None, faces: int | None = None,
                 vertices: int | None = None, reads: tuple[Path, ...] = ()):
        self._set(problem, over_limit, bounds, faces, vertices, reads)


_known: dict[tuple, MeshFacts] = {}
# Triangles of binary STL one run reads without records (see _small_binary_stl): about
# as long in Python as starting the seal keeper; 500 KB of STL.
DIRECT_TRIANGLES = 10_000
_direct_triangles = 0


def mesh_facts(path: Path, shown: str) -> MeshFacts:
    """The facts of the regular file at ``path`` (``shown`` names it in messages).
    OSError when it cannot be read at all; InputError when it is not a regular file."""
    path = Path(path).resolve()
    info = os.stat(path)
    identity = _identity(info)
    key = (str(path), *identity, max_mesh_bytes(), max_mesh_faces())
    if key not in _known:
        _known[key] = _facts(path, shown, info, identity)
    return _known[key]


def _facts(path: Path, shown: str, info, identity: list) -> MeshFacts:
    if not stat.S_ISREG(info.st_mode):
        scan_mesh(path, shown)  # raises the located InputError
    direct = _small_binary_stl(path, shown, info.st_size)
    if direct is not None:
        return direct
    kept = _by_path(path, identity)
    if kept is not None and not _maybe_over_limit(info.st_size, kept):
        return kept
    try:
        scan = scan_mesh(path, shown)
    except MeshOverLimit as error:
        return MeshFacts(over_limit=error.message)
    except InputError as error:  # a file whose own counts contradict it
        return _remember(path, identity, MeshFacts(problem=error.message))
    reads = tuple(scan.reads)
    triangles = binary_stl_triangles(path, info.st_size)
    if triangles:
        facts = MeshFacts(bounds=_binary_stl_bounds(path, triangles), faces=triangles,
                          vertices=3 * triangles, reads=reads)
        return _remember(path, identity, facts)
    digest = _content_digest(path, reads)
    found = _by_content(digest) if digest else None
    if found is None:
        found = _read(path, shown, scan)
        if found.over_limit is not None:
            return found
        if digest:
            _store(_CONTENT_SECTION, "content-" + digest, {"facts": _as_json(found)})
    facts = MeshFacts(found.problem, None, found.bounds, found.faces, found.vertices,
                      tuple(dict.fromkeys([*reads, *found.reads])))
    return _remember(path, identity, facts)


def _small_binary_stl(path: Path, shown: str, size: int) -> MeshFacts | None:
    """The facts of a binary STL small enough that reading it costs less than a record
    would, or None. A record is only believed once its seal is checked, which starts the
    keeper process (:mod:`mobile_car.seal_keeper`): a new interpreter, more time than
    reading thousands of triangles in Python. So the first triangles a run meets are
    read, within a budget, and never recorded; past it, the records spare numpy."""
    global _direct_triangles
    if path.suffix.lower() != ".stl" or size > 84 + 50 * DIRECT_TRIANGLES:
        return None  # not worth opening: a large one's record is read
    try:
        triangles = binary_stl_triangles(path, size)
    except (OSError, InputError):
        return None  # the full path says why, as it did
    if not triangles or _direct_triangles + triangles > DIRECT_TRIANGLES:
        return None
    try:
        scan = scan_mesh(path, shown)
    except MeshOverLimit as error:
        return MeshFacts(over_limit=error.message)
    except InputError as error:
        return MeshFacts(problem=error.message)
    _direct_triangles += triangles
    return MeshFacts(bounds=_binary_stl_bounds(path, triangles), faces=triangles,
                     vertices=3 * triangles, reads=tuple(scan.reads))


def _maybe_over_limit(size: int, facts: MeshFacts) -> bool:
    """Whether a file known from the cache may pass a limit now (the limits can change):
    then it is measured again, and the measure says which."""
    limit = max_mesh_faces()
    return size > max_mesh_bytes() or (facts.faces or 0) > limit or \
        (facts.vertices or 0) > 3 * limit


def _read(path: Path, shown: str, scan) -> MeshFacts:
    """The facts of a mesh trimesh must read: it loads, or why not; its box."""
    from ..held_signals import import_held

    trimesh = import_held("trimesh")  # numpy, trimesh: only for a mesh not yet known
    from .compressed import broken_errors, suffix_of
    from .mesh_reader import load_mesh

    if compressed_kind(path) is None and suffix_of(path.name) not in \
            trimesh.available_formats():
        return MeshFacts(faces=scan.faces, vertices=scan.vertices)  # exists: all we know
    try:
        loaded, reads = load_mesh(path, shown, textures=False, force="mesh")
    except MeshOverLimit as error:  # a member of an archive, counted once decompressed
        return MeshFacts(over_limit=error.message)
    except InputError as error:
        return MeshFacts(problem=error.message)
    except broken_errors() as exc:
        return MeshFacts(problem=_short(exc))
    except Exception as exc:  # trimesh raises anything from ValueError to struct.error
        return MeshFacts(problem=_short(exc))
    vertices = getattr(loaded, "vertices", None)
    if vertices is None or len(vertices) == 0:
        return MeshFacts(problem="it holds no geometry", reads=tuple(reads))
    return MeshFacts(bounds=_finite_bounds(loaded.bounds), faces=len(loaded.faces),
                     vertices=len(vertices), reads=tuple(reads))


def _short(exc: BaseException) -> str:
    return " ".join(str(exc).split())[:200] or type(exc).__name__


def _finite_bounds(bounds) -> tuple | None:
    low, high = (tuple(float(v) for v in corner) for corner in bounds)
    return (low, high) if all(map(math.isfinite, low + high)) else None


def binary_stl_triangles(path: Path, size: int | None = None) -> int:
    """The triangle count of a binary STL whose size matches it (however its header
    starts), else 0: then trimesh reads it (check, sim and export all decide by this)."""
    if path.suffix.lower() != ".stl":
        return 0
    with open_regular(path) as handle:
        if size is None:
            size = os.fstat(handle.fileno()).st_size
        if size < 134:
            return 0
        header = handle.read(84)
    count = int.from_bytes(header[80:84], "little")
    return count if size == 84 + 50 * count else 0


def _binary_stl_bounds(path: Path, triangles: int) -> tuple | None:
    """The box around a binary STL's corners: the nine floats of each 50-byte record
    copied out by numpy (a structured view), then each axis's minimum and maximum: no
    Python per triangle, and no reduction over a strided 3-D view, which is five times
    slower. A small one without numpy, whose import costs more than the reading."""
    if triangles <= DIRECT_TRIANGLES:
        return _small_stl_bounds(path, triangles)
    import numpy as np

    corners = np.dtype({"names": ["corners"], "formats": [("<f4", (9,))], "offsets": [12],
                        "itemsize": 50})
    with open_regular(path) as handle:
        handle.seek(84)
        data = handle.read(50 * triangles)
    points = np.frombuffer(data, dtype=corners, count=triangles)["corners"].reshape(-1, 3)
    with np.errstate(invalid="ignore"):
        return _finite_bounds(([points[:, k].min() for k in range(3)],
                               [points[:, k].max() for k in range(3)]))


def _small_stl_bounds(path: Path, triangles: int) -> tuple | None:
    """What _binary_stl_bounds finds, in Python: the 36 corner bytes of every record
    gathered by 36 strided slice copies (C loops), read as little-endian floats."""
    with open_regular(path) as handle:
        handle.seek(84)
        data = handle.read(50 * triangles)
    if len(data) < 50 * triangles:
        return None
    corners = bytearray(36 * triangles)
    for offset in range(36):
        corners[offset::36] = data[12 + offset::50][:triangles]
    if sys.byteorder == "little":  # read in place, without the array module's import
        values = memoryview(corners).cast("f").tolist()
    else:
        import array

        floats = array.array("f", bytes(corners))
        floats.byteswap()
        values = floats.tolist()
    if not math.isfinite(sum(values)):  # a NaN or an infinity: numpy's box is not finite
        return None
    return (tuple(min(values[axis::3]) for axis in range(3)),
            tuple(max(values[axis::3]) for axis in range(3)))


def _identity(info) -> list:
    return [info.st_dev, info.st_ino, info.st_size, info.st_mtime_ns, info.st_ctime_ns]


def _content_digest(path: Path, reads) -> str | None:
    """SHA-256 of the mesh's bytes and of the files it reads, with the reader's version."""
    import hashlib  # only for a mesh that is looked up: it loads OpenSSL

    digest = hashlib.sha256(f"mcar mesh facts {FACTS_VERSION}\0".encode())
    try:
        for file in (path, *reads):
            digest.update(str(Path(file).name).encode() + b"\0")
            with open_regular(file) as handle:
                if os.fstat(handle.fileno()).st_size > max_mesh_bytes():
                    return None  # a texture past the cap: not read, so not known by content
                digest.update(hashlib.file_digest(handle, "sha256").digest())
    except (OSError, InputError):
        return None
    return digest.hexdigest()


# -- the records -----------------------------------------------------------------------


def _folder() -> Path:
    from ..record_seal import cache_dir

    return cache_dir() / _FOLDER


def _path_name(path: Path) -> str:
    import hashlib

    return "path-" + hashlib.sha256(os.fsencode(str(path))).hexdigest()[:40]


def _by_path(path: Path, identity: list) -> MeshFacts | None:
    entry = _load(_PATH_SECTION, _path_name(path))
    if entry is None or entry.get("path") != str(path) or entry.get("identity") != identity:
        return None
    reads = entry.get("reads")
    if not isinstance(reads, list):
        return None
    for item in reads:  # a texture or .mtl edited: the record no longer holds
        if not (isinstance(item, list) and len(item) == 2 and isinstance(item[0], str)):
            return None
        try:
            if _identity(os.stat(item[0])) != item[1]:
                return None
        except (OSError, ValueError):
            return None
    facts = _from_json(entry.get("facts"))
    if facts is None:
        return None
    return MeshFacts(facts.problem, None, facts.bounds, facts.faces, facts.vertices,
                     tuple(Path(item[0]) for item in reads))


def _by_content(digest: str) -> MeshFacts | None:
    entry = _load(_CONTENT_SECTION, "content-" + digest)
    return None if entry is None else _from_json(entry.get("facts"))


def _remember(path: Path, identity: list, facts: MeshFacts) -> MeshFacts:
    reads = []
    for file in facts.reads:
        try:
            reads.append([str(file), _identity(os.stat(file))])
        except OSError:
            return facts  # gone already: not worth keeping
    _store(_PATH_SECTION, _path_name(path), {"path": str(path), "identity": identity,
                                             "reads": reads, "facts": _as_json(facts)})
    return facts


def _as_json(facts: MeshFacts) -> dict:
    return {"problem": facts.problem, "faces": facts.faces, "vertices": facts.vertices,
            "bounds": None if facts.bounds is None else [list(c) for c in facts.bounds]}


def _from_json(data) -> MeshFacts | None:
    """Facts from a record, or None for anything but what _as_json writes."""
    if not isinstance(data, dict) or set(data) != {"problem", "faces", "vertices", "bounds"}:
        return None
    problem, faces, vertices, bounds = (data[k] for k in ("problem", "faces", "vertices",
                                                           "bounds"))
    counts_ok = all(v is None or (type(v) is int and v >= 0) for v in (faces, vertices))
    if not counts_ok or not (problem is None or isinstance(problem, str)):
        return None
    if bounds is not None:
        corners_ok = isinstance(bounds, list) and len(bounds) == 2 and all(
            isinstance(c, list) and len(c) == 3 and all(
                type(v) in (int, float) and math.isfinite(v) for v in c) for c in bounds)
        if not corners_ok:
            return None
        bounds = tuple(tuple(float(v) for v in corner) for corner in bounds)
    return MeshFacts(problem=problem, bounds=bounds, faces=faces, vertices=vertices)


def _load(section: str, name: str) -> dict | None:
    from ..record_seal import unsealed_entries

    try:
        with open_regular(_folder() / f"{name}.json") as handle:
            data = handle.read(_RECORD_LIMIT + 1)
        if len(data) > _RECORD_LIMIT:
            return None
        import json

        entries = unsealed_entries(json.loads(data), section)
    except (OSError, ValueError, RecursionError, InputError):
        return None
    if entries is None or entries.get("version") != FACTS_VERSION:
        return None
    return entries


def _store(section: str, name: str, entry: dict) -> None:
    """Write a sealed record by rename; nothing where no key or folder can be had."""
    from ..record_seal import sealed_text

    text = sealed_text(section, {**entry, "version": FACTS_VERSION})
    if text is None:
        return
    folder = _folder()
    temporary = folder / f".{name}.{os.getpid()}.tmp"
    try:
        folder.mkdir(parents=True, exist_ok=True, mode=0o700)
        with open(temporary, "w", encoding="utf-8") as handle:
            handle.write(text)
        os.replace(temporary, folder / f"{name}.json")
    except OSError:
        try:
            temporary.unlink()
        except OSError:
            pass
