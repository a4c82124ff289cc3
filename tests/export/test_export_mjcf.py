"""mcar export --to mjcf: a folder MuJoCo loads with nothing else on the machine, read back
here with MuJoCo itself (geom groups, meshes, actuators, equality constraints, masses),
and the folder's own safety (written whole or not at all, never over a user's folder)."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest
from sim.robot_makers import ackermann, two_wheeler

from mobile_car.sim.engine import mujoco as engine

# Through mcar's import, which picks EGL first (see tests/sim/test_record.py).
mujoco = engine()

MIMIC = """
  <link name="flap_link">
    <visual><geometry><box size="0.02 0.02 0.02"/></geometry></visual>
    <inertial><mass value="0.01"/><inertia ixx="1e-6" iyy="1e-6" izz="1e-6" ixy="0" ixz="0"
      iyz="0"/></inertial>
  </link>
  <joint name="flap_joint" type="revolute">
    <parent link="base_link"/><child link="flap_link"/><origin xyz="0 0 0.1"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
    <mimic joint="wheel_left_joint" multiplier="-0.5" offset="0.1"/>
  </joint>"""


def _collada_box_mm(path, rgb=(200, 30, 30)):
    """A 40 x 60 x 20 mm box written as COLLADA in millimetres (<unit meter="0.001">)."""
    import trimesh

    box = trimesh.creation.box([40, 60, 20])
    box.visual.face_colors = [*rgb, 255]
    text = box.export(file_type="dae")
    text = text.decode() if isinstance(text, bytes) else text
    path.write_text(text.replace("<asset>", '<asset>\n    <unit name="millimetre" '
                                            'meter="0.001"/>', 1))


def _model(folder, name):
    """The export loaded by MuJoCo from a copy of the folder in a fresh place, the
    original removed: only what is inside the folder can be read."""
    elsewhere = folder.parent / "elsewhere" / folder.name
    shutil.copytree(folder, elsewhere)
    shutil.rmtree(folder)
    return mujoco.MjModel.from_xml_path(str(elsewhere / name)), elsewhere


def test_the_car_exports_visuals_collisions_motors_and_a_floor(run_mcar, package_copy, tmp_path):
    out = tmp_path / "out" / "car"
    result = run_mcar("export", package_copy / "urdf/mobile_robot.xacro", "--to", "mjcf",
                      "-o", out)
    assert result.returncode == 0, result.stderr
    assert sorted(p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file()) == [
        "mcar-export.json", "meshes/mobile_car_description/meshes/motor.stl",
        "mobile_robot.xml"]
    text = (out / "mobile_robot.xml").read_text()
    assert 'file="meshes/mobile_car_description/meshes/motor.stl"' in text
    manifest = json.loads((out / "mcar-export.json").read_text())
    assert manifest["format"] == "mjcf" and manifest["robot_file"] == "mobile_robot.xml"
    assert manifest["drive"]["left"] == ["wheel_left_joint"]
    shutil.rmtree(package_copy)  # the source package is gone
    model, _ = _model(out, "mobile_robot.xml")
    groups = {}
    for g in range(model.ngeom):
        if model.geom_bodyid[g]:
            groups.setdefault(int(model.geom_group[g]), set()).add(
                (int(model.geom_contype[g]), int(model.geom_conaffinity[g])))
    assert groups == {2: {(0, 0)}, 3: {(1, 0)}}  # visuals touch nothing; collisions the world
    visual_meshes = [g for g in range(model.ngeom) if model.geom_type[g] ==
                     mujoco.mjtGeom.mjGEOM_MESH and model.geom_group[g] == 2]
    assert len(visual_meshes) == 2  # both motors, drawn with the package's STL
    assert model.geom("mcar_floor").id >= 0
    assert abs(float(model.body_mass.sum()) - 0.70564) < 1e-6
    free = [j for j in range(model.njnt) if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE]
    assert [model.joint(j).name for j in free] == ["floating_base"]
    motors = sorted(model.actuator(a).name for a in range(model.nu))
    assert motors == ["mcar_motor_wheel_left_joint", "mcar_motor_wheel_right_joint"]
    data = mujoco.MjData(model)
    data.ctrl[:] = 5.0  # rad/s on both wheels: forward along +x, 32.5 mm wheels
    mujoco.mj_step(model, data, nstep=1000)
    assert 0.1 < data.qpos[0] < 0.17 and abs(data.qpos[1]) < 0.005


def test_a_fixed_base_without_floor_and_a_mimic_as_an_equality(run_mcar, tmp_path):
    (tmp_path / "flap.urdf").write_text(two_wheeler(extra=MIMIC))
    out = tmp_path / "flap"
    result = run_mcar("export", "flap.urdf", "--to", "mjcf", "-o", out, "--base", "fixed",
                      cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    model = mujoco.MjModel.from_xml_path(str(out / "two_wheeler.xml"))
    assert mujoco.mjtJoint.mjJNT_FREE not in set(model.jnt_type.tolist())
    assert all(model.geom(g).name != "mcar_floor" for g in range(model.ngeom))
    assert model.neq == 1 and model.eq_type[0] == mujoco.mjtEq.mjEQ_JOINT
    assert model.joint(int(model.eq_obj1id[0])).name == "flap_joint"
    assert model.joint(int(model.eq_obj2id[0])).name == "wheel_left_joint"
    assert np.allclose(model.eq_data[0][:2], [0.1, -0.5])


def test_a_collada_mesh_is_converted_in_metres_with_its_colour(run_mcar, tmp_path):
    meshes = tmp_path / "src" / "meshes"
    meshes.mkdir(parents=True)
    _collada_box_mm(meshes / "lid.dae")
    lid = """
  <link name="lid_link">
    <visual><geometry><mesh filename="meshes/lid.dae"/></geometry></visual>
    <collision><geometry><mesh filename="meshes/lid.dae"/></geometry></collision>
    <inertial><mass value="0.05"/><inertia ixx="1e-5" iyy="1e-5" izz="1e-5" ixy="0" ixz="0"
      iyz="0"/></inertial>
  </link>
  <joint name="lid_joint" type="fixed">
    <parent link="base_link"/><child link="lid_link"/><origin xyz="0 0 0.09"/>
  </joint>"""
    (tmp_path / "src" / "lid.urdf").write_text(two_wheeler(extra=lid))
    out = tmp_path / "lid"
    result = run_mcar("export", "lid.urdf", "--to", "mjcf", "-o", out, cwd=tmp_path / "src")
    assert result.returncode == 0, result.stderr
    assert "mcar export: converted meshes/lid.dae -> meshes/lid.dae.stl" in result.stderr
    assert json.loads((out / "mcar-export.json").read_text())["converted"] == [
        "meshes/lid.dae -> meshes/lid.dae.stl"]
    shutil.rmtree(tmp_path / "src")
    model, _ = _model(out, "two_wheeler.xml")
    (mesh,) = range(model.nmesh)
    vertices = model.mesh_vert[model.mesh_vertadr[mesh]:
                               model.mesh_vertadr[mesh] + model.mesh_vertnum[mesh]]
    extents = sorted(np.ptp(vertices, axis=0))  # (MuJoCo keeps float32 vertices)
    assert np.allclose(extents, [0.02, 0.04, 0.06], rtol=1e-6)  # metres, not millimetres
    visual = next(g for g in range(model.ngeom) if model.geom_dataid[g] == mesh and
                  model.geom_group[g] == 2)
    assert np.allclose(model.geom_rgba[visual], [200 / 255, 30 / 255, 30 / 255, 1], atol=0.01)


def test_an_ackermann_car_gets_its_steering_servos(run_mcar, tmp_path):
    (tmp_path / "car.urdf").write_text(ackermann())
    result = run_mcar("export", "car.urdf", "--to", "mjcf", "-o", "out", "--verify",
                      cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "out/ackermann_car.xml"))
    names = sorted(model.actuator(a).name for a in range(model.nu))
    assert names == ["mcar_motor_rear_left_wheel_joint", "mcar_motor_rear_right_wheel_joint",
                     "mcar_steer_front_left_steering_joint",
                     "mcar_steer_front_right_steering_joint"]
    assert "verified: turn passed as mcar sim judges it: radius error " in result.stderr


def test_a_missing_mesh_is_left_out_with_a_warning(run_mcar, tmp_path):
    ghost = """
  <link name="ghost_link">
    <visual><geometry><mesh filename="meshes/nowhere.stl"/></geometry></visual>
  </link>
  <joint name="ghost_joint" type="fixed"><parent link="base_link"/><child link="ghost_link"/>
  </joint>"""
    (tmp_path / "ghost.urdf").write_text(two_wheeler(extra=ghost))
    result = run_mcar("export", "ghost.urdf", "--to", "mjcf", "-o", "out", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    warning = ("link ghost_link: visual left out: mesh meshes/nowhere.stl: no such file "
               "(meshes/nowhere.stl)")
    assert f"ghost.urdf: warning: {warning}\n" in result.stderr
    assert json.loads((tmp_path / "out/mcar-export.json").read_text())["warnings"] == [warning]
    assert "two_wheeler.xml and 0 other files" in result.stderr


def test_build_format_mjcf_points_at_export(run_mcar, repo, tmp_path):
    result = run_mcar("build", "urdf/mobile_robot.xacro", "--format", "mjcf", "-o",
                      tmp_path / "car.xml", cwd=repo)
    assert result.returncode == 2
    assert "mcar export ROBOT --to mjcf -o DIR" in result.stderr
    assert not (tmp_path / "car.xml").exists()


@pytest.fixture
def small_car(tmp_path):
    (tmp_path / "car.urdf").write_text(two_wheeler())
    return tmp_path


def test_a_users_folder_is_never_replaced(run_mcar, small_car):
    mine = small_car / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("keep me")
    result = run_mcar("export", "car.urdf", "--to", "mjcf", "-o", mine, cwd=small_car)
    assert result.returncode == 2
    assert "is a folder mcar did not export into (no mcar-export.json)" in result.stderr
    assert [p.name for p in mine.iterdir()] == ["notes.txt"]


def test_a_folder_holding_an_input_is_refused(run_mcar, small_car):
    result = run_mcar("export", "car.urdf", "--to", "mjcf", "-o", ".", cwd=small_car)
    assert result.returncode == 2
    assert "holds car.urdf, a file this run reads" in result.stderr


def test_an_earlier_export_is_replaced_and_kept_when_the_new_one_fails(run_mcar, small_car):
    out = small_car / "out"
    assert run_mcar("export", "car.urdf", "--to", "mjcf", "-o", out,
                    cwd=small_car).returncode == 0
    (out / "stale.txt").write_text("from before")
    assert run_mcar("export", "car.urdf", "--to", "mjcf", "-o", out,
                    cwd=small_car).returncode == 0
    assert not (out / "stale.txt").exists()  # replaced whole
    before = (out / "two_wheeler.xml").read_bytes()
    broken = two_wheeler().replace('ixx="', 'ixx="9', 1)  # base_link: A + B < C
    (small_car / "car.urdf").write_text(broken)
    result = run_mcar("export", "car.urdf", "--to", "mjcf", "-o", out, cwd=small_car)
    assert result.returncode == 1
    assert (out / "two_wheeler.xml").read_bytes() == before
    assert sorted(p.name for p in small_car.iterdir()) == ["car.urdf", "out"]  # no staging
