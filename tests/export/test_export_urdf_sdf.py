"""mcar export --to urdf and --to sdf: the bundled car, TurtleBot3 burger, Husky and Jackal
exported with --verify from copies of their packages under tmp, the copies then deleted,
and the folders read here without mcar's help: the URDF by yourdfpy (meshes resolved in
the folder only, none missing) and urdfdom's check_urdf where installed, the SDF by
libsdformat (the Gazebo helper, where built); total mass equal to the built URDF's, the
same moving joints, no package:// left. Then what --verify catches in a tampered folder,
and a texture copied beside its mesh."""

from __future__ import annotations

import functools
import json
import shutil
import subprocess
from types import SimpleNamespace

import pytest
from conftest import REPO
from export.test_export_verify import REAL, _invoke, _urdf_facts
from sim.test_sim_real_robots import FOLDER

from mobile_car.errors import GazeboUnavailable

ROBOTS = ["car", "burger", "husky", "jackal"]


def _helper():
    from mobile_car.gazebo.helper import find_helper

    try:
        return find_helper()
    except GazeboUnavailable:
        return None


HELPER = _helper()
needs_helper = pytest.mark.skipif(HELPER is None, reason="the Gazebo helper mcar-sdformat is "
                                  "not built (make gazebo-helper: g++, libsdformat-dev)")


@pytest.fixture(scope="module")
def portable(tmp_path_factory):
    """(robot, format) -> (exit code, stderr, URDF mass, moving joints, folder); every
    source package deleted before the test reads the folders."""
    work = tmp_path_factory.mktemp("portable")
    sources = {"car": (work / "car_src", "mobile_car_description/urdf/mobile_robot.xacro")}
    package = work / "car_src" / "mobile_car_description"
    for name in ("urdf", "meshes"):
        shutil.copytree(REPO / name, package / name)
    shutil.copy(REPO / "package.xml", package / "package.xml")
    for robot in ROBOTS[1:] if FOLDER is not None else ():
        packages, path = REAL[robot]
        for name in packages:
            shutil.copytree(FOLDER / name, work / f"{robot}_src" / name)
        sources[robot] = (work / f"{robot}_src", path)
    done = {}
    formats = ("urdf", "sdf") if HELPER is not None else ("urdf",)
    for robot, (source, path) in sources.items():
        built = work / f"{robot}.urdf"
        assert _invoke("build", "--package-path", source, source / path, "-o",
                       built).exit_code == 0
        given = built if path.endswith(".urdf") else source / path  # TurtleBot3: xacro:arg
        for to in formats:
            result = _invoke("export", "--package-path", source, given, "--to", to, "-o",
                             work / f"{robot}_{to}", "--verify")
            done[robot, to] = (result.exit_code, result.stderr, *_urdf_facts(built),
                               work / f"{robot}_{to}")
    for source, _ in sources.values():
        shutil.rmtree(source)
    return done


def _robot(robot):
    if robot != "car" and FOLDER is None:
        pytest.skip("the shared real-robots folder is absent")
    return robot


@pytest.mark.parametrize("robot", ROBOTS)
def test_a_urdf_folder_loads_with_its_packages_gone(portable, robot):
    import yourdfpy

    code, stderr, mass, moving, folder = portable[_robot(robot), "urdf"]
    assert code == 0, stderr
    manifest = json.loads((folder / "mcar-export.json").read_text())
    path = folder / manifest["robot_file"]
    text = path.read_text()
    assert "package://" not in text and 'filename="meshes/' in text
    loaded = yourdfpy.URDF.load(str(path), load_meshes=True, load_collision_meshes=True,
                                build_collision_scene_graph=True,
                                filename_handler=functools.partial(
                                    yourdfpy.filename_handler_relative, dir=str(folder)))
    for link in loaded.robot.links:
        for holder in link.visuals + link.collisions:
            if holder.geometry.mesh is not None:
                assert (folder / holder.geometry.mesh.filename).is_file()
    assert sum(link.inertial.mass for link in loaded.robot.links
               if link.inertial is not None) == pytest.approx(mass, rel=1e-3)
    assert sorted(j.name for j in loaded.robot.joints if j.type != "fixed") == moving
    if shutil.which("check_urdf"):
        assert subprocess.run(["check_urdf", str(path)], capture_output=True).returncode == 0
        assert "verified: urdfdom's check_urdf parses it" in stderr


@needs_helper
@pytest.mark.parametrize("robot", ROBOTS)
def test_an_sdf_folder_loads_in_libsdformat_with_its_packages_gone(portable, robot):
    from lxml import etree

    code, stderr, mass, moving, folder = portable[_robot(robot), "sdf"]
    assert code == 0, stderr
    manifest = json.loads((folder / "mcar-export.json").read_text())
    path = folder / manifest["robot_file"]
    document = etree.parse(str(path), etree.XMLParser(recover=True)).getroot()
    uris = [u.text.strip() for u in document.iter("uri") if u.getparent().tag == "mesh"]
    assert uris and all(u.startswith("meshes/") and (folder / u).is_file() for u in uris)
    answer = json.loads(subprocess.run([str(HELPER)], stdin=path.open("rb"),
                                       capture_output=True, check=True).stdout)
    assert answer["errors"] == []
    assert sum(link["mass"] for link in answer["model"]["links"]) == pytest.approx(mass,
                                                                                    rel=1e-3)
    assert sorted(j["name"] for j in answer["model"]["joints"] if j["type"] != "fixed") == \
        moving
    assert "libsdformat lumps links on fixed joints" in stderr


