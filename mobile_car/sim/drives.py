"""Which joints drive and steer a robot, and so its drive kind: first what the package
declares (:mod:`.declared`: its Gazebo drive plugin, the controllers its control package
configures), else what the tree MuJoCo compiled shows (every joint at 0, the root at the
origin: positions in metres in the root frame, x forward, y left, z up).

In the tree, a *wheel* is a ``continuous`` joint about a roughly horizontal axis (within
HORIZONTAL of level) whose child's collision geometry reaches the floor at rest (within
FLOOR_TOLERANCE of the robot's lowest point): a head's swivel (upright), a castor's
swivel (upright), a dummy wheel in the air (Hunter 2's, 5 mm up) or a bicycle model's
virtual wheel (steer_bot's, 75 mm up) is not one. A wheel is on the left if its centre
has y > 0, on the right if y < 0. Above a wheel (between it and the root) may sit an
upright hinge: a ``revolute`` one is a steering joint, and so is a ``continuous`` one that
something turns (a ``<transmission>`` or a ``<ros2_control>`` command interface) about an
axis through its wheel (the gz_ros2_control Ackermann demo's steering joints, the MIT
racecar's right hinge); any other ``continuous`` one is a castor's swivel, free or not
(AgileX Tracer writes a transmission for each castor's), its wheel trailing behind its
axis (that wheel is a castor, not a drive wheel). A wheel below another wheel is a
roller of an omni or mecanum wheel; a small one on a level wheel's rim makes that wheel a
mecanum hub (:mod:`.mecanum`). The kinds:

* ``differential``: one wheel each side, none steered, any castors (TurtleBot3, Kobuki);
* ``skid-steer``: two or three wheels each side (4 or 6), none steered, all driven
  (Husky, Jackal);
* ``ackermann``: two steered wheels in front, one each side, each on its own steering
  joint, and unsteered wheels behind them; the rear wheels are driven, the front ones
  too where a ``<transmission>`` or ``<ros2_control>`` block gives their joint an actuator;
* ``mecanum``: two wheels a side, none steered, that the package declares mecanum or that
  carry rollers on their rims (:mod:`.mecanum`), each gripping at 45°;
* ``bicycle``: a single track: one steered wheel on the centre line, on its own steering
  joint, and one or more unsteered wheels on the centre line behind it, which are driven
  (the steered one too where it has an actuator, as for ``ackermann``);
* anything else (rollers that are not on four hubs, wheels on one side, a tricycle's
  steered wheel on the centre line before a pair, steering that is neither one Ackermann
  pair nor one bicycle wheel, legs): no drive, with a sentence saying what was found.

A declaration names joints; each maps onto the tree's wheels: a wheel is itself, a joint
that is no wheel of the tree (a bicycle model's ``rear_wheel_joint`` on the centre line,
``front_steer_joint``) stands for the real wheels (steering joints) at its x, both sides.
An Ackermann (or bicycle) controller whose steering joint IS a steering joint of the tree,
above a wheel on the centre line, declares a bicycle (steer_bot's bicycle_bot).
A declaration naming a ``fixed`` or missing joint is skipped here (lint reports it, E306).

``--drive KIND`` overrides the declared or found kind with one the tree's wheels allow
(an Ackermann car driven as skid-steer, its steering held straight); ``--left/--right``
name the driven wheels (a joint or a comma-separated group per side), the others roll
free. Each driven wheel carries where it came from (``Drive.sources``), for the report.
"""

from __future__ import annotations

import numpy as np

from ..check.urdf_model import parse_number
from ..errors import UsageError
from ..packages.package_config import DRIVE_KINDS as KINDS
from .drive_parts import Drive, Steering, Tree, Wheel
from .mecanum import (
    bare_hubs,
    declared_drive,
    declared_mecanum,
    grip_of_rollers,
    has_rollers,
    is_roller,
    mecanum_drive,
)
from .vehicle import HORIZONTAL, aloft_bodies  # what a wheel is: the test of a vehicle too

