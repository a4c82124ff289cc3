"""Robots made at test time, one function per drive kind, as URDF text: a box body on
wheels of given size and mass, every inertia from its shape (box, cylinder, sphere), so
that what the simulation measures depends only on the geometry the test chose.
Lengths in m, masses in kg, angles in rad."""

from __future__ import annotations

import math


def box_inertia(m, x, y, z):
    return (f'<inertia ixx="{m * (y * y + z * z) / 12:.6g}" ixy="0" ixz="0" '
            f'iyy="{m * (x * x + z * z) / 12:.6g}" iyz="0" izz="{m * (x * x + y * y) / 12:.6g}"/>')


def _cylinder_y_inertia(m, r, width):
    """A wheel turning about y: its axle's moment m·r²/2, the others m(3r²+w²)/12."""
    side = m * (3 * r * r + width * width) / 12
    return (f'<inertia ixx="{side:.6g}" ixy="0" ixz="0" iyy="{m * r * r / 2:.6g}" iyz="0" '
            f'izz="{side:.6g}"/>')


def _body(mass, size, lift, colour="0.8 0.1 0.1 1", axle=0.0):
    """A box ``lift`` above the axles, under a massless base_footprint ``axle`` below them
    (a root with an inertia is lost on KDL: check --strict warns, W208)."""
    x, y, z = size
    return f"""
  <material name="body_colour"><color rgba="{colour}"/></material>
  <link name="base_footprint"/>
  <joint name="base_joint" type="fixed">
    <parent link="base_footprint"/><child link="base_link"/><origin xyz="0 0 {axle:.6g}"/>
  </joint>
  <link name="base_link">
    <visual><origin xyz="0 0 {z / 2 + lift:.6g}"/>
      <geometry><box size="{x:.6g} {y:.6g} {z:.6g}"/></geometry>
      <material name="body_colour"/></visual>
    <collision><origin xyz="0 0 {z / 2 + lift:.6g}"/>
      <geometry><box size="{x:.6g} {y:.6g} {z:.6g}"/></geometry></collision>
    <inertial><origin xyz="0 0 {z / 2 + lift:.6g}"/><mass value="{mass:.6g}"/>
      {box_inertia(mass, x, y, z)}</inertial>
  </link>"""


def _wheel(name, parent, xyz, radius, width, mass, limit="", joint_type="continuous"):
    x, y, z = xyz
    return f"""
  <joint name="{name}_joint" type="{joint_type}">
    <parent link="{parent}"/><child link="{name}_link"/>
    <origin xyz="{x:.6g} {y:.6g} {z:.6g}"/><axis xyz="0 1 0"/>{limit}
  </joint>
  <link name="{name}_link">
    <visual><origin rpy="1.5707963 0 0"/>
      <geometry><cylinder radius="{radius:.6g}" length="{width:.6g}"/></geometry></visual>
    <collision><origin rpy="1.5707963 0 0"/>
      <geometry><cylinder radius="{radius:.6g}" length="{width:.6g}"/></geometry></collision>
    <inertial><mass value="{mass:.6g}"/>{_cylinder_y_inertia(mass, radius, width)}</inertial>
  </link>"""


def two_wheeler(mass: float = 0.7, scale: float = 1.0, castors: int = 1, limit: str = "",
                extra: str = "") -> str:
    """A car of ``mass`` kg: a box body on two drive wheels and ``castors`` ball castors,
    every length ``scale`` times the bundled car's; ``limit``: the wheel joints' <limit>."""
    r, width, track = 0.033 * scale, 0.02 * scale, 0.16 * scale
    body = (0.2 * scale, 0.12 * scale, 0.05 * scale)
    ball = 0.012 * scale
    wheel_mass, castor_mass = 0.08 * mass, 0.04 * mass / castors
    base_mass = mass - 2 * wheel_mass - castors * castor_mass
    wheel_i = wheel_mass * (3 * r * r + width * width) / 12
    parts = [f"""<?xml version="1.0"?>
<robot name="two_wheeler">
  <link name="base_link">
    <collision><origin xyz="0 0 {body[2] / 2 + 0.3 * r:.6g}"/>
      <geometry><box size="{body[0]:.6g} {body[1]:.6g} {body[2]:.6g}"/></geometry></collision>
    <inertial><origin xyz="0 0 {body[2] / 2 + 0.3 * r:.6g}"/><mass value="{base_mass:.6g}"/>
      {box_inertia(base_mass, *body)}</inertial>
  </link>"""]
    for side, y in (("left", track / 2), ("right", -track / 2)):
        parts.append(f"""
  <joint name="wheel_{side}_joint" type="continuous">
    <parent link="base_link"/><child link="wheel_{side}_link"/>
    <origin xyz="0 {y:.6g} 0" rpy="-1.5707963 0 0"/><axis xyz="0 0 1"/>{limit}
  </joint>
  <link name="wheel_{side}_link">
    <collision><geometry><cylinder radius="{r:.6g}" length="{width:.6g}"/></geometry></collision>
    <inertial><mass value="{wheel_mass:.6g}"/><inertia ixx="{wheel_i:.6g}" ixy="0" ixz="0"
      iyy="{wheel_i:.6g}" iyz="0" izz="{wheel_mass * r * r / 2:.6g}"/></inertial>
  </link>""")
    ys = [0.0] if castors == 1 else [body[1] / 3, -body[1] / 3]
    for number, y in enumerate(ys, 1):
        parts.append(f"""
  <joint name="castor_{number}_joint" type="fixed">
    <parent link="base_link"/><child link="castor_{number}_link"/>
    <origin xyz="{-0.08 * scale:.6g} {y:.6g} {ball - r:.6g}"/>
  </joint>
  <link name="castor_{number}_link">
    <collision><geometry><sphere radius="{ball:.6g}"/></geometry></collision>
    <inertial><mass value="{castor_mass:.6g}"/><inertia ixx="{0.4 * castor_mass * ball * ball:.6g}"
      ixy="0" ixz="0" iyy="{0.4 * castor_mass * ball * ball:.6g}" iyz="0"
      izz="{0.4 * castor_mass * ball * ball:.6g}"/></inertial>
  </link>""")
    parts.append(extra + "\n</robot>\n")
    return "".join(parts)


