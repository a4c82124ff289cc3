"""One robot input (a file, or ``-`` for standard input), and the words around it: how
inputs are named in messages, ``NAME:=VALUE`` arguments, the size limit. Kept free of
xacro and lxml imports so that checking a plain URDF stays light; which inputs the words
name is :mod:`mobile_car.load.selection`'s business.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from pathlib import Path

from ..errors import InputError, UsageError
from ..names import shown

STDIN = "-"
STDIN_LABEL = "<stdin>"


def display_path(path: str | os.PathLike) -> str:
    """A path for messages: relative to the working directory when below it, control
    characters escaped (a file name is data: see mobile_car.names)."""
    absolute = Path(os.path.abspath(path))
    try:
        return shown(absolute.relative_to(Path.cwd()))
    except ValueError:
        return shown(absolute)


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


def input_limit_mb() -> float:
    """MCAR_MAX_INPUT_MB, validated."""
    from ..settings import env_number

    return env_number(MAX_INPUT_MB_ENV, DEFAULT_MAX_INPUT_MB, 0.001, 1e6, "MB")


def check_size(size: int, shown: str) -> None:
    """InputError if ``size`` bytes are more than the limit (see check_input_size)."""
    limit_mb = input_limit_mb()
    if size > limit_mb * 1024 * 1024:
        raise InputError(f"{size / 1024 / 1024:.0f} MB is more than the {limit_mb:g} MB this "
                         f"command reads (xacro and the renderer hold ~45x the file in memory); "
                         f"set {MAX_INPUT_MB_ENV} to raise the limit (`mcar check` has none "
                         "for regular files)",
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
        """Expanded by xacro: a ``.xacro``, or another file that uses xacro (see
        :mod:`mobile_car.load.xacro_use`: TurtleBot3's ``.urdf`` files)."""
        return self.named_xacro or self.xacro_use is not None

    @property
    def named_xacro(self) -> bool:
        return self.path is not None and self.path.name.endswith(".xacro")

    @property
    def xacro_use(self) -> str | None:
        """For a file not named ``.xacro``: what in it is xacro (``<xacro:arg>``), or None."""
        if self.path is None or self.named_xacro:
            return None
        from .xacro_use import file_xacro_use

        return file_xacro_use(self.path)

    @property
    def relative(self) -> Path:
        """Its path below ``base`` (``wheel/test_wheel.urdf.xacro``), or its name."""
        if self.path is None:
            return Path("stdin.urdf")
        return self.path.relative_to(self.base) if self.base is not None else Path(self.path.name)
