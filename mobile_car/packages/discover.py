"""Find the robot files of a description package: what every command takes from a folder.

A robot file is a ``.urdf`` file, or a ``.xacro`` whose root is ``<robot name="...">``.
Macro libraries (``define.xacro``, ``wheel/wheel.xacro``) have a nameless ``<robot>``
root: they are included, never built alone. Deciding by content, not by file name,
lets another team's package work with no configuration.
"""

from __future__ import annotations

import functools
import re
from pathlib import Path

from ..errors import InputError
from ..load.bounded import open_regular, read_head, read_text_quietly
from ..load.inputs import input_limit_mb

# Folders of a package that hold outputs or tools, never robot files to take as inputs.
_NOT_SOURCES = {"build", "install", "log", "renders", "node_modules", "__pycache__"}


def root_element(path: Path) -> tuple[str, str | None] | None:
    """The root element's local name and ``name`` attribute; None when unreadable or
    not well-formed before it (a broken file is reported by whoever loads it).

    Read with the standard library's expat, which stops at the first element: lxml would
    cost a one-file ``mcar build`` its import time for one tag.
    """
    import xml.parsers.expat

    found: list[tuple[str, str | None]] = []

    def start(tag, attributes):
        found.append((tag.rpartition(":")[2], attributes.get("name")))
        raise StopIteration  # the root is all we want

    parser = xml.parsers.expat.ParserCreate()
    parser.StartElementHandler = start
    # The root comes after the prolog: a file of endless blanks (a FIFO) has none.
    left = int(input_limit_mb() * 1024 * 1024)
    try:
        with open_regular(path) as handle:
            while not found and left > 0:
                chunk = handle.read(min(65536, left))
                left -= len(chunk)
                parser.Parse(chunk, not chunk)
                if not chunk:
                    break
    except StopIteration:
        pass
    except (xml.parsers.expat.ExpatError, OSError, InputError):
        return None
    return found[0] if found else None


def is_robot_file(path: Path) -> bool:
    """True if the file's root element is a ``<robot>`` with a ``name`` attribute."""
    root = root_element(path)
    if root is not None:
        return root[0] == "robot" and bool(root[1])
    # A broken robot file is still a robot file: building it reports the error.
    try:
        head = read_head(path, 4096).decode("utf-8", errors="replace")
    except (OSError, InputError):
        return False
    return "<robot" in head and "name=" in head.split("<robot", 1)[1].split(">", 1)[0]


# Where description packages keep robot files, by ROS convention; a folder with none of
# these is searched itself.
ROBOT_FOLDERS = ("urdf", "robots", "xacro", "description")
_INCLUDE_RE = re.compile(r"<xacro:include\b[^>]*?\bfilename\s*=\s*[\"']([^\"']+)[\"']", re.S)
_FIND_RE = re.compile(r"^\$\(find\s+([^)\s]+)\)/?")


def _source_folders(root: Path) -> list[Path]:
    folders = [root / name for name in ROBOT_FOLDERS if (root / name).is_dir()]
    return folders or [root]


def source_base(root: Path) -> Path:
    """The folder a package's robot files are named from (and outputs mirror): its one
    robot folder (``urdf/``), or the package itself when it has several or none."""
    folders = _source_folders(root)
    return folders[0] if len(folders) == 1 else root


def robot_files(root: Path) -> list[Path]:
    """The robot files of a folder, sorted: every ``.urdf`` file and every ``.xacro``
    whose root is a named ``<robot>``, below its robot folders (``urdf/``, ``robots/``,
    ``xacro/``, ``description/``) or, with none, below the folder itself. Hidden and
    output folders (build/, renders/, ...) are skipped, and so is a named xacro that
    another xacro file includes (a macro file that names its ``<robot>`` anyway)."""
    found, xacros = [], []
    for folder in _source_folders(root):
        for path in folder.rglob("*"):
            if any(part.startswith(".") or part in _NOT_SOURCES
                   for part in path.relative_to(folder).parts[:-1]):
                continue
            if path.name.endswith(".urdf") and path.is_file():
                found.append(path)
            elif path.name.endswith(".xacro") and path.is_file():
                xacros.append(path)
                if is_robot_file(path):
                    found.append(path)
    included = _included_files(xacros, root)
    return sorted(path for path in found if path.resolve() not in included)


def _included_files(files: list[Path], root: Path) -> set[Path]:
    """The files that the xacro ``files`` include, as far as can be told without
    expanding them: relative names, and ``$(find PKG)/...`` of the package holding
    ``root``."""
    from .search import enclosing_package

    own = enclosing_package(root)
    included: set[Path] = set()
    for path in files:
        if not path.name.endswith(".xacro"):
            continue
        text = read_text_quietly(path)
        if text is None:
            continue
        for name in _INCLUDE_RE.findall(text):
            found = _FIND_RE.match(name)
            if found:
                if own is None or found.group(1) != own[0]:
                    continue
                target = own[1] / name[found.end():]
            elif "$" in name:
                continue
            else:
                target = path.parent / name
            included.add(target.resolve())
    return included


_MACRO_RE = re.compile(r"<xacro:macro\b[^>]*?\bname\s*=\s*[\"'](?:xacro:)?([^\"']+)[\"']", re.S)


@functools.lru_cache(maxsize=16)
def package_macros(folder: Path) -> frozenset[str]:
    """The names of the xacro macros defined in the package holding ``folder`` (none
    outside a package): what an unexpanded macro call in a URDF would be named."""
    from .search import enclosing_package

    own = enclosing_package(folder)
    if own is None:
        return frozenset()
    names: set[str] = set()
    for path in own[1].rglob("*.xacro"):
        if any(part.startswith(".") or part in _NOT_SOURCES
               for part in path.relative_to(own[1]).parts[:-1]):
            continue
        names.update(_MACRO_RE.findall(read_text_quietly(path) or ""))
    return frozenset(names)


def output_name(source: Path, base: Path) -> Path:
    """Where a built file goes, relative to the output folder: ``wheel/test_wheel.urdf``."""
    relative = source.relative_to(base)
    name = relative.name[: -len(".xacro")] if relative.name.endswith(".xacro") else relative.name
    if not name.endswith(".urdf"):
        name += ".urdf"
    return relative.with_name(name)
