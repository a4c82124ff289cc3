"""Mecanum is its own drive kind: a base on four plain cylinders (as linorobot2 and ROSbot
XL draw theirs) is mecanum where its package declares it (a <gazebo> planar_move plugin on
sliding wheels, mecanum_drive_controller in its X_control package's YAML, fdir1 with mu2
0), skid-steer where nothing does. Simulated with rollers that grip at 45°, it drives
forward, strafes left and spins at the rates its geometry gives, which the tests compute:
r·ω·t forward and sideways, r·ω/(a + b) yaw. The torque its motors get comes from its
tyres' grip, not from a <mu1> of 0.01 (linorobot2's rollers' free roll), and rollers that
grip the other way (an O pattern) strafe it the wrong way."""

from __future__ import annotations

import json
import math
import re

import pytest
from sim.robot_makers import PLANAR_MOVE, mecanum_rings, mecanum_wheels, skid_steer
from sim.test_sim_real_robots import FOLDER, needs_folder

# A wheelbase other than the track: the spin's r·ω/(a + b) is not 2·r·ω/track.
BASE = {"mass": 10.0, "wheelbase": 0.3, "track": 0.4, "radius": 0.06}
PACKAGE_XML = ('<?xml version="1.0"?><package format="3"><name>{}</name><version>0.0.1'
               '</version><description>d</description><maintainer email="t@example.com">t'
               '</maintainer><license>BSD</license></package>\n')
CONTROLLER_YAML = """# as ROSbot XL ships it (ros2_controllers' older parameter names)
/**/controller_manager:
  ros__parameters:
    base_controller:
      type: mecanum_drive_controller/MecanumDriveController
/**/base_controller:
  ros__parameters:
    front_left_wheel_name: front_left_wheel_joint
    front_right_wheel_name: front_right_wheel_joint
    rear_left_wheel_name: rear_left_wheel_joint
    rear_right_wheel_name: rear_right_wheel_joint
    wheel_separation_x: 0.3
    wheel_separation_y: 0.4
    wheel_radius: {radius}
"""
FDIR = """
  <gazebo reference="{wheel}_wheel_link"><collision><surface><friction><ode>
    <mu>1.0</mu><mu2>0.0</mu2><fdir1>{fdir}</fdir1>
  </ode></friction></surface></collision></gazebo>"""


def fdir_block(sign: int) -> str:
    """fdir1 on each wheel: the X pattern (sign 1, ROSbot XL's), the O pattern (-1)."""
    x_pattern = {"front_left": -1, "front_right": 1, "rear_left": 1, "rear_right": -1}
    return "".join(FDIR.format(wheel=w, fdir=f"1 {sign * s} 0") for w, s in x_pattern.items())


def sim_json(cli, path, *args):
    result = cli("sim", path, "--format", "json", *args)
    return result, json.loads(result.stdout)["files"][0]


def figures(entry) -> dict[str, dict[str, float]]:
    return {s["name"]: {f["name"]: f["value"] for f in s["figures"]} for s in entry["scenarios"]}


@pytest.fixture(scope="module")
def planar_move(tmp_path_factory):
    """linorobot2's shape: plain cylinders at <mu1> 0.01, a planar_move plugin; simulated
    once, all four scenarios."""
    from click.testing import CliRunner
    from mobile_car.cli.main import main

    path = tmp_path_factory.mktemp("mecanum") / "planar.urdf"
    path.write_text(mecanum_wheels(wheel_mu=0.01, extra=PLANAR_MOVE, **BASE))
    result = CliRunner().invoke(main, ["sim", str(path), "--format", "json"],
                                catch_exceptions=False)
    return result, json.loads(result.stdout)["files"][0]


