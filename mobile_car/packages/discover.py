"""Find the robot files of a description package: what every command takes from a folder.

A robot is a file that makes a ``<robot>`` with links and that no other file of the
package includes. Deciding by content, not by file name, lets another team's package
work with no configuration; deciding without running anything keeps a xacro (which is
code) from running before the user asked for it, and finding a folder's robots cheap.
Every file below the robot folders is looked at (:mod:`.file_shape`) and either taken
or skipped with the reason, which ``mcar ci -v`` lists:

* not a ``.urdf`` or ``.xacro`` (``jackal.gazebo``, launch configs, variant YAMLs);
* included by another file of the package: by a relative name, ``$(find OWN)/...``,
  or an argument's or environment variable's default (Husky's ``empty.urdf``, named in
  ``$(optenv HUSKY_URDF_EXTRAS empty.urdf)``);
* a root other than ``<robot>``;
* a nameless ``<robot>`` that uses xacro: a macro file, or a fragment to include
  (Jackal's ``custom_example.urdf``); a plain URDF without a name is still a robot,
  and checking it says what is missing;
* nothing that could make a link: no ``<link>``, macro call or include outside the
  ``<xacro:macro>`` bodies (a macro library with a named ``<robot>``, TurtleBot3's
  ``common_properties.urdf`` of materials, an empty placeholder);
* ``X.urdf`` beside ``X.urdf.xacro``: both would be built into ``X.urdf``, and the
  ``.xacro`` is the source (Panda ships both);
* left out by the package's ``mcar.yaml`` (``robots: include/exclude``, see
  :mod:`.package_config`);
* a link leading out of the package (every symlink followed): in CI a pull request
  commits the links, and ``urdf/robot.urdf`` -> ``/proc/self/environ`` is no robot of its.

A file that could make a link is taken even when the macros it calls make none:
checking it then says so (E106), and ``mcar.yaml`` can leave it out; a red run names
what it is about, where a silently skipped robot would make a green one.
"""

from __future__ import annotations

import functools
import re
from pathlib import Path

from ..errors import InputError
from ..load.bounded import open_regular, read_text_quietly
from ..load.inputs import input_limit_mb, is_urdf_name
from ..values import Value
from .asset_roots import link_out_of, real_path
from .file_shape import FileShape, file_shape, include_target

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


# Where description packages keep robot files, by ROS convention; a folder with none of
# these is searched itself.
ROBOT_FOLDERS = ("urdf", "robots", "xacro", "description")


def _source_folders(root: Path) -> list[Path]:
    folders = [root / name for name in ROBOT_FOLDERS if (root / name).is_dir()]
    return folders or [root]


def source_base(root: Path) -> Path:
    """The folder a package's robot files are named from (and outputs mirror): its one
    robot folder (``urdf/``), or the package itself when it has several or none."""
    folders = _source_folders(root)
    return folders[0] if len(folders) == 1 else root


class Skipped(Value):
    """A file below the robot folders that is not a robot, and why."""

    _fields = __slots__ = ("path", "reason")
    path: Path
    reason: str

    def __init__(self, path: Path, reason: str):
        self._set(path, reason)


class Discovery:
    """The robot files of a folder, sorted, and the files skipped there."""

    # A plain class, not a dataclass: never compared, and a dataclass costs every run
    # that imports it the compiling of its methods (values.py).
    def __init__(self, robots: list[Path] | None = None, skipped: list[Skipped] | None = None):
        self.robots = [] if robots is None else robots
        self.skipped = [] if skipped is None else skipped


def robot_files(root: Path) -> list[Path]:
    """The robot files of a folder, sorted (see :func:`discover`)."""
    return discover(root).robots


def discover(root: Path) -> Discovery:
    """The robot files below the robot folders of ``root`` (``urdf/``, ``robots/``,
    ``xacro/``, ``description/``, else ``root`` itself), hidden and output folders
    (build/, renders/, ...) left out, and every other file there with the reason."""
    from .package_config import load_package_config
    from .search import enclosing_package

    own = enclosing_package(root)
    config = load_package_config(own[1]) if own is not None else None
    files = _files(root)
    links_out = _links_out(files, own[1] if own is not None else root)
    shapes = {path: file_shape(path) for path in files
              if _is_candidate(path) and path not in links_out}
    included = _included(shapes, own)
    found = Discovery()
    taken: list[Path] = []
    for path in files:
        reason = links_out.get(path) or _why_not_a_robot(path, shapes.get(path), included,
                                                         root) \
            or _macro_library(path, shapes, own)
        if reason is None:
            taken.append(path)
        else:
            found.skipped.append(Skipped(path, reason))
    for path in _one_per_output(taken, found.skipped, root):
        selected, why_not = config.selects(path) if config is not None else (True, None)
        if selected:
            found.robots.append(path)
        else:
            found.skipped.append(Skipped(path, f"left out by {why_not}"))
    found.skipped.sort(key=lambda skipped: skipped.path)
    return found