UPRIGHT = 0.9       # |z| of an axis in the root frame above which a hinge steers (or swivels)
SIDE_EPSILON = 1e-6  # m: a wheel closer than this to the centre line is on neither side
ACKERMANN_X_TOLERANCE = 0.05  # of the wheelbase: the steering pivots stand side by side
FLOOR_TOLERANCE = 0.003  # m: a wheel's tyre this close to the robot's lowest point touches
# of a wheel's radius: a continuous hinge whose axis passes further from the wheel's centre
# is a castor's swivel, the wheel trailing behind it (Tracer's: 0.58), not a steering joint
STEER_TRAIL = 0.1
# A declared virtual joint stands for the axle nearest its x: the wheels within this share
# of a wheel's radius of the nearest (steer_bot's share its axle, Hunter 2's is 0.14 m off).
VIRTUAL_X_TOLERANCE = 0.5
CENTRE_SHARE = 0.1  # of the nearest side wheel's |y|: a declared joint this near is virtual
GEOMETRY = "geometry: a wheel that touches the floor"


def find_tree(mj, model, data, joints: dict, lowest: dict, turned=frozenset()) -> Tree:
    """The wheels, steering joints, rollers and castor wheels of a compiled model
    (``joints``: URDF joint name -> element, the robot's own joints; ``lowest``: geom ->
    the z of its lowest point, :func:`.model.lowest_points`; ``turned``: the joints an
    actuator turns (:func:`actuated_joints`): a continuous upright hinge among them whose
    axis passes through its wheel steers, any other swivels)."""
    names = {model.joint(j).name for j in range(model.njnt)}
    rolling = [_wheel(mj, model, data, joints, name) for name, element in joints.items()
               if element.get("type") == "continuous" and name in names]
    bare = [w for w in rolling if not w.geom_ids]
    rolling = [w for w in rolling if w.geom_ids]
    hubs = bare_hubs(model, data, bare, rolling)  # hubs that roll on rollers only
    # The floor is where the lowest level wheel touches: a body lower than its wheels rests
    # on its belly, which drop fails naming the part; it does not make its wheels no wheels.
    # (Collision geometry only: an export's visuals touch nothing.)
    level = [g for w in rolling if abs(data.xaxis[w.joint_id][2]) < HORIZONTAL
             for g in w.geom_ids]
    floor = min((lowest[g] for g in level), default=min(
        (z for g, z in lowest.items() if model.geom_contype[g] or model.geom_conaffinity[g]),
        default=0.0))
    not_wheels = {}
    high = aloft_bodies(model, data, lowest) if rolling else set()
    for wheel in rolling:
        why = _not_a_wheel(model, data, wheel, lowest, floor)
        if why is None and model.body(wheel.body_id).name in high:
            why = "high above the robot's lowest point at rest (a lever, not a wheel)"
        if why is not None:
            not_wheels[wheel.joint] = why
    wheel_bodies = {w.body_id: w for w in rolling + hubs if w.joint not in not_wheels}
    # A roller sits on a wheel's rim: any rolling joint below a floor wheel, touching or not.
    for wheel in rolling:
        if wheel.joint in not_wheels and _below(model, wheel.body_id, wheel_bodies):
            del not_wheels[wheel.joint]
    # Rollers on a level hub drawn without a tyre that is no mecanum hub (omni rollers
    # across the axle) are rollers too, not four small wheels.
    bare_level = {w.body_id for w in bare if w not in hubs
                  and abs(data.xaxis[w.joint_id][2]) < HORIZONTAL}
    on_bare = [w.joint for w in rolling if _below(model, w.body_id, bare_level)]
    candidates = [w for w in rolling if w.joint not in not_wheels
                  and w.joint not in on_bare] + hubs
    wheel_bodies = {w.body_id: w for w in candidates}
    wheels, rollers, castors, above, on_rims = [], [], [], {}, {}
    for wheel in candidates:
        hinge, below_wheel = None, False
        body = int(model.body_parentid[wheel.body_id])
        while body > 0:
            if body in wheel_bodies:
                below_wheel = True
                if is_roller(mj, model, data, wheel_bodies[body], wheel):
                    on_rims.setdefault(wheel_bodies[body].joint, []).append(wheel)
                break
            hinge = hinge or _upright_hinge(mj, model, data, body)
            body = int(model.body_parentid[body])
        if below_wheel:
            rollers.append(wheel.joint)
        elif (hinge is not None and joints[hinge].get("type") == "continuous"
              and not _steers_about_itself(model, data, hinge, wheel, turned)):
            castors.append(wheel.link)
        else:
            wheel.steering = hinge
            if hinge is not None:
                above.setdefault(hinge, []).append(wheel)
            wheels.append(wheel)
    for joint in on_bare:
        not_wheels.pop(joint, None)
    rollers += on_bare
    steering, odd = [], []
    for name, under in above.items():
        if len(under) != 1:
            odd.append(name)
            for wheel in under:
                wheel.steering = None
            continue
        steering.append(_steering(model, data, joints[name], name, under[0]))
    grips = {hub: grip_of_rollers(model, data, on_rim) for hub, on_rim in on_rims.items()}
    return Tree(wheels, steering, rollers, castors, odd, joints,
                lambda name: _wheel(mj, model, data, joints, name), not_wheels=not_wheels,
                roller_grip={hub: grip for hub, grip in grips.items() if grip is not None})