def skid_steer(per_side: int = 2, mass: float = 20.0, wheelbase: float = 0.4,
               track: float = 0.45, radius: float = 0.1, extra: str = "",
               limit: str = "") -> str:
    """A box on ``per_side`` wheels a side, evenly spaced over ``wheelbase``, every wheel
    on a continuous joint without <limit> (as Husky's and Jackal's) unless ``limit``
    gives one."""
    width = 0.25 * radius
    wheel_mass = 0.05 * mass
    body_mass = mass - 2 * per_side * wheel_mass
    body = (wheelbase + 2 * radius, track - width - 0.02, 0.6 * radius)
    xs = [wheelbase / 2 - i * wheelbase / (per_side - 1) for i in range(per_side)]
    names = ["front", "middle", "rear"] if per_side == 3 else ["front", "rear"]
    parts = [f'<?xml version="1.0"?>\n<robot name="skid_steer_{2 * per_side}">',
             _body(body_mass, body, 0.2 * radius, axle=radius)]
    for name, x in zip(names, xs, strict=False):
        for side, sign in (("left", 1), ("right", -1)):
            parts.append(_wheel(f"{name}_{side}_wheel", "base_link", (x, sign * track / 2, 0),
                                radius, width, wheel_mass, limit))
    parts.append(extra + "\n</robot>\n")
    return "".join(parts)


def ackermann(mass: float = 8.0, wheelbase: float = 0.5, track: float = 0.4,
              radius: float = 0.08, steer_limit: float = 0.6, steer_effort: float = 20.0,
              transmissions: bool = False) -> str:
    """A car: a box on two rear wheels and two front wheels, each front wheel on a
    knuckle link that a revolute steering joint (axis up, ±``steer_limit``) turns;
    ``transmissions``: a <transmission> on each of the four wheel joints (all-wheel
    drive), else none (rear-wheel drive)."""
    width = 0.3 * radius
    wheel_mass, knuckle_mass = 0.05 * mass, 0.01 * mass
    body_mass = mass - 4 * wheel_mass - 2 * knuckle_mass
    body = (wheelbase + 2 * radius, track - width - 0.06, 0.6 * radius)
    parts = ['<?xml version="1.0"?>\n<robot name="ackermann_car">',
             _body(body_mass, body, 0.2 * radius, "0.1 0.3 0.9 1", axle=radius)]
    knuckle_i = 0.4 * knuckle_mass * 0.02 ** 2
    for side, sign in (("left", 1), ("right", -1)):
        y = sign * track / 2
        parts.append(_wheel(f"rear_{side}_wheel", "base_link", (-wheelbase / 2, y, 0), radius,
                            width, wheel_mass))
        parts.append(f"""
  <joint name="front_{side}_steering_joint" type="revolute">
    <parent link="base_link"/><child link="front_{side}_knuckle"/>
    <origin xyz="{wheelbase / 2:.6g} {y:.6g} 0"/><axis xyz="0 0 1"/>
    <limit lower="{-steer_limit:.6g}" upper="{steer_limit:.6g}" effort="{steer_effort:g}"
           velocity="3"/>
  </joint>
  <link name="front_{side}_knuckle">
    <inertial><mass value="{knuckle_mass:.6g}"/><inertia ixx="{knuckle_i:.6g}" ixy="0"
      ixz="0" iyy="{knuckle_i:.6g}" iyz="0" izz="{knuckle_i:.6g}"/></inertial>
  </link>""")
        parts.append(_wheel(f"front_{side}_wheel", f"front_{side}_knuckle", (0, 0, 0), radius,
                            width, wheel_mass))
    if transmissions:
        for wheel in ("rear_left", "rear_right", "front_left", "front_right"):
            parts.append(f"""
  <transmission name="{wheel}_transmission">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="{wheel}_wheel_joint">
      <hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface>
    </joint>
    <actuator name="{wheel}_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>""")
    parts.append("\n</robot>\n")
    return "".join(parts)


def skid_multiplier(wheelbase: float, track: float) -> float:
    """The multiplier of a four-wheel skid-steer robot under Coulomb friction, equal loads:
    its wheels slide so that the friction moments balance, and it turns at
    2·r·ω/track · b² / (a² + b²) (a, b: half the wheelbase and track)."""
    a, b = wheelbase / 2, track / 2
    return (a * a + b * b) / (b * b)


def turning_radius(wheelbase: float, angle_deg: float) -> float:
    return wheelbase / math.tan(math.radians(angle_deg))


