"""The sensors section without its proofs (``mcar specs --no-proof``): MuJoCo's ray cast,
with its own housing test, is the figure, and gives the same values as the run with proofs
(trimesh's cast, MuJoCo's the proof) on robots whose lidar the robot blocks, whose camera
looks out of a housing, whose lidar sits in a shell or between rails; where MuJoCo refuses
a mesh trimesh reads, trimesh's cast stands in. A cold ``mcar specs --no-proof`` of a
robot without meshes imports neither trimesh nor scipy (~0.5 s of its start)."""

from __future__ import annotations

import math
import subprocess
import sys

import pytest
from conftest import MCAR, clean_environ
from specs.sensor_robots import (
    box,
    camera_sensor,
    lidar_link,
    link,
    post,
    ray_sensor,
    robot,
    sensors_of,
    values,
)

NO_PROOF = {"proof": False}


def _both(path, text):
    """(the section with proofs, the section without) of the robot ``text``."""
    _, proven = sensors_of(path, text)
    _, computed = sensors_of(path, None, NO_PROOF)
    return proven, computed


def _housed_camera() -> str:
    """A camera frame inside its housing's box (camera_link), 0.5 m from a wall."""
    housing = link("camera_link", "base_link", (0, 0, 0.6), box((0.04, 0.08, 0.03)))
    frame = link("camera_frame", "camera_link", (0.01, 0, 0))
    wall = link("wall", "base_link", (0.55, 1.05, 0.5), box((0.1, 2.0, 4.0)), mass=500)
    return housing + frame + wall + camera_sensor("camera_frame", math.radians(80))


def test_without_proofs_mujoco_casts_the_same_figures_and_housing(tmp_path):
    # A post ahead and a plate behind the lidar (W520), and a camera in a housing.
    plate = link("plate", "base_link", (-0.15, 0, 0.35), box((0.02, 0.2, 0.3)))
    text = robot(lidar_link(), post("post", (0.20, 0.10), 0.02), plate,
                 ray_sensor("lidar_link"), _housed_camera())
    proven, computed = _both(tmp_path / "blocked.urdf", text)
    assert values(computed) == values(proven)
    assert len(values(proven)["sensors.scanner.blocked"]) == 3
    assert 0 < values(proven)["sensors.eye.covered"] < 1
    assert [d.text() for d in computed.diagnostics] == [d.text() for d in proven.diagnostics]
    assert [d.rule for d in computed.diagnostics] == ["W520"]
    assert all(figure.proof is None for figure in computed.figures)
    # The same housing, found by MuJoCo's rays: the camera's frame and its camera_link.
    source = computed.figure("sensors.eye.covered").source
    assert "(mj_multiRay; its housing left out: links camera_frame, camera_link); " \
           "not cross-checked: --no-proof" in source
    assert "by MuJoCo's ray casting" in computed.figure("sensors.scanner.blocked").source
    assert "(its housing left out: links camera_frame, camera_link)" in \
        proven.figure("sensors.eye.covered").source
    assert "MuJoCo" not in proven.figure("sensors.scanner.blocked").source
    assert computed.notes == proven.notes == []


def test_a_shell_is_a_housing_and_rails_that_only_box_it_in_are_not_without_proofs(tmp_path):
    import trimesh

    def mesh_link(name, mesh, xyz=(0, 0, 0.3)):
        mesh.export(tmp_path / f"{name}.stl")
        return link(name, "base_link", xyz,
                    f'<visual><geometry><mesh filename="{name}.stl"/></geometry></visual>')

    # A long shell around the lidar, turned 30° and away from its file's origin: MuJoCo
    # keeps a mesh in its inertial frame, and the shell's box, taken in the file's frame
    # as trimesh's is, must be found to hold the lidar.
    shell = trimesh.creation.box((0.12, 0.08, 0.08))
    shell.apply_transform(trimesh.transformations.rotation_matrix(math.radians(30),
                                                                  (0, 0, 1)))
    shell.apply_translation((0.3, 0.1, 0))
    shell = mesh_link("shell", shell, (-0.3, -0.1, 0.3))
    proven, computed = _both(tmp_path / "housed.urdf",  # (from 1 cm: inside the shell)
                             robot(lidar_link(), shell, ray_sensor("lidar_link", near=0.01)))
    assert values(computed) == values(proven)
    assert values(computed)["sensors.scanner.blocked"] == []
    assert "its housing left out: links lidar_link, shell" in \
        computed.figure("sensors.scanner.blocked").source
    # Two rails either side, one mesh: its box holds the lidar, rays ahead leave it.
    rails = []
    for y in (0.1, -0.1):
        rail = trimesh.creation.box((0.02, 0.02, 0.2))
        rail.apply_translation((0, y, 0))
        rails.append(rail)
    rails = mesh_link("rails", trimesh.util.concatenate(rails))
    proven, computed = _both(tmp_path / "boxed.urdf",
                             robot(lidar_link(), rails, ray_sensor("lidar_link", near=0.01)))
    assert values(computed) == values(proven)
    assert len(values(computed)["sensors.scanner.blocked"]) == 2
    assert "its housing left out: link lidar_link)" in \
        computed.figure("sensors.scanner.blocked").source


