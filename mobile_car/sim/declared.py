"""What a robot's package says drives it, read before its geometry is looked at: the
``<gazebo>`` drive plugins in the URDF and the controllers its control package configures
(:mod:`.control_config` finds and reads their YAML).

A description names its drive joints in a few places, each a :class:`Declaration` here:

* Gazebo plugins: ``libgazebo_ros_diff_drive`` / gz-sim ``DiffDrive`` (``left_joint``,
  ``right_joint``, ROS 1 ``leftJoint``...; one per wheel of a side for skid-steer),
  ``skid_steer_drive`` (``leftFrontJoint``...), the Ackermann plugins
  (``gazebo_ros_ackermann_drive``, gz ``AckermannSteering``: rear/front wheel and
  ``*_steering_joint`` tags), gz ``MecanumDrive``; ``planar_move`` moves the body itself
  and names no wheel (nothing declared);
* controller YAML: ``diff_drive_controller`` (``left_wheel``/``right_wheel``, ROS 2
  ``left_wheel_names``...), ``ackermann_steering_controller`` and ``steer_drive_controller``
  (ROS 1 ``rear_wheel``/``front_steer``), the ROS 2 steering controllers (ackermann,
  bicycle, tricycle: ``rear_wheels_names``/``front_wheels_names``,
  ``traction_joints_names``/``steering_joints_names``, ``rear_wheel_name``...), the
  ``tricycle_controller`` (``traction_joint_name``/``steering_joint_name``) and
  ``mecanum_drive_controller`` (a joint per corner).

A declaration says its kind (a plain string: ``differential``/``skid-steer`` from the
number of wheels a side, ``ackermann``, ``mecanum``), the joints it drives and steers, and
where it is written (the plugin element, or a YAML file and line). :mod:`.drives` maps its
joints onto the wheels of the tree (a bicycle model's virtual joints onto the real wheels
they stand for); :func:`joint_problems` finds the ones that name a ``fixed`` or missing
joint, which lint reports (E306).
"""

from __future__ import annotations

from dataclasses import dataclass, field

# gazebo plugin tags naming wheel joints, by role.
LEFT_TAGS = ("left_joint", "leftJoint", "leftFrontJoint", "leftRearJoint")
RIGHT_TAGS = ("right_joint", "rightJoint", "rightFrontJoint", "rightRearJoint")
ACKERMANN_DRIVEN_TAGS = ("rear_left_wheel_joint", "rear_right_wheel_joint",
                         "rear_left_joint", "rear_right_joint")
ACKERMANN_STEER_TAGS = ("left_steering_joint", "right_steering_joint",
                        "front_left_steering_joint", "front_right_steering_joint")
MECANUM_TAGS = ("front_left_joint", "front_right_joint", "back_left_joint",
                "back_right_joint", "rear_left_joint", "rear_right_joint")
# controller YAML keys naming joints, by role.
YAML_LEFT = ("left_wheel", "left_wheel_names")
YAML_RIGHT = ("right_wheel", "right_wheel_names")
YAML_TRACTION = ("rear_wheel", "rear_wheels_names", "rear_wheel_name", "traction_joint_name",
                 "traction_joints_names")
YAML_STEER = ("front_steer", "front_wheels_names", "front_wheel_name", "steering_joint_name",
              "steering_joints_names")
YAML_MECANUM = ("front_left_wheel_command_joint_name", "front_right_wheel_command_joint_name",
                "rear_left_wheel_command_joint_name", "rear_right_wheel_command_joint_name",
                "front_left_wheel_joint", "front_right_wheel_joint", "rear_left_wheel_joint",
                "rear_right_wheel_joint",
                # Husarion's mecanum_drive_controller (ROSbot XL)
                "front_left_wheel_name", "front_right_wheel_name", "rear_left_wheel_name",
                "rear_right_wheel_name")


@dataclass
class Declaration:
    kind: str                 # differential, skid-steer, ackermann, mecanum
    source: str               # for people: "plugin X at URDF line N", "FILE:LINE (controller)"
    left: list[str] = field(default_factory=list)    # driven, by side (diff, skid-steer)
    right: list[str] = field(default_factory=list)
    driven: list[str] = field(default_factory=list)  # ackermann: traction; mecanum: all four
    steering: list[str] = field(default_factory=list)  # ackermann: steering joints
    element: object = None    # the plugin element (URDF), for the located error
    file: str | None = None   # the YAML file (controller) ...
    line: int | None = None   # ... and its line

    @property
    def joints(self) -> list[str]:
        return list(dict.fromkeys(self.left + self.right + self.driven + self.steering))


