"""The Gazebo helper -> mcar (docs/security.md, "The Gazebo helper"): libsdformat parses a
URDF that may come from an untrusted xacro, in C++, so what the helper answers is data,
checked field by field, within a time, memory and output bound; anything else is one
located line (E151, exit 1), never a traceback, and the helper never outlives the check.

Stand-in helpers (small Python programs named by MCAR_SDFORMAT) answer what a helper
subverted by a crafted file could: garbage, a pickle, forged fields, a flood, silence, a
crash. The real helper is held to its side: data on stdin only, JSON only on stdout,
nothing written under HOME."""

from __future__ import annotations

import json
import os
import pickle
import signal
import subprocess
import sys
import time

import pytest
from conftest import REPO

from mobile_car.errors import GazeboError, GazeboUnavailable
from mobile_car.gazebo.helper import run_helper

ROBOT = b'<robot name="r"><link name="a"><inertial><mass value="1"/><inertia ixx="1" ' \
        b'ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link></robot>'


def answer(**changes) -> dict:
    """A well-formed answer about ROBOT, with ``changes`` applied."""
    document = {"interface": 2, "sdformat": "12.3.0", "errors": [], "console_errors": [],
                "warnings": [], "lumped": [], "dropped": [], "model": {
                    "name": "r", "canonical_link": "", "joints": [], "frames": [],
                    "links": [{"name": "a", "mass": 1, "centre_of_mass": [0, 0, 0],
                               "inertia": [1, 1, 1, 0, 0, 0], "pose": [0, 0, 0, 0, 0, 0],
                               "collisions": 0, "visuals": 0, "sensors": 0}]}}
    document.update(changes)
    return document


def stand_in(tmp_path, body: str) -> str:
    """An executable helper whose stdout is what ``body`` (Python) writes to ``out``."""
    path = tmp_path / "stand-in"
    path.write_text(f"#!{sys.executable}\nimport os, sys, time\n"
                    "data = sys.stdin.buffer.read()\nout = sys.stdout.buffer\n" + body)
    path.chmod(0o755)
    return str(path)


def refused(tmp_path, monkeypatch, body: str, **env) -> str:
    monkeypatch.setenv("MCAR_SDFORMAT", stand_in(tmp_path, body))
    for name, value in env.items():
        monkeypatch.setenv(name, value)
    started = time.monotonic()
    with pytest.raises(GazeboError) as caught:
        run_helper(ROBOT, "robot.urdf")
    assert time.monotonic() - started < 10
    assert caught.value.file == "robot.urdf"
    return caught.value.message


def test_the_stand_in_answer_is_accepted_as_it_is(tmp_path, monkeypatch):
    """The control: the forgeries below differ from this only where they say."""
    monkeypatch.setenv("MCAR_SDFORMAT", stand_in(
        tmp_path, f"out.write({json.dumps(json.dumps(answer()))}.encode())"))
    report = run_helper(ROBOT, "robot.urdf")
    assert report.model.links[0].name == "a" and report.model.mass == 1.0


def test_a_pickle_is_never_unpickled(tmp_path, monkeypatch):
    marker = tmp_path / "ran"

    class Payload:
        def __reduce__(self):
            return os.system, (f"touch {marker}",)

    data = pickle.dumps(Payload())
    message = refused(tmp_path, monkeypatch, f"out.write({data!r})")
    assert message.startswith("the Gazebo helper sent back something that is not a report "
                              "(not JSON: ")
    assert not marker.exists()
    pickle.loads(data)  # the control: the payload does run a command when unpickled
    assert marker.exists()


VERSION = "a libsdformat version that is not one (a digit, then at most 63 of letters, " \
          "digits and .~+-)"


def forged(**changes) -> bytes:
    return json.dumps(answer(**changes)).encode()


@pytest.mark.parametrize("data, reason", [
    (b"\xff\xfe garbage", "not JSON: UnicodeDecodeError"),
    (b"[1, 2]", "not a JSON object"),
    (forged().replace(b'"mass": 1', b'"mass": NaN'), "not JSON: ValueError"),
    (b'{"interface": 1, "interface": 1}', "not JSON: ValueError"),
    (b"[" * 200_000 + b"]" * 200_000, "not JSON: RecursionError"),
    (forged(extra=True), "answer has the wrong fields (extra)"),
    (forged(errors="none"), "answer: 'errors' is not of its type"),
    (forged(sdformat="1" * 100), VERSION),
    (forged(sdformat="12.3.0\x1b[2J"), VERSION),  # printed in every report: no escapes
    (forged(sdformat=""), VERSION),
    (forged(console_errors=[{"where": "x"}]), "console_errors[0] has the wrong fields (text)"),
    (json.dumps({key: value for key, value in answer().items()
                 if key != "console_errors"}).encode(),  # format 1's fields, numbered 2
     "answer has the wrong fields (console_errors)"),
    (forged(warnings=[{"where": "x", "text": "a\0"}]),
     "warnings[0] is not a string of at most 65536 characters without NUL"),
    (forged(lumped=[{"link": "a"}]), "lumped[0] has the wrong fields (into)"),
], ids=["bytes", "list", "nan", "twice", "deep", "extra", "type", "long", "escape",
        "no-version", "console", "format-1-fields", "nul", "field"])