def _steers_about_itself(model, data, hinge: str, wheel: Wheel, turned) -> bool:
    """Whether a continuous upright ``hinge`` above ``wheel`` steers it: an actuator turns
    it, about an axis through the wheel's centre (a castor's wheel trails behind its
    swivel's axis)."""
    if hinge not in turned:
        return False
    joint = model.joint(hinge).id
    offset = data.xpos[wheel.body_id] - data.xanchor[joint]
    axis = data.xaxis[joint]
    trail = np.linalg.norm(offset - np.dot(offset, axis) * axis)
    return trail <= STEER_TRAIL * wheel.radius


def _not_a_wheel(model, data, wheel: Wheel, lowest: dict, floor: float) -> str | None:
    """Why a continuous joint moving collision geometry is no wheel, or None."""
    axis = data.xaxis[wheel.joint_id]
    if abs(axis[2]) >= HORIZONTAL:
        return "its axis stands upright (a swivel, not a wheel)"
    gap = min(lowest[g] for g in wheel.geom_ids) - floor
    if gap > FLOOR_TOLERANCE:
        return f"{1000 * gap:.1f} mm above the floor at rest (not a wheel)"
    return None


def _below(model, body: int, bodies) -> bool:
    body = int(model.body_parentid[body])
    while body > 0:
        if body in bodies:
            return True
        body = int(model.body_parentid[body])
    return False