def test_a_planar_move_base_on_plain_cylinders_is_mecanum_and_passes(planar_move):
    result, entry = planar_move
    assert result.exit_code == 0, result.stderr
    drive = entry["drive"]
    assert drive["kind"] == "mecanum"
    assert drive["declared"] == "<gazebo> plugin libgazebo_ros_planar_move.so"
    assert drive["left"] == ["front_left_wheel_joint", "rear_left_wheel_joint"]
    assert drive["right"] == ["front_right_wheel_joint", "rear_right_wheel_joint"]
    assert drive["grip_from"] == "the usual X pattern"
    h = round(math.sqrt(0.5), 4)
    assert {j: r["grip_axis"] for j, r in drive["rollers"].items()} == {
        "front_left_wheel_joint": [h, -h], "rear_right_wheel_joint": [h, -h],
        "front_right_wheel_joint": [h, h], "rear_left_wheel_joint": [h, h]}
    assert [(s["name"], s["status"]) for s in entry["scenarios"]] == [
        ("drop", "passed"), ("drive", "passed"), ("strafe", "passed"), ("spin", "passed")]


def test_its_motors_torque_comes_from_the_tyres_grip_not_the_rollers_mu(planar_move):
    _, entry = planar_move
    drive = entry["drive"]
    mu_g_r = 1.0 * BASE["mass"] * 9.81 * BASE["radius"] / 4  # mu 1, not 0.01
    for motor in drive["motors"].values():
        assert motor["effort"] == pytest.approx(mu_g_r, rel=1e-6)
        assert motor["effort_from"] == ("default: slips the wheels of 10 kg at mu 1 "
                                        "(mu·m·g·r / 4, mecanum)")
    for roller in drive["rollers"].values():
        assert (roller["mu"], roller["mu_across"]) == (1.0, 0.01)
        assert roller["mu_from"] == "a tyre's 1: the <mu1> 0.01 is the rollers' free roll"


def test_it_drives_strafes_and_spins_as_far_as_its_geometry_says(planar_move):
    _, entry = planar_move
    found = figures(entry)
    omega = entry["drive"]["command_speed"]
    r, a, b = BASE["radius"], BASE["wheelbase"] / 2, BASE["track"] / 2
    assert omega == pytest.approx(min(10.0, 0.5 / r))
    assert found["drive"]["distance error"] < 2.0
    assert found["drive"]["lateral drift"] < 0.001 and found["drive"]["heading change"] < 0.1
    strafe = next(s for s in entry["scenarios"] if s["name"] == "strafe")
    sideways = float(strafe["figures"][0]["detail"].split(" m to the left")[0])
    assert sideways == pytest.approx(r * omega * (3.0 - 0.25), rel=0.02)
    assert found["strafe"]["forward drift"] < 0.005 and found["strafe"]["heading change"] < 0.5
    spin = next(s for s in entry["scenarios"] if s["name"] == "spin")
    ideal = r * omega / (a + b)  # 2·r·ω/track would be 1.75 times as fast here
    assert f"of r·ω/(a + b) = {ideal:.4f} rad/s" in spin["figures"][0]["detail"]
    rate = float(spin["figures"][0]["detail"].split(" rad/s")[0])
    assert rate == pytest.approx(ideal, rel=0.03)
    assert found["spin"]["centre moved"] < 0.005


def test_text_report_names_the_kind_its_declaration_and_the_strafe(cli, tmp_path):
    path = tmp_path / "planar.urdf"
    path.write_text(mecanum_wheels(wheel_mu=0.01, extra=PLANAR_MOVE, **BASE))
    result = cli("sim", path, "--scenario", "strafe", terminal_width=200)
    assert result.exit_code == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[1].startswith("  mecanum (declared) drive wheels front_left_wheel_joint, "
                               "rear_left_wheel_joint (left), front_right_wheel_joint, "
                               "rear_right_wheel_joint (right): radius 0.06 m, track 0.4 m")
    assert ("  mecanum: <gazebo> plugin libgazebo_ros_planar_move.so; wheelbase 0.3 m; "
            "rollers grip along front_left_wheel_joint (+0.707, -0.707)") in result.stdout
    assert "  strafe PASSED" in lines
    assert "mcar sim: 1 passed, 0 failed, 0 skipped in 1 file" in result.stderr


