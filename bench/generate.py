"""Inputs for the benchmarks, generated (nothing large is committed).

    robot(n, shape, parts)  a URDF of n links, each with an inertial, a visual and a
                            collision (as CAD exporters write them), joined by revolute,
                            continuous, prismatic and fixed joints with origins, axes,
                            limits and dynamics:
        shape "tree"        each link hangs from a random earlier link (fixed seed): a
                            bushy tree, about 2.7 ln(n) deep, like a many-limbed robot;
        shape "chain"       each link hangs from the one before: the deepest tree (a
                            snake robot), where check_urdf's indented print grows as n^2;
        parts "distinct"    every number differs from link to link (what a CAD export
                            gives): the honest case, nothing to share between links;
        parts "repeated"    links are copies of four part models (segment, wheel, ...),
                            as robots built from modules or macros are.
    macros(n)               a xacro that defines a wheel macro and calls it n times.

Every robot is valid and physical (inertias from the shape's formulas), so both checkers
must accept it and print the same tree.
"""

from __future__ import annotations

import math
import random

JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed")
SHAPES = ("tree", "chain")
PARTS = ("distinct", "repeated")


def _g(value: float) -> str:
    return f"{value:.6g}"


def _vector(rng: random.Random, scale: float) -> str:
    return " ".join(_g(rng.uniform(-scale, scale)) for _ in range(3))


def _shape(rng: random.Random, kind: int) -> tuple[str, tuple[float, float, float], float]:
    """A geometry element, its inertia factors (Ixx, Iyy, Izz per kg) and its volume."""
    if kind == 0:
        x, y, z = (rng.uniform(0.02, 0.3) for _ in range(3))
        return (f'<box size="{_g(x)} {_g(y)} {_g(z)}"/>',
                ((y * y + z * z) / 12, (x * x + z * z) / 12, (x * x + y * y) / 12), x * y * z)
    if kind == 1:
        r, h = rng.uniform(0.01, 0.1), rng.uniform(0.01, 0.3)
        side = (3 * r * r + h * h) / 12
        return (f'<cylinder radius="{_g(r)}" length="{_g(h)}"/>', (side, side, r * r / 2),
                math.pi * r * r * h)
    r = rng.uniform(0.01, 0.1)
    return f'<sphere radius="{_g(r)}"/>', (2 * r * r / 5,) * 3, 4 * math.pi * r ** 3 / 3


def _link_body(rng: random.Random, kind: int, shapes: int = 3) -> str:
    """The content of a link: inertial, visual and collision, all numbers drawn from rng;
    ``shapes`` 3: boxes, cylinders and spheres, 2: boxes and cylinders only."""
    geometry, factors, volume = _shape(rng, kind % shapes)
    # A density some material has (foam to steel): mcar check fails a mass no part has (E119)
    mass = rng.uniform(50.0, 8000.0) * volume
    ixx, iyy, izz = (mass * f for f in factors)
    return (f'    <inertial>\n'
            f'      <origin xyz="{_vector(rng, 0.05)}" rpy="0 0 0"/>\n'
            f'      <mass value="{_g(mass)}"/>\n'
            f'      <inertia ixx="{_g(ixx)}" ixy="0" ixz="0" iyy="{_g(iyy)}" iyz="0" '
            f'izz="{_g(izz)}"/>\n'
            f'    </inertial>\n'
            f'    <visual>\n'
            f'      <origin xyz="{_vector(rng, 0.05)}" rpy="{_vector(rng, 1.5)}"/>\n'
            f'      <geometry>{geometry}</geometry>\n'
            f'      <material name="{("grey", "black", "orange")[kind % 3]}"/>\n'
            f'    </visual>\n'
            f'    <collision>\n'
            f'      <origin xyz="{_vector(rng, 0.05)}" rpy="{_vector(rng, 1.5)}"/>\n'
            f'      <geometry>{geometry}</geometry>\n'
            f'    </collision>\n')


