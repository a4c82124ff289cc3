"""A drive or spin that falls short names its likely cause from what was measured while
the robot drove (mobile_car/sim/causes.py): a castor the floor drags, motors at their
effort limit, tyres that slip, a robot that tipped onto its body. Each fault is put into
a package `mcar init` wrote, through config.xacro's own dimensions (--set), and the
message checked against the numbers it reports; the tipping robot is made at test time
(tests/sim/robot_makers.py)."""

from __future__ import annotations

import json
import re

import pytest
from conftest import mcar_process
from sim.robot_makers import tips_back

ROBOT = "urdf/bot_description.urdf.xacro"
NUMBER = r"([\d.]+)"


@pytest.fixture(scope="module")
def package(mcar_bin, tmp_path_factory):
    folder = tmp_path_factory.mktemp("causes")
    made = mcar_process("init", "bot_description", cwd=folder)
    assert made.returncode == 0, made.stderr
    return folder / "bot_description"


@pytest.fixture
def sim(mcar_bin, package):
    """`mcar sim ROBOT --set NAME=VALUE --format json`: (exit code, {scenario: message})."""

    def run(*settings):
        args = [a for s in settings for a in ("--set", s)]
        done = mcar_process("sim", ROBOT, *args, "--format", "json", cwd=package, timeout=300)
        (robot,) = json.loads(done.stdout)["files"]
        return done.returncode, {s["name"]: s["message"] for s in robot["scenarios"]}

    return run


def _rolled_and_moved(message: str) -> tuple[float, float, float]:
    rolled, commanded, moved = re.search(
        rf"the wheels rolled {NUMBER} m of the {NUMBER} m commanded and the robot "
        rf"(?:moved|turned them through an arc of) {NUMBER} m", message).groups()
    return float(rolled), float(commanded), float(moved)


def test_a_sound_robot_names_no_cause(sim):
    code, messages = sim()
    assert code == 0
    assert messages == {"drop": "ok", "drive": "ok", "spin": "ok"}


def test_a_dragging_castor_is_named_with_the_force_it_drags_with(sim):
    """castor_friction 1: the ball slides instead of rolling. The floor holds it back
    with mu × the load it carries, about a quarter of the robot's weight here."""
    code, messages = sim("castor_friction=1")
    assert code == 1
    for scenario, verb in (("drive", "drove"), ("spin", "turned")):
        message = messages[scenario]
        assert message.startswith(f"{verb} short; likely cause: a dragging castor: the floor "
                                  "holds castor_link back with "), message
        force, ratio, normal, share = map(float, re.search(
            rf"back with {NUMBER} N \({NUMBER} × the {NUMBER} N it carries, {NUMBER}% of "
            "the robot's weight\\), where a free-rolling castor \\(mu 0.01\\) holds back "
            "under 1%", message).groups())
        assert ratio == pytest.approx(force / normal, abs=0.01)
        assert 0.9 <= ratio <= 1.0  # Coulomb: the friction force is mu × the normal force
        assert share > 2  # over CASTOR_DRAG_SHARE
        rolled, commanded, moved = _rolled_and_moved(message)
        assert moved < rolled <= commanded
    assert "effort limit" not in messages["drive"]  # the motors were never at their limit


def test_a_dragging_castor_of_a_little_friction_is_not_a_fault(sim):
    code, messages = sim("castor_friction=0.05")
    assert code == 0 and messages["drive"] == "ok"


def test_motors_at_their_effort_limit_are_named_with_the_time_at_it(sim):
    code, messages = sim("wheel_effort=0.01")
    assert code == 1
    message = messages["drive"]
    assert message.startswith(
        "drove short; likely cause: the motors' effort limit (wheel_left_joint 0.01 N·m, "
        "wheel_right_joint 0.01 N·m): at it for "), message
    at, watched = map(float, re.search(rf"at it for {NUMBER} s of {NUMBER} s", message).groups())
    assert watched == pytest.approx(3.0) and 0.3 <= at <= watched
    rolled, commanded, moved = _rolled_and_moved(message)
    short = float(re.search(rf"\({NUMBER}% short of the command\)", message)[1])
    assert short == pytest.approx(100 * (1 - rolled / commanded), abs=0.1)
    assert short > 10
    assert moved == pytest.approx(rolled, rel=0.01)  # the tyres grip: they do not slip
    assert "dragging castor" not in message


