"""What a simulator would disagree with in a description that ``mcar check`` accepts: the
``<gazebo>`` DiffDrive parameters against the geometry, and links whose mass the engine
would have to invent. Diagnostics are ``FILE:LINE: error: message [E301]``, as check's.

Rule ids are their own series (E3xx, W3xx, in .diagnostics) so that check's table stays
check_urdf's.
"""

from __future__ import annotations

import re

from ..check.mujoco_inertia import make_physical, refusals
from ..check.urdf_model import parse_number
from ..load.bounded import read_text_quietly
from ..load.inputs import display_path
from .declared import joint_problems, meant_for
from .diagnostics import SimDiagnostic

RELATIVE_TOLERANCE = 0.01
# The tags gz-sim's DiffDrive, gazebo_ros (ROS 2) and gazebo_ros (ROS 1) plugins read.
SEPARATION_TAGS = ("wheel_separation", "wheelSeparation")
RADIUS_TAGS = ("wheel_radius",)
DIAMETER_TAGS = ("wheel_diameter", "wheelDiameter")
LEFT_TAGS = ("left_joint", "leftJoint")
RIGHT_TAGS = ("right_joint", "rightJoint")


class Locator:
    """Element of the built URDF -> (file, line): check's source map (where xacro wrote
    the element); for a plugin's parameter it cannot place, the first line of the
    sources that holds its tag."""

    def __init__(self, checked):
        self.checked = checked
        loaded = checked.loaded
        self.files = list(loaded.deps) if loaded is not None and loaded.from_xacro else []

    def __call__(self, element) -> tuple[str, int | None]:
        file, line, _ = self.checked.where(element)
        if line is not None:
            return file, line
        if self.files and element.getparent() is not None and \
                element.getparent().tag == "plugin":
            pattern = re.compile(rf"<{re.escape(element.tag)}\b")
            for path in self.files:
                for number, text in enumerate((read_text_quietly(path) or "").splitlines(), 1):
                    if pattern.search(text):
                        return display_path(path), number
        return file, line


def moving_links_without_mass(checked) -> list[SimDiagnostic]:
    """E305 for moving links without mass: run before the engine, which would refuse them."""
    locate = Locator(checked)
    robot = checked.robot
    moving = {j.child for j in robot.joints if j.type not in ("fixed", None)}
    children = {j.child for j in robot.joints}
    found = []
    for link in robot.links:  # the root: mcar sim gives it a free joint
        if link.name not in children and _subtree_mass(robot, link.name) <= 0:
            found.append(_at(locate, "E305", link.element,
                             f"root link {link.name} and the links fixed to it have no mass: "
                             "MuJoCo cannot move the robot freely; give one of them an "
                             "<inertial>"))
    for link in robot.links:
        if link.name in moving and link_mass(link) <= 0:
            # A wheel's mass could live on a fixed child link: the engine adds those up.
            if _subtree_mass(robot, link.name) > 0:
                continue
            found.append(_at(locate, "E305", link.element,
                             f"link {link.name} moves (child of a non-fixed joint) but has no "
                             "mass: MuJoCo cannot simulate it, Gazebo leaves it out with what "
                             "moves below it (mcar check --gazebo); give it an <inertial> "
                             "(--fix-inertia gives it a token mass)"))
    return found


def refused_inertias(checked) -> list[SimDiagnostic]:
    """E310 for each inertia tensor MuJoCo refuses (not positive definite, or breaking the
    triangle inequality: check only warns, W204 and W205; all zeros on a moving link with
    a mass), at its <inertia>: run before the engine, which would stop at the first
    without naming its link."""
    locate = Locator(checked)
    return [_at(locate, "E310", item.element, f"{item.describe()}: MuJoCo refuses it; "
                + ("--fix-inertia gives it a small sphere's"
                   if item.problem in ("no-inertia", "tiny")
                   else "--fix-inertia puts the nearest physical tensor in its place"))
            for item in refusals(checked.robot.element, massless=False)]


def refused_error(diagnostics: list[SimDiagnostic]) -> str:
    """The one-line reason a robot with E305 or E310 is not simulated."""
    if any(d.message.startswith("root link") for d in diagnostics):
        return "a link MuJoCo must move has no mass (E305 above)"
    links = len(diagnostics)
    return (f"MuJoCo refuses {links} link{'s' * (links != 1)} (E305/E310 above); "
            "--fix-inertia makes {} physical".format("them" if links != 1 else "it"))


def physical_urdf(urdf: bytes) -> tuple[bytes, list[str]]:
    """``urdf`` with every inertia MuJoCo refuses made physical (--fix-inertia), and one
    line per link changed (:mod:`mobile_car.check.mujoco_inertia`)."""
    from lxml import etree

    root = etree.fromstring(urdf, etree.XMLParser(resolve_entities=False, no_network=True))
    found = refusals(root)
    if not found:
        return urdf, []
    lines = make_physical(root, found)
    return etree.tostring(root, encoding="utf-8"), lines


