"""The robot in its rest pose (every joint at zero): where each link's frame is, and the
box around each visual and collision shape, in metres, in the root's frame.

``mcar check`` states the robot's size from it and judges plausibility on it
(:mod:`.plausibility`), without numpy (check must stay quick to start; a large robot's is
worked out with numpy by :mod:`.rest_pose_arrays`). What each link holds comes read
already (:class:`LinkShapes`): :mod:`.plain_links` reads it while proving a link clean, so
a robot's elements are walked once; :func:`link_shapes` reads the other links. Each link's
pose is composed from its parent's (rotations as 9-tuples, row by row; the URDF's ``rpy``
is fixed-axis roll, pitch, yaw, as urdfdom reads it: R = Rz(yaw) Ry(pitch) Rx(roll)). A
shape's box in the root's frame is the box around the rotated box of the shape (its
corners' spread: ``|R| h``), so it may be looser than the shape, never tighter. A mesh's
own box comes from :mod:`mobile_car.load.mesh_facts` (its file's unit applied), times its
``scale``; a mesh whose box is not known (missing, broken, over a limit) has none.
"""

from __future__ import annotations

from math import cos, inf, sin

ZERO = (0.0, 0.0, 0.0)
ONE = (1.0, 1.0, 1.0)
IDENTITY = ((1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0), (0.0, 0.0, 0.0))

# The classes here are plain classes, not dataclasses: never compared, and a dataclass
# costs every run that imports it the compiling of its methods (values.py).


class LinkShapes:
    """What a link holds, its numbers read: ``bodies`` are (kind, shape element, xyz, rpy,
    dims) per visual and collision, dims a box's size, a cylinder's (radius, length), a
    sphere's (radius,), a mesh's scale; ``inertial`` is (element, mass, six moments, rpy)
    of its first <inertial>, or None."""

    __slots__ = ("bodies", "inertial", "twin")

    def __init__(self, bodies: list, inertial: tuple | None = None, twin: object = None):
        self.bodies = bodies
        self.inertial = inertial
        # The link's own element when the elements above are those of an earlier link
        # whose content is byte for byte the same (link_bodies.py) or whose skeleton is,
        # without a mesh (link_skeletons.py): the numbers above are this link's, a
        # message must name this link's lines (own_elements).
        self.twin = twin


def own_elements(shapes: LinkShapes) -> LinkShapes:
    """``shapes`` pointing at its own link's elements. A clean link keeps every body, in
    order: the i-th read body is its i-th <visual> or <collision>."""
    if shapes.twin is None:
        return shapes
    bodies = []
    found = (child for child in shapes.twin if child.tag in ("visual", "collision"))
    for (kind, _shape, xyz, rpy, dims), body in zip(shapes.bodies, found, strict=False):
        geometry = next(child for child in body if child.tag == "geometry")
        shape = next(child for child in geometry if child.tag.__class__ is str)
        bodies.append((kind, shape, xyz, rpy, dims))
    inertial = shapes.inertial
    if inertial is not None:
        own = next(child for child in shapes.twin if child.tag == "inertial")
        inertial = (own, *inertial[1:])
    return LinkShapes(bodies, inertial)


def link_shapes(element) -> LinkShapes:
    """The LinkShapes of a ``<link>`` read here (one :mod:`.plain_links` did not prove
    clean): the first <origin> and <geometry> of each body, as urdfdom reads them; a
    body or inertial whose numbers do not read is left out (check reports it: E114)."""
    bodies, inertial = [], None
    for body in element:
        kind = body.tag
        if kind == "inertial":
            if inertial is None:
                inertial = _inertial_of(body)
            continue
        if kind != "visual" and kind != "collision":
            continue
        parts = firsts(body)
        geometry, origin = parts.get("geometry"), parts.get("origin")
        shape = None if geometry is None else next(
            (child for child in geometry if child.tag.__class__ is str), None)
        xyz = ZERO if origin is None else _numbers(origin.get("xyz"), ZERO)
        rpy = ZERO if origin is None else _numbers(origin.get("rpy"), ZERO)
        dims = None if shape is None else _dims(shape)
        if xyz is not None and rpy is not None and dims is not None:
            bodies.append((kind, shape, xyz, rpy, dims))
    return LinkShapes(bodies, inertial)


