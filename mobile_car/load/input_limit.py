"""How an input is named in messages, and how large an input mcar reads: the two things
every reader of input needs, kept in a module that imports nothing of mcar's loaders (the
bounded reader uses them, and the loaders use the bounded reader)."""

from __future__ import annotations

import os
from pathlib import Path

from ..errors import InputError
from ..names import shown


def display_path(path: str | os.PathLike) -> str:
    """A path for messages: relative to the working directory when below it, control
    characters escaped (a file name is data: see mobile_car.names)."""
    absolute = Path(os.path.abspath(path))
    try:
        return shown(absolute.relative_to(Path.cwd()))
    except ValueError:
        return shown(absolute)


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


