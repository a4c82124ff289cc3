"""The sensors a robot carries, as ``mcar specs`` reads them: every lidar and camera its
``<gazebo reference="LINK"><sensor>`` blocks declare (Gazebo classic's ``<ray>``, gz's
``<lidar>``, ``<camera>``), else the links named like one, with stated defaults.

Only what the description says is read here (no geometry, no numpy): the sensor's place
on its link, its samples, angles, range, field of view. :mod:`.self_view` casts its rays.
Angles in rad, lengths in m.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..check.urdf_model import parse_number

LIDAR_TYPES = ("ray", "gpu_ray", "lidar", "gpu_lidar")
CAMERA_TYPES = ("camera", "depth", "depth_camera", "rgbd_camera")
# A link named so is a lidar's frame where no <sensor> declares one (TurtleBot3's
# base_scan, a hokuyo_link, velodyne).
LIDAR_WORDS = ("laser", "lidar", "scan", "hokuyo", "velodyne", "lms1xx", "ouster", "urg")
CAMERA_WORDS = ("camera",)
# An optical frame looks along z (REP 103's camera_optical_frame), not the sensor's x.
NOT_A_SENSOR_FRAME = ("optical",)
# Stated defaults for a lidar known by its link's name only: RPLIDAR A1-class, one sample
# a degree around the turn.
DEFAULT_SAMPLES = 360
DEFAULT_MIN_ANGLE = -math.pi
DEFAULT_MAX_ANGLE = math.pi - 2 * math.pi / DEFAULT_SAMPLES
DEFAULT_RANGE = (0.12, 12.0)
# Gazebo's own defaults for a camera (sdformat camera.sdf): 60 degrees, 320 x 240.
DEFAULT_HFOV = 1.047
DEFAULT_IMAGE = (320, 240)
DEFAULT_FAR = 100.0
# More rays than this in one scan is no scanner (the bundled car's config allows 100,000):
# the count comes from the description and sizes the arrays cast, so it is bounded.
MAX_SAMPLES = 100_000


@dataclass
class Sensor:
    """One lidar or camera: ``name`` (the <sensor>'s, else its link's), ``kind`` "lidar"
    or "camera", the ``link`` it rides on and ``pose`` (x, y, z, roll, pitch, yaw) on that
    link's frame (then a camera's ``camera_pose`` on the sensor's, as SDF composes them);
    ``source`` says where it was read (file:line) or which defaults it takes; ``element``
    the <sensor> (None when known by name)."""

    name: str
    kind: str
    link: str
    pose: tuple = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    camera_pose: tuple = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)  # a <camera><pose>, on the sensor's
    source: str = ""
    element: object = None
    file: str | None = None
    line: int | None = None
    samples: int = DEFAULT_SAMPLES
    min_angle: float = DEFAULT_MIN_ANGLE
    max_angle: float = DEFAULT_MAX_ANGLE
    range_min: float = DEFAULT_RANGE[0]
    range_max: float = DEFAULT_RANGE[1]
    hfov: float = DEFAULT_HFOV
    image: tuple = DEFAULT_IMAGE
    layers: int = 1  # a 3D lidar's <vertical><samples>: its horizontal plane is cast
    defaults: list[str] = field(default_factory=list)  # what the description left out

    def azimuths(self) -> list[float]:
        """Each sample's angle (rad, sensor frame), as Gazebo spreads them: min to max in
        samples - 1 steps (min alone for one sample)."""
        if self.samples == 1:
            return [self.min_angle]
        step = (self.max_angle - self.min_angle) / (self.samples - 1)
        return [self.min_angle + i * step for i in range(self.samples)]

    @property
    def step(self) -> float:
        return 0.0 if self.samples == 1 else \
            (self.max_angle - self.min_angle) / (self.samples - 1)


class SensorProblem(ValueError):
    """A sensor whose figures cannot be read (a number that is none, too many samples)."""


def find_sensors(robot, where) -> tuple[list[Sensor], list[str]]:
    """(the lidars and cameras of ``robot`` (check's Robot), notes on those left out);
    ``where``: element -> (file, line, note), check's source map."""
    links = {link.name for link in robot.links}
    found, notes, declared = [], [], set()
    for gazebo in robot.element.iterchildren("gazebo"):
        link = gazebo.get("reference")
        for element in gazebo.iterchildren("sensor"):
            kind = _kind(element.get("type"))
            if kind is None:
                continue
            declared.add(kind)
            file, line, _ = where(element)
            name = element.get("name") or link or "sensor"
            at = f"{file}:{line}" if line else file
            if link is None:
                notes.append(f"sensor {name} ({at}): in a <gazebo> block without a "
                             "reference, on no link: left out")
                continue
            if link not in links:
                notes.append(f"sensor {name} ({at}): <gazebo reference=\"{link}\"> names no "
                             "link of the robot: left out")
                continue
            try:
                sensor = _declared(element, kind, name, link)
            except SensorProblem as problem:
                notes.append(f"sensor {name} ({at}): {problem}: left out")
                continue
            sensor.file, sensor.line, sensor.element = file, line, element
            sensor.source = f"<sensor type=\"{element.get('type')}\"> on link {link} ({at})"
            if sensor.defaults:
                sensor.source += f"; not given, taken as {', '.join(sensor.defaults)}"
            found.append(sensor)
    # Names are a guess where the description declares no sensor of the kind: one it
    # declares, even one left out, says where its sensors are.
    for kind, words in (("lidar", LIDAR_WORDS), ("camera", CAMERA_WORDS)):
        if kind not in declared:
            found += _named(robot, kind, words, where)
    return _unique(found), notes


def _kind(type_text) -> str | None:
    kind = (type_text or "").strip()
    return "lidar" if kind in LIDAR_TYPES else "camera" if kind in CAMERA_TYPES else None


def _declared(element, kind: str, name: str, link: str) -> Sensor:
    sensor = Sensor(name, kind, link, pose=_pose(element.find("pose")))
    if kind == "lidar":
        block = element.find("ray")
        if block is None:
            block = element.find("lidar")
        horizontal = _path(block, "scan", "horizontal")
        samples = _number(horizontal, "samples")
        resolution = _number(horizontal, "resolution")
        if samples is not None:
            count = samples * (resolution if resolution and resolution > 0 else 1.0)
            if not 1 <= count <= MAX_SAMPLES:
                raise SensorProblem(f"{count:g} samples, outside 1..{MAX_SAMPLES:,}")
            sensor.samples = max(1, round(count))
        else:
            sensor.defaults.append(f"{DEFAULT_SAMPLES} samples")
        for attribute, tag in (("min_angle", "min_angle"), ("max_angle", "max_angle")):
            value = _number(horizontal, tag)
            if value is None:
                sensor.defaults.append(f"{tag} {math.degrees(getattr(sensor, attribute)):g}°")
            else:
                setattr(sensor, attribute, value)
        for attribute, tag in (("range_min", "min"), ("range_max", "max")):
            value = _number(_path(block, "range"), tag)
            if value is None:
                sensor.defaults.append(f"range {tag} {getattr(sensor, attribute):g} m")
            else:
                setattr(sensor, attribute, value)
        layers = _number(_path(block, "scan", "vertical"), "samples")
        sensor.layers = round(layers) if layers and 1 <= layers <= MAX_SAMPLES else 1
        if sensor.max_angle < sensor.min_angle:
            raise SensorProblem("max_angle below min_angle")
        if not 0 <= sensor.range_min < sensor.range_max:
            raise SensorProblem("range min and max are not 0 <= min < max")
    else:
        camera = element.find("camera")
        sensor.camera_pose = _pose(_path(camera, "pose"))
        value = _number(camera, "horizontal_fov")
        if value is None:
            sensor.defaults.append(f"horizontal_fov {DEFAULT_HFOV} rad")
        elif not 0 < value < math.pi:
            raise SensorProblem(f"horizontal_fov {value:g} rad, outside 0..pi")
        else:
            sensor.hfov = value
        image = _path(camera, "image")
        width, height = _number(image, "width"), _number(image, "height")
        if width and height and width > 0 and height > 0:
            sensor.image = (width, height)
        else:
            sensor.defaults.append("image {}x{}".format(*DEFAULT_IMAGE))
        # From the lens: a near clip is where Gazebo starts drawing, not what the lens
        # sees (Husky's Blackfly clips at 0.5 m, its front laser 0.19 m ahead).
        far = _number(_path(camera, "clip"), "far")
        sensor.range_min, sensor.range_max = 0.0, far if far and far > 0 else DEFAULT_FAR
    return sensor


def _named(robot, kind: str, words, where) -> list[Sensor]:
    """The links named like a ``kind`` (``words``), but for one whose child is named so
    too (a laser_mount above its laser): the sensor's frame is the last of them."""
    def named(name: str) -> bool:
        lower = name.lower()
        return any(w in lower for w in words) and not any(w in lower for w in
                                                          NOT_A_SENSOR_FRAME)

    children = {}
    for joint in robot.joints:
        children.setdefault(joint.parent, []).append(joint.child)
    found = []
    for link in robot.links:
        if not link.name or not named(link.name):
            continue
        if any(named(child) for child in children.get(link.name, ())):
            continue
        file, line, _ = where(link.element)
        at = f"{file}:{line}" if line else file
        sensor = Sensor(link.name, kind, link.name, file=file, line=line)
        if kind == "lidar":
            sensor.source = (f"link {link.name} ({at}), named like a lidar, no <sensor>: "
                             f"default {DEFAULT_SAMPLES} samples from "
                             f"{math.degrees(DEFAULT_MIN_ANGLE):g}° to "
                             f"{math.degrees(DEFAULT_MAX_ANGLE):g}°, range "
                             f"{DEFAULT_RANGE[0]:g}..{DEFAULT_RANGE[1]:g} m")
        else:
            sensor.source = (f"link {link.name} ({at}), named like a camera, no <sensor>: "
                             f"default horizontal_fov {DEFAULT_HFOV} rad, image "
                             "{}x{}, looking along the link's x".format(*DEFAULT_IMAGE))
            sensor.range_min, sensor.range_max = 0.0, DEFAULT_FAR
        found.append(sensor)
    return found


def _unique(sensors: list[Sensor]) -> list[Sensor]:
    """Names made unique (two <sensor name="laser">): the later ones take _2, _3..."""
    seen: dict[str, int] = {}
    for sensor in sensors:
        count = seen.get(sensor.name, 0) + 1
        seen[sensor.name] = count
        if count > 1:
            sensor.name = f"{sensor.name}_{count}"
    return sensors


def _path(element, *tags):
    for tag in tags:
        if element is None:
            return None
        element = element.find(tag)
    return element


def _number(parent, tag: str) -> float | None:
    """The finite number in ``parent``'s ``<tag>``, None where there is none."""
    element = None if parent is None else parent.find(tag)
    if element is None or not (element.text or "").strip():
        return None
    value = parse_number(element.text.strip())
    if value is None or not math.isfinite(value):
        raise SensorProblem(f"<{tag}> {element.text.strip()[:40]!r} is not a finite number")
    return value


def _pose(element) -> tuple:
    """A <pose> "x y z roll pitch yaw" (SDF's, on the sensor's link); zeros without one."""
    if element is None or not (element.text or "").strip():
        return (0.0,) * 6
    values = [parse_number(v) for v in element.text.split()]
    if len(values) != 6 or any(v is None or not math.isfinite(v) for v in values):
        raise SensorProblem(f"<pose> {element.text.strip()[:60]!r} is not six finite numbers")
    return tuple(values)
