"""The numbers the rest of a ROS 2 stack needs, written for it: Nav2's costmap footprint
and radius, the drive controller's geometry and limits (ros2_controllers), and the
laser_filters that take the robot's own body out of its scans. ``mcar specs ROBOT --stack
DIR`` writes them as ``nav2.yaml``, ``controllers.yaml`` and ``laser_filters.yaml``;
:mod:`.stack_check` compares the package's own YAML with the same figures.

Each fragment is a plain dict laid out as its node reads it (``yaml.safe_dump`` writes it,
``yaml.safe_load`` reads it back): Nav2's ``local_costmap: local_costmap:
ros__parameters:`` nesting of nav2_bringup's ``nav2_params.yaml``; a ``controller_manager``
entry naming the controller's type, then the controller's own ``ros__parameters``.
Parameter names are ros2_controllers' own, by ROS 2 release (``DISTROS``): Jazzy and later
(``traction_joints_names``, ``traction_track_width``...; ``wheels_per_side`` is gone) or
Humble (``rear_wheels_names``, ``front_wheel_track``, ``wheels_per_side``...).

Lengths are rounded to the millimetre outward (a footprint or radius never shrinks), the
drive's geometry to the micrometre, angles in radians to 1e-4 rad outward.
"""

from __future__ import annotations

import math
from pathlib import Path

from .figures import Figure, Section
from .lookup import figure_value
from .sensors import laser_filters_fragment

DISTROS = ("jazzy", "humble")  # jazzy: also Kilted and Rolling
FILES = ("nav2.yaml", "controllers.yaml", "laser_filters.yaml")



def _out(value: float, step: float = 0.001) -> float:
    """``value`` rounded away from zero to ``step``: a bound never shrinks."""
    return math.copysign(math.ceil(round(abs(value) / step, 6)) * step, value) if value \
        else 0.0


def _round(value: float) -> float:
    return round(float(value), 6)


def footprint_text(points) -> str:
    """A polygon as Nav2 writes its ``footprint`` parameter: the string "[[x, y], ...]"."""
    return "[" + ", ".join(f"[{_out(x):g}, {_out(y):g}]" for x, y in points) + "]"


def nav2_fragment(sections) -> dict:
    """Nav2's local and global costmap parameters: ``footprint`` (body.footprint, the
    robot's outline on the floor) and ``robot_radius`` (body.radius.circumscribed); Nav2
    uses the footprint where one is given, the radius otherwise. {} without either."""
    params = {}
    footprint = figure_value(sections, "body.footprint")
    radius = figure_value(sections, "body.radius.circumscribed")
    if footprint:
        params["footprint"] = footprint_text(footprint)
    if radius:
        params["robot_radius"] = _out(radius)
    if not params:
        return {}
    return {"local_costmap": {"local_costmap": {"ros__parameters": dict(params)}},
            "global_costmap": {"global_costmap": {"ros__parameters": dict(params)}}}


def controller_fragment(sections, sim, distro: str = "jazzy", control=None) -> dict:
    """The ros2_controllers controller for sim's drive (``sim.drive``): its joints, its
    geometry (wheels.radius, wheels.track, wheels.wheelbase, else the drive's own) and,
    for a differential or skid-steer drive, velocity limits from statics.top_speed;
    ``control``: the package's :class:`~mobile_car.sim.control_config.ControlConfig`,
    whose ``wheel_separation_multiplier`` is carried over. {} for a robot sim cannot
    drive."""
    drive = getattr(sim, "drive", None)
    if drive is None:
        return {}
    radius = figure_value(sections, "wheels.radius") or drive.radius
    if drive.kind in ("differential", "skid-steer"):
        name, kind, params = _differential(sections, drive, radius, distro, control)
    elif drive.kind == "ackermann":
        name, kind, params = _ackermann(sections, drive, radius, distro)
    elif drive.kind == "bicycle":
        name, kind, params = _bicycle(sections, drive, radius, distro)
    elif drive.kind == "mecanum":
        name, kind, params = _mecanum(drive, radius)
    else:
        return {}
    return {"controller_manager": {"ros__parameters": {name: {"type": kind}}},
            name: {"ros__parameters": params}}


