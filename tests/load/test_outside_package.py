"""Outside any package, a command with no INPUT does not fall back to the mobile car bundled
with mcar: a CI job started in the wrong folder went green on mcar's own robot. It says
what to do (one line, exit 2, nothing written); --bundled asks for the bundled car."""

from __future__ import annotations

import pytest


def expected(folder) -> str:
    return (f"mcar: error: no robot package here: {folder} has no package.xml above it and "
            "no packages in it or its src/; name a robot file or folder, or give --bundled "
            "for the mobile car bundled with mcar\n")


@pytest.mark.parametrize("args", [("build",), ("check",), ("tree",), ("render",), ("config",),
                                  ("ci",), ("sim",), ("check", "wheel"),
                                  ("sweep", "--vary", "wheel_radius=0.03..0.04:2"),
                                  ("view", "--no-browser", "--port", "0")])
def test_no_input_outside_a_package_is_an_error_that_says_what_to_do(run_mcar, tmp_path, args):
    result = run_mcar(*args, cwd=tmp_path)
    assert (result.returncode, result.stdout, result.stderr) == (2, "", expected(tmp_path))
    assert list(tmp_path.iterdir()) == []  # no build/, no renders/


def test_bundled_asks_for_the_bundled_car(run_mcar, tmp_path):
    result = run_mcar("check", "--bundled", "-q", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    first = result.stderr.splitlines()[0]
    assert first.startswith("mcar: package mobile_car_description (") and \
        first.endswith(", bundled with mcar)")


def test_bundled_changes_nothing_inside_a_package(run_mcar, repo):
    plain = run_mcar("tree", "mobile_robot.xacro", cwd=repo / "urdf")
    bundled = run_mcar("tree", "--bundled", "mobile_robot.xacro", cwd=repo / "urdf")
    assert plain.returncode == bundled.returncode == 0
    assert plain.stdout == bundled.stdout
