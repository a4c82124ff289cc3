"""Massless links a converter makes no body of, handled before it reads the robot.

A link with no ``<inertial>`` and no geometry (the bundled car's ``base_link``, Husky's
``base_link``) is a frame, not a body: urdf-usd-converter makes no rigid body of it, so a
joint hung on it has the stage at its end (the car's wheels would be jointed to the
world) and, under a floating base, a fixed part on it would fall away.

Where such a link is the root or sits on a fixed joint, its children are re-hung on the
nearest link with mass fixed to it (``base_link`` -> ``body_link`` on the car): each
child's joint origin is composed through the fixed joints between them, so every link
keeps its place, its mass and its inertia, and every moving joint its axis (given in
the joint's own frame, which does not change). Only the joints' parent names change,
and each is said. Gazebo lumps fixed links into one body instead; this keeps each link.

Lengths in m, angles in rad.
"""

from __future__ import annotations

from ..check.urdf_model import parse_number
from ..diff.geometry import Pose, matrix_rpy, rotate


def rehang_on_bodies(root) -> list[str]:
    """Re-hang the children of each massless, geometry-less link (root or fixed-jointed)
    on the nearest massed link fixed below it, in place; one line per link re-hung from."""
    links = {link.get("name"): link for link in root.iterchildren("link")}
    joints = list(root.iterchildren("joint"))
    notes = []
    for name in _top_down(links, joints):
        if not _is_frame(links[name]):
            continue
        below = [j for j in root.iterchildren("joint") if _end(j, "parent") == name]
        above = next((j for j in root.iterchildren("joint") if _end(j, "child") == name), None)
        if above is not None and above.get("type") != "fixed":
            continue  # a massless link on a moving joint: the description's own problem
        found = _nearest_body(root, links, name)
        if found is None:
            continue
        anchor, path = found
        first = path[0]
        moved = [j for j in below if j is not first]
        if not moved:
            continue
        to_anchor = Pose()
        for joint in path:
            to_anchor = to_anchor @ _origin(joint)
        back = _inverse(to_anchor)
        for joint in moved:
            _set_origin(joint, back @ _origin(joint))
            joint.find("parent").set("link", anchor)
        notes.append(f"joints {', '.join(j.get('name') for j in moved)} re-hung from "
                     f"{name} (no mass: a frame, no body in the converter) on {anchor}, "
                     "fixed to it, in the same place")
    return notes


def _top_down(links: dict, joints: list) -> list[str]:
    children = {}
    has_parent = set()
    for joint in joints:
        children.setdefault(_end(joint, "parent"), []).append(_end(joint, "child"))
        has_parent.add(_end(joint, "child"))
    order = [name for name in links if name not in has_parent]
    seen = set(order)
    for name in order:  # grows as it goes: breadth first
        for child in children.get(name, ()):
            if child in links and child not in seen:
                seen.add(child)
                order.append(child)
    return order


def _nearest_body(root, links: dict, start: str):
    """(link, fixed joints from ``start`` to it) for the nearest link with mass reached
    through fixed joints only; among equally near ones the one carrying most mass on
    fixed joints (the chassis, not a sensor); None if none is."""
    level = [(start, [])]
    while level:
        reached = []
        for name, path in level:
            for joint in root.iterchildren("joint"):
                if _end(joint, "parent") == name and joint.get("type") == "fixed":
                    reached.append((_end(joint, "child"), [*path, joint]))
        massed = [(name, path) for name, path in reached
                  if name in links and _mass(links[name]) > 0]
        if massed:
            return max(massed, key=lambda item: _fixed_mass(root, links, item[0]))
        level = reached
    return None


def _fixed_mass(root, links: dict, name: str) -> float:
    """The mass of ``name`` and of every link fixed below it."""
    total = _mass(links[name]) if name in links else 0.0
    for joint in root.iterchildren("joint"):
        if _end(joint, "parent") == name and joint.get("type") == "fixed":
            total += _fixed_mass(root, links, _end(joint, "child"))
    return total


def _is_frame(link) -> bool:
    return _mass(link) <= 0 and link.find("visual") is None and link.find("collision") is None


def _mass(link) -> float:
    mass = link.find("inertial/mass")
    value = parse_number(mass.get("value")) if mass is not None else None
    return value or 0.0


def _end(joint, tag: str) -> str | None:
    element = joint.find(tag)
    return element.get("link") if element is not None else None


def _origin(joint) -> Pose:
    origin = joint.find("origin")
    xyz = _numbers(origin.get("xyz") if origin is not None else None)
    rpy = _numbers(origin.get("rpy") if origin is not None else None)
    return Pose.of(xyz, rpy)


def _numbers(text: str | None) -> tuple[float, float, float]:
    values = [parse_number(v) for v in (text or "").split()]
    if len(values) != 3 or any(v is None for v in values):
        return (0.0, 0.0, 0.0)
    return tuple(values)


def _inverse(pose: Pose) -> Pose:
    transposed = tuple(tuple(pose.r[j][i] for j in range(3)) for i in range(3))
    return Pose(transposed, tuple(-v for v in rotate(transposed, pose.t)))


def _set_origin(joint, pose: Pose) -> None:
    from lxml import etree

    origin = joint.find("origin")
    if origin is None:
        origin = etree.Element("origin")
        joint.insert(0, origin)
    origin.set("xyz", " ".join(f"{v:.17g}" for v in pose.t))
    origin.set("rpy", " ".join(f"{v:.17g}" for v in matrix_rpy(pose.r)))
