"""Joint rules: type, parent and child, axis, limits, mimic, dynamics, safety, calibration.

Everything here that urdfdom rejects (a malformed origin or axis, a limit without effort,
a revolute joint without limits, ...) is an error here too, so ``mcar check`` never
passes a file ``check_urdf`` fails. What urdfdom lets through but no robot can use
(lower > upper, a zero axis, a mimic of a joint that does not exist) is an error as well.
"""

from __future__ import annotations

import math

from .context import MAX_ANGLE, MAX_LENGTH, Reporter, within
from .urdf_reader import Joint, Robot

JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")
_AXIS_TYPES = {"revolute", "continuous", "prismatic", "planar"}
_LIMITED_TYPES = {"revolute", "prismatic"}


def check_joints(robot: Robot, report: Reporter) -> dict:
    """Check every joint; return the origin of each joint proved plain, read: joint ->
    (xyz, rpy) (the rest pose starts from them rather than read them again)."""
    link_names = {link.name for link in robot.links}
    joint_names = {joint.name for joint in robot.joints}
    once_clean = report.once_clean
    origins = {}
    for joint in robot.joints:
        origin = _plainly_sound(joint, link_names, report)
        if origin:
            origins[joint] = origin
            continue
        owner = f"joint '{joint.name}'" if joint.name else "joint"
        if joint.type not in JOINT_TYPES:
            _bad_type(joint, owner, report)
        _check_links(joint, owner, link_names, report)
        parts = joint.parts
        report.origin(parts.get("origin"), owner)
        axis, limit = parts.get("axis"), parts.get("limit")
        # The verdicts depend on the type and the attributes only: check each pair once.
        once_clean(("axis", joint.type, None if axis is None else tuple(axis.items())),
                   _check_axis, joint, axis, owner, report)
        once_clean(("limit", joint.type, None if limit is None else tuple(limit.items())),
                   _check_limit, joint, limit, owner, report)
        _check_mimic(joint, owner, joint_names, report)
        _check_dynamics_safety_calibration(joint, owner, report)
    return origins


# The parts of a joint written the usual way; a joint with any other (mimic,
# safety_controller, calibration) goes through every check below.
_PLAIN_PARTS = frozenset({"parent", "child", "origin", "axis", "limit", "dynamics"})


def _plainly_sound(joint: Joint, link_names: set, report: Reporter) -> tuple | None:
    """The origin's (xyz, rpy), read, if the checks below would find nothing in a joint
    written the usual way, proved in one pass without wording anything (a third of the
    time on a robot whose every number differs). None only says "not proved here": the
    checks below decide.
    Each condition mirrors one of them; tests/check/test_plain_links.py holds the two alike."""
    kind, parent, child = joint.type, joint.parent, joint.child
    if (kind not in JOINT_TYPES or not parent or not child or parent not in link_names
            or child not in link_names):
        return None
    tags = joint.tags
    if tags is not None:  # read by its skeleton: the texts come read
        if not _PLAIN_PARTS.issuperset(tags):
            return None
        return _sound(kind, "origin" in tags, "axis" in tags, "limit" in tags,
                      "dynamics" in tags, joint.texts, report)
    parts = joint.parts
    if not _PLAIN_PARTS.issuperset(parts):
        return None
    origin, axis = parts.get("origin"), parts.get("axis")
    limit, dynamics = parts.get("limit"), parts.get("dynamics")
    xyz_text = rpy_text = axis_text = effort = velocity = lower = upper = damping = \
        friction = None
    if origin is not None:
        xyz_text, rpy_text = origin.get("xyz"), origin.get("rpy")
    if axis is not None:
        axis_text = axis.get("xyz")
    if limit is not None:
        get = limit.get
        effort, velocity, lower, upper = (get("effort"), get("velocity"), get("lower"),
                                          get("upper"))
    if dynamics is not None:
        damping, friction = dynamics.get("damping"), dynamics.get("friction")
    return _sound(kind, origin is not None, axis is not None, limit is not None,
                  dynamics is not None, (xyz_text, rpy_text, axis_text, effort, velocity,
                                         lower, upper, damping, friction), report)


def _sound(kind: str, has_origin: bool, has_axis: bool, has_limit: bool,
           has_dynamics: bool, texts: tuple, report: Reporter) -> tuple | None:
    """_plainly_sound's verdict on the texts of a joint's numbers (in the order of
    joint_skeletons.TEXTS, None where absent), given which parts it has."""
    xyz_text, rpy_text, axis_text, effort, velocity, lower_text, upper_text, damping, \
        friction = texts
    value, values = report.value, report.values
    xyz = rpy = _ZERO
    if has_origin:
        if xyz_text is not None:
            xyz = values(xyz_text, 3)
            if xyz is None or not within(xyz, MAX_LENGTH):
                return None
        if rpy_text is not None:
            rpy = values(rpy_text, 3)
            if rpy is None or not within(rpy, MAX_ANGLE):
                return None
    if has_axis:
        if axis_text is None:
            if kind in _AXIS_TYPES:
                return None
        else:
            direction = values(axis_text, 3)
            if direction is None or not within(direction, MAX_LENGTH) or \
                    (kind in _AXIS_TYPES and math.hypot(*direction) < 1e-12):
                return None
    if not has_limit:
        if kind in _LIMITED_TYPES:
            return None
    else:
        if effort is None or velocity is None or value(effort) is None or \
                value(velocity) is None:
            return None
        lower = 0.0 if lower_text is None else value(lower_text)
        upper = 0.0 if upper_text is None else value(upper_text)
        if lower is None or upper is None:
            return None
        if lower > upper and (kind in _LIMITED_TYPES
                              or (lower_text is not None and upper_text is not None)):
            return None
    if has_dynamics:
        if damping is None and friction is None:
            return None
        if (damping is not None and value(damping) is None) or \
                (friction is not None and value(friction) is None):
            return None
    return xyz, rpy


