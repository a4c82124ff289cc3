"""Every inertia MuJoCo refuses is named by link and line before MuJoCo runs (it used to
stop `mcar sim` and `mcar export` with its own "inertia must have positive eigenvalues",
no link named: PMB2), and --fix-inertia makes it physical, saying what changed (PR2's
massless gripper frames stopped both even with --fix-inertia)."""

from __future__ import annotations

import math
import re

import pytest
from conftest import line_of
from sim.robot_makers import (
    massless_frame,
    non_positive_antenna,
    pr2_like_inertias,
    zero_tensor_swivel,
)

from mobile_car.sim.engine import mujoco as engine

ANTENNA_MOMENTS = "-3.535e-08, 3.501e-08, 9.087e-08"




@pytest.fixture(scope="module")
def robots(tmp_path_factory):
    folder = tmp_path_factory.mktemp("inertia")
    (folder / "antenna.urdf").write_text(non_positive_antenna())
    (folder / "frame.urdf").write_text(massless_frame())
    (folder / "swivel.urdf").write_text(zero_tensor_swivel())
    return folder


def test_a_tensor_not_positive_definite_is_named_with_its_line(run_mcar, robots):
    line = line_of(non_positive_antenna(), 'iyz="7.74e-09"')  # (lxml: where the tag ends)
    result = run_mcar("sim", "antenna.urdf", "--scenario", "drop", cwd=robots)
    assert result.returncode == 1
    assert (f"antenna.urdf:{line}: error: link antenna_link: inertia is not positive definite "
            f"(principal moments {ANTENNA_MOMENTS} kg m²): MuJoCo refuses it; --fix-inertia "
            "puts the nearest physical tensor in its place [E310]") in result.stderr
    assert ("antenna.urdf: error: MuJoCo refuses 1 link (E305/E310 above); --fix-inertia "
            "makes it physical") in result.stderr
    assert "positive eigenvalues" not in result.stderr  # MuJoCo's own words, no link named
    # the report's lint line: the refusal, then each link's, one "; " between each
    # (the gz_ros2_control Ackermann demo's read "...makes them physicalE310 link ...")
    assert ("  lint   FAILED  MuJoCo refuses 1 link (E305/E310 above); --fix-inertia makes it "
            "physical; E310 link antenna_link: inertia is not positive definite") \
        in result.stdout


def test_fix_inertia_puts_the_nearest_physical_tensor_and_says_so(run_mcar, robots):
    result = run_mcar("sim", "antenna.urdf", "--scenario", "drop", "--fix-inertia",
                      cwd=robots)
    assert result.returncode == 0, result.stderr
    assert (f"mcar: antenna.urdf: --fix-inertia: link antenna_link: inertia not positive "
            f"definite (principal moments {ANTENNA_MOMENTS}) -> the nearest physical tensor, "
            "principal moments 4.196e-11, 6.292e-08, 6.292e-08 kg m² on the same axes"
            ) in result.stderr
    assert "  drop   PASSED" in result.stdout


def test_the_export_names_the_link_and_line_then_fixes_it(run_mcar, robots, tmp_path):
    line = line_of(non_positive_antenna(), 'iyz="7.74e-09"')  # (lxml: where the tag ends)
    refused = run_mcar("export", robots / "antenna.urdf", "--to", "mjcf", "-o", "out",
                       cwd=tmp_path)
    assert refused.returncode == 1
    assert (f"  link antenna_link: inertia is not positive definite (principal moments "
            f"{ANTENNA_MOMENTS} kg m²) ({robots / 'antenna.urdf'}:{line})"
            ) in refused.stderr
    assert not (tmp_path / "out").exists()
    fixed = run_mcar("export", robots / "antenna.urdf", "--to", "mjcf", "-o", "out",
                     "--fix-inertia", cwd=tmp_path)
    assert fixed.returncode == 0, fixed.stderr
    assert "warning: link antenna_link: inertia not positive definite" in fixed.stderr
    mujoco = engine()
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "out/two_wheeler.xml"))
    assert (model.body("antenna_link").inertia > 0).all()


def test_a_massless_moving_frame_gets_a_token_mass(run_mcar, robots, tmp_path):
    line = line_of(massless_frame(), '<link name="gap_frame"/>')
    refused = run_mcar("sim", "frame.urdf", "--scenario", "drop", cwd=robots)
    assert refused.returncode == 1
    assert re.search(rf"frame\.urdf:{line}: error: link gap_frame moves .* give it an "
                     r"<inertial> \(--fix-inertia gives it a token mass\) \[E305\]",
                     refused.stderr)
    token = ("link gap_frame: moves without mass; given a token 1 g (the inertia of a 1 cm "
             "solid sphere), as MuJoCo needs a mass to move it")
    fixed = run_mcar("sim", "frame.urdf", "--scenario", "drop", "--fix-inertia", cwd=robots)
    assert fixed.returncode == 0, fixed.stderr
    assert f"mcar: frame.urdf: --fix-inertia: {token}" in fixed.stderr
    exported = run_mcar("export", robots / "frame.urdf", "--to", "mjcf", "-o", "out",
                        "--fix-inertia", "--verify", cwd=tmp_path)
    assert exported.returncode == 0, exported.stderr
    assert f"frame.urdf: warning: {token}" in exported.stderr
    assert ("verified: mass 0.701 kg, the description's 0.7 kg + 0.001 kg given to "
            "massless links") in exported.stderr


def test_a_moving_link_with_mass_and_no_inertia_is_named_and_given_one(run_mcar, robots):
    line = line_of(zero_tensor_swivel(), 'ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"')
    refused = run_mcar("sim", "swivel.urdf", "--scenario", "drop", cwd=robots)
    assert refused.returncode == 1
    assert (f"swivel.urdf:{line}: error: link swivel_link: moves with a mass but an inertia "
            "of zeros (MuJoCo needs it positive): MuJoCo refuses it; --fix-inertia gives it "
            "a small sphere's [E310]") in refused.stderr
    fixed = run_mcar("sim", "swivel.urdf", "--scenario", "drop", "--fix-inertia", cwd=robots)
    assert fixed.returncode == 0, fixed.stderr
    assert ("--fix-inertia: link swivel_link: moves with 0.01 kg but an inertia of zeros; "
            "given that of a 1 cm solid sphere of its mass (4e-07 kg m² about each axis)"
            ) in fixed.stderr


def test_the_mended_mjcf_loads_in_mujoco_and_stands(run_mcar, tmp_path):
    (tmp_path / "both.urdf").write_text(pr2_like_inertias())
    result = run_mcar("export", "both.urdf", "--to", "mjcf", "-o", "out", "--fix-inertia",
                      cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    mujoco = engine()
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "out/two_wheeler.xml"))
    data = mujoco.MjData(model)
    mujoco.mj_step(model, data, nstep=round(1 / model.opt.timestep))  # 1 s, motors at 0
    free = next(j for j in range(model.njnt) if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE)
    w = data.qpos[model.jnt_qposadr[free] + 3]  # the quaternion's w: cos(tilt / 2)
    assert abs(w) > math.cos(math.radians(1) / 2)  # upright within 1°
    start = model.jnt_dofadr[free]
    assert abs(data.qvel[start:start + 3]).max() < 0.002  # at rest: under 2 mm/s
