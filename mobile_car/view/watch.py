"""Whether any of a robot's files changed since it was last looked at.

Polling the files' stamps (a robot has a few dozen files at most) needs no notification
library and sees every way an editor saves: in place (new mtime and size) or by writing a
new file and renaming it over the old one (new inode); a file removed counts as changed.
"""

from __future__ import annotations

import os
from pathlib import Path


def _stamp(path: Path) -> tuple | None:
    try:
        info = os.stat(path)
    except OSError:
        return None
    return info.st_mtime_ns, info.st_size, info.st_ino


class FileWatch:
    """The stamps of a set of files; :meth:`changed` says if one differs now."""

    def __init__(self, paths=()):
        self.watch(paths)

    def watch(self, paths) -> None:
        """Watch these files from now on (after a rebuild: its own list of files)."""
        self.stamps = {Path(path): _stamp(Path(path)) for path in paths}

    @property
    def paths(self) -> list[Path]:
        return list(self.stamps)

    def changed(self) -> list[Path]:
        """The files whose stamp differs from the one recorded; each is recorded anew,
        so one edit is reported once."""
        changed = []
        for path, stamp in self.stamps.items():
            now = _stamp(path)
            if now != stamp:
                self.stamps[path] = now
                changed.append(path)
        return changed
