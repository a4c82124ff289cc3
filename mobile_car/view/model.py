"""One robot input, loaded and checked as ``mcar render`` does, as a yourdfpy model for viser.

A robot that ``mcar check`` rejects (any error) is refused with
:class:`~mobile_car.errors.CheckFailed`, carrying check's diagnostics, so the viewer shows
what the command line would print, and never a half-built robot. yourdfpy builds the
scene, but every mesh is read by mcar's reader (:class:`MeshesReadByMcar`): within the mesh
limits and in metres, COLLADA as RViz reads it, as ``mcar render`` draws it. A mesh that
is not read (missing, broken, over a limit: check's W207 and W210, shown as warnings) is
left out.
"""

from __future__ import annotations

import io
import logging
import math
from dataclasses import dataclass, field
from pathlib import Path

import yourdfpy

from ..errors import McarError, RenderError
from ..load.inputs import RobotInput
from ..load.robot import LoadOptions
from ..render.assembly import mesh_scene
from ..render.jobs import drawable_check
from ..render.session import SHOWN_WARNINGS, model_source

# The joint types a slider moves (and ``mcar render --joint`` poses).
MOVING = ("revolute", "continuous", "prismatic")


@dataclass
class JointRange:
    """A movable joint's slider: ``lower``..``upper`` (radians or metres), ``home`` is
    where the robot is drawn at start and after reset (zero, or the nearer limit)."""

    name: str
    kind: str  # revolute, continuous or prismatic
    lower: float
    upper: float

    @property
    def home(self) -> float:
        return min(max(0.0, self.lower), self.upper)


@dataclass
class ViewModel:
    """A checked robot ready to show: the yourdfpy model (both scene graphs built), the
    joints a slider moves, and every file it was made from (to watch for edits)."""

    urdf: yourdfpy.URDF
    joints: list[JointRange]
    files: list[Path] = field(default_factory=list)
    warnings: list = field(default_factory=list)  # check's diagnostics worth showing

    @property
    def has_collision(self) -> bool:
        return any(link.collisions for link in self.urdf.robot.links)


def load_model(inp: RobotInput, options: LoadOptions, stdin=None) -> ViewModel:
    """Load, check and parse one input; McarError (CheckFailed for check's findings)."""
    result = drawable_check(inp, options, collision=False, stdin=stdin)
    loaded = result.loaded
    source = model_source(loaded)
    meshes = [mesh.path for mesh in result.mesh_files if mesh.path is not None]
    meshes += [path for mesh in result.mesh_files for path in mesh.reads]
    generated = options.overrides.path if options.overrides is not None else None
    files = [path for path in dict.fromkeys([*loaded.deps, *meshes]) if path != generated]

    # A mesh over a limit (W210), missing or broken (W207) is not read: a name that is no
    # file, which is left out.
    unread = {mesh.path for mesh in result.mesh_files if mesh.over_limit or not mesh.sound}

    def resolve(fname: str) -> str:
        try:
            path = loaded.search.resolve_uri(fname, base=source.path.parent)
        except McarError:  # outside the allowed folders (W215), or no package: not read
            return ""
        return "" if path in unread else str(path)

    # yourdfpy logs what it cannot load; a library must not print, and mcar check has
    # reported every real problem above.
    logging.getLogger("yourdfpy").addHandler(logging.NullHandler())
    logging.getLogger("yourdfpy").propagate = False
    try:
        parsed = yourdfpy.URDF.load(io.BytesIO(source.xml), build_scene_graph=False,
                                    load_meshes=False, build_collision_scene_graph=False,
                                    load_collision_meshes=False)
        urdf = MeshesReadByMcar(robot=parsed.robot, filename_handler=resolve,
                                build_scene_graph=True, load_meshes=True,
                                build_collision_scene_graph=True, load_collision_meshes=True)
    except McarError:
        raise
    except Exception as exc:  # yourdfpy and trimesh raise anything from KeyError to ValueError
        raise RenderError(f"cannot build the model: {type(exc).__name__}: {exc}",
                          file=inp.label) from None
    warnings = [d for d in result.diagnostics if d.rule in SHOWN_WARNINGS]
    return ViewModel(urdf, joint_ranges(urdf), files, warnings)


class MeshesReadByMcar(yourdfpy.URDF):
    """yourdfpy's model, its meshes read by mcar's reader instead of ``trimesh.load``
    (the one place yourdfpy reads a file: ``_geometry2trimeshscene``)."""

    def _geometry2trimeshscene(self, geometry, load_file, force_mesh, skip_materials):
        if geometry.mesh is None:
            return super()._geometry2trimeshscene(geometry, load_file, force_mesh,
                                                  skip_materials)
        if not load_file:
            return None
        path = self._filename_handler(fname=geometry.mesh.filename)
        if not path:
            return None
        return mesh_scene(geometry, lambda _name: path, skip_materials, [])


def joint_ranges(urdf: yourdfpy.URDF) -> list[JointRange]:
    """A slider range for every joint that moves on its own (mimic joints follow theirs):
    the URDF's limits; a continuous joint turns a full circle, -pi..pi."""
    ranges = []
    for joint in urdf.actuated_joints:
        if joint.type not in MOVING:  # floating, planar: no one slider moves them
            continue
        limit = joint.limit
        lower = None if limit is None else limit.lower
        upper = None if limit is None else limit.upper
        if joint.type == "continuous" or lower is None or upper is None:
            lower, upper = -math.pi, math.pi
        ranges.append(JointRange(joint.name, joint.type, float(lower), float(upper)))
    return ranges


def error_lines(error: McarError) -> list[str]:
    """The lines ``mcar`` prints for an error (uncoloured), for the page."""
    diagnostics = getattr(error, "diagnostics", None)
    if diagnostics:
        return [diagnostic.text() for diagnostic in diagnostics]
    where = error.location()
    return [f"{where + ': ' if where else ''}error: {error.message}",
            *(f"  {line}" for line in error.details)]
