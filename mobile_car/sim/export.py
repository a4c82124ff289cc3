"""``mcar build --format mjcf``: the MuJoCo model ``mcar sim`` simulates, as MJCF text, so
that MuJoCo users get the car directly: the robot with its free joint, the floor, the
contact choices and the velocity motors on the drive wheels (see :mod:`.model`).

Collision meshes are referenced by absolute path (``strippath`` off): the written file
loads from wherever it is written on this machine, and nothing is copied beside it; to
move it to another machine, move the meshes with it and edit the paths.
"""

from __future__ import annotations


def mjcf(loaded, left: str | None = None, right: str | None = None) -> str:
    """The MJCF of a loaded robot (a LoadedRobot); raises SimModelError (exit 1) where
    MuJoCo cannot make a model of it."""
    from .model import SimModelError, build_model

    sim = build_model(loaded.urdf, loaded.label, loaded.base, loaded.search, left, right)
    try:
        return sim.spec.to_xml()
    except ValueError as error:  # pragma: no cover - a model that compiled writes out
        raise SimModelError(f"MuJoCo cannot write the model: {error}",
                            file=loaded.label) from None