def test_the_cars_sdf_says_what_gazebo_lumps(portable):
    if HELPER is None:
        pytest.skip("the Gazebo helper mcar-sdformat is not built")
    stderr = portable["car", "sdf"][1]
    assert "16 URDF links become 3 Gazebo links" in stderr
    assert "verified: mass 0.70564 kg, the description's 0.70564 kg" in stderr


def test_verify_names_a_package_uri_and_a_missing_mesh(portable, tmp_path):
    from mobile_car.export import ExportError
    from mobile_car.export.verify_portable import verify_urdf

    folder = tmp_path / "urdf"
    shutil.copytree(portable["car", "urdf"][4], folder)
    manifest = json.loads((folder / "mcar-export.json").read_text())
    exported = SimpleNamespace(**{k: manifest[k] for k in ("robot_file", "urdf_mass",
                                                            "moving_joints")})
    assert verify_urdf(folder, exported)[2] == "2 moving joints"
    path = folder / exported.robot_file
    original = path.read_text()
    path.write_text(original.replace('filename="meshes/',
                                     'filename="package://mobile_car_description/', 1))
    with pytest.raises(ExportError, match=r"mesh package://mobile_car_description/"
                                          r"mobile_car_description/meshes/motor.stl: a URI"):
        verify_urdf(folder, exported)
    path.write_text(original)
    shutil.rmtree(folder / "meshes")
    with pytest.raises(ExportError, match=r"mesh meshes/.*motor.stl: missing"):
        verify_urdf(folder, exported)


def test_a_texture_and_an_ascii_stl_are_copied_beside_the_urdf(tmp_path):
    package = tmp_path / "src" / "toy"
    (package / "meshes").mkdir(parents=True)
    (package / "package.xml").write_text("<package><name>toy</name></package>")
    (package / "meshes" / "block.stl").write_text(
        "solid b\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
        "vertex 0 1 0\nendloop\nendfacet\nendsolid b\n")
    (package / "meshes" / "skin.png").write_bytes(b"\x89PNG\r\n\x1a\n" + b"\0" * 32)
    urdf = package / "toy.urdf"
    urdf.write_text("""<robot name="toy"><link name="base">
      <visual><geometry><mesh filename="package://toy/meshes/block.stl"/></geometry>
        <material name="skin"><texture filename="package://toy/meshes/skin.png"/></material>
      </visual>
      <inertial><mass value="2"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/>
      </inertial></link></robot>""")
    out = tmp_path / "out"
    result = _invoke("export", "--package-path", tmp_path / "src", urdf, "--to", "urdf",
                     "-o", out, "--verify")
    assert result.exit_code == 0, result.stderr
    assert (out / "meshes/toy/meshes/block.stl").read_bytes() == \
        (package / "meshes/block.stl").read_bytes()  # kept as it is, ASCII
    assert (out / "meshes/toy/meshes/skin.png").read_bytes() == \
        (package / "meshes/skin.png").read_bytes()
    text = (out / "toy.urdf").read_text()
    assert '<texture filename="meshes/toy/meshes/skin.png"/>' in text
    assert "package://" not in text


def test_sdf_without_the_helper_is_an_environment_error(run_mcar, repo, tmp_path):
    result = run_mcar("export", repo / "urdf/mobile_robot.xacro", "--to", "sdf", "-o",
                      tmp_path / "sdf", env={"MCAR_SDFORMAT": str(tmp_path / "none")})
    assert result.returncode == 2
    assert result.stderr.count("\n") == 1 and "make gazebo-helper" in result.stderr
    assert not (tmp_path / "sdf").exists()


@pytest.mark.parametrize(("to", "option", "said"), [
    ("urdf", "--base=fixed", "--base applies to --to mjcf and usd, not to --to urdf"),
    ("sdf", "--fix-inertia", "--fix-inertia applies to --to mjcf, not to --to sdf"),
    ("usd", "--no-floor", "--no-floor applies to --to mjcf, not to --to usd")])
def test_an_option_of_another_format_is_a_usage_error(repo, tmp_path, to, option, said):
    result = _invoke("export", repo / "urdf/mobile_robot.xacro", "--to", to, "-o",
                     tmp_path / "out", option)
    assert result.exit_code == 2
    assert result.stderr == f"mcar: error: {said}\n"
    assert not (tmp_path / "out").exists()


@needs_helper
def test_links_libsdformat_leaves_out_are_warned_and_fail_verify(repo, tmp_path):
    robot = repo / "tests/gazebo/cases/massless_middle_link.urdf"
    result = _invoke("export", robot, "--to", "sdf", "-o", tmp_path / "sdf")
    assert result.exit_code == 0
    assert "warning: libsdformat leaves out arm, tip, tip2 (a link without mass and what " \
           "moves below it): the SDF has 1 kg of the URDF's 1.75 kg" in result.stderr
    result = _invoke("export", robot, "--to", "sdf", "-o", tmp_path / "verified", "--verify")
    assert result.exit_code == 1
    assert result.stderr.endswith("verified: error: total mass 1 kg, the description's "
                                  "1.75 kg (42.9% apart, more than 0.1%)\n")
    assert not (tmp_path / "verified").exists()