def effective_separation(track: float, control) -> float:
    return track * (control.multiplier if control is not None else 1.0)


def _differential(sections, drive, radius, distro, control):
    track = figure_value(sections, "wheels.track") or drive.track
    params = {"left_wheel_names": [w.joint for w in drive.left],
              "right_wheel_names": [w.joint for w in drive.right],
              "wheel_separation": _round(track), "wheel_radius": _round(radius)}
    if distro == "humble":
        params["wheels_per_side"] = len(drive.left)
    if control is not None:
        params["wheel_separation_multiplier"] = control.multiplier
    speed = figure_value(sections, "statics.top_speed")
    if speed:
        turn = 2 * speed / effective_separation(track, control)
        flag = {"has_velocity_limits": True} if distro == "humble" else {}
        params["linear"] = {"x": {**flag, "max_velocity": round(speed, 3),
                                  "min_velocity": -round(speed, 3)}}
        params["angular"] = {"z": {**flag, "max_velocity": round(turn, 3),
                                   "min_velocity": -round(turn, 3)}}
    return "diff_drive_controller", "diff_drive_controller/DiffDriveController", params


def _ackermann(sections, drive, radius, distro):
    traction = [w for w in drive.right + drive.left if w.steering is None]
    steering = drive.steering[::-1]  # ros2_controllers: right joint, left joint
    wheelbase = figure_value(sections, "wheels.wheelbase") or drive.wheelbase
    traction_track = _side_distance([w.y for w in traction])
    steering_track = _side_distance([s.y for s in steering])
    if distro == "humble":
        params = {"front_steering": True,
                  "rear_wheels_names": [w.joint for w in traction],
                  "front_wheels_names": [s.joint for s in steering],
                  "wheelbase": _round(wheelbase), "front_wheel_track": _round(steering_track),
                  "rear_wheel_track": _round(traction_track),
                  "front_wheels_radius": _round(radius), "rear_wheels_radius": _round(radius)}
    else:
        params = {"traction_joints_names": [w.joint for w in traction],
                  "steering_joints_names": [s.joint for s in steering],
                  "wheelbase": _round(wheelbase), "traction_track_width": _round(traction_track),
                  "steering_track_width": _round(steering_track),
                  "traction_wheels_radius": _round(radius)}
    return ("ackermann_steering_controller",
            "ackermann_steering_controller/AckermannSteeringController", params)


def _side_distance(ys) -> float:
    left = [y for y in ys if y > 0]
    right = [y for y in ys if y < 0]
    if not (left and right):
        return 0.0
    return sum(left) / len(left) - sum(right) / len(right)


def _bicycle(sections, drive, radius, distro):
    wheelbase = figure_value(sections, "wheels.wheelbase") or drive.wheelbase
    traction = [w.joint for w in drive.centre or drive.rear]
    steering = [s.joint for s in drive.steering]
    if distro == "humble":
        params = {"front_steering": True, "rear_wheels_names": traction,
                  "front_wheels_names": steering, "wheelbase": _round(wheelbase),
                  "front_wheel_radius": _round(radius), "rear_wheel_radius": _round(radius)}
    else:
        params = {"traction_joints_names": traction, "steering_joints_names": steering,
                  "wheelbase": _round(wheelbase), "traction_wheel_radius": _round(radius)}
    return ("bicycle_steering_controller",
            "bicycle_steering_controller/BicycleSteeringController", params)


def _mecanum(drive, radius):
    """mecanum_drive_controller's names; ``sum_of_robot_center_projection_on_X_Y_axis`` is
    lx + ly, the wheels' mean distance from the root frame's origin along x and along y
    (base_frame_offset 0: the root frame is the robot's centre)."""
    from ..sim.mecanum import center_projection, corners

    wheels = drive.left + drive.right
    by_corner = corners(wheels)  # (sim drives as mecanum only four wheels two a side)
    params = {f"{corner}_wheel_command_joint_name": by_corner[corner].joint
              for corner in ("front_left", "rear_left", "front_right", "rear_right")}
    params["kinematics"] = {"base_frame_offset": {"x": 0.0, "y": 0.0, "theta": 0.0},
                            "wheels_radius": _round(radius),
                            "sum_of_robot_center_projection_on_X_Y_axis":
                                _round(center_projection(wheels))}
    return ("mecanum_drive_controller", "mecanum_drive_controller/MecanumDriveController",
            params)


