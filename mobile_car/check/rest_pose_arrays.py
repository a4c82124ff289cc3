"""The rest pose of a large robot with numpy: what :mod:`.rest_pose` works out link by link,
for every link at once.

From 2,000 links up (checker.LARGE_ROBOT), composing poses and boxes in Python costs as
much as the rest of the check (a 3x3 product is 45 Python operations, a link has three),
while importing numpy costs a few hundredths of a second. The numbers come read already
(the LinkShapes check read while checking the links); here the rotations are made for
all shapes at once, and the poses composed down the tree by doubling (each link's pose to
its ancestor, then to that one's ancestor: log2 of the depth steps, also for a
20,000-link chain).

:class:`ArraysPose` answers what the plausibility rules ask of a rest pose. For the
inertia rules it works out every link's ratios in bulk (the trace against its solid, a
wheel's moment about its axle against m r²) and hands over only the links within 1% of a
bound or beyond it; :mod:`.plausibility` judges those link by link, as it judges every
link of a small robot, so the verdicts and messages are the same
(``tests/check/test_plausibility_paths.py`` holds the two paths to it).
"""

from __future__ import annotations

import numpy as np

from . import plausibility as rules
from .joint_skeletons import AXIS_XYZ
from .rest_pose import ZERO, Shape, frame_of, own_box, own_elements

_SLACK = 1.01  # candidates a hair beyond each bound: the link's own judgement decides


class ArraysPose:
    # A plain class, not a dataclass: never compared, and a dataclass costs the run that
    # imports it the dataclasses module and the compiling of its methods (values.py).
    def __init__(self, low: np.ndarray, high: np.ndarray, local_low: np.ndarray,
                 local_high: np.ndarray, own_low: np.ndarray, own_high: np.ndarray,
                 frames_low: np.ndarray, frames_high: np.ndarray, bodies: list,
                 tags: np.ndarray, dims: np.ndarray, judged: list | None = None):
        self.low = low                  # (shapes, 3) boxes in the root's frame
        self.high = high
        self.local_low = local_low      # (shapes, 3) boxes in the link's frame
        self.local_high = local_high
        self.own_low = own_low          # (shapes, 3) boxes in the shape's own frame
        self.own_high = own_high
        self.frames_low = frames_low    # (3,) around every link's origin
        self.frames_high = frames_high
        self.bodies = bodies  # per shape: (link, kind, element, xyz, rpy, LinkShapes, index)
        self.tags = tags      # per shape: 0 box, 1 cylinder, 2 sphere, 3 mesh
        self.dims = dims      # (shapes, 3): box size, (r, r, length), (r, r, r); meshes 0
        self.judged = [] if judged is None else judged  # (link, <inertial>, [Shape]) to judge

    def extents(self) -> tuple | None:
        if not len(self.low):
            return None
        return tuple(float(v) for v in self.high.max(axis=0) - self.low.min(axis=0))

    def shape(self, index: int) -> Shape:
        """Shape ``index`` as :func:`.rest_pose.rest_pose` makes it."""
        link, kind, element, xyz, rpy, held, order = self.bodies[index]
        if held.twin is not None:  # a repeated link's: its own element, for messages
            element = own_elements(held).bodies[order][1]
        own = (tuple(self.own_low[index].tolist()), tuple(self.own_high[index].tolist()))
        tag, (a, b, c) = int(self.tags[index]), self.dims[index].tolist()
        size = ((a, b, c), (a, c), (a,), tuple(h - lo for lo, h in zip(*own, strict=True)))[tag]
        return Shape(link, kind, element.tag, element, size, tuple(self.low[index].tolist()),
                     tuple(self.high[index].tolist()), frame_of(xyz, rpy), own)

    def lowest_collision(self, links) -> dict:
        """As :meth:`.rest_pose.RestPose.lowest_collision`."""
        wanted, lowest = set(links), {}
        for index, (link, kind, *_rest) in enumerate(self.bodies):
            if kind == "collision" and link in wanted:
                z = float(self.low[index, 2])
                lowest[link] = min(z, lowest.get(link, z))
        return lowest

    def largest(self) -> Shape | None:
        if not len(self.low):
            return None
        return self.shape(int(np.argmax((self.high - self.low).max(axis=1))))

    def meshes(self) -> list[Shape]:
        return [self.shape(int(i)) for i in np.flatnonzero(self.tags == 3)]

    def rest_box(self) -> tuple:
        keep = self.tags != 3
        low, high = self.frames_low, self.frames_high
        if keep.any():
            low = np.minimum(low, self.low[keep].min(axis=0))
            high = np.maximum(high, self.high[keep].max(axis=0))
        return tuple(low.tolist()), tuple(high.tolist())

    def judged_links(self):
        return iter(self.judged)