def test_without_a_declaration_plain_cylinders_stay_skid_steer(cli, tmp_path):
    # A robot named "mecanum_wheels" with a <mu1> of 0.01 declares nothing: geometry says
    # four wheels two a side, skid-steer.
    path = tmp_path / "plain.urdf"
    path.write_text(mecanum_wheels(wheel_mu=0.01, **BASE))
    result, entry = sim_json(cli, path, "--scenario", "drop")
    assert result.exit_code == 0, result.stderr
    assert entry["drive"]["kind"] == "skid-steer" and "rollers" not in entry["drive"]
    # planar_move says only that Gazebo moves the base: on tyres that grip (Summit XL's
    # skid-steer variant, mu 1) it is no mecanum declaration.
    gripping = tmp_path / "gripping.urdf"
    gripping.write_text(mecanum_wheels(wheel_mu=1.0, extra=PLANAR_MOVE, **BASE))
    result, entry = sim_json(cli, gripping, "--scenario", "drop")
    assert result.exit_code == 0, result.stderr
    assert entry["drive"]["kind"] == "skid-steer"
    skid = tmp_path / "skid.urdf"
    skid.write_text(skid_steer())
    result, entry = sim_json(cli, skid, "--scenario", "strafe")
    assert entry["drive"]["kind"] == "skid-steer"
    assert [(s["name"], s["status"], s["message"]) for s in entry["scenarios"]] == [
        ("strafe", "skipped", "strafe moves a mecanum robot sideways: a skid-steer robot "
                              "cannot")]


def make_packages(root, radius: float):
    for name in ("rover_description", "rover_control"):
        (root / name).mkdir()
        (root / name / "package.xml").write_text(PACKAGE_XML.format(name))
    (root / "rover_description" / "rover.urdf").write_text(mecanum_wheels(**BASE))
    (root / "rover_control" / "config").mkdir()
    (root / "rover_control" / "config" / "mecanum.yaml").write_text(
        CONTROLLER_YAML.format(radius=radius))


def test_a_mecanum_drive_controller_in_the_control_package_declares_it(cli, tmp_path,
                                                                         monkeypatch):
    make_packages(tmp_path, BASE["radius"])
    monkeypatch.chdir(tmp_path)
    result, entry = sim_json(cli, "rover_description/rover.urdf", "--package-path", tmp_path,
                             "--scenario", "drop")
    assert result.exit_code == 0, result.stderr
    assert entry["drive"]["kind"] == "mecanum"
    assert entry["drive"]["declared"] == ("rover_control/config/mecanum.yaml:8 "
                                          "(mecanum_drive_controller)")


def test_a_controller_configured_for_other_wheels_does_not(cli, tmp_path, monkeypatch):
    # ROSbot XL ships a mecanum YAML for its 50 mm mecanum wheels beside a diff-drive one
    # for its 48 mm tyres on the same joints: with the tyres, it is skid-steer.
    make_packages(tmp_path, 0.8 * BASE["radius"])
    monkeypatch.chdir(tmp_path)
    result, entry = sim_json(cli, "rover_description/rover.urdf", "--package-path", tmp_path,
                             "--scenario", "drop")
    assert result.exit_code == 0, result.stderr
    assert entry["drive"]["kind"] == "skid-steer"


