"""A URDF as world-space coloured triangles, ready for either renderer to draw.

yourdfpy poses every link (all joints at zero) and loads the geometry with trimesh; this
module flattens that scene into three parallel arrays, one row per triangle corner:
position (metres, world frame), smooth-shading normal, and RGBA colour in 0..1.

Colours follow rviz: a URDF ``<material>`` (named, defined once at the top, or inline)
colours primitives and meshes that carry no colour of their own (yourdfpy writes it into
the mesh's face colours); meshes with their own materials (COLLADA) keep them. Collision
geometry has no material in URDF, so it takes its link's first visual colour, as rviz does.

Mesh files are resolved with :class:`~mobile_car.packages.search.PackageSearch`, the same search
``mcar build`` uses, and are checked before loading so that a missing one is reported with
its file and line instead of being dropped silently (yourdfpy only logs a warning).
"""

from __future__ import annotations

import hashlib
import io
import logging
import math
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import trimesh
import yourdfpy
from lxml import etree

from ..errors import McarError, RenderError
from ..expand.xacro_build import display_path
from ..packages.search import PackageSearch

# Faces meeting at less than this angle are shaded as one smooth surface (cylinder
# sides, spheres); sharper edges (box corners, cylinder rims) stay crisp.
SMOOTH_ANGLE = math.radians(30)
# trimesh's colour for geometry without any material (rviz uses a similar grey).
NO_MATERIAL_RGBA = (0.6, 0.6, 0.62, 1.0)
# Smoothed meshes kept for reuse within a process (see _smooth_corners).
_SMOOTHED: dict[str, tuple] = {}
_SMOOTHED_LIMIT = 64


@dataclass
class Scene:
    """Triangle corners of a whole robot: ``positions``/``normals`` (N*3, 3) float32,
    ``colors`` (N*3, 4) float32 in 0..1; ``bounds`` is ((xmin, ymin, zmin), (xmax, ...))
    in metres, or None when there is nothing to draw."""

    positions: np.ndarray
    normals: np.ndarray
    colors: np.ndarray

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


def mesh_files(root: etree._Element, source: ModelSource, search: PackageSearch,
               collision: bool) -> list[Path]:
    """Every mesh file the chosen geometry (visual or collision) reads, checked to exist."""
    return [path for _uri, path, _where in _meshes(root, source, search, collision)]


def _meshes(root: etree._Element, source: ModelSource, search: PackageSearch,
            collision: bool):
    """(uri, file, where) of each mesh of the chosen geometry; RenderError if missing."""
    kind = "collision" if collision else "visual"
    for mesh in root.iterfind(f"link/{kind}/geometry/mesh"):
        uri = (mesh.get("filename") or "").strip()
        link = mesh.getparent().getparent().getparent().get("name", "?")
        where = {"file": display_path(source.path), "line": _line(mesh, source)}
        if not uri:
            raise RenderError(f"link '{link}': <mesh> without a filename", **where)
        try:
            path = search.resolve_uri(uri, base=source.path.parent)
        except McarError as exc:
            raise RenderError(f"link '{link}': mesh {uri}: {exc.message}", **where) from None
        if not path.is_file():
            raise RenderError(f"link '{link}': mesh {uri} not found (looked at "
                              f"{display_path(path)})", **where)
        yield uri, path, dict(where, link=link)


def _unpack_compressed(root, source: ModelSource, search: PackageSearch, collision: bool,
                       folder: Path) -> dict[str, str]:
    """uri -> a decompressed copy in ``folder`` of each compressed mesh (trimesh would
    decompress a bomb whole; here it stops at MCAR_MAX_MESH_MB): a single mesh as its
    own file, an archive as an uncompressed zip trimesh reads as it would the original."""
    import zipfile

    from ..load.compressed import broken_errors, compressed_kind, decompressed_members

    unpacked: dict[str, str] = {}
    for uri, path, where in _meshes(root, source, search, collision):
        kind = compressed_kind(path)
        if kind is None or uri in unpacked:
            continue
        try:
            members = decompressed_members(path, display_path(path))
        except McarError as exc:
            message = exc.message
        except broken_errors() as exc:
            message = " ".join(str(exc).split())[:200] or type(exc).__name__
        else:
            message = None
        if message is not None:
            raise RenderError(f"link '{where['link']}': mesh {uri}: {message}",
                              file=where["file"], line=where["line"])
        target = folder / str(len(unpacked))
        target.mkdir()
        if kind in ("bz2", "gz"):
            (target / Path(members[0][0]).name).write_bytes(members[0][1])
            unpacked[uri] = str(target / Path(members[0][0]).name)
        else:
            with zipfile.ZipFile(target / "mesh.zip", "w", zipfile.ZIP_STORED) as archive:
                for name, data in members:
                    archive.writestr(name, data)
            unpacked[uri] = str(target / "mesh.zip")
    return unpacked