def _rotations(rpy: np.ndarray) -> np.ndarray:
    """(n, 3, 3) from fixed-axis roll, pitch, yaw: Rz(yaw) Ry(pitch) Rx(roll)."""
    cr, cp, cy = np.cos(rpy).T
    sr, sp, sy = np.sin(rpy).T
    return np.stack([cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,
                     sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,
                     -sp, cp * sr, cp * cr], axis=1).reshape(-1, 3, 3)


def _numbers(texts: list, width: int) -> np.ndarray:
    """(n, width) from texts of ``width`` numbers each (None: zeros); ValueError if one
    is not that many numbers."""
    zero = " ".join(["0"] * width)
    words = " ".join(zero if text is None else text for text in texts).split()
    if len(words) != width * len(texts):
        raise ValueError(f"not {width} numbers each")
    return np.array(words, dtype=float).reshape(-1, width)


def _axis_text(joint) -> str:
    """The text of a joint's axis as urdfdom reads it: 1 0 0 without an <axis>, 0 0 0 for
    one without xyz (a joint read by its skeleton has it read already)."""
    if joint.tags is not None:
        if "axis" not in joint.tags:
            return "1 0 0"
        text = joint.texts[AXIS_XYZ]
        return "0 0 0" if text is None else text
    axis = joint.parts.get("axis")
    return "1 0 0" if axis is None else axis.get("xyz", "0 0 0")


def _rows(flat: list, width: int) -> np.ndarray:
    """(n, width) from the floats of n rows gathered one after the other in ``flat``
    (each row's tuples added to one list as they are read): one pass, which np.array
    over a list of tuples is not (it first works out their nesting), nor a chain over
    them: a few hundredths of a second on 20,000 links."""
    return np.fromiter(flat, dtype=float, count=len(flat)).reshape(-1, width)


def _origin(joint) -> tuple | None:
    """(xyz, rpy) of a joint's <origin> read here, zeros where absent; None where one is
    not three numbers as ``float`` reads them."""
    origin = joint.parts.get("origin")
    if origin is None:
        return ZERO, ZERO
    read = []
    for text in (origin.get("xyz"), origin.get("rpy")):
        if text is None:
            read.append(ZERO)
            continue
        words = text.split()
        try:
            read.append(tuple(map(float, words)))
        except ValueError:
            return None
        if len(words) != 3:
            return None
    return read[0], read[1]


def _compose(parent: np.ndarray, rotation: np.ndarray, shift: np.ndarray) -> tuple:
    """Every link's pose in the root's frame from its pose in its parent's (doubling:
    each pose to its ancestor composed with that ancestor's, until every ancestor is the
    root, whose pose is the identity and whose parent is itself)."""
    while True:
        grand = parent[parent]
        if np.array_equal(grand, parent):
            return rotation, shift
        shift = np.einsum("nij,nj->ni", rotation[parent], shift) + shift[parent]
        rotation = rotation[parent] @ rotation
        parent = grand


_TAGS = {"box": 0, "cylinder": 1, "sphere": 2, "mesh": 3}


