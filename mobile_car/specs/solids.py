"""The inertia a link's shapes give it: each box, cylinder and sphere in closed form, each
mesh through trimesh's mass properties (read by :func:`mobile_car.load.mesh_reader.load_mesh`,
the one way to trimesh, within its limits), and several shapes as one solid of uniform
density: their volumes, centroids and tensors added by the parallel-axis theorem, the mass
shared by volume (shapes that overlap count twice: said in the figure's assumption).

A :class:`Solid` is a shape's volume (m³), centroid (m) and tensor about its centroid per
unit density (m⁵), all in its link's frame; :func:`tensor_about` turns their sum into the
tensor of a given mass about a given point and axes (kg m²). numpy is imported here only:
``mcar specs`` imports this module when it computes inertias.
"""

from __future__ import annotations

from dataclasses import dataclass
from math import pi

import numpy as np

from ..check.rest_pose import frame_of


class NoVolume(Exception):
    """A shape that gives no inertia (a mesh that cannot be read, or of no volume); the
    message says why, for the section's notes."""


@dataclass
class Solid:
    volume: float
    centroid: np.ndarray  # (3,)
    tensor: np.ndarray    # (3, 3), about the centroid, per unit density
    hull: bool = False    # a mesh that is not watertight: its convex hull's


def box(x: float, y: float, z: float) -> Solid:
    volume = x * y * z
    return Solid(volume, np.zeros(3),
                 volume / 12 * np.diag([y * y + z * z, x * x + z * z, x * x + y * y]))


def cylinder(radius: float, length: float) -> Solid:
    """About its own z axis, as URDF's cylinder."""
    volume = pi * radius * radius * length
    side = volume * (3 * radius * radius + length * length) / 12
    return Solid(volume, np.zeros(3), np.diag([side, side, volume * radius * radius / 2]))


def sphere(radius: float) -> Solid:
    volume = 4 / 3 * pi * radius ** 3
    return Solid(volume, np.zeros(3), np.eye(3) * volume * 0.4 * radius * radius)


def mesh(path, scale: tuple) -> Solid:
    """The solid of the mesh file at ``path`` times ``scale`` (per axis, as URDF's
    ``<mesh scale>``), in metres: its own if watertight, else its convex hull's."""
    from ..errors import InputError
    from ..load.mesh_reader import load_mesh

    try:
        loaded, _read = load_mesh(path, str(path), textures=False, force="mesh")
    except InputError as error:
        raise NoVolume(error.message) from None
    except Exception as error:  # trimesh raises anything on a file it cannot parse
        raise NoVolume(f"cannot be read: {' '.join(str(error).split())[:200]}") from None
    if getattr(loaded, "faces", None) is None or not len(loaded.faces):
        raise NoVolume("holds no triangles")
    transform = np.diag([*scale, 1.0])
    loaded.apply_transform(transform)  # (trimesh turns the faces over on a mirroring scale)
    hull = not loaded.is_watertight
    solid = loaded.convex_hull if hull else loaded
    volume = float(solid.volume)
    if not volume > 0:
        raise NoVolume("encloses no volume")
    # trimesh's density is 1: its mass is the volume, its moments per unit density
    return Solid(volume, np.array(solid.center_mass, dtype=float),
                 np.array(solid.moment_inertia, dtype=float), hull)


def placed(solid: Solid, xyz: tuple, rpy: tuple) -> Solid:
    """``solid`` moved by a URDF ``<origin>`` into its link's frame."""
    rotation, _ = frame_of(tuple(xyz), tuple(rpy))
    r = np.array(rotation, dtype=float).reshape(3, 3)
    return Solid(solid.volume, r @ solid.centroid + np.array(xyz, dtype=float),
                 r @ solid.tensor @ r.T, solid.hull)


def tensor_about(solids: list[Solid], mass: float, xyz: tuple, rpy: tuple) -> np.ndarray:
    """The tensor (kg m²) of ``mass`` spread over ``solids`` (link frame) at one density,
    about the point ``xyz`` in the axes ``rpy`` (an ``<inertial><origin>``)."""
    point = np.array(xyz, dtype=float)
    total = np.zeros((3, 3))
    for solid in solids:
        d = solid.centroid - point
        total += solid.tensor + solid.volume * (d @ d * np.eye(3) - np.outer(d, d))
    density = mass / sum(s.volume for s in solids)
    rotation, _ = frame_of(tuple(xyz), tuple(rpy))
    r = np.array(rotation, dtype=float).reshape(3, 3)
    return density * (r.T @ total @ r)



def six(tensor) -> list[float]:
    """[ixx, ixy, ixz, iyy, iyz, izz], URDF's order; a product of inertia under 1e-12 of
    the largest moment is rounding's noise off a zero (a turned cylinder's 1e-21), 0."""
    values = [float(tensor[0, 0]), float(tensor[0, 1]), float(tensor[0, 2]),
              float(tensor[1, 1]), float(tensor[1, 2]), float(tensor[2, 2])]
    small = 1e-12 * max(abs(v) for v in values)
    return [0.0 if abs(v) < small else v for v in values]


def matrix(values) -> np.ndarray:
    xx, xy, xz, yy, yz, zz = values
    return np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]], dtype=float)
