"""E119 **mass-implausible**: masses no built robot has, which a simulator still drives.

A URDF parser reads any mass; a typo of units or a digit (1000 kg for a 28 g TurtleBot3
wheel) makes a robot that drives in simulation and nowhere else. Two tests, each wide
enough that no released robot comes near it (the figures of the 24 robots tried are in
docs/rules.md):

* a part a continuous joint turns (a wheel) weighing over WHEEL_OVER_REST times the rest
  of the robot (all of it but such parts): the heaviest wheels built weigh about as much
  as the robot they carry (a hub motor's), not five times as much (the heaviest of 24
  released robots tried: 0.36 times, Hunter 2's);
* a density no material has: mass over the volume of its geometry above DENSEST kg/m³
  (osmium, the densest element, is 22 590) or below LIGHTEST kg/m³ (air is 1.2; a foam is
  30). The volume is its collision shapes', the volume simulators give it; a link with
  none is not judged by density, as its visuals may be a marker or a stand-in (sdformat's
  own test robots draw a 1000 kg link as a 0.1 x 0.1 x 1 m bar and load it): boxes,
  cylinders and spheres exactly, a mesh by the box around it, which can only be
  larger, so "too dense" is said only when even the largest volume the shapes could
  have is too small. "Too light" needs the smallest volume they could have, which only
  a box, cylinder or sphere gives (a mesh may be a thin shell); it is said of a link
  over TOKEN_MASS only, as a link of a gram or less is a token mass on a frame or a
  sensor (Gazebo needs one), not a part someone weighed. Shapes that all fit in a
  PLACEHOLDER cube are not judged either: released robots give their IMUs and sensor
  mounts a 1 mm or 1 cm box and a real mass (PR2's accelerometers, Summit XL's laser
  base, LIMO's IMU), a stand-in, not a claim about the part's size. Shapes that are all
  thinner than SHEET are a surface, not a volume: "too dense" is not said of them (iCub's
  feet collide by a 1 mm sole plate under their 0.38 kg, as a contact patch; a part is
  never that thin and that heavy), "too light" still is, as a sheet only makes the
  volume smaller. Nor is "too dense" said of a link whose visual shapes have room for
  its mass (a mesh by its box): its collision shapes are then a contact stand-in smaller
  than the part (Unitree H1's 2.7 kg hip links collide by a disc 4 cm across and 1 cm
  thick), while a unit or digit wrong makes the mass too much for both.

Masses in kg, lengths in m.
"""

from __future__ import annotations

from math import pi

from .context import Reporter
from .rest_pose import firsts, own_box, own_elements
from .structure import moving_links

WHEEL_OVER_REST = 5.0
DENSEST = 25_000.0
LIGHTEST = 1.0
TOKEN_MASS = 0.001
PLACEHOLDER = 0.02  # m: shapes that all fit in a cube of this side are a placeholder
SHEET = 0.002  # m: shapes all thinner than this are a contact surface, not a volume


def check_masses(robot, tree, held: dict, mesh_bounds: dict, report: Reporter) -> None:
    """E119 on every link ``held`` (link -> LinkShapes) with a mass."""
    masses = {name: shapes.inertial[1] for name, shapes in held.items()
              if shapes.inertial is not None and shapes.inertial[1] > 0}
    total = sum(masses.values())
    turned = {joint.child for joint in robot.joints if joint.type == "continuous"}
    moving = moving_links(tree)
    wheels = {name for name in masses if name in turned and name in moving}
    # The robot the wheels carry: all of it but its wheels (two 1000 kg wheels must not
    # each count the other as the robot).
    rest = total - sum(masses[name] for name in wheels)
    tags: dict = {}  # shape element -> its tag (_density)
    for name, mass in masses.items():
        shapes = held[name]
        if name in wheels and 0 < rest < mass / WHEEL_OVER_REST:
            report.add("E119", _mass_element(shapes), f"link '{name}' turns on a continuous "
                       f"joint (a wheel) and weighs {mass:g} kg, {mass / rest:.0f} times the "
                       f"{rest:.3g} kg of the robot without its wheels: no wheel built is "
                       f"over {WHEEL_OVER_REST:g} times its robot (a unit or a digit wrong?)")
            continue
        _density(name, mass, shapes, mesh_bounds, report, tags)


def _mass_element(shapes):
    """Where a message about a link's mass points: its own <mass>, else its <inertial>
    (looked up only for a message: most links have none; a repeated link's elements are
    its twin's until own_elements maps them, which costs a walk of the link)."""
    inertial = own_elements(shapes).inertial[0]
    return firsts(inertial).get("mass", inertial)


def _density(name: str, mass: float, shapes, mesh_bounds: dict, report: Reporter,
             tags: dict) -> None:
    """E119 if ``mass`` is denser or lighter than its collision shapes can be; ``tags``
    keeps each shape element's tag (the links read by one skeleton share their first
    one's elements: lxml would make the tag again for each)."""
    largest, smallest = 0.0, 0.0  # the volume the shapes could have at most, at least
    across = 0.0
    for kind, shape, _xyz, _rpy, dims in shapes.bodies:
        tag = tags.get(shape)
        if tag is None:
            tag = tags[shape] = shape.tag
        if tag != "box" and tag != "cylinder" and tag != "sphere":
            _density_of_meshes(name, mass, shapes, mesh_bounds, report)
            return
        if kind != "collision":
            continue
        # own_box's sizes without building its box: what a 20,000-link robot saves
        if min(dims) <= 0:
            return
        volume = _volume(tag, dims)
        across = max(across, *dims) if tag == "box" else max(across, 2 * dims[0], dims[-1])
        largest += volume
        smallest = max(smallest, volume)
    _judge_density(name, mass, shapes, largest, smallest, across, mesh_bounds, report)


