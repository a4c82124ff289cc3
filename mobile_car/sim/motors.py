"""Where a drive wheel's motor figures (effort limit, speed limit) come from.

A description says them in several places, and many say none (TurtleBot3's wheel joints are
``continuous`` without ``<limit>``, which URDF allows). Each figure is taken from the
first of these places that gives it (a number, zero included), and carries the place it
came from, which the report prints:

1. the joint's own ``<limit effort velocity>`` (an explicit 0 is kept: that motor cannot
   move, and drive says so);
2. the ``<ros2_control>`` joint of that name: its ``effort`` / ``velocity`` command
   interface's ``max`` (or ``-min``) parameter;
3. a ``<gazebo>`` diff-drive or skid-steer plugin naming the joint (or naming no joints):
   the wheel torque (``max_wheel_torque``, ROS 1 ``wheelTorque`` or ``torque``) and, of
   gz-sim's DiffDrive, ``max_linear_velocity`` / wheel radius;
4. ``mcar sim --effort``;
5. a default: the torque that holds the robot on a 10 degree slope, shared by the drive
   wheels (m·g·sin 10°·r / n); for a skid-steer robot, which turns by dragging its tyres
   sideways, the torque that slips its wheels on the floor (mu·m·g·r / n, mu their
   friction): with the slope's torque, a Husky's wheels stall and it cannot turn (0.01 of
   the rate it should). No speed limit (the scenarios then command
   :data:`~mobile_car.sim.run.DEFAULT_SPEED`, slower on large wheels).

``--speed`` is the speed limit whatever the description says (the user knows the motor).
A speed limit whose rim speed r·ω is over MAX_RIM_SPEED is a placeholder, not a motor's:
no wheeled robot these packages describe runs its wheels faster (Warthog, the fastest,
5 m/s; Husky 1 m/s, Jackal 2 m/s), while Summit XL's ``velocity="100"`` on 0.11 m wheels
is 11 m/s, and driving at half of it fails on wheel hop and slip. The figure is kept and
said to be a placeholder; the scenarios drive as if no limit were given.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..check.urdf_model import parse_number

SLOPE_DEGREES = 10.0
GRAVITY = 9.81
MAX_RIM_SPEED = 5.0  # m/s: a wheel speed limit faster at the rim is a placeholder
# Parameter names of the drive plugins: ROS 2 gazebo_ros, ROS 1 libgazebo_ros_diff_drive and
# libgazebo_ros_skid_steer_drive.
TORQUE_TAGS = ("max_wheel_torque", "wheelTorque", "torque")  # the last: skid-steer plugin
LINEAR_VELOCITY_TAGS = ("max_linear_velocity",)  # gz-sim DiffDrive, in m/s
JOINT_TAGS = ("left_joint", "right_joint", "leftJoint", "rightJoint")
# The skid-steer plugin of gazebo_ros (ROS 1) names its four joints so.
SKID_JOINT_TAGS = ("leftFrontJoint", "rightFrontJoint", "leftRearJoint", "rightRearJoint")


@dataclass
class MotorFigures:
    effort: float            # N·m
    effort_from: str
    velocity: float | None   # rad/s; None: the description sets no speed limit
    velocity_from: str
    placeholder: str | None = None  # why the velocity is not a motor's, or None

    @property
    def usable_velocity(self) -> float | None:
        """The speed limit the scenarios drive by: None for a placeholder."""
        return None if self.placeholder else self.velocity

    def as_json(self) -> dict:
        document = {"effort": round(self.effort, 6), "effort_from": self.effort_from,
                    "velocity": None if self.velocity is None else round(self.velocity, 6),
                    "velocity_from": self.velocity_from}
        if self.placeholder:
            document["placeholder"] = self.placeholder
        return document


def motor_figures(extras, joint, radius: float, drive_wheels: int, mass: float,
                  effort_flag: float | None = None, speed_flag: float | None = None,
                  slip_friction: float | None = None,
                  kind: str = "skid-steer") -> MotorFigures:
    """The figures of the drive joint element ``joint``; ``extras``: the robot's top-level
    ``<ros2_control>`` and ``<gazebo>`` elements; ``slip_friction``: a skid-steer robot's
    tyre friction, whose default torque slips the wheels rather than holds the slope (a
    mecanum robot's too: ``kind`` names it in the source)."""
    name = joint.get("name")
    efforts, velocities = [], []
    limit = _first(joint, "limit")
    if limit is not None:
        efforts.append((_number(limit.get("effort")), "joint <limit effort>"))
        velocities.append((_number(limit.get("velocity")), "joint <limit velocity>"))
    interfaces = _ros2_control_interfaces(extras, name)
    efforts.append((interfaces.get("effort"), "<ros2_control> effort command interface"))
    velocities.append((interfaces.get("velocity"), "<ros2_control> velocity command interface"))
    for plugin in _diff_drive_plugins(extras, name):
        label = plugin.get("filename") or plugin.get("name") or "diff drive"
        efforts.append((_tag_number(plugin, TORQUE_TAGS), f"<gazebo> plugin {label} torque"))
        linear = _tag_number(plugin, LINEAR_VELOCITY_TAGS)
        velocities.append((linear / radius if linear is not None and radius > 0 else None,
                           f"<gazebo> plugin {label} max_linear_velocity / wheel radius"))
    efforts.append((effort_flag, "--effort"))
    if speed_flag is not None:  # the user's figure overrides every other source
        velocities.insert(0, (speed_flag, "--speed"))
    effort, effort_from = _first_given(efforts)
    if effort is None and slip_friction is not None:
        effort = slip_friction * mass * GRAVITY * radius / max(1, drive_wheels)
        effort_from = (f"default: slips the wheels of {mass:.3g} kg at mu {slip_friction:g} "
                       f"(mu·m·g·r / {drive_wheels}, {kind})")
    elif effort is None:
        effort = slope_torque(mass, radius, drive_wheels)
        effort_from = (f"default: holds {mass:.3g} kg on a {SLOPE_DEGREES:g}° slope "
                       f"(m·g·sin {SLOPE_DEGREES:g}°·r / {drive_wheels})")
    velocity, velocity_from = _first_given(velocities)
    if velocity is None:
        velocity_from = "none given"
    return MotorFigures(effort, effort_from, velocity, velocity_from,
                        _placeholder(velocity, velocity_from, radius))


def _placeholder(velocity: float | None, source: str, radius: float) -> str | None:
    """Why a speed limit is a placeholder (its rim speed over MAX_RIM_SPEED), or None."""
    if velocity is None or source == "--speed" or velocity * radius <= MAX_RIM_SPEED:
        return None
    return (f"a placeholder: {velocity:g} rad/s is {velocity * radius:.3g} m/s at the rim "
            f"(r·ω, r {radius:.4g} m), over the {MAX_RIM_SPEED:g} m/s no wheeled robot "
            "exceeds")


def slope_torque(mass: float, radius: float, drive_wheels: int) -> float:
    """Each drive wheel's share of the torque that holds ``mass`` on the slope."""
    return (mass * GRAVITY * math.sin(math.radians(SLOPE_DEGREES)) * radius
            / max(1, drive_wheels))


def _first_given(candidates):
    for value, source in candidates:
        if value is not None and value >= 0:
            return value, source
    return None, ""


def _first(element, tag):
    for child in element:
        if child.tag == tag:
            return child
    return None


def _number(text) -> float | None:
    value = parse_number(text.strip()) if text is not None else None
    return value if value is not None and math.isfinite(value) else None


def _ros2_control_interfaces(extras, joint_name) -> dict[str, float]:
    """interface name -> the largest command magnitude its min/max parameters allow."""
    found = {}
    for block in extras:
        if block.tag != "ros2_control":
            continue
        for joint in block:
            if joint.tag != "joint" or joint.get("name") != joint_name:
                continue
            for interface in joint:
                if interface.tag != "command_interface":
                    continue
                bounds = [_number(param.text) for param in interface
                          if param.tag == "param" and param.get("name") in ("min", "max")]
                bounds = [abs(b) for b in bounds if b is not None]
                kind = interface.get("name")
                if bounds and kind not in found:
                    found[kind] = max(bounds)
    return found


def _diff_drive_plugins(extras, joint_name):
    """The diff-drive and skid-steer plugins that drive ``joint_name`` (or name no joint
    at all)."""
    for gazebo in extras:
        if gazebo.tag != "gazebo":
            continue
        for plugin in gazebo:
            if plugin.tag != "plugin":
                continue
            text = f"{plugin.get('name', '')} {plugin.get('filename', '')}".lower()
            if not any(word in text for word in ("diffdrive", "diff_drive", "diff-drive",
                                                 "skid_steer", "skidsteer")):
                continue
            named = {(child.text or "").strip() for child in plugin
                     if child.tag in JOINT_TAGS + SKID_JOINT_TAGS}
            if not named or joint_name in named:
                yield plugin


def _tag_number(plugin, tags) -> float | None:
    for tag in tags:
        for child in plugin:
            if child.tag == tag:
                return _number(child.text)
    return None
