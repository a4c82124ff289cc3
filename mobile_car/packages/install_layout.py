"""Where a file of an installed ROS 2 package comes from in its source folder.

``$(find PKG)`` under ROS 2 is ``PREFIX/share/PKG``: the folders CMakeLists.txt
installs there, not the source tree. A package may install ``description/urdf`` as
``share/PKG/urdf``, so its robot writes ``$(find PKG)/urdf/x.xacro``, a path that does
not exist in the checkout mcar finds (ros2_control_demos installs every example's
``description/ros2_control`` so). This maps such a path back through the package's
``install(DIRECTORY ...)`` and ``install(FILES ...)`` rules whose destination is
``share/${PROJECT_NAME}``: only for a file that is missing where it was named, so a
package laid out as it installs reads exactly what it did.
"""

from __future__ import annotations

import re
from pathlib import Path, PurePosixPath

from ..load.bounded import read_text_quietly

_INSTALL = re.compile(r"\binstall\s*\(([^()]*)\)", re.IGNORECASE)
_PROJECT = re.compile(r"\bproject\s*\(\s*([A-Za-z0-9_.-]+)", re.IGNORECASE)
_COMMENT = re.compile(r"#[^\n]*")
# Words after which an install() rule's sources end (CMake's install() keywords).
_KEYWORDS = {"DESTINATION", "PATTERN", "REGEX", "FILES_MATCHING", "USE_SOURCE_PERMISSIONS",
             "PERMISSIONS", "FILE_PERMISSIONS", "DIRECTORY_PERMISSIONS", "CONFIGURATIONS",
             "COMPONENT", "OPTIONAL", "EXCLUDE_FROM_ALL", "RENAME", "MESSAGE_NEVER",
             "EXCLUDE"}


def install_rules(root: Path, name: str) -> list[tuple[str, str, str]]:
    """The (kind, source, destination) of each rule of ``root``'s CMakeLists.txt that
    installs into ``share/NAME``: kind DIRECTORY or FILES, source relative to ``root`` as
    written (a trailing ``/`` kept: it installs the folder's contents), destination
    relative to ``share/NAME`` ("" for the share folder itself)."""
    text = read_text_quietly(root / "CMakeLists.txt")
    if not text:
        return []
    text = _COMMENT.sub("", text)
    project = _PROJECT.search(text)
    names = {name} | ({project.group(1)} if project else set())
    rules = []
    for body in _INSTALL.findall(text):
        words = [w.strip("\"'") for w in body.split()]
        if not words or words[0] not in ("DIRECTORY", "FILES") or "DESTINATION" not in words:
            continue
        sources = []
        for word in words[1:]:
            if word in _KEYWORDS:
                break
            sources.append(word)
        destination = _share_relative(words[words.index("DESTINATION") + 1:], names)
        if destination is not None:
            rules += [(words[0], source, destination) for source in sources]
    return rules


def _share_relative(after: list[str], names: set[str]) -> str | None:
    if not after:
        return None
    parts = PurePosixPath(after[0].replace("${PROJECT_NAME}", "\0")).parts
    if len(parts) < 2 or parts[0] != "share" or parts[1] not in names | {"\0"}:
        return None
    rest = parts[2:]
    if any("$" in p or "\0" in p or p == ".." for p in rest):
        return None  # a variable mcar does not know, or a path out of the share folder
    return "/".join(rest)


def source_of(root: Path, name: str, inner: str, rules: list | None = None) -> Path | None:
    """The file of package ``name`` (source folder ``root``) installed as
    ``share/NAME/INNER``, if its rules install one there and it exists; else None.
    ``rules``: its :func:`install_rules`, where the caller keeps them (read once a run,
    not once for each path a checkout lacks)."""
    wanted = PurePosixPath(inner).parts
    if ".." in wanted:
        return None
    for kind, source, destination in install_rules(root, name) if rules is None else rules:
        src = PurePosixPath(source)
        if "$" in source or ".." in src.parts or src.is_absolute():
            continue  # CMake would take it from outside the package: mcar does not
        if kind == "FILES":
            target = PurePosixPath(destination, src.name).parts
            found = root / source if wanted == target else None
        else:
            # "dir" installs as DEST/dir, "dir/" only its contents into DEST
            into = PurePosixPath(destination) if source.endswith("/") else \
                PurePosixPath(destination, src.name)
            top = tuple(p for p in into.parts if p != ".")
            found = root / src / Path(*wanted[len(top):]) \
                if wanted[:len(top)] == top and len(wanted) > len(top) else None
        if found is not None and found.is_file() and _inside(found, root):
            return found
    return None


def _inside(path: Path, root: Path) -> bool:
    """Whether ``path``, every link followed, lies below ``root``: a folder or file the
    rules name may be a link out of the package (to the CI runner's files)."""
    try:
        return path.resolve().is_relative_to(root.resolve())
    except (OSError, RuntimeError):  # a loop of links
        return False
