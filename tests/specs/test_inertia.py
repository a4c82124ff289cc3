"""mcar specs' inertia section: the tensor a link's geometry gives its declared mass (box,
cylinder, sphere in closed form, a mesh through trimesh, several shapes as one solid),
and W530 with the <inertial> to write instead, at the xacro line the user edits."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from conftest import line_of
from specs.mech_robots import box_inertia, written

from mobile_car.check.checker import check_input
from mobile_car.load.inputs import RobotInput
from mobile_car.specs.inertia import inertia_section


def section_of(path: Path):
    checked = check_input(RobotInput(path))
    assert checked.failure is None and not checked.errors, checked.diagnostics
    return inertia_section(checked)


def robot(*links: str) -> str:
    """A base and the given links, each fixed below it."""
    joints = "".join(
        f'<joint name="j{i}" type="fixed"><parent link="base"/><child link="{name}"/></joint>'
        for i, name in enumerate(_names(links)))
    return (f'<?xml version="1.0"?>\n<robot name="r">\n  <link name="base"/>\n'
            f'{"".join(links)}\n  {joints}\n</robot>\n')


def _names(links):
    return [text.split('name="', 1)[1].split('"', 1)[0] for text in links]


def link(name: str, mass: float, shapes: str, inertia: str = "", origin: str = "") -> str:
    inertia = inertia or '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'
    return (f'\n  <link name="{name}">{shapes}\n    <inertial>{origin}<mass value="{mass:g}"/>'
            f'\n      {inertia}\n    </inertial>\n  </link>')


def collision(geometry: str, xyz: str = "0 0 0", rpy: str = "0 0 0") -> str:
    return (f'\n    <collision><origin xyz="{xyz}" rpy="{rpy}"/>'
            f'<geometry>{geometry}</geometry></collision>')


def close(values, expected, rel=1e-12):
    scale = max(abs(v) for v in expected)
    assert all(abs(a - b) <= rel * scale for a, b in zip(values, expected, strict=True)), \
        (values, expected)


@pytest.fixture(scope="module")
def primitives(tmp_path_factory):
    folder = tmp_path_factory.mktemp("primitives")
    text = robot(
        link("block", 3, collision('<box size="0.3 0.2 0.1"/>')),
        link("drum", 2, collision('<cylinder radius="0.1" length="0.4"/>')),
        # the same drum on its side: its axis along y
        link("roller", 2, collision('<cylinder radius="0.1" length="0.4"/>',
                                    rpy=f"{math.pi / 2!r} 0 0")),
        link("ball", 1.5, collision('<sphere radius="0.2"/>')),
        # a box 0.5 m ahead of the declared centre of mass: the parallel-axis theorem
        link("offset", 2, collision('<box size="0.2 0.2 0.2"/>', xyz="0.5 0 0")),
        # two halves side by side are the whole box
        link("halves", 4, collision('<box size="0.15 0.2 0.1"/>', xyz="-0.075 0 0")
             + collision('<box size="0.15 0.2 0.1"/>', xyz="0.075 0 0")),
        link("drawn", 1, '\n    <visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>'))
    found = section_of(written(folder, "primitives.urdf", text))
    found.path, found.text = folder / "primitives.urdf", text
    return found


def box_six(m, x, y, z):
    return [m * (y * y + z * z) / 12, 0, 0, m * (x * x + z * z) / 12, 0, m * (x * x + y * y) / 12]


def test_a_box_cylinder_and_sphere_give_their_closed_forms(primitives):
    close(primitives.figure("inertia.block").value, box_six(3, 0.3, 0.2, 0.1))
    side = 2 * (3 * 0.01 + 0.16) / 12
    close(primitives.figure("inertia.drum").value, [side, 0, 0, side, 0, 2 * 0.01 / 2])
    close(primitives.figure("inertia.roller").value, [side, 0, 0, 2 * 0.01 / 2, 0, side])
    moment = 0.4 * 1.5 * 0.04
    close(primitives.figure("inertia.ball").value, [moment, 0, 0, moment, 0, moment])
    block = primitives.figure("inertia.block")
    assert block.unit == "kg m²"
    line = line_of(primitives.text, '<mass value="3"/>')
    assert block.source == (f"collision geometry (<box>), declared mass 3 kg "
                            f"({primitives.path}:{line})")


def test_a_shape_off_the_centre_of_mass_and_several_shapes_add_up(primitives):
    own = box_six(2, 0.2, 0.2, 0.2)
    shifted = own[:]
    shifted[3] += 2 * 0.25  # m d² about y and z, none about x (the offset is along x)
    shifted[5] += 2 * 0.25
    close(primitives.figure("inertia.offset").value, shifted)
    close(primitives.figure("inertia.halves").value, box_six(4, 0.3, 0.2, 0.1))


def test_a_link_without_collision_takes_its_visual_and_says_so(primitives):
    drawn = primitives.figure("inertia.drawn")
    close(drawn.value, box_six(1, 0.1, 0.1, 0.1))
    assert drawn.source.startswith("visual geometry (<box>)")
    assert "no collision geometry, the visual's taken" in drawn.source


def test_a_wildly_declared_tensor_is_w530_and_a_right_one_is_not(primitives):
    # every link above declares 1 kg m² about each axis: hundreds of times too much
    flagged = {d.message.split("'")[1] for d in primitives.diagnostics}
    assert flagged == {"block", "drum", "roller", "ball", "offset", "halves", "drawn"}
    assert all(d.rule == "W530" for d in primitives.diagnostics)


@pytest.fixture(scope="module")
def meshes(tmp_path_factory):
    import trimesh

    folder = tmp_path_factory.mktemp("meshes")
    trimesh.creation.box(extents=(1.0, 2.0, 4.0)).export(folder / "box.stl")
    open_box = trimesh.creation.box(extents=(1.0, 2.0, 4.0))  # (exact in an STL's float32)
    open_box.update_faces([i for i in range(len(open_box.faces)) if i != 0])  # one hole
    open_box.export(folder / "open.stl")
    text = robot(
        link("primitive", 2, collision('<box size="0.3 0.2 0.1"/>')),
        # a 1 x 2 x 4 m box mesh, scaled to 0.3 x 0.2 x 0.1 m, turned half a turn about z
        link("scaled", 2, collision('<mesh filename="box.stl" scale="0.3 0.1 0.025"/>',
                                    rpy=f"0 0 {math.pi!r}")),
        link("mirrored", 2, collision('<mesh filename="box.stl" scale="-0.3 0.1 0.025"/>')),
        link("open", 2, collision('<mesh filename="open.stl" scale="0.3 0.1 0.025"/>')))
    return section_of(written(folder, "meshes.urdf", text))


def test_a_mesh_box_is_the_box_primitive(meshes):
    expected = meshes.figure("inertia.primitive").value
    close(meshes.figure("inertia.scaled").value, expected, rel=1e-9)
    close(meshes.figure("inertia.mirrored").value, expected, rel=1e-9)
    assert meshes.figure("inertia.scaled").source.startswith(
        "collision geometry (mesh box.stl), declared mass 2 kg")


def test_a_mesh_with_a_hole_is_taken_by_its_convex_hull_and_said(meshes):
    hull = meshes.figure("inertia.open")
    close(hull.value, box_six(2, 0.3, 0.2, 0.1), rel=1e-9)
    assert hull.source.endswith("; not watertight, its convex hull taken: mesh open.stl")


def test_a_mesh_that_cannot_be_read_is_a_note_not_a_figure(tmp_path):
    (tmp_path / "junk.stl").write_bytes(b"solid nothing\nendsolid\n")
    text = robot(link("junk", 1, collision('<mesh filename="junk.stl"/>')),
                 link("block", 1, collision('<box size="0.1 0.1 0.1"/>'),
                      box_inertia(1, 0.1, 0.1, 0.1)))
    checked = check_input(RobotInput(written(tmp_path, "junk.urdf", text)))
    found = inertia_section(checked)
    assert found.figure("inertia.junk") is None
    assert any(n.startswith("link junk: collision mesh junk.stl ") and
               n.endswith("; no inertia from its geometry") for n in found.notes), found.notes
    assert found.figure("inertia.block") is not None and not found.diagnostics


MACRO = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <!-- block: a box of mass m kg, size x y z m; its inertia typed in by hand -->
  <xacro:macro name="block" params="name m x y z scale">
    <link name="${name}">
      <collision><geometry><box size="${x} ${y} ${z}"/></geometry></collision>
      <inertial>
        <origin xyz="0 0 0.01" rpy="0 0 0"/>
        <mass value="${m}"/>
        <inertia ixx="${scale * m * (y*y + z*z) / 12}" ixy="0" ixz="0"
                 iyy="${scale * m * (x*x + z*z) / 12}" iyz="0"
                 izz="${scale * m * (x*x + y*y) / 12}"/>
      </inertial>
    </link>
  </xacro:macro>
</robot>
"""

