"""Plausibility: the robot's size, and the mistakes of unit and inertia that a URDF parser
accepts and a simulator explodes on. Judged on the rest pose (:mod:`.rest_pose`); lengths
in metres, masses in kg, inertias in kg m².

* W211 **robot-huge**: the robot is more than BUILDING_M across (a mesh in millimetres or
  inches read as metres makes a 0.3 m robot 50 to 300 m long).
* W212 **mesh-scale**: one mesh is more than MESH_LARGER times larger, or under
  1/MESH_SMALLER the size of the rest of the robot (every other shape, and the link frames:
  where the joints put the parts): millimetres read as metres, or a scale applied twice.
  Parts are often far smaller than their robot (a screw), never far larger.
* W213 **inertia-size**: a link's inertia against a solid of its mass filling its
  collision shapes (its visual shapes when it has none), compared by the trace (the sum
  of the principal moments, which no rotation changes): over INERTIA_ABOVE times is more
  than its mass can have inside that space (all of it at the far corners gives 3 times
  the solid box); under 1/INERTIA_BELOW_SHAPE of the formula of its one box, cylinder or
  sphere, or 1/INERTIA_BELOW_BOX of the box around several shapes or a mesh (a box is
  looser), is a mass packed at a point, which makes the part spin up like a top; that
  one is said of moving links only (a fixed link's inertia is added to its parent's,
  where too little of it changes nothing).
* W214 **wheel-inertia**: a wheel (a link a continuous joint turns, round about that
  joint's axis: one cylinder along it, or a sphere, or shapes whose box is round about a
  coordinate axis) whose moment about its axle is over WHEEL_ABOVE m r² (a ring, all mass
  at the rim, has m r²) or under WHEEL_BELOW m r² (a tenth of a solid disc's m r² / 2).
  Real wheels lie between 0.3 and 0.7 m r². A wheel is judged by this rule, not W213.
"""

from __future__ import annotations

from math import sqrt

from .context import Reporter
from .inertia import principal_moments
from .rest_pose import ZERO, RestPose, Shape, firsts, frame_of, span
from .structure import moving_links

BUILDING_M = 20.0
MESH_LARGER = 100.0
MESH_SMALLER = 1000.0
INERTIA_ABOVE = 10.0
INERTIA_BELOW_SHAPE = 10.0
INERTIA_BELOW_BOX = 100.0
WHEEL_ABOVE = 1.25
WHEEL_BELOW = 0.05
PARALLEL = 0.99  # |cos| between a cylinder's axis and the axle to call them parallel


def check_plausibility(robot, tree, pose: RestPose, report: Reporter) -> None:
    """The rules on ``pose`` (a RestPose, or the RestPose-like ArraysPose of a large
    robot, which hands over only the links it could not clear itself)."""
    _robot_size(robot, pose, report)
    _mesh_scales(pose, report)
    moving = moving_links(tree)
    for name, inertial, shapes in pose.judged_links():
        _inertia(name, inertial, shapes, tree, name in moving, report)


def metres(value: float) -> str:
    return f"{value:.3g} m" if value >= 0.01 else f"{value * 1000:.3g} mm"


def _robot_size(robot, pose: RestPose, report: Reporter) -> None:
    extents = pose.extents()
    if extents is None or max(extents) <= BUILDING_M:
        return
    biggest = pose.largest()
    across = span(biggest.low, biggest.high)
    hint = "a mesh in millimetres or inches read as metres?" if biggest.tag == "mesh" else \
        "a length in centimetres or millimetres written as metres?"
    report.add("W211", robot.element, f"the robot is {_sizes(extents)} m in its rest pose, "
               f"larger than a building; its largest part: link '{biggest.link}' "
               f"{biggest.kind} {_named(biggest)}, {metres(across)} across ({hint})")


def _named(shape: Shape) -> str:
    if shape.tag == "mesh":
        return f"mesh '{shape.element.get('filename')}'"
    return f"<{shape.tag}>"


