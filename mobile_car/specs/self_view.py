"""What a robot's sensors see of the robot itself: its visual and collision geometry at
rest as one triangle soup (render's assembly: the same poses, primitives and bounded mesh
reads ``mcar render`` draws), and the sensors' rays cast against it with trimesh (Embree
where it is installed, else trimesh's own ray-triangle test).

Visual geometry counts as much as collision geometry: a standoff drawn but never made to
collide still stops a real laser. The sensor's housing is left out: its own link's
geometry, and that of any link whose geometry encloses the sensor's origin (TurtleBot3
waffle's camera frames sit inside camera_link's body, behind its lens): a ray cast from
inside would hit its inner face.
Frames: the root link's at rest (every joint at 0, sim's springs at their rest).
"""

from __future__ import annotations

import io
import logging
import math
from dataclasses import dataclass, field

import numpy as np

from ..check.colours import without_unusable_colours

# The camera's rays: a coarse grid through pixel centres, its aspect the image's, its
# rows bounded (the image's size comes from the description: 1 x 10^9 is a number too).
CAMERA_COLUMNS = 64
CAMERA_MAX_ROWS = 4 * CAMERA_COLUMNS
# The key of the intersector on every link not kept apart (link names are strings).
REST = ("rest",)


@dataclass
class Extent:
    """One geometry's extent, to tell whether a sensor sits inside it: ``inverse`` takes a
    root-frame point to the geometry's own frame, where ``shape`` ("box", "cylinder",
    "sphere": the unit primitives; "mesh": its box ``low``..``high``) holds it."""

    link: str
    kind: str
    inverse: np.ndarray
    low: np.ndarray | None = None
    high: np.ndarray | None = None

    def holds(self, point: np.ndarray) -> bool:
        if not np.isfinite(self.inverse).all():
            return False
        x, y, z = self.inverse[:3, :3] @ point + self.inverse[:3, 3]
        if self.kind == "box":
            return max(abs(x), abs(y), abs(z)) <= 0.5
        if self.kind == "cylinder":
            return x * x + y * y <= 1.0 and abs(z) <= 0.5
        if self.kind == "sphere":
            return x * x + y * y + z * z <= 1.0
        return bool((self.low <= (x, y, z)).all() and ((x, y, z) <= self.high).all())