def mecanum(mass: float = 10.0, wheelbase: float = 0.4, track: float = 0.4,
            radius: float = 0.06) -> str:
    """A box on four mecanum wheels, each carrying two rollers on continuous joints (a
    real one has ten or more; two make the kind as plain to the tree)."""
    width = 0.5 * radius
    wheel_mass, roller_mass = 0.05 * mass, 0.005 * mass
    body_mass = mass - 4 * wheel_mass - 8 * roller_mass
    body = (wheelbase, track - width - 0.04, 0.6 * radius)
    parts = ['<?xml version="1.0"?>\n<robot name="mecanum_base">',
             _body(body_mass, body, 0.2 * radius, axle=radius)]
    roller = 0.2 * radius
    roller_i = 0.4 * roller_mass * roller * roller
    for end, x in (("front", wheelbase / 2), ("rear", -wheelbase / 2)):
        for side, sign in (("left", 1), ("right", -1)):
            name = f"{end}_{side}_wheel"
            parts.append(_wheel(name, "base_link", (x, sign * track / 2, 0), radius, width,
                                wheel_mass))
            for number, z in ((1, radius - roller), (2, roller - radius)):
                parts.append(f"""
  <joint name="{name}_roller_{number}" type="continuous">
    <parent link="{name}_link"/><child link="{name}_roller_{number}_link"/>
    <origin xyz="0 0 {z:.6g}" rpy="0 0 0.7853982"/><axis xyz="1 0 0"/>
  </joint>
  <link name="{name}_roller_{number}_link">
    <collision><geometry><sphere radius="{roller:.6g}"/></geometry></collision>
    <inertial><mass value="{roller_mass:.6g}"/><inertia ixx="{roller_i:.6g}" ixy="0" ixz="0"
      iyy="{roller_i:.6g}" iyz="0" izz="{roller_i:.6g}"/></inertial>
  </link>""")
    parts.append("\n</robot>\n")
    return "".join(parts)


def arm(links: int = 3) -> str:
    """An arm of ``links`` boxes on revolute joints on a fixed base: no wheels."""
    return _arm("arm", "arm_{}_joint", "arm_{}_link", [("revolute", "0 1 0")] * links,
                '<box size="0.05 0.05 0.3"/>')


def swivel_arm() -> str:
    """An arm whose first and third joints turn without end about upright axes, each link
    with collision geometry (Kinova Gen3's joints 1, 3, 5 and 7 are continuous): no wheels."""
    return _arm("swivel_arm", "joint_{}", "link_{}",
                [("continuous", "0 0 1"), ("revolute", "0 1 0"), ("continuous", "0 0 1")],
                '<cylinder radius="0.03" length="0.3"/>')


def _arm(name: str, joint: str, link: str, joints: list[tuple[str, str]], shape: str) -> str:
    """A fixed base and a chain of 0.3 m links of ``shape`` on ``joints`` (kind, axis),
    named by the patterns ``joint`` and ``link``."""
    parts = [f'<?xml version="1.0"?>\n<robot name="{name}">', _body(5.0, (0.2, 0.2, 0.1), 0.0)]
    parent = "base_link"
    for number, (kind, axis) in enumerate(joints, start=1):
        child = link.format(number)
        parts.append(f"""
  <joint name="{joint.format(number)}" type="{kind}">
    <parent link="{parent}"/><child link="{child}"/>
    <origin xyz="0 0 {0.1 if number == 1 else 0.3}"/><axis xyz="{axis}"/>
    <limit lower="-1.5" upper="1.5" effort="10" velocity="1"/>
  </joint>
  <link name="{child}">
    <collision><origin xyz="0 0 0.15"/><geometry>{shape}</geometry>
    </collision>
    <inertial><origin xyz="0 0 0.15"/><mass value="0.5"/>{box_inertia(0.5, 0.05, 0.05, 0.3)}
    </inertial>
  </link>""")
        parent = child
    parts.append("\n</robot>\n")
    return "".join(parts)


def heavy_wheels(wheel_mass: float = 1000.0) -> str:
    """two_wheeler() whose wheels weigh ``wheel_mass`` kg each, their inertia scaled with
    it (a TurtleBot3 burger's 28 g wheel typed as 1000 kg: every tensor stays physical)."""
    import re

    text = two_wheeler()

    def scaled(link):
        old = float(re.search(r'<mass value="([^"]+)"', link.group(0)).group(1))
        return re.sub(r'(mass value|ixx|iyy|izz)="([^"]+)"',
                      lambda m: f'{m.group(1)}="{float(m.group(2)) * wheel_mass / old:.6g}"',
                      link.group(0))

    return re.sub(r'<link name="wheel_(left|right)_link">.*?</link>', scaled, text,
                  flags=re.DOTALL)


# PMB2's antenna inertia as released (pmb2_description urdf/objects/antenna.urdf.xacro):
# principal moments -3.5e-8, 3.5e-8, 9.1e-8 kg m², not positive definite.
_ANTENNA = """
  <joint name="antenna_joint" type="fixed">
    <parent link="base_link"/><child link="antenna_link"/><origin xyz="-0.05 0 0.08"/>
  </joint>
  <link name="antenna_link">
    <inertial><mass value="0.001"/>
      <inertia ixx="2.371e-08" ixy="6.119e-08" ixz="1.179e-08" iyy="2.833e-08"
        iyz="7.74e-09" izz="3.849e-08"/>
    </inertial>
  </link>"""

# PR2's gripper gap (pr2_description urdf/gripper_v0/gripper.urdf.xacro): a frame with no
# mass and no geometry at the end of a prismatic joint.
_FINGER_FRAME = """
  <joint name="gap_joint" type="prismatic">
    <parent link="base_link"/><child link="gap_frame"/><origin xyz="0.05 0 0.08"/>
    <axis xyz="0 1 0"/><limit effort="10" lower="0" upper="0.09" velocity="0.2"/>
  </joint>
  <link name="gap_frame"/>"""


