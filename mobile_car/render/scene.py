"""A URDF as world-space coloured triangles, ready for either renderer to draw.

yourdfpy reads the URDF, :mod:`~mobile_car.render.assembly` poses every link (all joints
at zero) and trimesh loads the geometry; this module flattens it into three parallel
arrays, one row per triangle corner: position (metres, world frame), smooth-shading
normal, and RGBA colour in 0..1.

Colours follow rviz: a URDF ``<material>`` (named, defined once at the top, or inline)
colours primitives and meshes that carry no colour of their own (yourdfpy writes it into
the mesh's face colours); meshes with their own materials (COLLADA) keep them. Collision
geometry has no material in URDF, so it takes its link's first visual colour, as rviz does.

Mesh files are resolved with :class:`~mobile_car.packages.search.PackageSearch`, the same search
``mcar build`` uses, and read within the mesh limits, in metres
(:mod:`mobile_car.load.mesh_reader`). One that is not read (over a limit, missing, broken:
``mcar check`` reports it with its line, W207 or W210) is drawn as a magenta box
(PLACEHOLDER_RGBA): the size and place of its link's other shapes where it has some, else
a fifth of the rest of the robot; the rest of the robot is drawn.
"""

from __future__ import annotations

import hashlib
import io
import logging
import math
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import trimesh
import yourdfpy
from lxml import etree

from ..errors import McarError, RenderError
from ..expand.xacro_build import display_path
from ..packages.search import PackageSearch
from .assembly import Piece, link_poses, pieces, unit_primitive
from .frames import axis_boxes, axis_length, chosen_frames, labels
from .pose import joint_positions
from .smoothing import smooth_shade

# Faces meeting at less than this angle are shaded as one smooth surface (cylinder
# sides, spheres); sharper edges (box corners, cylinder rims) stay crisp.
SMOOTH_ANGLE = math.radians(30)
# trimesh's colour for geometry without any material (rviz uses a similar grey).
NO_MATERIAL_RGBA = (0.6, 0.6, 0.62, 1.0)
# A mesh over a limit (W210): a box in a colour no robot part has, the colour of a
# missing texture in many 3D tools; its side a fraction of the rest of the robot.
PLACEHOLDER_RGBA = (255, 0, 255, 255)
PLACEHOLDER_FRACTION = 0.2
PLACEHOLDER_SIDE = 0.1  # metres, when nothing else is drawn
# Smoothed meshes kept for reuse within a process (see _smooth_corners).
_SMOOTHED: dict[str, tuple] = {}
_SMOOTHED_LIMIT = 64
# Smoothed unit box, cylinder and sphere: positions and normals (see assembly.py).
_UNIT_CORNERS: dict[str, tuple] = {}


@dataclass
class Scene:
    """Triangle corners of a whole robot: ``positions``/``normals`` (N*3, 3) float32,
    ``colors`` (N*3, 4) float32 in 0..1; ``bounds`` is ((xmin, ymin, zmin), (xmax, ...))
    in metres, or None when there is nothing to draw."""

    positions: np.ndarray
    normals: np.ndarray
    colors: np.ndarray
    # With load_scene(with_links=True): the link each corner belongs to, as an index
    # into ``link_names`` (mcar diff recolours the changed links).
    link_of: np.ndarray | None = None
    link_names: tuple[str, ...] = ()
    # The files the meshes pulled in (materials, textures), inputs like the meshes.
    reads: tuple[Path, ...] = ()
    # Link names to lay over the picture: (text, world point) per drawn frame (frames.py).
    labels: tuple = ()
    frames_only: bool = False  # nothing but link frames is drawn (a skeleton)

    @property
    def triangle_count(self) -> int:
        return len(self.positions) // 3

    @property
    def bounds(self) -> np.ndarray | None:
        if not len(self.positions):
            return None
        return np.array([self.positions.min(axis=0), self.positions.max(axis=0)], dtype=float)


@dataclass
class ModelSource:
    """A URDF document and where it came from, for mesh paths and error messages.

    ``path`` is the file the user named (a .urdf, or the .xacro it was built from);
    relative mesh paths are taken from its folder. ``lines_match`` is true when line numbers
    in ``xml`` are line numbers in ``path`` (a plain .urdf), so errors can cite them.
    """

    xml: bytes
    path: Path
    lines_match: bool


