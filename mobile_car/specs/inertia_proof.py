"""MuJoCo's proof of an ``inertia.<link>`` figure: the same shapes given to MuJoCo's own
inertia from geometry (``inertiafromgeom``, one density over them), its body's mass,
centre and principal tensor turned back into the tensor about the declared
``<inertial>`` origin and axes, and compared with the figure. MuJoCo computes boxes,
cylinders and spheres with its own formulas and meshes with its own volume integrals
(``exact`` for a closed mesh, ``convex`` for one taken by its hull, as the figure took
it), so the two agree only if both are right.

A mesh goes to MuJoCo as sim gives it (:func:`mobile_car.sim.meshes.mujoco_mesh`: a
copy MuJoCo reads, in metres, in the user's cache). Imports MuJoCo: only when asked.
"""

from __future__ import annotations

import math

import numpy as np

from .figures import Proof

TOLERANCE = 1e-6  # of the largest moment


def mujoco_proof(bodies: list, paths: list, hulls: list, mass: float, xyz: tuple,
                 rpy: tuple, values: list) -> Proof:
    """``bodies``: the link's (kind, shape, xyz, rpy, dims) the figure used, ``paths``
    each one's mesh file (None for a primitive), ``hulls`` whether the figure took its
    convex hull; ``values`` the figure."""
    from ..sim.engine import mujoco
    from ..sim.meshes import mujoco_mesh
    from .solids import six

    mj = mujoco()
    spec = mj.MjSpec()
    spec.compiler.inertiafromgeom = mj.mjtInertiaFromGeom.mjINERTIAFROMGEOM_TRUE
    body = spec.worldbody.add_body(name="link")
    for index, ((_kind, shape, at, turn, dims), path, hull) in enumerate(
            zip(bodies, paths, hulls, strict=True)):  # noqa: B007 (index names the meshes)
        geom = body.add_geom(pos=list(at), quat=_quat(turn))
        if shape.tag == "box":
            geom.type, geom.size = mj.mjtGeom.mjGEOM_BOX, [d / 2 for d in dims]
        elif shape.tag == "cylinder":
            geom.type, geom.size = mj.mjtGeom.mjGEOM_CYLINDER, [dims[0], dims[1] / 2, 0]
        elif shape.tag == "sphere":
            geom.type, geom.size = mj.mjtGeom.mjGEOM_SPHERE, [dims[0], 0, 0]
        else:
            name = f"mesh{index}"
            spec.add_mesh(name=name, file=str(mujoco_mesh(path).resolve()), scale=list(dims),
                          inertia=mj.mjtMeshInertia.mjMESH_INERTIA_CONVEX if hull else
                          mj.mjtMeshInertia.mjMESH_INERTIA_EXACT)
            geom.type, geom.meshname = mj.mjtGeom.mjGEOM_MESH, name
    try:
        model = spec.compile()
    except ValueError as error:
        text = str(error).strip().splitlines()
        return Proof(None, False, shown_tolerance(), f"MuJoCo cannot take an inertia from these "
                     f"shapes: {text[0] if text else type(error).__name__}")
    found = model.body("link")
    density = mass / float(found.mass[0])  # (each geom at 1000 kg/m³: the same for all)
    rotation = np.zeros(9)
    mj.mju_quat2Mat(rotation, np.array(found.iquat, dtype=float))
    r = rotation.reshape(3, 3)
    about_centre = density * (r @ np.diag(found.inertia) @ r.T)
    d = np.array(found.ipos, dtype=float) - np.array(xyz, dtype=float)
    about_point = about_centre + mass * (d @ d * np.eye(3) - np.outer(d, d))
    axes = np.zeros(9)
    mj.mju_quat2Mat(axes, np.array(_quat(rpy)))
    a = axes.reshape(3, 3)
    measured = six(a.T @ about_point @ a)
    scale = max(abs(v) for v in values) or 1.0
    error = max(abs(m - v) for m, v in zip(measured, values, strict=True)) / scale
    return Proof(measured, error <= TOLERANCE, shown_tolerance(),
                 f"MuJoCo's inertia from the same shapes (inertiafromgeom): off by "
                 f"{error:.2g} of the largest moment")


def shown_tolerance() -> str:
    return f"{TOLERANCE:g} of the largest moment"


def _quat(rpy: tuple) -> list[float]:
    """URDF's fixed-axis roll, pitch, yaw as MuJoCo's (w, x, y, z)."""
    roll, pitch, yaw = (v / 2 for v in rpy)
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch),
                              math.sin(pitch), math.cos(yaw), math.sin(yaw))
    return [cr * cp * cy + sr * sp * sy, sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy]