_ZERO = (0.0, 0.0, 0.0)


def _bad_type(joint: Joint, owner: str, report: Reporter) -> None:
    kinds = ", ".join(JOINT_TYPES)
    if joint.type is None:
        report.add("E120", joint.element, f"{owner} has no type; one of: {kinds}")
    else:
        report.add("E120", joint.element, f"{owner} has unknown type '{joint.type}'; "
                                          f"one of: {kinds}")


def _check_links(joint: Joint, owner: str, link_names: set, report: Reporter) -> None:
    for role, name in (("parent", joint.parent), ("child", joint.child)):
        if name and name in link_names:
            continue
        element = joint.parts.get(role)
        if element is None:
            report.add("E121", joint.element, f"{owner} has no <{role} link=\"...\"/>")
        elif not name:
            report.add("E121", element, f"{owner}: <{role}> has no link name")
        else:
            report.add("E122", element, f"{owner}: {role} link '{name}' is not defined; "
                       f"add <link name=\"{name}\"/> or fix the name")


def _check_axis(joint: Joint, axis, owner: str, report: Reporter) -> None:
    if axis is None:
        return  # urdfdom's default is 1 0 0
    if axis.get("xyz") is None:
        if joint.type in _AXIS_TYPES:
            report.add("E125", axis, f"{owner}: <axis> has no xyz, so urdfdom sets it "
                       "to 0 0 0; write e.g. xyz=\"0 0 1\"")
        return
    xyz = report.numbers(axis, "xyz", 3, owner)
    if not report.bounded(axis, "xyz", xyz, MAX_LENGTH, "", owner):
        return
    if xyz is not None and joint.type in _AXIS_TYPES and math.hypot(*xyz) < 1e-12:
        report.add("E125", axis, f"{owner}: axis xyz=\"{axis.get('xyz')}\" has "
                   "length 0")


def _check_limit(joint: Joint, limit, owner: str, report: Reporter) -> None:
    if limit is None:
        if joint.type in _LIMITED_TYPES:
            report.add("E123", joint.element, f"{owner} is {joint.type} but has no "
                       "<limit lower=... upper=... effort=... velocity=.../>")
        return
    attrs = limit
    missing = [attr for attr in ("effort", "velocity") if attrs.get(attr) is None]
    if missing:
        report.add("E123", limit, f"{owner}: <limit> has no {' and no '.join(missing)}")
    values = {attr: report.number(limit, attr, owner)
              for attr in ("lower", "upper", "effort", "velocity")}
    given = attrs.get("lower") is not None and attrs.get("upper") is not None
    if joint.type in _LIMITED_TYPES or given:
        # urdfdom reads a missing lower or upper as 0.
        lower = 0.0 if attrs.get("lower") is None else values["lower"]
        upper = 0.0 if attrs.get("upper") is None else values["upper"]
        if lower is not None and upper is not None and lower > upper:
            report.add("E124", limit, f"{owner}: limit lower {lower:g} > upper {upper:g}"
                       + ("" if given else " (a missing lower or upper is 0)"))


def _check_mimic(joint: Joint, owner: str, joint_names: set, report: Reporter) -> None:
    mimic = joint.parts.get("mimic")
    if mimic is None:
        return
    target = mimic.get("joint")
    if not target:
        report.add("E126", mimic, f"{owner}: <mimic> has no joint=\"...\"")
    elif target == joint.name:
        report.add("E126", mimic, f"{owner} mimics itself")
    elif target not in joint_names:
        report.add("E126", mimic, f"{owner} mimics joint '{target}', which is not "
                   "defined")
    report.number(mimic, "multiplier", owner)
    report.number(mimic, "offset", owner)


def _check_dynamics_safety_calibration(joint: Joint, owner: str, report: Reporter) -> None:
    dynamics = joint.parts.get("dynamics")
    if dynamics is not None:
        if dynamics.get("damping") is None and dynamics.get("friction") is None:
            report.add("E127", dynamics, f"{owner}: <dynamics> has neither damping nor "
                       "friction")
        report.number(dynamics, "damping", owner)
        report.number(dynamics, "friction", owner)
    safety = joint.parts.get("safety_controller")
    if safety is not None:
        if safety.get("k_velocity") is None:
            report.add("E127", safety, f"{owner}: <safety_controller> has no k_velocity")
        for attr in ("soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"):
            report.number(safety, attr, owner)
    calibration = joint.parts.get("calibration")
    if calibration is not None:
        for attr in ("rising", "falling"):
            report.number(calibration, attr, owner)
