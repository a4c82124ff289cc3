"""Robots the specs tests measure, as URDF text, with round numbers so that every figure
can be worked out by hand in the test that checks it. Lengths in m, masses in kg."""

from __future__ import annotations

from sim.robot_makers import box_inertia, skid_steer

# A box on two wheels and a castor ball; the root frame at the axle.
BODY = (0.30, 0.20, 0.10)       # size
BODY_AT = (0.05, 0.0, 0.08)     # its centre
BODY_MASS = 4.0
WHEEL_RADIUS, WHEEL_WIDTH, WHEEL_Y, WHEEL_MASS = 0.05, 0.04, 0.13, 0.5
BALL_RADIUS, BALL_AT, BALL_MASS = 0.02, (0.15, 0.0, -0.03), 0.2


def box_on_wheels(extra: str = "", collision: bool = True) -> str:
    """A differential car: the body box, two wheels turning about y whose outer faces
    stand out of the body's sides, a castor ball ahead reaching the wheels' floor."""
    x, y, z = BODY_AT

    def shape(geometry: str, origin: str = "") -> str:
        return f"<collision>{origin}<geometry>{geometry}</geometry></collision>" \
            if collision else f"<visual>{origin}<geometry>{geometry}</geometry></visual>"

    wheel_side = WHEEL_MASS * (3 * WHEEL_RADIUS ** 2 + WHEEL_WIDTH ** 2) / 12
    parts = [f"""<?xml version="1.0"?>
<robot name="box_on_wheels">
  <link name="base_link">
    {shape(f'<box size="{BODY[0]} {BODY[1]} {BODY[2]}"/>', f'<origin xyz="{x} {y} {z}"/>')}
    <inertial><origin xyz="{x} {y} {z}"/><mass value="{BODY_MASS}"/>
      {box_inertia(BODY_MASS, *BODY)}</inertial>
  </link>"""]
    for side, sign in (("left", 1), ("right", -1)):
        parts.append(f"""
  <joint name="wheel_{side}_joint" type="continuous">
    <parent link="base_link"/><child link="wheel_{side}_link"/>
    <origin xyz="0 {sign * WHEEL_Y} 0"/><axis xyz="0 1 0"/>
  </joint>
  <link name="wheel_{side}_link">
    {shape(f'<cylinder radius="{WHEEL_RADIUS}" length="{WHEEL_WIDTH}"/>',
           '<origin rpy="1.5707963267948966 0 0"/>')}
    <inertial><mass value="{WHEEL_MASS}"/><inertia ixx="{wheel_side:.6g}" ixy="0" ixz="0"
      iyy="{WHEEL_MASS * WHEEL_RADIUS ** 2 / 2:.6g}" iyz="0" izz="{wheel_side:.6g}"/></inertial>
  </link>""")
    ball = 0.4 * BALL_MASS * BALL_RADIUS ** 2
    parts.append(f"""
  <joint name="castor_joint" type="fixed">
    <parent link="base_link"/><child link="castor_link"/>
    <origin xyz="{BALL_AT[0]} {BALL_AT[1]} {BALL_AT[2]}"/>
  </joint>
  <link name="castor_link">
    {shape(f'<sphere radius="{BALL_RADIUS}"/>')}
    <inertial><mass value="{BALL_MASS}"/><inertia ixx="{ball:.6g}" ixy="0" ixz="0"
      iyy="{ball:.6g}" iyz="0" izz="{ball:.6g}"/></inertial>
  </link>{extra}
</robot>
""")
    return "".join(parts)


PAYLOAD_MASS, PAYLOAD_X = 4.0, 0.15


def four_wheels_loaded() -> str:
    """sim's skid-steer box (20 kg, wheelbase 0.4 m) with a payload of PAYLOAD_MASS kg
    PAYLOAD_X ahead of its centre: four supports, statically indeterminate."""
    payload = f"""
  <joint name="payload_joint" type="fixed">
    <parent link="base_link"/><child link="payload_link"/>
    <origin xyz="{PAYLOAD_X} 0 0.2"/>
  </joint>
  <link name="payload_link">
    <inertial><mass value="{PAYLOAD_MASS}"/>{box_inertia(PAYLOAD_MASS, 0.1, 0.1, 0.1)}</inertial>
  </link>"""
    return skid_steer(extra=payload)