def rest_pose_arrays(robot, tree, shapes_of: dict, mesh_bounds: dict,
                     origins: dict | None = None) -> ArraysPose | None:
    """The ArraysPose of a robot whose tree is sound, from what each link holds (the
    LinkShapes in ``shapes_of``, by link name) and the joints' origins read already
    (``origins``: joint -> (xyz, rpy), as check_joints returns them; the others are read
    here); None where a joint's origin does not read as ``float`` reads it (then
    :func:`.rest_pose.rest_pose` decides, element by element)."""
    names = {link.name: index for index, link in enumerate(robot.links)}
    count = len(names)
    origins = origins or {}
    # Gathered in lists and put into arrays at once: an item set in an array one by one
    # costs more than a list's append.
    parents, children, flat, turning, axes = [], [], [], [], []
    origin_of = origins.get
    for joints in tree.children.values():
        for joint in joints:
            child = names[joint.child]
            parents.append(names[joint.parent])
            children.append(child)
            origin = origin_of(joint)
            if origin is None:
                origin = _origin(joint)
                if origin is None:
                    return None
            flat += origin[0]
            flat += origin[1]
            if joint.type == "continuous":
                turning.append(child)
                axes.append(_axis_text(joint))
    try:
        axes = _numbers(axes, 3)
    except ValueError:
        return None
    parent = np.arange(count)
    parent[children] = parents
    joint_origins = _rows(flat, 6)
    joint_rotation, joint_shift = _rotations(joint_origins[:, 3:6]), joint_origins[:, 0:3]
    bodies, links, tags, numbers, meshes = [], [], [], [], {}
    inertial_rows, inertials, masses, moments = [], [], [], []  # moments: the six, then rpy
    # Shape element -> its tag's number: the links read by one skeleton share their first
    # one's elements (link_skeletons.py), whose tag lxml would make again for each.
    tag_of: dict = {}
    shapes_get = shapes_of.get
    for index, link in enumerate(robot.links):
        name = link.name
        held = shapes_get(name)
        if held is None:
            continue
        inertial = held.inertial
        if inertial is not None:
            inertial_rows.append(index)
            inertials.append(held)
            masses.append(inertial[1])
            moments += inertial[2]
            moments += inertial[3]
        for order, (kind, element, xyz, rpy, dims) in enumerate(held.bodies):
            tag = tag_of.get(element)
            if tag is None:
                tag = tag_of[element] = _TAGS.get(element.tag, -1)
            if tag == 3:
                known = own_box("mesh", dims, element, mesh_bounds)
                if known is None:
                    continue
                meshes[len(bodies)] = known[1]
                dims = ZERO
            elif tag < 0:
                continue
            bodies.append((name, kind, element, xyz, rpy, held, order))
            links.append(index)
            tags.append(tag)
            numbers += xyz
            numbers += rpy
            numbers += (dims * 3)[:3]  # (r,) -> r r r; (r, l) -> r l r
    rotation = np.tile(np.eye(3), (count, 1, 1))
    shift = np.zeros((count, 3))
    rotation[children], shift[children] = joint_rotation, joint_shift
    rotation, shift = _compose(parent, rotation, shift)
    links, tags = np.array(links, dtype=int), np.array(tags, dtype=int)
    numbers = _rows(numbers, 9)
    body_shift, body_rotation = numbers[:, 0:3], _rotations(numbers[:, 3:6])
    dims = numbers[:, 6:9]
    # A shape's box in its own frame: a box's size, a cylinder's (r, length, r) as
    # (r, r, length), a sphere's (r, r, r), about their centre; meshes as their files say.
    cylinder, sphere = (tags == 1)[:, None], (tags == 2)[:, None]
    dims = np.where(cylinder, dims[:, [0, 0, 1]], dims)
    half = np.where(cylinder, dims * [1.0, 1.0, 0.5], np.where(sphere, dims, dims / 2))
    centre = np.zeros_like(dims)
    for i, (low, high) in meshes.items():
        centre[i] = [(a + b) / 2 for a, b in zip(low, high, strict=True)]
        half[i] = [(b - a) / 2 for a, b in zip(low, high, strict=True)]
    local_centre = np.einsum("nij,nj->ni", body_rotation, centre) + body_shift
    local_half = np.einsum("nij,nj->ni", np.abs(body_rotation), half)
    placed = rotation[links]
    world_centre = np.einsum("nij,nj->ni", placed, local_centre) + shift[links]
    world_half = np.einsum("nij,nj->ni", np.abs(placed @ body_rotation), half)
    pose = ArraysPose(world_centre - world_half, world_centre + world_half,
                      local_centre - local_half, local_centre + local_half,
                      centre - half, centre + half, shift.min(axis=0), shift.max(axis=0),
                      bodies, tags, dims)
    doubtful = _doubtful(pose, links, count, np.array(turning, dtype=int), axes,
                         np.array(inertial_rows, dtype=int), masses, _rows(moments, 9),
                         body_rotation)
    shapes: dict[str, list] = {}
    for i in np.flatnonzero(doubtful[links]).tolist():
        shapes.setdefault(bodies[i][0], []).append(pose.shape(i))
    pose.judged = [(robot.links[row].name, own_elements(held).inertial,
                    shapes[robot.links[row].name])
                   for row, held in zip(inertial_rows, inertials, strict=True)
                   if robot.links[row].name in shapes]
    return pose


