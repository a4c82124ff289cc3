"""Compressed mesh files (``.stl.bz2``, ``.stl.gz``, ``.zip``, ``.tar.gz``, ``.tar.bz2``,
and the formats that are zip archives: ``.zae`` COLLADA, ``.3mf``, ``.3dxml``),
decompressed within a cap.

trimesh decompresses such files itself, whole: 20 KB of ``.stl.bz2`` can stand for 3 GB.
Here the standard library's decompressors are read in chunks and stopped once the
decompressed bytes (every member of an archive, and a tar's headers, together) pass
``MCAR_MAX_MESH_MB``; the caller hands trimesh the bytes.
"""

from __future__ import annotations

from pathlib import Path

from ..errors import InputError

MAX_MESH_MB_ENV = "MCAR_MAX_MESH_MB"
DEFAULT_MAX_MESH_MB = 256  # a binary STL of 5 million triangles
_CHUNK = 1 << 20
# Mesh formats that are zip archives; trimesh would inflate every member whole.
ZIP_FORMATS = ("zae", "3mf", "3dxml")
# Longest first: ``x.tar.gz`` is a tar, ``x.stl.gz`` one mesh.
KINDS = ("tar.gz", "tgz", "tar.bz2", "zip", "bz2", "gz", *ZIP_FORMATS)


class MeshOverLimit(InputError):
    """A mesh larger than a limit the user can raise: not read, drawn as a marker."""


def broken_errors() -> tuple[type[BaseException], ...]:
    """What a corrupt compressed file raises (bz2 and gzip: OSError "invalid data")."""
    import tarfile
    import zipfile
    import zlib

    return (OSError, EOFError, ValueError, zlib.error, zipfile.BadZipFile, tarfile.TarError)


def compressed_kind(path: str | Path) -> str | None:
    """Which of KINDS the file name says it is, or None for a plain file."""
    name = Path(path).name.lower()
    return next((kind for kind in KINDS if name.endswith("." + kind)), None)


def max_mesh_bytes() -> int:
    from ..settings import env_number

    return int(env_number(MAX_MESH_MB_ENV, DEFAULT_MAX_MESH_MB, 1, 1e6, "MB") * 1024 * 1024)


class _Budget:
    """The decompressed bytes left; InputError (naming the file) once they are spent."""

    def __init__(self, shown: str):
        self.left = max_mesh_bytes()
        self.cap = self.left
        self.shown = shown

    def spend(self, count: int) -> None:
        self.left -= count
        if self.left < 0:
            raise MeshOverLimit(f"decompresses to more than {self.cap / 1024 / 1024:g} MB; "
                             f"set {MAX_MESH_MB_ENV} to raise the limit", file=self.shown)


class _Capped:
    """A binary stream that charges every byte read from it to a _Budget."""

    def __init__(self, raw, budget: _Budget):
        self.raw = raw
        self.budget = budget

    def read(self, size: int = -1) -> bytes:
        if size is None or size < 0:
            return b"".join(iter(lambda: self.read(_CHUNK), b""))
        data = self.raw.read(min(size, _CHUNK, self.budget.left + 1))
        self.budget.spend(len(data))
        return data


def decompressed_members(path: Path, shown: str | None = None) -> list[tuple[str, bytes]]:
    """(name, bytes) of each file a compressed mesh holds: one for ``.bz2``/``.gz`` (its
    name without that suffix), each regular member of an archive. InputError over the
    cap; one of broken_errors() for a corrupt file."""
    # Imported here: checking a robot without compressed meshes never needs them.
    import bz2
    import gzip
    import tarfile
    import zipfile

    kind = compressed_kind(path)
    budget = _Budget(shown or str(path))
    if kind in ("bz2", "gz"):
        opener = bz2.open if kind == "bz2" else gzip.open
        with opener(path, "rb") as stream:
            return [(Path(path).name[:-len(kind) - 1], _Capped(stream, budget).read())]
    if kind == "zip" or kind in ZIP_FORMATS:
        members = []
        with zipfile.ZipFile(path) as archive:
            for info in archive.infolist():
                if not info.is_dir():
                    with archive.open(info) as stream:
                        members.append((info.filename, _Capped(stream, budget).read()))
        return members
    opener = bz2.open if kind == "tar.bz2" else gzip.open
    members = []
    # "r|": a stream, read in order, so tar headers (pax ones can be large) are charged too.
    with opener(path, "rb") as raw, tarfile.open(fileobj=_Capped(raw, budget), mode="r|") as tar:
        for member in tar:
            if member.isfile():
                members.append((member.name, tar.extractfile(member).read()))
    return members


def suffix_of(name: str) -> str:
    """A member's format as trimesh names it: ``wheel.STL`` -> ``stl``."""
    return name.rpartition(".")[2].lower()