def test_slipping_wheels_are_named_with_how_much_they_slipped(sim):
    """wheel_friction 0.05, its range's lowest: the tyres spin faster than the car goes."""
    code, messages = sim("wheel_friction=0.05")
    assert code == 1
    message = messages["drive"]
    assert message.startswith("drove short; likely cause: wheel slip: "), message
    rolled, commanded, moved = _rolled_and_moved(message)
    assert rolled == pytest.approx(commanded, rel=0.01)  # the motors kept their speed
    slip = float(re.search(rf"\({NUMBER}% less than its wheels rolled\)", message)[1])
    assert slip == pytest.approx(100 * (1 - moved / rolled), abs=0.1)
    assert slip > 1
    assert message.split("; distance error")[0].endswith(
        "the motors below their effort limit; the tyres' friction (mu 0.05) cannot pass "
        "the drive force to the floor")


def test_an_ackermann_cars_effort_limit_names_its_driven_rear_wheels(run_mcar, tmp_path):
    assert run_mcar("init", "car", "--drive", "ackermann", cwd=tmp_path).returncode == 0
    done = run_mcar("sim", "urdf/car.urdf.xacro", "--set", "wheel_effort=0.01",
                    cwd=tmp_path / "car", timeout=300)
    assert done.returncode == 1
    (line,) = [x for x in done.stderr.splitlines() if "drive failed" in x]
    assert line.startswith(
        "urdf/car.urdf.xacro: error: drive failed: drove short; likely cause: the motors' "
        "effort limit (wheel_rear_left_joint 0.01 N·m, wheel_rear_right_joint 0.01 N·m): "
        "at it for "), line
    rolled, commanded, moved = _rolled_and_moved(line)
    assert rolled < 0.9 * commanded and moved == pytest.approx(rolled, rel=0.01)


@pytest.fixture(scope="module")
def balance(tmp_path_factory):
    """(exit code, drive's message) of TurtleBot 4's balance (:func:`tips_back`): its
    centre of mass 2 mm ahead of its axle, no castor behind; and the same 30 mm ahead."""
    from click.testing import CliRunner
    from mobile_car.cli.main import main
    folder, runs = tmp_path_factory.mktemp("balance"), {}
    for name, ahead in (("tips", 0.002), ("stands", 0.03)):
        path = folder / f"{name}.urdf"
        path.write_text(tips_back(ahead=ahead))
        result = CliRunner().invoke(main, ["sim", str(path), "--scenario", "drive",
                                           "--format", "json"], catch_exceptions=False)
        (robot,) = json.loads(result.stdout)["files"]
        runs[name] = result.exit_code, robot["scenarios"][0]["message"]
    return runs


def test_a_robot_that_tips_back_onto_its_body_says_so_not_wheel_slip(balance):
    code, message = balance["tips"]
    assert code == 1
    head = "drove short; likely cause: tipped back onto base_link: pitch -"
    assert message.startswith(head), message
    pitch = float(message[len(head):].split(" deg")[0])
    assert 3 <= pitch <= 6  # the box's back edge, 10 mm up 0.15 m behind the axle: 3.8 deg
    assert (f"({pitch:.2f} deg off the pose it rests in, bound 3 deg), on the floor "
            in message)
    # 2.51 kg of body 2 mm ahead and a 10 g castor 0.12 m ahead, of 3 kg: 2.07 mm.
    assert " s after the wheels started; its centre of mass 2.1 mm ahead of its axle, " \
        in message, message
    assert "wheel slip" not in message


def test_the_same_robot_with_its_weight_further_forward_drives(balance):
    """The control: 30 mm ahead of its axle, the ramp does not tip it."""
    assert balance["stands"] == (0, "ok")
