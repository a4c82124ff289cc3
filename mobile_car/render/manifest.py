"""Remember what each picture was rendered from, to skip pictures whose inputs are unchanged.

The manifest (``.mcar-render.json`` in the output folder) maps each output, by its path
relative to that folder, to what decided its pixels, twice over:

* ``key`` and ``files``: a hash of the settings (arguments, overrides, package search,
  render options, mcar's version; see :mod:`mobile_car.freshness`) and the stamps of every
  file the picture was made from (the robot file, everything its expansion read, its
  meshes and what they pull in: ``.mtl`` files, textures). A run that finds both unchanged
  skips the picture after a few ``stat()`` calls, loading nothing: a no-op ``mcar render``
  never imports xacro or trimesh.
* ``input``: a fingerprint of the expanded URDF, the mesh (and texture) bytes and the
  settings, for when a stamped file did change: a picture whose URDF comes out the same
  is not redrawn.

Plus the renderer that drew it (a picture drawn by OpenGL does not satisfy ``--renderer
raycast``, either satisfies ``auto``), the hash and stat of the PNG written (a picture
edited or replaced by hand is rendered again) and the check's warnings shown with it. A
missing or unreadable manifest (or one over ``MCAR_MAX_INPUT_MB``) just means that
everything is rendered.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

from ..freshness import (
    Basis,
    diagnostics_from,
    identity,
    is_environment_stamp,
    key_of,
    output_current,
    output_stamp,
    read_record,
    stamps_current,
    write_record,
)

MANIFEST_NAME = ".mcar-render.json"
CONTACT_SHEET = "index.png"
# Bump when the same input and options give different pixels (lighting, overlays, camera).
DRAWING_VERSION = 3  # 2: link frames with names; 3: COLLADA units applied, unread meshes drawn
# as markers


def sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def input_fingerprint(urdf: bytes, meshes: list[Path], settings: dict) -> str:
    """Hash of the URDF, its mesh files and the files they pull in (names and bytes; for a
    file over the mesh size limit, which is not read, its identity) and the
    settings (plain data)."""
    from ..load.compressed import max_mesh_bytes

    digest = hashlib.sha256()
    digest.update(key_of("drawing", DRAWING_VERSION, settings).encode())  # mcar's version too
    digest.update(sha256(urdf).encode())
    cap = max_mesh_bytes()
    for mesh in meshes:
        with open(mesh, "rb") as handle:  # in chunks: a mesh may be large
            info = os.fstat(handle.fileno())
            if info.st_size > cap:
                mesh_hash = " ".join(map(str, identity(info)))  # (not read: never hashed)
            else:
                mesh_hash = hashlib.file_digest(handle, "sha256").hexdigest()
        digest.update(str(mesh).encode() + b"\0" + mesh_hash.encode())
    return digest.hexdigest()


def picture_key(basis: Basis, options) -> str:
    """The key of a picture: its robot's basis and the render options (RenderOptions)."""
    return key_of("render", DRAWING_VERSION, basis.settings, options.fingerprint())