def _doubtful(pose: ArraysPose, links: np.ndarray, count: int, turning: np.ndarray,
              axes: np.ndarray, rows: np.ndarray, masses: list, moments: np.ndarray,
              body_rotation: np.ndarray) -> np.ndarray:
    """Per link: True where its inertia is within _SLACK of a W213 or W214 bound, or
    beyond one (its own judgement then decides). ``masses`` and ``moments``: per row of
    ``rows``, its inertial's mass and nine numbers (the six moments, then its rpy), read
    with the shapes. ``body_rotation``: each shape's rotation in its link's frame."""
    if not len(pose.tags):
        return np.zeros(count, dtype=bool)
    collision = np.array([body[1] == "collision" for body in pose.bodies], dtype=bool)
    has_collision = np.zeros(count, dtype=bool)
    has_collision[links[collision]] = True
    own = np.flatnonzero(collision == has_collision[links])  # collision shapes, else visual
    own = own[np.argsort(links[own], kind="stable")]
    shapes_of = np.bincount(links[own], minlength=count)
    low = np.full((count, 3), np.nan)
    high = np.full((count, 3), np.nan)
    if len(own):
        starts = np.flatnonzero(np.r_[True, np.diff(links[own]) != 0])
        first = links[own][starts]
        low[first] = np.minimum.reduceat(pose.local_low[own], starts)
        high[first] = np.maximum.reduceat(pose.local_high[own], starts)
    extent = high - low
    one = np.zeros(count, dtype=int)
    one[links[own]] = own  # the link's shape, where it has one
    tag, dims = pose.tags[one], pose.dims[one]
    radius, length = dims[:, 0], dims[:, 2]
    primitive = (shapes_of == 1) & (tag != 3)
    per_kg = np.where(primitive, np.select(
        [tag == 0, tag == 1], [(dims * dims).sum(axis=1) / 6,
                               (6 * radius * radius + length * length) / 6],
        default=1.2 * radius * radius), (extent * extent).sum(axis=1) / 6)
    below = np.where(primitive, rules.INERTIA_BELOW_SHAPE, rules.INERTIA_BELOW_BOX)
    doubtful = np.zeros(count, dtype=bool)
    if not len(rows):
        return doubtful
    mass = np.array(masses, dtype=float)
    turn = _rotations(moments[:, 6:9])
    ixx, ixy, ixz, iyy, iyz, izz = moments[:, 0:6].T
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = (ixx + iyy + izz) / (mass * per_kg[rows])
        doubtful[rows] = ~((ratio * _SLACK <= rules.INERTIA_ABOVE)
                           & (ratio * below[rows] >= _SLACK))
        # A wheel: the moment about its axle against m r², r its radius as the rule
        # takes it (one cylinder or sphere, else half the box across the axle).
        wheel = np.zeros(count, dtype=bool)
        wheel[turning] = True
        axle = np.zeros((count, 3))
        axle[turning] = axes / np.linalg.norm(axes, axis=1, keepdims=True)
        # One cylinder is a wheel only turning about its own axis (its frame's z): one
        # clearly across its axle is judged by W213 alone, above (plausibility._wheel).
        # Without this, every such link of a CAD export was handed over to be cleared.
        along = np.abs(np.einsum("ni,ni->n", body_rotation[one][:, :, 2], axle))
        wheel &= ~((shapes_of == 1) & (tag == 1) & (along < rules.PARALLEL - 1e-9))
        across = np.abs(axle).argmax(axis=1)
        spread = np.where(np.arange(3) == across[:, None], 0.0, extent).max(axis=1) / 2
        r = np.where((shapes_of == 1) & ((tag == 1) | (tag == 2)), radius, spread)
        a = np.einsum("nji,nj->ni", turn, axle[rows])  # the axle in the inertia's frame
        x, y, z = a.T
        about = (ixx * x * x + iyy * y * y + izz * z * z
                 + 2 * (ixy * x * y + ixz * x * z + iyz * y * z))
        share = about / (mass * r[rows] ** 2)
        doubtful[rows] |= wheel[rows] & ~((share * _SLACK <= rules.WHEEL_ABOVE)
                                          & (share >= rules.WHEEL_BELOW * _SLACK))
    return doubtful
