"""A 5,000-link tree, made at test time: every link has an inertia, a visual and a
collision; each link hangs from one of the 40 links before it, so the tree is both wide
and deep, and joint names are not in file order."""

import random

LINKS = 5000


def urdf() -> str:
    rng = random.Random(5000)
    out = ['<?xml version="1.0"?>', '<robot name="tree_5000">',
           '  <material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>']
    for i in range(LINKS):
        out.append(
            f'  <link name="link_{i}">'
            + ("" if i == 0 else
               '<inertial><mass value="0.1"/>'
               '<inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-6"/></inertial>')
            + '<visual><geometry><box size="0.01 0.01 0.01"/></geometry>'
              '<material name="grey"/></visual>'
              '<collision><geometry><sphere radius="0.005"/></geometry></collision></link>')
    for i in range(1, LINKS):
        parent = rng.randrange(max(0, i - 40), i)
        out.append(
            f'  <joint name="j{rng.randrange(10**6):06d}_{i}" type="revolute">'
            f'<origin xyz="0.01 0 0" rpy="0 0 {i % 7 * 0.1:.1f}"/>'
            f'<parent link="link_{parent}"/><child link="link_{i}"/><axis xyz="0 0 1"/>'
            '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>')
    out.append("</robot>")
    return "\n".join(out) + "\n"
