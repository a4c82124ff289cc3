"""MuJoCo's cast of what the sensors see of the robot: the same URDF made into a MuJoCo
model by sim's own code (:func:`mobile_car.sim.model.prepare_urdf`: meshes MuJoCo reads,
in metres), with every ``<visual>`` made a geom beside the collisions (sim's model drops
them, and a visual-only standoff still stops a laser), the root welded where it is, the
joints at rest. MuJoCo's own kinematics place the sensor; ``mj_multiRay`` casts its rays,
its housing left out.

It is the proof of :mod:`.self_view`'s cast (trimesh's), the housing then the links
:mod:`.self_view` finds; with the proofs off (``mcar specs --no-proof``) it is the figure
itself, its housing found here by the same test (:meth:`RayProof.housing`), and trimesh
(which brings scipy, ~0.5 s cold) is not imported at all.
"""

from __future__ import annotations

import re

import numpy as np
from lxml import etree

from ..errors import McarError
from ..sim.engine import mujoco
from ..sim.model import as_urdfdom_reads, prepare_urdf
from .self_view import enclosing_directions, sensor_offset

# Every body gets this much mass (the <inertial>s are taken out: the proof only poses the
# robot), as MuJoCo refuses to compile a massless moving link (a frame on a continuous
# joint).
BOUND_MASS = 1e-6
BOUND_INERTIA = 1e-9
# The geom group a sensor's housing is moved to while its rays are cast (the rays skip it).
SKIPPED_GROUP = 5
# MuJoCo's geom types (mjtGeom) a URDF gives: its <sphere>, <cylinder>, <box>, <mesh>.
SPHERE, CYLINDER, BOX, MESH = 2, 5, 6, 7
ANY_DISTANCE = 1e10  # mj_multiRay's cutoff for a ray of any length (MuJoCo's mjMAXVAL)


class ProofUnavailable(Exception):
    """MuJoCo could not make the proof's model (said in a note; the figures stand)."""


