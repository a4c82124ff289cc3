"""Robots for the specs-mechanics tests (inertia, joints), written at test time: masses
as points (tiny spheres) where a test wants a gravity load it can work out by hand, and
every inertia from its shape where it wants none flagged. Lengths in m, masses in kg,
angles in rad."""

from __future__ import annotations

import math
from pathlib import Path

G = 9.81


def point_inertia(m: float, r: float = 0.01) -> str:
    """A solid sphere of radius ``r``: a mass all but at its centre."""
    i = 0.4 * m * r * r
    return f'<inertia ixx="{i:.6g}" ixy="0" ixz="0" iyy="{i:.6g}" iyz="0" izz="{i:.6g}"/>'


def box_inertia(m: float, x: float, y: float, z: float) -> str:
    return (f'<inertia ixx="{m * (y * y + z * z) / 12:.9g}" ixy="0" ixz="0" '
            f'iyy="{m * (x * x + z * z) / 12:.9g}" iyz="0" izz="{m * (x * x + y * y) / 12:.9g}"/>')


BASE = f"""
  <link name="base_link">
    <collision><origin xyz="0 0 0.05"/><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
    <inertial><origin xyz="0 0 0.05"/><mass value="10"/>
      {box_inertia(10, 0.4, 0.3, 0.1)}</inertial>
  </link>"""


def lift(mass: float = 5.0, effort: float = 20.0) -> str:
    """A prismatic lift along z carrying ``mass`` (a 0.1 m cube): it needs mass·g."""
    return f"""<?xml version="1.0"?>
<robot name="lift">{BASE}
  <joint name="lift_joint" type="prismatic">
    <parent link="base_link"/><child link="carriage"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>
    <limit lower="0" upper="0.3" effort="{effort:g}" velocity="0.1"/>
  </joint>
  <link name="carriage">
    <collision><origin xyz="0 0 0.05"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
    <inertial><origin xyz="0 0 0.05"/><mass value="{mass:g}"/>
      {box_inertia(mass, 0.1, 0.1, 0.1)}</inertial>
  </link>
</robot>
"""


def arm(m1: float = 2.0, l1: float = 0.4, m2: float = 1.0, l2: float = 0.3,
        tilt: float = 0.5, shoulder: tuple = (-0.2, 1.5), elbow: tuple = (-1.0, 1.0),
        effort: float = 100.0, elbow_effort: float = 100.0) -> str:
    """A two-link arm on the base, both joints about y. At 0 the upper arm points ``tilt``
    rad above the horizontal (forward, up); its mass ``m1`` is a point at ``l1`` from the
    shoulder; the forearm's ``m2`` at ``l2`` beyond the elbow, straight on at 0. Turning
    the shoulder by q lowers the arm by q: it is horizontal at q = tilt."""
    cx, cz = math.cos(tilt), math.sin(tilt)
    return f"""<?xml version="1.0"?>
<robot name="arm">{BASE}
  <joint name="shoulder" type="revolute">
    <parent link="base_link"/><child link="upper_arm"/>
    <origin xyz="0 0 0.2"/><axis xyz="0 1 0"/>
    <limit lower="{shoulder[0]:g}" upper="{shoulder[1]:g}" effort="{effort:g}" velocity="1"/>
  </joint>
  <link name="upper_arm">
    <inertial><origin xyz="{l1 * cx:.9g} 0 {l1 * cz:.9g}"/><mass value="{m1:g}"/>
      {point_inertia(m1)}</inertial>
  </link>
  <joint name="elbow" type="revolute">
    <parent link="upper_arm"/><child link="forearm"/>
    <origin xyz="{l1 * cx:.9g} 0 {l1 * cz:.9g}"/><axis xyz="0 1 0"/>
    <limit lower="{elbow[0]:g}" upper="{elbow[1]:g}" effort="{elbow_effort:g}" velocity="1"/>
  </joint>
  <link name="forearm">
    <inertial><origin xyz="{l2 * cx:.9g} 0 {l2 * cz:.9g}"/><mass value="{m2:g}"/>
      {point_inertia(m2)}</inertial>
  </link>
</robot>
"""


def steering(effort: float = 0.0, offset: float = 0.05, mass: float = 2.0,
             kingpin: float = 0.2) -> str:
    """A steering joint whose axis leans ``kingpin`` rad off the vertical (about x), its
    ``mass`` ``offset`` m out to the side: gravity turns it (Hunter 2's steering)."""
    return f"""<?xml version="1.0"?>
<robot name="steer">{BASE}
  <joint name="steer_joint" type="revolute">
    <parent link="base_link"/><child link="knuckle"/>
    <origin xyz="0.2 0.15 0.05" rpy="{kingpin:g} 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-0.6" upper="0.6" effort="{effort:g}" velocity="1"/>
  </joint>
  <link name="knuckle">
    <inertial><origin xyz="0 {offset:g} 0"/><mass value="{mass:g}"/>
      {point_inertia(mass)}</inertial>
  </link>
</robot>
"""


def written(folder: Path, name: str, text: str) -> Path:
    path = folder / name
    path.write_text(text)
    return path


