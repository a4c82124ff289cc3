"""A tab or line break in a number's attribute, as urdfdom 3.0 reads it (TinyXML keeps it,
lxml turns it into a space): urdfdom splits a list on spaces and reads each piece with
``istream >> double``, which skips whitespace before a number and wants nothing after it.
Unitree's dexterous hands (dex2_5/Left_Hand.urdf) break a line after an inertia value:
one error, not two (the second said "between numbers" of a single number; the line is
where its tag ends, as libxml2 gives it); a line break before a number is read by
urdfdom, and by mcar (an error before)."""

from __future__ import annotations

import subprocess

import pytest

ROBOT = """<robot name="r">
  <link name="base"/>
  <link name="arm">
    <inertial><mass value="0.0075"/>
      <inertia ixx="0.0004" ixy="0" ixz="{ixz}" iyy="0.0004" iyz="0" izz="0.0004"/>
    </inertial>
  </link>
  <joint name="j" type="fixed">
    <origin xyz="{xyz}"/>
    <parent link="base"/>
    <child link="arm"/>
  </joint>
</robot>
"""


def _check(run_mcar, tmp_path, **values):
    path = tmp_path / "r.urdf"
    path.write_text(ROBOT.format(**{"ixz": "0", "xyz": "0 0 0.1", **values}))
    return run_mcar("check", "-q", "r.urdf", cwd=tmp_path), path


@pytest.mark.parametrize("values", [{"ixz": "\n0"}, {"ixz": "\t0"}, {"xyz": "\n0 0 0.1"},
                                    {"xyz": "0 0 \n0.1"}], ids=repr)
def test_whitespace_before_a_number_is_read(run_mcar, tmp_path, check_urdf, values):
    result, path = _check(run_mcar, tmp_path, **values)
    theirs = subprocess.run([check_urdf, str(path)], capture_output=True, text=True)
    assert (theirs.returncode, theirs.stderr) == (0, "")
    assert (result.returncode, result.stderr) == (0, "")


def test_a_line_break_after_a_single_number_is_one_error(run_mcar, tmp_path, check_urdf):
    result, path = _check(run_mcar, tmp_path, ixz="-0.00000000003261\n")
    theirs = subprocess.run([check_urdf, str(path)], capture_output=True, text=True)
    assert "inertia element ixz is not a valid double" in theirs.stderr
    assert result.returncode == 1
    assert result.stderr.splitlines() == [
        "r.urdf:6: error: link 'arm': <inertia ixz=\"-0.00000000003261 \"> is not a number "
        "urdfdom can read [E114]",
        "mcar check: 1 error, 0 warnings in 1 file"]


@pytest.mark.parametrize("xyz", ["0 0\n0.1", "0 0 0.1\n", "0\t0 0.1", "0 \n 0 0.1"],
                         ids=repr)
def test_a_tab_or_line_break_after_a_number_in_a_list_is_an_error(run_mcar, tmp_path,
                                                                  check_urdf, xyz):
    result, path = _check(run_mcar, tmp_path, xyz=xyz)
    theirs = subprocess.run([check_urdf, str(path)], capture_output=True, text=True)
    assert theirs.returncode != 0
    assert result.returncode == 1
    assert "xyz=\"...\" has a tab or line break between numbers; urdfdom separates numbers " \
           "by spaces only [E114]" in result.stderr
