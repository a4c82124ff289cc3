"""mcar specs' joints section: what gravity asks of each joint in its worst pose (MuJoCo's
qfrc_bias), against its declared effort, and W501 where the effort cannot hold it."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from conftest import line_of
from specs.mech_robots import G, arm, lift, steering, written

from mobile_car.check.checker import check_input
from mobile_car.load.inputs import RobotInput
from mobile_car.specs.joints import STEP_DEG, joints_section


def checked(folder: Path, name: str, text: str):
    result = check_input(RobotInput(written(folder, name, text)))
    assert result.failure is None and not result.errors, result.diagnostics
    return result


def test_an_undersized_lift_is_w501_at_its_limit_with_the_figures(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    text = lift(mass=5.0, effort=20.0)
    found = joints_section(check_input(RobotInput(written(Path("."), "lift.urdf", text))))
    gravity = found.figure("joints.lift_joint.gravity")
    assert gravity.value == pytest.approx(5.0 * G, rel=1e-9)
    assert gravity.unit == "N"
    effort = found.figure("joints.lift_joint.effort")
    line = line_of(text, "<limit ")
    assert (effort.value, effort.source) == (20.0, f"<limit effort> of joint lift_joint "
                                                   f"(lift.urdf:{line})")
    (warning,) = found.diagnostics
    assert warning.text() == (
        f"lift.urdf:{line}: warning: joint 'lift_joint': <limit effort> 20 N is under the "
        f"{5 * G:.4g} N gravity asks of it in its worst pose (lift_joint 0 m), carrying 5 kg: "
        "it cannot hold it there [W501]")


def test_a_lift_whose_effort_holds_its_load_is_not_flagged(tmp_path):
    found = joints_section(checked(tmp_path, "lift.urdf", lift(mass=5.0, effort=60.0)))
    assert found.figure("joints.lift_joint.gravity").value == pytest.approx(5.0 * G)
    assert not found.diagnostics


def test_an_arms_worst_pose_is_found_horizontal_within_the_grid_step(tmp_path):
    tilt = 0.5  # at 0 the arm points 0.5 rad up: it is horizontal with the shoulder at 0.5
    found = joints_section(checked(tmp_path, "arm.urdf", arm(tilt=tilt)))
    shoulder = found.figure("joints.shoulder.gravity")
    # the upper arm's 2 kg at 0.4 m and the forearm's 1 kg at 0.7 m, held out straight
    assert shoulder.value == pytest.approx(G * (2 * 0.4 + 1 * 0.7), rel=1e-4)
    assert shoulder.unit == "N·m"
    pose = shoulder.source.split("poses: ", 1)[1]
    shoulder_deg, elbow_deg = (float(part.split()[1].rstrip("°")) for part in pose.split(", "))
    assert abs(shoulder_deg - math.degrees(tilt)) <= STEP_DEG
    assert elbow_deg == 0.0  # of the elbow's lower, middle, upper: straight on
    elbow = found.figure("joints.elbow.gravity")
    assert elbow.value == pytest.approx(G * 1 * 0.3, rel=1e-4)
    assert abs(float(elbow.source.rsplit(" ", 1)[1].rstrip("°")) - math.degrees(tilt)) \
        <= STEP_DEG
    assert not found.diagnostics  # 100 N·m holds both


def test_a_weak_shoulder_is_w501_and_the_elbow_that_holds_is_not(tmp_path):
    found = joints_section(checked(tmp_path, "arm.urdf", arm(effort=10.0, elbow_effort=5)))
    (warning,) = found.diagnostics
    assert warning.message.startswith(
        f"joint 'shoulder': <limit effort> 10 N·m is under the {G * 1.5:.4g} N·m gravity "
        "asks of it in its worst pose (shoulder ")
    assert warning.message.endswith("elbow 0°), carrying 3 kg: it cannot hold it there")
    assert warning.text().endswith("[W501]")


def test_an_effort_of_0_on_a_steering_joint_gravity_turns_is_w501(tmp_path):
    found = joints_section(checked(tmp_path, "steer.urdf", steering(effort=0.0)))
    # 2 kg 5 cm out on an axis leaning 0.2 rad: m g d sin(lean) sin(turn), at its 0.6 limit
    expected = 2 * G * 0.05 * math.sin(0.2) * math.sin(0.6)
    assert found.figure("joints.steer_joint.gravity").value == pytest.approx(expected, rel=1e-6)
    (warning,) = found.diagnostics
    assert warning.message.startswith(f"joint 'steer_joint': <limit effort> 0 N·m is under the "
                                      f"{expected:.4g} N·m gravity asks of it")
    assert warning.rule == "W501"


def test_an_upright_steering_joint_carries_nothing_and_0_is_enough(tmp_path):
    found = joints_section(checked(tmp_path, "steer.urdf", steering(effort=0.0, kingpin=0.0)))
    assert found.figure("joints.steer_joint.gravity").value < 1e-9
    assert not found.diagnostics  # (a rounding's load is no load)


def test_a_mimic_joint_follows_its_leader_and_is_not_judged(tmp_path):
    text = arm().replace('<limit lower="-1"', '<mimic joint="shoulder" multiplier="-1"/>'
                                                '<limit lower="-1"')
    found = joints_section(checked(tmp_path, "mimic.urdf", text))
    assert found.figure("joints.elbow.gravity") is None
    assert "joint elbow follows joint shoulder (<mimic>): not judged on its own" in found.notes
    # the forearm turned back by as much as the shoulder turns it: it stays at its tilt
    # while the upper arm is horizontal (at shoulder = 0.5 rad)
    shoulder = found.figure("joints.shoulder.gravity")
    reach = 2 * 0.4 + 1 * (0.4 + 0.3 * math.cos(0.5))
    assert shoulder.value == pytest.approx(G * reach, rel=1e-3)


def test_a_continuous_joint_gravity_never_turns_is_a_note_not_figures(tmp_path):
    # a castor's swivel: upright, its wheel's mass on its axis
    text = steering(kingpin=0.0, offset=0.0).replace('type="revolute"', 'type="continuous"')
    text = text.replace('<limit lower="-0.6" upper="0.6" effort="0" velocity="1"/>', "")
    found = joints_section(checked(tmp_path, "swivel.urdf", text))
    assert found.figures == [] and found.diagnostics == []
    assert found.notes == ["joint steer_joint: continuous, no <limit effort>, and gravity "
                           "turns it in no pose (castor swivels, wheels rolling free): no "
                           "figure"]


def test_with_sims_model_the_drive_wheels_are_left_out_and_a_spring_carries_its_joint(
        tmp_path):
    from sim.robot_makers import sprung

    from mobile_car.sim.model import build_model

    result = checked(tmp_path, "sprung.urdf", sprung(mass=3.0))
    sim = build_model(result.loaded.urdf, "sprung.urdf", tmp_path, None)
    found = joints_section(result, sim)
    keys = {f.key for f in found.figures}
    assert keys == {f"joints.wheel_drop_{side}_joint.{what}" for side in ("left", "right")
                    for what in ("gravity", "effort")}
    spring = next(s for s in sim.springs if s.joint == "wheel_drop_left_joint")
    carried = found.figure("joints.wheel_drop_left_joint.gravity")
    assert carried.value == pytest.approx(spring.stiffness * abs(spring.rest - spring.reference))
    assert carried.source.startswith("sim's spring on it (wheel_drop_left_joint 0..6 mm")
    assert not found.diagnostics  # a spring carries it, not its effort of 0
    assert (f"joint wheel_drop_left_joint is a suspension: a spring carries its "
            f"{carried.value:.4g} N at rest, not its effort (its <limit effort> 0 N is under "
            "that)") in found.notes


def test_mujoco_holds_each_joint_in_its_worst_pose_with_the_figures_force(tmp_path):
    # the shoulder held horizontal with its forearm straight out: were the elbow not
    # locked, the forearm would swing down and the shoulder would carry less
    found = joints_section(checked(tmp_path, "arm.urdf", arm()))
    for key in ("joints.shoulder.gravity", "joints.elbow.gravity"):
        figure = found.figure(key)
        assert figure.proof.agrees, figure.proof.detail
        assert figure.proof.measured == pytest.approx(figure.value, rel=0.01)
        assert figure.proof.detail.startswith("MuJoCo held it in that pose for 0.3 s, the "
                                              "other joints locked, with a servo on it alone: ")
    lifted = joints_section(checked(tmp_path, "lift.urdf", lift())).figure(
        "joints.lift_joint.gravity")
    assert lifted.proof.agrees and lifted.proof.measured == pytest.approx(5 * G, rel=0.01)


def test_control_the_hold_disagrees_with_a_load_that_is_off(tmp_path):
    from mobile_car.sim.model import jointed_model
    from mobile_car.specs.joints import PoseSearch
    from mobile_car.specs.joints_proof import held_load

    result = checked(tmp_path, "lift.urdf", lift())
    model, _notes = jointed_model(result.loaded.urdf, "lift.urdf")
    search = PoseSearch(model, {})
    pose = [("lift_joint", 0.1, "prismatic")]
    assert held_load(search, "lift_joint", pose, 5 * G, "N").agrees
    proof = held_load(search, "lift_joint", pose, 5 * G * 1.02, "N")
    assert not proof.agrees and proof.measured == pytest.approx(5 * G, rel=1e-3)


LIFT_MACRO = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <!-- lift: a carriage of mass m kg on a prismatic joint, up to effort N -->
  <xacro:macro name="lift" params="parent m effort">
    <joint name="lift_joint" type="prismatic">
      <parent link="${parent}"/><child link="carriage"/>
      <axis xyz="0 0 1"/>
      <limit lower="0" upper="0.3"
             effort="${effort}" velocity="0.1"/>
    </joint>
    <link name="carriage">
      <inertial><mass value="${m}"/>
        <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
    </link>
  </xacro:macro>
</robot>
"""

