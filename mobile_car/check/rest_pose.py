"""The robot in its rest pose (every joint at zero): where each link's frame is, and the
box around each visual and collision shape, in metres, in the root's frame.

``mcar check`` states the robot's size from it and judges plausibility on it
(:mod:`.plausibility`), without numpy: check must stay quick to start, and a robot of
20,000 links is walked once, each link's pose composed from its parent's (rotations as
9-tuples, row by row; the URDF's ``rpy`` is fixed-axis roll, pitch, yaw, as urdfdom reads
it: R = Rz(yaw) Ry(pitch) Rx(roll)). A shape's box in the root's frame is the box around
the rotated box of the shape (its corners' spread: ``|R| h``), so it may be looser than
the shape, never tighter. A mesh's own box comes from :mod:`mobile_car.load.mesh_facts`
(its file's unit applied), times its ``scale``; a mesh whose box is not known (missing,
broken, over a limit) has none. Numbers are read as ``float`` reads them; one that is not
a number leaves its element out (check reports it: E114).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from math import cos, sin

IDENTITY = ((1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0), (0.0, 0.0, 0.0))


@dataclass(slots=True)
class Shape:
    """One visual or collision shape: ``kind`` (visual, collision), ``tag`` (box,
    cylinder, sphere, mesh), ``size`` (box: its size; cylinder: radius and length; sphere:
    radius; mesh: its box's extents), ``low``/``high`` the box around it in the root's
    frame, as (x, y, z) corners; ``placed`` its pose in its link's frame and ``own`` its
    box in its own frame, (low, high), from which :attr:`local` is worked out if asked."""

    link: str
    kind: str
    tag: str
    element: object     # the shape element (<box>, <mesh>, ...)
    size: tuple
    low: tuple
    high: tuple
    placed: tuple
    own: tuple

    @property
    def local(self) -> tuple:
        """(low, high) of the box around the shape in its link's frame."""
        return placed_box(self.placed, *self.own)


@dataclass
class RestPose:
    poses: dict = field(default_factory=dict)   # link -> (rotation 9-tuple, origin)
    shapes: list[Shape] = field(default_factory=list)
    inertials: dict = field(default_factory=dict)  # link -> its first <inertial>

    def extents(self, shapes: list[Shape] | None = None) -> tuple | None:
        """(x, y, z) of the box around ``shapes`` (default: all), None if there are none."""
        low, high = union(shapes if shapes is not None else self.shapes)
        return None if low is None else tuple(h - lo for lo, h in zip(low, high, strict=True))


def union(shapes) -> tuple:
    """(low, high) around the shapes' boxes, or (None, None)."""
    x0 = y0 = z0 = float("inf")
    x1 = y1 = z1 = float("-inf")
    for shape in shapes:
        low, high = shape.low, shape.high
        if low[0] < x0:
            x0 = low[0]
        if low[1] < y0:
            y0 = low[1]
        if low[2] < z0:
            z0 = low[2]
        if high[0] > x1:
            x1 = high[0]
        if high[1] > y1:
            y1 = high[1]
        if high[2] > z1:
            z1 = high[2]
    if x0 > x1:
        return None, None
    return (x0, y0, z0), (x1, y1, z1)


def _numbers(text: str | None, default: tuple | None = None) -> tuple | None:
    if text is None:
        return default
    words = text.split()
    if len(words) != 3:
        return None
    try:
        return (float(words[0]), float(words[1]), float(words[2]))
    except ValueError:
        return None


_frames: dict[tuple, tuple] = {}


def frame(origin) -> tuple | None:
    """(rotation, translation) of an ``<origin>`` element (None: identity); None when its
    numbers cannot be read. Remembered by text: robots repeat their origins."""
    if origin is None:
        return IDENTITY
    key = (origin.get("xyz"), origin.get("rpy"))
    found = _frames.get(key)
    if found is not None:
        return found
    xyz, rpy = _numbers(key[0], (0.0, 0.0, 0.0)), _numbers(key[1], (0.0, 0.0, 0.0))
    if xyz is None or rpy is None:
        return None
    roll, pitch, yaw = rpy
    if roll == pitch == yaw == 0:
        found = (IDENTITY[0], xyz)
    else:
        cr, sr, cp, sp = cos(roll), sin(roll), cos(pitch), sin(pitch)
        cy, sy = cos(yaw), sin(yaw)
        found = ((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,
                  sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,
                  -sp, cp * sr, cp * cr), xyz)
    if len(_frames) < 100_000:
        _frames[key] = found
    return found


def compose(outer: tuple, inner: tuple) -> tuple:
    """The pose ``inner`` expressed in ``outer``'s parent frame."""
    a, b, u = outer[0], inner[0], inner[1]
    if b is IDENTITY[0]:
        rotation = a
    elif a is IDENTITY[0]:
        rotation = b
    else:
        a0, a1, a2, a3, a4, a5, a6, a7, a8 = a
        b0, b1, b2, b3, b4, b5, b6, b7, b8 = b
        rotation = (a0 * b0 + a1 * b3 + a2 * b6, a0 * b1 + a1 * b4 + a2 * b7,
                    a0 * b2 + a1 * b5 + a2 * b8, a3 * b0 + a4 * b3 + a5 * b6,
                    a3 * b1 + a4 * b4 + a5 * b7, a3 * b2 + a4 * b5 + a5 * b8,
                    a6 * b0 + a7 * b3 + a8 * b6, a6 * b1 + a7 * b4 + a8 * b7,
                    a6 * b2 + a7 * b5 + a8 * b8)
    return rotation, apply(outer, u)


def apply(pose: tuple, point: tuple) -> tuple:
    (r, t), (x, y, z) = pose, point
    return (r[0] * x + r[1] * y + r[2] * z + t[0], r[3] * x + r[4] * y + r[5] * z + t[1],
            r[6] * x + r[7] * y + r[8] * z + t[2])


def placed_box(pose: tuple, low: tuple, high: tuple) -> tuple:
    """(low, high) of the box around the box low..high placed by ``pose``."""
    r, t = pose
    cx, cy, cz = (low[0] + high[0]) * 0.5, (low[1] + high[1]) * 0.5, (low[2] + high[2]) * 0.5
    hx, hy, hz = (high[0] - low[0]) * 0.5, (high[1] - low[1]) * 0.5, (high[2] - low[2]) * 0.5
    r0, r1, r2, r3, r4, r5, r6, r7, r8 = r
    x = r0 * cx + r1 * cy + r2 * cz + t[0]
    y = r3 * cx + r4 * cy + r5 * cz + t[1]
    z = r6 * cx + r7 * cy + r8 * cz + t[2]
    dx = abs(r0) * hx + abs(r1) * hy + abs(r2) * hz
    dy = abs(r3) * hx + abs(r4) * hy + abs(r5) * hz
    dz = abs(r6) * hx + abs(r7) * hy + abs(r8) * hz
    return (x - dx, y - dy, z - dz), (x + dx, y + dy, z + dz)


def shape_box(element, mesh_bounds: dict) -> tuple | None:
    """(size, (low, high)) of a shape in its own frame, or None (unknown, unreadable)."""
    tag = element.tag
    try:
        if tag == "box":
            size = _numbers(element.get("size"))
            if size is None or min(size) <= 0:
                return None
            return size, (tuple(-v / 2 for v in size), tuple(v / 2 for v in size))
        if tag == "cylinder":
            radius, length = float(element.get("radius")), float(element.get("length"))
            if not (radius > 0 and length > 0):
                return None
            return (radius, length), ((-radius, -radius, -length / 2),
                                      (radius, radius, length / 2))
        if tag == "sphere":
            radius = float(element.get("radius"))
            return ((radius,), ((-radius,) * 3, (radius,) * 3)) if radius > 0 else None
    except (TypeError, ValueError):
        return None
    if tag != "mesh" or mesh_bounds.get(element) is None:
        return None
    scale = _numbers(element.get("scale"), (1.0, 1.0, 1.0))
    if scale is None:
        return None
    low, high = mesh_bounds[element]
    ends = [sorted((lo * s, h * s)) for lo, h, s in zip(low, high, scale, strict=True)]
    low, high = tuple(e[0] for e in ends), tuple(e[1] for e in ends)
    return tuple(h - lo for lo, h in zip(low, high, strict=True)), (low, high)


def rest_pose(robot, tree, mesh_bounds: dict) -> RestPose:
    """The rest pose of a robot whose tree is sound (``tree.is_sound``); ``mesh_bounds``
    maps a ``<mesh>`` element to its box in its own frame (None: unknown)."""
    result = RestPose()
    poses = result.poses
    poses[tree.root] = IDENTITY
    stack = [tree.root]
    children = tree.children
    while stack:
        parent = stack.pop()
        pose = poses[parent]
        for joint in children.get(parent, ()):
            origin = frame(joint.parts.get("origin"))
            poses[joint.child] = pose if origin is None else compose(pose, origin)
            stack.append(joint.child)
    append = result.shapes.append
    inertials = result.inertials
    for link in robot.links:
        pose = poses.get(link.name)
        if pose is None:
            continue
        # The link's children in one loop (each find() would cost as much as the whole
        # walk); the first <origin> and <geometry> of each body, as urdfdom reads them.
        for body in link.element:
            kind = body.tag
            if kind != "visual" and kind != "collision":
                if kind == "inertial" and link.name not in inertials:
                    inertials[link.name] = body
                continue
            origin = geometry = None
            for part in body:
                tag = part.tag
                if tag == "origin":
                    if origin is None:
                        origin = part
                elif tag == "geometry" and geometry is None:
                    geometry = part
            element = None
            if geometry is not None:
                for element in geometry:
                    if element.tag.__class__ is str:
                        break
                else:
                    element = None
            known = None if element is None else shape_box(element, mesh_bounds)
            if known is None:
                continue
            placed = frame(origin)
            if placed is None:
                continue
            size, own = known
            low, high = placed_box(compose(pose, placed), *own)
            append(Shape(link.name, kind, element.tag, element, size, low, high, placed, own))
    return result
