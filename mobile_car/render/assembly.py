"""Where every visual (or collision) of a robot sits in the world, in one pass over its tree.

yourdfpy can build a trimesh.Scene for the robot, but trimesh's scene graph rehashes all its
edges on many operations, so building and reading it costs O(links²): a 2,000-link robot
took 18 s, a 10,000-link one minutes. Here the links' world poses are composed once, each
from its parent's, with numpy 4x4 matrices (joints at zero, or where `--joint` puts them), and
each geometry becomes a :class:`Piece`.

Boxes, cylinders and spheres are the same unit primitive with the size folded into the
piece's transform: their smooth shading does not change with the size (a box's edges are
right angles at any size, a cylinder's side faces meet at 360°/sections whatever its radius
and length), so it is computed once per shape and colour instead of once per link.

Mesh files are read through :func:`mobile_car.load.mesh_reader.load_mesh`, within every
mesh limit and in metres. One over a limit, missing, or that cannot be read becomes a
placeholder piece (a box, drawn magenta by :mod:`.scene`) and the rest of the robot is
drawn: where the link's other geometry (its collision shapes for a visual, its visual
shapes for a collision) says how big the part is, the box takes that size and place;
else :mod:`.scene` sizes it from the rest of the robot.
"""

from __future__ import annotations

from collections import defaultdict, deque
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import trimesh
import yourdfpy

from ..errors import McarError
from ..load.mesh_reader import load_mesh

# Joint types whose position yourdfpy applies (at zero it is the origin, but a mimic's
# offset still turns or shifts the child).
_MOVING = ("revolute", "continuous", "prismatic")


@dataclass
class Piece:
    """One geometry of a link, placed in the world by ``transform`` (4x4): either ``mesh``
    (from a file, in its own frame, coloured) or ``primitive``, the name of a unit box,
    cylinder or sphere (see :func:`unit_primitive`; ``transform`` includes the size) with
    ``rgba``, the 0..255 colour yourdfpy would give it (None: no URDF colour).
    ``placeholder``: a mesh not read (over a limit, missing, broken): a unit box, sized by
    the scene unless ``sized`` (its transform holds the size its link's shapes give).
    ``overlay``: drawn in ``rgba`` whatever the view colours (a link frame's axis)."""

    link: str
    transform: np.ndarray
    mesh: trimesh.Trimesh | None = None
    primitive: str | None = None
    rgba: tuple | None = None
    placeholder: bool = False
    overlay: bool = False
    sized: bool = False


def joint_position(joint: yourdfpy.Joint, positions: dict[str, float] | None) -> float:
    """The joint's position: as given (default zero), or for a mimic joint, the position
    of the joint it follows times its multiplier plus its offset (yourdfpy's rule)."""
    positions = positions or {}
    if joint.mimic is None:
        return positions.get(joint.name, 0.0)
    multiplier = 1.0 if joint.mimic.multiplier is None else joint.mimic.multiplier
    return positions.get(joint.mimic.joint, 0.0) * multiplier + (joint.mimic.offset or 0.0)


def joint_matrix(joint: yourdfpy.Joint, positions: dict[str, float] | None = None) -> np.ndarray:
    """The child's pose in the parent's frame with the joints at ``positions`` (joint name
    -> radians or metres; default every joint at zero), as yourdfpy has it."""
    origin = np.eye(4) if joint.origin is None else joint.origin
    if joint.type not in _MOVING:
        return origin
    q = joint_position(joint, positions)
    if q == 0.0:
        return origin  # origin @ (a rotation or shift by 0) is exactly the origin
    axis = np.asarray(joint.axis if joint.axis is not None else (1.0, 0.0, 0.0), dtype=float)
    if joint.type == "prismatic":
        return origin @ trimesh.transformations.translation_matrix(q * axis)
    return origin @ trimesh.transformations.rotation_matrix(q, axis)


def link_poses(robot: yourdfpy.Robot,
               positions: dict[str, float] | None = None) -> dict[str, np.ndarray]:
    """Every link's world pose: the tree walked once from its roots. A link no joint
    reaches (a second root) stays at the origin, where yourdfpy puts it too. A joint
    naming an undefined link is a ValueError (``mcar check`` reports it first: E122)."""
    children = defaultdict(list)
    has_parent = set()
    names = {link.name for link in robot.links}
    for joint in robot.joints:
        for role, name in (("parent", joint.parent), ("child", joint.child)):
            if name not in names:
                raise ValueError(f"joint '{joint.name}': {role} link '{name}' is not defined")
        children[joint.parent].append(joint)
        has_parent.add(joint.child)
    poses = {}
    queue = deque()
    for link in robot.links:
        if link.name not in has_parent and link.name not in poses:
            poses[link.name] = np.eye(4)
            queue.append(link.name)
    while queue:
        parent = queue.popleft()
        for joint in children.get(parent, ()):
            if joint.child not in poses:  # a second parent or a cycle: first one wins
                poses[joint.child] = poses[parent] @ joint_matrix(joint, positions)
                queue.append(joint.child)
    for link in robot.links:  # links only on a cycle: check reports those
        poses.setdefault(link.name, np.eye(4))
    return poses


