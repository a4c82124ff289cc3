"""Whether a robot is a vehicle, read from its checked tree before any engine is started:
what ``mcar ci`` and ``mcar sim`` of a package decide to simulate.

A vehicle has wheels (continuous joints about a level axis moving collision geometry, two
or more) and another link with collision geometry to stand on (a castor, a body). An
upright continuous joint is a swivel (a castor's, a turntable's, an arm's: Kinova Gen3's
joints 1, 3, 5 and 7 turn without end about upright axes), never a wheel, as sim's drive
finder (:mod:`.drives`) already judges it; and a wheel reaches the floor: a level one
high above the robot's lowest point at rest is a lever (:func:`aloft`: ABB's IRB 2400
links its arm through levers on continuous joints 0.5 m and more up). Anything else is
"not a vehicle", in one of a few kinds (no wheels; wheels and nothing to stand on; one
wheel), each with the detail of this robot; ci prints one line per kind. A vehicle is
simulated even when sim then finds no drive kind it can drive (mecanum, wheels on one
side): that is a failure of ci, not a skip, unless the package opts the robot out
(``mcar.yaml``, :mod:`mobile_car.packages.package_config`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..check.rest_pose import IDENTITY, compose, frame
from ..check.urdf_model import axis_of, parse_number
from .lint import link_mass

# rad: a revolute joint limited to ± this or more turns without end, as urdfdom and KDL
# read it (swerve bases and Neobotix's MP-400 and MP-500 write ±1e16): sim simulates it
# continuous (model.as_urdfdom_reads), so it is a wheel here too
UNLIMITED = 1e6
FIXED_TO_THE_WORLD = "fixed to the world"  # a NotAVehicle kind: nothing to drop
HORIZONTAL = 0.5  # |z| of a wheel's axis in the root frame below which it can roll (30°)
# of the robot's height at rest: a wheel's lowest point lies at most this far above the
# robot's lowest point (aloft)
NEAR_FLOOR = 0.25


@dataclass(frozen=True)
class NotAVehicle:
    kind: str    # "no wheels", "one wheel", "nothing but its wheels to stand on",
    #              FIXED_TO_THE_WORLD
    detail: str  # this robot's joints or links

    def __str__(self) -> str:
        return f"not a vehicle: {self.kind} ({self.detail})"


def not_a_vehicle(robot, rest=None) -> NotAVehicle | None:
    """Why a robot is not a vehicle, or None. A part's test file (the wheel pair on a
    bare base_link) is not one; a car whose castor is set too high still is, so that drop
    fails it. Mass is not asked for here: a car that lost an <inertial> must fail (E305),
    not go unsimulated. ``rest``: the check's rest pose (``CheckResult.rest``), which
    tells the levers high above the floor (:func:`aloft`) from wheels; without it every
    level endless joint's child counts."""
    fixed = anchored(robot)
    if fixed is not None:
        return NotAVehicle(FIXED_TO_THE_WORLD, fixed)
    colliding = {link.name for link in robot.links if link.collisions}
    level = level_turning((j.type, j.parent, j.child, j.parts.get("origin"), axis_of(j))
                          for j in robot.joints)
    wheels = {j.child for j in robot.joints if turns_without_end(j) and j.child in colliding
              and j.child in level}
    high = set() if rest is None or not wheels else _aloft_at_rest(robot, rest, wheels)
    wheels -= high
    kind = lacks(colliding, wheels)
    if kind == "no wheels":
        return NotAVehicle(kind, _no_wheels(robot, colliding, level, high))
    if kind == "one wheel":
        levers = _levers(robot, high)
        return NotAVehicle(kind, f"{', '.join(sorted(wheels))} on a continuous joint"
                                 + (f"; {levers}" if levers else ""))
    if kind is not None:
        return NotAVehicle(kind, f"only {', '.join(sorted(wheels))} have collision geometry, "
                                 "no castor or body")
    return None


def turns_without_end(joint) -> bool:
    """A continuous joint, or a revolute one limited to ±UNLIMITED or more."""
    return endless(joint.type, joint.parts.get("limit"))


def endless(kind: str | None, limit) -> bool:
    """Whether a joint of type ``kind`` with this ``<limit>`` element (or None) turns
    without end: :func:`turns_without_end` of a joint as lxml reads it (an export's)."""
    if kind == "continuous":
        return True
    if kind != "revolute" or limit is None:
        return False
    lower = parse_number(limit.get("lower") or "0")
    upper = parse_number(limit.get("upper") or "0")
    return None not in (lower, upper) and lower <= -UNLIMITED and upper >= UNLIMITED


def anchored(robot) -> str | None:
    """How the robot is fixed to the world, or None: its root is a link named ``world``,
    which Gazebo welds to its world (and MoveIt and robot_state_publisher take for the
    fixed frame): franka's panda with ``gazebo:=true``, an arm on its table. Such a robot
    is not dropped: it stands where it is bolted."""
    children = {j.child for j in robot.joints}
    if "world" in children:
        return None
    held = [j for j in robot.joints if j.parent == "world"]
    if not held:
        return None
    return ", ".join(f"joint {j.name} ({j.type}) holds {j.child} to link 'world'"
                     for j in held[:3]) + (", ..." if len(held) > 3 else "")


def lacks(colliding: set[str], wheels: set[str]) -> str | None:
    """What keeps a robot from being a vehicle (a NotAVehicle kind), or None: ``colliding``,
    its links with collision geometry; ``wheels``, those of them a continuous joint turns.
    The test of :func:`not_a_vehicle`, and of an export's manifest (no check model there)."""
    if not wheels:
        return "no wheels"
    if len(wheels) < 2:
        return "one wheel"
    if not colliding - wheels:
        return "nothing but its wheels to stand on"
    return None


