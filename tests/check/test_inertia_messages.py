"""W204's message gives the principal moments a user can act on: a moment within round-off
of 0 is 0 (Unitree B1's base in example-robot-data's b1-z1.urdf, every entry 1e-6, was
"principal moments -4.235e-22, 4.235e-22, 3e-06")."""

from __future__ import annotations

RANK_ONE = """<robot name="r">
  <link name="base">
    <inertial>
      <mass value="1e-6"/>
      <inertia ixx="1e-6" ixy="1e-6" ixz="1e-6" iyy="1e-6" iyz="1e-6" izz="1e-6"/>
    </inertial>
  </link>
</robot>
"""


def test_moments_within_round_off_of_zero_are_shown_as_zero(run_mcar, tmp_path):
    (tmp_path / "r.urdf").write_text(RANK_ONE)
    result = run_mcar("check", "-q", "r.urdf", cwd=tmp_path)
    assert result.returncode == 0
    assert ("r.urdf:5: warning: link 'base': inertia is not positive definite (principal "
            "moments 0, 0, 3e-06) [W204]\n") in result.stderr


def test_a_negative_moment_is_still_shown(run_mcar, tmp_path):
    (tmp_path / "r.urdf").write_text(RANK_ONE.replace('ixx="1e-6"', 'ixx="-1e-6"')
                                     .replace('ixy="1e-6" ixz="1e-6"', 'ixy="0" ixz="0"')
                                     .replace('iyz="1e-6"', 'iyz="0"'))
    result = run_mcar("check", "-q", "r.urdf", cwd=tmp_path)
    assert "(principal moments -1e-06, 1e-06, 1e-06) [W204]" in result.stderr