def _files(root: Path) -> list[Path]:
    files = []
    for folder in _source_folders(root):
        for path in folder.rglob("*"):
            parts = path.relative_to(folder).parts
            if any(part.startswith(".") or part in _NOT_SOURCES for part in parts[:-1]) \
                    or parts[-1].startswith("."):
                continue
            if path.is_file():
                files.append(path)
    return sorted(files)


def _links_out(files: list[Path], folder: Path) -> dict[Path, str]:
    """The files that are links (or lie below a linked folder) leading out of ``folder``
    (the package) or into its ``.git``, each with why it is skipped. A pull request
    commits links: one named ``urdf/robot.urdf`` leading to ``/proc/self/environ`` or a
    key made mcar ci copy the runner's file into build/robot.urdf. A file named on the
    command line is still read wherever it leads: the user named it."""
    bound = real_path(folder)
    found = {}
    for path in files:
        why = link_out_of(path, bound)
        if why is not None:  # one named on the command line is read: "name it to read it"
            named = " (name it to read it)" if why.endswith(f"outside {bound}") else ""
            found[path] = f"{why}: not taken{named}"
    return found


def _is_candidate(path: Path) -> bool:
    return path.name.endswith(".xacro") or is_urdf_name(path.name)


def _why_not_a_robot(path: Path, shape: FileShape | None, included: dict[Path, Path],
                     root: Path) -> str | None:
    by = included.get(path.resolve()) if included else None
    if by is not None:
        return f"included by {_shown_from(by, root)}"
    if shape is None:
        return "not a .urdf or .xacro file"
    if shape.root is None:
        return None  # unreadable or broken: loading it says what is wrong
    if shape.root != "robot":
        return f"its root is <{shape.root}>, not <robot>"
    xacro = shape.uses_xacro or path.name.endswith(".xacro")
    if not shape.name and xacro:
        what = "a macro file" if shape.macros else "a fragment to include"
        return f"{what}: its <robot> has no name"
    if shape.read_whole and not shape.links and not shape.makers:
        if shape.macros:
            return "defines macros only: no <link> outside <xacro:macro>"
        return "no <link>, and nothing that makes one: a fragment"
    return None


def _macro_library(path: Path, shapes: dict, own) -> str | None:
    """Why a named ``<robot>`` that defines macros and includes only files that make no
    link either is a macro library (MiR's ``mir_100_v1.urdf.xacro``, kept "for backward
    compatibility", wraps ``mir_v1.urdf.xacro``'s macro in another), or None: its
    includes are what could make a link, so they are followed within the package."""
    shape = shapes.get(path)
    if shape is None or not shape.read_whole or shape.links or shape.calls or \
            not shape.macros or not shape.includes:
        return None
    by_real = {p.resolve(): found for p, found in shapes.items()}
    seen, todo = {path.resolve()}, [(path, shape)]
    while todo:
        including, current = todo.pop()
        for spec in current.includes:
            target = include_target(spec, including, current, own)
            if target is None:
                return None  # another package's, or an expression: it may make links
            target = target.resolve()
            if target in seen:
                continue
            found = by_real.get(target)
            if found is None or not found.read_whole or found.links or found.calls:
                return None
            seen.add(target)
            todo.append((target, found))
    return "defines macros only, and includes only files that make no <link>"


def _one_per_output(taken: list[Path], skipped: list[Skipped], root: Path) -> list[Path]:
    """``X.urdf`` beside ``X.urdf.xacro`` (or ``X.xacro``): one robot, the xacro."""
    xacro_outputs = {path.parent / _output_file_name(path.name): path
                     for path in taken if path.name.endswith(".xacro")}
    kept = []
    for path in taken:
        source = xacro_outputs.get(path) if not path.name.endswith(".xacro") else None
        if source is None:
            kept.append(path)
        else:
            skipped.append(Skipped(path, f"the URDF of {_shown_from(source, root)} beside "
                                         "it (one robot: its xacro is built)"))
    return kept


def _shown_from(path: Path, root: Path) -> str:
    try:
        return path.resolve().relative_to(root.resolve()).as_posix()
    except ValueError:
        return str(path)


def _included(shapes: dict[Path, FileShape], own) -> dict[Path, Path]:
    """Resolved path of each file included by one of ``shapes`` -> the first includer."""
    included: dict[Path, Path] = {}
    for path, shape in shapes.items():
        for spec in shape.includes:
            target = include_target(spec, path, shape, own)
            if target is not None:
                target = target.resolve()
                if target != path.resolve():
                    included.setdefault(target, path)
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


def _output_file_name(name: str) -> str:
    name = name[: -len(".xacro")] if name.endswith(".xacro") else name
    # NAME.URDF is built into NAME.urdf, as every output is named
    return name[: -len(".urdf")] + ".urdf" if is_urdf_name(name) else name + ".urdf"


def output_name(source: Path, base: Path) -> Path:
    """Where a built file goes, relative to the output folder: ``wheel/test_wheel.urdf``."""
    relative = source.relative_to(base)
    return relative.with_name(_output_file_name(relative.name))
