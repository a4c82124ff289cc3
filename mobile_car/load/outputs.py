"""Outputs never destroy inputs: no output may be a file the run reads, and no two inputs
may be written to one output.

``mcar build self.xacro -o self.xacro`` replaced the source with its URDF, ``-o
incd/props.xacro`` an include, ``--junit-xml tut/04_xacro.xacro`` a source; ``a.xacro``
and ``a.urdf.xacro`` were both built to ``a.urdf``, one robot lost. Every command checks
its outputs here before it writes them (exit 2, naming both files).
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from pathlib import Path

from ..errors import UsageError
from .inputs import display_path


def names_folder(output: str) -> bool:
    """True for an ``-o`` that ends in a slash: a folder, even one that does not exist yet
    (``-o newdir/`` wrote a file named ``newdir``)."""
    return output.endswith(("/", os.sep))


def shown_dep(path: Path, absolute: bool) -> str:
    """A file a build read, for ``--deps``: relative to the working directory (``..``
    where needed), or absolute; one way for every file."""
    return os.path.abspath(path) if absolute else os.path.relpath(path)


def _key(path: Path) -> str:
    return os.path.realpath(path)


def refuse_overwriting(output: Path | str, protected: Iterable[Path | None],
                       what: str = "a file this run reads") -> None:
    """UsageError if ``output`` is (a link to) one of the ``protected`` files."""
    refuse_overwriting_each([output], protected, what)


def refuse_overwriting_each(outputs: Iterable[Path | str], protected: Iterable[Path | None],
                            what: str = "a file this run reads") -> None:
    """refuse_overwriting() for each of ``outputs``, every path resolved once: checking
    each output against every input made ``mcar build`` of 1000 robots a million
    realpath() calls (50 s)."""
    keys: dict[str, Path] = {}
    for path in protected:
        if path is not None:
            keys.setdefault(_key(Path(path)), Path(path))
    for output in outputs:
        clash = keys.get(_key(Path(output)))
        if clash is not None:
            raise UsageError(f"would overwrite {display_path(clash)}, {what}; "
                             "write the output somewhere else", file=display_path(output))


def refuse_clashes(targets: Iterable[tuple[Path, Path | None]]) -> None:
    """UsageError if two sources map to one output: ``targets`` is (output, source) pairs."""
    seen: dict[str, Path | None] = {}
    for output, source in targets:
        key = _key(output)
        if key in seen and seen[key] != source:
            first, second = seen[key], source
            raise UsageError(f"{_shown(first)} and {_shown(second)} would both be written to "
                             "this file; build or draw them one at a time with -o",
                             file=display_path(output))
        seen[key] = source


def _shown(path: Path | None) -> str:
    return "<stdin>" if path is None else display_path(path)
