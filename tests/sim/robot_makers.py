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
               track: float = 0.45, radius: float = 0.1, extra: str = "") -> str:
    """A box on ``per_side`` wheels a side, evenly spaced over ``wheelbase``, every wheel
    on a continuous joint without <limit> (as Husky's and Jackal's)."""
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
                                radius, width, wheel_mass))
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
    parts = ['<?xml version="1.0"?>\n<robot name="arm">', _body(5.0, (0.2, 0.2, 0.1), 0.0)]
    parent = "base_link"
    for number in range(1, links + 1):
        parts.append(f"""
  <joint name="arm_{number}_joint" type="revolute">
    <parent link="{parent}"/><child link="arm_{number}_link"/>
    <origin xyz="0 0 {0.1 if number == 1 else 0.3}"/><axis xyz="0 1 0"/>
    <limit lower="-1.5" upper="1.5" effort="10" velocity="1"/>
  </joint>
  <link name="arm_{number}_link">
    <collision><origin xyz="0 0 0.15"/><geometry><box size="0.05 0.05 0.3"/></geometry>
    </collision>
    <inertial><origin xyz="0 0 0.15"/><mass value="0.5"/>{box_inertia(0.5, 0.05, 0.05, 0.3)}
    </inertial>
  </link>""")
        parent = f"arm_{number}_link"
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
    # A heavy castor housing puts the centre of mass ahead of the axle, as Create 3's is.
    parts.append(_ball("front_caster", "base_link", (0.12, 0, ball - r - castor_below), ball,
                       0.1 * mass))
    parts.append("\n</robot>\n")
    return "".join(parts)


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
