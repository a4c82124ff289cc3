"""Link frames drawn as RViz's TF display draws them: small red, green and blue axes (x, y,
z) at a link's origin, with the link's name beside it.

A robot with no geometry at all (the tutorial's skeleton: five links joined by fixed
joints) would otherwise be an empty grid. ``--frames`` chooses which links get axes:
``auto`` (every link when nothing else would be drawn, else none), ``bare`` (links without
geometry of the kind drawn), ``all`` (every link, as RViz's TF display) or ``none``.

Axes are ordinary triangles in the scene (thin boxes, so both renderers draw them); the
names are 2D text laid over the picture at each frame's projected origin. Frames that
project to the same spot (a skeleton's joints have no origins) share one label, the names
listed in tree order and indented by depth, so the picture still shows the tree.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass

import numpy as np

AXIS_RGBA = ((230, 40, 40, 255), (40, 170, 60, 255), (40, 90, 230, 255))  # x, y, z
AXIS_SHARE = 0.15       # of the drawn geometry's largest extent
SPREAD_SHARE = 0.25     # of the frames' spread, when nothing else is drawn
AXIS_LENGTH = 0.1       # metres, when the frames all lie at one point
AXIS_THICKNESS = 1 / 14  # of the axis length


@dataclass(frozen=True)
class Frame:
    """A link frame to draw: its name, world pose (4x4) and depth in the tree."""

    link: str
    pose: np.ndarray
    depth: int


def chosen_frames(robot, poses: dict, has_geometry: set[str], choice: str) -> list[Frame]:
    """The frames ``choice`` asks for, in tree order (depth first from each root)."""
    if choice == "none":
        return []
    if choice == "auto":
        wanted = set() if has_geometry else {link.name for link in robot.links}
    elif choice == "bare":
        wanted = {link.name for link in robot.links} - has_geometry
    else:
        wanted = {link.name for link in robot.links}
    return [Frame(name, poses[name], depth) for name, depth in _tree_order(robot)
            if name in wanted and name in poses]


def _tree_order(robot) -> list[tuple[str, int]]:
    children, has_parent = defaultdict(list), set()
    for joint in robot.joints:
        children[joint.parent].append(joint.child)
        has_parent.add(joint.child)
    order, seen = [], set()
    roots = [link.name for link in robot.links if link.name not in has_parent]
    stack = [(name, 0) for name in reversed(roots)]
    while stack:
        name, depth = stack.pop()
        if name in seen:  # a cycle or a second parent: check reports those
            continue
        seen.add(name)
        order.append((name, depth))
        stack.extend((child, depth + 1) for child in reversed(children.get(name, ())))
    order += [(link.name, 0) for link in robot.links if link.name not in seen]
    return order


def axis_length(frames: list[Frame], bounds: np.ndarray | None) -> float:
    """How long each axis is drawn: a share of the robot's size, or of the frames'
    spread when there is no geometry, or AXIS_LENGTH when they all sit at one point."""
    if bounds is not None and float(np.ptp(bounds, axis=0).max()) > 0:
        return AXIS_SHARE * float(np.ptp(bounds, axis=0).max())
    origins = np.array([frame.pose[:3, 3] for frame in frames]) if frames else np.zeros((1, 3))
    spread = float(np.ptp(origins, axis=0).max())
    return SPREAD_SHARE * spread if spread > 0 else AXIS_LENGTH


def axis_boxes(frame: Frame, length: float) -> list[tuple[np.ndarray, tuple]]:
    """(transform of a unit box, RGBA 0..255) for the x, y and z axes of one frame."""
    thick = length * AXIS_THICKNESS
    boxes = []
    for axis, rgba in enumerate(AXIS_RGBA):
        size = [thick, thick, thick]
        size[axis] = length
        offset = np.zeros(3)
        offset[axis] = length / 2
        local = np.diag([*size, 1.0])
        local[:3, 3] = offset
        boxes.append((frame.pose @ local, rgba))
    return boxes


def labels(frames: list[Frame]) -> tuple[tuple[str, tuple[float, float, float]], ...]:
    """(text, world point) per frame origin: frames at one point share a label listing
    their names in tree order, indented by their depth below the first."""
    grouped: dict[tuple, list[Frame]] = {}
    for frame in frames:
        key = tuple(np.round(frame.pose[:3, 3], 6))
        grouped.setdefault(key, []).append(frame)
    found = []
    for point, members in grouped.items():
        top = min(frame.depth for frame in members)
        lines = [("  " * (frame.depth - top)) + frame.link for frame in members]
        found.append(("\n".join(lines), tuple(float(v) for v in point)))
    return tuple(found)
