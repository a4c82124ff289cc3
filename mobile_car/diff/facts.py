"""What a robot is, as plain comparable facts: per joint, link, frame and for the whole.

Every fact is a :class:`Value`: a kind (which says the unit it is shown in) and either
numbers in SI units or a text. Two robots written differently (attribute order, number
spelling, element order) give equal facts, since the facts are read through urdfdom's own
rules (:mod:`mobile_car.check.urdf_model`), never from the text.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import NamedTuple

from ..check.inertia import principal_moments
from ..check.urdf_model import (
    axis_of,
    first_child,
    origin_of,
    parse_number,
    parse_numbers,
    parse_xml,
)
from ..check.urdf_reader import read_links, read_robot
from ..errors import McarError
from .geometry import Pose, half_extents, matrix_rpy
from .mesh_bounds import mesh_bounds


class Value(NamedTuple):
    """One fact: ``kind`` is length (m), angle (rad), mass (kg), inertia (kg m^2), ratio,
    number, text, or ``unit:U`` (a config dimension in unit U); ``data`` a tuple of
    floats or a str."""

    kind: str
    data: tuple | str


def text(value) -> Value:
    return Value("text", "" if value is None else str(value))


@dataclass
class RobotFacts:
    name: str
    label: str
    joints: dict[str, dict[str, Value]] = field(default_factory=dict)
    links: dict[str, dict[str, Value]] = field(default_factory=dict)
    frames: dict[str, dict[str, Value]] = field(default_factory=dict)
    totals: dict[str, Value] = field(default_factory=dict)
    dimensions: dict[str, Value] | None = None  # from config.xacro, when the robot has one
    notes: list[str] = field(default_factory=list)  # what could not be measured, and why


class FactsError(McarError):
    """The robot cannot be described: not XML, not a robot, no tree (exit 1)."""

    exit_code = 1


def robot_facts(urdf: bytes, label: str, base: Path, search) -> RobotFacts:
    """The facts of a URDF; ``base`` and ``search`` resolve its mesh files."""
    from ..check.urdf_model import XmlError

    try:
        root = parse_xml(urdf)
    except XmlError as error:
        raise FactsError(error.message, file=label, line=error.line) from None
    if root.tag != "robot":
        raise FactsError(f"the root element is <{root.tag}>, not <robot>", file=label)
    robot = read_robot(root)
    read_links(robot.links, robot.anomalies)
    facts = RobotFacts(robot.name or "", label)
    materials = {element.get("name"): _material_colour(parts) for element, parts in
                 robot.materials}
    for joint in robot.joints:
        if joint.name is not None and joint.name not in facts.joints:
            facts.joints[joint.name] = _joint_facts(joint)
    links = {}
    for link in robot.links:
        if link.name is not None and link.name not in links:
            links[link.name] = link
            facts.links[link.name] = _link_facts(link, materials)
    poses = _world_poses(robot, links)
    boxes = []
    mass, moment = 0.0, [0.0, 0.0, 0.0]
    for name, link in links.items():
        pose = poses[name]
        facts.frames[name] = {"position": Value("length", pose.t),
                              "rotation": Value("angle", matrix_rpy(pose.r))}
        inertial = link.inertial
        if inertial is not None and "mass" in inertial:
            value = parse_number(inertial["mass"].get("value")) or 0.0
            centre = pose.apply(origin_of(link.parts["inertial"])["xyz"])
            mass += value
            moment = [m + value * c for m, c in zip(moment, centre, strict=True)]
        for body in link.visuals:
            box = _body_box(body, pose, base, search, label, facts.notes)
            if box is not None:
                boxes.append(box)
    facts.totals["mass"] = Value("mass", (mass,))
    if mass > 0:
        facts.totals["centre of mass"] = Value("length", tuple(m / mass for m in moment))
    if boxes:
        low = tuple(min(box[0][i] for box in boxes) for i in range(3))
        high = tuple(max(box[1][i] for box in boxes) for i in range(3))
        facts.totals["bounding box min"] = Value("length", low)
        facts.totals["bounding box max"] = Value("length", high)
        size = tuple(h - lo for h, lo in zip(high, low, strict=True))
        facts.totals["size"] = Value("length", size)
        # The ground outline the robot needs (length x width): what a doorway or a
        # parking spot is measured against.
        facts.totals["footprint"] = Value("length", (high[0] - low[0], high[1] - low[1]))
    return facts


def _numbers(text_value, count: int, default=None) -> tuple | None:
    value = parse_numbers(text_value, count) if text_value is not None else None
    return value if isinstance(value, tuple) else default


def _joint_facts(joint) -> dict[str, Value]:
    facts = {"type": text(joint.type), "parent": text(joint.parent), "child": text(joint.child)}
    origin = origin_of(joint.element)
    facts["origin xyz"] = Value("length", origin["xyz"])
    facts["origin rpy"] = Value("angle", origin["rpy"])
    axis = axis_of(joint)
    if axis is not None:
        facts["axis"] = Value("ratio", axis)
    travel = "length" if joint.type == "prismatic" else "angle"
    limit = joint.parts.get("limit")
    if limit is not None:
        for key, kind in (("lower", travel), ("upper", travel), ("effort", "number"),
                          ("velocity", "number")):
            number = parse_number(limit.get(key))
            if number is not None:
                facts[f"limit {key}"] = Value(kind, (number,))
    for part, keys in (("dynamics", ("damping", "friction")),
                       ("mimic", ("multiplier", "offset"))):
        element = joint.parts.get(part)
        if element is None:
            continue
        if part == "mimic":
            facts["mimic joint"] = text(element.get("joint"))
        for key in keys:
            number = parse_number(element.get(key))
            if number is not None:
                facts[f"{part} {key}"] = Value("number", (number,))
    return facts


def _material_colour(parts: dict) -> tuple | None:
    colour = parts.get("color")
    return _numbers(colour.get("rgba"), 4) if colour is not None else None


def _link_facts(link, materials: dict) -> dict[str, Value]:
    facts: dict[str, Value] = {}
    inertial = link.inertial
    if inertial is not None:
        if "mass" in inertial:
            facts["mass"] = Value("mass", (parse_number(inertial["mass"].get("value")) or 0.0,))
        facts["centre of mass"] = Value("length", origin_of(link.parts["inertial"])["xyz"])
        inertia = inertial.get("inertia")
        if inertia is not None:
            terms = [parse_number(inertia.get(k)) or 0.0
                     for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")]
            facts["principal inertia"] = Value("inertia", principal_moments(*terms))
    for kind, bodies in (("visual", link.visuals), ("collision", link.collisions)):
        for index, body in enumerate(bodies):
            label = kind if index == 0 else f"{kind} {index + 1}"
            facts.update(_body_facts(label, body, materials if kind == "visual" else None))
    return facts


def _body_facts(label: str, body, materials: dict | None) -> dict[str, Value]:
    facts = {}
    shape = body.shapes[0] if body.shapes else None
    facts[f"{label} geometry"] = text(shape.tag if shape is not None else "none")
    if shape is not None:
        if shape.tag == "box":
            facts[f"{label} size"] = Value("length", _numbers(shape.get("size"), 3, ()))
        elif shape.tag == "cylinder":
            facts[f"{label} radius, length"] = Value("length", (
                parse_number(shape.get("radius")) or 0.0, parse_number(shape.get("length")) or 0.0))
        elif shape.tag == "sphere":
            facts[f"{label} radius"] = Value("length", (parse_number(shape.get("radius")) or 0.0,))
        elif shape.tag == "mesh":
            facts[f"{label} mesh"] = text(shape.get("filename"))
            facts[f"{label} scale"] = Value("ratio", _numbers(shape.get("scale"), 3,
                                                              (1.0, 1.0, 1.0)))
    origin = origin_of(body.element)
    facts[f"{label} origin xyz"] = Value("length", origin["xyz"])
    facts[f"{label} origin rpy"] = Value("angle", origin["rpy"])
    if materials is not None:
        material = first_child(body.element, "material")
        if material is not None:
            name = material.get("name")
            facts[f"{label} material"] = text(name)
            own = body.material.get("color") if body.material else None
            rgba = _numbers(own.get("rgba"), 4) if own is not None else materials.get(name)
            if rgba is not None:
                facts[f"{label} colour"] = Value("ratio", rgba)
            texture = body.material.get("texture") if body.material else None
            if texture is not None:
                facts[f"{label} texture"] = text(texture.get("filename"))
    return facts


def _world_poses(robot, links: dict) -> dict[str, Pose]:
    """Each link's pose with every joint at zero; a link no joint reaches sits at the
    origin (a second root), as in the renderer."""
    children: dict[str, list] = {}
    has_parent = set()
    for joint in robot.joints:
        if joint.parent in links and joint.child in links and joint.child not in has_parent:
            children.setdefault(joint.parent, []).append(joint)
            has_parent.add(joint.child)
    poses: dict[str, Pose] = {}
    pending = [name for name in links if name not in has_parent]
    for name in pending:
        poses[name] = Pose()
    while pending:
        name = pending.pop()
        for joint in children.get(name, ()):
            if joint.child in poses:  # a cycle: mcar check reports it (E121)
                continue
            origin = origin_of(joint.element)
            poses[joint.child] = poses[name] @ Pose.of(origin["xyz"], origin["rpy"])
            pending.append(joint.child)
    for name in links:  # a cycle cut off from every root
        poses.setdefault(name, Pose())
    return poses


def _body_box(body, link_pose: Pose, base: Path, search, label: str, notes: list):
    """The world box (low, high) around one visual, or None (no shape, unreadable mesh)."""
    shape = body.shapes[0] if body.shapes else None
    if shape is None:
        return None
    origin = origin_of(body.element)
    pose = link_pose @ Pose.of(origin["xyz"], origin["rpy"])
    centre = pose.t
    if shape.tag == "box":
        half = half_extents("box", _numbers(shape.get("size"), 3, (0.0, 0.0, 0.0)), pose.r)
    elif shape.tag == "cylinder":
        size = (parse_number(shape.get("radius")) or 0.0, parse_number(shape.get("length")) or 0.0)
        half = half_extents("cylinder", size, pose.r)
    elif shape.tag == "sphere":
        half = half_extents("sphere", (parse_number(shape.get("radius")) or 0.0,), pose.r)
    elif shape.tag == "mesh":
        bounds = mesh_bounds(shape.get("filename") or "", base, search)
        if isinstance(bounds, str):
            notes.append(f"{label}: the bounding box leaves out mesh "
                         f"'{shape.get('filename')}': {bounds}")
            return None
        scale = _numbers(shape.get("scale"), 3, (1.0, 1.0, 1.0))
        low, high = ([b * s for b, s in zip(corner, scale, strict=True)] for corner in bounds)
        middle = tuple((lo + hi) / 2 for lo, hi in zip(low, high, strict=True))
        centre = pose.apply(middle)
        extents = tuple(abs(hi - lo) for lo, hi in zip(low, high, strict=True))
        half = half_extents("box", extents, pose.r)
    else:
        return None
    pairs = list(zip(centre, half, strict=True))
    return tuple(c - h for c, h in pairs), tuple(c + h for c, h in pairs)
