"""A path or argument -> display.launch's robot_description command (docs/security.md, "The
robot -> RViz"): roslaunch splits a param's command with shlex, and on main the launch wrote
model:= between single quotes, so a robot file named ``evil.urdf.xacro' '' --no-sandbox '-o``
beside a hostile evil.urdf.xacro made ``roslaunch ... display.launch model:=<it>`` (and
``mcar view --rviz <it>``) run ``mcar build evil.urdf.xacro --no-sandbox``: its xacro ran
programs. Now every value reaches robot_description as one hex word that the script decodes
and checks: whatever the characters, mcar build gets exactly the argv meant, with the
sandbox on, and args:= passes NAME:=VALUE, --set and --config only.

Checked with ``roslaunch --dump-params`` (no master: roslaunch runs the param commands and
prints the parameters), once with a stand-in mcar first on PATH that records its argv, once
with the real mcar and a hostile xacro that would create a marker file."""

from __future__ import annotations

import json
import os
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import MCAR, REPO

# The hostile xacro: a comprehension gets round xacro's guard to os.system (the sandbox
# test corpus's run_program.xacro), touching MARKER.
HOSTILE = """<robot name="evil" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="a"/>
  <link name="${{[g['system']('touch {marker}') for g in [c.__init__.__globals__ for x in
    [()] for c in x.__class__.__base__.__subclasses__() if c.__name__ == '_wrap_close']][0]}}"/>
</robot>
"""
RECORDED = '<robot name="recorded"><link name="a"/></robot>'
# main's line: roslaunch splits what $(arg ...) put into it.
OLD_COMMAND = "{script} '{model}' '{config}' {args}"
QUOTED_NAME = "evil.urdf.xacro' '' --no-sandbox '-o"


def no_roslaunch() -> str | None:
    absent = [tool for tool in ("roslaunch", "rospack") if shutil.which(tool) is None]
    return f"ROS 1's {' and '.join(absent)} not installed (make rviz installs it)" \
        if absent else None


@pytest.fixture
def ros_env(tmp_path) -> dict:
    if no_roslaunch():
        pytest.skip(no_roslaunch())
    env = {name: value for name, value in os.environ.items() if not name.startswith("ROS")}
    env.update(ROS_HOME=str(tmp_path / "ros-home"), ROS_LOG_DIR=str(tmp_path / "ros-log"),
               ROS_PACKAGE_PATH=str(REPO), HOME=str(tmp_path))
    return env


@pytest.fixture
def recorder(tmp_path) -> tuple[Path, Path]:
    """(a folder holding a stand-in ``mcar`` that appends its argv to the log, the log)."""
    folder = tmp_path / "recorder"
    folder.mkdir()
    log = tmp_path / "argv.log"
    (folder / "mcar").write_text(
        f"#!{sys.executable}\nimport json, sys\n"
        f"open({str(log)!r}, 'a').write(json.dumps(sys.argv[1:]) + '\\n')\n"
        f"print({RECORDED!r})\n")
    (folder / "mcar").chmod(0o755)
    return folder, log


def recorded(log: Path) -> list[list[str]]:
    return [json.loads(line) for line in log.read_text().splitlines()] if log.exists() else []