def choose_drive(tree: Tree, actuated: set[str], left=None, right=None,
                 kind: str | None = None, declared=(),
                 mecanum=()) -> tuple[Drive | None, str | None]:
    """(the drive, None), or (None, why the robot is no vehicle sim can drive);
    ``declared``: the package's declarations (:mod:`.declared`), the first that maps
    onto the tree wins; ``mecanum``: its mecanum declarations (:mod:`.mecanum`);
    UsageError where --left/--right/--drive ask for what the tree does not allow."""
    if kind is not None and kind not in KINDS:
        raise UsageError(f"--drive {kind}: the drive kinds are {', '.join(KINDS)}")
    if left or right:
        return _named(tree, _names(left), _names(right), kind), None
    if kind is None:
        # The mecanum reader's declarations first: it checks a controller's wheel radius
        # against the wheels' (ROSbot XL ships a diff-drive and a mecanum controller for the
        # same four joints); the other readers' mecanum declarations are plugins.
        drive = mecanum_drive(tree, list(mecanum)) if declared_mecanum(tree, mecanum) else None
        if drive is not None:
            drive.chosen = "declared"
            drive.sources = _each(drive.driven, drive.declared)
            return drive, None
        for declaration in declared:
            found = _from_declaration(tree, declaration)
            if found is not None:
                return found
    lefts = [w for w in tree.wheels if w.y > SIDE_EPSILON]
    rights = [w for w in tree.wheels if w.y < -SIDE_EPSILON]
    why = _why_not(tree)
    if why is not None and (kind is None or not (lefts and rights)):
        if kind is not None:
            raise UsageError(f"--drive {kind}: {why}")
        return None, why
    found = None if why is not None else _kind_of(tree, lefts, rights, mecanum)
    if found is None and kind is None:
        return None, _no_kind(tree, lefts, rights)
    kind = kind or found
    chosen = "found from the tree" if kind == found else "--drive"
    source = GEOMETRY if chosen == "found from the tree" else "--drive " + kind
    if kind == "ackermann":
        if found != "ackermann":
            raise UsageError(f"--drive ackermann: {_no_ackermann(tree, tree.steering)}")
        driven = [w for w in tree.wheels if w.steering is None or w.joint in actuated]
        free = [w for w in tree.wheels if w not in driven]
        return Drive("ackermann", _side(driven, 1), _side(driven, -1), free,
                     _sorted_steering(tree.steering), chosen=chosen,
                     sources=_each(driven, source)), None
    if kind == "bicycle":
        if found != "bicycle":
            raise UsageError(f"--drive bicycle: {_no_bicycle(tree)}")
        driven = [w for w in tree.wheels if w.steering is None or w.joint in actuated]
        return _bicycle(tree, tree.steering, driven, chosen, _each(driven, source)), None
    if kind == "mecanum":
        drive = mecanum_drive(tree, list(mecanum))
        if drive is None:
            raise UsageError(f"--drive mecanum: {len(lefts)} wheel(s) on the left, "
                             f"{len(rights)} on the right; mecanum drives two a side")
        drive.chosen, drive.sources = chosen, _each(drive.driven, source)
        return drive, None
    if kind == "differential" and (len(lefts) != 1 or len(rights) != 1):
        raise UsageError(f"--drive differential: {len(lefts)} wheels on the left, "
                         f"{len(rights)} on the right; name the two driven ones with "
                         "--left JOINT --right JOINT")
    if kind == "skid-steer" and (len(lefts) < 2 or len(rights) < 2):
        raise UsageError(f"--drive skid-steer: {len(lefts)} wheel(s) on the left, "
                         f"{len(rights)} on the right; skid-steer drives two or more a side")
    return Drive(kind, lefts, rights, chosen=chosen, sources=_each(lefts + rights, source)), None


def _each(wheels, source: str) -> dict[str, str]:
    return {w.joint: source for w in wheels}


def _from_declaration(tree: Tree, declaration) -> tuple[Drive | None, str | None] | None:
    """The drive a declaration gives, (None, why) when it declares a kind sim does not
    drive, or None when it does not fit this robot (a joint fixed, missing or no wheel):
    the next declaration, else the geometry, decides."""
    if any(tree.joints.get(n) is None or tree.joints[n].get("type") == "fixed"
           for n in declaration.joints):
        return None
    if declaration.kind == "mecanum":
        if declaration.element is None:  # a controller YAML: the mecanum reader's to judge
            return None
        drive = declared_drive(tree, "mecanum",
                               declaration.left + declaration.right + declaration.driven,
                               declaration.source)
        if drive is None:
            return None
        drive.chosen = "declared"
        drive.sources = _each(drive.driven, declaration.source)
        return drive, None
    if declaration.kind not in KINDS:
        return None, (f"{declaration.kind} wheels ({declaration.source}): not a drive kind "
                      f"mcar sim drives ({', '.join(KINDS)})")
    sources: dict[str, str] = {}
    wheels = {w.joint: w for w in tree.wheels}

    def mapped(names) -> list[Wheel] | None:
        found = []
        for name in names:
            real = [wheels[name]] if name in wheels else _stands_for(tree, name)
            if not real:
                return None
            for wheel in real:
                sources[wheel.joint] = declaration.source + (
                    "" if wheel.joint == name else f" ({name} stands for it)")
            found += [w for w in real if w not in found]
        return found
    if declaration.kind == "ackermann":
        driven = mapped(declaration.driven)
        steering = _steering_for(tree, declaration.steering)
        if not driven or steering is None:
            return None
        if _single_track(steering, declaration.steering):
            why = _no_bicycle(tree)
            if why is not None:
                return None, f"{why} ({declaration.source})"
            return _bicycle(tree, steering, driven, "declared", sources), None
        why = _no_ackermann(tree, steering)
        if why is not None:
            return None, f"{why} ({declaration.source})"
        free = [w for w in tree.wheels if w not in driven]
        return Drive("ackermann", _side(driven, 1), _side(driven, -1), free,
                     _sorted_steering(steering), chosen="declared", sources=sources), None
    driven = mapped(declaration.left + declaration.right)
    if not driven:
        return None
    lefts, rights = _side(driven, 1), _side(driven, -1)
    if not lefts or len(lefts) != len(rights) or 2 * len(lefts) != len(driven):
        return None  # (a wheel on the centre line, or named on both sides: E303 says so)
    kind = "differential" if len(lefts) == len(rights) == 1 else "skid-steer"
    free = [w for w in tree.wheels if w not in driven]
    return Drive(kind, lefts, rights, free, chosen="declared", sources=sources), None