def _dims(shape) -> tuple | None:
    get = shape.get
    try:
        if shape.tag == "box":
            return _numbers(get("size"))
        if shape.tag == "cylinder":
            return float(get("radius")), float(get("length"))
        if shape.tag == "sphere":
            return (float(get("radius")),)
    except (TypeError, ValueError):
        return None
    return _numbers(get("scale"), ONE) if shape.tag == "mesh" else None


def _inertial_of(inertial) -> tuple | None:
    parts = firsts(inertial)
    mass, inertia, origin = parts.get("mass"), parts.get("inertia"), parts.get("origin")
    try:
        value = float(mass.get("value"))
        moments = tuple(float(inertia.get(name)) for name in
                        ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"))
    except (AttributeError, TypeError, ValueError):
        return None
    rpy = ZERO if origin is None else _numbers(origin.get("rpy"), ZERO)
    return None if rpy is None else (inertial, value, moments, rpy)


class Shape:
    """One visual or collision shape: ``kind`` (visual, collision), ``tag`` (box,
    cylinder, sphere, mesh), ``size`` (box: its size; cylinder: radius and length; sphere:
    radius; mesh: its box's extents), ``low``/``high`` the box around it in the root's
    frame, as (x, y, z) corners; ``placed`` its pose in its link's frame and ``own`` its
    box in its own frame, (low, high), from which :attr:`local` is worked out if asked."""

    __slots__ = ("link", "kind", "tag", "element", "size", "low", "high", "placed", "own")

    def __init__(self, link: str, kind: str, tag: str, element: object, size: tuple,
                 low: tuple, high: tuple, placed: tuple, own: tuple):
        self.link = link
        self.kind = kind
        self.tag = tag
        self.element = element  # the shape element (<box>, <mesh>, ...)
        self.size = size
        self.low = low
        self.high = high
        self.placed = placed
        self.own = own

    @property
    def local(self) -> tuple:
        """(low, high) of the box around the shape in its link's frame."""
        return placed_box(self.placed, *self.own)


class RestPose:
    """The rest pose as the plausibility rules read it (:mod:`.rest_pose_arrays` makes the
    same from numpy arrays for a large robot). Only the shapes a rule looks at one by one
    are kept (meshes, and the shapes of links with an inertia that the inertia rules
    read: their collision shapes, else their visual ones); the boxes around all of them,
    and the widest, are kept as they are placed."""

    def __init__(self):
        self.poses: dict = {}  # link -> (rotation 9-tuple, origin)
        self.shapes: list[Shape] = []
        self.inertials: dict = {}  # link -> LinkShapes.inertial
        self.low = [float("inf")] * 3  # around every shape
        self.high = [float("-inf")] * 3
        self.rest_low = [float("inf")] * 3  # but meshes
        self.rest_high = [float("-inf")] * 3
        self.widest: tuple | None = None  # (span, Shape)
        self.judged: dict = {}  # link -> the kind of shape its inertia is read with
        self.collision_low: dict = {}  # link -> the lowest z of its collision shapes

    def lowest_collision(self, links) -> dict:
        """link -> the lowest z of its collision shapes, of ``links`` that have one whose
        size is known."""
        return {name: self.collision_low[name] for name in links
                if name in self.collision_low}

    def extents(self) -> tuple | None:
        """(x, y, z) of the box around every shape, None if there is none."""
        if self.widest is None:
            return None
        return tuple(h - lo for lo, h in zip(self.low, self.high, strict=True))

    def largest(self) -> Shape | None:
        """The shape whose box is the widest."""
        return None if self.widest is None else self.widest[1]

    def meshes(self) -> list[Shape]:
        return [shape for shape in self.shapes if shape.tag == "mesh"]

    def rest_box(self) -> tuple:
        """(low, high) around every shape but the meshes, and every link's frame."""
        points = [t for _r, t in self.poses.values()]
        if self.rest_low[0] <= self.rest_high[0]:
            points += [tuple(self.rest_low), tuple(self.rest_high)]
        if not points:
            return None, None
        return (tuple(min(p[i] for p in points) for i in range(3)),
                tuple(max(p[i] for p in points) for i in range(3)))

    def judged_links(self):
        """(link, its <inertial>, its shapes) of every link with both."""
        by_link: dict[str, list[Shape]] = {}
        for shape in self.shapes:
            by_link.setdefault(shape.link, []).append(shape)
        for name, inertial in self.inertials.items():
            own = [shape for shape in by_link.get(name, ()) if shape.kind == self.judged[name]]
            if own:
                yield name, inertial, own


def span(low, high) -> float:
    """The widest side of the box low..high."""
    return max(high[0] - low[0], high[1] - low[1], high[2] - low[2])


def firsts(element) -> dict:
    """Tag -> the first child of that tag (urdfdom reads the first; lxml's find() is slow
    Python, a loop over the children is not)."""
    found = {}
    for child in element:
        tag = child.tag
        if tag.__class__ is str and tag not in found:
            found[tag] = child
    return found


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


def frame_of(xyz: tuple, rpy: tuple) -> tuple:
    """(rotation, translation) of read numbers; identity rotations share one tuple."""
    if rpy == ZERO:
        return IDENTITY[0], xyz
    roll, pitch, yaw = rpy
    cr, sr, cp, sp = cos(roll), sin(roll), cos(pitch), sin(pitch)
    cy, sy = cos(yaw), sin(yaw)
    return ((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,
             sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,
             -sp, cp * sr, cp * cr), xyz)


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


def own_box(tag: str, dims: tuple, element, mesh_bounds: dict) -> tuple | None:
    """(size, (low, high)) of a shape in its own frame from its read numbers, or None
    (a mesh whose box is not known, a size that is not positive)."""
    if tag == "box":
        if min(dims) <= 0:
            return None
        x, y, z = dims
        return dims, ((-x / 2, -y / 2, -z / 2), (x / 2, y / 2, z / 2))
    if tag == "cylinder":
        radius, length = dims
        if not (radius > 0 and length > 0):
            return None
        return dims, ((-radius, -radius, -length / 2), (radius, radius, length / 2))
    if tag == "sphere":
        radius = dims[0]
        return (dims, ((-radius,) * 3, (radius,) * 3)) if radius > 0 else None
    known = mesh_bounds.get(element)
    if tag != "mesh" or known is None:
        return None
    ends = [sorted((lo * s, h * s)) for lo, h, s in zip(*known, dims, strict=True)]
    low, high = tuple(e[0] for e in ends), tuple(e[1] for e in ends)
    return tuple(h - lo for lo, h in zip(low, high, strict=True)), (low, high)


def rest_pose(robot, tree, shapes_of: dict, mesh_bounds: dict) -> RestPose:
    """The rest pose of a robot whose tree is sound (``tree.is_sound``); ``shapes_of``
    maps a link to its LinkShapes, ``mesh_bounds`` a ``<mesh>`` element to its box in its
    own frame (None: unknown)."""
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
    low, high, rest_low, rest_high = result.low, result.high, result.rest_low, result.rest_high
    widest = 0.0
    for link in robot.links:
        pose, held = poses.get(link.name), shapes_of.get(link.name)
        if pose is None or held is None:
            continue
        held = own_elements(held)
        placed_shapes = []
        for kind, element, xyz, rpy, dims in held.bodies:
            tag = element.tag
            known = own_box(tag, dims, element, mesh_bounds)
            if known is None:
                continue
            placed = frame_of(xyz, rpy)
            size, own = known
            box_low, box_high = placed_box(compose(pose, placed), *own)
            placed_shapes.append((kind, tag, element, size, box_low, box_high, placed, own))
            if kind == "collision" and box_low[2] < result.collision_low.get(link.name, inf):
                result.collision_low[link.name] = box_low[2]
            for i in range(3):
                if box_low[i] < low[i]:
                    low[i] = box_low[i]
                if box_high[i] > high[i]:
                    high[i] = box_high[i]
                if tag != "mesh":
                    if box_low[i] < rest_low[i]:
                        rest_low[i] = box_low[i]
                    if box_high[i] > rest_high[i]:
                        rest_high[i] = box_high[i]
        # The inertia rules read a link's collision shapes, else its visual ones.
        judged = None
        if held.inertial is not None:
            result.inertials[link.name] = held.inertial
            judged = "collision" if any(p[0] == "collision" for p in placed_shapes) \
                else "visual"
            result.judged[link.name] = judged
        for kind, tag, element, size, box_low, box_high, placed, own in placed_shapes:
            shape = None
            if tag == "mesh" or kind == judged:
                shape = Shape(link.name, kind, tag, element, size, box_low, box_high, placed,
                              own)
                append(shape)
            across = span(box_low, box_high)
            if result.widest is None or across > widest:
                widest = across
                result.widest = (across, shape or Shape(link.name, kind, tag, element, size,
                                                        box_low, box_high, placed, own))
    return result