def non_positive_antenna() -> str:
    """two_wheeler() carrying PMB2's antenna, whose tensor MuJoCo refuses."""
    return two_wheeler(extra=_ANTENNA)


def massless_frame() -> str:
    """two_wheeler() carrying PR2's gripper-gap frame, moving without mass."""
    return two_wheeler(extra=_FINGER_FRAME)


# A swivel with a mass and an inertia of zeros, which MuJoCo refuses on a moving body.
_ZERO_TENSOR = """
  <joint name="swivel_joint" type="continuous">
    <parent link="base_link"/><child link="swivel_link"/><origin xyz="0 0 0.09"/>
    <axis xyz="0 0 1"/>
  </joint>
  <link name="swivel_link">
    <inertial><mass value="0.01"/>
      <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>
  </link>"""


def zero_tensor_swivel() -> str:
    """two_wheeler() with a swivel of 10 g whose inertia is all zeros."""
    return two_wheeler(extra=_ZERO_TENSOR)


def pr2_like_inertias() -> str:
    """two_wheeler() with both of the above: PMB2's antenna and PR2's gripper-gap frame."""
    return two_wheeler(extra=_ANTENNA + _FINGER_FRAME)


def skid_plate(sag: float = 0.004) -> str:
    """The two-wheeler with a skid plate fixed under its body just ahead of the axle, its
    bottom ``sag`` m below the wheels' (negative: above them): a body lower than the
    wheels rests on its belly."""
    r = 0.033
    size = (0.06, 0.08, 0.01)
    plate = f"""
  <joint name="plate_joint" type="fixed">
    <parent link="base_link"/><child link="plate_link"/>
    <origin xyz="0.05 0 {-r - sag + size[2] / 2:.6g}"/>
  </joint>
  <link name="plate_link">
    <collision><geometry><box size="{size[0]:.6g} {size[1]:.6g} {size[2]:.6g}"/></geometry>
    </collision>
    <inertial><mass value="0.02"/>{box_inertia(0.02, *size)}</inertial>
  </link>"""
    return two_wheeler(extra=plate)


def weak_motors(effort: float = 0.004) -> str:
    """The two-wheeler whose wheel joints allow ``effort`` N·m (and 20 rad/s): too little
    to turn its wheels at 10 rad/s against its own inertia in time."""
    return two_wheeler(limit=f'<limit effort="{effort:g}" velocity="20"/>')


def massless(robot: str) -> str:
    """``robot`` with every <inertial> taken out: a visual-only description (as
    urdf_tutorial's 06-flexible.urdf), which weighs nothing."""
    import re

    return re.sub(r"<inertial>.*?</inertial>", "", robot, flags=re.S)


def _castor(name, parent, xyz, radius, mass, swivel_height):
    """A castor: a continuous swivel about z (its fork, with collision geometry as MiR's)
    ``swivel_height`` above the axle, over a free wheel on a continuous joint about y."""
    x, y, z = xyz
    fork_i = 0.4 * mass * radius * radius
    return f"""
  <joint name="{name}_swivel_joint" type="continuous">
    <parent link="{parent}"/><child link="{name}_fork"/>
    <origin xyz="{x:.6g} {y:.6g} {z + swivel_height:.6g}"/><axis xyz="0 0 1"/>
  </joint>
  <link name="{name}_fork">
    <collision><origin xyz="0 0 {-swivel_height / 2:.6g}"/>
      <geometry><box size="{radius:.6g} {radius:.6g} {swivel_height / 2:.6g}"/></geometry>
    </collision>
    <inertial><mass value="{mass:.6g}"/><inertia ixx="{fork_i:.6g}" ixy="0" ixz="0"
      iyy="{fork_i:.6g}" iyz="0" izz="{fork_i:.6g}"/></inertial>
  </link>""" + _wheel(name, f"{name}_fork", (-radius, 0, -swivel_height), radius,
                      radius, mass)


def castor_swivels(mass: float = 20.0, track: float = 0.4, radius: float = 0.06) -> str:
    """MiR's shape: a box on two drive wheels in the middle and four castors at its
    corners, each a continuous swivel (upright, its fork with collision geometry) over a
    free castor wheel of half the drive wheels' radius."""
    width, castor_r = 0.3 * radius, 0.5 * radius
    wheel_mass, castor_mass = 0.05 * mass, 0.01 * mass
    body_mass = mass - 2 * wheel_mass - 8 * castor_mass
    body = (0.6, track - width - 0.04, 0.6 * radius)
    parts = ['<?xml version="1.0"?>\n<robot name="castor_swivels">',
             _body(body_mass, body, 0.2 * radius, axle=radius)]
    for side, sign in (("left", 1), ("right", -1)):
        parts.append(_wheel(f"{side}_wheel", "base_link", (0, sign * track / 2, 0), radius,
                            width, wheel_mass))
    for end, x in (("front", 0.25), ("back", -0.2)):
        for side, sign in (("left", 1), ("right", -1)):
            parts.append(_castor(f"{end}_{side}_castor", "base_link",
                                 (x, sign * track / 3, castor_r - radius), castor_r,
                                 castor_mass, 0.04))
    parts.append("\n</robot>\n")
    return "".join(parts)


