"""What several readers of one run ask of the same file, made once a process while the file
stays the same: sim's converted collision meshes, a control package's parsed YAML."""

from __future__ import annotations

import os


class FileMemo:
    """What was made of a file, kept within one process while the file's identity holds
    (an edit, even one that puts the size and mtime back, makes it again): for what
    several readers of one run ask of the same file. At most ``most`` files are kept."""

    def __init__(self, most: int):
        self._kept: dict[str, tuple[list[int], object]] = {}  # real path -> (identity, made)
        self._most = most

    def get(self, path, make, still_good=None):
        """``make()``'s value for ``path``, made again unless kept under its identity (and
        ``still_good(value)``, where given); a file that cannot be stat'ed is made every
        time (``make`` says why it cannot be read), what ``make`` raises never kept."""
        from .freshness import identity  # (not at import: it imports dataclasses)

        try:
            real = os.path.realpath(path)
            stamp = identity(os.stat(real))
        except (OSError, ValueError):
            return make()
        kept = self._kept.get(real)
        if kept is not None and kept[0] == stamp and (still_good is None
                                                       or still_good(kept[1])):
            return kept[1]
        made = make()
        if len(self._kept) >= self._most:
            self._kept.clear()
        self._kept[real] = (stamp, made)
        return made