def _joint_body(rng: random.Random, kind: str) -> str:
    """The content of a joint after its parent and child, numbers drawn from rng."""
    text = f'    <origin xyz="{_vector(rng, 0.2)}" rpy="{_vector(rng, 1.5)}"/>\n'
    if kind != "fixed":
        text += f'    <axis xyz="{("1 0 0", "0 1 0", "0 0 1")[rng.randrange(3)]}"/>\n'
    if kind in ("revolute", "prismatic"):
        low = rng.uniform(0.1, 3.0)
        text += (f'    <limit lower="{_g(-low)}" upper="{_g(rng.uniform(0.1, 3.0))}" '
                 f'effort="{_g(rng.uniform(1, 100))}" velocity="{_g(rng.uniform(0.5, 5))}"/>\n')
    if kind != "fixed":
        text += (f'    <dynamics damping="{_g(rng.uniform(0, 0.5))}" '
                 f'friction="{_g(rng.uniform(0, 0.1))}"/>\n')
    return text


MATERIALS = ('  <material name="grey"><color rgba="0.6 0.6 0.6 1"/></material>\n'
             '  <material name="black"><color rgba="0.1 0.1 0.1 1"/></material>\n'
             '  <material name="orange"><color rgba="1 0.42 0.04 1"/></material>\n')


def robot(n: int, shape: str = "tree", parts: str = "distinct", seed: int = 7,
          shapes: int = 3) -> str:
    """A valid URDF of ``n`` links; see the module docstring for ``shape`` and ``parts``;
    ``shapes=2`` leaves out spheres (1,280 triangles each: the render bench's robots)."""
    if shape not in SHAPES or parts not in PARTS:
        raise ValueError(f"shape {shape!r} / parts {parts!r}")
    rng = random.Random(seed)
    # Repeated parts: four link models and four joint models, each used again and again.
    models = random.Random(seed + 1)
    link_models = [_link_body(models, k, shapes) for k in range(4)]
    joint_models = [_joint_body(models, JOINT_TYPES[k]) for k in range(4)]
    out = [f'<?xml version="1.0"?>\n<robot name="{shape}_{parts}_{n}">\n', MATERIALS,
           '  <link name="base_link"/>\n']
    for i in range(1, n):
        kind = rng.randrange(4)
        parent = 0 if i == 1 else (i - 1 if shape == "chain" else rng.randrange(1, i))
        parent_name = "base_link" if parent == 0 else f"link_{parent}"
        joint_type = JOINT_TYPES[kind]
        if parts == "distinct":
            link_body, joint_body = (_link_body(rng, kind, shapes),
                                      _joint_body(rng, joint_type))
        else:
            link_body, joint_body = link_models[kind], joint_models[kind]
        out.append(f'  <link name="link_{i}">\n{link_body}  </link>\n'
                   f'  <joint name="joint_{i}" type="{joint_type}">\n'
                   f'    <parent link="{parent_name}"/>\n    <child link="link_{i}"/>\n'
                   f'{joint_body}  </joint>\n')
    out.append("</robot>\n")
    return "".join(out)


def macros(n: int) -> str:
    calls = "\n".join(f'  <xacro:wheel index="{i}" radius="${{0.03 + {i} * 1e-5}}"/>'
                      for i in range(n))
    return f'''<?xml version="1.0"?>
<robot name="macros" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="width" value="0.026"/>
  <xacro:macro name="wheel" params="index radius">
    <link name="wheel_${{index}}">
      <visual><geometry><cylinder radius="${{radius}}" length="${{width}}"/></geometry></visual>
      <inertial><mass value="0.04"/><inertia ixx="${{0.04 * (3 * radius**2 + width**2) / 12}}"
        ixy="0" ixz="0" iyy="${{0.04 * (3 * radius**2 + width**2) / 12}}" iyz="0"
        izz="${{0.04 * radius**2 / 2}}"/></inertial>
    </link>
    <joint name="wheel_${{index}}_joint" type="continuous">
      <parent link="base_link"/><child link="wheel_${{index}}"/><axis xyz="0 1 0"/>
    </joint>
  </xacro:macro>
  <link name="base_link"/>
{calls}
</robot>
'''
