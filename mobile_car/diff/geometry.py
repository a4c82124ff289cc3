"""The little 3-D arithmetic a robot comparison needs, in plain Python: poses composed
down a tree of a few dozen frames, the box around a placed primitive (principal moments
come from check's inertia module). numpy would cost more to import than all of this costs to run.
"""

from __future__ import annotations

import math

Matrix = tuple[tuple[float, float, float], ...]
Vector = tuple[float, float, float]

IDENTITY: Matrix = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


def rpy_matrix(rpy) -> Matrix:
    """URDF's fixed-axis roll, pitch, yaw: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    roll, pitch, yaw = rpy
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return ((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
            (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
            (-sp, cp * sr, cp * cr))


def matrix_rpy(m: Matrix) -> Vector:
    """The roll, pitch, yaw of a rotation (urdfdom's convention, as rpy_matrix)."""
    pitch = math.atan2(-m[2][0], math.hypot(m[0][0], m[1][0]))
    if abs(math.cos(pitch)) < 1e-12:  # gimbal lock: put everything in roll
        return (math.atan2(-m[1][2], m[1][1]), pitch, 0.0)
    return (math.atan2(m[2][1], m[2][2]), pitch, math.atan2(m[1][0], m[0][0]))


def multiply(a: Matrix, b: Matrix) -> Matrix:
    return tuple(tuple(sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3))
                 for i in range(3))


def rotate(m: Matrix, v) -> Vector:
    return tuple(m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2] for i in range(3))


class Pose:
    """A rigid transform: rotation ``r`` then translation ``t``."""

    __slots__ = ("r", "t")

    def __init__(self, r: Matrix = IDENTITY, t: Vector = (0.0, 0.0, 0.0)):
        self.r = r
        self.t = t

    @classmethod
    def of(cls, xyz, rpy) -> Pose:
        return cls(rpy_matrix(rpy), tuple(map(float, xyz)))

    def __matmul__(self, other: Pose) -> Pose:
        moved = rotate(self.r, other.t)
        shifted = tuple(a + b for a, b in zip(self.t, moved, strict=True))
        return Pose(multiply(self.r, other.r), shifted)

    def apply(self, point) -> Vector:
        moved = rotate(self.r, point)
        return tuple(a + b for a, b in zip(moved, self.t, strict=True))


def angle_between(a: Matrix, b: Matrix) -> float:
    """The angle (radians) of the rotation taking ``a`` to ``b``."""
    trace = sum(a[k][i] * b[k][i] for i in range(3) for k in range(3))  # trace(aᵀ b)
    return math.acos(max(-1.0, min(1.0, (trace - 1.0) / 2.0)))


def half_extents(kind: str, size, r: Matrix) -> Vector:
    """Half the world-axis extent of a primitive centred at the origin, turned by ``r``."""
    if kind == "sphere":
        return (size[0],) * 3
    if kind == "cylinder":  # radius, length; its axis is local z
        radius, half = size[0], size[1] / 2.0
        return tuple(abs(r[i][2]) * half + radius * math.sqrt(max(0.0, 1.0 - r[i][2] ** 2))
                     for i in range(3))
    # a box, or a mesh's own box (size = its extents)
    return tuple(sum(abs(r[i][j]) * size[j] / 2.0 for j in range(3)) for i in range(3))