ROBOT = """<?xml version="1.0"?>
<robot name="blocks" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="parts/block.xacro"/>
  <link name="base"/>
  <xacro:block name="right_block" m="2" x="0.2" y="0.1" z="0.05" scale="1"/>
  <joint name="a" type="fixed"><parent link="base"/><child link="right_block"/></joint>
  <xacro:block name="wrong_block" m="2" x="0.2" y="0.1" z="0.05" scale="10"/>
  <joint name="b" type="fixed"><parent link="base"/><child link="wrong_block"/></joint>
</robot>
"""


def test_a_10x_inertia_in_a_macro_file_is_corrected_at_its_xacro_line(tmp_path, monkeypatch):
    (tmp_path / "parts").mkdir()
    written(tmp_path / "parts", "block.xacro", MACRO)
    written(tmp_path, "blocks.urdf.xacro", ROBOT)
    monkeypatch.chdir(tmp_path)  # (files are named as the user named them: relative)
    found = section_of(Path("blocks.urdf.xacro"))
    (warning,) = found.diagnostics  # the right block is not flagged
    line = line_of(MACRO, "<inertia ixx=")  # (the <inertia> the user edits, its first line)
    # the geometry about the declared centre, 1 cm above the box's: m d² added about x, y
    ixx, iyy, izz = 2 * 0.0125 / 12 + 2e-4, 2 * 0.0425 / 12 + 2e-4, 2 * 0.05 / 12
    assert warning.text() == (
        f"parts/block.xacro:{line}: warning: link 'wrong_block': declared inertia "
        f"[{10 * 2 * 0.0125 / 12:.4g}, 0, 0, {10 * 2 * 0.0425 / 12:.4g}, 0, "
        f"{10 * 2 * 0.05 / 12:.4g}] kg m² is implausible: "
        f"{10 * 2 * 0.05 / 12 / izz:.3g} times the geometry's about one of its principal "
        f"axes (over 3 times off); its geometry with 2 kg gives [{ixx:.4g}, 0, 0, {iyy:.4g}, "
        f"0, {izz:.4g}]; put in place of the <inertial> at parts/block.xacro:7: "
        f'<inertial><origin xyz="0 0 0.01" rpy="0 0 0"/><mass value="2"/><inertia '
        f'ixx="{ixx:.6g}" ixy="0" ixz="0" iyy="{iyy:.6g}" iyz="0" izz="{izz:.6g}"/>'
        "</inertial> (in xacro:block called at blocks.urdf.xacro:7) [W530]")
    close(found.figure("inertia.wrong_block").value, [ixx, 0, 0, iyy, 0, izz])


