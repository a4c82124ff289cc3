"""Inputs for the benchmarks, generated (nothing large is committed).

    tree(n)   a URDF of n links, each joint's parent chosen among the earlier links
              (a bushy tree, fixed seed), with box visuals and inertials;
    chain(n)  a URDF of n links in one line (the deepest tree);
    macros(n) a xacro that defines a wheel macro and calls it n times.
"""

from __future__ import annotations

import random

JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed")


def _link(i: int) -> str:
    return (f'  <link name="link_{i}">\n'
            f'    <inertial><mass value="1.0"/>'
            f'<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>\n'
            f'    <visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>\n'
            f'  </link>\n')


def _joint(i: int, parent: int) -> str:
    kind = JOINT_TYPES[i % len(JOINT_TYPES)]
    limit = ('<limit lower="-1" upper="1" effort="10" velocity="1"/>'
             if kind in ("revolute", "prismatic") else "")
    return (f'  <joint name="joint_{i}" type="{kind}">\n'
            f'    <parent link="link_{parent}"/><child link="link_{i}"/>\n'
            f'    <origin xyz="0.1 0 0" rpy="0 0 0.1"/><axis xyz="0 0 1"/>{limit}\n'
            f'  </joint>\n')


def tree(n: int, seed: int = 7) -> str:
    rng = random.Random(seed)
    parts = ['<?xml version="1.0"?>\n<robot name="tree">\n', _link(0)]
    for i in range(1, n):
        parts += [_link(i), _joint(i, rng.randrange(max(0, i - 20), i))]
    parts.append("</robot>\n")
    return "".join(parts)


def chain(n: int) -> str:
    parts = ['<?xml version="1.0"?>\n<robot name="chain">\n', _link(0)]
    for i in range(1, n):
        parts += [_link(i), _joint(i, i - 1)]
    parts.append("</robot>\n")
    return "".join(parts)


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
