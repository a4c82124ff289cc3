"""The package's own ROS YAML (:mod:`.stack_check` finds it) compared with the robot:
each mismatch a warning at the YAML line that says it (rules W510-W514).

What is compared (tolerance TOLERANCE, relative):

* ``wheel_separation`` x ``wheel_separation_multiplier`` (the effective separation, as
  the controller computes with it) with the drive wheels' track (W510); a skid-steer
  robot's effective separation is rightly larger (its wheels scrub when it turns): there
  the plain ``wheel_separation`` is compared where a multiplier holds the correction,
  else only an effective separation below the track is flagged; ``wheelbase`` and
  ``wheel_separation_h`` (ROS 1) with an Ackermann or bicycle drive's wheelbase;
* ``wheel_radius`` x ``wheel_radius_multiplier`` (ROS 2: each side's), the steering
  controllers' ``*_wheels_radius`` and ``*_wheel_radius``, with the wheels' radius (W511);
* mecanum_drive_controller's ``kinematics``: ``wheels_radius`` (W511) and
  ``sum_of_robot_center_projection_on_X_Y_axis`` with the wheels' lx + ly (W510);
* the joints a differential, skid-steer or mecanum controller names with the drive's
  wheels, by side or corner (W512);
* a Nav2 ``footprint`` that leaves part of the robot's own outline out, or, without a
  footprint, a ``robot_radius`` under its circumscribed radius (W513);
* ``LaserScanAngularBoundsFilterInPlace`` bounds that leave part of a blocked sector
  (sensors.<name>.blocked) in the scan (W514; with the sensors section only).
"""

from __future__ import annotations

import math
from pathlib import Path

from ..check.diagnostics import Diagnostic
from ..load.inputs import display_path
from .lookup import blocked_sectors, figure_value

TOLERANCE = 0.01
FOOTPRINT_SLACK = 0.001  # m: Nav2's footprint may round the outline by a millimetre
SEPARATION_KEYS = ("wheel_separation",)
WHEELBASE_KEYS = ("wheelbase", "wheel_separation_h")
RADIUS_KEYS = ("wheel_radius", "wheels_radius", "traction_wheels_radius", "rear_wheels_radius",
               "front_wheels_radius", "traction_wheel_radius", "rear_wheel_radius",
               "front_wheel_radius")
RADIUS_MULTIPLIERS = ("wheel_radius_multiplier", "left_wheel_radius_multiplier",
                      "right_wheel_radius_multiplier")


def compare(found, checked, sim, sections) -> tuple[list[Diagnostic], list[str]]:
    diagnostics, notes = [], []
    drive = sim.drive
    joints = {j.name for j in checked.robot.joints}
    if drive is not None:
        undecided = _undecided_variants(found.controllers, joints, checked.loaded)
        for path, keys in found.controllers:
            said = _controller(path, keys, drive, joints, sections, notes)
            diagnostics += [_variant_note(d, undecided) for d in said] \
                if path in undecided else said
    outline = figure_value(sections, "body.footprint")
    radius = figure_value(sections, "body.radius.circumscribed")
    for path, keys in found.nav2:
        diagnostics += _nav2(path, keys, outline, radius)
    blocked = blocked_sectors(sections)
    if blocked:
        diagnostics += _filters(found.filters, blocked)
    return sorted(set(diagnostics), key=Diagnostic.sort_key), notes


def _undecided_variants(controllers, joints: set[str], loaded) -> list[Path]:
    """The controller files of which mcar cannot tell the one the robot runs: two or more
    configure a drive controller of its wheels, the robot names none in ``<parameters>``
    and no launch of the package chose (:mod:`mobile_car.sim.control_variants`): ROSbot
    2's mecanum and differential files, where its launch were not found. [] otherwise."""
    from ..sim.control_config import _named_parameters, _names_in_order
    from ..sim.declared import in_yaml_mapping

    files = []
    for path, keys in controllers:
        declaration = in_yaml_mapping(keys, display_path(path), _names_in_order)
        if declaration is not None and any(n in joints for n in declaration.joints):
            files.append(path)
    files = list(dict.fromkeys(files))
    if len(files) < 2 or loaded is None or _named_parameters(loaded):
        return []
    return files