def stack_documents(sections, sim, distro: str = "jazzy", control=None) -> dict[str, tuple]:
    """file name -> (header comment lines, document) for each fragment that has content."""
    documents = {}
    nav2 = nav2_fragment(sections)
    if nav2:
        documents["nav2.yaml"] = (["Nav2 costmap parameters from mcar specs: merge into "
                                   "your nav2_params.yaml",
                                   "footprint: body.footprint (collision geometry at rest); "
                                   "robot_radius: body.radius.circumscribed"], nav2)
    controllers = controller_fragment(sections, sim, distro, control)
    if controllers:
        documents["controllers.yaml"] = (_controller_header(sections, sim, distro, control),
                                         controllers)
    filters = laser_filters_fragment(sections)  # (the sensors part's: the scan's own angles)
    if filters:
        documents["laser_filters.yaml"] = (["laser_filters chains from mcar specs: the "
                                            "sectors the robot's own body blocks "
                                            "(sensors.<name>.blocked)"], filters)
    return documents


def _controller_header(sections, sim, distro, control) -> list[str]:
    lines = [f"ros2_controllers parameters from mcar specs ({distro} parameter names): "
             f"{sim.drive.kind} drive"]
    if control is not None and sim.drive.kind in ("differential", "skid-steer"):
        track = figure_value(sections, "wheels.track") or sim.drive.track
        lines.append(f"wheel_separation {track:.4f} m is the wheels' spacing; "
                     f"wheel_separation_multiplier {control.multiplier:g} is the package's "
                     f"({control.where}): effective {effective_separation(track, control):.4f} m")
    return lines


def yaml_text(header: list[str], document: dict) -> str:
    import yaml

    comment = "".join(f"# {line}\n" for line in header)
    return comment + yaml.safe_dump(document, sort_keys=False, default_flow_style=None,
                                    allow_unicode=True)


def write_stack(folder, sections, sim, distro: str = "jazzy", control=None,
                inputs=()) -> list[Path]:
    """Write each fragment into ``folder`` (created), each file atomically; a fragment
    without content is not written (a robot without a lidar has no laser_filters.yaml).
    ``inputs``: files this run read (the package's own YAML), never written over: refused
    before any file is written."""
    from ..atomic import atomic_write
    from ..load.outputs import refuse_overwriting_each

    folder = Path(folder)
    documents = stack_documents(sections, sim, distro, control)
    targets = [folder / name for name in documents]
    refuse_overwriting_each(targets, inputs, "a file this run read (the package's own YAML)")
    return [atomic_write(target, yaml_text(*documents[target.name])) for target in targets]


def section(context) -> Section:
    """The stack section: the controller geometry as written (figures stack.*), and the
    package's own YAML compared with it (:mod:`.stack_check`, W510-W514)."""
    from .stack_check import compare_package, package_control

    sim, checked = context.sim, context.checked
    result = Section("stack")
    # (the sections computed before it: body, statics, joints, sensors)
    sections = context.sections
    drive = getattr(sim, "drive", None)
    control = package_control(checked, sim)
    if drive is not None and drive.kind in ("differential", "skid-steer"):
        track = figure_value(sections, "wheels.track") or drive.track
        effective = effective_separation(track, control)
        source = "the drive wheels' spacing (wheels.track)"
        if control is not None:
            source += f" x wheel_separation_multiplier {control.multiplier:g} ({control.where})"
        result.figures.append(Figure("stack.wheel_separation", "effective wheel separation",
                                     round(effective, 6), "m", source))
    elif drive is None and sim is not None:  # (no model at all: the body's notes say why)
        result.notes.append(f"no drive controller: {sim.why_no_drive or 'no drive found'}")
    diagnostics, notes, _read = compare_package(checked, sim, sections)
    result.diagnostics += diagnostics
    result.notes += notes
    return result
