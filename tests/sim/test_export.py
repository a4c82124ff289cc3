"""mcar build --format mjcf: the model mcar sim runs, written as MJCF that MuJoCo loads back
from wherever it was written, the car driving off when its motors turn."""

from __future__ import annotations

import numpy as np

from mobile_car.sim.engine import mujoco as engine

# Through mcar's import, which picks EGL first: a bare `import mujoco` here would fix GLFW
# as the renderer for every later test in this process (test_record.py).
mujoco = engine()

ROBOT = "urdf/mobile_robot.xacro"
# One link, its collision a mesh of the bundled package: the mesh must resolve from the
# written file's folder, not from where the robot was built.
MESH_ROBOT = """<?xml version="1.0"?>
<robot name="meshy">
  <link name="base_link">
    <inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0"
      iyz="0"/></inertial>
    <collision><geometry>
      <mesh filename="package://mobile_car_description/meshes/motor.stl" scale="0.001 0.001 0.001"/>
    </geometry></collision>
  </link>
</robot>
"""


def test_the_written_model_has_the_free_and_drive_joints_and_drives(run_mcar, repo, tmp_path):
    out = tmp_path / "models" / "car.xml"
    result = run_mcar("build", ROBOT, "--format", "mjcf", "-o", out, cwd=repo)
    assert result.returncode == 0, result.stderr
    assert out.read_text().startswith('<mujoco model="mobile_robot">')
    model = mujoco.MjModel.from_xml_path(str(out))
    kinds = {model.joint(j).name: int(model.jnt_type[j]) for j in range(model.njnt)}
    assert kinds == {"mcar_free": mujoco.mjtJoint.mjJNT_FREE,
                     "wheel_left_joint": mujoco.mjtJoint.mjJNT_HINGE,
                     "wheel_right_joint": mujoco.mjtJoint.mjJNT_HINGE}
    motors = {model.joint(int(model.actuator_trnid[a][0])).name: model.actuator_forcerange[a]
              for a in range(model.nu)}
    assert sorted(motors) == ["wheel_left_joint", "wheel_right_joint"]
    assert all(np.allclose(limits, [-0.43, 0.43]) for limits in motors.values())
    assert model.opt.timestep == 0.001
    # The motors' velocity servos roll it forward along +x (r = 32.5 mm, 5 rad/s, 1 s).
    data = mujoco.MjData(model)
    data.ctrl[:] = 5.0
    mujoco.mj_step(model, data, nstep=1000)
    assert 0.1 < data.qpos[0] < 0.17 and abs(data.qpos[1]) < 0.005


def test_a_collision_mesh_resolves_from_the_written_files_folder(run_mcar, tmp_path):
    source = tmp_path / "src"
    source.mkdir()
    (source / "meshy.urdf").write_text(MESH_ROBOT)
    result = run_mcar("build", "meshy.urdf", "--format", "mjcf", "-o", tmp_path / "a/m.xml",
                      cwd=source)
    assert result.returncode == 0, result.stderr
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    moved = elsewhere / "m.xml"
    moved.write_text((tmp_path / "a/m.xml").read_text())
    model = mujoco.MjModel.from_xml_path(str(moved))
    assert model.nmesh == 1 and model.mesh_vertnum[0] > 8
    assert "/meshes/motor.stl" in moved.read_text()


def test_a_package_builds_into_xml_files_and_names_what_mujoco_refuses(run_mcar, repo,
                                                                       tmp_path):
    result = run_mcar("build", "urdf/wheel", "urdf/laser", "--format", "mjcf", "-o",
                      tmp_path / "out/", cwd=repo)
    assert result.returncode == 1
    assert (tmp_path / "out/laser/test_laser.xml").is_file()
    assert not list((tmp_path / "out").rglob("*.urdf"))
    assert "urdf/wheel/test_wheel.urdf.xacro: error: MuJoCo cannot simulate the robot: mass " \
           "and inertia of moving bodies must be larger than mjMINVAL" in result.stderr
    assert result.stderr.endswith(f"1 of 2 files built into {tmp_path / 'out'}\n")