def _variant_note(diagnostic: Diagnostic, files: list[Path]) -> Diagnostic:
    """W510-W512's finding on a file of :func:`_undecided_variants`, said as a note."""
    names = ", ".join(display_path(path) for path in files)
    return Diagnostic("N405", diagnostic.file, diagnostic.line,
                      f"{diagnostic.message} [{diagnostic.rule}, if this variant runs it: "
                      f"the robot names none of {names} in <parameters>, and no launch of "
                      "the package chooses one by an argument of this build]")


def _at(rule: str, path: Path, key_node, message: str) -> Diagnostic:
    return Diagnostic(rule, display_path(path), key_node.start_mark.line + 1, message)


def _number(keys: dict, key: str) -> float | None:
    from ..sim.control_config import _number as number

    return number(keys[key][1]) if key in keys else None


def _controller(path, keys, drive, joints, sections, notes) -> list[Diagnostic]:
    from ..sim.control_config import _names_in_order
    from ..sim.declared import in_yaml_mapping
    declaration = in_yaml_mapping(keys, display_path(path), _names_in_order)
    if declaration is None or not any(n in joints for n in declaration.joints):
        return []  # not a drive controller, or another robot's
    found = []
    radius = figure_value(sections, "wheels.radius") or drive.radius
    if declaration.kind in ("differential", "skid-steer", "mecanum"):
        found += _names(path, keys, drive, joints)
    if declaration.kind in ("differential", "skid-steer") and \
            drive.kind in ("differential", "skid-steer"):
        track = figure_value(sections, "wheels.track") or drive.track
        found += _separation(path, keys, drive, track, notes)
    if declaration.kind == "ackermann" and drive.kind in ("ackermann", "bicycle"):
        wheelbase = figure_value(sections, "wheels.wheelbase") or drive.wheelbase
        for key in WHEELBASE_KEYS:
            value = _number(keys, key)
            if value is not None and _differs(value, wheelbase):
                found.append(_at("W510", path, keys[key][0],
                                 f"{key} {value:g} m, but the robot's wheelbase (rear axle "
                                 f"to steering pivots) is {wheelbase:.4g} m "
                                 f"({_off(value, wheelbase)})"))
    found += _radius(path, keys, radius)
    if declaration.kind == "mecanum" and drive.kind == "mecanum":
        found += _mecanum_kinematics(path, keys, drive, radius)
    return found


def _mecanum_kinematics(path, keys, drive, radius) -> list[Diagnostic]:
    """mecanum_drive_controller's ``kinematics``: ``wheels_radius`` (W511) and
    ``sum_of_robot_center_projection_on_X_Y_axis``, lx + ly (W510)."""
    import yaml

    node = keys.get("kinematics", (None, None))[1]
    if not isinstance(node, yaml.MappingNode):
        return []
    inner = {k.value: (k, v) for k, v in node.value if isinstance(k, yaml.ScalarNode)}
    found = _radius(path, inner, radius)
    key = "sum_of_robot_center_projection_on_X_Y_axis"
    value = _number(inner, key)
    from ..sim.mecanum import center_projection

    lx_ly = center_projection(drive.left + drive.right)
    if value is not None and _differs(value, lx_ly):
        found.append(_at("W510", path, inner[key][0],
                         f"{key} {value:g} m, but the wheels stand {lx_ly:.4g} m from the "
                         f"root frame along x plus along y ({_off(value, lx_ly)})"))
    return found


