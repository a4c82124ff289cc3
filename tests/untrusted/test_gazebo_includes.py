"""A robot -> libsdformat's file lookups (docs/security.md, "The Gazebo helper"): an
``<include>`` in a ``<gazebo>`` block makes libsdformat read the model folder or file it
names (a path, file://, model://) into the robot; on main a model folder outside the package
ended up in ``mcar build --format sdf`` and ``mcar export --to sdf``, and an include of
/etc/passwd said it exists. Now it is refused, located, before the helper starts (E152), and
the helper called directly with such a robot cannot read the planted file: its seccomp
filter refuses every file lookup once libsdformat is set up."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest
from conftest import REPO

from mobile_car.errors import GazeboError
from mobile_car.gazebo.helper import run_helper

PLANTED = "PLANTED_MODEL_NAME"
INERTIAL = ('<inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" '
            'izz="1"/></inertial>')
HELPER_RAN = "helper-ran"


@pytest.fixture
def outside(tmp_path) -> Path:
    """A model folder and a secret file outside any package, as an attacker plants them."""
    model = tmp_path / "elsewhere" / "planted_model"
    model.mkdir(parents=True)
    (model / "model.config").write_text(
        '<?xml version="1.0"?><model><name>planted</name><sdf version="1.6">model.sdf</sdf>'
        '</model>')
    (model / "model.sdf").write_text(
        f'<?xml version="1.0"?><sdf version="1.6"><model name="{PLANTED}"><link '
        'name="planted_link"/></model></sdf>')
    (tmp_path / "elsewhere" / "secret.txt").write_text("SECRET-CONTENT\n")
    return model


def robot_with(uri: str, include: str = "include") -> str:
    return (f'<robot name="r">\n  <link name="base_footprint"/>\n  <joint name="j" '
            f'type="fixed"><parent link="base_footprint"/><child link="base"/></joint>\n'
            f'  <link name="base">{INERTIAL}</link>\n  <gazebo>\n'
            f'    <{include}><uri>{uri}</uri></{include.split()[0]}>\n  </gazebo>\n</robot>\n')


def uris(model: Path) -> dict[str, str]:
    return {"folder": str(model), "file-uri": f"file://{model}",
            "passwd": "/etc/passwd", "model-uri": "model://planted_model",
            "secret": str(model.parent / "secret.txt")}


def recording_helper(tmp_path) -> str:
    """A stand-in helper that leaves a file behind when it is started at all."""
    import sys

    path = tmp_path / "stand-in"
    path.write_text(f"#!{sys.executable}\nopen({str(tmp_path / HELPER_RAN)!r}, 'w')\n")
    path.chmod(0o755)
    return str(path)


@pytest.mark.parametrize("kind", ["folder", "file-uri", "passwd", "model-uri", "secret"])
def test_check_build_and_export_refuse_an_include_before_the_helper_starts(
        cli, monkeypatch, tmp_path, outside, kind):
    uri = uris(outside)[kind]
    robot = tmp_path / "robot.urdf"
    robot.write_text(robot_with(uri))
    monkeypatch.setenv("MCAR_SDFORMAT", recording_helper(tmp_path))
    monkeypatch.setenv("SDF_PATH", str(outside.parent))  # where model:// would look
    line = (f"robot.urdf:6: error: <include> of {uri}: libsdformat would read that file or "
            "model folder from disk into the robot, and mcar's Gazebo helper reads no file; "
            "include the model from the Gazebo world or launch file instead [E152]")
    monkeypatch.chdir(tmp_path)
    checked = cli("check", "-q", "--gazebo", "robot.urdf")
    assert checked.exit_code == 1
    assert checked.stderr.splitlines() == [line, "mcar check: 1 error, 0 warnings in 1 file"]
    out = tmp_path / "robot.sdf"
    out.write_text("earlier")
    built = cli("build", "--format", "sdf", "robot.urdf", "-o", out)
    assert (built.exit_code, built.stderr.splitlines()) == (1, [line])
    assert out.read_text() == "earlier"
    exported = cli("export", "robot.urdf", "--to", "sdf", "-o", tmp_path / "export")
    assert (exported.exit_code, exported.stderr.splitlines()) == (1, [line])
    assert not (tmp_path / "export").exists()
    assert not (tmp_path / HELPER_RAN).exists()
    # Control: the same robot without the include is given to the helper.
    robot.write_text(robot_with(uri).replace("include>", "not_an_include>"))
    cli("check", "-q", "--gazebo", "robot.urdf")
    assert (tmp_path / HELPER_RAN).exists()


def test_an_include_written_in_a_macro_is_located_at_its_source_line(cli, monkeypatch,
                                                                     tmp_path, outside):
    monkeypatch.setenv("MCAR_SDFORMAT", recording_helper(tmp_path))
    robot = tmp_path / "robot.urdf.xacro"
    robot.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:macro name="extra" params="where">\n'
        '    <gazebo><include><uri>${where}</uri></include></gazebo>\n'
        '  </xacro:macro>\n'
        f'  <link name="base_footprint"/>\n  <joint name="j" type="fixed"><parent '
        f'link="base_footprint"/><child link="base"/></joint>\n  <link name="base">{INERTIAL}'
        f'</link>\n  <xacro:extra where="{outside}"/>\n</robot>\n')
    monkeypatch.chdir(tmp_path)
    result = cli("build", "--format", "sdf", "robot.urdf.xacro")
    assert result.exit_code == 1
    assert result.stderr.startswith(f"robot.urdf.xacro:3: error: <include> of {outside}: ")
    assert result.stderr.rstrip().endswith("(in xacro:extra called at robot.urdf.xacro:8) "
                                           "[E152]")
    assert PLANTED not in result.stdout
    assert not (tmp_path / HELPER_RAN).exists()


@pytest.mark.parametrize("urdf", [
    # tinyxml2 knows no namespaces: to libsdformat this is an <include>
    '<robot name="r"><link name="a"/><gazebo><include xmlns="urn:x"><uri>/etc/passwd</uri>'
    '</include></gazebo></robot>',
    # not XML lxml reads (a second root), which tinyxml2 might still read in part
    '<robot name="r"><link name="a"/><gazebo>\n<include><uri>/etc/passwd</uri></include>'
    '</gazebo></robot><robot/>',
], ids=["default-namespace", "not-well-formed"])
def test_the_last_guard_refuses_an_include_whoever_calls_the_helper(tmp_path, monkeypatch,
                                                                    urdf):
    monkeypatch.setenv("MCAR_SDFORMAT", recording_helper(tmp_path))
    with pytest.raises(GazeboError, match=r"\[E152\]$") as caught:
        run_helper(urdf.encode(), "robot.urdf")
    assert caught.value.file == "robot.urdf"
    assert not (tmp_path / HELPER_RAN).exists()


def test_ci_fails_the_robot_without_asking_the_helper(run_mcar, package_copy, tmp_path,
                                                      outside):
    gazebo_file = package_copy / "urdf" / "mobile_robot.gazebo.xacro"
    text = gazebo_file.read_text()
    at = text.rindex("</robot>")
    gazebo_file.write_text(text[:at] + f"  <gazebo><include><uri>{outside}</uri></include>"
                           "</gazebo>\n" + text[at:])
    line = text[:at].count("\n") + 1
    result = run_mcar("ci", package_copy / "urdf" / "mobile_robot.xacro", "--no-render",
                      "--no-sim", "--build-dir", tmp_path / "out",
                      env={"MCAR_SDFORMAT": recording_helper(tmp_path)}, cwd=tmp_path,
                      timeout=300)
    assert result.returncode == 1, result.stderr
    assert f"mobile_robot.gazebo.xacro:{line}: error: <include> of {outside}: " \
           in result.stderr
    assert "[E152]" in result.stderr and "Traceback" not in result.stderr
    assert not (tmp_path / HELPER_RAN).exists()


def helper_answer(helper: Path, urdf: str, home: Path) -> dict:
    done = subprocess.run([str(helper), "--sdf"], input=urdf.encode(), capture_output=True,
                          timeout=60, env={"HOME": str(home), "PATH": "/usr/bin:/bin"},
                          cwd="/")
    assert done.returncode == 0, done.stderr
    assert done.stderr == b""  # confined, and not noisy about it
    return json.loads(done.stdout)


def test_the_helper_called_directly_cannot_read_a_planted_model_or_file(gazebo_helper,
                                                                       tmp_path, outside):
    home = tmp_path / "home"
    home.mkdir()
    texts = {}
    for kind, uri in uris(outside).items():
        document = helper_answer(gazebo_helper, robot_with(uri), home)
        assert PLANTED not in document["sdf"] and "SECRET" not in json.dumps(document)
        errors = [e["text"] for e in document["errors"]]
        # libsdformat did follow the include (the control: it would have read the file),
        # and found nothing
        assert f"Unable to find uri[{uri}]" in errors, errors
        texts[kind] = [t.replace(uri, "URI") for t in errors]
    # A planted folder, a planted file, /etc/passwd and a path that is not there all look
    # the same from inside: not even whether the file exists gets out.
    missing = helper_answer(gazebo_helper, robot_with(str(tmp_path / "absent")), home)
    absent = [e["text"].replace(str(tmp_path / "absent"), "URI") for e in missing["errors"]]
    assert all(errors == absent for errors in texts.values())
    assert list(home.iterdir()) == []  # no ~/.sdformat/sdformat.log either
    # and the confined helper still answers a normal robot
    car = helper_answer(gazebo_helper, robot_with("x").replace("<gazebo>", "<!--").replace(
        "</gazebo>", "-->"), home)
    assert car["errors"] == []
    assert [link["name"] for link in car["model"]["links"]] == ["base_footprint"]


def test_the_kernel_refuses_the_lookups_libsdformat_makes(gazebo_helper, tmp_path, outside):
    """The control, seen by strace: libsdformat does look the planted model up (on main it
    then read it into the SDF), and every lookup fails with EPERM."""
    import shutil

    if not shutil.which("strace"):
        pytest.skip("strace is not installed")
    trace = tmp_path / "trace"
    done = subprocess.run(["strace", "-f", "-o", str(trace), "-e", "trace=%file,prctl",
                           str(gazebo_helper), "--sdf"], input=robot_with(str(outside)).encode(),
                          capture_output=True, timeout=60, env={"PATH": "/usr/bin:/bin"})
    if done.returncode != 0 and b"ptrace" in done.stderr:
        pytest.skip(f"strace cannot trace here: {done.stderr.decode()[:200]}")
    assert PLANTED not in done.stdout.decode()
    after = trace.read_text().split("PR_SET_SECCOMP", 1)[1]
    lookups = [line for line in after.splitlines() if f'"{outside}' in line]
    assert lookups, after  # it tried
    assert all(line.endswith("= -1 EPERM (Operation not permitted)") for line in lookups), \
        lookups


def test_the_confined_helper_converts_the_bundled_car_as_before(cli, gazebo, tmp_path):
    out = tmp_path / "car.sdf"
    result = cli("build", "--format", "sdf", REPO / "urdf" / "mobile_robot.xacro", "-o", out)
    assert result.exit_code == 0, result.stderr
    assert out.read_text().count("<link name=") == 3
