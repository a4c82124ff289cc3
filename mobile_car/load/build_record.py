"""What each built file in a build folder was made from, so that a build with nothing
changed writes nothing and expands nothing.

One record per build folder (``.mcar-build.json``), one entry per output, written by every
command that builds into the folder (``mcar build``, ``mcar ci``), so that none of them
undoes another's work: an entry holds the output's *key* (a hash of what decides it
besides the files it reads: the output format, xacro arguments, overrides, package search;
see :mod:`mobile_car.freshness`), the stamps of every file it was made from, the stamp of
the output as written, and xacro's warnings (shown again when the output is kept). An
output is current when its key and every stamp match and the file is still what was
written; anything else, or a record that is damaged, forged or not sealed by this user's
mcar (:mod:`mobile_car.record_seal`), means building it again.

Kept free of xacro, lxml, numpy: a no-op build reads its record through this.
"""

from __future__ import annotations

import os
from pathlib import Path

from ..freshness import (
    Stamper,
    file_sha256,
    key_of,
    output_current,
    output_stamp,
    read_record,
    stamps_current,
    write_record,
)

RECORD_NAME = ".mcar-build.json"
SECTION = "outputs"


def build_key(output_format: str, settings: dict) -> str:
    """The key of a built file: its format and its basis' settings (freshness.Basis)."""
    return key_of("build", output_format, settings)


class BuildRecord:
    """The entries of one build folder; ``save()`` writes them back, sealed, if changed."""

    def __init__(self, folder: Path):
        self.folder = Path(folder)
        self.path = self.folder / RECORD_NAME
        self.entries: dict[str, dict] = read_record(self.path, SECTION)
        self.stamper = Stamper()
        self._changed = False

    def name(self, target: Path) -> str:
        return Path(os.path.relpath(os.path.abspath(target),
                                    os.path.abspath(self.folder))).as_posix()

    def fresh(self, target: Path, key: str) -> list[str] | None:
        """xacro's warnings for ``target`` if it is current for ``key`` (see the module's
        docstring), else None."""
        entry = self.entries.get(self.name(target))
        if not entry or entry.get("key") != key:
            return None
        warnings = entry.get("warnings")
        if not isinstance(warnings, list) or not all(isinstance(w, str) for w in warnings):
            return None
        current, refreshed = stamps_current(entry.get("files"))
        if not current:
            return None
        written, touched = output_current(target, entry.get("output"))
        if not written:
            return None
        self._changed = self._changed or refreshed or touched
        return list(warnings)

    def record(self, target: Path, key: str, reads, warnings, generated=()) -> None:
        """Remember what ``target``, just written, was made from: ``reads``, the files
        its expansion and settings read (``generated``: files written for it, such as
        the overrides' properties file, which are not inputs)."""
        name = self.name(target)
        self._changed = True
        files = self.stamper.stamps(reads, skip=generated)
        try:
            output = output_stamp(target, file_sha256(target))
        except OSError:
            output = None
        if files is None or output is None:  # something could not be stamped: build again
            self.entries.pop(name, None)
            return
        self.entries[name] = {"key": key, "files": files, "output": output,
                              "warnings": [str(w) for w in warnings]}

    def save(self) -> None:
        if self._changed:
            write_record(self.path, SECTION, self.entries)
            self._changed = False