def bicycle_model(wheelbase: float = 0.5, track: float = 0.4, radius: float = 0.08,
                  lift: float = 0.075) -> str:
    """steer_bot's shape: an Ackermann car (:func:`ackermann`) with the virtual joints of
    its bicycle model, the ones ackermann_steering_controller reads, on the centre line:
    ``front_steer_joint`` (revolute about z at the front axle) and ``rear_wheel_joint``
    (continuous, at the rear axle, its small wheel ``lift`` m off the floor)."""
    small = radius / 4
    knuckle_i = 0.4 * 0.05 * small * small
    virtual = f"""
  <joint name="front_steer_joint" type="revolute">
    <parent link="base_link"/><child link="front_steer_link"/>
    <origin xyz="{wheelbase / 2:.6g} 0 {radius:.6g}"/><axis xyz="0 0 1"/>
    <limit lower="-0.6" upper="0.6" effort="20" velocity="3"/>
  </joint>
  <link name="front_steer_link">
    <collision><geometry><cylinder radius="{small:.6g}" length="{small:.6g}"/></geometry>
    </collision>
    <inertial><mass value="0.05"/><inertia ixx="{knuckle_i:.6g}" ixy="0" ixz="0"
      iyy="{knuckle_i:.6g}" iyz="0" izz="{knuckle_i:.6g}"/></inertial>
  </link>""" + _wheel("rear_wheel", "base_link", (-wheelbase / 2, 0, small - radius + lift),
                      small, small, 0.05)
    return ackermann(wheelbase=wheelbase, track=track, radius=radius).replace(
        "\n</robot>\n", virtual + "\n</robot>\n")


ACKERMANN_CONTROLLER = """# as ackermann_steering_controller (ROS 1) reads it
ackermann_steering_controller:
  type: 'ackermann_steering_controller/AckermannSteeringController'
  rear_wheel: 'rear_wheel_joint'
  front_steer: 'front_steer_joint'
  wheel_separation_h: 0.5
  wheel_radius: 0.08
"""


def tricycle(mass: float = 5.0, wheelbase: float = 0.4, track: float = 0.3,
             radius: float = 0.05) -> str:
    """A box on two rear wheels and one front wheel on the centre line, steered by a
    revolute joint about z: no drive kind mcar sim drives."""
    width, wheel_mass = 0.3 * radius, 0.05 * mass
    body_mass = mass - 3 * wheel_mass - 0.05
    body = (wheelbase, track - width - 0.04, 0.6 * radius)
    parts = ['<?xml version="1.0"?>\n<robot name="tricycle">',
             _body(body_mass, body, 0.2 * radius, axle=radius)]
    for side, sign in (("left", 1), ("right", -1)):
        parts.append(_wheel(f"rear_{side}_wheel", "base_link",
                            (-wheelbase / 2, sign * track / 2, 0), radius, width, wheel_mass))
    parts.append(f"""
  <joint name="front_steering_joint" type="revolute">
    <parent link="base_link"/><child link="front_fork"/>
    <origin xyz="{wheelbase / 2:.6g} 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-0.6" upper="0.6" effort="5" velocity="3"/>
  </joint>
  <link name="front_fork">
    <inertial><mass value="0.05"/><inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0"
      izz="1e-5"/></inertial>
  </link>""")
    parts.append(_wheel("front_wheel", "front_fork", (0, 0, 0), radius, width, wheel_mass))
    parts.append("\n</robot>\n")
    return "".join(parts)


def bicycle(mass: float = 4.0, wheelbase: float = 0.4, radius: float = 0.05,
            width: float = 0.03, steer_limit: float = 0.6) -> str:
    """A single track: a box on a rear wheel and a front wheel, both on the centre line,
    the front one under a revolute fork about z (``front_steering_joint``, ±``steer_limit``
    rad); it stands on its tyres' ``width`` alone, its centre of mass 1.5 radii up."""
    wheel_mass, fork_mass = 0.05 * mass, 0.05
    body_mass = mass - 2 * wheel_mass - fork_mass
    body = (wheelbase, 2 * width, 0.6 * radius)
    parts = ['<?xml version="1.0"?>\n<robot name="bicycle">',
             _body(body_mass, body, 0.2 * radius, axle=radius),
             _wheel("rear_wheel", "base_link", (-wheelbase / 2, 0, 0), radius, width,
                    wheel_mass)]
    parts.append(f"""
  <joint name="front_steering_joint" type="revolute">
    <parent link="base_link"/><child link="front_fork"/>
    <origin xyz="{wheelbase / 2:.6g} 0 0"/><axis xyz="0 0 1"/>
    <limit lower="{-steer_limit:.6g}" upper="{steer_limit:.6g}" effort="5" velocity="3"/>
  </joint>
  <link name="front_fork">
    <inertial><mass value="{fork_mass:.6g}"/><inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5"
      iyz="0" izz="1e-5"/></inertial>
  </link>""")
    parts.append(_wheel("front_wheel", "front_fork", (0, 0, 0), radius, width, wheel_mass))
    parts.append("\n</robot>\n")
    return "".join(parts)


BICYCLE_CONTROLLER = """# ackermann_steering_controller (ROS 1) naming a single track's joints
ackermann_steering_controller:
  type: 'ackermann_steering_controller/AckermannSteeringController'
  rear_wheel: 'rear_wheel_joint'
  front_steer: 'front_steering_joint'
  wheel_separation_h: 0.4
  wheel_radius: 0.05
"""


def dummy_wheel(gap: float = 0.005) -> str:
    """Hunter 2's shape: :func:`two_wheeler` and a small wheel on a continuous joint
    beside the right drive wheel, ``gap`` m above the floor (a model of a sensor wheel,
    never on the floor)."""
    r = 0.01
    return two_wheeler(extra=_wheel("dummy_wheel", "base_link", (-0.05, -0.05, r - 0.033 + gap),
                                    r, 0.005, 0.005))


