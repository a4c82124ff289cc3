"""A file URI is confined as the tools mcar hands the robot to read it, not only as mcar
reads it.

mcar reads ``file://`` and ``package://`` names as they are written; RViz's
resource_retriever (curl) %-decodes them, takes ``file://localhost/`` as ``file:///``, and
fetches any other URL (``file:/x``, ``FILE:///x``, ``gopher://``) that mcar took for a
relative file name.
So ``file://PKG/meshes/%2e%2e/%2e%2e/outside/secret.stl`` was, to mcar, a missing file
inside the package (W207, no W215), and ``mcar view --rviz`` opened RViz on it, which
read the file outside. Each form is now W215 at its line; the control reads every one of
them with curl, as RViz does, and gets the secret.
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest
from hostile import PACKAGE_XML

MARK = "MCAR-SECRET-93b0d2"
# (line in the robot, URI): {pkg} the package, {outside} the folder beside it.
URIS = [
    (4, "file://localhost{outside}/secret.stl"),
    (5, "file://{pkg}/meshes/%2e%2e/%2e%2e/outside/secret.stl"),
    (6, "file://{pkg}/meshes/..%2f..%2foutside/secret.stl"),
    (7, "package://atk/%2e%2e/outside/secret.stl"),
    (8, "package://atk/meshes/..%2F..%2Foutside/secret.stl"),
    (9, "file://127.0.0.1{outside}/secret.stl"),
    (10, "file:{outside}/secret.stl"),
    (11, "FILE://{outside}/secret.stl"),
]
# A URL of any other scheme: curl sends the request (here to a local Redis).
GOPHER = "gopher://127.0.0.1:6379/_FLUSHALL%0d%0a.stl"


def _robot(root: Path) -> Path:
    package, outside = root / "pkg", root / "outside"
    (package / "urdf").mkdir(parents=True)
    (package / "meshes").mkdir()
    outside.mkdir()
    (outside / "secret.stl").write_text(f"solid {MARK}\nendsolid\n")
    (package / "package.xml").write_text(PACKAGE_XML)
    visuals = "".join(f'    <visual><geometry><mesh filename="{uri}"/></geometry></visual>\n'
                      for _, uri in URIS)
    robot = package / "urdf" / "robot.urdf"
    robot.write_text('<?xml version="1.0"?>\n<robot name="atk">\n  <link name="base">\n'
                     + visuals.format(pkg=package, outside=outside) + "  </link>\n</robot>\n")
    return robot


@pytest.fixture
def robot(tmp_path) -> Path:
    return _robot(tmp_path)


def test_every_decoded_form_is_refused_at_its_line(run_mcar, robot):
    result = run_mcar("check", "urdf/robot.urdf", cwd=robot.parents[1])
    assert result.returncode == 0, result.stderr
    refused = [line for line in result.stderr.splitlines() if line.endswith("[W215]")]
    assert [int(line.split(":")[1]) for line in refused] == [line for line, _ in URIS]
    assert refused[3].startswith("urdf/robot.urdf:7: warning: mesh "
                                 "'package://atk/%2e%2e/outside/secret.stl' is outside the "
                                 "folders a robot may name files in: ")
    assert "W207" not in result.stderr  # no longer a missing file inside
    assert refused[-1] == (f"urdf/robot.urdf:11: warning: mesh 'FILE://{robot.parents[2]}"
                           "/outside/secret.stl' is a URL mcar does not read, which RViz "
                           "would fetch (through curl); not read, drawn as a magenta box "
                           "[W215]")


def test_a_url_of_any_other_scheme_is_refused(run_mcar, robot):
    robot.write_text(robot.read_text().replace(
        "  </link>", f'    <visual><geometry><mesh filename="{GOPHER}"/></geometry>'
                     "</visual>\n  </link>"))
    result = run_mcar("check", "urdf/robot.urdf", cwd=robot.parents[1])
    assert result.returncode == 0, result.stderr
    assert f"urdf/robot.urdf:12: warning: mesh '{GOPHER}' is a URL mcar does not read, " \
        "which RViz would fetch (through curl); not read, drawn as a magenta box [W215]" \
        in result.stderr.splitlines()


def test_a_name_with_an_escape_inside_the_package_is_still_allowed(run_mcar, tmp_path):
    """A %-escape that stays inside is no attack: a missing file, said as before (W207)."""
    robot = _robot(tmp_path)
    robot.write_text(robot.read_text().replace("%2e%2e/%2e%2e/outside/", "%2e/"))
    result = run_mcar("check", "urdf/robot.urdf", cwd=robot.parents[1])
    assert result.returncode == 0, result.stderr
    line_5 = [line for line in result.stderr.splitlines()
              if line.startswith("urdf/robot.urdf:5:")]
    assert len(line_5) == 1 and line_5[0].endswith("[W207]"), result.stderr


@pytest.mark.skipif(shutil.which("curl") is None, reason="curl is not installed")
@pytest.mark.parametrize("line, uri", URIS)
def test_control_curl_reads_the_secret_through_each_form(robot, line, uri):
    """RViz reads meshes through resource_retriever, which hands file:// to curl (and
    package:// as file:// under the package): each form reaches the secret."""
    package = robot.parents[1]
    url = uri.format(pkg=package, outside=robot.parents[2] / "outside")
    if url.startswith("package://atk/"):  # resource_retriever: the package's folder
        url = f"file://{package}/" + url[len("package://atk/"):]
    read = subprocess.run(["curl", "-sS", url], capture_output=True, text=True, timeout=30)
    assert MARK in read.stdout, read.stderr


@pytest.mark.skipif(shutil.which("roslaunch") is None, reason="ROS 1's roslaunch is not "
                    "installed")
def test_rviz_is_not_opened_on_a_decoded_escape(run_mcar, robot):
    result = run_mcar("view", "--rviz", "urdf/robot.urdf", cwd=robot.parents[1])
    assert result.returncode == 1
    assert result.stderr.splitlines()[-1] == (
        "urdf/robot.urdf: error: not opened in RViz: 8 files outside the folders a robot "
        "may name files in (W215 above), which RViz would read")
    assert result.stdout == ""  # roslaunch never ran