def parse_urdf(source: ModelSource) -> etree._Element:
    """The root ``<robot>`` element; malformed XML is a RenderError with its line."""
    parser = etree.XMLParser(remove_blank_text=True, resolve_entities=False, no_network=True)
    try:
        root = etree.fromstring(source.xml, parser=parser)
    except etree.XMLSyntaxError as exc:
        line = exc.lineno if source.lines_match else None
        raise RenderError(f"not well-formed XML: {exc.msg}", file=display_path(source.path),
                          line=line) from None
    if etree.QName(root).localname != "robot":
        raise RenderError(f"root element is <{etree.QName(root).localname}>, not <robot>",
                          file=display_path(source.path), line=_line(root, source))
    if not root.get("name"):
        raise RenderError("<robot> has no name: a macro file is not a robot; render a file "
                          "that includes it", file=display_path(source.path),
                          line=_line(root, source))
    return root


def _line(element, source: ModelSource) -> int | None:
    return element.sourceline if source.lines_match else None


def load_scene(source: ModelSource, search: PackageSearch, collision: bool = False,
               joints=(), with_links: bool = False, frames: str = "auto") -> Scene:
    """Pose the robot (joints at zero, or as ``joints``, (name, value text) pairs of
    ``--joint``) and flatten its geometry into triangles; ``with_links`` also notes which
    link each corner belongs to; ``frames`` says which link frames get axes and names
    (:mod:`.frames`)."""
    parse_urdf(source)  # a located error for what is no robot, before yourdfpy reads it
    return _load_model(source, search, collision, joints, with_links, frames)


def _load_model(source: ModelSource, search: PackageSearch, collision: bool,
                joints=(), with_links: bool = False, frames: str = "auto") -> Scene:
    def resolve(fname: str) -> str:
        return str(search.resolve_uri(fname, base=source.path.parent))

    reads: list[Path] = []

    # yourdfpy reports unconnected links and unreadable meshes through logging; the
    # library must not print, and every real problem is raised below instead.
    logging.getLogger("yourdfpy").addHandler(logging.NullHandler())
    logging.getLogger("yourdfpy").propagate = False
    try:
        # Only the parsing: yourdfpy's scene graph costs O(links²) (see assembly.py).
        model = yourdfpy.URDF.load(
            io.BytesIO(source.xml), filename_handler=resolve, build_scene_graph=False,
            load_meshes=False, build_collision_scene_graph=False,
            load_collision_meshes=False)
        positions = joint_positions(model.robot, joints, display_path(source.path))
        link_colors = _link_colors(model) if collision else {}
        with np.errstate(all="ignore"):  # an overflow is reported below, not as a warning
            placed = list(pieces(model.robot, resolve, collision, positions, reads))
            drawn = chosen_frames(model.robot, link_poses(model.robot, positions),
                                  {piece.link for piece in placed}, frames)
            scene = _flatten(placed, link_colors, with_links, drawn)
        scene.labels = labels(drawn)
        scene.frames_only = bool(drawn) and not placed
        scene.reads = tuple(dict.fromkeys(reads))
    except McarError:
        raise
    except Exception as exc:  # yourdfpy and trimesh raise anything from KeyError to ValueError
        raise RenderError(f"cannot build the model: {type(exc).__name__}: {exc}",
                          file=display_path(source.path)) from None
    if not (np.isfinite(scene.positions).all() and np.isfinite(scene.normals).all()):
        # mcar check bounds the URDF's numbers; a mesh file's own vertices can still be
        # beyond what float32 holds (3.4e38), or not numbers at all.
        raise RenderError("the geometry does not fit in float32 coordinates (a mesh file "
                          "with vertices that are not finite numbers, or too large "
                          "for its scale)", file=display_path(source.path))
    return scene


def _material_rgba(material, materials: dict) -> tuple | None:
    if material is None:
        return None
    if material.color is not None:
        return tuple(material.color.rgba)
    named = materials.get(material.name)
    if named is not None and named.color is not None:
        return tuple(named.color.rgba)
    return None


def _link_colors(model: yourdfpy.URDF) -> dict[str, tuple]:
    """Each link's first visual colour, used for its collision geometry."""
    materials = {m.name: m for m in model.robot.materials}
    colors = {}
    for link in model.robot.links:
        for visual in link.visuals:
            rgba = _material_rgba(visual.material, materials)
            if rgba is not None:
                colors[link.name] = rgba
                break
    return colors


