"""Default outputs stay in the folder they are placed in.

With no ``-o``, mcar writes into ``build/`` and ``renders/`` below its *output root*: the
root of the package you stand in when no INPUT named the robots (or a part name did),
else the working folder (:attr:`~.selection.Selection.output_root`). Those folders come
with the checkout, so a pull request can commit ``build`` as a link to ``~/.ssh`` or to
another project, or ``build/exports``, ``build/wheel`` or ``build/.mcar-ci.json`` as one:
``mcar ci`` then wrote URDFs, pictures, exports and records there, replacing files of the
same names. So a default output folder, every folder below it that a write goes through,
and every file written there (a record included) must resolve inside the output root;
a link that leads out is refused with one line naming it and where it leads (exit 2). A
link that stays inside the root is followed. A folder the user names (``-o``,
``--build-dir``, ``--render-dir``) is the user's: it is written wherever it leads.

One place decides it: :func:`default_folder` resolves the folder once and remembers it,
and the writers every output goes through (:func:`mobile_car.atomic.atomic_write`,
:func:`mobile_car.export.folder.staged_folder`, :func:`mobile_car.freshness.read_record`)
ask :func:`placed` where a path below it really is, and write beneath that resolved
folder rather than through the links again. What is left is a race with another process
that swaps a folder of the checkout for a link between that resolution and the write;
the xacro sandbox cannot (it creates nothing), and whoever can has the checkout anyway.
"""

from __future__ import annotations

import os
from pathlib import Path

from ..errors import UsageError
from ..names import shown
from ..packages.asset_roots import within
from .input_limit import display_path

# Default output folders of this run, resolved -> (the output root they must stay in, the
# option that names another folder instead).
_folders: dict[str, tuple[str, str]] = {}


def default_folder(root: Path, name: str, option: str) -> Path:
    """The folder ``name`` (``build``, ``renders``) below the output root ``root``,
    resolved; UsageError if it is, or lies below, a link leading out of ``root``
    (``option``: how the user names the folder instead, for the message)."""
    checkout = os.path.realpath(root)
    real = os.path.realpath(os.path.join(checkout, name))
    if not _inside(real, checkout):
        _refuse(checkout, os.path.join(checkout, name), option)
    _folders[real] = (checkout, option)
    return Path(real)


def forget_default_folders() -> None:
    """A new command starts with none (one process may run several: tests, the view)."""
    _folders.clear()


def placed(path: str | os.PathLike) -> tuple[Path, bool]:
    """Where to write ``path``: (the path with its folder resolved, True) when it lies
    below a default output folder and stays in its output root; (``path``, False) for
    any other path. UsageError when a folder on the way, or the file itself, is a link
    leading out of the output root."""
    if not _folders:
        return Path(path), False
    absolute = os.path.abspath(path)
    for folder, (checkout, option) in _folders.items():
        if not _inside(absolute, folder):
            continue
        parent = os.path.realpath(os.path.dirname(absolute))
        if not _inside(parent, checkout):
            _refuse(checkout, os.path.dirname(absolute), option)
        target = os.path.join(parent, os.path.basename(absolute))
        if os.path.islink(target) and not _inside(os.path.realpath(target), checkout):
            _refuse(checkout, target, option)
        return Path(target), True
    return Path(path), False


def _inside(path: str, folder: str) -> bool:
    return within(path, [folder])


def _refuse(checkout: str, path: str, option: str) -> None:
    """UsageError naming the first link on the way from ``checkout`` to ``path`` that
    leads out of it, and where it leads."""
    link = path
    parts = Path(os.path.relpath(path, checkout)).parts
    for depth in range(1, len(parts) + 1):
        prefix = os.path.join(checkout, *parts[:depth])
        if os.path.islink(prefix) and not _inside(os.path.realpath(prefix), checkout):
            link = prefix
            break
    raise UsageError(f"is a link to {shown(os.path.realpath(link))}, outside {shown(checkout)}, "
                     "the folder mcar writes its default outputs in: nothing was written "
                     f"there; remove the link, or name the output folder with {option}",
                     file=display_path(link))
