"""mcar export --to mjcf --verify on the robots people ship and on the bundled car: each
exported from a copy of its packages under tmp, the copy then deleted, and the folder
loaded by MuJoCo here (not by mcar): the total mass equals the URDF's (summed by this test
from the URDF mcar build writes) within 0.1%, the moving joints are the URDF's, and the
car passes sim's scenarios (drop, drive, spin) under its own actuators. Then the PR2-like
inertias: refused with every link named, or fixed by MuJoCo with one warning per link;
and a tampered export that --verify's checks catch, naming what differs."""

from __future__ import annotations

import json
import math
import re
import shutil

import pytest
from conftest import REPO
from lxml import etree
from sim.robot_makers import two_wheeler
from sim.test_sim_real_robots import FOLDER, needs_folder

from mobile_car.sim.engine import mujoco as engine

mujoco = engine()

# robot -> (packages it reads from the shared folder, its file there)
REAL = {
    "burger": (["turtlebot3_description"], "turtlebot3_description/urdf/turtlebot3_burger.urdf"),
    "waffle": (["turtlebot3_description"], "turtlebot3_description/urdf/turtlebot3_waffle.urdf"),
    "waffle_pi": (["turtlebot3_description"],
                  "turtlebot3_description/urdf/turtlebot3_waffle_pi.urdf"),
    "husky": (["husky_description", "clearpath_deps"], "husky_description/urdf/husky.urdf.xacro"),
    "jackal": (["jackal_description", "clearpath_deps"],
               "jackal_description/urdf/jackal.urdf.xacro"),
}


def _invoke(*args):
    from click.testing import CliRunner
    from mobile_car.cli.main import main

    return CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=False)


def _urdf_facts(urdf_path):
    """(total mass, moving joints) as the URDF says, read here without mcar."""
    root = etree.parse(str(urdf_path)).getroot()
    mass = sum(float(m.get("value")) for m in root.findall("link/inertial/mass"))
    moving = sorted(j.get("name") for j in root.findall("joint") if j.get("type") != "fixed")
    return mass, moving


def _export(source, urdf, out, package_path):
    """Build the URDF (for the test's own figures), export with --verify, and return
    (exit code, stderr, URDF mass, URDF moving joints)."""
    built = out.parent / f"{out.name}.urdf"
    result = _invoke("build", "--package-path", package_path, source, "-o", built)
    assert result.exit_code == 0, result.output
    mass, moving = _urdf_facts(built)
    # TurtleBot3's .urdf holds a <xacro:arg>: it is exported from the built file, as
    # ROS 2 launch expands it; the xacro robots from their .xacro.
    given = built if str(source).endswith(".urdf") else source
    result = _invoke("export", "--package-path", package_path, given, "--to", "mjcf", "-o",
                     out, "--verify")
    return result.exit_code, result.stderr, mass, moving


@pytest.fixture(scope="session")
def exports(tmp_path_factory):
    """robot -> (exit code, stderr, URDF mass, moving joints, folder), every source gone."""
    work = tmp_path_factory.mktemp("exports")
    done = {}
    car = work / "car_src" / "mobile_car_description"
    for name in ("urdf", "meshes"):
        shutil.copytree(REPO / name, car / name)
    shutil.copy(REPO / "package.xml", car / "package.xml")
    done["car"] = (*_export(car / "urdf/mobile_robot.xacro", None, work / "car", car),
                   work / "car")
    shutil.rmtree(work / "car_src")
    if FOLDER is not None:
        for robot, (packages, path) in REAL.items():
            source = work / f"{robot}_src"
            for package in packages:
                shutil.copytree(FOLDER / package, source / package)
            done[robot] = (*_export(source / path, None, work / robot, source), work / robot)
            shutil.rmtree(source)
    return done


def _check_loaded(folder, mass, moving):
    (robot_file,) = [p for p in folder.glob("*.xml")]
    model = mujoco.MjModel.from_xml_path(str(robot_file))
    assert math.isclose(float(model.body_mass.sum()), mass, rel_tol=1e-3)
    joints = sorted(model.joint(j).name for j in range(model.njnt)
                    if model.jnt_type[j] != mujoco.mjtJoint.mjJNT_FREE)
    assert joints == moving
    data = mujoco.MjData(model)
    mujoco.mj_step(model, data, nstep=1000)  # 1 s on the floor, motors at 0
    assert sum(v * v for v in data.qvel[:3]) ** 0.5 < 0.02  # at rest
    start = data.qpos[:3].copy()
    drive = json.loads((folder / "mcar-export.json").read_text())["drive"]
    for joint in drive["left"] + drive["right"]:
        axis = data.xaxis[model.joint(joint).id]
        data.ctrl[model.actuator(f"mcar_motor_{joint}").id] = 4.0 if axis[1] >= 0 else -4.0
    mujoco.mj_step(model, data, nstep=1000)
    forward = data.qpos[0] - start[0]
    assert 0.5 * drive["radius"] * 4.0 < forward < 1.1 * drive["radius"] * 4.0
    return model