def _names(path, keys, drive, joints) -> list[Diagnostic]:
    """W512 for each joint a controller names that is not the drive wheel it names it as:
    a side's (differential, skid-steer), or a corner's (mecanum)."""
    from ..sim.control_config import _names_in_order
    from ..sim.declared import YAML_LEFT, YAML_MECANUM, YAML_RIGHT

    if drive.kind == "mecanum":
        corners = _corners(drive)
        where = {joint: corner.replace("_", " ") for corner, joint in corners.items()}
        groups = [(tag, [corners[tag.split("_wheel")[0]]]) for tag in YAML_MECANUM
                  if tag.split("_wheel")[0] in corners]
    else:
        sides = {"left": [w.joint for w in drive.left], "right": [w.joint for w in drive.right]}
        where = {joint: side for side, names in sides.items() for joint in names}
        groups = [(tag, sides["left"]) for tag in YAML_LEFT] + \
            [(tag, sides["right"]) for tag in YAML_RIGHT]
    found = []
    for tag, own in groups:
        if tag not in keys:
            continue
        for name in _names_in_order(keys[tag][1]):
            if name in own:
                continue
            if name not in joints:
                why = "the robot has no joint of that name"
            elif name in where:
                why = f"it is the {where[name]} wheel"
            else:
                why = f"it is no drive wheel ({', '.join(own)})"
            found.append(_at("W512", path, keys[tag][0], f"{tag} names {name}: {why}"))
    return found


def _corners(drive) -> dict[str, str]:
    """front_left, front_right, rear_left, rear_right -> the mecanum wheel's joint."""
    from ..sim.mecanum import corners

    return {corner: wheel.joint for corner, wheel in corners(drive.left + drive.right).items()}


def _separation(path, keys, drive, track, notes) -> list[Diagnostic]:
    key = next((k for k in SEPARATION_KEYS if k in keys), None)
    multiplier = _number(keys, "wheel_separation_multiplier")
    factor = multiplier if multiplier is not None and multiplier > 0 else 1.0
    if key is None:
        if multiplier is not None:
            notes.append(f"{display_path(path)}: no wheel_separation: the controller takes "
                         f"the wheels' spacing, {track:.4g} m, x wheel_separation_multiplier "
                         f"{factor:g} = {track * factor:.4g} m effective")
        return []
    value = _number(keys, key)
    if value is None:
        return []
    effective = value * factor
    said = (f"{key} {value:g} m x wheel_separation_multiplier {factor:g} = {effective:.4g} m "
            "effective" if multiplier is not None else f"{key} {value:g} m")
    if drive.kind == "skid-steer" and factor != 1.0:
        wrong, compared = _differs(value, track), value   # the correction is the multiplier's
        said = f"{key} {value:g} m (its multiplier {factor:g} holds the skid correction)"
    elif drive.kind == "skid-steer":
        wrong, compared = effective < track * (1 - TOLERANCE), effective
    else:
        wrong, compared = _differs(effective, track), effective
    if not wrong:
        return []
    names = " and ".join(", ".join(w.joint for w in g) for g in (drive.left, drive.right))
    return [_at("W510", path, keys[key][0],
                f"{said}, but the drive wheels {names} are {track:.4g} m apart "
                f"({_off(compared, track)}): odometry and turning rates would be off")]


def _radius(path, keys, radius) -> list[Diagnostic]:
    found = []
    for key in (k for k in RADIUS_KEYS if k in keys):
        value = _number(keys, key)
        if value is None:
            continue
        factors = [f for f in (_number(keys, m) for m in RADIUS_MULTIPLIERS) if f]
        factor = sum(factors) / len(factors) if factors else 1.0
        effective = value * factor
        if _differs(effective, radius):
            said = (f"{key} {value:g} m x its radius multiplier {factor:g} = {effective:.4g} m"
                    if factors else f"{key} {value:g} m")
            found.append(_at("W511", path, keys[key][0],
                             f"{said}, but the drive wheels' collision radius is "
                             f"{radius:.4g} m ({_off(effective, radius)}): the robot would "
                             "drive faster or slower than commanded"))
    return found


def _nav2(path, keys, outline, radius) -> list[Diagnostic]:
    found = []
    polygon = None
    if "footprint" in keys:
        polygon = _polygon(_footprint_value(keys["footprint"][1]))
        if polygon and outline:
            outside = [p for p in outline if not _covers(polygon, p)]
            if outside:
                x, y = max(outside, key=lambda p: _distance_out(polygon, p))
                found.append(_at("W513", path, keys["footprint"][0],
                                 f"footprint leaves part of the robot out: its outline "
                                 f"reaches ({x:.3f}, {y:.3f}) m, "
                                 f"{_distance_out(polygon, (x, y)) * 1000:.0f} mm outside "
                                 "(body.footprint, collision geometry at rest)"))
    if not polygon and "robot_radius" in keys and radius:
        value = _number(keys, "robot_radius")
        if value is not None and value < radius - FOOTPRINT_SLACK:
            found.append(_at("W513", path, keys["robot_radius"][0],
                             f"robot_radius {value:g} m, but the robot reaches "
                             f"{radius:.3f} m from its root (body.radius.circumscribed): "
                             "Nav2 would plan paths it cannot fit through"))
    return found