def in_urdf(extras, locate=None) -> list[Declaration]:
    """The drive plugins of ``extras`` (the robot's top-level ``<gazebo>`` elements, and
    others, ignored), in document order; ``locate(element)``: (file, line) where the
    source wrote it (check's source map), for the report."""
    found = []
    for gazebo in extras:
        if gazebo.tag != "gazebo":
            continue
        for plugin in gazebo:
            if plugin.tag == "plugin":
                declaration = _plugin(plugin, locate)
                if declaration is not None:
                    found.append(declaration)
    return found


def _plugin(plugin, locate=None) -> Declaration | None:
    label = plugin.get("filename") or plugin.get("name") or "plugin"
    text = f"{plugin.get('name', '')} {plugin.get('filename', '')}".lower().replace("-", "_")
    file, line = locate(plugin) if locate is not None else (None, None)
    source = f"<gazebo> plugin {label}" + (f" at {file}:{line}" if file and line else "")

    def names(tags):
        return [(c.text or "").strip() for c in plugin if c.tag in tags and (c.text or "").strip()]
    if "ackermann" in text:
        driven, steering = names(ACKERMANN_DRIVEN_TAGS), names(ACKERMANN_STEER_TAGS)
        if not driven:  # gz AckermannSteering: left_joint/right_joint are the rear wheels
            driven = names(LEFT_TAGS + RIGHT_TAGS)
        if driven or steering:
            return Declaration("ackermann", source, driven=driven, steering=steering,
                               element=plugin)
        return None
    if "mecanum" in text:
        wheels = names(MECANUM_TAGS)
        return Declaration("mecanum", source, driven=wheels, element=plugin) if wheels else None
    if any(word in text for word in ("diffdrive", "diff_drive", "skid_steer", "skidsteer")):
        left, right = names(LEFT_TAGS), names(RIGHT_TAGS)
        if left and right:
            return Declaration(_side_kind(left, right, "skid" in text), source, left, right,
                               element=plugin)
    return None


def _side_kind(left, right, skid: bool = False) -> str:
    return "differential" if len(left) == len(right) == 1 and not skid else "skid-steer"


def in_yaml_mapping(keys: dict, path: str, names) -> Declaration | None:
    """The controller a YAML mapping configures, or None; ``keys``: key -> (key node,
    value node), ``names(node)``: the joint names a value node holds."""
    def joints(tags):
        found, first = [], None
        for tag in tags:
            if tag in keys:
                found += names(keys[tag][1])
                first = first or keys[tag][0]
        return found, first
    kind_text = str(getattr(keys.get("type", (None, None))[1], "value", "") or "").lower()
    left, at_left = joints(YAML_LEFT)
    right, _ = joints(YAML_RIGHT)
    if left and right:
        return _yaml(_side_kind(left, right), path, at_left, left=left, right=right)
    traction, at_traction = joints(YAML_TRACTION)
    steering, at_steer = joints(YAML_STEER)
    if traction and steering:
        return _yaml("ackermann", path, at_traction or at_steer, driven=traction,
                     steering=steering)
    if "mecanum" in kind_text or any(k.endswith(("_command_joint_name", "_wheel_name"))
                                     and k.startswith(("front_", "rear_")) for k in keys):
        wheels, at = joints(YAML_MECANUM)
        if len(wheels) == 4:
            return _yaml("mecanum", path, at, driven=wheels)
    return None


def _yaml(kind, path, key, **joints) -> Declaration:
    line = key.start_mark.line + 1 if key is not None else None
    where = f"{path}:{line}" if line else path
    return Declaration(kind, f"controller YAML {where}", file=path, line=line, **joints)


def joint_problems(declaration: Declaration, joints: dict) -> list[tuple[str, str]]:
    """(joint, why) for each joint the declaration names that cannot drive or steer:
    missing from the robot, or ``fixed``; ``joints``: name -> type."""
    found = []
    for name in declaration.joints:
        if name not in joints:
            found.append((name, "the robot has no joint of that name"))
        elif joints[name] == "fixed":
            found.append((name, "a fixed joint: it cannot turn a wheel"))
    return found


def meant_for(declaration: Declaration, joints: dict) -> bool:
    """Whether a declaration is this robot's: a plugin in its URDF always is; a control
    package's YAML (which may configure several robots) only when it names one of its
    joints."""
    return declaration.element is not None or any(n in joints for n in declaration.joints)