def _material_colors(mesh: trimesh.Trimesh) -> trimesh.visual.ColorVisuals:
    """Per-vertex colours from a mesh's own material: its texture, else its main colour."""
    visual = mesh.visual
    if getattr(visual, "uv", None) is not None and len(visual.uv) == len(mesh.vertices):
        try:
            sampled = visual.to_color()
            colors = np.asarray(sampled.vertex_colors)
            if colors.shape == (len(mesh.vertices), 4):
                return trimesh.visual.ColorVisuals(mesh, vertex_colors=colors)
        except Exception:  # an unreadable texture: fall back to the material's colour
            pass
    material = getattr(visual, "material", None)
    color = getattr(material, "main_color", None)
    if color is None:
        color = np.round(np.array(NO_MATERIAL_RGBA) * 255)
    face_colors = np.tile(np.asarray(color, dtype=np.uint8)[:4], (len(mesh.faces), 1))
    return trimesh.visual.ColorVisuals(mesh, face_colors=face_colors)


def _smooth_corners(mesh: trimesh.Trimesh) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Triangle corners of a coloured mesh, in its own frame: positions, smooth normals,
    RGBA 0..1. Cached by content: the same motor mesh twice in a robot, or in every file
    of a package, is smoothed once (the costly part for large meshes)."""
    visual = mesh.visual
    colours = visual.vertex_colors if visual.kind == "vertex" else visual.face_colors
    key = hashlib.sha1(b"".join(np.ascontiguousarray(a).tobytes() for a in (
        mesh.vertices, mesh.faces, colours))).hexdigest()
    cached = _SMOOTHED.get(key)
    if cached is None:
        smooth = smooth_shade(mesh, SMOOTH_ANGLE)
        corners = smooth.faces.reshape(-1)
        cached = (smooth.vertices[corners], smooth.vertex_normals[corners],
                  smooth.visual.vertex_colors[corners, :4] / 255.0)
        if len(_SMOOTHED) >= _SMOOTHED_LIMIT:
            _SMOOTHED.pop(next(iter(_SMOOTHED)))
        _SMOOTHED[key] = cached
    return cached


def _face_colors(piece: Piece, link_colors: dict[str, tuple]) -> np.ndarray | None:
    """The colour a piece is drawn in when its own is not kept: its link's first visual
    colour for collision geometry, else None (keep the mesh's or the URDF's colour)."""
    if link_colors:
        # int(255 * c), as yourdfpy converts visual colours, so both agree exactly
        return (np.array(link_colors.get(piece.link, NO_MATERIAL_RGBA)) * 255).astype(np.uint8)
    return None


def _primitive_corners(piece: Piece, link_colors: dict[str, tuple]) -> tuple:
    """The smoothed corners of a unit primitive, in the piece's colour. The shape is
    smoothed once per process: a primitive has one colour, which smoothing keeps."""
    colour = PLACEHOLDER_RGBA if piece.placeholder else \
        piece.rgba if piece.overlay else _face_colors(piece, link_colors)
    if colour is None:
        colour = piece.rgba if piece.rgba is not None else \
            np.round(np.array(NO_MATERIAL_RGBA) * 255).astype(np.uint8)
    shape = _UNIT_CORNERS.get(piece.primitive)
    if shape is None:
        positions, normals, _ = _smooth_corners(unit_primitive(piece.primitive))
        shape = _UNIT_CORNERS[piece.primitive] = (positions, normals)
    positions, normals = shape
    rgba = np.asarray(colour, dtype=np.uint8)[:4] / 255.0
    return positions, normals, np.broadcast_to(rgba, (len(positions), 4))


def _mesh_corners(piece: Piece, link_colors: dict[str, tuple]) -> tuple | None:
    mesh = piece.mesh
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        return None
    mesh = mesh.copy()
    if not isinstance(mesh.visual, trimesh.visual.ColorVisuals):
        mesh.visual = _material_colors(mesh)
    colour = _face_colors(piece, link_colors)
    if colour is not None:
        mesh.visual.face_colors = colour
    elif not mesh.visual.defined:
        mesh.visual.face_colors = np.round(np.array(NO_MATERIAL_RGBA) * 255).astype(np.uint8)
    return _smooth_corners(mesh)


def _sized_markers(markers: list[Piece], bounds) -> list[Piece]:
    """The placeholders of meshes not read, as boxes a fraction of the robot's size."""
    side = PLACEHOLDER_SIDE
    if bounds is not None and float(np.ptp(bounds, axis=0).max()) > 0:
        side = PLACEHOLDER_FRACTION * float(np.ptp(bounds, axis=0).max())
    scale = np.diag([side, side, side, 1.0])
    return [Piece(piece.link, piece.transform @ scale, primitive="box", placeholder=True)
            for piece in markers]