@dataclass
class RobotSurface:
    """``triangles`` (N, 3, 3) in the root frame at rest, ``piece_of`` (N,) an index into
    ``pieces`` (each geometry's :class:`Extent`); ``poses`` link -> 4x4 in the root frame;
    ``notes`` what was left out."""

    triangles: np.ndarray
    piece_of: np.ndarray
    pieces: list
    poses: dict
    notes: list[str] = field(default_factory=list)
    _casters: dict = field(default_factory=dict)
    _apart: set = field(default_factory=set)

    def placed(self, link: str) -> bool:
        return link in self.poses

    def frame(self, sensor) -> np.ndarray:
        """The sensor's frame (4x4) in the root frame."""
        return sensor_frame(sensor, self.poses)

    def blocked(self, sensor, origin: np.ndarray, directions: np.ndarray,
                housing: list[str]) -> np.ndarray:
        """(N,) bool: the ray meets the robot (the sensor's ``housing`` aside) within the
        sensor's range. As Gazebo casts it, the ray starts at range min: a part nearer is
        not seen (a real scanner reports no range there either). The nearest part met
        lies within the range exactly where the nearest of some part of the robot does:
        the links kept apart (:meth:`keep_apart`) are cast one by one, the rest together,
        each made ray-ready once a run (a scene of the robot without each sensor's housing
        cost Go1 and Baxter seconds a sensor)."""
        hit = np.zeros(len(directions), dtype=bool)
        if not len(directions):
            return hit
        if not set(housing) <= self._apart:  # (a housing keep_apart was not told of)
            self._apart |= set(housing)
            self._casters.pop(REST, None)
        starts = origin + directions * sensor.range_min
        reach = sensor.range_max - sensor.range_min
        parts = [link for link in self.links() if link in self._apart and link not in housing]
        for caster in [self.caster(link) for link in parts] + [self._rest()]:
            if caster is None:
                continue
            locations, rays, _ = caster.intersects_location(starts, directions,
                                                            multiple_hits=False)
            if len(rays):
                distance = np.linalg.norm(locations - starts[rays], axis=1)
                hit[rays[distance <= reach]] = True
        return hit

    def keep_apart(self, spots) -> None:
        """``spots``: the (link, origin) of every sensor to be cast. The links that may be
        one's housing (its own, any with a shape whose box holds its origin) are made
        ray-ready one by one, the rest of the robot once, together: a robot of many links
        is not cast link by link."""
        for link, origin in spots:
            self._apart |= {link} | {piece.link for piece in self.pieces if piece.holds(origin)}
        self._casters.pop(REST, None)

    def _rest(self):
        if REST not in self._casters:
            owned = [i for i, piece in enumerate(self.pieces) if piece.link not in self._apart]
            self._casters[REST] = _intersector(self.triangles[np.isin(self.piece_of, owned)])
        return self._casters[REST]

    def housing(self, link: str, origin: np.ndarray) -> list[str]:
        """The links a sensor on ``link`` at ``origin`` looks out of: its own, and any
        other whose geometry encloses its origin (a camera frame inside the camera link's
        body, behind its lens): their geometry is left out of its view. A link's geometry
        encloses a point one of its shapes' box holds where every ray from the point along
        the 6 axes and the 8 diagonals meets it (a chassis whose box holds a lidar in a
        recess open above does not)."""
        near = {piece.link for piece in self.pieces if piece.holds(origin)} - {link}
        return [link] + sorted(other for other in near if self._encloses(other, origin))

    def _encloses(self, link: str, origin: np.ndarray) -> bool:
        directions, caster = enclosing_directions(), self.caster(link)
        if caster is None:
            return False
        _, rays, _ = caster.intersects_location(
            np.broadcast_to(origin, directions.shape), directions, multiple_hits=False)
        return len(set(rays.tolist())) == len(directions)

    def links(self) -> list[str]:
        """The links with geometry, in the order of their first piece."""
        return list(dict.fromkeys(piece.link for piece in self.pieces))

    def caster(self, link: str):
        """A ray intersector on ``link``'s triangles alone (None when it has none: a mesh
        of no faces), made once."""
        if link not in self._casters:
            owned = [i for i, piece in enumerate(self.pieces) if piece.link == link]
            self._casters[link] = _intersector(self.triangles[np.isin(self.piece_of, owned)])
        return self._casters[link]


def enclosing_directions() -> np.ndarray:
    """The directions a housing meets: the 6 axes and the 8 diagonals, unit length."""
    axes = np.vstack([np.eye(3), -np.eye(3)])
    diagonals = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)],
                         dtype=float) / math.sqrt(3)
    return np.vstack([axes, diagonals])


def robot_surface(loaded, positions: dict[str, float]) -> RobotSurface:
    """The visual and collision geometry of ``loaded`` (a LoadedRobot), joints at
    ``positions`` (others at 0). A mesh that cannot be read (check's W207, W210) is left
    out, and said so: render's stand-in box is not the part's shape."""
    import yourdfpy

    from ..render.assembly import link_poses, pieces, unit_primitive

    logging.getLogger("yourdfpy").addHandler(logging.NullHandler())
    logging.getLogger("yourdfpy").propagate = False

    def resolve(name: str) -> str:
        return str(loaded.search.resolve_uri(name, base=loaded.base))

    model = yourdfpy.URDF.load(io.BytesIO(without_unusable_colours(loaded.urdf)),
                               filename_handler=resolve, build_scene_graph=False,
                               load_meshes=False, build_collision_scene_graph=False,
                               load_collision_meshes=False)
    triangles, owners, extents, notes = [], [], [], []
    units = {}
    for collision in (True, False):
        with np.errstate(all="ignore"):
            for piece in pieces(model.robot, resolve, collision, positions, []):
                if piece.placeholder:
                    notes.append(f"link {piece.link}: a {'collision' if collision else 'visual'}"
                                 " mesh not read is left out of what its sensors see")
                    continue
                if piece.primitive is not None:
                    if piece.primitive not in units:
                        unit = unit_primitive(piece.primitive)
                        units[piece.primitive] = np.asarray(unit.vertices)[unit.faces]
                    corners = units[piece.primitive]
                    extent = Extent(piece.link, piece.primitive, _inverse(piece.transform))
                else:
                    vertices = np.asarray(piece.mesh.vertices, dtype=float)
                    corners = vertices[piece.mesh.faces]
                    extent = Extent(piece.link, "mesh", _inverse(piece.transform),
                                    vertices.min(axis=0), vertices.max(axis=0))
                placed = corners @ piece.transform[:3, :3].T + piece.transform[:3, 3]
                if not np.isfinite(placed).all():
                    notes.append(f"link {piece.link}: geometry without finite coordinates "
                                 "left out of what its sensors see")
                    continue
                triangles.append(placed)
                owners.append(np.full(len(placed), len(extents)))
                extents.append(extent)
    poses = link_poses(model.robot, positions)
    if triangles:
        soup, piece_of = np.concatenate(triangles), np.concatenate(owners)
    else:
        soup, piece_of = np.zeros((0, 3, 3)), np.zeros(0, dtype=int)
    return RobotSurface(soup, piece_of, extents, poses, list(dict.fromkeys(notes)))


