"""Mesh files read once a run: within :func:`kept` (``mcar specs``, whose sections look
at the robot's visuals with render's reader and simulate them with sim's), each file
:func:`~.mesh_reader.load_mesh` reads is parsed once while its stamp holds for the
readers of its geometry alone (textures left out) and once for render's (with them),
however many ``<mesh>`` elements name it (Unitree Go1 names calf.dae four times).
Outside it nothing is kept: a command that measures a large robot's meshes one by one
does not hold them all.

No trimesh here: the commands that read no mesh import this module too.
"""

from __future__ import annotations

import os
from contextlib import contextmanager

_kept: dict | None = None  # key -> what mesh_reader keeps, within kept() only


@contextmanager
def kept():
    """Keep the meshes read within (nested: the outermost decides)."""
    global _kept
    outermost = _kept is None
    if outermost:
        _kept = {}
    try:
        yield
    finally:
        if outermost:
            _kept = None


def key_of(path, options: dict):
    """The key of ``path`` read with ``options`` (the real file, its stamp), or None
    where nothing is kept or the file cannot be stamped (reading it says why)."""
    if _kept is None:
        return None
    from ..freshness import identity

    try:
        real = os.path.realpath(path)
        stamp = tuple(identity(os.stat(real)))
    except (OSError, ValueError):
        return None
    return real, stamp, tuple(sorted(options.items()))


def get(key):
    return None if _kept is None or key is None else _kept.get(key)


def put(key, value) -> None:
    if _kept is not None and key is not None:
        _kept[key] = value
