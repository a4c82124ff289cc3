"""MuJoCo's proof of what the sensors see of the robot: the same URDF made into a MuJoCo
model by sim's own code (:func:`mobile_car.sim.model.prepare_urdf`: meshes MuJoCo reads,
in metres), with every ``<visual>`` made a geom beside the collisions (sim's model drops
them, and a visual-only standoff still stops a laser), the root welded where it is, the
joints at rest. MuJoCo's own kinematics place the sensor; ``mj_multiRay`` casts its rays,
its housing (the links :mod:`.self_view` finds) left out.
"""

from __future__ import annotations

import re

import numpy as np
from lxml import etree

from ..errors import McarError
from ..sim.engine import mujoco
from ..sim.model import as_urdfdom_reads, prepare_urdf
from .self_view import sensor_offset

# Every body gets this much mass (the <inertial>s are taken out: the proof only poses the
# robot), as MuJoCo refuses to compile a massless moving link (a frame on a continuous
# joint).
BOUND_MASS = 1e-6
BOUND_INERTIA = 1e-9
# The geom group a sensor's housing is moved to while its rays are cast (the rays skip it).
SKIPPED_GROUP = 5


class ProofUnavailable(Exception):
    """MuJoCo could not make the proof's model (said in a note; the figures stand)."""


class RayProof:
    """The robot in MuJoCo, geometry visual and collision, ready to cast rays."""

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

    def blocked(self, sensor, origin: np.ndarray, directions: np.ndarray,
                housing: list[str]) -> np.ndarray:
        """(N,) bool: MuJoCo's ray from range min meets a geom within the range, the
        sensor's ``housing`` aside (:meth:`.self_view.RobotSurface.housing`: the links'
        geoms put, for the cast, in a group the rays skip)."""
        model, count = self.model, len(directions)
        bodies = {self._body(link) for link in housing} - {-1}
        skipped = [g for g in range(model.ngeom) if model.geom_bodyid[g] in bodies]
        kept = model.geom_group[skipped].copy()
        model.geom_group[skipped] = SKIPPED_GROUP
        groups = np.ones(6, dtype=np.uint8)
        groups[SKIPPED_GROUP] = 0
        geoms = np.full(count, -1, dtype=np.int32)
        distance = np.full(count, -1.0)
        reach = float(sensor.range_max - sensor.range_min)
        directions = np.ascontiguousarray(directions, dtype=float)
        try:
            if sensor.range_min == 0:
                self.mj.mj_multiRay(model, self.data, np.asarray(origin, dtype=float),
                                    directions.ravel(), groups, 1, -1, geoms, distance, None,
                                    count, reach)
            else:  # each ray starts at range min, as Gazebo's: one point each
                found = np.zeros(1, dtype=np.int32)
                for index, direction in enumerate(directions):
                    start = origin + direction * sensor.range_min
                    distance[index] = self.mj.mj_ray(model, self.data, start, direction,
                                                     groups, 1, -1, found)
                    geoms[index] = found[0]
        finally:
            model.geom_group[skipped] = kept
        return (geoms >= 0) & (distance >= 0) & (distance <= reach)

    def _body(self, link: str) -> int:
        try:
            return int(self.model.body(link).id)
        except KeyError:
            return -1


def _first_line(error) -> str:
    text = str(getattr(error, "message", error)).strip().splitlines()
    return text[0].removeprefix("Error: ") if text else type(error).__name__