class RayProof:
    """The robot in MuJoCo, geometry visual and collision, ready to cast rays."""

    engine = "mujoco"  # (the figures' sources name the engine that cast them)

    def __init__(self, loaded, start: dict[str, float]):
        mj = self.mj = mujoco()
        parser = etree.XMLParser(resolve_entities=False, no_network=True)
        root = etree.fromstring(loaded.urdf, parser)
        as_urdfdom_reads(root)
        for link in root.iterchildren("link"):
            # The proof only poses the robot: no mass is needed, and an inertia MuJoCo
            # refuses (E310) would cost every sensor its proof. Each body gets BOUND_MASS.
            for inertial in list(link.iterchildren("inertial")):
                link.remove(inertial)
            for visual in list(link.iterchildren("visual")):
                visual.tag = "collision"
                for material in visual.findall("material"):
                    visual.remove(material)
        try:
            # (prepare_urdf calls every mesh it is given a collision mesh: here it is any)
            self.notes = [note.replace(": collision mesh ", ": mesh ", 1)
                          for note in prepare_urdf(root, loaded.base, loaded.search)]
            spec = mj.MjSpec.from_string(etree.tostring(root, encoding="unicode"))
        except (ValueError, McarError) as error:
            raise ProofUnavailable(_first_line(error)) from None
        spec.compiler.boundmass = BOUND_MASS
        spec.compiler.boundinertia = BOUND_INERTIA
        self.refused = False  # a mesh MuJoCo refused is left out (trimesh would see it)
        self.model = self._compile(spec)
        self.data = mj.MjData(self.model)
        for name, position in start.items():
            try:
                joint = self.model.joint(name)
            except KeyError:
                continue
            self.data.qpos[self.model.jnt_qposadr[joint.id]] = position
        mj.mj_kinematics(self.model, self.data)

    def _compile(self, spec):
        """The compiled model; a mesh MuJoCo refuses (a flat decal: "coplanar vertices,
        cannot compute convex hull") is left out of the proof with a note, and the rest
        compiled again: the proof then differs where that mesh blocks, and says why."""
        for _ in range(len(spec.meshes) + 1):
            try:
                return spec.compile()
            except ValueError as error:
                found = re.search(r"mesh '([^']*)'", str(error))
                mesh = spec.mesh(found.group(1)) if found else None
                if mesh is None:
                    raise ProofUnavailable(_first_line(error)) from None
                self.refused = True
                for geom in list(spec.geoms):
                    if geom.meshname == mesh.name:
                        self.notes.append(f"link {geom.parent.name}: mesh {mesh.file} left "
                                          f"out of the proof: {_first_line(error)}")
                        spec.delete(geom)
                spec.delete(mesh)
        raise ProofUnavailable("MuJoCo refuses every mesh")

    def frame(self, sensor) -> np.ndarray:
        """The sensor's frame (4x4, root frame) as MuJoCo's kinematics place its link."""
        body = self._body(sensor.link)
        link = np.eye(4)
        if body >= 0:
            link[:3, :3] = self.data.xmat[body].reshape(3, 3)
            link[:3, 3] = self.data.xpos[body]
        return link @ sensor_offset(sensor)

    def placed(self, link: str) -> bool:
        """Whether MuJoCo's model has ``link`` (every link is a body: no fixed link fused)."""
        return self._body(link) >= 0

    def blocked(self, sensor, origin: np.ndarray, directions: np.ndarray,
                housing: list[str]) -> np.ndarray:
        """(N,) bool: MuJoCo's ray from range min meets a geom within the range, the
        sensor's ``housing`` aside (:meth:`housing`, or with trimesh's figure
        :meth:`.self_view.RobotSurface.housing`: the links' geoms put, for the cast, in a
        group the rays skip)."""
        bodies = {self._body(link) for link in housing} - {-1}
        skipped = [g for g in range(self.model.ngeom) if self.model.geom_bodyid[g] in bodies]
        reach = float(sensor.range_max - sensor.range_min)
        geoms, distance = self._cast(origin, directions, skipped, sensor.range_min, reach)
        return (geoms >= 0) & (distance >= 0) & (distance <= reach)

    def _cast(self, origin, directions, skipped: list[int], start: float, reach: float):
        """(geom hit or -1, distance) of each ray from ``origin`` + ``start`` along it,
        the ``skipped`` geoms aside, within ``reach``."""
        model, count = self.model, len(directions)
        kept = model.geom_group[skipped].copy()
        model.geom_group[skipped] = SKIPPED_GROUP
        groups = np.ones(6, dtype=np.uint8)
        groups[SKIPPED_GROUP] = 0
        geoms = np.full(count, -1, dtype=np.int32)
        distance = np.full(count, -1.0)
        directions = np.ascontiguousarray(directions, dtype=float)
        origin = np.asarray(origin, dtype=float)
        try:
            if start == 0:
                self.mj.mj_multiRay(model, self.data, origin, directions.ravel(), groups, 1,
                                    -1, geoms, distance, None, count, reach)
            else:  # each ray starts at range min, as Gazebo's: one point each
                found = np.zeros(1, dtype=np.int32)
                for index, direction in enumerate(directions):
                    distance[index] = self.mj.mj_ray(model, self.data, origin + direction * start,
                                                     direction, groups, 1, -1, found)
                    geoms[index] = found[0]
        finally:
            model.geom_group[skipped] = kept
        return geoms, distance

    def housing(self, link: str, origin: np.ndarray) -> list[str]:
        """The links a sensor on ``link`` at ``origin`` looks out of, by
        :meth:`.self_view.RobotSurface.housing`'s test on MuJoCo's geoms: its own, and any
        other with a shape whose box holds the origin and whose geometry every ray from
        it along the 6 axes and the 8 diagonals meets."""
        own = self._body(link)
        near = {int(self.model.geom_bodyid[g]) for g in range(self.model.ngeom)
                if self.model.geom_bodyid[g] != own and self._holds(g, origin)}
        names = sorted(self.model.body(body).name for body in near if self._encloses(body, origin))
        return [link] + names

    def _holds(self, geom: int, point: np.ndarray) -> bool:
        """Whether geom ``geom``'s shape (a mesh: the box of its vertices in the mesh
        file's frame, as :class:`.self_view.Extent`'s) holds ``point``."""
        model, kind = self.model, self.model.geom_type[geom]
        x, y, z = local = self.data.geom_xmat[geom].reshape(3, 3).T @ \
            (np.asarray(point, dtype=float) - self.data.geom_xpos[geom])
        size = model.geom_size[geom]
        if kind == BOX:
            return bool((np.abs(local) <= size).all())
        if kind == CYLINDER:
            return bool(x * x + y * y <= size[0] ** 2 and abs(z) <= size[1])
        if kind == SPHERE:
            return bool(x * x + y * y + z * z <= size[0] ** 2)
        if kind != MESH:
            return False
        # MuJoCo moves a mesh's vertices to its inertial frame (mesh_pos, mesh_quat): the
        # file's frame, where the box is taken, is that move undone.
        mesh = model.geom_dataid[geom]
        rotation = np.zeros(9)
        self.mj.mju_quat2Mat(rotation, model.mesh_quat[mesh])
        rotation = rotation.reshape(3, 3)
        start = model.mesh_vertadr[mesh]
        vertices = model.mesh_vert[start:start + model.mesh_vertnum[mesh]] @ rotation.T + \
            model.mesh_pos[mesh]
        inside = rotation @ local + model.mesh_pos[mesh]
        return bool((vertices.min(axis=0) <= inside).all() and
                    (inside <= vertices.max(axis=0)).all())

    def _encloses(self, body: int, origin: np.ndarray) -> bool:
        skipped = [g for g in range(self.model.ngeom) if self.model.geom_bodyid[g] != body]
        geoms, _ = self._cast(origin, enclosing_directions(), skipped, 0.0, ANY_DISTANCE)
        return bool((geoms >= 0).all())

    def _body(self, link: str) -> int:
        try:
            return int(self.model.body(link).id)
        except KeyError:
            return -1


def _first_line(error) -> str:
    text = str(getattr(error, "message", error)).strip().splitlines()
    return text[0].removeprefix("Error: ") if text else type(error).__name__