def _footprint_value(node):
    """A footprint as Nav2 writes it (the string "[[x, y], ...]", parsed by the bounded
    loader: a pull request's YAML may nest it a million deep) or as a YAML list."""
    import yaml

    from ..config.bounded_yaml import compose_and_load

    if isinstance(node, yaml.SequenceNode):
        return [[getattr(c, "value", None) for c in getattr(p, "value", ())]
                for p in node.value]
    if not isinstance(node, yaml.ScalarNode):
        return None
    try:
        return compose_and_load(node.value)[1]
    except (yaml.YAMLError, RecursionError):
        return None


def _polygon(value) -> list[tuple[float, float]] | None:
    if not isinstance(value, list) or len(value) < 3:
        return None
    try:
        points = [(float(x), float(y)) for x, y in value]
    except (TypeError, ValueError):
        return None
    return points if all(math.isfinite(c) for p in points for c in p) else None


def _covers(polygon, point) -> bool:
    return _inside(polygon, point) or _distance_out(polygon, point) <= FOOTPRINT_SLACK


def _inside(polygon, point) -> bool:
    x, y = point
    inside = False
    for (x1, y1), (x2, y2) in zip(polygon, polygon[1:] + polygon[:1], strict=True):
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            inside = not inside
    return inside


def _distance_out(polygon, point) -> float:
    """How far ``point`` lies from the polygon's edges (0 inside)."""
    if _inside(polygon, point):
        return 0.0
    px, py = point
    best = math.inf
    for (x1, y1), (x2, y2) in zip(polygon, polygon[1:] + polygon[:1], strict=True):
        dx, dy = x2 - x1, y2 - y1
        t = max(0.0, min(1.0, ((px - x1) * dx + (py - y1) * dy) / (dx * dx + dy * dy or 1)))
        best = min(best, math.hypot(px - x1 - t * dx, py - y1 - t * dy))
    return best


def _filters(filters, blocked) -> list[Diagnostic]:
    """W514 at each bounds filter chain that leaves part of a blocked sector in."""
    found = []
    by_file: dict[Path, list] = {}
    for path, keys in filters:
        by_file.setdefault(path, []).append(keys)
    for path, mappings in by_file.items():
        bounds, first = [], None
        for keys in mappings:
            kind = getattr(keys.get("type", (None, None))[1], "value", "")
            if "AngularBoundsFilterInPlace" not in str(kind) or "params" not in keys:
                continue
            first = first or keys["type"][0]
            params = _params(keys["params"][1])
            if params is not None:
                bounds.append(params)
        if first is None:
            continue
        for sensor, sectors in blocked.items():
            for lower, upper in sectors:
                if not any(lo <= lower + 1e-4 and hi >= upper - 1e-4 for lo, hi in bounds):
                    found.append(_at("W514", path, first,
                                     f"no angular bounds filter covers {sensor}'s blocked "
                                     f"sector {lower:.3f}..{upper:.3f} rad "
                                     f"({math.degrees(lower):.1f}..{math.degrees(upper):.1f} "
                                     "deg): the robot's own body stays in its scans"))
    return found


def _params(node):
    import yaml

    if not isinstance(node, yaml.MappingNode):
        return None
    values = {k.value: v for k, v in node.value if isinstance(k, yaml.ScalarNode)}
    try:
        return float(values["lower_angle"].value), float(values["upper_angle"].value)
    except (KeyError, AttributeError, ValueError):
        return None


def _differs(value: float, actual: float) -> bool:
    return abs(value - actual) > TOLERANCE * abs(actual)


def _off(value: float, actual: float) -> str:
    return f"{100 * (value - actual) / actual:+.1f}%" if actual else "off"
