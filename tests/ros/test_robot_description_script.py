"""scripts/robot_description, which display.launch runs for robot_description: it finds
an mcar (PATH's, else the package's own .venv, as after `make demo` without activating
it) and passes the launch's config and args to `mcar build`, each given as display.launch
encodes it (one word: "x" and the value's bytes in hex). Needs no ROS."""

from __future__ import annotations

import os
import shutil
import subprocess

import pytest
from conftest import MCAR

# A PATH with no mcar on it, as in a shell where no virtualenv is active.
BARE_PATH = "/usr/bin:/bin"
NAME = "demo_description"


@pytest.fixture
def package(tmp_path):
    if shutil.which("mcar", path=BARE_PATH):
        pytest.skip(f"an mcar is installed on {BARE_PATH}: the fallback cannot be seen")
    subprocess.run([str(MCAR), "init", NAME], cwd=tmp_path, check=True, capture_output=True)
    return tmp_path / NAME


def _encoded(value: str) -> str:
    """A value as display.launch hands it to the script."""
    return "x" + value.encode("utf-8").hex()


def _describe(package, config="", args="", path=BARE_PATH):
    env = {key: value for key, value in os.environ.items() if not key.startswith("ROS_")}
    env["PATH"] = path
    model = str(package / "urdf" / f"{NAME}.urdf.xacro")
    return subprocess.run([str(package / "scripts" / "robot_description"),
                           *(_encoded(value) for value in (model, config, args))],
                          env=env, capture_output=True, text=True, cwd=package)


def _built(package, *args):
    return subprocess.run([str(MCAR), "build", str(package / "urdf" / f"{NAME}.urdf.xacro"),
                           *args, "-o", "-"], capture_output=True, text=True, check=True).stdout


def test_the_packages_own_venv_when_none_is_active(package):
    (package / ".venv" / "bin").mkdir(parents=True)
    (package / ".venv" / "bin" / "mcar").symlink_to(MCAR)  # what `make demo` leaves there
    described = _describe(package)
    assert described.returncode == 0, described.stderr
    assert described.stdout == _built(package)


def test_the_mcar_on_path_first_with_config_and_args(package, tmp_path):
    overrides = tmp_path / "long.yaml"
    overrides.write_text("base_length: 45cm\n")
    described = _describe(package, str(overrides), "--set base_width=22cm",
                          path=f"{MCAR.parent}:{BARE_PATH}")
    assert described.returncode == 0, described.stderr
    assert described.stdout == _built(package, "--config", str(overrides),
                                      "--set", "base_width=22cm")
    assert '<box size="0.45 0.22 0.05"/>' in described.stdout


def test_no_mcar_anywhere_is_one_line_and_exit_2(package):
    described = _describe(package)
    assert described.returncode == 2 and described.stdout == ""
    assert described.stderr == (
        f"robot_description: mcar is neither on PATH nor in {package}/.venv: "
        "activate the virtualenv it is installed in, or pip install mcar\n")


def test_a_bad_robot_is_mcars_own_error(package):
    (package / "urdf" / f"{NAME}.urdf.xacro").write_text("<robot name='x'><link></robot>")
    described = _describe(package, path=f"{MCAR.parent}:{BARE_PATH}")
    assert described.returncode == 1 and described.stdout == ""
    assert f"{NAME}.urdf.xacro:1" in described.stderr and "error:" in described.stderr
