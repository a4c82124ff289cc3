"""What every command does with its inputs before any xacro: name them in messages and
read ``NAME:=VALUE`` words. Kept apart from :mod:`mobile_car.build` so that checking a
plain URDF never imports xacro (and PyYAML with it: a fifth of a small check's run).
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from .errors import UsageError


def display_path(path: str | os.PathLike) -> str:
    """A path for messages: relative to the working directory when below it."""
    absolute = Path(os.path.abspath(path))
    try:
        return str(absolute.relative_to(Path.cwd()))
    except ValueError:
        return str(absolute)


def parse_mapping_args(words: list[str]) -> dict[str, str]:
    """``NAME:=VALUE`` words as a dict; anything else is a usage error."""
    mappings: dict[str, str] = {}
    for word in words:
        name, sep, value = word.partition(":=")
        if not sep or not name or not re.fullmatch(r"[A-Za-z_][\w.-]*", name):
            raise UsageError(f"argument '{word}' is not of the form NAME:=VALUE")
        mappings[name] = value
    return mappings