def _stands_for(tree: Tree, name: str) -> list[Wheel]:
    """The wheels a declared joint that is no wheel of the tree drives: a bicycle model's
    virtual wheel (on the centre line) stands for the tree's wheels at its x (the axle's
    two); a wheel off the centre line is itself, touching the floor or not (drop then
    says it does not); a joint moving no collision geometry drives nothing."""
    element = tree.joints.get(name)
    if element is None or element.get("type") not in ("continuous", "revolute"):
        return []
    virtual = tree.make(name)
    sides = [abs(w.y) for w in tree.wheels if abs(w.y) > SIDE_EPSILON]
    if not sides or abs(virtual.y) > CENTRE_SHARE * min(sides):
        return [virtual] if virtual.geom_ids else []
    return _nearest_axle(tree.wheels, virtual.x, lambda w: w.x,
                         max(w.radius for w in tree.wheels))


def _nearest_axle(items, x: float, x_of, radius: float) -> list:
    """The items nearest ``x`` along the robot, with those within VIRTUAL_X_TOLERANCE of a
    wheel's radius of them: one axle (a virtual joint may sit off it: Hunter 2's)."""
    if not items:
        return []
    nearest = min(abs(x_of(i) - x) for i in items)
    return [i for i in items if abs(x_of(i) - x) <= nearest + VIRTUAL_X_TOLERANCE * radius]


def _single_track(steering: list[Steering], names: list[str]) -> bool:
    """Whether a declaration's steering is a bicycle's: one real steering joint (named,
    not stood for) above a wheel on the centre line."""
    return (len(steering) == 1 and steering[0].joint in names
            and abs(steering[0].wheel.y) <= SIDE_EPSILON)


def _bicycle(tree: Tree, steering: list[Steering], driven: list[Wheel], chosen: str,
             sources: dict) -> Drive:
    free = [w for w in tree.wheels if w not in driven]
    return Drive("bicycle", [], [], free, list(steering), chosen=chosen, sources=sources,
                 centre=driven)


def _steering_for(tree: Tree, names: list[str]) -> list[Steering] | None:
    """The tree's steering joints the declared ones name or stand for (a bicycle model's
    ``front_steer_joint``: the real steering joints at its x), or None."""
    by_name = {s.joint: s for s in tree.steering}
    found = []
    for name in names:
        if name in by_name:
            real = [by_name[name]]
        else:
            element = tree.joints.get(name)
            if element is None:
                return None
            radius = max((w.radius for w in tree.wheels), default=0.0)
            real = _nearest_axle(tree.steering, tree.make(name).x, lambda s: s.x, radius)
        if not real:
            return None
        found += [s for s in real if s not in found]
    return found