class Manifest:
    """The fingerprints of the pictures in one folder; ``save()`` writes it atomically."""

    def __init__(self, folder: Path):
        self.folder = Path(folder)
        self.path = self.folder / MANIFEST_NAME
        self.entries: dict[str, dict] = read_record(self.path, "outputs")
        self._changed = False

    def key(self, target: Path) -> str:
        """The output's name in the manifest: its path relative to the folder."""
        return Path(os.path.relpath(Path(target).resolve(), self.folder.resolve())).as_posix()

    def _png_current(self, target: Path, entry: dict) -> bool:
        """The PNG is still what was written: same stat, else same bytes."""
        if entry.get("png_stat") is None:  # written by an older mcar: compare the bytes
            try:
                return sha256(Path(target).read_bytes()) == entry.get("png")
            except OSError:
                return False
        ok, refreshed = output_current(target, entry["png_stat"])
        self._changed = self._changed or refreshed
        return ok

    def is_current(self, target: Path, fingerprint: str, renderer: str = "auto") -> bool:
        """True if ``target`` was drawn from this fingerprint by an acceptable renderer
        (``auto``: any) and is still as written."""
        entry = self.entries.get(self.key(target))
        if not entry or entry.get("input") != fingerprint:
            return False
        if renderer != "auto" and entry.get("renderer") != renderer:
            return False
        return self._png_current(target, entry)

    def fresh(self, target: Path, key: str, renderer: str = "auto") -> dict | None:
        """The entry of ``target`` if its key and every stamped file are unchanged and
        the picture is as written (nothing is loaded), else None."""
        entry = self.entries.get(self.key(target))
        if not entry or entry.get("key") != key or not entry.get("files"):
            return None
        if renderer != "auto" and entry.get("renderer") != renderer:
            return None
        try:  # the warnings shown again with the picture: damaged, and it is drawn again
            diagnostics_from(entry.get("warnings") or [])
        except ValueError:
            return None
        current, refreshed = stamps_current(entry["files"])
        self._changed = self._changed or refreshed
        if not current or not self._png_current(target, entry):
            return None
        return entry

    def record(self, target: Path, fingerprint: str, png: bytes, caption: str,
               renderer: str | None = None) -> None:
        entry = {"input": fingerprint, "png": sha256(png), "caption": caption,
                 "png_stat": output_stamp(target, sha256(png))}
        if renderer is not None:
            entry["renderer"] = renderer
        self.entries[self.key(target)] = entry
        self._changed = True

    def stamp(self, target: Path, key: str, files: list | None, warnings: list) -> None:
        """Record what ``target`` was made from (``files``: stamps, None when one could
        not be stamped) and the warnings shown with it, for :meth:`fresh`."""
        entry = self.entries.get(self.key(target))
        if entry is None:
            return
        entry.update(key=key, files=files, warnings=warnings)
        self._changed = True

    def forget_all_but(self, keys: set[str]) -> None:
        """Drop entries of outputs no longer produced (after a full run)."""
        stale = set(self.entries) - keys
        for key in stale:
            del self.entries[key]
        self._changed = self._changed or bool(stale)

    def orphans(self, keys: set[str]) -> set[str]:
        """The entries no run can make again: not among ``keys`` (this run's outputs) and
        made from a file that is gone (a robot file deleted, a variant removed) or from
        files never stamped. The pictures another command drew into the same folder (mcar
        ci's variants, beside mcar render's pictures) are kept, so that neither command
        undoes the other's work and both show the same contact sheet."""
        found = set()
        for key, entry in self.entries.items():
            if key in keys or key == CONTACT_SHEET:
                continue
            files = entry.get("files")
            if not isinstance(files, list) or not files or not all(
                    is_environment_stamp(stamp) or isinstance(stamp, list) and stamp
                    and isinstance(stamp[0], str) and os.path.exists(stamp[0])
                    for stamp in files):
                found.add(key)
        return found

    def forget_orphans(self, keys: set[str]) -> None:
        """Drop :meth:`orphans` (after a full run over a package or folder)."""
        self.forget_all_but(set(self.entries) - self.orphans(keys))

    @staticmethod
    def sheet_caption(key: str) -> str:
        """A picture's caption on the contact sheet: its path below the folder, without
        ``.png`` (``chassis/steps/01_plate``). One rule, whichever command drew it."""
        return key.removesuffix(".png")

    def sheet_pictures(self) -> list[tuple[str, dict]]:
        """The pictures the contact sheet shows: every one listed that is on disk."""
        return sorted((key, entry) for key, entry in self.entries.items()
                      if key != CONTACT_SHEET and isinstance(entry.get("png"), str)
                      and (self.folder / key).is_file())

    def sheet_fingerprint(self) -> str:
        return sha256(repr((DRAWING_VERSION, [(key, entry.get("png"))
                                              for key, entry in self.sheet_pictures()])).encode())

    def sheet_is_current(self) -> bool:
        return self.is_current(self.folder / CONTACT_SHEET, self.sheet_fingerprint())

    def save(self) -> None:
        if self._changed:
            write_record(self.path, "outputs", self.entries)
            self._changed = False