def test_the_bundled_car_loads_with_its_package_gone(exports):
    code, stderr, mass, moving, folder = exports["car"]
    assert code == 0, stderr
    assert "verified: mass 0.70564 kg, the description's 0.70564 kg" in stderr
    _check_loaded(folder, mass, moving)


@needs_folder
@pytest.mark.parametrize("robot", sorted(REAL))
def test_a_real_robot_loads_with_its_packages_gone(exports, robot):
    code, stderr, mass, moving, folder = exports[robot]
    assert code == 0, stderr
    assert "verified: MuJoCo loads it from the folder alone" in stderr
    assert "verified: drive passed as mcar sim judges it: distance error " in stderr
    _check_loaded(folder, mass, moving)


@needs_folder
def test_husky_collada_meshes_are_converted_and_listed(exports):
    folder = exports["husky"][4]
    manifest = json.loads((folder / "mcar-export.json").read_text())
    assert "package://husky_description/meshes/wheel.dae -> " \
           "meshes/husky_description/meshes/wheel.dae.stl" in manifest["converted"]
    assert "meshes/husky_description/meshes/top_plate.stl" in manifest["meshes"]  # as it was
    assert all(not p.suffix == ".dae" for p in folder.rglob("*"))


@needs_folder
def test_waffle_says_which_mesh_its_package_lacks(exports):
    stderr = exports["waffle"][1]
    assert "warning: link base_link: visual left out: mesh " \
           "package://turtlebot3_description/meshes/bases/waffle_base.stl: no such file" in stderr


PR2_LIKE = """
  <link name="arm_link">
    <inertial><mass value="0.5"/><inertia ixx="0.001" iyy="0.002" izz="0.01" ixy="0" ixz="0"
      iyz="0"/></inertial>
    <collision><geometry><box size="0.02 0.02 0.1"/></geometry></collision>
  </link>
  <joint name="arm_joint" type="revolute">
    <parent link="base_link"/><child link="arm_link"/><origin xyz="0 0 0.1"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="5" velocity="1"/>
  </joint>
  <link name="hand_link">
    <inertial><mass value="0.1"/><inertia ixx="0.0001" iyy="0.0001" izz="0.0003" ixy="0"
      ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="hand_joint" type="fixed"><parent link="arm_link"/><child link="hand_link"/>
  </joint>"""


def test_inertias_that_break_the_triangle_inequality_are_named(run_mcar, tmp_path):
    (tmp_path / "pr2ish.urdf").write_text(two_wheeler(extra=PR2_LIKE))
    result = run_mcar("export", "pr2ish.urdf", "--to", "mjcf", "-o", "out", cwd=tmp_path)
    assert result.returncode == 1
    assert result.stderr.splitlines() == [
        "pr2ish.urdf: error: MuJoCo refuses the inertia of 2 links (arm_link, hand_link); "
        "--fix-inertia applies MuJoCo's own fixes (balanceinertia, inertia from geometry)",
        "  link arm_link: principal moments 0.001, 0.002, 0.01 kg m² break A + B >= C "
        "(0.001 + 0.002 < 0.01) (pr2ish.urdf:39)",  # where each <inertia> is written
        "  link hand_link: principal moments 0.0001, 0.0001, 0.0003 kg m² break A + B >= C "
        "(0.0001 + 0.0001 < 0.0003) (pr2ish.urdf:48)"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pr2ish.urdf"]


def test_the_fix_option_balances_them_with_a_warning_each(run_mcar, tmp_path):
    (tmp_path / "pr2ish.urdf").write_text(two_wheeler(extra=PR2_LIKE))
    result = run_mcar("export", "pr2ish.urdf", "--to", "mjcf", "-o", "out", "--fix-inertia",
                      "--verify", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    warnings = [line for line in result.stderr.splitlines() if ": warning: " in line]
    assert warnings == [
        "pr2ish.urdf: warning: link arm_link: inertia balanced by MuJoCo (balanceinertia): "
        "principal moments 0.001, 0.002, 0.01 -> 0.004333 each kg m²",
        "pr2ish.urdf: warning: link hand_link: inertia balanced by MuJoCo (balanceinertia): "
        "principal moments 0.0001, 0.0001, 0.0003 -> 0.0001667 each kg m²"]
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "out/two_wheeler.xml"))
    assert model.body("arm_link").inertia == pytest.approx([0.013 / 3] * 3)
    assert model.body("wheel_left_link").inertia.tolist() != [model.body(
        "wheel_left_link").inertia[0]] * 3  # the others keep the description's