def diff_drive_plugin(left: str, right: str) -> str:
    """A ROS 2 gazebo_ros diff-drive plugin naming ``left`` and ``right`` joints."""
    return f"""
  <gazebo>
    <plugin name="diff_drive" filename="libgazebo_ros_diff_drive.so">
      <left_joint>{left}</left_joint>
      <right_joint>{right}</right_joint>
    </plugin>
  </gazebo>"""


PLANAR_MOVE = """
  <gazebo>
    <plugin name="object_controller" filename="libgazebo_ros_planar_move.so">
      <command_topic>cmd_vel</command_topic>
    </plugin>
  </gazebo>"""


def mecanum_wheels(mass: float = 10.0, wheelbase: float = 0.4, track: float = 0.4,
                   radius: float = 0.06, wheel_mu: float | None = None,
                   extra: str = "", lift: float = 0.2) -> str:
    """A box on four plain cylinders (mecanum wheels as linorobot2 and ROSbot XL draw
    them: no roller links); ``wheel_mu``: each wheel's <gazebo><mu1> (linorobot2: 0.01);
    ``extra``: what declares them mecanum (PLANAR_MOVE), else nothing does; ``lift``: the
    body's centre above the axles, in wheel radii."""
    width = 0.5 * radius
    wheel_mass = 0.05 * mass
    body_mass = mass - 4 * wheel_mass
    body = (wheelbase, track - width - 0.04, 0.6 * radius)
    parts = ['<?xml version="1.0"?>\n<robot name="mecanum_wheels">',
             _body(body_mass, body, lift * radius, axle=radius)]
    for end, x in (("front", wheelbase / 2), ("rear", -wheelbase / 2)):
        for side, sign in (("left", 1), ("right", -1)):
            name = f"{end}_{side}_wheel"
            parts.append(_wheel(name, "base_link", (x, sign * track / 2, 0), radius, width,
                                wheel_mass))
            if wheel_mu is not None:
                parts.append(f'\n  <gazebo reference="{name}_link"><mu1>{wheel_mu:g}</mu1>'
                             f'<mu2>{wheel_mu:g}</mu2></gazebo>')
    parts.append(extra + "\n</robot>\n")
    return "".join(parts)


def centre_wheel(mass: float = 20.0, radius: float = 0.1) -> str:
    """A four-wheel skid-steer box with a fifth wheel on its centre line: a vehicle that
    no drive kind fits (sim cannot drive it)."""
    width = 0.25 * radius
    return skid_steer(mass=mass, radius=radius, extra=_wheel(
        "centre_wheel", "base_link", (0, 0, 0), radius, width, 0.05 * mass)).replace(
        'name="skid_steer_4"', 'name="centre_wheel"')


def mecanum_rings(mass: float = 10.0, wheelbase: float = 0.4, track: float = 0.4,
                  radius: float = 0.06, rollers: int = 8, pattern: int = 1) -> str:
    """A box on four mecanum hubs without collision geometry of their own, each carrying a
    ring of ``rollers`` roller links (spheres) whose axes, at the bottom, lie at 45°: the
    usual X pattern (``pattern`` 1: the front left and rear right rollers along (1, -1)),
    or the O pattern (-1); ``pattern`` 0: rollers across the axle, omni wheels."""
    width = 0.5 * radius
    hub_mass, roller_mass = 0.04 * mass, 0.002 * mass
    body_mass = mass - 4 * hub_mass - 4 * rollers * roller_mass
    body = (wheelbase, track - width - 0.04, 0.6 * radius)
    ball = 0.15 * radius
    roller_i = 0.4 * roller_mass * ball * ball
    parts = ['<?xml version="1.0"?>\n<robot name="mecanum_rings">',
             _body(body_mass, body, 0.2 * radius, axle=radius)]
    for end, x in (("front", wheelbase / 2), ("rear", -wheelbase / 2)):
        for side, sign in (("left", 1), ("right", -1)):
            name = f"{end}_{side}_wheel"
            across = -pattern if (end == "front") == (side == "left") else pattern
            parts.append(f"""
  <joint name="{name}_joint" type="continuous">
    <parent link="base_link"/><child link="{name}_link"/>
    <origin xyz="{x:.6g} {sign * track / 2:.6g} 0"/><axis xyz="0 1 0"/>
  </joint>
  <link name="{name}_link">
    <inertial><mass value="{hub_mass:.6g}"/>{_cylinder_y_inertia(hub_mass, radius, width)}
    </inertial>
  </link>""")
            for number in range(rollers):
                angle = 2 * math.pi * number / rollers
                x_at, z_at = -(radius - ball) * math.sin(angle), -(radius - ball) * math.cos(angle)
                parts.append(f"""
  <joint name="{name}_roller_{number}" type="continuous">
    <parent link="{name}_link"/><child link="{name}_roller_{number}_link"/>
    <origin xyz="{x_at:.6g} 0 {z_at:.6g}" rpy="0 {angle:.6g} 0"/>
    <axis xyz="{1 if pattern == 0 else 0.7071068} {0.7071068 * across:.6g} 0"/>
  </joint>
  <link name="{name}_roller_{number}_link">
    <collision><geometry><sphere radius="{ball:.6g}"/></geometry></collision>
    <inertial><mass value="{roller_mass:.6g}"/><inertia ixx="{roller_i:.6g}" ixy="0" ixz="0"
      iyy="{roller_i:.6g}" iyz="0" izz="{roller_i:.6g}"/></inertial>
  </link>""")
    parts.append("\n</robot>\n")
    return "".join(parts)