def test_a_forged_answer_is_refused_saying_why(tmp_path, monkeypatch, data, reason):
    (tmp_path / "answer").write_bytes(data)
    message = refused(tmp_path, monkeypatch, f"out.write(open({str(tmp_path / 'answer')!r}, "
                                             "'rb').read())")
    assert message == f"the Gazebo helper sent back something that is not a report ({reason})"


def test_forged_numbers_counts_and_joint_types_are_refused(tmp_path, monkeypatch):
    link = answer()["model"]["links"][0]
    for key, value, reason in (("collisions", "3", "links[0]: 'collisions' is not of its "
                                                   "type"),
                               ("mass", True, "links[0]: 'mass' is not of its type"),
                               ("collisions", -1, "links[0] is not a count"),
                               ("pose", [0, 0, 0], "links[0].pose is not 6 numbers"),
                               ("inertia", [1e400] * 6, "links[0].inertia is not a number")):
        forged = json.loads(json.dumps(answer()))
        forged["model"]["links"][0] = {**link, key: value}
        text = json.dumps(forged).replace("Infinity", "1e400")
        message = refused(tmp_path, monkeypatch, f"out.write({text.encode()!r})")
        assert reason in message, (key, message)
    forged = answer()
    forged["model"]["joints"] = [{"name": "j", "type": "__import__('os')", "parent": "a",
                                  "child": "a"}]
    message = refused(tmp_path, monkeypatch, f"out.write({json.dumps(forged).encode()!r})")
    assert "joints[0] has no joint type libsdformat knows" in message


def test_a_flood_is_cut_at_the_output_bound(tmp_path, monkeypatch):
    body = "chunk = b'x' * (1 << 20)\nwhile True:\n    out.write(chunk)\n"
    message = refused(tmp_path, monkeypatch, body, MCAR_GAZEBO_OUTPUT_MB="2")
    assert message == "the Gazebo helper sent more than MCAR_GAZEBO_OUTPUT_MB=2"


def test_a_silent_helper_is_killed_at_the_time_bound(tmp_path, monkeypatch):
    pid_file = tmp_path / "pid"
    body = f"open({str(pid_file)!r}, 'w').write(str(os.getpid()))\ntime.sleep(600)\n"
    started = time.monotonic()
    message = refused(tmp_path, monkeypatch, body, MCAR_GAZEBO_TIMEOUT="1")
    assert time.monotonic() - started < 5
    assert message == "libsdformat took longer than MCAR_GAZEBO_TIMEOUT=1 s"
    with pytest.raises(ProcessLookupError):  # killed and reaped: no process left
        os.kill(int(pid_file.read_text()), 0)


def test_a_crash_is_one_line_with_its_stderr_escaped(tmp_path, monkeypatch):
    body = ("sys.stderr.write('free(): invalid pointer \\x1b]0;pwned\\x07\\n')\n"
            f"sys.stderr.flush()\nos.kill(os.getpid(), {int(signal.SIGSEGV)})\n")
    message = refused(tmp_path, monkeypatch, body)
    assert message == ("the Gazebo helper was ended by SIGSEGV (libsdformat crashed, or "
                       "needed more than MCAR_GAZEBO_MEMORY_MB=4096): free(): invalid pointer "
                       "\\x1b]0;pwned\\x07")


def test_memory_is_bounded(tmp_path, monkeypatch):
    message = refused(tmp_path, monkeypatch, "hog = bytearray(2 << 30)\n",
                      MCAR_GAZEBO_MEMORY_MB="256")
    assert message.startswith("the Gazebo helper failed (exit status 1): Traceback")
    assert message.endswith("MemoryError")


def test_the_helper_gets_data_and_an_empty_environment(tmp_path, monkeypatch):
    seen = tmp_path / "seen.json"
    body = (f"import json\njson.dump({{'env': sorted(os.environ), 'cwd': os.getcwd(), "
            f"'stdin': data.decode()}}, open({str(seen)!r}, 'w'))\n"
            f"out.write({json.dumps(answer()).encode()!r})\n")
    monkeypatch.setenv("MCAR_SDFORMAT", stand_in(tmp_path, body))
    monkeypatch.setenv("HOME", str(tmp_path))
    run_helper(ROBOT, "robot.urdf")
    got = json.loads(seen.read_text())
    assert set(got["env"]) <= {"PATH", "LC_ALL", "LD_LIBRARY_PATH", "LC_CTYPE"}
    assert "HOME" not in got["env"]
    assert got["cwd"] == "/"
    assert got["stdin"] == ROBOT.decode()


