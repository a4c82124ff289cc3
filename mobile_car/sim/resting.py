"""How a robot rests on the floor by its geometry alone: the plane under its supports
(the lowest points of its wheels and castors) that carries its centre of mass, so that a
robot whose castor reaches lower than its wheels (Create 3, TurtleBot 4 on their
retracted wheel drops) rests leaning on it, as built, and is released in that pose. Drop
judges the tilt against this pose, not against level. Lengths in m, angles in rad."""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

# A support plane steeper than this is no rest: the robot is released level and drop
# shows what it does.
MAX_REST_TILT = math.radians(10)
# A plane tilted less is level: the rounding of the geometry's numbers (3e-9 rad on a car
# whose castor and wheels reach the same floor), which a run at a motor's limit amplified
# into 18 mm of drift between sim and the same robot's export.
LEVEL = 1e-6


@dataclass
class RestPose:
    height: float        # the root's height above the floor
    quat: list[float]    # the root's orientation (w, x, y, z)
    roll: float
    pitch: float


def rest_pose(mj, model, data, root_body: int, support_geoms, lowest_points) -> RestPose:
    """The pose of the root when the geometry rests on the floor with the joints where
    ``data`` has them; ``data``'s root is moved (upright at the origin, then into the
    pose) and its kinematics done."""
    free = _free_qpos(model)
    data.qpos[free:free + 7] = [0, 0, 0, 1, 0, 0, 0]
    mj.mj_kinematics(model, data)
    mj.mj_comPos(model, data)
    lowest = lowest_points(mj, model, data)
    points = np.array([[data.geom_xpos[g][0], data.geom_xpos[g][1], lowest[g]]
                       for g in support_geoms])
    roll = pitch = 0.0
    plane = _support_plane(points, data.subtree_com[root_body][:2])
    if plane is not None:
        a, b = plane
        pitch, roll = math.atan(a), -math.atan(b)
        if max(abs(pitch), abs(roll)) > MAX_REST_TILT or \
                max(abs(pitch), abs(roll)) < LEVEL:
            roll = pitch = 0.0
    quat = _quat(roll, pitch)
    data.qpos[free + 3:free + 7] = quat
    mj.mj_kinematics(model, data)
    lowest = lowest_points(mj, model, data)
    return RestPose(-min(lowest[g] for g in support_geoms), quat, roll, pitch)


def _support_plane(points, com) -> tuple[float, float] | None:
    """(a, b) of the plane z = a·x + b·y + c through three support points, every point
    on or above it, that is highest under the centre of mass (the lower hull's facet the
    robot stands on); None when no three points make one."""
    best, best_height = None, -np.inf
    for i, j, k in itertools.combinations(range(len(points)), 3):
        matrix = np.array([[p[0], p[1], 1.0] for p in points[[i, j, k]]])
        if abs(np.linalg.det(matrix)) < 1e-9:
            continue
        a, b, c = np.linalg.solve(matrix, points[[i, j, k], 2])
        if (points[:, 2] - (a * points[:, 0] + b * points[:, 1] + c) < -1e-7).any():
            continue
        height = a * com[0] + b * com[1] + c
        if height > best_height:
            best, best_height = (float(a), float(b)), height
    return best


def _quat(roll: float, pitch: float) -> list[float]:
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    return [cr * cp, sr * cp, cr * sp, -sr * sp]


def _free_qpos(model) -> int:
    return int(model.jnt_qposadr[model.joint("mcar_free").id])
