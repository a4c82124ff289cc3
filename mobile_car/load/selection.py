"""Which robot inputs a command's words name: files, ``-``, folders, part names, or none.

Every command takes the same words: a ``.urdf`` or ``.xacro`` file, ``-`` for standard
input, a folder (its robot files, see :func:`~mobile_car.packages.discover.robot_files`),
or the name of a part folder of the package being worked on (``wheel``); no word at all
means that package (:mod:`mobile_car.load.package`). A folder inside a package is named
from the package, so its outputs mirror the same way however it was named
(``urdf/wheel/test_wheel.urdf.xacro`` -> ``build/wheel/test_wheel.urdf``), under the
package's root.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from ..errors import UsageError
from .inputs import STDIN, RobotInput, display_path, is_urdf_name


class Selection:
    """The inputs a command's words name, and how they were named."""

    # A plain class, not a dataclass: never compared, and a dataclass costs every run
    # that imports it the compiling of its methods (values.py).
    def __init__(self, kind: str, inputs: list[RobotInput] | None = None,
                 root: Path | None = None, output_root: Path | None = None,
                 working: object = None, skipped: list | None = None):
        self.kind = kind  # "files" (files and "-"), "folder", "parts" or "package"
        self.inputs = [] if inputs is None else inputs
        self.root = root  # the folder or package, for those kinds
        # Where build/ and renders/ go: the root of the package you stand in when no
        # INPUT named it, else the working directory.
        self.output_root = Path() if output_root is None else output_root
        self.working = working  # the WorkingSet, when the package was chosen for the user
        # Files found below the folders named that are not robots, with why (mcar ci -v).
        self.skipped = [] if skipped is None else skipped  # of packages.discover.Skipped

    @property
    def reads_stdin(self) -> bool:
        return any(inp.path is None for inp in self.inputs)


def robot_inputs(root: Path, base: Path | None = None,
                 skipped: list | None = None) -> list[RobotInput]:
    """The robot files of a folder, each named from ``base`` (default: the folder's own
    source folder, see :func:`~mobile_car.packages.discover.source_base`); the files
    found there that are not robots are added to ``skipped``."""
    from ..packages.discover import discover, source_base

    found = discover(root)
    if skipped is not None:
        skipped += found.skipped
    files = found.robots
    base = base or source_base(root)
    if any(not path.is_relative_to(base) for path in files):
        base = root
    return [RobotInput(path, base) for path in files]


def require_robot_inputs(root: Path, base: Path | None = None,
                         skipped: list | None = None) -> list[RobotInput]:
    """robot_inputs(), or a UsageError naming the folder (and what was skipped there)
    when there is none."""
    from ..packages.discover import ROBOT_FOLDERS

    passed_over: list = []
    inputs = robot_inputs(root, base, passed_over)
    if skipped is not None:
        skipped += passed_over
    if not inputs:
        raise UsageError("no robot files in this folder (looked in "
                         f"{', '.join(name + '/' for name in ROBOT_FOLDERS)} or the folder "
                         f"itself){_what_was_skipped(passed_over)}", file=display_path(root))
    return inputs


def _what_was_skipped(skipped: list) -> str:
    """``; skipped 3 files that are not robots: a.xacro (defines macros only), ...``"""
    if not skipped:
        return ""
    shown = [f"{display_path(s.path)} ({s.reason})" for s in skipped[:3]]
    more = f", and {len(skipped) - 3} more" if len(skipped) > 3 else ""
    files = "file that is" if len(skipped) == 1 else "files that are"
    return f"; skipped {len(skipped)} {files} not robots: {', '.join(shown)}{more}"


def package_parts(root: Path) -> list[str]:
    """The part folders of a package (``wheel``, ...) that hold robot files."""
    return sorted({inp.relative.parts[0] for inp in robot_inputs(root)
                   if len(inp.relative.parts) > 1})


def _looks_like_file(name: str) -> bool:
    return "/" in name or name.endswith(".xacro") or is_urdf_name(name)


def _folder(folder: Path, skipped: list) -> list[RobotInput]:
    """A folder's inputs, named from its package when it lies in one, so that outputs
    mirror the same way however the package or a subfolder was named."""
    from ..packages.discover import source_base
    from ..packages.search import enclosing_package

    own = enclosing_package(folder)
    if own is None:
        return require_robot_inputs(folder, skipped=skipped)
    # Absolute, as the package's root is: messages show paths relative to the cwd anyway.
    return require_robot_inputs(folder.resolve(), source_base(own[1]), skipped)


