"""Lists of numbers that miscount each other out: a URDF urdfdom refuses must not pass.

`mcar check` reads a link's (and only a link's) lists of three numbers together
(``Reporter.triples``): the texts joined, split once and counted, the count being that of
all of them. An attacker who knows it writes one list short and another long in the same
link, ``xyz="0 0"`` beside ``rpy="0 0 1.5708 0"``: six numbers between them, as two
sound lists have. urdfdom reads each list alone and refuses the link's first such list
(the link is left half read in the model every ROS tool loads): mcar must say so. The
defence is the proof of the quick reading (``Reporter.numbers_confirmed``: every text
read together has its two spaces), which sends the document to urdfdom's reading, list
by list. The control: with that proof waved through, the same file is passed clean.
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from mobile_car.check import checker
from mobile_car.check import context as check_context
from mobile_car.packages.search import PackageSearch

ROBOT = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base_link"/>
  <link name="upper">
    <inertial>
      <origin xyz="0 0 0.1" rpy="0 0 0"/>
      <mass value="1.5"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.012" iyz="0" izz="0.004"/>
    </inertial>
    <visual>
      <origin xyz="{xyz}" rpy="{rpy}"/>
      <geometry><box size="0.1 0.1 0.3"/></geometry>
    </visual>
    <collision>
      <origin xyz="0.1 0.1 0.1" rpy="0.1 0.1 0.1"/>
      <geometry><box size="{size}"/></geometry>
    </collision>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base_link"/><child link="upper"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1.57" upper="1.57" effort="10" velocity="2"/>
  </joint>
</robot>
"""
ORIGIN_LINE = 11  # the visual's <origin> in ROBOT
# Each shifts the numbers after it by one place, so that every one still lands where a
# sound number could be (sizes positive, angles small) and the link looks plain.
ATTACKS = {
    "xyz short, rpy long": dict(xyz="0 0", rpy="0 0 1.5708 0", size="0.1 0.1 0.3"),
    "rpy long, the box of the next body short": dict(xyz="0 0 0", rpy="0 0 1.5708 0.1",
                                                     size="0.1 0.3"),
}
SOUND = dict(xyz="0 0 0", rpy="0 0 1.5708", size="0.1 0.1 0.3")


def _write(tmp_path: Path, numbers: dict) -> Path:
    path = tmp_path / "arm.urdf"
    path.write_text(ROBOT.format(**numbers))
    return path


def _in_process(path: Path) -> list[str]:
    result = checker.check_urdf_data(path.read_bytes(), str(path), base=path.parent,
                                     search=PackageSearch(origin=path))
    return [d.rule for d in result.diagnostics]


@pytest.mark.parametrize("name", sorted(ATTACKS))
def test_lists_that_miscount_each_other_out_are_refused(name, tmp_path, run_mcar):
    path = _write(tmp_path, ATTACKS[name])
    result = run_mcar("check", str(path))
    assert result.returncode == 1, result.stdout + result.stderr
    errors = [line for line in result.stderr.splitlines() if ": error: " in line]
    assert len(errors) == 2 and all(line.endswith("[E114]") for line in errors), errors
    assert errors[0].startswith(f"{path}:{ORIGIN_LINE}: error: ")
    assert "mcar check: 2 errors" in result.stderr


@pytest.mark.skipif(shutil.which("check_urdf") is None, reason="check_urdf not installed")
@pytest.mark.parametrize("name", sorted(ATTACKS))
def test_check_urdf_refuses_them_too(name, tmp_path):
    """What the refusal is judged against: urdfdom reads each list alone and refuses the
    first (it says so and stops reading the link; check_urdf still exits 0)."""
    path = _write(tmp_path, ATTACKS[name])
    result = subprocess.run(["check_urdf", str(path)], capture_output=True, text=True,
                            timeout=60)
    assert "but 3 expected while parsing vector" in result.stderr, result.stderr


@pytest.mark.parametrize("name", sorted(ATTACKS))
def test_control_without_the_proof_they_would_pass(name, tmp_path, monkeypatch):
    path = _write(tmp_path, ATTACKS[name])
    assert _in_process(path) == ["E114", "E114"]
    monkeypatch.setattr(check_context, "_CLEAN", set())
    monkeypatch.setattr(check_context.Reporter, "numbers_confirmed", lambda self: True)
    assert _in_process(path) == []  # read together, the six numbers looked sound


def test_the_sound_robot_passes(tmp_path, run_mcar):
    result = run_mcar("check", str(_write(tmp_path, SOUND)))
    assert result.returncode == 0, result.stderr
    assert "Successfully Parsed" in result.stdout and "error" not in result.stderr