def test_a_tensor_mujoco_refuses_is_w530_though_its_size_is_near(tmp_path):
    # 120 kg m² about z against 50 + 50: no rigid body has it; yet each moment is within
    # 3x of those of a 100 kg box of moments 50, 50, 80 (its sides √4.8, √4.8, √1.2 m)
    side, height = math.sqrt(4.8), math.sqrt(1.2)
    shapes = collision(f'<box size="{side!r} {side!r} {height!r}"/>')
    bad = '<inertia ixx="50" ixy="0" ixz="0" iyy="50" iyz="0" izz="120"/>'
    found = section_of(written(tmp_path, "triangle.urdf",
                               robot(link("plate", 100, shapes, bad))))
    (warning,) = found.diagnostics
    close(found.figure("inertia.plate").value, [50, 0, 0, 50, 0, 80])
    assert "declared inertia [50, 0, 0, 50, 0, 120] kg m² is implausible: MuJoCo refuses " \
           "it (principal moments 50, 50, 120 kg m² break A + B >= C (50 + 50 < 120))" \
           in warning.message
    assert warning.text().endswith("[W530]")


def test_a_sensors_stand_in_shape_has_its_figure_but_is_not_judged(tmp_path):
    # a 1 cm box for a 10 g IMU with a token 1e-7 kg m²: 60 times its box's, but the box
    # is a stand-in (as mass-implausible leaves shapes within a 2 cm cube); the 3 cm one
    # is judged
    token = '<inertia ixx="1e-7" ixy="0" ixz="0" iyy="1e-7" iyz="0" izz="1e-7"/>'
    found = section_of(written(tmp_path, "imu.urdf", robot(
        link("imu", 0.01, collision('<box size="0.01 0.01 0.01"/>'), token),
        link("camera", 0.01, collision('<box size="0.03 0.03 0.03"/>'), token))))
    close(found.figure("inertia.imu").value, box_six(0.01, 0.01, 0.01, 0.01))
    assert [d.message.split("'")[1] for d in found.diagnostics] == ["camera"]


