"""A package's CMakeLists.txt may not lead mcar out of the package.

mcar reads a package's ``install()`` rules to find where ``$(find PKG)/DIR/x`` comes from
when the checkout has no such path (docs/build.md). A pull request writes those rules: an
absolute source (``install(FILES /home/runner/.ssh/id_rsa DESTINATION share/atk/parts)``),
a source folder that is a link out of the package, or ``..``. None of them may map the
include to a file outside the package; the planted secret must appear in no output. The
control lays the same files inside the package: they are read, so the test can see them.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from hostile import PACKAGE_XML

MARK = "MCAR-SECRET-7c41aa"
ROBOT = """<?xml version="1.0"?>
<robot name="atk" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find atk)/{inner}"/>
  <link name="base"/>
  <xacro:stolen/>
</robot>
"""
PART = f"""<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="stolen"><link name="{MARK}"/></xacro:macro>
</robot>
"""


def _package(tmp_path: Path, how: str) -> tuple[Path, Path]:
    """The hostile package ``atk`` (its robot file) and the folder outside it holding the
    secret part; ``how`` is the way its rules reach out, or "inside" for the control."""
    package, outside = tmp_path / "atk", tmp_path / "runner"
    (package / "urdf").mkdir(parents=True)
    outside.mkdir()
    (outside / "part.xacro").write_text(PART)
    (package / "package.xml").write_text(PACKAGE_XML)
    rules, inner = {
        "absolute": (f"install(FILES {outside}/part.xacro DESTINATION share/atk/parts)",
                     "parts/part.xacro"),
        "link": ("install(DIRECTORY description/control DESTINATION share/${PROJECT_NAME})",
                 "control/part.xacro"),
        "dotdot": ("install(DIRECTORY ../runner/ DESTINATION share/${PROJECT_NAME}/parts)",
                   "parts/part.xacro"),
        "inside": ("install(DIRECTORY description/control DESTINATION share/${PROJECT_NAME})",
                   "control/part.xacro"),
    }[how]
    (package / "description").mkdir()
    if how == "link":
        os.symlink(outside, package / "description" / "control")
    if how == "inside":
        (package / "description" / "control").mkdir()
        (package / "description" / "control" / "part.xacro").write_text(PART)
    (package / "CMakeLists.txt").write_text(f"project(atk)\n{rules}\n")
    robot = package / "urdf" / "robot.urdf.xacro"
    robot.write_text(ROBOT.format(inner=inner))
    return robot, outside


@pytest.mark.parametrize("how", ["absolute", "link", "dotdot"])
def test_install_rules_reaching_out_of_the_package_map_nothing(how, tmp_path, run_mcar):
    robot, _outside = _package(tmp_path, how)
    out = tmp_path / "out.urdf"
    result = run_mcar("build", robot, "-o", out, cwd=tmp_path)
    assert result.returncode == 1, result.stderr
    first = result.stderr.splitlines()[0]
    assert first == ("atk/urdf/robot.urdf.xacro:3: error: cannot read "
                     f"atk/{'control' if how == 'link' else 'parts'}/part.xacro: "
                     "No such file or directory")
    assert MARK not in result.stdout + result.stderr
    assert not out.exists()


def test_the_same_part_inside_the_package_is_read(tmp_path, run_mcar):
    robot, _outside = _package(tmp_path, "inside")
    out = tmp_path / "out.urdf"
    result = run_mcar("build", robot, "-o", out, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert f'<link name="{MARK}"/>' in out.read_text()


@pytest.mark.parametrize("how", ["absolute", "link", "dotdot"])
def test_the_rules_themselves_map_nothing_outside(how, tmp_path):
    """The mapping refuses on its own, not only through Landlock (which a kernel may lack,
    and which allows every package root)."""
    from mobile_car.packages.install_layout import source_of

    robot, _outside = _package(tmp_path, how)
    inner = robot.read_text().split("$(find atk)/")[1].split('"')[0]
    assert source_of(tmp_path / "atk", "atk", inner) is None
    control, _ = _package(tmp_path / "control", "inside")
    assert source_of(control.parents[1], "atk", "control/part.xacro") == \
        control.parents[1] / "description" / "control" / "part.xacro"