def test_fdir1_gives_the_grip_axes_and_an_o_pattern_strafes_the_wrong_way(cli, tmp_path):
    ok = tmp_path / "x.urdf"
    ok.write_text(mecanum_wheels(extra=fdir_block(1), **BASE))
    result, entry = sim_json(cli, ok, "--scenario", "strafe")
    assert result.exit_code == 0, result.stderr
    assert entry["drive"]["declared"].startswith("<gazebo> fdir1 with mu2 0 on ")
    assert entry["drive"]["grip_from"] == "<gazebo> fdir1"
    assert {r["mu_from"] for r in entry["drive"]["rollers"].values()} == \
        {"<gazebo> mu, mu2 with fdir1"}
    # Control: the same robot with its rollers the other way round moves right.
    wrong = tmp_path / "o.urdf"
    wrong.write_text(mecanum_wheels(extra=fdir_block(-1), **BASE))
    result, entry = sim_json(cli, wrong, "--scenario", "strafe")
    assert result.exit_code == 1
    strafe = entry["scenarios"][0]
    assert strafe["status"] == "failed"
    assert "with its wheels set to move it left: its rollers grip the other way" in \
        strafe["message"]


def test_drive_mecanum_needs_two_wheels_a_side(cli, tmp_path):
    path = tmp_path / "six.urdf"
    path.write_text(skid_steer(per_side=3))
    result = cli("sim", path, "--drive", "mecanum", "--scenario", "drop")
    assert result.exit_code == 2
    assert ("--drive mecanum: 3 wheel(s) on the left, 3 on the right; mecanum drives two a "
            "side") in result.stderr


# linorobot2's mecanum base, read in place (../shared/real-robots/SOURCES.md): mcar called
# it skid-steer and failed its drive and spin on a torque from its rollers' mu 0.01.
LINOROBOT2 = "linorobot2_description/urdf/robots/mecanum.urdf.xacro"


@needs_folder
def test_linorobot2_mecanum_is_mecanum_and_drives_strafes_and_spins(cli):
    result = cli("sim", "--package-path", FOLDER, FOLDER / LINOROBOT2, "--format", "json")
    assert result.exit_code == 0, result.stderr
    entry = json.loads(result.stdout)["files"][0]
    drive = entry["drive"]
    assert (drive["kind"], drive["declared"]) == (
        "mecanum", "<gazebo> plugin libgazebo_ros_planar_move.so")
    assert (drive["wheel_radius"], drive["track"], drive["wheelbase"]) == (0.07162, 0.271, 0.24)
    assert [(s["name"], s["status"]) for s in entry["scenarios"]] == [
        ("drop", "passed"), ("drive", "passed"), ("strafe", "passed"), ("spin", "passed")]
    found = figures(entry)
    assert found["drive"]["distance error"] < 2.0 and found["strafe"]["sideways error"] < 3.0
    assert found["spin"]["yaw rate error"] < 3.0


@needs_folder
def test_linorobot2_mecanum_exports_a_verified_mjcf(cli, tmp_path):
    # Its wheels grip as tyres in the file (mu 1, not the rollers' 0.01): it drives.
    result = cli("export", "--package-path", FOLDER, FOLDER / LINOROBOT2, "--to", "mjcf",
                 "-o", tmp_path / "out", "--verify")
    assert result.exit_code == 0, result.stderr
    assert ("mecanum wheels: their rollers are not in the file (mcar sim models them); each "
            "wheel grips as a tyre of mu 1: the robot drives and turns, but does not "
            "strafe") in result.stderr
    # judged as sim judges, on drop and drive only: the file holds no rollers to strafe on
    assert "verified: drop passed as mcar sim judges it" in result.stderr
    error = re.search(r"verified: drive passed as mcar sim judges it: distance error "
                      r"([0-9.]+) %", result.stderr)
    assert error and float(error[1]) < 2.0, result.stderr  # mu 0.01: 85% short
    assert "strafe" not in result.stderr.replace("does not strafe", "")
    written = (tmp_path / "out" / "linorobot2_2wd.xml").read_text()
    assert 'friction="0.01' not in written