def test_mujoco_takes_the_same_inertias_from_the_same_shapes(primitives, meshes):
    for found in (primitives, meshes):
        for figure in found.figures:
            assert figure.proof.agrees, (figure.key, figure.proof.detail)
            close(figure.proof.measured, figure.value, rel=1e-6)
            assert figure.proof.detail.startswith(
                "MuJoCo's inertia from the same shapes (inertiafromgeom): off by ")


def test_control_mujocos_proof_disagrees_with_a_figure_that_is_off(tmp_path):
    from mobile_car.check.rest_pose import link_shapes
    from mobile_car.specs.inertia_proof import mujoco_proof

    text = robot(link("block", 3, collision('<box size="0.3 0.2 0.1"/>', xyz="0.1 0 0")))
    checked = check_input(RobotInput(written(tmp_path, "off.urdf", text)))
    block = next(link for link in checked.robot.links if link.name == "block")
    bodies = link_shapes(block.element).bodies
    right = box_six(3, 0.3, 0.2, 0.1)
    right[3] += 3 * 0.01  # the box 0.1 m ahead of the centre of mass: m d² about y, z
    right[5] += 3 * 0.01
    proof = mujoco_proof(bodies, [None], [False], 3, (0, 0, 0), (0, 0, 0), right)
    assert proof.agrees
    wrong = right[:3] + [right[3] * 1.001] + right[4:]
    proof = mujoco_proof(bodies, [None], [False], 3, (0, 0, 0), (0, 0, 0), wrong)
    assert not proof.agrees and proof.detail.endswith("off by 0.00088 of the largest moment")


def test_the_tensor_is_given_in_the_declared_inertial_axes(tmp_path):
    # the inertial frame turned a quarter turn about z: its x is the link's y
    turned = f'<origin xyz="0 0 0" rpy="0 0 {math.pi / 2!r}"/>'
    text = robot(link("block", 3, collision('<box size="0.3 0.2 0.1"/>'),
                      box_inertia(3, 0.2, 0.3, 0.1), turned))
    found = section_of(written(tmp_path, "turned.urdf", text))
    close(found.figure("inertia.block").value, box_six(3, 0.2, 0.3, 0.1))
    assert not found.diagnostics  # declared right, in those axes
    assert found.figure("inertia.block").proof.agrees


def test_without_proofs_mujoco_is_not_asked(primitives):
    """--no-proof (and diff and sweep) ask for the figures only: the same tensors, no proof."""
    robot = check_input(RobotInput(primitives.path))
    proven, bare = inertia_section(robot), inertia_section(robot, proof=False)
    assert [(f.key, f.value) for f in bare.figures] == [(f.key, f.value) for f in proven.figures]
    assert all(f.proof is not None for f in proven.figures)
    assert all(f.proof is None for f in bare.figures)