def lint(checked, sim, declared=()) -> list[SimDiagnostic]:
    """Every sim diagnostic of a checked robot and its model, sorted; ``declared``: the
    package's drive declarations (:mod:`.declared`), whose joints must turn."""
    locate = Locator(checked)
    found = _declared_joints(checked, declared, locate)
    named_badly = {name for d in declared for name, _ in
                   joint_problems(d, {j.name: j.type for j in checked.robot.joints})}
    for link in checked.robot.links:
        if link.collisions and link.inertial is None:
            found.append(_at(locate, "W304", link.element,
                             f"link {link.name} has collision geometry but no <inertial>: "
                             "Gazebo leaves it out if it moves (lumps it if fixed), MuJoCo "
                             "gives it a mass from its volume; mcar sim keeps it massless"))
    for plugin in _diff_drive_plugins(checked.robot.element):
        found += _check_plugin(plugin, sim, locate, named_badly)
    return sorted(found, key=lambda d: (d.file, d.line or 0, d.rule))


def _declared_joints(checked, declared, locate) -> list[SimDiagnostic]:
    """E306 for each joint a drive declaration names that is fixed or missing, at the
    declaration: the plugin's tag naming it, or the controller YAML's line. A control
    package's YAML naming none of this robot's joints is another robot's, not flagged."""
    types = {j.name: j.type for j in checked.robot.joints}
    found, said = [], set()
    for declaration in declared:
        if not meant_for(declaration, types):
            continue
        for name, why in joint_problems(declaration, types):
            if name in said:  # once per joint, at its first declaration
                continue
            said.add(name)
            message = (f"{declaration.kind} drive declaration names joint {name}: {why}; "
                       "the robot cannot be driven as its package says")
            if declaration.element is not None:
                tag = next((c for c in declaration.element if (c.text or "").strip() == name),
                           declaration.element)
                found.append(_at(locate, "E306", tag, message))
            else:
                found.append(SimDiagnostic("E306", declaration.file, declaration.line,
                                           message))
    return found


def _diff_drive_plugins(root):
    for plugin in root.iter("plugin"):
        text = f"{plugin.get('name', '')} {plugin.get('filename', '')}".lower()
        if "diffdrive" in text or "diff_drive" in text or "diff-drive" in text:
            yield plugin


def _child(plugin, tags):
    for tag in tags:
        element = plugin.find(tag)
        if element is not None:
            return element
    return None


def _value(element) -> float | None:
    return parse_number((element.text or "").strip()) if element is not None else None


def _check_plugin(plugin, sim, locate, named_badly=frozenset()) -> list[SimDiagnostic]:
    found = []
    drive = sim.drive
    lefts, rights = (drive.left, drive.right) if drive else ([], [])
    for side, tags, group, others in (("left", LEFT_TAGS, lefts, rights),
                                      ("right", RIGHT_TAGS, rights, lefts)):
        # gz-sim's DiffDrive takes a <left_joint> per wheel of a side (skid-steer).
        for element in (e for e in plugin if e.tag in tags):
            name = (element.text or "").strip()
            if name in {w.joint for w in group} or name in named_badly:  # (E306 says it)
                continue
            other = next((w for w in others if w.joint == name), None)
            if other is not None:
                problem = (f"is the {'right' if side == 'left' else 'left'} wheel "
                           f"(y = {other.y:+.4g} m)")
            elif not group:
                problem = "is not a drive wheel: the robot has none the simulation could find"
            else:
                problem = f"is not the {side} drive wheel, {' or '.join(w.joint for w in group)}"
            found.append(_at(locate, "E303", element,
                             f"DiffDrive {element.tag} {name}: {problem}"))
    if not sim.drives:
        return found
    separation = _child(plugin, SEPARATION_TAGS)
    value = _value(separation)
    # A skid-steer robot's plugin rightly holds its effective track (spin measures it).
    if value is not None and drive.kind != "skid-steer" and _differs(value, drive.track):
        names = " and ".join(", ".join(w.joint for w in g) for g in (lefts, rights))
        found.append(_at(locate, "E301", separation,
                         f"DiffDrive {separation.tag} {value:g} m, but the drive wheels "
                         f"{names} are {drive.track:.4g} m apart: odometry and turning rates "
                         f"would be off by {100 * abs(value - drive.track) / drive.track:.1f}%"))
    radius = drive.radius
    element = _child(plugin, RADIUS_TAGS)
    value, factor = _value(element), 1.0
    if element is None:
        element = _child(plugin, DIAMETER_TAGS)
        value, factor = _value(element), 0.5
    if value is not None and _differs(value * factor, radius):
        found.append(_at(locate, "E302", element,
                         f"DiffDrive {element.tag} {value:g} m, but the drive wheels' collision "
                         f"radius is {radius:.4g} m"))
    return found


def _differs(value: float, actual: float) -> bool:
    return abs(value - actual) > RELATIVE_TOLERANCE * abs(actual)


def _at(locate, rule, element, message) -> SimDiagnostic:
    file, line = locate(element)
    return SimDiagnostic(rule, file, line, message)


def link_mass(link) -> float:
    if link.inertial is None or link.inertial.get("mass") is None:
        return 0.0
    return parse_number(link.inertial["mass"].get("value")) or 0.0


def _subtree_mass(robot, name) -> float:
    links = {link.name: link for link in robot.links}
    total, todo = 0.0, [name]
    while todo:
        current = todo.pop()
        total += link_mass(links[current]) if current in links else 0.0
        todo += [j.child for j in robot.joints if j.parent == current and j.type == "fixed"]
    return total
