"""A pull request's links may not make mcar read the runner's files as its own inputs.

Git commits symlinks. The attacks, found after issue 39 was merged:

* ``urdf/robot.urdf`` -> ``/proc/self/environ`` (or a key, or any file outside the
  checkout): ``mcar ci`` found it as the package's robot and wrote its bytes into
  build/robot.urdf (the environment of the CI step, its tokens with it), malformed or not;
* ``urdf/`` -> a folder outside: every file there was taken;
* ``mcar.yaml`` -> a token file: the error quoting its first value (``expected a mapping
  ..., got 'ghp_...'``) printed the token into the CI log.

Each is now refused unread. The controls put the same bytes in the package as plain
files: they reach the output or the message, so the tests can see a leak.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from hostile import PACKAGE_XML, files_holding

MARK = "MCAR-SECRET-1c4e77"
ROBOT = """<?xml version="1.0"?>
<robot name="ok"><link name="base"/></robot>
"""


def _package(root: Path) -> Path:
    """root/pkg, a package; root/outside, the runner's files (not a robot, and a robot)."""
    (root / "pkg" / "urdf").mkdir(parents=True)
    (root / "pkg" / "package.xml").write_text(PACKAGE_XML)
    (root / "outside").mkdir()
    (root / "outside" / "secret").write_text(f"root:x:0:0:{MARK}:/root:/bin/sh\n")
    (root / "outside" / "token").write_text(f"ghp_{MARK}\n")
    (root / "outside" / "robot.urdf").write_text(ROBOT.replace("ok", MARK))
    return root / "pkg"


@pytest.mark.parametrize("target", ["secret", "robot.urdf", "/proc/self/environ"])
def test_ci_does_not_take_a_robot_file_linked_out_of_the_package(run_mcar, tmp_path,
                                                                target):
    package = _package(tmp_path)
    link = package / "urdf" / "robot.urdf"
    link.symlink_to(tmp_path / "outside" / target if not target.startswith("/") else target)
    result = run_mcar("ci", cwd=package, env={"MCAR_TEST_TOKEN": MARK})
    assert result.returncode == 2, result.stdout + result.stderr
    real = link.resolve() if not target.startswith("/") else None
    line = result.stderr.splitlines()[-1]
    assert line.startswith(".: error: no robot files in this folder (looked in urdf/, "
                           "robots/, xacro/, description/ or the folder itself); skipped 1 "
                           "file that is not robots: urdf/robot.urdf (a link to ")
    assert line.endswith(f", outside {package}: not taken (name it to read it))")
    if real is not None:
        assert f"(a link to {real}, outside" in line
    assert MARK not in result.stdout + result.stderr
    assert files_holding(package, MARK.encode()) == []


def test_a_robot_folder_linked_out_of_the_package_is_not_searched(run_mcar, tmp_path):
    package = _package(tmp_path)
    (package / "urdf").rmdir()
    (package / "urdf").symlink_to(tmp_path / "outside")  # its robot.urdf names MARK
    result = run_mcar("ci", cwd=package)
    assert result.returncode == 2, result.stdout + result.stderr
    assert "skipped 3 files that are not robots: urdf/robot.urdf (a link to " \
        f"{tmp_path / 'outside' / 'robot.urdf'}, outside {package}: not taken" in result.stderr
    assert MARK not in result.stdout + result.stderr
    assert files_holding(package, MARK.encode()) == []


def test_control_the_same_bytes_in_the_package_reach_build(run_mcar, tmp_path):
    """Without the boundary (the file a plain file of the package) ci copies its bytes,
    malformed as they are, into build/robot.urdf: the tests above would see them."""
    package = _package(tmp_path)
    secret = (tmp_path / "outside" / "secret").read_bytes()
    (package / "urdf" / "robot.urdf").write_bytes(secret)
    result = run_mcar("ci", cwd=package)
    assert result.returncode == 1, result.stdout + result.stderr
    assert files_holding(package / "build", MARK.encode()) == ["robot.urdf"]


def test_a_link_inside_the_package_is_still_a_robot(run_mcar, tmp_path):
    package = _package(tmp_path)
    (package / "shared").mkdir()
    (package / "shared" / "robot.urdf").write_text(ROBOT)
    (package / "urdf" / "robot.urdf").symlink_to(package / "shared" / "robot.urdf")
    result = run_mcar("ci", cwd=package)
    assert result.returncode == 0, result.stdout + result.stderr
    assert b'<robot name="ok">' in (package / "build" / "robot.urdf").read_bytes()


@pytest.mark.parametrize("linked", [True, False])  # False: the control, a plain mcar.yaml
def test_mcar_yaml_linked_out_of_the_repository_is_not_read(run_mcar, tmp_path, linked):
    package = _package(tmp_path)
    (package / "urdf" / "robot.urdf").write_text(ROBOT)
    token = tmp_path / "outside" / "token"
    if linked:
        (package / "mcar.yaml").symlink_to(token)
    else:
        (package / "mcar.yaml").write_bytes(token.read_bytes())
    result = run_mcar("ci", cwd=package)
    assert result.returncode == 2, result.stdout + result.stderr
    if not linked:
        assert MARK in result.stderr
        return
    assert result.stderr.splitlines() == [
        f"{package / 'mcar.yaml'}: error: a link to {token}, outside {package}: not read"]
    assert MARK not in result.stdout + result.stderr


def test_mcar_yaml_linked_inside_its_repository_is_read(run_mcar, tmp_path):
    """A monorepo's packages may share one mcar.yaml: a link within the repository."""
    repository = tmp_path / "repo"
    package = _package(repository)
    (repository / ".git").mkdir()
    (package / "urdf" / "robot.urdf").write_text(ROBOT)
    (repository / "shared.yaml").write_text("robots: {exclude: ['urdf/*']}\n")
    (package / "mcar.yaml").symlink_to(repository / "shared.yaml")
    result = run_mcar("ci", "-v", cwd=package)
    assert result.returncode == 2, result.stdout + result.stderr
    assert "urdf/robot.urdf (left out by " in result.stderr


def test_links_into_the_checkout_s_git_folder_are_no_inputs(run_mcar, tmp_path):
    """Inside the package, yet the checkout's: .git/config holds a CI job's token."""
    package = _package(tmp_path)
    (package / ".git").mkdir()
    (package / ".git" / "config").write_text(f"[http]\n\textraheader = basic {MARK}\n")
    (package / "urdf" / "robot.urdf").symlink_to(package / ".git" / "config")
    result = run_mcar("ci", cwd=package)
    assert result.returncode == 2, result.stdout + result.stderr
    assert result.stderr.splitlines()[-1].endswith(
        f"urdf/robot.urdf (a link to {package}/.git/config, in a version-control folder: "
        "not taken)")
    (package / "urdf" / "robot.urdf").unlink()
    (package / "urdf" / "robot.urdf").write_text(ROBOT)
    (package / "mcar.yaml").symlink_to(package / ".git" / "config")
    result = run_mcar("ci", cwd=package)
    assert result.returncode == 2, result.stdout + result.stderr
    assert result.stderr.splitlines() == [
        f"{package / 'mcar.yaml'}: error: a link to {package}/.git/config, in a "
        "version-control folder: not read"]
    assert files_holding(package, MARK.encode()) == [".git/config"]
