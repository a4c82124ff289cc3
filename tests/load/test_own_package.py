"""A package made by hand: from its root and from a subfolder, build, ci and render work
on that package only, say so on stderr, and write under its root (issue 12)."""

from __future__ import annotations

import pytest

HEAD = '<robot name="{}" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
BOX = '<visual><geometry><box size="0.2 0.1 0.05"/></geometry></visual>'


@pytest.fixture
def package(tmp_path):
    root = tmp_path / "my_robot"
    (root / "urdf" / "arm").mkdir(parents=True)
    (root / "package.xml").write_text(
        '<?xml version="1.0"?><package format="3"><name>my_robot</name><version>0.1.0'
        '</version><description>d</description><maintainer email="a@b.c">a</maintainer>'
        "<license>MIT</license></package>")
    (root / "urdf" / "arm" / "arm.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="arm" '
        f'params="parent"><link name="arm_link">{BOX}</link><joint name="arm_joint" '
        'type="fixed"><parent link="${parent}"/><child link="arm_link"/></joint>'
        "</xacro:macro></robot>")
    (root / "urdf" / "my_robot.urdf.xacro").write_text(
        HEAD.format("my_robot") + '<xacro:include filename="$(find my_robot)/urdf/arm/'
        f'arm.xacro"/><link name="base_link">{BOX}</link><xacro:arm parent="base_link"/>'
        "</robot>")
    return root


@pytest.mark.parametrize("where", [".", "urdf/arm"])
def test_commands_work_on_the_package_you_stand_in(run_mcar, package, where, quiet_renderer):
    cwd = package / where
    said = f"mcar: package my_robot ({package})"
    built = run_mcar("build", cwd=cwd)
    assert built.returncode == 0, built.stderr
    assert built.stderr.splitlines()[0] == said
    assert "1 of 1 files built" in built.stderr  # its one robot, not the mobile car's
    assert (package / "build" / "my_robot.urdf").is_file()
    ci = run_mcar("ci", *quiet_renderer, cwd=cwd)
    assert ci.returncode == 0, ci.stderr
    assert ci.stderr.splitlines()[0] == said
    assert "mcar ci: 1 of 1 files passed" in ci.stderr
    render = run_mcar("render", *quiet_renderer, "--force", cwd=cwd)
    assert render.returncode == 0, render.stderr
    assert render.stderr.splitlines()[0] == said
    assert (package / "renders" / "my_robot.png").is_file()
    assert not (cwd / "build").exists() or cwd == package


def test_a_subfolder_is_mirrored_as_the_package_is(run_mcar, package, tmp_path):
    (package / "urdf" / "arm" / "test_arm.urdf.xacro").write_text(
        HEAD.format("test_arm") + '<xacro:include filename="$(find my_robot)/urdf/arm/'
        'arm.xacro"/><link name="base_link"/><xacro:arm parent="base_link"/></robot>')
    named = run_mcar("build", "urdf/arm", cwd=package)
    assert named.returncode == 0, named.stderr
    assert (package / "build" / "arm" / "test_arm.urdf").is_file()
    whole = run_mcar("build", cwd=package / "urdf" / "arm")
    assert whole.returncode == 0, whole.stderr
    assert sorted(p.relative_to(package / "build").as_posix()
                  for p in (package / "build").rglob("*.urdf")) == \
        ["arm/test_arm.urdf", "my_robot.urdf"]


def test_robots_kept_in_robots_folder_are_found(run_mcar, package):
    (package / "robots").mkdir()
    (package / "robots" / "two_arms.urdf.xacro").write_text(
        HEAD.format("two_arms") + '<xacro:include filename="$(find my_robot)/urdf/arm/'
        'arm.xacro"/><link name="base_link"/><xacro:arm parent="base_link"/></robot>')
    built = run_mcar("build", cwd=package)
    assert built.returncode == 0, built.stderr
    assert sorted(p.relative_to(package / "build").as_posix()
                  for p in (package / "build").rglob("*.urdf")) == \
        ["robots/two_arms.urdf", "urdf/my_robot.urdf"]


def test_a_workspace_is_every_package_in_it(run_mcar, package, tmp_path):
    result = run_mcar("check", "-q", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stderr.splitlines()[0] == f"mcar: workspace {tmp_path}: 1 package (my_robot)"