@pytest.mark.parametrize("interface", [1, 3])
def test_a_helper_of_another_format_is_an_environment_error(tmp_path, monkeypatch, cli,
                                                            interface):
    """Format 1 (before issue 41) put what libsdformat printed among its errors: a helper
    built then is refused, not half-read."""
    old = {key: value for key, value in answer(interface=interface).items()
           if key != "console_errors"}
    monkeypatch.setenv("MCAR_SDFORMAT", stand_in(
        tmp_path, f"out.write({json.dumps(old).encode()!r})"))
    with pytest.raises(GazeboUnavailable, match=f"answers in format {interface}, and this "
                                                "mcar reads format 2: rebuild it"):
        run_helper(ROBOT, "robot.urdf")
    result = cli("check", "--gazebo", REPO / "urdf" / "laser" / "test_laser.urdf.xacro")
    assert result.exit_code == 2


def test_no_model_without_an_error_still_fails_the_check(tmp_path, run_mcar):
    """A helper (or a libsdformat) that returns no error but no model either: printed
    errors are only notes, so the missing model itself is the error."""
    robot = tmp_path / "robot.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    silent = answer(model=None, console_errors=[{"where": "urdfdom", "text": "odd"}])
    result = run_mcar("check", "--gazebo", robot, cwd=tmp_path, env={
        "MCAR_SDFORMAT": stand_in(tmp_path, f"out.write({json.dumps(silent).encode()!r})")})
    assert result.returncode == 1
    assert result.stderr.splitlines() == [
        "robot.urdf:1: error: libsdformat 12.3.0 made no model of the robot and returned no "
        "error [E151]",
        "robot.urdf:1: note: libsdformat 12.3.0 printed an error it did not return, and "
        "loaded the robot past it: odd (urdfdom) [N404]",
        "mcar check: 1 error, 0 warnings in 1 file"]
    # the control: the same answer with the model passes
    loaded = answer(console_errors=[{"where": "urdfdom", "text": "odd"}])
    result = run_mcar("check", "-q", "--gazebo", robot, cwd=tmp_path, env={
        "MCAR_SDFORMAT": stand_in(tmp_path, f"out.write({json.dumps(loaded).encode()!r})")})
    assert result.returncode == 0 and result.stderr == "", result.stderr


def test_check_gazebo_reports_a_broken_helper_as_one_located_line(tmp_path, monkeypatch,
                                                                  run_mcar):
    robot = tmp_path / "robot.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    result = run_mcar("check", "-q", "--gazebo", robot, cwd=tmp_path,
                      env={"MCAR_SDFORMAT": stand_in(tmp_path, "out.write(b'\\x80garbage')")})
    assert result.returncode == 1
    assert result.stderr.splitlines() == [
        "robot.urdf:1: error: the Gazebo helper sent back something that is not a report "
        "(not JSON: UnicodeDecodeError) [E151]", "mcar check: 1 error, 0 warnings in 1 file"]


def test_the_real_helper_answers_json_only_and_writes_nothing_under_home(gazebo_helper,
                                                                         tmp_path):
    broken = b'<robot name="x"><link name="a"/><joint name="j" type="fixed"><parent ' \
             b'link="a"/><child link="nowhere"/></joint></robot>'
    done = subprocess.run([str(gazebo_helper)], input=broken, capture_output=True,
                          timeout=60, env={"HOME": str(tmp_path), "PATH": "/usr/bin:/bin"},
                          cwd=tmp_path)
    assert done.returncode == 0
    document = json.loads(done.stdout)  # urdfdom's complaint did not land on stdout
    assert document["model"] is None
    assert {"where": "urdfdom", "text": "Failed to build tree: child link [nowhere] of joint "
                                        "[j] not found"} in document["console_errors"]
    # the verdict is libsdformat's Errors list only: each with its code, none printed
    assert document["errors"] and all(error["where"].startswith("error code ")
                                      for error in document["errors"])
    assert list(tmp_path.iterdir()) == []  # no ~/.sdformat/sdformat.log
    assert done.stderr == b""


@pytest.mark.parametrize("signum, code", [(signal.SIGTERM, 143), (signal.SIGINT, 130)])
def test_a_signal_mid_conversion_ends_mcar_and_the_helper(tmp_path, mcar_bin, signum, code):
    robot = tmp_path / "robot.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    pid_file = tmp_path / "pid"
    helper = stand_in(tmp_path, f"open({str(pid_file)!r}, 'w').write(str(os.getpid()))\n"
                                "time.sleep(600)\n")
    env = dict(os.environ, MCAR_SDFORMAT=helper)
    process = subprocess.Popen([str(mcar_bin), "check", "--gazebo", str(robot)], env=env,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 30
    while not pid_file.exists() or not pid_file.read_text():
        assert time.monotonic() < deadline and process.poll() is None
        time.sleep(0.05)
    started = time.monotonic()
    process.send_signal(signum)
    _out, err = process.communicate(timeout=10)
    assert time.monotonic() - started < 2
    assert process.returncode == code
    assert "Traceback" not in err
    with pytest.raises(ProcessLookupError):
        os.kill(int(pid_file.read_text()), 0)