def _flatten(placed: Iterator[Piece], link_colors: dict[str, tuple],
             with_links: bool = False, frames=()) -> Scene:
    placed = list(placed)
    # Each piece is shaped once: the sizes of the placeholders and of the frame axes come
    # from the bounds of the pieces shaped before them, and smoothing a mesh again for
    # those bounds (once per pass, past the smoothing cache's size) was most of the time.
    shapes: dict[int, tuple | None] = {}

    def shape(piece: Piece) -> tuple | None:
        if id(piece) not in shapes:
            shapes[id(piece)] = _primitive_corners(piece, link_colors) \
                if piece.primitive is not None else _mesh_corners(piece, link_colors)
        return shapes[id(piece)]

    markers = [piece for piece in placed if piece.placeholder and not piece.sized]
    if markers:
        placed = [piece for piece in placed if not (piece.placeholder and not piece.sized)]
        placed += _sized_markers(markers, _bounds(placed, shape))
    if frames:  # axes sized by the rest of the robot
        length = axis_length(frames, _bounds(placed, shape))
        placed += [Piece(frame.link, transform, primitive="box", rgba=rgba, overlay=True)
                   for frame in frames for transform, rgba in axis_boxes(frame, length)]
    shaped = []
    # Where two faces lie in one plane, the one drawn first shows. Pictures keep the order
    # they had when yourdfpy's scene named the pieces geometry_0, geometry_1, ... and they
    # were drawn sorted by name (geometry_10 before geometry_2).
    for index in sorted(range(len(placed)), key=str):
        piece = placed[index]
        corners = shape(piece)
        if corners is not None:
            shaped.append((piece.transform, corners, piece.link))
    # Written straight into the float32 arrays the renderer takes: a robot of 10,000
    # links has millions of corners, and lists of float64 parts would triple the memory.
    count = sum(len(corners[0]) for _, corners, _ in shaped)
    positions = np.empty((count, 3), np.float32)
    normals = np.empty((count, 3), np.float32)
    colors = np.empty((count, 4), np.float32)
    names: dict[str, int] = {}
    link_of = np.empty(count, np.int32) if with_links else None
    start = 0
    for transform, (local_positions, local_normals, corner_colors), link in shaped:
        end = start + len(local_positions)
        positions[start:end] = _placed(local_positions, transform)
        # Normals go with the inverse transpose, which also covers scaled meshes.
        turned = local_normals @ np.linalg.inv(transform[:3, :3])
        normals[start:end] = turned / np.maximum(
            np.linalg.norm(turned, axis=1, keepdims=True), 1e-12)
        colors[start:end] = corner_colors
        if link_of is not None:
            link_of[start:end] = names.setdefault(link, len(names))
        start = end
    return Scene(positions, normals, colors, link_of, tuple(names))


def _placed(local_positions: np.ndarray, transform: np.ndarray) -> np.ndarray:
    """Corner positions in the world, in float64 (stored as float32 by the caller)."""
    return local_positions @ transform[:3, :3].T + transform[:3, 3]


def _bounds(placed: list[Piece], shape) -> np.ndarray | None:
    """What ``Scene.bounds`` of these pieces would be, without building their scene."""
    low, high = [], []
    for piece in placed:
        corners = shape(piece)
        if corners is not None and len(corners[0]):
            # float32 first, as the scene stores them, so the bounds agree to the bit
            world = _placed(corners[0], piece.transform).astype(np.float32)
            low.append(world.min(axis=0))
            high.append(world.max(axis=0))
    if not low:
        return None
    return np.array([np.min(low, axis=0), np.max(high, axis=0)], dtype=float)
