"""Remember what each picture was rendered from, to skip pictures whose inputs are unchanged.

The manifest (``.mcar-render.json`` in the output folder) maps each output, by its path
relative to that folder, to a fingerprint of everything that decides its pixels: the URDF
bytes, the bytes of every mesh it reads, the render options and the version of the drawing
code; plus the renderer that drew it (a picture drawn by OpenGL does not satisfy
``--renderer raycast``, either satisfies ``auto``) and a hash of the PNG written, so that a
picture edited or replaced by hand is rendered again. A missing or unreadable manifest (or
one over ``MCAR_MAX_INPUT_MB``) just means that everything is rendered.
"""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path

from .. import __version__
from ..atomic import atomic_write
from ..errors import InputError
from ..load.bounded import read_input

MANIFEST_NAME = ".mcar-render.json"
# Bump when the same input and options give different pixels (lighting, overlays, camera).
DRAWING_VERSION = 1


def sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def input_fingerprint(urdf: bytes, meshes: list[Path], settings: dict) -> str:
    """Hash of the URDF, its mesh files (names and bytes) and the settings (plain data)."""
    digest = hashlib.sha256()
    header = {"mcar": __version__, "drawing": DRAWING_VERSION, "settings": settings}
    digest.update(json.dumps(header, sort_keys=True).encode())
    digest.update(sha256(urdf).encode())
    for mesh in meshes:
        with open(mesh, "rb") as handle:  # in chunks: a mesh may be large
            mesh_hash = hashlib.file_digest(handle, "sha256").hexdigest()
        digest.update(str(mesh).encode() + b"\0" + mesh_hash.encode())
    return digest.hexdigest()


class Manifest:
    """The fingerprints of the pictures in one folder; ``save()`` writes it atomically."""

    def __init__(self, folder: Path):
        self.folder = Path(folder)
        self.path = self.folder / MANIFEST_NAME
        self.entries: dict[str, dict] = {}
        self._changed = False
        try:  # within the input limit: it may be a link to /dev/zero, or a FIFO
            data = json.loads(read_input(self.path))
            if isinstance(data, dict) and isinstance(data.get("outputs"), dict):
                self.entries = {k: v for k, v in data["outputs"].items() if isinstance(v, dict)}
        except (OSError, ValueError, RecursionError, InputError):
            pass

    def key(self, target: Path) -> str:
        """The output's name in the manifest: its path relative to the folder."""
        return Path(os.path.relpath(Path(target).resolve(), self.folder.resolve())).as_posix()

    def is_current(self, target: Path, fingerprint: str, renderer: str = "auto") -> bool:
        """True if ``target`` was drawn from this fingerprint by an acceptable renderer
        (``auto``: any) and is still as written."""
        entry = self.entries.get(self.key(target))
        if not entry or entry.get("input") != fingerprint:
            return False
        if renderer != "auto" and entry.get("renderer") != renderer:
            return False
        try:
            return sha256(Path(target).read_bytes()) == entry.get("png")
        except OSError:
            return False

    def record(self, target: Path, fingerprint: str, png: bytes, caption: str,
               renderer: str | None = None) -> None:
        entry = {"input": fingerprint, "png": sha256(png), "caption": caption}
        if renderer is not None:
            entry["renderer"] = renderer
        self.entries[self.key(target)] = entry
        self._changed = True

    def forget_all_but(self, keys: set[str]) -> None:
        """Drop entries of outputs no longer produced (after a full run)."""
        stale = set(self.entries) - keys
        for key in stale:
            del self.entries[key]
        self._changed = self._changed or bool(stale)

    def save(self) -> None:
        if self._changed:
            text = json.dumps({"outputs": dict(sorted(self.entries.items()))}, indent=1)
            atomic_write(self.path, text + "\n")
            self._changed = False
