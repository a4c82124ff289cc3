"""One robot input (a file, or ``-`` for standard input), and the words around it: how
inputs are named in messages, ``NAME:=VALUE`` arguments, the size limit. Kept free of
xacro and lxml imports so that checking a plain URDF stays light; which inputs the words
name is :mod:`mobile_car.load.selection`'s business.
"""

from __future__ import annotations

import re
from pathlib import Path

from ..errors import UsageError
from ..values import Value
from .input_limit import (  # noqa: F401  (their home before; imported from here too)
    DEFAULT_MAX_INPUT_MB,
    MAX_INPUT_MB_ENV,
    check_input_size,
    check_size,
    display_path,
    input_limit_mb,
)

STDIN = "-"
STDIN_LABEL = "<stdin>"


def is_urdf_name(name: str) -> bool:
    """A URDF by its name: ``.urdf`` in any case, as check_urdf and xacro take any name;
    the SolidWorks exporter (sw_urdf_exporter) writes ``robots/NAME.URDF``, which Robotiq's
    2F-85 and the BarrettHand descriptions ship."""
    return name.lower().endswith(".urdf")


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


def split_words(words) -> tuple[list[str], dict[str, str]]:
    """The command line's words as (inputs, NAME:=VALUE mappings)."""
    words = list(words)
    return ([w for w in words if ":=" not in w],
            parse_mapping_args([w for w in words if ":=" in w]))


class RobotInput(Value):
    """One robot to load: a file, or standard input (``path`` None)."""

    _fields = __slots__ = ("path", "base")
    path: Path | None
    # The folder the input was found in (a folder or package input); outputs mirror the
    # input's place below it. None for a file the user named.
    base: Path | None

    def __init__(self, path: Path | None, base: Path | None = None):
        self._set(path, base)

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
