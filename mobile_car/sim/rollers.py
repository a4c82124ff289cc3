"""Mecanum wheels in MuJoCo: each wheel touches the floor through a contact that grips
along its rollers' axis and lets it roll freely across it.

A URDF draws a mecanum wheel as a plain cylinder (linorobot2, ROSbot XL), or with a few
roller links that make the kind plain but not a rolling surface. Neither rolls as a
mecanum wheel does, so the wheel's own collision geometry is taken off the floor and a
capsule of the wheel's radius, lying level along its grip axis (:mod:`.mecanum`), touches
the floor instead, with anisotropic friction: GRIP along the capsule, the rollers' free
roll across it. MuJoCo orients a capsule-on-plane contact along the capsule's axis, and
an explicit contact pair's five friction coefficients apply in that frame
(google-deepmind/mujoco#67); the capsule belongs to the wheel's body, so the contact moves
with the wheel's rim and a wheel that turns pushes the robot along the grip axis. The
wheel turns, and its capsule with it: before every step :meth:`Rollers.align` turns each
capsule back by its joint's angle, so that it stays level along its grip axis
(``model.geom_quat``, which MuJoCo reads in the step's kinematics). Roller links keep
their joints but leave the floor to the capsule.

Friction: the grip is the wheel's tyre's, its ``<gazebo>`` ``mu`` with ``fdir1`` (ROSbot
XL: 1), else its ``<mu1>`` where that is a tyre's (GRIP_MIN or more), else MuJoCo's
default of 1: a ``<mu1>`` of 0.01 (linorobot2) is the rollers' free roll that Gazebo's
planar_move needs, not a grip. Across it: the declared ``mu2``, else FREE_ROLL, and
FREE_ROLL at least: a roller rolls, its resistance is a rolling one, as a castor ball's
(mu 0.01), never Gazebo's ideal 0 (ROSbot, ROSbot XL, Ridgeback: ``mu2`` 0 with
``fdir1``). MuJoCo's elliptic cone at MIN_MU across and 1 along (a ratio of 1e5) let a
braked robot creep down along its grip at 0.08 mm/s on a slope of 8° (Ridgeback's tilt
proof took it for a slide at 7.6-8.3°, its figure 35.2°; ROSbot's at 19-24°); at 0.01
across it holds to its figure.
"""

from __future__ import annotations

import numpy as np

from .mecanum import half_spans

TYRE = 1.0          # mu of a tyre that declares none (MuJoCo's default)
GRIP_MIN = 0.1      # a declared mu1 under this is the rollers' free roll, not a grip
FREE_ROLL = 0.01    # mu across the grip axis: the rollers roll (the castors' ball's mu)
MIN_MU = 1e-5       # MuJoCo's least friction coefficient (mjMINMU)
HALF_LENGTH = 0.1   # of the radius: the capsule's half-length, a short contact patch


def tyre_grip(wheel, sources) -> tuple[float, float, str]:
    """(mu along the grip axis, mu across it, where they came from) of a mecanum wheel;
    ``sources``: servos.DriveSources."""
    for declaration in sources.mecanum:
        if wheel.link in declaration.grip_mu:
            mu, mu2 = declaration.grip_mu[wheel.link]
            return mu, max(mu2, FREE_ROLL), "<gazebo> mu, mu2 with fdir1"
    declared = sources.friction.get(wheel.link)
    if declared is not None and declared >= GRIP_MIN:
        return declared, FREE_ROLL, "<gazebo> mu1"
    if declared is not None:
        return TYRE, FREE_ROLL, (f"a tyre's {TYRE:g}: the <mu1> {declared:g} is the "
                                 "rollers' free roll")
    return TYRE, FREE_ROLL, f"a tyre's {TYRE:g} (none declared)"


def add_rollers(mj, spec, shape, drive, sources) -> None:
    """Give each mecanum wheel of ``drive`` its gripping capsule (geom ``mcar_grip_J``)
    and contact pair with the floor; its own geoms, and its roller links', stop touching
    the floor. ``shape``: the model compiled from the description, every joint at 0
    (its kinematics done). The friction each wheel got goes to ``drive.grip_mu``."""
    if drive is None or drive.kind != "mecanum":
        return
    data = mj.MjData(shape)
    mj.mj_kinematics(shape, data)
    for wheel in drive.wheels:
        below = _subtree(shape, wheel.body_id)
        for geom in spec.geoms:
            if geom.name != "mcar_floor" and shape.body(geom.parent.name).id in below:
                geom.contype, geom.conaffinity = 0, 0
        rotation = data.xmat[wheel.body_id].reshape(3, 3)
        grip = np.array([wheel.grip[0], wheel.grip[1], 0.0])
        quat = np.zeros(4)
        mj.mju_quatZ2Vec(quat, rotation.T @ grip)  # the capsule's z along the grip axis
        centre = np.zeros(3)
        if wheel.geom_ids:  # the tyre's centre, in the wheel's frame
            centre = shape.geom_pos[max(wheel.geom_ids,
                                        key=lambda g: shape.geom_rbound[g])].copy()
        body = spec.body(wheel.link)
        body.add_geom(name=f"mcar_grip_{wheel.joint}", type=mj.mjtGeom.mjGEOM_CAPSULE,
                      size=[wheel.radius, HALF_LENGTH * wheel.radius, 0], pos=centre,
                      quat=quat, contype=0, conaffinity=0, mass=0, rgba=[0.1, 0.1, 0.1, 1])
        grip_mu, free_mu, source = tyre_grip(wheel, sources)
        spec.add_pair(name=f"mcar_grip_{wheel.joint}", geomname1=f"mcar_grip_{wheel.joint}",
                      geomname2="mcar_floor", condim=3,
                      friction=[grip_mu, free_mu, 0.005, 1e-4, 1e-4])
        drive.grip_mu[wheel.joint] = (grip_mu, free_mu, source)


