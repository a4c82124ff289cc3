"""The robot ``mcar specs`` describes: sim's SimModel, made by sim's own preamble
(:func:`mobile_car.sim.prepare.prepare`: refused inertias, ``--fix-inertia``, what the
package declares, mecanum YAML, mcar.yaml ``sim.drive``), and the robot at rest in it; a
robot sim cannot model (no collision geometry, no mass, inertias MuJoCo refuses) has
none, and the notes say why. Its mass and centre of mass are then read from the URDF
(:func:`urdf_mass`), so the figures that need no engine are still given."""

from __future__ import annotations

import math

from ..check.rest_pose import IDENTITY, apply, compose, frame
from ..check.urdf_model import parse_number


def specs_model(checked, *, left=None, right=None, kind: str | None = None,
                effort: float | None = None, speed: float | None = None,
                fix_inertia: bool = False, setting=None) -> tuple[object, list[str]]:
    """(the SimModel of a robot that passed ``mcar check``, or None; notes: what sim
    changed or left out, or why there is no model). Arguments as
    :func:`mobile_car.sim.report.simulate`'s."""
    from ..sim.prepare import prepare
    from ..sim.vehicle import unsimulable

    problems = unsimulable(checked.robot)
    if problems:
        return None, [f"not modelled in MuJoCo: {problems[0]}"]
    prepared = prepare(checked, left, right, kind, effort, speed, fix_inertia, setting)
    if prepared.sim is None:
        lines = [f"{d.rule} at {d.location()}: {d.message}" for d in prepared.diagnostics]
        return None, [*lines, f"not modelled in MuJoCo: {prepared.error}"]
    return prepared.sim, prepared.notes


def at_rest(sim):
    """MjData of ``sim`` with the robot in the pose its geometry rests in (root above the
    floor frame's origin, springs at rest under its weight), kinematics done: what every
    figure "at rest" is measured on."""
    from ..sim.run import Run

    return Run(sim).data


def urdf_mass(checked) -> tuple[float, list[float] | None]:
    """(the robot's mass in kg, its centre of mass [x, y, z] in the root frame with every
    joint at 0, None when it has no mass) from the URDF's ``<inertial>`` elements alone."""
    tree = checked.tree
    links = {link.name: link for link in checked.robot.links}
    poses = {tree.root: IDENTITY}
    stack = [tree.root]
    while stack:
        parent = stack.pop()
        for joint in tree.children.get(parent, ()):
            if joint.child in poses:
                continue
            origin = frame(joint.parts.get("origin"))
            poses[joint.child] = poses[parent] if origin is None else compose(
                poses[parent], origin)
            stack.append(joint.child)
    total, moment = 0.0, [0.0, 0.0, 0.0]
    for name, pose in poses.items():
        inertial = links[name].inertial if name in links else None
        if not inertial or inertial.get("mass") is None:
            continue
        mass = parse_number(inertial["mass"].get("value")) or 0.0
        if not math.isfinite(mass) or mass <= 0:
            continue
        origin = frame(inertial.get("origin"))
        centre = apply(pose, origin[1] if origin is not None else (0.0, 0.0, 0.0))
        total += mass
        moment = [m + mass * c for m, c in zip(moment, centre, strict=True)]
    if total <= 0:
        return 0.0, None
    return total, [m / total for m in moment]