def _ball(name, parent, xyz, radius, mass):
    x, y, z = xyz
    i = 0.4 * mass * radius * radius
    return f"""
  <joint name="{name}_joint" type="fixed">
    <parent link="{parent}"/><child link="{name}_link"/><origin xyz="{x:.6g} {y:.6g} {z:.6g}"/>
  </joint>
  <link name="{name}_link">
    <collision><geometry><sphere radius="{radius:.6g}"/></geometry></collision>
    <inertial><mass value="{mass:.6g}"/><inertia ixx="{i:.6g}" ixy="0" ixz="0" iyy="{i:.6g}"
      iyz="0" izz="{i:.6g}"/></inertial>
  </link>"""


def castors_fore_and_aft(mass: float = 2.0, back_lift: float = 0.002) -> str:
    """Kobuki's shape: a box on two drive wheels (radius 35 mm, axle at the middle) and a
    ball castor in front and behind; the back one ``back_lift`` above the floor the
    wheels and the front one stand on."""
    r, ball = 0.035, 0.015
    parts = ['<?xml version="1.0"?>\n<robot name="fore_and_aft">',
             _body(0.8 * mass, (0.3, 0.2, 0.05), 0.0, axle=r)]
    for side, y in (("left", 0.115), ("right", -0.115)):
        parts.append(_wheel(f"wheel_{side}", "base_link", (0, y, 0), r, 0.02, 0.08 * mass))
    # The front castor heavier: the robot leans on it, as Kobuki does.
    parts.append(_ball("caster_front", "base_link", (0.12, 0, ball - r), ball, 0.1 * mass))
    parts.append(_ball("caster_back", "base_link", (-0.12, 0, ball - r + back_lift), ball,
                       0.02 * mass))
    parts.append("\n</robot>\n")
    return "".join(parts)


def level_castors(castor_mu: float | None = None) -> str:
    """ros2_control_demos' diffbot: a 0.3 kg box on two 0.3 kg wheels of 15 mm turning at
    most 1 rad/s, and two ball castors in front and behind whose lowest points are level
    with the wheels' (four supports: how they share the weight statics cannot say);
    ``castor_mu``: the balls' <gazebo><mu1> (None: none given)."""
    r = 0.015
    parts = ['<?xml version="1.0"?>\n<robot name="level_castors">',
             _body(0.3, (0.1, 0.1, 0.05), 0.0)]
    for side, y in (("left", 0.05), ("right", -0.05)):
        parts.append(_wheel(f"wheel_{side}", "base_link", (0, y, 0), r, 0.02, 0.3,
                            limit='\n    <limit effort="100" velocity="1"/>'))
    for name, x in (("caster_front", 0.035), ("caster_back", -0.035)):
        parts.append(_ball(name, "base_link", (x, 0, 0), r, 0.1))
        if castor_mu is not None:
            parts.append(f"""
  <gazebo reference="{name}_link"><mu1>{castor_mu:g}</mu1><mu2>{castor_mu:g}</mu2></gazebo>""")
    parts.append("\n</robot>\n")
    return "".join(parts)


def tips_back(mass: float = 3.0, ahead: float = 0.002, height: float = 0.1) -> str:
    """TurtleBot 4's balance: a box on two drive wheels (radius 35 mm) and one ball castor
    in front, none behind; its centre of mass ``ahead`` m ahead of the axle, ``height`` m
    above the floor. The box reaches 0.15 m behind the axle, 10 mm above the floor: the
    speed ramp's acceleration, over g·ahead/height, tips it back onto it."""
    r, ball, length = 0.035, 0.012, 0.3
    wheel_mass = 0.08 * mass
    body_mass = mass - 2 * wheel_mass - 0.01
    tall = 2 * (height - 0.01)
    parts = [f"""<?xml version="1.0"?>
<robot name="tips_back">
  <link name="base_link">
    <collision><origin xyz="{ahead - length / 2 + 0.15:.6g} 0 {height - r:.6g}"/>
      <geometry><box size="{length:.6g} 0.2 {tall:.6g}"/></geometry></collision>
    <inertial><origin xyz="{ahead:.6g} 0 {height - r:.6g}"/><mass value="{body_mass:.6g}"/>
      {box_inertia(body_mass, length, 0.2, tall)}</inertial>
  </link>"""]
    for side, y in (("left", 0.13), ("right", -0.13)):
        parts.append(_wheel(f"wheel_{side}", "base_link", (0, y, 0), r, 0.02, wheel_mass))
    parts.append(_ball("castor_front", "base_link", (0.12, 0, ball - r), ball, 0.01))
    parts.append("\n</robot>\n")
    return "".join(parts)


def sprung(mass: float = 3.0, castor_below: float = 0.003, travel: float = 0.006,
           gazebo: bool = False) -> str:
    """Create 3's shape: a box on two drive wheels, each on a prismatic wheel-drop joint
    (axis down, 0..``travel``), and a front castor that reaches ``castor_below`` below
    the wheels with the joints at 0; ``gazebo``: the springs' stiffness and reference in
    the joints' <gazebo> blocks (4000 N/m, extended at ``travel``, as Create 3's)."""
    r, ball = 0.035, 0.012
    parts = ['<?xml version="1.0"?>\n<robot name="sprung">',
             _body(0.8 * mass, (0.3, 0.2, 0.05), 0.0, axle=r)]
    for side, y in (("left", 0.115), ("right", -0.115)):
        parts.append(f"""
  <joint name="wheel_drop_{side}_joint" type="prismatic">
    <parent link="base_link"/><child link="wheel_drop_{side}"/><origin xyz="0 {y:.6g} 0"/>
    <axis xyz="0 0 -1"/><limit lower="0" upper="{travel:.6g}" effort="0" velocity="0"/>
    <dynamics damping="50"/>
  </joint>
  <link name="wheel_drop_{side}">
    <inertial><mass value="0.02"/><inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0"
      izz="1e-5"/></inertial>
  </link>""")
        parts.append(_wheel(f"wheel_{side}", f"wheel_drop_{side}", (0, 0, 0), r, 0.02,
                            0.06 * mass))
        if gazebo:
            parts.append(f"""
  <gazebo reference="wheel_drop_{side}_joint">
    <springStiffness>4000</springStiffness><springReference>{travel:.6g}</springReference>
  </gazebo>""")
    parts.append(_ball("front_caster", "base_link", (0.12, 0, ball - r - castor_below), ball,
                       0.02 * mass))
    parts.append("\n</robot>\n")
    # The body's mass 20 mm ahead of the axle, as Create 3's is: it leans on its castor.
    return "".join(parts).replace('<inertial><origin xyz="0 0 ',
                                  '<inertial><origin xyz="0.02 0 ', 1)