def level_turning(joints) -> set[str]:
    """The children of the joints whose axis lies within HORIZONTAL of level in the root
    frame, every joint at 0: ``joints`` are (type, parent, child, its ``<origin>`` element
    or None, its axis or None: fixed and floating joints have none). An origin that cannot
    be read counts as none."""
    joints = list(joints)
    above = {child: (parent, origin) for _kind, parent, child, origin, _axis in joints}
    rotations: dict[str, tuple] = {}

    def rotation(link: str) -> tuple:
        chain = []
        while link in above and link not in rotations and len(chain) <= len(above):
            chain.append(link)
            link = above[link][0]
        pose = rotations.get(link, IDENTITY)
        for name in reversed(chain):
            pose = compose(pose, frame(above[name][1]) or IDENTITY)
            rotations[name] = pose
        return pose[0]

    level = set()
    for _kind, _parent, child, _origin, axis in joints:
        if not axis:
            continue
        norm = math.sqrt(sum(a * a for a in axis))
        if norm == 0 or not math.isfinite(norm):
            continue
        r = rotation(child)  # the child's frame is the joint's: the axis is given in it
        up = (r[6] * axis[0] + r[7] * axis[1] + r[8] * axis[2]) / norm
        if abs(up) < HORIZONTAL:
            level.add(child)
    return level


def aloft(lowest: dict, bottom: float, height: float) -> set[str]:
    """The links of ``lowest`` (link -> the z of its lowest collision point, every joint
    at 0) that stay high above the floor: their lowest point more than NEAR_FLOOR of the
    robot's ``height`` above its ``bottom``, the lowest point of its collision geometry.
    A wheel touches the floor the robot stands on (the castor or body lower than it by a
    few millimetres at most); the parallel-linkage levers of ABB's IRB 2400 turn without
    end about level axes 0.6 m and more up the arm."""
    if not height > 0:
        return set()
    return {link for link, z in lowest.items() if z - bottom > NEAR_FLOOR * height}


def aloft_bodies(model, data, lowest: dict) -> set[str]:
    """The bodies of a compiled MuJoCo model whose collision geometry stays high above
    the floor as :func:`aloft` judges it (kinematics done on ``data``; ``lowest``: geom ->
    the z of its lowest point, :func:`.model.lowest_points`), the robot's height over
    every geom's box: what sim's drive finder and an export, which have no check's rest
    pose, ask."""
    import numpy as np

    lowest_of, tops = {}, []
    for g, z in lowest.items():
        rot = data.geom_xmat[g].reshape(3, 3)
        centre, half = model.geom_aabb[g][:3], model.geom_aabb[g][3:]
        tops.append(float(data.geom_xpos[g][2] + rot[2] @ centre + np.abs(rot[2]) @ half))
        if model.geom_contype[g] or model.geom_conaffinity[g]:
            name = model.body(int(model.geom_bodyid[g])).name
            lowest_of[name] = min(z, lowest_of.get(name, z))
    if not lowest_of:
        return set()
    bottom = min(lowest_of.values())
    return aloft(lowest_of, bottom, max(tops) - bottom)


def _aloft_at_rest(robot, rest, wheels: set[str]) -> set[str]:
    extents = rest.extents()
    lowest = rest.lowest_collision(link.name for link in robot.links)
    if extents is None or not lowest:
        return set()
    return aloft({link: z for link, z in lowest.items() if link in wheels},
                 min(lowest.values()), extents[2])


def _levers(robot, high: set[str]) -> str | None:
    """What the joints turning the links of ``high`` (:func:`aloft`) are, or None."""
    levers = [j.name for j in robot.joints if j.child in high]
    if not levers:
        return None
    if len(levers) == 1:
        return (f"continuous joint {levers[0]} turns about a level axis high above the "
                "floor (a lever)")
    return (f"continuous joints {', '.join(levers)} turn about level axes high above the "
            "floor (levers)")


def _no_wheels(robot, colliding: set[str], level: set[str], high: set[str]) -> str:
    endless = [j for j in robot.joints if turns_without_end(j)]
    upright = [j.name for j in endless if j.child in colliding and j.child not in level]
    levers = _levers(robot, high)
    if levers:
        return levers
    if upright:
        if len(upright) == 1:
            return f"continuous joint {upright[0]} turns about an upright axis (a swivel)"
        return f"continuous joints {', '.join(upright)} turn about upright axes (swivels)"
    continuous = [j for j in robot.joints if j.type == "continuous"]
    if continuous:
        names = ", ".join(j.name for j in continuous)
        return f"continuous joints {names} move no collision geometry"
    joints = ", ".join(f"{j.name} ({j.type})" for j in robot.joints[:6])
    more = ", ..." if len(robot.joints) > 6 else ""
    return f"no continuous joint{': ' + joints + more if joints else ''}"


def unsimulable(robot) -> list[str]:
    """Why the robot cannot even be dropped (the tutorial's visual-only car), or []."""
    problems = []
    if not any(link.collisions for link in robot.links):
        problems.append("no link has <collision> geometry: nothing can rest on the floor, "
                        "the robot would fall through it")
    if sum(link_mass(link) for link in robot.links) <= 0:
        problems.append("no link has mass (<inertial>): there is nothing to simulate")
    return problems


def grouped(skipped) -> list[tuple[str, list]]:
    """(reason kind, the items with it) for ``skipped``: (item, NotAVehicle or a package's
    reason text) pairs, in first-seen order: one line per kind of skip."""
    groups: dict[str, list] = {}
    for item, why in skipped:
        key = f"not a vehicle: {why.kind}" if isinstance(why, NotAVehicle) else str(why)
        groups.setdefault(key, []).append(item)
    return list(groups.items())