def test_a_moving_link_without_mass_gets_one_from_its_geometry(run_mcar, tmp_path):
    flag = """
  <link name="flag_link"><collision><geometry><box size="0.03 0.03 0.03"/></geometry></collision>
  </link>
  <joint name="flag_joint" type="revolute"><parent link="base_link"/><child link="flag_link"/>
    <origin xyz="0 0 0.2"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1"
    velocity="1"/></joint>"""
    (tmp_path / "flag.urdf").write_text(two_wheeler(extra=flag))
    refused = run_mcar("export", "flag.urdf", "--to", "mjcf", "-o", "out", cwd=tmp_path)
    assert refused.returncode == 1
    assert "  link flag_link: moves but has no mass (MuJoCo needs one)" in refused.stderr
    fixed = run_mcar("export", "flag.urdf", "--to", "mjcf", "-o", "out", "--fix-inertia",
                     "--verify", cwd=tmp_path)
    assert fixed.returncode == 0, fixed.stderr
    assert ("flag.urdf: warning: link flag_link: moves without mass; MuJoCo gave it 0.027 kg "
            "and its inertia from its collision geometry") in fixed.stderr  # 30 mm of water
    assert "verified: mass 0.727 kg, the description's 0.7 kg + 0.027 kg given to massless " \
           "links" in fixed.stderr


# Valkyrie's virtual frames (val_description valkyrie_A.urdf): 1e-7 kg, moments 3.3e-22 kg m².
# Positive, so check does not warn, but under the 1e-14 MuJoCo's fullinertia takes as positive
# (its URDF reader gives every tensor so): the compile stopped at the first, unnamed.
TINY_FRAME = """
  <link name="imu_frame">
    <inertial><mass value="1e-07"/>
      <inertia ixx="3.3333e-22" ixy="0" ixz="0" iyy="3.3333e-22" iyz="0" izz="5e-22"/>
    </inertial>
  </link>
  <joint name="imu_joint" type="fixed"><parent link="base_link"/><child link="imu_frame"/>
    <origin xyz="0 0 0.1"/></joint>"""