def test_a_declaration_read_elsewhere_gets_its_mecanum_drive_from_the_tree():
    # The entry point drives.py's "declarations first" calls with the kind and the wheel
    # joints a controller names.
    import mujoco
    from lxml import etree

    from mobile_car.sim.drives import find_tree
    from mobile_car.sim.mecanum import declared_drive
    from mobile_car.sim.model import lowest_points

    text = mecanum_wheels(**BASE)
    model = mujoco.MjModel.from_xml_string(text)
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    joints = {j.get("name"): j for j in etree.fromstring(text.encode()) if j.tag == "joint"}
    tree = find_tree(mujoco, model, data, joints, lowest_points(mujoco, model, data))
    names = ["front_left_wheel_joint", "front_right_wheel_joint", "rear_left_wheel_joint",
             "rear_right_wheel_joint"]
    drive = declared_drive(tree, "mecanum", names, "base.yaml:3 (mecanum_drive_controller)")
    assert drive.kind == "mecanum" and drive.declared == "base.yaml:3 (mecanum_drive_controller)"
    assert [w.joint for w in drive.left] == ["front_left_wheel_joint", "rear_left_wheel_joint"]
    assert [w.grip for w in drive.driven] == [(math.sqrt(0.5), -math.sqrt(0.5)),
                                              (math.sqrt(0.5), math.sqrt(0.5)),
                                              (math.sqrt(0.5), math.sqrt(0.5)),
                                              (math.sqrt(0.5), -math.sqrt(0.5))]
    assert declared_drive(tree, "mecanum", names[:3]) is None  # three wheels: no mecanum
    assert declared_drive(tree, "diff_drive", names) is None


def test_named_wheels_drive_as_mecanum_when_asked(cli, tmp_path):
    path = tmp_path / "plain.urdf"
    path.write_text(mecanum_wheels(**BASE))
    left = "front_left_wheel_joint,rear_left_wheel_joint"
    right = "front_right_wheel_joint,rear_right_wheel_joint"
    result, entry = sim_json(cli, path, "--left", left, "--right", right, "--drive", "mecanum",
                             "--scenario", "drop")
    assert result.exit_code == 0, result.stderr
    assert (entry["drive"]["kind"], entry["drive"]["chosen"]) == ("mecanum", "--left/--right")
    result = cli("sim", path, "--left", "front_left_wheel_joint,front_right_wheel_joint",
                 "--right", "rear_left_wheel_joint,rear_right_wheel_joint", "--drive",
                 "mecanum", "--scenario", "drop")
    assert result.exit_code == 2
    assert "--drive mecanum drives two wheels a side, one in front of the other" in \
        result.stderr


@pytest.mark.parametrize("pattern", [1, -1], ids=["X", "O"])
def test_hubs_on_rings_of_roller_links_get_their_grip_axes_from_the_rollers(cli, tmp_path,
                                                                              pattern):
    # Hubs without collision geometry of their own, eight roller links each: the rollers
    # make the rim (its radius the wheel's) and say which way they grip.
    path = tmp_path / "rings.urdf"
    path.write_text(mecanum_rings(pattern=pattern, **BASE))
    result, entry = sim_json(cli, path, "--scenario", "strafe")
    drive = entry["drive"]
    assert (drive["kind"], drive["declared"], drive["grip_from"]) == (
        "mecanum", "rollers on the wheels' rims", "the roller links")
    assert drive["wheel_radius"] == BASE["radius"] and drive["castors"] == []
    h = pattern * round(math.sqrt(0.5), 4)
    assert drive["rollers"]["front_left_wheel_joint"]["grip_axis"] == [abs(h), -h]
    strafe = entry["scenarios"][0]
    if pattern == 1:
        assert result.exit_code == 0, result.stderr
        assert strafe["status"] == "passed"
    else:  # an O pattern, driven as mecanum_drive_controller drives: it moves right
        assert result.exit_code == 1
        assert strafe["message"].startswith("moved to the right (")


def test_omni_wheels_rollers_across_their_axle_are_not_mecanum(cli, tmp_path):
    path = tmp_path / "omni.urdf"
    path.write_text(mecanum_rings(pattern=0, **BASE))
    result, entry = sim_json(cli, path, "--scenario", "drop")
    assert entry["drive"] is None
    assert "not a drive kind mcar sim drives" in entry["why_no_drive"]