def actuated_joints(root) -> set[str]:
    """Joints a ``<transmission>`` or a ``<ros2_control>`` command interface drives."""
    found = set()
    for block in root:
        if block.tag == "transmission":
            found |= {j.get("name") for j in block if j.tag == "joint" and j.get("name")}
        elif block.tag == "ros2_control":
            found |= {j.get("name") for j in block if j.tag == "joint" and j.get("name")
                      and any(c.tag == "command_interface" for c in j)}
    return found


def _names(value) -> list[str]:
    if not value:
        return []
    words = value.split(",") if isinstance(value, str) else list(value)
    return [w.strip() for w in words if w.strip()]


def _named(tree: Tree, lefts: list[str], rights: list[str], kind: str | None) -> Drive:
    """The drive the user named with --left/--right (and --drive)."""
    if not (lefts and rights):
        raise UsageError("--left and --right go together: name the drive joints of each side")
    if len(set(lefts + rights)) != len(lefts + rights):
        raise UsageError("--left/--right: a joint is named twice")
    by_name = {w.joint: w for w in tree.wheels}
    for name in lefts + rights:
        if name not in by_name:
            by_name[name] = _named_wheel(tree, name)
    left, right = [by_name[n] for n in lefts], [by_name[n] for n in rights]
    free = [w for w in tree.wheels if w.joint not in lefts + rights]
    ackermann = _kind_of(tree, _side(tree.wheels, 1), _side(tree.wheels, -1)) == "ackermann"
    if kind is None:
        kind = ("ackermann" if ackermann else "differential" if len(left) == len(right) == 1
                else "skid-steer")
    if kind == "ackermann" and not ackermann:
        raise UsageError("--drive ackermann: " + _no_ackermann(tree, tree.steering))
    if kind == "differential" and (len(left), len(right)) != (1, 1):
        raise UsageError("--drive differential drives one wheel a side: name one joint "
                         "each with --left and --right")
    if kind == "skid-steer" and (len(left) < 2 or len(right) < 2):
        raise UsageError("--drive skid-steer drives two or more wheels a side: name them "
                         "with --left A,B --right C,D")
    if kind == "mecanum":
        drive = mecanum_drive(tree, [], lefts + rights)
        if drive is None or {w.joint for w in drive.left} != set(lefts):
            raise UsageError("--drive mecanum drives two wheels a side, one in front of the "
                             "other: name them with --left A,B --right C,D")
        drive.chosen = "--left/--right"
        return drive
    steering = _sorted_steering(tree.steering) if kind == "ackermann" else []
    return Drive(kind, left, right, free, steering, chosen="--left/--right",
                 sources=_each(left + right, "--left/--right"))


def _named_wheel(tree: Tree, name: str) -> Wheel:
    """A joint named with --left/--right that was not found as a wheel: a revolute one
    may drive, as before; anything else is refused, saying why."""
    element = tree.joints.get(name)
    if element is None:
        raise UsageError(f"--left/--right {name}: the robot has no joint of that name")
    steering = next((s for s in tree.steering if s.joint == name), None)
    if steering is not None:
        raise UsageError(f"--left/--right {name}: a steering joint (it turns "
                         f"{steering.wheel.joint}) cannot drive a wheel")
    if name in tree.rollers:
        raise UsageError(f"--left/--right {name}: a roller of another wheel cannot drive "
                         "the robot")
    if element.get("type") not in ("continuous", "revolute"):
        raise UsageError(f"--left/--right {name}: a {element.get('type')} joint cannot drive "
                         "a wheel")
    wheel = tree.make(name)
    if not wheel.geom_ids:
        raise UsageError(f"--left/--right {name}: link {wheel.link} has no <collision> "
                         "geometry to roll on")
    return wheel