def _inverse(transform: np.ndarray) -> np.ndarray:
    """The inverse of a placed piece's transform (its scale included); a flat one (a
    box of zero thickness) has none: NaN, and holds no sensor (its triangles still
    block rays)."""
    try:
        return np.linalg.inv(transform)
    except np.linalg.LinAlgError:
        return np.full((4, 4), np.nan)


def _intersector(triangles: np.ndarray):
    import trimesh

    if not len(triangles):
        return None
    mesh = trimesh.Trimesh(vertices=triangles.reshape(-1, 3),
                           faces=np.arange(len(triangles) * 3).reshape(-1, 3),
                           process=False, validate=False)
    if trimesh.ray.has_embree:
        from trimesh.ray.ray_pyembree import RayMeshIntersector
    else:
        from trimesh.ray.ray_triangle import RayMeshIntersector
    return RayMeshIntersector(mesh)


def sensor_frame(sensor, poses: dict) -> np.ndarray:
    """The sensor's frame (4x4) in the root frame: its link's pose, then its offset."""
    return poses[sensor.link] @ sensor_offset(sensor)


def sensor_offset(sensor) -> np.ndarray:
    """The sensor's frame (4x4) on its link's: its <pose>, then a camera's <pose>."""
    x, y, z, roll, pitch, yaw = sensor.pose
    cx, cy, cz, croll, cpitch, cyaw = sensor.camera_pose
    return pose_matrix((x, y, z), (roll, pitch, yaw)) @ \
        pose_matrix((cx, cy, cz), (croll, cpitch, cyaw))


def pose_matrix(xyz, rpy) -> np.ndarray:
    """4x4 of a translation and fixed-axis roll, pitch, yaw (URDF's and SDF's order)."""
    roll, pitch, yaw = rpy
    cr, sr, cp, sp = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    matrix = np.eye(4)
    matrix[:3, :3] = [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                      [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                      [-sp, cp * sr, cp * cr]]
    matrix[:3, 3] = xyz
    return matrix


def lidar_rays(sensor, frame: np.ndarray) -> np.ndarray:
    """(samples, 3) unit directions in the root frame: each sample's azimuth in the
    sensor's xy plane."""
    angles = np.asarray(sensor.azimuths())
    local = np.stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)], axis=1)
    return local @ frame[:3, :3].T


def camera_grid(sensor) -> tuple[int, int]:
    """(columns, rows) of the coarse grid a camera's image is sampled on."""
    width, height = sensor.image
    return CAMERA_COLUMNS, min(CAMERA_MAX_ROWS, max(1, round(CAMERA_COLUMNS * height / width)))


def camera_rays(sensor, frame: np.ndarray) -> np.ndarray:
    """(columns * rows, 3) unit directions through the grid's cell centres, the camera
    looking along its frame's x (Gazebo's camera convention), y to the image's left."""
    columns, rows = camera_grid(sensor)
    half_width = math.tan(sensor.hfov / 2)
    half_height = half_width * sensor.image[1] / sensor.image[0]
    u = (1 - 2 * (np.arange(columns) + 0.5) / columns) * half_width
    v = (1 - 2 * (np.arange(rows) + 0.5) / rows) * half_height
    left, up = np.meshgrid(u, v)
    local = np.stack([np.ones(left.size), left.ravel(), up.ravel()], axis=1)
    local /= np.linalg.norm(local, axis=1, keepdims=True)
    return local @ frame[:3, :3].T
