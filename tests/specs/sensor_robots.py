"""Robots made at test time for the sensors section: a box body, a sensor on a link above
it, and posts and walls of known size at known places, so what the sensor sees of the
robot is known in closed form. Lengths in m, angles in rad. And the one way the tests
check a robot and take its sensors section."""

from __future__ import annotations

import math
from pathlib import Path

from mobile_car.check.checker import check_input
from mobile_car.load.inputs import RobotInput
from mobile_car.load.robot import LoadOptions

BODY = (0.30, 0.20, 0.10)  # the body box, its underside at z 0.05
LIDAR_Z = 0.30             # the scan plane's height


def box(size, xyz=(0, 0, 0), rpy=(0, 0, 0), visual=True, collision=True) -> str:
    origin = f'<origin xyz="{" ".join(f"{v:.9g}" for v in xyz)}" ' \
             f'rpy="{" ".join(f"{v:.9g}" for v in rpy)}"/>'
    shape = f'<geometry><box size="{" ".join(f"{v:.9g}" for v in size)}"/></geometry>'
    return (f"<visual>{origin}{shape}</visual>" if visual else "") + \
        (f"<collision>{origin}{shape}</collision>" if collision else "")


def link(name: str, parent: str, xyz, body: str = "", rpy=(0, 0, 0), mass=0.1) -> str:
    """A link fixed to ``parent`` at ``xyz``, ``rpy``, holding ``body`` (its shapes)."""
    inertial = f'<inertial><mass value="{mass}"/><inertia ixx="1e-4" ixy="0" ixz="0" ' \
               'iyy="1e-4" iyz="0" izz="1e-4"/></inertial>'
    return (f'<joint name="{name}_joint" type="fixed"><parent link="{parent}"/>'
            f'<child link="{name}"/><origin xyz="{" ".join(f"{v:.9g}" for v in xyz)}" '
            f'rpy="{" ".join(f"{v:.9g}" for v in rpy)}"/></joint>'
            f'<link name="{name}">{body}{inertial}</link>')


def robot(*parts: str, name: str = "sensed") -> str:
    """A box body (base_link) and ``parts`` (links, <gazebo> blocks)."""
    x, y, z = BODY
    return (f'<?xml version="1.0"?>\n<robot name="{name}">'
            f'<link name="base_link">{box(BODY, (0, 0, 0.05 + z / 2))}'
            '<inertial><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" '
            'iyz="0" izz="0.01"/></inertial></link>' + "".join(parts) + "</robot>\n")


def lidar_link(name: str = "lidar_link", xyz=(0, 0, LIDAR_Z), rpy=(0, 0, 0)) -> str:
    """The scanner: its housing a small box around its origin (left out of its view)."""
    return link(name, "base_link", xyz, box((0.04, 0.04, 0.04)), rpy)


def post(name: str, centre, side: float, top: float = 0.5, **kinds) -> str:
    """A square post ``side`` wide standing on the body, centred at (x, y), up to ``top``."""
    x, y = centre
    bottom = 0.05 + BODY[2]
    return link(name, "base_link", (x, y, (bottom + top) / 2),
                box((side, side, top - bottom), **kinds))


def ray_sensor(link_name: str, samples=360, min_angle=-math.pi,
               max_angle=math.pi - 2 * math.pi / 360, near=0.1, far=10.0, kind="ray",
               block="ray", pose="") -> str:
    """A <gazebo reference> lidar: Gazebo classic's <ray>, or gz's <lidar> block."""
    pose = f"<pose>{pose}</pose>" if pose else ""
    return (f'<gazebo reference="{link_name}"><sensor name="scanner" type="{kind}">{pose}'
            f"<{block}><scan><horizontal><samples>{samples}</samples>"
            f"<resolution>1</resolution><min_angle>{min_angle}</min_angle>"
            f"<max_angle>{max_angle}</max_angle></horizontal></scan>"
            f"<range><min>{near}</min><max>{far}</max></range></{block}>"
            "</sensor></gazebo>")


def camera_sensor(link_name: str, hfov: float, width=640, height=480, far=20.0) -> str:
    return (f'<gazebo reference="{link_name}"><sensor name="eye" type="camera">'
            f"<camera><horizontal_fov>{hfov}</horizontal_fov><image><width>{width}</width>"
            f"<height>{height}</height></image><clip><near>0.02</near><far>{far}</far></clip>"
            "</camera></sensor></gazebo>")


def sensors_of(path: Path, text: str | None = None, options=None, sim=None,
               package_paths=(), mappings=None):
    """(the CheckResult, the sensors Section) of the robot at ``path`` (written first
    when ``text`` is given)."""
    from mobile_car.specs.sensors import sensors_section

    if text is not None:
        path.write_text(text)
    checked = check_input(RobotInput(path), LoadOptions(package_paths=list(package_paths),
                                                        mappings=dict(mappings or {})))
    assert checked.failure is None and not [d for d in checked.diagnostics if d.is_error], \
        checked.diagnostics
    return checked, sensors_section(checked, sim, options or {})


def values(section) -> dict:
    return {figure.key: figure.value for figure in section.figures}


def subtended(corners, origin=(0.0, 0.0)) -> tuple[float, float]:
    """(min, max) azimuth in degrees of ``corners`` (x, y) seen from ``origin``."""
    angles = [math.degrees(math.atan2(y - origin[1], x - origin[0])) for x, y in corners]
    return min(angles), max(angles)


def square(centre, side: float) -> list[tuple[float, float]]:
    x, y = centre
    h = side / 2
    return [(x - h, y - h), (x - h, y + h), (x + h, y - h), (x + h, y + h)]