def _why_not(tree: Tree) -> str | None:
    """Why the tree has no drive of any kind, or None."""
    if tree.rollers and not has_rollers(tree):
        return (f"omni or mecanum wheels (rollers {', '.join(tree.rollers[:4])}"
                f"{', ...' if len(tree.rollers) > 4 else ''} turn about the wheels): not a drive "
                f"kind mcar sim drives ({', '.join(KINDS)})")
    if not tree.wheels:
        if tree.castor_wheels:
            return ("no drive wheels: only castor wheels on swivels "
                    f"({', '.join(tree.castor_wheels)})")
        if tree.not_wheels:
            return ("no drive wheels: no continuous joint about a level axis touches the floor ("
                    + "; ".join(f"{j}: {why}" for j, why in tree.not_wheels.items()) + ")")
        return "no drive wheels: no continuous joint moves a link with collision geometry"
    centre = [w.joint for w in tree.wheels if abs(w.y) <= SIDE_EPSILON]
    if centre and _no_bicycle(tree) is not None:
        return (f"a wheel on the centre line ({', '.join(centre)}): not a drive kind mcar sim "
                f"drives ({', '.join(KINDS)})")
    return None


def _kind_of(tree: Tree, lefts, rights, declared=()) -> str | None:
    steered = [w for w in tree.wheels if w.steering is not None]
    if steered or tree.odd_steering:
        if _no_ackermann(tree, tree.steering) is None:
            return "ackermann"
        return "bicycle" if _no_bicycle(tree) is None else None
    if len(lefts) == len(rights) == 2 and (has_rollers(tree)
                                           or declared_mecanum(tree, declared)):
        return "mecanum"
    if len(lefts) == len(rights) == 1:
        return "differential"
    if len(lefts) == len(rights) and len(lefts) in (2, 3):
        return "skid-steer"
    return None


def _no_ackermann(tree: Tree, steering: list[Steering]) -> str | None:
    """Why ``steering`` (the tree's, or the joints a declaration names) is not one
    Ackermann pair in front, or None when it is."""
    if tree.odd_steering:
        return (f"steering joint {', '.join(tree.odd_steering)} turns several wheels at once, "
                "not one Ackermann pair")
    if not steering:
        return ("no steering joints: no revolute joint about an upright axis above a wheel")
    sides = sorted(np.sign(s.y) for s in steering)
    rear = [w for w in tree.wheels if w.steering is None]
    if len(steering) != 2 or sides != [-1, 1]:
        return (f"{len(steering)} steering joint(s) ({', '.join(s.joint for s in steering)}), "
                "not one each side")
    if not any(w.y > 0 for w in rear) or not any(w.y < 0 for w in rear):
        return "steered wheels but no unsteered wheel each side to drive and turn about"
    base = np.mean([s.x for s in steering]) - np.mean([w.x for w in rear])
    if base <= 0:
        return "the steered wheels are not in front of the others"
    if abs(steering[0].x - steering[1].x) > ACKERMANN_X_TOLERANCE * base:
        return "the two steering pivots are not side by side"
    return None


def _no_bicycle(tree: Tree) -> str | None:
    """Why the wheels are not a bicycle's (one steered wheel before unsteered ones, all on
    the centre line), or None when they are."""
    if tree.odd_steering:
        return (f"steering joint {', '.join(tree.odd_steering)} turns several wheels at once, "
                "not one bicycle wheel")
    if len(tree.steering) != 1:
        return (f"{len(tree.steering)} steering joint(s) "
                f"({', '.join(s.joint for s in tree.steering) or 'none'}), not one bicycle "
                "wheel")
    steering = tree.steering[0]
    rear = [w for w in tree.wheels if w.steering is None]
    off = [w.joint for w in tree.wheels if abs(w.y) > SIDE_EPSILON]
    if off:
        return (f"the wheels are not all on the centre line ({', '.join(off)} beside it), "
                "not a bicycle")
    if not rear:
        return "a steered wheel but no unsteered wheel to drive and turn about"
    if steering.x - np.mean([w.x for w in rear]) <= 0:
        return "the steered wheel is not in front of the others"
    return None


def _no_kind(tree: Tree, lefts, rights) -> str:
    if any(w.steering for w in tree.wheels) or tree.odd_steering:
        return (f"{_no_ackermann(tree, tree.steering)}: not a drive kind mcar sim drives "
                f"({', '.join(KINDS)})")
    names = (f"{', '.join(w.joint for w in lefts) or 'none'} / "
             f"{', '.join(w.joint for w in rights) or 'none'}")
    return (f"{len(lefts)} wheel(s) on the left and {len(rights)} on the right ({names}): not "
            f"a drive kind mcar sim drives ({', '.join(KINDS)})")


