"""Meshes as RViz and Gazebo read them, in every command that measures or draws one.

tests/load/meshes_as_rviz/ holds one small file per case, each the same 0.4 x 0.2 x 0.1 m
box where RViz draws it (corner at the origin, long side along x): a COLLADA in
millimetres, a Z_UP / Y_UP pair (RViz and Gazebo ignore the tag), a colour of three numbers
run together (TurtleBot4's rplidar.dae), a node named ``<STL_BINARY>`` unescaped
(velodyne_description), and a binary STL whose header starts with "solid". robot.urdf
puts them side by side. The real files they stand for are checked too, in place, where
the shared real-robots folder is.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from sim.test_sim_real_robots import FOLDER, needs_folder

HERE = Path(__file__).resolve().parent / "meshes_as_rviz"
ROBOT = HERE / "robot.urdf"
CASES = ["box_mm.dae", "box_zup.dae", "box_yup.dae", "bad_colour.dae", "stl_binary_id.dae",
         "solid_header.stl"]
BOX = [[0.0, 0.0, 0.0], [0.4, 0.2, 0.1]]
RED = (204, 26, 26, 255)  # the files' diffuse 0.8 0.1 0.1


@pytest.mark.parametrize("name", CASES)
def test_each_file_is_the_box_rviz_draws(name):
    from mobile_car.load.mesh_reader import load_mesh

    mesh, _ = load_mesh(HERE / name, force="mesh")
    assert mesh.bounds == pytest.approx(np.array(BOX))
    assert len(mesh.faces) == 12
    if name.endswith(".dae"):  # its own colour kept, the bad specular one read past
        assert tuple(mesh.visual.material.main_color) == RED


def test_check_reads_every_one_without_a_warning(cli):
    result = cli("check", "--format", "json", ROBOT)
    [document] = json.loads(result.stdout)["files"]
    assert document["diagnostics"] == [] and result.exit_code == 0


def test_render_draws_each_at_its_size_and_in_its_colour():
    from mobile_car.load.inputs import RobotInput
    from mobile_car.load.robot import LoadOptions, load_robot
    from mobile_car.render.scene import load_scene
    from mobile_car.render.session import model_source

    loaded = load_robot(RobotInput(ROBOT), LoadOptions())
    scene = load_scene(model_source(loaded), loaded.search, with_links=True)
    assert set(scene.link_names) == {"base", "z_up", "y_up", "bad_colour", "stl_binary_id",
                                     "solid_header"}
    for index, link in enumerate(scene.link_names):
        points = scene.positions[scene.link_of == index]
        offset = [0.0, float(["base", "z_up", "y_up", "bad_colour", "stl_binary_id",
                              "solid_header"].index(link)), 0.0]
        assert np.array([points.min(axis=0), points.max(axis=0)]) == pytest.approx(
            np.array(BOX) + offset, abs=1e-6), link
    base = scene.link_names.index("base")
    colours = {tuple(c) for c in np.rint(scene.colors[scene.link_of == base] * 255).astype(int)}
    assert colours == {RED}


def test_view_reads_them_as_render_draws_them():
    from mobile_car.load.inputs import RobotInput
    from mobile_car.load.robot import LoadOptions
    from mobile_car.view.model import load_model

    model = load_model(RobotInput(ROBOT), LoadOptions())
    assert model.urdf.scene.bounds == pytest.approx(np.array([[0, 0, 0], [0.4, 5.2, 0.1]]))
    assert model.urdf.collision_scene.bounds == pytest.approx(np.array(BOX))


def test_sim_hands_mujoco_the_millimetre_collada_in_metres(tmp_path, monkeypatch):
    """MuJoCo reads no COLLADA: it gets the converted mesh, in metres, from the cache."""
    monkeypatch.setenv("MCAR_CACHE_DIR", str(tmp_path / "cache"))
    from mobile_car.packages.search import PackageSearch
    from mobile_car.sim.model import build_model

    sim = build_model(ROBOT.read_bytes(), str(ROBOT), HERE, PackageSearch(origin=ROBOT))
    assert sim.notes == []
    [geom] = [g for g in range(sim.model.ngeom) if sim.model.geom_bodyid[g] != 0]
    mesh = sim.model.geom_dataid[geom]
    start, count = sim.model.mesh_vertadr[mesh], sim.model.mesh_vertnum[mesh]
    vertices = sim.model.mesh_vert[start:start + count]
    # MuJoCo turns a mesh into its principal frame: its extents, sorted, are the box's.
    assert sorted(np.ptp(vertices, axis=0)) == pytest.approx([0.1, 0.2, 0.4], abs=1e-6)
    assert sim.rest_height == pytest.approx(0.0, abs=1e-6)  # its bottom face on the floor
    [converted] = (tmp_path / "cache" / "mujoco-meshes").iterdir()
    assert converted.suffix == ".stl"


@needs_folder
def test_the_real_files_load_as_rviz_draws_them():
    from mobile_car.load.mesh_reader import load_mesh

    velodyne = FOLDER / "clearpath_deps/velodyne_simulator/velodyne_description/meshes"
    for name in ("VLP16_base_1.dae", "VLP16_base_2.dae", "VLP16_scan.dae"):
        mesh, _ = load_mesh(velodyne / name, force="mesh")  # Y_UP over Z-up data: upright
        width, depth, height = mesh.extents
        assert height < 0.05 < min(width, depth) < 0.12, name
    camera, _ = load_mesh(FOLDER / "turtlebot3_description/meshes/sensors/r200.dae",
                          force="mesh")  # units of 2.54 mm: a 13 cm camera, not a 51 m slab
    assert camera.extents == pytest.approx([0.13, 0.02, 0.0063], abs=1e-3)