LIFTER = """<?xml version="1.0"?>
<robot name="lifter" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="parts/lift.xacro"/>
  <link name="base_link"/>
  <xacro:lift parent="base_link" m="5" effort="20"/>
</robot>
"""


def test_w501_points_at_the_limit_in_the_macro_file_and_the_call(tmp_path, monkeypatch):
    (tmp_path / "parts").mkdir()
    written(tmp_path / "parts", "lift.xacro", LIFT_MACRO)
    written(tmp_path, "lifter.urdf.xacro", LIFTER)
    monkeypatch.chdir(tmp_path)
    result = check_input(RobotInput(Path("lifter.urdf.xacro")))
    (warning,) = joints_section(result).diagnostics
    assert warning.text() == (
        f"parts/lift.xacro:{line_of(LIFT_MACRO, '<limit ')}: warning: joint 'lift_joint': "
        f"<limit effort> 20 N is under the {5 * G:.4g} N gravity asks of it in its worst "
        "pose (lift_joint 0 m), carrying 5 kg: it cannot hold it there (in xacro:lift "
        "called at lifter.urdf.xacro:5) [W501]")


def test_gravity_leans_as_the_robot_rests(tmp_path):
    from mobile_car.sim.model import jointed_model
    from mobile_car.specs.joints import PoseSearch

    result = checked(tmp_path, "lift.urdf", lift())
    for lean, share in ((0.1, math.cos(0.1)), (math.pi / 2, 0.0)):
        model, _notes = jointed_model(result.loaded.urdf, "lift.urdf")
        # the root turned by ``lean`` about x (w, x, y, z): the lift's axis leans with it
        search = PoseSearch(model, {}, [math.cos(lean / 2), math.sin(lean / 2), 0, 0])
        load, _pose, _tried = search.worst("lift_joint")
        assert load == pytest.approx(5 * G * share, abs=1e-9)


