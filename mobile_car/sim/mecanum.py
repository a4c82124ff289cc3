"""Mecanum wheels: what says a robot is a mecanum base, and which way each wheel's rollers
grip.

A mecanum wheel grips the floor along its contact roller's axis only (the roller rolls
freely across it), at 45° to the wheel's axle. The *grip axis* of a wheel is that axis,
seen from above at the floor, as a unit (x, y) in the root frame (x forward, y left). The
usual X pattern, the one ``mecanum_drive_controller``'s kinematics assume
(ω_fl = (vx − vy − (a + b)·ωz) / r ...), grips along (1, −1) at the front left and rear
right wheels and (1, 1) at the others: the rollers on top, seen from above, at +45° on
the front left and rear right.

A robot is mecanum when its package says so (a declaration) or its tree shows it:

* ``mecanum_drive_controller`` in a controller YAML of its package's ``X_control`` or
  ``X_controller`` sibling, naming four of the robot's wheel joints, and whose
  ``wheel_radius`` (where given) is the wheels' within RADIUS_TOLERANCE (ROSbot XL ships
  a diff-drive and a mecanum YAML for the same joints: its xacro argument picks the
  wheels, 48 or 50 mm, and so the YAML that fits them);
* a ``<gazebo>`` ``planar_move`` plugin (linorobot2's ``omni_drive.urdf.xacro``: Gazebo
  moves the base) on a robot with two wheels a side that all slide (their ``<mu1>`` under
  GRIP_MIN: linorobot2's 0.01, Summit XL's omni wheels' 0): planar_move alone says only
  that Gazebo moves the base, and Summit XL moves its skid-steer variant, on rubber
  wheels of mu 1, with it too;
* ``<fdir1>`` with ``mu2`` near 0 in the wheels' ``<gazebo reference>`` (Gazebo's own
  mecanum model; ROSbot XL in simulation), which also gives each wheel's grip axis;
* from the tree: four wheels, two a side, each carrying rollers on its rim (small wheels
  whose centre is off its axle by half its radius or more, turning about an axis slanted
  from its axle: 45° on a mecanum wheel, where an omni wheel's rollers turn across it and
  a rocker's wheels parallel to it); a hub without collision
  geometry of its own counts as a wheel where three or more rollers make its rim.

A wheel macro named ``mecanum`` is not a declaration. The grip axes come from ``fdir1``,
else from the roller links (the lowest roller of each wheel) where they make an X or an
O pattern, else the usual X pattern from each wheel's corner.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..check.urdf_model import parse_number

CORNERS = ("front_left", "front_right", "rear_left", "rear_right")
RADIUS_TOLERANCE = 0.02   # of the wheels' radius: a controller YAML for other wheels
FREE_MU = 0.1             # mu2 / mu1 under this: fdir1 declares a grip axis, not a tyre
GRIP_MIN = 0.1            # a <mu1> under this is rollers' free roll, not a tyre's grip
ROLLER_SHARE = 0.5        # a roller is smaller than this share of its wheel's radius ...
RIM_SHARE = 0.5           # ... and its centre this share of it or more off the axle
MIN_ROLLERS = 3           # rollers on a hub without a tyre of its own
SLANT_DEGREES = (20, 70)  # a roller's axis to its hub's: a mecanum wheel's 45°, roughly
CONTROLLER = "mecanum_drive_controller"
PLANAR_MOVE = re.compile(r"planar_?move", re.IGNORECASE)
# ros2_controllers' mecanum_drive_controller (Jazzy: ..._command_joint_name) and the
# older names of Husarion's and others' (front_left_wheel_name).
_WHEEL_KEY = re.compile(r"^(front|rear)_(left|right)_wheel(_command)?(_joint)?_name$")
_RADIUS_KEYS = ("wheel_radius", "wheels_radius")


@dataclass
class Declaration:
    """What a package says of its mecanum base: where (for the report), the wheel joint
    of each corner it names (none for planar_move), the wheel radius it is configured for
    (m, or None), and link -> grip axis (x, y) from ``fdir1``."""

    where: str
    wheels: dict[str, str] = field(default_factory=dict)
    radius: float | None = None
    grip: dict[str, tuple[float, float]] = field(default_factory=dict)
    grip_mu: dict[str, tuple[float, float]] = field(default_factory=dict)  # link: mu, mu2
    sliding: set[str] | None = None  # planar_move: the links whose <mu1> slides

    def fits(self, wheels) -> bool:
        """True when it names (or can be read as naming) these four wheels."""
        joints = {w.joint for w in wheels}
        if self.wheels and set(self.wheels.values()) != joints:
            return False
        if self.radius is not None:
            radius = float(np.mean([w.radius for w in wheels]))
            if radius <= 0 or abs(self.radius - radius) > RADIUS_TOLERANCE * radius:
                return False
        if self.grip and not {w.link for w in wheels} <= set(self.grip):
            return False
        if self.sliding is not None and not {w.link for w in wheels} <= self.sliding:
            return False
        return True


def urdf_declarations(root) -> list[Declaration]:
    """The declarations of the URDF itself: a planar_move plugin, fdir1 grip axes."""
    found = []
    sliding = set()
    for gazebo in root.iterchildren("gazebo"):
        mu = gazebo.find("mu1")
        # Gazebo reads <mu1>0.01</mu1> and <mu1 value="0.0"/> alike
        values = _number_list(mu) or (_number_list_text(mu.get("value"))
                                      if mu is not None else [])
        if gazebo.get("reference") and values and values[0] < GRIP_MIN:
            sliding.add(gazebo.get("reference"))
    for gazebo in root.iterchildren("gazebo"):
        for plugin in gazebo.iterchildren("plugin"):
            text = f"{plugin.get('name', '')} {plugin.get('filename', '')}"
            if PLANAR_MOVE.search(text):
                label = plugin.get("filename") or plugin.get("name")
                found.append(Declaration(f"<gazebo> plugin {label}", sliding=sliding))
    grip, grip_mu = {}, {}
    for gazebo in root.iterchildren("gazebo"):
        link = gazebo.get("reference")
        for ode in gazebo.iter("ode"):
            fdir, mu, mu2 = (_number_list(ode.find(tag)) for tag in ("fdir1", "mu", "mu2"))
            if link and len(fdir) == 3 and mu and mu2 and mu[0] > 0 and \
                    mu2[0] <= FREE_MU * mu[0] and math.hypot(fdir[0], fdir[1]) > 0:
                norm = math.hypot(fdir[0], fdir[1])
                grip[link] = (fdir[0] / norm, fdir[1] / norm)
                grip_mu[link] = (mu[0], mu2[0])
    if grip:
        found.append(Declaration("<gazebo> fdir1 with mu2 0 on " + ", ".join(sorted(grip)),
                                 grip=grip, grip_mu=grip_mu))
    return found


def yaml_declarations(loaded) -> tuple[list[Declaration], list[str]]:
    """The ``mecanum_drive_controller`` configurations of the robot's control packages
    (:func:`.control_config.control_packages`: found, bounded and a link out of the
    repository refused as for every controller), and the files that could not be read."""
    from .control_config import control_packages

    found, problems = [], []
    for files in control_packages(loaded, problems):
        for path in files:
            found += _from_yaml(path, problems)
    return found, problems


def _from_yaml(path: Path, problems: list[str]) -> list[Declaration]:
    import yaml

    from ..load.inputs import display_path
    from .control_config import yaml_mappings

    found = []
    for keys in yaml_mappings(path, problems, CONTROLLER):
        wheels, radius, line = {}, None, None
        for name, (key, value) in keys.items():
            match = _WHEEL_KEY.match(name)
            if match and isinstance(value, yaml.ScalarNode) and value.value:
                wheels[f"{match[1]}_{match[2]}"] = value.value
                line = line or key.start_mark.line + 1
            elif name in _RADIUS_KEYS and isinstance(value, yaml.ScalarNode):
                radius = parse_number(value.value)
        if len(wheels) == 4:
            found.append(Declaration(f"{display_path(path)}:{line} ({CONTROLLER})", wheels,
                                     radius))
    return found


def _number_list(element) -> list[float]:
    return _number_list_text(element.text) if element is not None else []


def _number_list_text(text) -> list[float]:
    values = [parse_number(v) for v in (text or "").split()]
    return [] if None in values else values


def is_roller(mj, model, data, hub, roller) -> bool:
    """True when wheel ``roller`` (below wheel ``hub`` in the tree) is a roller on the hub's
    rim: smaller than ROLLER_SHARE of its radius, its centre RIM_SHARE of it or more off the
    hub's axle, the axle about level (a castor's swivel is upright: not a hub)."""
    axis = data.xaxis[hub.joint_id]
    if hub.radius <= 0 or abs(axis[2]) > 0.5 or roller.radius >= ROLLER_SHARE * hub.radius:
        return False
    offset = data.xpos[roller.body_id] - data.xanchor[hub.joint_id]
    off_axle = np.linalg.norm(offset - (offset @ axis) * axis)
    return bool(off_axle >= RIM_SHARE * hub.radius and _slanted(data, hub, roller))


def _slanted(data, hub, roller) -> bool:
    """A mecanum roller turns about an axis at SLANT_DEGREES to its hub's (45° on every
    wheel made): not parallel to it (a rocker's or bogie's wheels), nor across it (an
    omni wheel's rollers)."""
    cosine = abs(float(data.xaxis[hub.joint_id] @ data.xaxis[roller.joint_id]))
    low, high = (math.radians(d) for d in SLANT_DEGREES)
    return math.cos(high) <= cosine <= math.cos(low)


def bare_hubs(model, data, bare, wheels) -> list:
    """The wheels of ``bare`` (continuous joints moving no collision geometry) that carry
    MIN_ROLLERS or more of ``wheels`` around their level axle, each smaller than
    ROLLER_SHARE of the rim they make: a mecanum hub drawn without a tyre, whose rollers
    touch the floor. Each gets the radius of that rim (its rollers' outer reach)."""
    hubs = []
    for hub in bare:
        axis = data.xaxis[hub.joint_id]
        if abs(axis[2]) > 0.5:
            continue
        reach = []
        for wheel in wheels:
            body = int(model.body_parentid[wheel.body_id])
            while body > 0 and body != hub.body_id:
                body = int(model.body_parentid[body])
            if body == hub.body_id and _slanted(data, hub, wheel):
                offset = data.xpos[wheel.body_id] - data.xanchor[hub.joint_id]
                off_axle = float(np.linalg.norm(offset - (offset @ axis) * axis))
                reach.append((off_axle, wheel.radius))
        rim = max((d + r for d, r in reach), default=0.0)
        if len(reach) >= MIN_ROLLERS and all(r < ROLLER_SHARE * rim for _, r in reach):
            hub.radius = rim
            hubs.append(hub)
    return hubs


def grip_of_rollers(model, data, rollers) -> tuple[float, float] | None:
    """The grip axis (x, y) of the lowest of a wheel's rollers, or None when it stands
    upright (a roller turning about z grips nothing)."""
    lowest = min(rollers, key=lambda w: float(data.xpos[w.body_id][2]))
    axis = data.xaxis[lowest.joint_id]
    norm = math.hypot(axis[0], axis[1])
    if norm < 0.5:
        return None
    x, y = axis[0] / norm, axis[1] / norm
    return (x, y) if x >= 0 else (-x, -y)


def corners(wheels) -> dict[str, object] | None:
    """corner -> wheel for four wheels two a side (front: the larger x of each side)."""
    lefts = sorted((w for w in wheels if w.y > 0), key=lambda w: -w.x)
    rights = sorted((w for w in wheels if w.y < 0), key=lambda w: -w.x)
    if len(wheels) != 4 or len(lefts) != 2 or len(rights) != 2:
        return None
    return dict(zip(CORNERS, (lefts[0], rights[0], lefts[1], rights[1]), strict=True))


def center_projection(wheels) -> float:
    """lx + ly: the wheels' mean distance from the root frame's origin along x plus along
    y (mecanum_drive_controller's ``sum_of_robot_center_projection_on_X_Y_axis``)."""
    return sum(abs(w.x) + abs(w.y) for w in wheels) / len(wheels)


def usual_x(corner: str) -> tuple[float, float]:
    """The grip axis of the usual X pattern at ``corner``."""
    h = math.sqrt(0.5)
    return (h, -h) if corner in ("front_left", "rear_right") else (h, h)


def set_grips(tree, by_corner: dict, declared: list[Declaration]) -> str:
    """Give each wheel its grip axis (``wheel.grip``), from fdir1, the roller links or the
    usual X pattern; returns where they came from."""
    fdir = next((d for d in declared if d.grip), None)
    if fdir is not None and all(w.link in fdir.grip for w in by_corner.values()):
        for wheel in by_corner.values():
            wheel.grip = fdir.grip[wheel.link]
        return "<gazebo> fdir1"
    rollers = {c: tree.roller_grip.get(w.joint) for c, w in by_corner.items()}
    if all(rollers.values()) and _x_or_o(rollers):
        for corner, wheel in by_corner.items():
            wheel.grip = rollers[corner]
        return "the roller links"
    for corner, wheel in by_corner.items():
        wheel.grip = usual_x(corner)
    if any(rollers.values()):
        return "the usual X pattern (the roller links make no X or O pattern)"
    return "the usual X pattern"


def _x_or_o(grips: dict) -> bool:
    """The lowest rollers make an X or an O: diagonal wheels alike, each at about 45°."""
    sign = {c: math.copysign(1.0, g[0] * g[1]) for c, g in grips.items()}
    diagonal = abs(abs(grips["front_left"][0]) - math.sqrt(0.5)) < 0.15
    return (diagonal and sign["front_left"] == sign["rear_right"] != sign["front_right"]
            == sign["rear_left"] and all(abs(abs(g[0]) - math.sqrt(0.5)) < 0.15
                                         for g in grips.values()))


def mecanum_drive(tree, declared: list[Declaration], names=None):
    """The mecanum Drive of ``tree`` (a drives.Tree): its four wheels (``names``: the
    wheel joints a declaration names, else the tree's) with their grip axes, or None
    when they are not four, two a side. ``declared``: what the package said."""
    from .drive_parts import Drive

    wheels = tree.wheels if not names else [w for w in tree.wheels if w.joint in set(names)]
    by_corner = corners(wheels)
    if by_corner is None:
        return None
    source = set_grips(tree, by_corner, declared)
    fitting = [d for d in declared if d.fits(wheels)]
    drive = Drive("mecanum", [by_corner["front_left"], by_corner["rear_left"]],
                  [by_corner["front_right"], by_corner["rear_right"]])
    drive.declared = fitting[0].where if fitting else "rollers on the wheels' rims"
    drive.grip_from = source
    return drive


def declared_drive(tree, kind: str, wheel_names, where: str = "declared"):
    """The drive a declaration read elsewhere (a controller YAML, a plugin) gives: for kind
    ``mecanum``, the mecanum Drive of the tree's wheels ``wheel_names`` (``where`` names
    the declaration in the report), or None where they are not four, two a side, or the
    kind is another."""
    if kind != "mecanum":
        return None
    return mecanum_drive(tree, [Declaration(where)], list(wheel_names))


def declared_mecanum(tree, declared: list[Declaration]) -> bool:
    """Whether a declaration that fits the tree's wheels makes it mecanum."""
    wheels = [w for w in tree.wheels if abs(w.y) > 0]
    return corners(wheels) is not None and any(d.fits(wheels) for d in declared)


def has_rollers(tree) -> bool:
    """Four wheels two a side, each with rollers on its rim."""
    by_corner = corners(tree.wheels)
    return by_corner is not None and all(w.joint in tree.roller_grip
                                         for w in by_corner.values())


def mecanum_speeds(drive, vx: float, vy: float, yaw_rate: float) -> dict[str, float]:
    """joint -> wheel speed (rad/s, positive rolling forward) for a body velocity (vx, vy)
    m/s and yaw rate (rad/s) about the wheels' centre, as mecanum_drive_controller
    commands them: for the usual X pattern's grip axis g at each corner, at p from the
    centre, r·ω·g_x = (v + ωz × p) · g. Rollers that grip otherwise (an O pattern) then
    move the robot otherwise, as they would on the real robot."""
    cx = float(np.mean([w.x for w in drive.driven]))
    cy = float(np.mean([w.y for w in drive.driven]))
    speeds = {}
    for wheel in drive.driven:
        px, py = wheel.x - cx, wheel.y - cy
        gx, gy = usual_x(f"{'front' if px > 0 else 'rear'}_{'left' if py > 0 else 'right'}")
        along = (vx - yaw_rate * py) * gx + (vy + yaw_rate * px) * gy
        speeds[wheel.joint] = along / (wheel.radius * gx)
    return speeds


def half_spans(drive) -> tuple[float, float]:
    """(a, b): half the wheelbase and half the track of the four wheels (m)."""
    xs = [w.x for w in drive.driven]
    return (max(xs) - min(xs)) / 2, drive.track / 2