def _is_own_stdin(name: str) -> bool:
    """True for ``/dev/stdin`` (``/dev/fd/0``, ...) when standard input is a pipe, a
    socket or a terminal: read as ``-`` is, since opening it by name would be refused as
    a FIFO or device. A regular file on stdin is read by its name like any file, and
    ``/dev/null`` on stdin stays the device it is."""
    if name == STDIN:
        return False
    try:
        named, ours = os.stat(name), os.fstat(0)
    except (OSError, ValueError):
        return False
    streams = stat.S_ISFIFO(ours.st_mode) or stat.S_ISSOCK(ours.st_mode) or os.isatty(0)
    return streams and os.path.samestat(named, ours)


def select(names: list[str], working) -> Selection:
    """The inputs the words name. ``working()`` gives the WorkingSet a command without
    INPUT (or with part names) works on; it is called only then."""
    if not names:
        return _package(working())
    names = [STDIN if _is_own_stdin(name) else name for name in names]
    if names.count(STDIN) > 1:
        raise UsageError("- (stdin) can be given only once")
    paths = [None if name == STDIN else Path(name) for name in names]
    missing = [name for name, path in zip(names, paths, strict=True)
               if path is not None and not path.exists()]
    # A missing name that looks like a file is a file (loading it says "no such file");
    # one that does not may be a part name.
    if all(_looks_like_file(name) for name in missing):
        folders = [path for path in paths if path is not None and path.is_dir()]
        skipped: list = []
        if len(names) == 1 and folders:
            return Selection("folder", _folder(folders[0], skipped), folders[0], Path.cwd(),
                             skipped=skipped)
        inputs: list[RobotInput] = []
        for path in paths:
            if path is not None and path.is_dir():
                inputs += _folder(path, skipped)
            else:
                inputs.append(RobotInput(path))
        return Selection("files", inputs, output_root=Path.cwd(), skipped=skipped)
    if len(missing) < len(names):
        raise UsageError(f"no such file: {missing[0]} (give files, or part names, not both)")
    return _parts(names, working())


def _package(working) -> Selection:
    skipped: list = []
    if working.kind == "workspace":  # named from the workspace: packages cannot collide
        inputs = [inp for package in working.packages
                  for inp in robot_inputs(package.root, working.folder, skipped)]
        if not inputs:
            raise UsageError("no robot files in any package of this workspace"
                             f"{_what_was_skipped(skipped)}", file=display_path(working.folder))
        return Selection("package", inputs, working.folder, working.output_root, working,
                         skipped)
    root = working.packages[0].root
    return Selection("package", require_robot_inputs(root, skipped=skipped), root,
                     working.output_root, working, skipped)


def _parts(names: list[str], working) -> Selection:
    from ..packages.discover import source_base

    if working.kind == "workspace":
        raise UsageError(f"no such file: {names[0]} (part names need one package; in a "
                         "workspace, give the part's folder)")
    root = working.packages[0].root
    known = package_parts(root)
    unknown = [name for name in names if name not in known]
    if unknown:
        raise UsageError(f"no file or part named {', '.join(map(repr, unknown))}; parts of "
                         f"{display_path(source_base(root))}: {', '.join(known) or 'none'}")
    skipped: list = []
    inputs = [inp for inp in robot_inputs(root, skipped=skipped)
              if inp.relative.parts[0] in names]
    return Selection("parts", inputs, root, working.output_root, working,
                     [s for s in skipped if _in_parts(s.path, root, names)])


def _in_parts(path: Path, root: Path, names: list[str]) -> bool:
    from ..packages.discover import source_base

    try:
        return path.relative_to(source_base(root)).parts[0] in names
    except ValueError:
        return False


def one_robot(selection: Selection, command: str) -> RobotInput:
    """The one robot a single-robot command (tree, view, sim --record) works on: the input
    named, or, for a package or folder, its complete robot: the one robot file nearest
    its source folder (``urdf/mobile_robot.xacro``, not the parts' test files below it).
    A UsageError lists the choices, one per detail line, when that is not one file."""
    inputs = selection.inputs
    if len(inputs) == 1:
        return inputs[0]
    if selection.kind == "files":
        raise UsageError(f"{command} works on one robot, and {len(inputs)} were named: "
                         "name one INPUT")
    top = complete_robots(inputs)
    if len(top) == 1:
        return top[0]
    raise UsageError(f"{command} works on one robot, and there are {len(top)} here: name "
                     "one INPUT", details=[inp.label for inp in top])


def complete_robots(inputs: list[RobotInput]) -> list[RobotInput]:
    """The robot files at the shallowest depth below where they were found: a package's
    complete robots (urdf/*.xacro), whose parts and their test files sit in folders below
    (urdf/wheel/test_wheel.urdf.xacro)."""
    depth = min(len(inp.relative.parts) for inp in inputs)
    return [inp for inp in inputs if len(inp.relative.parts) == depth]
