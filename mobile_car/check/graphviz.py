"""Write a tree diagram: the Graphviz text itself (``.dot``, ``.gv``), or a picture drawn by
the ``dot`` tool (``.svg``, ``.png``, ``.pdf``) when it is installed.

Unlike urdfdom's ``urdf_to_graphiz``, nothing is claimed that was not written: a missing
``dot`` or a failing one is an error, and the output file is only replaced (atomically)
once the whole picture exists.
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

from ..atomic import atomic_write
from ..errors import InputError, UsageError

TEXT_SUFFIXES = (".dot", ".gv")
PICTURE_SUFFIXES = (".svg", ".png", ".pdf")
DOT_TIMEOUT_SECONDS = 300


def write_graph(dot_text: str, output: str | Path) -> Path:
    """Write ``dot_text`` to ``output``, as text or drawn by ``dot`` according to its suffix."""
    target = Path(output)
    suffix = target.suffix.lower()
    if suffix in TEXT_SUFFIXES:
        return atomic_write(target, dot_text)
    if suffix not in PICTURE_SUFFIXES:
        raise UsageError(f"--graphviz {output}: the name must end in "
                         f"{', '.join(TEXT_SUFFIXES + PICTURE_SUFFIXES)}")
    dot = shutil.which("dot")
    if dot is None:
        raise InputError(f"cannot draw {target.name}: the `dot` tool (Debian package graphviz) "
                         f"is not installed; write a .dot file instead", file=str(target))
    try:
        done = subprocess.run([dot, f"-T{suffix[1:]}"], input=dot_text.encode("utf-8"),
                              capture_output=True, timeout=DOT_TIMEOUT_SECONDS)
    except (OSError, subprocess.TimeoutExpired) as exc:
        raise InputError(f"`dot` failed: {exc}", file=str(target)) from None
    if done.returncode != 0 or not done.stdout:
        reason = " ".join(done.stderr.decode("utf-8", "replace").split())[:300]
        raise InputError(f"`dot` failed (exit {done.returncode}): {reason or 'no output'}",
                         file=str(target))
    return atomic_write(target, done.stdout)