def _density_of_meshes(name: str, mass: float, shapes, mesh_bounds: dict,
                       report: Reporter) -> None:
    """:func:`_density` of a link with a shape other than a box, cylinder or sphere."""
    if shapes.twin is not None and any(body[1].tag == "mesh" for body in shapes.bodies):
        shapes = own_elements(shapes)  # a mesh's bounds are known by its own element
    bodies = [b for b in shapes.bodies if b[0] == "collision"]
    largest, smallest = 0.0, 0.0
    across = 0.0
    for _kind, shape, _xyz, _rpy, dims in bodies:
        extent = _extent(shape, dims, mesh_bounds)
        if extent is None:
            return  # a mesh of unknown size, a size not positive: no volume to judge by
        volume, size = extent
        across = max(across, size)
        largest += volume
        if shape.tag != "mesh":  # (a mesh's box is the most its volume can be, not least)
            smallest = max(smallest, volume)
    _judge_density(name, mass, shapes, largest, smallest, across, mesh_bounds, report)


def _judge_density(name: str, mass: float, shapes, largest: float, smallest: float,
                   across: float, mesh_bounds: dict, report: Reporter) -> None:
    if largest <= 0 or across <= PLACEHOLDER:  # fits in the cube, its side included
        return
    if mass / largest > DENSEST:
        # (asked only then: a sound robot's links are judged without looking further)
        if _thickest(shapes, mesh_bounds) < SHEET:
            return  # a contact surface, not the part's volume
        drawn = _visual_volume(shapes, mesh_bounds)
        if drawn is not None and mass / drawn <= DENSEST:
            return  # its collision shapes are a contact stand-in, its visuals the part
        visuals = f" and visual shapes of {_litres(drawn)}" if drawn else ""
        densest = mass / max(largest, drawn or 0.0)
        report.add("E119", _mass_element(shapes), f"link '{name}': {mass:g} kg in its collision "
                   f"shapes of {_litres(largest)}{visuals} is {densest:.3g} kg/m³ at least, "
                   f"denser than any material (osmium: 22 590 kg/m³; the bound is {DENSEST:g}): a "
                   "unit or a digit wrong?")
    elif smallest > 0 and mass > TOKEN_MASS and mass / smallest < LIGHTEST:
        report.add("E119", _mass_element(shapes), f"link '{name}': {mass:g} kg in its collision "
                   f"shapes of {_litres(smallest)} or more is {mass / smallest:.3g} kg/m³ at most, "
                   f"lighter than any solid (air: 1.2 kg/m³; the bound is {LIGHTEST:g}): "
                   "a unit or a digit wrong?")


def _visual_volume(shapes, mesh_bounds: dict) -> float | None:
    """The most volume the link's visual shapes could have (a mesh by its box), or None
    when it has none or one of unknown size."""
    volume = 0.0
    for kind, shape, _xyz, _rpy, dims in shapes.bodies:
        if kind != "visual":
            continue
        extent = _extent(shape, dims, mesh_bounds)
        if extent is None:
            return None
        volume += extent[0]
    return volume or None


def _extent(shape, dims: tuple, mesh_bounds: dict) -> tuple[float, float] | None:
    """(the most volume, the size across) of one shape: a box, cylinder or sphere by its
    own sizes, a mesh by its box; None where its size is unknown or not positive."""
    tag = shape.tag
    if tag == "box" or tag == "cylinder" or tag == "sphere":
        if min(dims) <= 0:
            return None
        return _volume(tag, dims), max(dims) if tag == "box" else max(2 * dims[0], dims[-1])
    box = own_box(tag, dims, shape, mesh_bounds)
    if box is None:
        return None
    (x, y, z), (low, high) = box
    return x * y * z, max(h - lo for lo, h in zip(low, high, strict=True))


def _volume(tag: str, dims: tuple) -> float:
    """The volume of a box, cylinder or sphere of positive size (own_box said so)."""
    if tag == "box":
        x, y, z = dims
        return x * y * z
    if tag == "cylinder":
        radius, length = dims
        return pi * radius * radius * length
    return 4 / 3 * pi * dims[0] ** 3


def _thickest(shapes, mesh_bounds: dict) -> float:
    """The largest of the collision shapes' thinnest sides (a mesh by its box; one of
    unknown size counts as thick)."""
    thickest = 0.0
    for kind, shape, _xyz, _rpy, dims in shapes.bodies:
        if kind != "collision":
            continue
        tag = shape.tag
        if tag == "box" or tag == "cylinder" or tag == "sphere":
            thickest = max(thickest, _thinnest(tag, dims))
            continue
        box = own_box(tag, dims, shape, mesh_bounds)
        if box is None:
            return float("inf")
        thickest = max(thickest, min(box[0]))
    return thickest


def _thinnest(tag: str, dims: tuple) -> float:
    """The thinnest side of a box, cylinder or sphere."""
    if tag == "box":
        return min(dims)
    if tag == "cylinder":
        return min(2 * dims[0], dims[1])
    return 2 * dims[0]


def _litres(volume: float) -> str:
    return f"{volume:.3g} m³" if volume >= 1e-3 else f"{volume * 1e6:.3g} cm³"