def _mesh_scales(pose: RestPose, report: Reporter) -> None:
    meshes = pose.meshes()
    if not meshes:
        return
    low, high = pose.rest_box()
    frames = [] if low is None else [low, high]
    # The box around everything but one mesh: the rest, with each mesh left out in turn.
    before = _running(meshes, frames)
    after = _running(meshes[::-1], frames)[::-1]
    for index, shape in enumerate(meshes):
        rest_low, rest_high = _joined(before[index], after[index + 1])
        if rest_low is None:
            continue
        rest, size = span(rest_low, rest_high), max(shape.size)
        if rest <= 0 or size <= 0:
            continue
        if size > MESH_LARGER * rest:
            report.add("W212", shape.element, f"link '{shape.link}': mesh "
                       f"'{shape.element.get('filename')}' is {metres(size)} across, "
                       f"{size / rest:.0f} times the rest of the robot ({metres(rest)}): a mesh "
                       "in millimetres or inches read as metres? (give the <mesh> a scale, "
                       "such as scale=\"0.001 0.001 0.001\")")
        elif size * MESH_SMALLER < rest:
            report.add("W212", shape.element, f"link '{shape.link}': mesh "
                       f"'{shape.element.get('filename')}' is {metres(size)} across, 1/"
                       f"{rest / size:.0f} of the rest of the robot ({metres(rest)}): a scale "
                       "applied twice, or metres read as millimetres?")


def _running(shapes: list[Shape], points: list) -> list:
    """[box around points and shapes[:i]] for i in 0..len(shapes)."""
    low = tuple(min(p[i] for p in points) for i in range(3)) if points else None
    high = tuple(max(p[i] for p in points) for i in range(3)) if points else None
    boxes = [(low, high)]
    for shape in shapes:
        low, high = _joined((low, high), (shape.low, shape.high))
        boxes.append((low, high))
    return boxes


def _joined(a: tuple, b: tuple) -> tuple:
    if a[0] is None:
        return b
    if b[0] is None:
        return a
    return (tuple(map(min, a[0], b[0])), tuple(map(max, a[1], b[1])))


def _inertia(name: str, inertial: tuple, shapes: list[Shape], tree, moving: bool,
             report: Reporter) -> None:
    """W213, or W214 for a wheel; ``inertial`` is (element, mass, moments, rpy). A tensor
    that is not positive definite is W204's, not these rules': looked at only before a
    warning, as most links are within every bound."""
    element, mass, moments, rpy = inertial
    if mass <= 0:
        return
    own = [s for s in shapes if s.kind == "collision"] or shapes
    wheel = _wheel(name, own, tree)
    if wheel is not None:
        _wheel_inertia(name, element, frame_of(ZERO, rpy), mass, moments, wheel, report)
        return
    trace = moments[0] + moments[3] + moments[5]  # the sum of the principal moments
    single = len(own) == 1 and own[0].tag != "mesh"
    if single:
        solid, below = solid_trace(own[0], mass), INERTIA_BELOW_SHAPE
    else:
        low, high = _local_union(own)
        size = tuple(h - lo for lo, h in zip(low, high, strict=True))
        solid, below = mass * sum(v * v for v in size) / 6, INERTIA_BELOW_BOX
    if solid <= 0:
        return
    ratio = trace / solid
    above, under = ratio > INERTIA_ABOVE, ratio * below < 1 and moving
    if not (above or under) or principal_moments(*moments)[0] <= 0:
        return
    what = _described(own[0]) if single else \
        f"the box around its {own[0].kind} shapes ({_sizes(size)} m)"
    inertia = firsts(element)["inertia"]
    if above:
        report.add("W213", inertia, f"link '{name}': its inertia (trace {trace:.3g} kg m²) is "
                   f"{ratio:.0f} times that of a solid of {mass:g} kg filling {what} "
                   f"({solid:.3g} kg m²): more than its mass can have there")
    else:
        report.add("W213", inertia, f"link '{name}': its inertia (trace {trace:.3g} kg m²) is "
                   f"1/{1 / ratio:.0f} of that of a solid of {mass:g} kg filling {what} "
                   f"({solid:.3g} kg m²): too small for its size")


def _local_union(shapes: list[Shape]) -> tuple:
    """(low, high) around the shapes in their link's frame."""
    boxes = [s.local for s in shapes]
    lows, highs = [box[0] for box in boxes], [box[1] for box in boxes]
    return (tuple(min(v[i] for v in lows) for i in range(3)),
            tuple(max(v[i] for v in highs) for i in range(3)))


