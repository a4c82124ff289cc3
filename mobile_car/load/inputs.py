"""What the user names, as robot inputs: files, the robot files of a folder, ``-``, part names.

Every command takes the same words: a ``.urdf`` or ``.xacro`` file, a folder (its ``.urdf``
files and robot ``.xacro`` files, below its ``urdf/`` when it has one), ``-`` for standard
input, or the name of a part folder of the package the command works on (``wheel``); no
word at all means that package. ``NAME:=VALUE`` words are xacro arguments. Kept free of
xacro and lxml imports so that checking a plain URDF stays light.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import InputError, UsageError

STDIN = "-"
STDIN_LABEL = "<stdin>"


def display_path(path: str | os.PathLike) -> str:
    """A path for messages: relative to the working directory when below it."""
    absolute = Path(os.path.abspath(path))
    try:
        return str(absolute.relative_to(Path.cwd()))
    except ValueError:
        return str(absolute)


def parse_mapping_args(words: list[str]) -> dict[str, str]:
    """``NAME:=VALUE`` words as the ``xacro`` command reads them (its own
    ``load_mappings``): whitespace around name and value is dropped, an empty value
    drops the mapping (the argument keeps its default, as ROS 2 launch files expect of
    ``tf_prefix:=``), a private ``_name`` is ignored, the last of repeated names wins.
    Where xacro would fail or silently drop a word mcar cannot read as one argument (no
    name, two ``:=``, a name xacro cannot declare), that is a usage error."""
    for word in words:
        name, sep, value = word.partition(":=")
        name = name.strip()
        if not sep or ":=" in value or not re.fullmatch(r"[A-Za-z_][\w.-]*", name):
            raise UsageError(f"argument '{word}' is not of the form NAME:=VALUE")
    if not words:
        return {}
    from xacro.cli import load_mappings  # the xacro command's own rules

    return load_mappings(words)


# xacro holds a document as a DOM of Python objects, tens of times the file's size (the
# figures: bench/notes.md): refuse what would exhaust a CI runner's memory.
MAX_INPUT_MB_ENV = "MCAR_MAX_INPUT_MB"
DEFAULT_MAX_INPUT_MB = 16


def check_input_size(path: Path) -> None:
    """InputError if the file is larger than xacro (or the renderer) should take on."""
    check_size(path.stat().st_size, display_path(path))


def check_size(size: int, shown: str) -> None:
    """InputError if ``size`` bytes are more than the limit (see check_input_size)."""
    try:
        limit_mb = float(os.environ.get(MAX_INPUT_MB_ENV, DEFAULT_MAX_INPUT_MB))
    except ValueError:
        limit_mb = DEFAULT_MAX_INPUT_MB
    if size > limit_mb * 1024 * 1024:
        raise InputError(f"{size / 1024 / 1024:.0f} MB is more than the {limit_mb:g} MB this "
                         f"command reads (xacro and the renderer hold ~45x the file in memory); "
                         f"set {MAX_INPUT_MB_ENV} to raise the limit (`mcar check` has none)",
                         file=shown)


def split_words(words) -> tuple[list[str], dict[str, str]]:
    """The command line's words as (inputs, NAME:=VALUE mappings)."""
    words = list(words)
    return ([w for w in words if ":=" not in w],
            parse_mapping_args([w for w in words if ":=" in w]))


@dataclass(frozen=True)
class RobotInput:
    """One robot to load: a file, or standard input (``path`` None)."""

    path: Path | None
    # The folder the input was found in (a folder or package input); outputs mirror the
    # input's place below it. None for a file the user named.
    base: Path | None = None

    @property
    def label(self) -> str:
        return STDIN_LABEL if self.path is None else display_path(self.path)

    @property
    def is_xacro(self) -> bool:
        return self.path is not None and self.path.name.endswith(".xacro")

    @property
    def relative(self) -> Path:
        """Its path below ``base`` (``wheel/test_wheel.urdf.xacro``), or its name."""
        if self.path is None:
            return Path("stdin.urdf")
        return self.path.relative_to(self.base) if self.base is not None else Path(self.path.name)


@dataclass
class Selection:
    """The inputs a command's words name, and how they were named."""

    kind: str  # "files" (files and "-"), "folder", "parts" or "package"
    inputs: list[RobotInput] = field(default_factory=list)
    root: Path | None = None  # the folder or package, for those kinds

    @property
    def reads_stdin(self) -> bool:
        return any(inp.path is None for inp in self.inputs)


def robot_inputs(root: Path) -> list[RobotInput]:
    """The robot files of a folder (see :func:`~mobile_car.packages.discover.robot_files`),
    each with the folder holding them as base."""
    from ..packages.discover import robot_files, source_base

    base = source_base(root)
    return [RobotInput(path, base) for path in robot_files(root)]


def require_robot_inputs(root: Path) -> list[RobotInput]:
    """robot_inputs(root), or a UsageError naming the folder when there is none."""
    from ..packages.discover import source_base

    inputs = robot_inputs(root)
    if not inputs:
        raise UsageError("no .urdf or robot .xacro files in this folder",
                         file=display_path(source_base(root)))
    return inputs


def package_parts(root: Path) -> list[str]:
    """The part folders of a package (``wheel``, ...) that hold robot files."""
    return sorted({inp.relative.parts[0] for inp in robot_inputs(root)
                   if len(inp.relative.parts) > 1})


def _looks_like_file(name: str) -> bool:
    return "/" in name or name.endswith((".urdf", ".xacro"))


def select(names: list[str], package_root) -> Selection:
    """The inputs the words name. ``package_root()`` gives the package a command without
    INPUT (or with part names) works on; it is called only then."""
    if not names:
        root = package_root()
        return Selection("package", require_robot_inputs(root), root)
    if names.count(STDIN) > 1:
        raise UsageError("- (stdin) can be given only once")
    paths = [None if name == STDIN else Path(name) for name in names]
    missing = [name for name, path in zip(names, paths, strict=True)
               if path is not None and not path.exists()]
    # A missing name that looks like a file is a file (loading it says "no such file");
    # one that does not may be a part name.
    if all(_looks_like_file(name) for name in missing):
        folders = [path for path in paths if path is not None and path.is_dir()]
        if len(names) == 1 and folders:
            return Selection("folder", require_robot_inputs(folders[0]), folders[0])
        inputs: list[RobotInput] = []
        for path in paths:
            if path is not None and path.is_dir():
                inputs += require_robot_inputs(path)
            else:
                inputs.append(RobotInput(path))
        return Selection("files", inputs)
    if len(missing) < len(names):
        raise UsageError(f"no such file: {missing[0]} (give files, or part names, not both)")
    from ..packages.discover import source_base

    root = package_root()
    known = package_parts(root)
    unknown = [name for name in names if name not in known]
    if unknown:
        raise UsageError(f"no file or part named {', '.join(map(repr, unknown))}; parts of "
                         f"{display_path(source_base(root))}: {', '.join(known) or 'none'}")
    return Selection("parts", [inp for inp in robot_inputs(root)
                               if inp.relative.parts[0] in names], root)