def _side(wheels, sign: int) -> list[Wheel]:
    return [w for w in wheels if w.y * sign > SIDE_EPSILON]


def _sorted_steering(steering: list[Steering]) -> list[Steering]:
    return sorted(steering, key=lambda s: -s.y)  # left first


def _wheel(mj, model, data, joints, name) -> Wheel:
    joint_id = model.joint(name).id
    body = int(model.jnt_bodyid[joint_id])
    # Its collision geoms only: a model with visuals (mcar export) has geoms that touch
    # nothing (contype = conaffinity = 0), which neither roll nor size the tyre.
    geoms = [g for g in range(model.ngeom) if model.geom_bodyid[g] == body
             and (model.geom_contype[g] or model.geom_conaffinity[g])]
    limit = _child(joints[name], "limit")

    def number(key):
        return parse_number(limit.get(key)) if limit is not None else None
    radius = max((rolling_radius(mj, model, g, data, joint_id) for g in geoms), default=0.0)
    return Wheel(name, model.body(body).name, joint_id, body, geoms, radius,
                 float(data.xpos[body][0]), float(data.xpos[body][1]), number("effort"),
                 number("velocity"))


def _steering(model, data, element, name: str, wheel: Wheel) -> Steering:
    joint_id = model.joint(name).id
    limit = _child(element, "limit")

    def number(key):
        return parse_number(limit.get(key)) if limit is not None else None
    anchor = data.xanchor[joint_id]
    # a continuous joint turns without end: urdfdom drops its <limit lower/upper>
    endless = element.get("type") == "continuous"
    return Steering(name, joint_id, wheel, float(anchor[0]), float(anchor[1]),
                    1.0 if data.xaxis[joint_id][2] > 0 else -1.0,
                    None if endless else number("lower"), None if endless else number("upper"),
                    number("effort"))


def _upright_hinge(mj, model, data, body: int) -> str | None:
    """The name of a hinge joint on ``body`` whose axis stands upright, or None."""
    for j in range(model.body_jntadr[body], model.body_jntadr[body] + model.body_jntnum[body]):
        if model.jnt_type[j] == mj.mjtJoint.mjJNT_HINGE and abs(data.xaxis[j][2]) > UPRIGHT:
            return model.joint(j).name
    return None


def _child(element, tag):
    for child in element:
        if child.tag == tag:
            return child
    return None


def rolling_radius(mj, model, g, data, joint_id: int) -> float:
    """The radius geom ``g`` rolls on: a cylinder's, sphere's or capsule's own; a mesh's
    farthest vertex from the wheel joint's axis (``joint_id``, placed by ``data``), not its
    bounding sphere, which reaches the corners of its box: AgileX Tracer's 121 x 84 mm
    mesh tyre was 95 mm for 60.5 mm, and drive and spin failed on a 36% 'wheel slip' that
    was the radius's; any other shape's bounding sphere."""
    kind, size = mj.mjtGeom(int(model.geom_type[g])), model.geom_size[g]
    if kind in (mj.mjtGeom.mjGEOM_CYLINDER, mj.mjtGeom.mjGEOM_SPHERE,
                mj.mjtGeom.mjGEOM_CAPSULE):
        return float(size[0])
    if kind == mj.mjtGeom.mjGEOM_MESH:
        mesh = model.geom_dataid[g]
        start, count = model.mesh_vertadr[mesh], model.mesh_vertnum[mesh]
        points = (model.mesh_vert[start:start + count] @ data.geom_xmat[g].reshape(3, 3).T
                  + data.geom_xpos[g] - data.xanchor[joint_id])
        axis = data.xaxis[joint_id]
        across = points - np.outer(points @ axis, axis)
        return float(np.sqrt((across ** 2).sum(axis=1).max()))
    return float(model.geom_rbound[g])