def test_moments_under_mujocos_smallest_are_named_and_fixed(run_mcar, tmp_path):
    (tmp_path / "val.urdf").write_text(two_wheeler(extra=TINY_FRAME))
    refused = run_mcar("export", "val.urdf", "--to", "mjcf", "-o", "out", cwd=tmp_path)
    assert refused.returncode == 1
    assert refused.stderr.splitlines()[1:] == [
        "  link imu_frame: principal moments 3.333e-22, 3.333e-22, 5e-22 kg m², the smallest "
        "under the 1e-14 MuJoCo takes as positive (val.urdf:39)"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["val.urdf"]
    fixed = run_mcar("export", "val.urdf", "--to", "mjcf", "-o", "out", "--fix-inertia",
                     "--verify", cwd=tmp_path)
    assert fixed.returncode == 0, fixed.stderr
    assert ("val.urdf: warning: link imu_frame: has 1e-07 kg and principal moments under "
            "MuJoCo's 1e-14 kg m²; given that of a 1 cm solid sphere of its mass (4e-12 kg m² "
            "about each axis)") in fixed.stderr
    assert "verified: mass 0.7 kg, the description's 0.7 kg" in fixed.stderr


def test_the_descriptions_own_mujoco_block_gives_way_to_mcars(run_mcar, tmp_path):
    # Unitree's G1 and H1 carry MuJoCo's URDF extension for their own mesh folder: mcar's
    # was added beside it, and MuJoCo refused the robot ("repeated element: 'mujoco'")
    urdf = two_wheeler().replace(
        "<robot name=\"two_wheeler\">",
        "<robot name=\"two_wheeler\">\n  <mujoco>\n    <compiler meshdir=\"../meshes\" "
        "discardvisual=\"false\"/>\n  </mujoco>", 1)
    assert urdf.count("<mujoco>") == 1
    (tmp_path / "unitreeish.urdf").write_text(urdf)
    result = run_mcar("export", "unitreeish.urdf", "--to", "mjcf", "-o", "out", "--verify",
                      cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "verified: mass 0.7 kg, the description's 0.7 kg" in result.stderr
    assert "meshdir" not in (tmp_path / "out" / "two_wheeler.xml").read_text()


ARM_ON_A_BARE_BASE = """<?xml version="1.0"?>
<robot name="bolted_arm">
  <link name="base_link"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
  </link>
  <link name="arm_link">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0"
      iyz="0"/></inertial>
    <collision><geometry><box size="0.05 0.05 0.3"/></geometry></collision>
  </link>
  <joint name="arm_joint" type="revolute">
    <parent link="base_link"/><child link="arm_link"/><origin xyz="0 0 0.2"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="5" velocity="1"/>
  </joint>
</robot>
"""


def test_a_floating_root_without_mass_is_judged_as_the_moving_link_it_is(run_mcar, tmp_path):
    # ABB's arms: a base_link without <inertial>, every other link on a joint. Floating, the
    # base moves; MuJoCo refused it only at the last compile, past --fix-inertia's reach.
    (tmp_path / "arm.urdf").write_text(ARM_ON_A_BARE_BASE)
    refused = run_mcar("export", "arm.urdf", "--to", "mjcf", "-o", "out", cwd=tmp_path)
    assert refused.returncode == 1
    assert refused.stderr.splitlines()[1:] == [
        "  link base_link: moves but has no mass (MuJoCo needs one) (arm.urdf:3)"]
    fixed = run_mcar("export", "arm.urdf", "--to", "mjcf", "-o", "out", "--fix-inertia",
                     "--verify", cwd=tmp_path)
    assert fixed.returncode == 0, fixed.stderr
    assert ("arm.urdf: warning: link base_link: moves without mass; MuJoCo gave it 4 kg "
            "and its inertia from its collision geometry") in fixed.stderr
    bolted = run_mcar("export", "arm.urdf", "--to", "mjcf", "-o", "fixed", "--base", "fixed",
                      cwd=tmp_path)  # welded to the world, the base need not move
    assert bolted.returncode == 0, bolted.stderr


def test_verify_names_a_mass_that_differs(tmp_path):
    from mobile_car.errors import McarError
    from mobile_car.export.mjcf import Exported
    from mobile_car.export.verify import verify_mjcf

    (tmp_path / "car.urdf").write_text(two_wheeler())
    assert _invoke("export", tmp_path / "car.urdf", "--to", "mjcf", "-o",
                   tmp_path / "out").exit_code == 0
    document = json.loads((tmp_path / "out/mcar-export.json").read_text())
    exported = Exported(**{k: document[k] for k in Exported.__dataclass_fields__})
    assert verify_mjcf(tmp_path / "out", exported)[0] == "MuJoCo loads it from the folder alone"
    exported.urdf_mass = 0.8
    with pytest.raises(McarError, match=r"total mass 0\.7 kg, the description's 0\.8 kg "
                                        r"\(12\.5% apart, more than 0\.1%\)"):
        verify_mjcf(tmp_path / "out", exported)
    exported.urdf_mass, exported.moving_joints = 0.7, ["wheel_left_joint", "arm_joint"]
    with pytest.raises(McarError, match="moving joints differ: missing arm_joint; not in the "
                                        "description: wheel_right_joint"):
        verify_mjcf(tmp_path / "out", exported)
    xml = tmp_path / "out/two_wheeler.xml"
    xml.write_text(xml.read_text().replace("<asset>", '<asset><mesh name="x" file="/etc/x.stl"/>'))
    with pytest.raises(McarError, match="mesh /etc/x.stl: an absolute path"):
        verify_mjcf(tmp_path / "out", exported)


def test_a_robot_that_tips_over_fails_verify_and_writes_nothing(run_mcar, tmp_path):
    """A 1 kg mast on a 0.7 kg two-wheeler (its mass from a 10 cm box of water) pitches the
    car over: --verify says so, as sim would, at the folder asked for, and nothing is
    written."""
    mast = """
  <link name="mast_link"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
  <joint name="mast_joint" type="revolute"><parent link="base_link"/><child link="mast_link"/>
    <origin xyz="0 0 0.2"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1"
    velocity="1"/></joint>"""
    (tmp_path / "mast.urdf").write_text(two_wheeler(extra=mast))
    result = run_mcar("export", "mast.urdf", "--to", "mjcf", "-o", "out", "--fix-inertia",
                      "--verify", cwd=tmp_path)
    assert result.returncode == 1
    # Released in the pose it rests in, it stands, on the edge; it goes over as it drives.
    assert result.stderr.startswith("out: error: drive failed as mcar sim judges it: ")
    turned = re.search(r"heading change (\d+\.\d+) deg \(bound <= 2.00 deg\)", result.stderr)
    assert float(turned.group(1)) > 90  # over on its back
    assert result.stderr.endswith(" (spin failed too)\n")
    assert len(result.stderr.splitlines()) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mast.urdf"]