def load_scene(source: ModelSource, search: PackageSearch, collision: bool = False) -> Scene:
    """Pose the robot at zero joint positions and flatten its geometry into triangles."""
    root = parse_urdf(source)
    mesh_files(root, source, search, collision)  # report a missing mesh before yourdfpy hides it
    with tempfile.TemporaryDirectory(prefix="mcar-meshes-") as folder:
        unpacked = _unpack_compressed(root, source, search, collision, Path(folder))
        return _load_model(source, search, collision, unpacked)


def _load_model(source: ModelSource, search: PackageSearch, collision: bool,
                unpacked: dict[str, str]) -> Scene:
    def resolve(fname: str) -> str:
        if fname.strip() in unpacked:
            return unpacked[fname.strip()]
        return str(search.resolve_uri(fname, base=source.path.parent))

    # yourdfpy reports unconnected links and unreadable meshes through logging; the
    # library must not print, and every real problem is raised below instead.
    logging.getLogger("yourdfpy").addHandler(logging.NullHandler())
    logging.getLogger("yourdfpy").propagate = False
    try:
        model = yourdfpy.URDF.load(
            io.BytesIO(source.xml), filename_handler=resolve,
            build_scene_graph=not collision, load_meshes=not collision,
            build_collision_scene_graph=collision, load_collision_meshes=collision,
            force_collision_mesh=False)
    except McarError:
        raise
    except Exception as exc:  # yourdfpy and trimesh raise anything from KeyError to ValueError
        raise RenderError(f"cannot build the model: {type(exc).__name__}: {exc}",
                          file=display_path(source.path)) from None
    graph_scene = model.collision_scene if collision else model.scene
    link_colors = _link_colors(model) if collision else {}
    return _flatten(graph_scene, link_colors)


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
        smooth = trimesh.graph.smooth_shade(mesh, angle=SMOOTH_ANGLE, facet_minarea=None)
        corners = smooth.faces.reshape(-1)
        cached = (smooth.vertices[corners], smooth.vertex_normals[corners],
                  smooth.visual.vertex_colors[corners, :4] / 255.0)
        if len(_SMOOTHED) >= _SMOOTHED_LIMIT:
            _SMOOTHED.pop(next(iter(_SMOOTHED)))
        _SMOOTHED[key] = cached
    return cached


def _flatten(graph_scene: trimesh.Scene, link_colors: dict[str, tuple]) -> Scene:
    positions, normals, colors = [], [], []
    parents = graph_scene.graph.transforms.parents
    for node in sorted(graph_scene.graph.nodes_geometry):
        transform, geometry_name = graph_scene.graph[node]
        mesh = graph_scene.geometry.get(geometry_name)
        if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
            continue
        mesh = mesh.copy()
        if not isinstance(mesh.visual, trimesh.visual.ColorVisuals):
            mesh.visual = _material_colors(mesh)
        if link_colors:
            rgba = link_colors.get(parents.get(node), NO_MATERIAL_RGBA)
            # int(255 * c), as yourdfpy converts visual colours, so both agree exactly
            mesh.visual.face_colors = (np.array(rgba) * 255).astype(np.uint8)
        elif not mesh.visual.defined:
            mesh.visual.face_colors = np.round(np.array(NO_MATERIAL_RGBA) * 255).astype(np.uint8)
        local_positions, local_normals, corner_colors = _smooth_corners(mesh)
        linear, offset = transform[:3, :3], transform[:3, 3]
        positions.append(local_positions @ linear.T + offset)
        # Normals go with the inverse transpose, which also covers scaled meshes.
        turned = local_normals @ np.linalg.inv(linear)
        normals.append(turned / np.maximum(np.linalg.norm(turned, axis=1, keepdims=True), 1e-12))
        colors.append(corner_colors)
    if not positions:
        empty = np.zeros((0, 3), np.float32)
        return Scene(empty, empty.copy(), np.zeros((0, 4), np.float32))
    return Scene(np.concatenate(positions).astype(np.float32),
                 np.concatenate(normals).astype(np.float32),
                 np.concatenate(colors).astype(np.float32))