def _sizes(values) -> str:
    return " x ".join(f"{v:.3g}" for v in values)


def _described(shape: Shape) -> str:
    if shape.tag == "box":
        return f"its {shape.kind} box ({_sizes(shape.size)} m)"
    if shape.tag == "cylinder":
        return (f"its {shape.kind} cylinder (radius {shape.size[0]:.3g} m, length "
                f"{shape.size[1]:.3g} m)")
    return f"its {shape.kind} sphere (radius {shape.size[0]:.3g} m)"


def solid_trace(shape: Shape, mass: float) -> float:
    """Ixx + Iyy + Izz of a solid box, cylinder or sphere of ``mass``."""
    if shape.tag == "box":
        return mass * sum(v * v for v in shape.size) / 6
    if shape.tag == "cylinder":
        radius, length = shape.size
        return mass * (6 * radius * radius + length * length) / 6
    return 1.2 * mass * shape.size[0] ** 2


def _wheel(name: str, shapes: list[Shape], tree) -> tuple | None:
    """(axle unit vector in the link frame, radius) when ``name`` is a wheel, else None."""
    joints = tree.parent_joints.get(name) or []
    if len(joints) != 1 or joints[0].type != "continuous":
        return None
    axis = _axis(joints[0])
    if axis is None:
        return None
    if len(shapes) == 1 and shapes[0].tag in ("cylinder", "sphere"):
        shape = shapes[0]
        if shape.tag == "sphere":
            return axis, shape.size[0]
        rotation = shape.placed[0]  # the cylinder's axis is its frame's z
        along = abs(rotation[2] * axis[0] + rotation[5] * axis[1] + rotation[8] * axis[2])
        return (axis, shape.size[0]) if along > PARALLEL else None
    along = max(range(3), key=lambda i: abs(axis[i]))
    if abs(axis[along]) < PARALLEL:
        return None
    low, high = _local_union(shapes)
    across = [high[i] - low[i] for i in range(3) if i != along]
    if min(across) <= 0 or max(across) > 1.1 * min(across):  # not round about the axle
        return None
    return axis, max(across) / 2


def _axis(joint) -> tuple | None:
    element = joint.parts.get("axis")
    text = "1 0 0" if element is None else element.get("xyz", "0 0 0")
    try:
        x, y, z = (float(v) for v in text.split())
    except ValueError:
        return None
    length = sqrt(x * x + y * y + z * z)
    return None if length == 0 else (x / length, y / length, z / length)


def _wheel_inertia(name: str, inertial, placed: tuple, mass: float, moments: tuple,
                   wheel: tuple, report: Reporter) -> None:
    (ax, ay, az), radius = wheel
    ixx, ixy, ixz, iyy, iyz, izz = moments
    r = placed[0]
    # The axle in the inertia's frame (Rᵀ a), then aᵀ I a.
    x = r[0] * ax + r[3] * ay + r[6] * az
    y = r[1] * ax + r[4] * ay + r[7] * az
    z = r[2] * ax + r[5] * ay + r[8] * az
    axle = (ixx * x * x + iyy * y * y + izz * z * z
            + 2 * (ixy * x * y + ixz * x * z + iyz * y * z))
    ring = mass * radius * radius
    if ring <= 0:
        return
    share = axle / ring
    if WHEEL_BELOW <= share <= WHEEL_ABOVE or principal_moments(*moments)[0] <= 0:
        return
    element = firsts(inertial)["inertia"]
    if share > WHEEL_ABOVE:
        report.add("W214", element, f"link '{name}' is a wheel of {mass:g} kg and radius "
                   f"{radius:.3g} m: its moment about the axle, {axle:.3g} kg m², is "
                   f"{share:.3g} m r², more than a ring of that mass and radius has (m r² = "
                   f"{ring:.3g}); a solid disc has m r² / 2")
    else:
        report.add("W214", element, f"link '{name}' is a wheel of {mass:g} kg and radius "
                   f"{radius:.3g} m: its moment about the axle, {axle:.3g} kg m², is "
                   f"{share:.2g} m r², under a tenth of a solid disc's (m r² / 2 = "
                   f"{ring / 2:.3g})")