_UNIT = {"box": lambda: trimesh.primitives.Box(extents=(1.0, 1.0, 1.0)),
         "cylinder": lambda: trimesh.primitives.Cylinder(radius=1.0, height=1.0),
         "sphere": lambda: trimesh.primitives.Sphere(radius=1.0)}


def unit_primitive(kind: str) -> trimesh.Trimesh:
    """A new unit box (1 m sides), cylinder or sphere (radius 1 m, length 1 m), centred."""
    return _UNIT[kind]()


def _visual_rgba(body, materials: dict) -> tuple | None:
    """The colour yourdfpy.urdf.apply_visual_color writes into a visual's faces."""
    material = getattr(body, "material", None)
    if material is None:
        return None
    color = material.color
    if color is None and material.name is not None and material.name in materials:
        color = materials[material.name].color
    return None if color is None else tuple(int(255 * channel) for channel in color.rgba)


def _primitive(geometry) -> tuple[str, np.ndarray] | None:
    """(unit shape, its scale as a 4x4 matrix) for a box, cylinder or sphere; else None."""
    if geometry.box is not None:
        return "box", np.diag([*np.asarray(geometry.box.size, dtype=float), 1.0])
    if geometry.cylinder is not None:
        radius, length = geometry.cylinder.radius, geometry.cylinder.length
        return "cylinder", np.diag([radius, radius, length, 1.0])
    if geometry.sphere is not None:
        radius = geometry.sphere.radius
        return "sphere", np.diag([radius, radius, radius, 1.0])
    return None


def mesh_scene(geometry, filename: Callable[[str], str], skip_materials: bool,
               reads: list[Path]):
    """A mesh file as a trimesh.Scene in metres, scaled, loaded the way yourdfpy loads it
    (the files it pulls in added to ``reads``); None if it is not read: over a mesh
    limit, missing, or broken (mcar check says which, with the <mesh>'s line: W207,
    W210)."""
    try:
        scene, pulled = load_mesh(filename(geometry.mesh.filename), ignore_broken=True,
                                  force="scene", skip_materials=skip_materials)
    except (McarError, OSError):  # over a limit, not found, not a regular file
        return None
    except Exception:  # trimesh and pycollada raise anything on a file they cannot parse
        return None
    if not any(len(getattr(mesh, "faces", ())) for mesh in scene.geometry.values()):
        return None  # nothing to draw: the marker shows where it belongs
    reads.extend(pulled)
    if geometry.mesh.scale is not None:
        scene = scene.scaled(geometry.mesh.scale)
    return scene


_UNIT_BOUNDS = {"box": 0.5, "sphere": 1.0}  # half extent of the unit shapes; cylinder apart


def _shapes_box(bodies) -> np.ndarray | None:
    """The box (4x4: a unit box scaled and placed) around the primitive shapes of
    ``bodies`` in their link's frame, or None when they hold no primitive."""
    corners = []
    for body in bodies:
        primitive = None if body.geometry is None else _primitive(body.geometry)
        if primitive is None:
            continue
        kind, scale = primitive
        half = np.array([1.0, 1.0, 0.5]) if kind == "cylinder" else \
            np.full(3, _UNIT_BOUNDS[kind])
        unit = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * half
        placed = (np.eye(4) if body.origin is None else body.origin) @ scale
        corners.append(unit @ placed[:3, :3].T + placed[:3, 3])
    if not corners:
        return None
    points = np.concatenate(corners)
    low, high = points.min(axis=0), points.max(axis=0)
    box = np.diag([*np.maximum(high - low, 1e-6), 1.0])
    box[:3, 3] = (low + high) / 2
    return box


def pieces(robot: yourdfpy.Robot, filename: Callable[[str], str],
           collision: bool, positions: dict[str, float] | None = None,
           reads: list[Path] | None = None) -> Iterator[Piece]:
    """Every visual (or collision) geometry of ``robot``, placed in the world with the
    joints at ``positions`` (default zero) and, for a visual, coloured with its URDF
    material as yourdfpy colours it. The files meshes pull in (materials, textures) are
    added to ``reads``."""
    reads = [] if reads is None else reads
    poses = link_poses(robot, positions)
    materials = {material.name: material for material in robot.materials}
    for link in robot.links:
        pose = poses[link.name]
        for body in link.collisions if collision else link.visuals:
            if body.geometry is None:
                continue
            placed = pose if body.origin is None else pose @ body.origin
            primitive = _primitive(body.geometry)
            if primitive is not None:
                kind, scale = primitive
                rgba = None if collision else _visual_rgba(body, materials)
                yield Piece(link.name, placed @ scale, primitive=kind, rgba=rgba)
                continue
            if body.geometry.mesh is None:
                continue
            scene = mesh_scene(body.geometry, filename, collision, reads)
            if scene is None:
                known = _shapes_box(link.visuals if collision else link.collisions)
                if known is not None:
                    yield Piece(link.name, pose @ known, primitive="box", placeholder=True,
                                sized=True)
                else:
                    yield Piece(link.name, placed, primitive="box", placeholder=True)
                continue
            for node in scene.graph.nodes_geometry:
                transform, name = scene.graph.get(node)
                mesh = scene.geometry[name]
                if not collision:
                    yourdfpy.urdf.apply_visual_color(mesh, body, materials)
                yield Piece(link.name, placed @ transform, mesh)