def test_without_proofs_no_joint_is_held_in_mujoco(tmp_path):
    """--no-proof (and diff and sweep) ask for the figures only: the same load, no proof."""
    robot = checked(tmp_path, "lift.urdf", lift(mass=5.0, effort=60.0))
    proven, bare = joints_section(robot), joints_section(robot, proof=False)
    assert [(f.key, f.value) for f in bare.figures] == [(f.key, f.value) for f in proven.figures]
    assert proven.figure("joints.lift_joint.gravity").proof is not None
    assert all(f.proof is None for f in bare.figures)


def test_a_joint_carrying_no_declared_mass_is_a_note_not_figures_nor_w501(tmp_path):
    # ABB's and Franka's kinematic descriptions: no <inertial>, efforts of 0. MuJoCo's
    # token gram on each massless moving link used to be judged: W501 "0 N·m is under the
    # 0.04574 N·m gravity asks", and proofs failing on micro-newton-metres.
    import re

    forearm_bare = re.sub(r'(<link name="forearm">)\s*<inertial>.*?</inertial>', r"\1",
                          arm(elbow_effort=0.0), flags=re.S)
    found = joints_section(checked(tmp_path, "arm.urdf", forearm_bare))
    assert [f.key for f in found.figures] == ["joints.shoulder.gravity",
                                              "joints.shoulder.effort"]
    assert found.figure("joints.shoulder.gravity").proof.agrees
    assert not found.diagnostics
    assert ("joint elbow: no link beyond it has mass (<inertial>): not judged (gravity asks "
            "nothing the description says)") in found.notes
    bare = re.sub(r"<inertial>.*?</inertial>", "", arm(effort=0.0, elbow_effort=0.0),
                  flags=re.S)
    found = joints_section(checked(tmp_path, "bare.urdf", bare))
    assert (found.figures, found.diagnostics) == ([], [])
    assert found.notes == ["joints shoulder, elbow: no link beyond them has mass "
                           "(<inertial>): not judged (gravity asks nothing the description "
                           "says)"]