def mecanum_summary(sim) -> dict:
    """The mecanum figures of the report (JSON-ready): what declared it, and each wheel's
    grip axis and friction along and across it."""
    drive = sim.drive
    a, b = half_spans(drive)
    return {"declared": drive.declared, "grip_from": drive.grip_from,
            "wheelbase": round(2 * a, 6), "yaw_rate_per_wheel_speed": round(
                drive.radius / (a + b), 6),
            "rollers": {w.joint: {"grip_axis": [round(w.grip[0], 4), round(w.grip[1], 4)],
                                  "mu": drive.grip_mu[w.joint][0],
                                  "mu_across": drive.grip_mu[w.joint][1],
                                  "mu_from": drive.grip_mu[w.joint][2]}
                        for w in drive.driven}}


def mecanum_lines(d: dict) -> list[str]:
    """The report's lines for a mecanum drive (``d``: its drive summary)."""
    rollers = d["rollers"]
    axes = ", ".join(f"{joint} ({r['grip_axis'][0]:+.3f}, {r['grip_axis'][1]:+.3f})"
                     for joint, r in rollers.items())
    lines = [f"  mecanum: {d['declared']}; wheelbase {d['wheelbase']:g} m; rollers grip "
             f"along {axes}, from {d['grip_from']}"]
    alike: dict[str, list[str]] = {}
    for joint, r in rollers.items():
        alike.setdefault(f"mu {r['mu']:g} along ({r['mu_from']}), {r['mu_across']:g} across",
                         []).append(joint)
    lines += [f"  tyre {', '.join(joints)}: {text}" for text, joints in alike.items()]
    return lines


def roller_bodies(model, wheels) -> set[int]:
    """The bodies below mecanum wheels (those with a grip axis: their roller links): part
    of the wheel, not castors, and off the floor (the gripping capsule touches it)."""
    gripping = [w for w in wheels if w.grip is not None]
    return set().union(set(), *(_subtree(model, w.body_id) for w in gripping)) - {
        w.body_id for w in gripping}


def _subtree(model, body: int) -> set[int]:
    found = {body}
    for b in range(body + 1, model.nbody):
        if int(model.body_parentid[b]) in found:
            found.add(b)
    return found


class Rollers:
    """Keeps each gripping capsule level along its grip axis as its wheel turns."""

    def __init__(self, mj, model, drive):
        wheels = [w for w in drive.wheels if w.grip is not None]
        self.geoms = np.array([model.geom(f"mcar_grip_{w.joint}").id for w in wheels], int)
        self.qpos = np.array([model.jnt_qposadr[model.joint(w.joint).id] for w in wheels], int)
        axes = np.array([model.jnt_axis[model.joint(w.joint).id] for w in wheels])
        self.rest = model.geom_quat[self.geoms].copy()  # at every joint's 0
        # rotation(axis, -angle) ⊗ rest = cos(angle/2)·rest - sin(angle/2)·((0, axis) ⊗ rest):
        # linear in cos and sin, so each step costs two products (this runs every step).
        w, v = self.rest[:, 0], self.rest[:, 1:]
        turned = np.empty_like(self.rest)
        turned[:, 0] = -np.einsum("ij,ij->i", axes, v)
        turned[:, 1:] = w[:, None] * axes + np.cross(axes, v)
        self.turned = -turned
        for wheel, geom in zip(wheels, self.geoms, strict=True):
            wheel.geom_ids = [int(geom)]  # what touches the floor now

    def align(self, model, data) -> None:
        """Turn each capsule back by its wheel joint's angle."""
        half = 0.5 * data.qpos[self.qpos]
        model.geom_quat[self.geoms] = (np.cos(half)[:, None] * self.rest
                                       + np.sin(half)[:, None] * self.turned)