def test_a_mesh_mujoco_refuses_leaves_trimesh_to_cast_without_proofs(tmp_path):
    import trimesh

    flat = trimesh.Trimesh(vertices=[[0, -0.05, -0.05], [0, 0.05, -0.05], [0, -0.05, 0.05],
                                     [0, 0.05, 0.05]], faces=[[0, 1, 2], [1, 3, 2]])
    flat.export(tmp_path / "decal.stl")
    decal = link("decal", "base_link", (0.2, 0, 0.3),
                 '<visual><geometry><mesh filename="decal.stl"/></geometry></visual>')
    proven, computed = _both(tmp_path / "decal.urdf",
                             robot(lidar_link(), decal, ray_sensor("lidar_link")))
    # MuJoCo cannot make a hull of the decal: without it the lidar would see nothing.
    assert not proven.figure("sensors.scanner.blocked").proof.agrees
    assert proven.figure("sensors.scanner.blocked").proof.measured == []
    assert values(computed) == values(proven)
    assert len(values(computed)["sensors.scanner.blocked"]) == 1
    assert "MuJoCo" not in computed.figure("sensors.scanner.blocked").source
    assert computed.notes == []


def _imported(robot_path, *options) -> set[str]:
    """The modules a cold `mcar specs` of ``robot_path`` imports (python -X importtime)."""
    done = subprocess.run([sys.executable, "-X", "importtime", str(MCAR), "specs",
                           *options, str(robot_path)], capture_output=True, text=True,
                          env=clean_environ(), cwd=robot_path.parent, timeout=120)
    assert done.returncode in (0, 1), done.stderr[-2000:]
    assert "sensors.scanner.blocked" not in done.stdout  # (a table, not keys)
    assert "scanner" in done.stdout
    return {line.split("|")[-1].strip() for line in done.stderr.splitlines()
            if line.startswith("import time:")}


@pytest.fixture(scope="module")
def lidar_robot(tmp_path_factory):
    path = tmp_path_factory.mktemp("no_proof") / "lidar.urdf"
    wheel = ('<collision><origin rpy="1.5707963 0 0"/><geometry><cylinder radius="0.05" '
             'length="0.02"/></geometry></collision>')
    wheels = "".join(
        f'<joint name="{side}_joint" type="continuous"><parent link="base_link"/>'
        f'<child link="{side}_wheel"/><origin xyz="0 {y} 0.05"/><axis xyz="0 1 0"/></joint>'
        f'<link name="{side}_wheel">{wheel}<inertial><mass value="0.2"/><inertia '
        'ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial></link>'
        for side, y in (("left", 0.12), ("right", -0.12)))
    path.write_text(robot(lidar_link(), post("post", (0.20, 0.10), 0.02),
                          ray_sensor("lidar_link"), wheels))
    return path


def test_mcar_specs_no_proof_of_a_robot_without_meshes_imports_no_trimesh(lidar_robot):
    modules = _imported(lidar_robot, "--no-proof")
    assert "mujoco" in modules
    assert not {m for m in modules if m.split(".")[0] in ("trimesh", "scipy", "yourdfpy")}


def test_control_with_proofs_trimesh_and_scipy_are_imported(lidar_robot):
    modules = _imported(lidar_robot)
    assert {"trimesh", "scipy"} <= {m.split(".")[0] for m in modules}