def dump(launch_argv: list[str], env: dict, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(["roslaunch", "--dump-params", *launch_argv], env=env, cwd=cwd,
                          capture_output=True, text=True, timeout=60)


@pytest.fixture
def hostile(tmp_path) -> dict:
    """The evil xacro under a plain name and under names that were attacks."""
    folder = tmp_path / "robots"
    folder.mkdir()
    marker = tmp_path / "MARKER"
    text = HOSTILE.format(marker=marker)
    names = {"plain": "evil.urdf.xacro", "quoted": QUOTED_NAME, "dash": "-o.urdf.xacro",
             "odd": "a b`id`\t$HOME\\ \"c\".urdf.xacro"}
    for name in names.values():
        (folder / name).write_text(text)
    return {"folder": folder, "marker": marker, **{k: folder / v for k, v in names.items()}}


def test_the_old_launch_line_split_a_quoted_name_into_options(hostile):
    """The control: main's command line, split as roslaunch splits it."""
    words = shlex.split(OLD_COMMAND.format(script="robot_description",
                                           model=hostile["quoted"], config="", args=""))
    assert words[1:] == [str(hostile["plain"]), "", "--no-sandbox", "-o", ""]
    # and so mcar build ran the xacro unconfined: the hostile file does what it says
    done = subprocess.run([str(MCAR), "build", "--no-sandbox", str(hostile["plain"]),
                           "-o", os.devnull], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and hostile["marker"].exists()


@pytest.mark.parametrize("model_key, config, args, argv_tail", [
    # roslaunch drops an argument with a second ":=": NAME:=VALUE is written NAME%3A=VALUE
    ("quoted", "{folder}/c' --no-sandbox '.yaml", "prefix%3A=left_ --set wheel_radius=40%20mm "
     "--config /a%20b/it's.yaml --set=x=%25 n%3A=`id`\tm%3A=a%0Ab",
     ["--config={folder}/c' --no-sandbox '.yaml", "prefix:=left_", "--set=wheel_radius=40 mm",
      "--config=/a b/it's.yaml", "--set=x=%", "n:=`id`", "m:=a\nb", "-o", "-", "--",
      "{model}"]),
    ("dash", "-c.yaml", "", ["--config=-c.yaml", "-o", "-", "--", "./{model_name}"]),
], ids=["quotes-spaces-backticks-newlines", "leading-dash"])
def test_display_launch_gives_mcar_build_exactly_the_argv_meant(
        ros_env, recorder, hostile, tmp_path, model_key, config, args, argv_tail):
    folder, log = recorder
    model = hostile[model_key]
    given = {"model": str(model) if model_key != "dash" else model.name,
             "config": config.format(folder=hostile["folder"]), "args": args}
    env = dict(ros_env, PATH=f"{folder}:/usr/bin:/bin")
    done = dump([str(REPO / "launch" / "display.launch"),
                 *(f"{name}:={value}" for name, value in given.items())], env,
                cwd=hostile["folder"])
    assert done.returncode == 0, done.stdout + done.stderr
    assert recorded(log) == [["build", *(word.format(
        folder=hostile["folder"], model=model, model_name=model.name) for word in argv_tail)]]
    assert done.stdout.startswith(f"/robot_description: '{RECORDED}")


def refusal(word: str) -> str:
    return (f"robot_description: args: '{word}' is not NAME:=VALUE, --set NAME=VALUE or "
            "--config FILE\n")


def test_args_refuses_an_option_through_roslaunch(ros_env, recorder, hostile):
    folder, log = recorder
    env = dict(ros_env, PATH=f"{folder}:/usr/bin:/bin")
    done = dump([str(REPO / "launch" / "display.launch"), f"model:={hostile['plain']}",
                 "args:=--no-sandbox"], env, cwd=hostile["folder"])
    assert refusal("--no-sandbox") in done.stderr
    assert "/robot_description:" not in done.stdout  # roslaunch gave up (its status is 0)
    assert recorded(log) == []  # mcar never ran


def encoded(value: str) -> str:
    return "x" + value.encode("utf-8").hex()


@pytest.mark.parametrize("args, word", [
    ("x%3A=1 -o /tmp/elsewhere", "-o"),
    ("%2D%2Dno-sandbox", "--no-sandbox"),  # decoded, then checked
    ("--set 'a b'", "b'"),  # no quoting: %20 is a space
    ("--package-path /", "--package-path"),
    ("-x:=1", "-x:=1"),
    ("x:=1 --config", None),
])
def test_args_refuses_anything_but_settings_naming_the_word(recorder, hostile, args, word):
    """The script as display.launch runs it: one line, exit 2, mcar never run."""
    folder, log = recorder
    done = subprocess.run([str(REPO / "scripts" / "robot_description"),
                           encoded(str(hostile["plain"])), encoded(""), encoded(args)],
                          env={"PATH": f"{folder}:/usr/bin:/bin"}, capture_output=True,
                          text=True, timeout=30)
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr == (refusal(word) if word else
                           "robot_description: args: --config needs a value after it\n")
    assert recorded(log) == []


@pytest.mark.parametrize("words", [
    ["x", "x"],  # one missing
    ["--no-sandbox", "x", "x"],  # not encoded
    ["x2d2", "x", "x"],  # odd length
    ["x", "x", "x"],  # no model
])
def test_the_script_takes_only_what_the_launch_encodes(recorder, words):
    folder, log = recorder
    done = subprocess.run([str(REPO / "scripts" / "robot_description"), *words],
                          env={"PATH": f"{folder}:/usr/bin:/bin"}, capture_output=True,
                          text=True, timeout=30)
    assert done.returncode == 2 and done.stdout == ""
    assert len(done.stderr.splitlines()) == 1
    assert done.stderr.startswith("robot_description: ")
    assert recorded(log) == []


def test_a_substitution_in_a_value_is_refused_by_roslaunch_itself(ros_env, recorder,
                                                                  hostile):
    folder, log = recorder
    env = dict(ros_env, PATH=f"{folder}:/usr/bin:/bin")
    done = dump([str(REPO / "launch" / "display.launch"), f"model:={hostile['plain']}$(id)"],
                env, cwd=hostile["folder"])
    assert "Unknown substitution command [id]" in done.stderr
    assert "/robot_description:" not in done.stdout
    assert recorded(log) == []


def test_the_real_mcar_builds_a_quoted_name_with_the_sandbox_on(ros_env, hostile):
    env = dict(ros_env, PATH=f"{MCAR.parent}:/usr/bin:/bin")
    done = dump([str(REPO / "launch" / "display.launch"), f"model:={hostile['quoted']}"],
                env, cwd=hostile["folder"])
    assert "error: the xacro sandbox forbids running programs (os.system)" in done.stderr
    assert "/robot_description:" not in done.stdout  # robot_description failed
    assert not hostile["marker"].exists()


def test_the_seed_command_still_resolves_find_in_model(ros_env, recorder, tmp_path):
    folder, log = recorder
    env = dict(ros_env, PATH=f"{folder}:/usr/bin:/bin")
    done = dump([str(REPO / "launch" / "display.launch"),
                 "model:=$(find mobile_car_description)/urdf/mobile_robot.xacro"], env,
                cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert recorded(log) == [["build", "-o", "-", "--",
                              str(REPO / "urdf" / "mobile_robot.xacro")]]


def test_the_launch_mcar_init_writes_quotes_too(ros_env, recorder, hostile, tmp_path):
    subprocess.run([str(MCAR), "init", "demo_description"], cwd=tmp_path, check=True,
                   capture_output=True, timeout=60)
    folder, log = recorder
    env = dict(ros_env, PATH=f"{folder}:/usr/bin:/bin",
               ROS_PACKAGE_PATH=str(tmp_path / "demo_description"))
    done = dump(["demo_description", "display.launch", f"model:={hostile['quoted']}",
                 "args:=--set base_width=22%20cm"], env, cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert recorded(log) == [["build", "--set=base_width=22 cm", "-o", "-", "--",
                              str(hostile["quoted"])]]


def test_mcar_view_rvizs_command_line_passes_exactly_what_it_means(ros_env, recorder,
                                                                   hostile, tmp_path):
    from mobile_car.load.inputs import RobotInput
    from mobile_car.view import rviz

    folder, log = recorder
    build_args = ["--set", "wheel_radius=40 mm", "--config", str(hostile["folder"] / "a b'%.yaml"),
                  "prefix:=left -o"]
    launch = rviz.plan("/usr/bin/roslaunch", RobotInput(hostile["odd"]), "a",
                       None, build_args, [], tmp_path)
    env = dict(launch.env, PATH=f"{folder}:/usr/bin:/bin", ROS_HOME=ros_env["ROS_HOME"],
               ROS_LOG_DIR=ros_env["ROS_LOG_DIR"])
    done = dump(launch.argv[1:], env, cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert recorded(log) == [["build", "--set=wheel_radius=40 mm",
                              f"--config={hostile['folder']}/a b'%.yaml", "prefix:=left -o",
                              "-o", "-", "--", str(hostile["odd"])]]


@pytest.mark.parametrize("name", ["new\nline.urdf.xacro", "a:=b.urdf.xacro",
                                  "trailing.urdf.xacro "])
def test_mcar_view_rviz_refuses_a_path_roslaunch_would_drop(tmp_path, name):
    """roslaunch ignores model:= with a newline or a second := (the launch then shows its
    default robot) and strips white space: mcar says so instead of showing another robot."""
    from mobile_car.errors import UsageError
    from mobile_car.load.inputs import RobotInput
    from mobile_car.view import rviz

    robot = tmp_path / name
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    with pytest.raises(UsageError, match="roslaunch cannot pass this path on whole"):
        rviz.plan("/usr/bin/roslaunch", RobotInput(robot), "a", None, [], [], tmp_path)


def test_rvizs_configuration_reaches_it_as_one_word(ros_env):
    """The rviz node's args, resolved by roslaunch's own substitution code and split as
    roslaunch splits a node's args (shlex): one word, whatever the path."""
    from xml.etree import ElementTree

    node = ElementTree.parse(REPO / "launch" / "display.launch").getroot().find(
        "node[@name='rviz']")
    hostile_path = "/tmp/a b' -f x'\"`id`$HOME.rviz"
    program = ("import json, shlex, sys\n"
               "from roslaunch.substitution_args import resolve_args\n"
               "value = resolve_args(sys.argv[1], {'arg': {'rvizconfig_given': sys.argv[2]}})\n"
               "print(json.dumps(shlex.split(value)))\n")
    done = subprocess.run(["/usr/bin/python3", "-c", program, node.get("args"), hostile_path],
                          env=ros_env, capture_output=True, text=True, timeout=30)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout) == [f"--display-config={hostile_path}"]
    # the control: main's args="-d $(arg rvizconfig)" gave RViz an option of the path's
    assert shlex.split("-d /tmp/a b -f x.rviz") == ["-d", "/tmp/a", "b", "-f", "x.rviz"]