def fixed_wheels(gap: float = 0.0001) -> str:
    """A base on four wheels on fixed joints (no drive), one ``gap`` above the floor."""
    r = 0.05
    parts = ['<?xml version="1.0"?>\n<robot name="fixed_wheels">',
             _body(5.0, (0.4, 0.3, 0.06), 0.02, axle=r)]
    for name, x, y in (("fl", 0.15, 0.18), ("fr", 0.15, -0.18), ("rl", -0.15, 0.18),
                       ("rr", -0.15, -0.18)):
        z = gap if name == "rr" else 0.0
        parts.append(_wheel(name, "base_link", (x, y, z), r, 0.03, 0.3, joint_type="fixed"))
    parts.append("\n</robot>\n")
    return "".join(parts)


def kobuki_like(back_lift: float = 0.002, castor_mu: float | None = 0.0) -> str:
    """Kobuki's base as its description has it: two drive wheels of 10 g with 0.001 kg m²
    about every axis, a castor in front and one behind (``back_lift`` above the floor),
    each a cylinder lying across the robot (rolling forward) of ``castor_mu`` friction
    (<gazebo><mu1>; None: none given)."""
    r, cr = 0.035, 0.017
    parts = ['<?xml version="1.0"?>\n<robot name="kobuki_like">',
             _body(2.3, (0.3, 0.3, 0.08), 0.0, axle=r)]
    for side, y in (("left", 0.115), ("right", -0.115)):
        parts.append(f"""
  <joint name="wheel_{side}_joint" type="continuous">
    <parent link="base_link"/><child link="wheel_{side}_link"/>
    <origin xyz="0 {y:.6g} 0" rpy="-1.5707963 0 0"/><axis xyz="0 0 1"/>
  </joint>
  <link name="wheel_{side}_link">
    <collision><geometry><cylinder length="0.0206" radius="{r:.6g}"/></geometry></collision>
    <inertial><mass value="0.01"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0"
      izz="0.001"/></inertial>
  </link>""")
    # (The front castor's 0.1 kg puts the centre of mass ahead of the axle: the robot
    # leans on it, as Kobuki rests on its front castor.)
    for name, x, lift, mass in (("front", 0.115, 0.0, 0.1), ("back", -0.135, back_lift, 0.01)):
        parts.append(f"""
  <joint name="caster_{name}_joint" type="fixed">
    <parent link="base_link"/><child link="caster_{name}_link"/>
    <origin xyz="{x:.6g} 0 {cr - r + lift:.6g}" rpy="-1.5707963 0 0"/>
  </joint>
  <link name="caster_{name}_link">
    <collision><geometry><cylinder length="0.0176" radius="{cr:.6g}"/></geometry></collision>
    <inertial><mass value="{mass:g}"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001"
      iyz="0" izz="0.001"/></inertial>
  </link>""")
        if castor_mu is not None:
            parts.append(f"""
  <gazebo reference="caster_{name}_link"><mu1>{castor_mu:g}</mu1><mu2>{castor_mu:g}</mu2>
  </gazebo>""")
    parts.append("\n</robot>\n")
    return "".join(parts)


def planar_base(mu: str = "0.0001") -> str:
    """Neobotix MPO-700 as Gazebo's planar_move has it: a 5 kg box on four wheels on fixed
    joints whose <mu1> is nearly 0, so that nothing but the plugin moves it."""
    parts = ['<?xml version="1.0"?>\n<robot name="planar_base">\n  <link name="base_link">'
             '<collision><origin xyz="0 0 0.25"/><geometry><box size="0.6 0.4 0.2"/>'
             '</geometry></collision><inertial><origin xyz="0 0 0.07"/><mass value="5"/>'
             '<inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>'
             '</link>']
    for name, x, y in (("fl", 0.24, 0.23), ("fr", 0.24, -0.23), ("rl", -0.24, 0.23),
                       ("rr", -0.24, -0.23)):
        parts.append(f"""
  <joint name="{name}_joint" type="fixed"><parent link="base_link"/>
    <child link="{name}_wheel_link"/><origin xyz="{x} {y} 0.09" rpy="1.5708 0 0"/></joint>
  <link name="{name}_wheel_link"><collision><geometry><cylinder radius="0.09" length="0.03"/>
    </geometry></collision><inertial><mass value="0.3"/><inertia ixx="0.001" ixy="0" ixz="0"
    iyy="0.001" iyz="0" izz="0.001"/></inertial></link>
  <gazebo reference="{name}_wheel_link"><mu1>{mu}</mu1><mu2>{mu}</mu2></gazebo>""")
    return "".join(parts) + "\n</robot>\n"
