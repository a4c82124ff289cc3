"""A description may not get files from outside its folders into an export, a picture or
a record (issue 39, item 1).

The attack, found on main: a robot names a "texture" ``file:///etc/shadow``, a mesh
``../../../home/ci/.bashrc`` or a link inside its package that leads out of it, and
``mcar export`` (and ``mcar ci`` with ``export:`` in the pull request's mcar.yaml) copied
the file byte for byte into the folder CI uploads. Each form is planted here against a
"secret" outside the package; every one must be refused (W215, at its line), never read,
and absent from every output. The controls name the same files with ``--asset-path``: the
attack then works, so the tests can fail.
"""

from __future__ import annotations

import importlib.util
import json
import shutil
from pathlib import Path

import pytest
from hostile import PACKAGE_XML, cube_stl, files_holding

MARK = b"MCAR-SECRET-7f3a9c"  # in every secret file: what must never reach an output



OBJ = """mtllib {outside}/evil.mtl
mtllib ../../outside/evil.mtl
mtllib local.mtl
v 0 0 0
v 0.1 0 0
v 0 0.1 0
v 0 0 0.1
vt 0 0
vt 1 0
vt 0 1
usemtl skin
f 1/1 3/3 2/2
f 1/1 2/2 4/1
f 1/1 4/1 3/3
f 2/2 3/3 4/1
"""
# Every form a description can name the secret by; the line of each in robot.urdf.
ROBOT = """<?xml version="1.0"?>
<robot name="atk">
  <link name="base">
    <visual><geometry><box size="0.1 0.1 0.1"/></geometry>
      <material name="a"><texture filename="file://{outside}/secret.png"/></material>
    </visual>
    <visual><geometry><box size="0.1 0.1 0.1"/></geometry>
      <material name="b"><texture filename="../../outside/secret.png"/></material>
    </visual>
    <visual><geometry><box size="0.1 0.1 0.1"/></geometry>
      <material name="c"><texture filename="package://atk/meshes/linked.png"/></material>
    </visual>
    <visual><geometry><mesh filename="file://{outside}/secret.stl"/></geometry></visual>
    <visual><geometry><mesh filename="{outside}/secret.stl"/></geometry></visual>
    <visual><geometry><mesh filename="package://atk/../outside/secret.stl"/></geometry></visual>
    <visual><geometry><mesh filename="package://atk/meshes/linked.stl"/></geometry></visual>
    <visual><geometry><mesh filename="../../outside/secret.stl"/></geometry></visual>
    <collision><geometry><mesh filename="package://atk/meshes/linked.stl"/></geometry></collision>
    <visual><geometry><mesh filename="package://atk/meshes/quad.obj"/></geometry></visual>
    <visual><geometry><mesh filename="package://atk/meshes/cube.stl"/></geometry></visual>
    <inertial><mass value="1"/>
      <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
</robot>
"""
REFUSED_LINES = [5, 8, 11, 13, 14, 15, 16, 17, 18]


def _attack(root: Path) -> Path:
    """root/outside holds the secrets; root/pkg the package naming them every way. The
    robot file's path."""
    outside = root / "outside"
    meshes = root / "pkg" / "meshes"
    urdf = root / "pkg" / "urdf"
    for folder in (outside, meshes, urdf):
        folder.mkdir(parents=True)
    (outside / "secret.png").write_bytes(b"\x89PNG\r\n\x1a\n" + MARK + b" id_rsa")
    (outside / "secret.stl").write_bytes(cube_stl(2.0, MARK))  # a big cube: it shows
    (outside / "evil.mtl").write_bytes(b"# " + MARK + b"\nnewmtl skin\nKd 1 0 0\n")
    (meshes / "linked.stl").symlink_to(outside / "secret.stl")
    (meshes / "linked.png").symlink_to(outside / "secret.png")
    (meshes / "cube.stl").write_bytes(cube_stl(0.05, b"inside"))
    (meshes / "quad.obj").write_text(OBJ.format(outside=outside))
    (meshes / "local.mtl").write_text(f"newmtl skin\nKd 1 1 1\nmap_Kd {outside}/secret.png\n"
                                      "map_Ks ../../outside/secret.png\nmap_Ka linked.png\n")
    (root / "pkg" / "package.xml").write_text(PACKAGE_XML)
    robot = urdf / "robot.urdf"
    robot.write_text(ROBOT.format(outside=outside))
    return robot


@pytest.fixture
def robot(tmp_path) -> Path:
    return _attack(tmp_path)


def test_check_refuses_every_form_at_its_line(run_mcar, robot):
    package = robot.parents[1]
    plain = run_mcar("check", "urdf/robot.urdf", cwd=package)
    assert plain.returncode == 0, plain.stderr
    found = [line for line in plain.stderr.splitlines() if line.endswith("[W215]")]
    assert [int(line.split(":")[1]) for line in found] == REFUSED_LINES
    assert all(line.startswith("urdf/robot.urdf:") and ": warning: " in line
               for line in found)
    outside = robot.parents[2] / "outside"
    assert found[0] == (
        f"urdf/robot.urdf:5: warning: texture 'file://{outside}/secret.png' is outside the "
        f"folders a robot may name files in: {package}, {_bundled()}; --asset-path DIR (or "
        "assets.paths in the package's mcar.yaml) allows one; not read [W215]")
    assert f"(it leads to {outside}/secret.stl)" in found[6]  # the link is followed
    strict = run_mcar("check", "--strict", "urdf/robot.urdf", cwd=package)
    assert strict.returncode == 1
    assert [line for line in strict.stderr.splitlines() if "[W215]" in line] == found


def test_asset_path_allows_the_folder(run_mcar, robot):
    """The control: with the secret's folder allowed, nothing is W215 any more."""
    package = robot.parents[1]
    result = run_mcar("check", "--asset-path", "../outside", "urdf/robot.urdf", cwd=package)
    assert result.returncode == 0
    assert "W215" not in result.stderr
    assert [line.split(":")[1] for line in result.stderr.splitlines() if "W207" in line] \
        == ["15", "16", "18"]  # a package:// path leaving its package, as before


def _bundled() -> Path:
    from mobile_car.packages.bundled import description_dir

    return description_dir().resolve()


FORMATS = ["urdf", "mjcf"] + (["usd"] if importlib.util.find_spec("urdf_usd_converter")
                              else [])


@pytest.mark.parametrize("to", FORMATS)
def test_no_export_holds_a_byte_of_a_file_outside(run_mcar, robot, to):
    package = robot.parents[1]
    result = run_mcar("export", "urdf/robot.urdf", "--to", to, "-o", "out", cwd=package)
    assert result.returncode == 0, result.stderr
    assert (package / "out" / "mcar-export.json").is_file()
    assert files_holding(package / "out", MARK) == []
    assert "is outside the folders a robot may name files in" in result.stderr
    # the copy of the OBJ and its .mtl name only what the folder holds
    copied = {p.name: p.read_text() for p in (package / "out").rglob("*")
              if p.suffix in (".obj", ".mtl")}
    if to == "urdf":
        assert copied["quad.obj"].count("mtllib") == 1 and "mtllib local.mtl" in \
            copied["quad.obj"]
        assert "map_" not in copied["local.mtl"] and "outside" not in copied["local.mtl"]


def test_control_an_allowed_folder_is_exported(run_mcar, robot):
    """Without the boundary (its folder allowed) the same robot's export holds the secret:
    the test above would see it."""
    package = robot.parents[1]
    result = run_mcar("export", "urdf/robot.urdf", "--to", "urdf", "-o", "out",
                      "--asset-path", "../outside", cwd=package)
    assert result.returncode == 0, result.stderr
    assert files_holding(package / "out", MARK)


def test_a_picture_draws_a_refused_mesh_as_a_missing_one(run_mcar, robot):
    """The secret cube (2 m) would fill the picture: drawn as if it were missing instead,
    and the render's record stamps no file outside."""
    package, outside = robot.parents[1], robot.parents[2] / "outside"
    args = ("render", "urdf/robot.urdf", "--renderer", "raycast", "--size", "64x64")
    refused = run_mcar(*args, "-o", "refused/", cwd=package)
    assert refused.returncode == 0, refused.stderr
    assert [int(line.split(":")[1]) for line in refused.stderr.splitlines()
            if line.endswith("[W215]")] == REFUSED_LINES  # said with the picture
    allowed = run_mcar(*args, "-o", "allowed/", "--asset-path", "../outside", cwd=package)
    assert allowed.returncode == 0, allowed.stderr
    secret = (outside / "secret.stl").read_bytes()
    (outside / "secret.stl").unlink()
    missing = run_mcar(*args, "-o", "missing/", cwd=package)
    assert missing.returncode == 0, missing.stderr
    (outside / "secret.stl").write_bytes(secret)
    picture = "robot.png"
    assert (package / "refused" / picture).read_bytes() == \
        (package / "missing" / picture).read_bytes()
    assert (package / "refused" / picture).read_bytes() != \
        (package / "allowed" / picture).read_bytes()
    # the render's record stamps (and so hashed) the files read: none outside
    record = json.loads((package / "refused" / ".mcar-render.json").read_text())
    stamped = [entry[0] for entry in record["outputs"][picture]["files"]]
    assert stamped and not [name for name in stamped if str(outside) in name]
    assert all(name.startswith(str(package)) for name in stamped)
    assert files_holding(package / "refused", MARK) == []


def _ci_package(root: Path, yaml: str) -> Path:
    robot = _attack(root)
    package = robot.parents[1]
    (package / "mcar.yaml").write_text(yaml)
    return package


CI_ROBOT = """<?xml version="1.0"?>
<robot name="atk">
  <link name="base">
    <visual><geometry><mesh filename="file://{outside}/secret.stl"/></geometry>
      <material name="a"><texture filename="file://{outside}/secret.png"/></material>
    </visual>
    <visual><geometry><box size="0.1 0.1 0.1"/></geometry>
      <material name="b"><texture filename="../../outside/secret.png"/></material>
    </visual>
  </link>
</robot>
"""


def test_ci_with_export_fails_strict_and_copies_nothing(run_mcar, tmp_path):
    """The CI attack rebuilt: the pull request's mcar.yaml asks for an export of a robot
    that names files outside and is otherwise clean (main passed it under --strict)."""
    package = _ci_package(tmp_path, "export: {formats: [urdf]}\n")
    (package / "urdf" / "robot.urdf").write_text(CI_ROBOT.format(outside=tmp_path / "outside"))
    strict = run_mcar("ci", "--strict", cwd=package)
    assert strict.returncode == 1
    assert [line.split(":")[1] for line in strict.stderr.splitlines()
            if line.endswith("[W215]")] == ["4", "5", "8"]
    assert "FAILED (check)" in strict.stdout
    assert files_holding(package, MARK) == []
    lenient = run_mcar("ci", cwd=package)  # warnings pass: exported, without the secret
    assert lenient.returncode == 0, lenient.stdout + lenient.stderr
    assert list((package / "build").rglob("mcar-export.json"))
    assert files_holding(package, MARK) == []
    # the control: the same folders allowed, the export holds the secret
    allowed = run_mcar("ci", "--strict", "--asset-path", "..", cwd=package)
    assert allowed.returncode == 0, allowed.stdout + allowed.stderr
    assert files_holding(package / "build", MARK)


def test_mcar_yaml_may_allow_a_folder_inside_its_repository(run_mcar, tmp_path):
    repository = tmp_path / "repo"
    package = _ci_package(repository, "assets:\n  paths: [../outside]\n")
    (repository / ".git").mkdir()
    result = run_mcar("check", "urdf/robot.urdf", cwd=package)
    assert result.returncode == 0, result.stderr
    assert "W215" not in result.stderr
    # what stays refused is a package:// path leaving its package, as before (W207)
    assert [line.split(":")[1] for line in result.stderr.splitlines() if "W207" in line] \
        == ["15", "16", "18"]


@pytest.mark.parametrize("named, why", [
    ("../outside", "'../outside' leads to {outside}, outside {package}"),
    ("{outside}", "'{outside}' is absolute; name a folder relative to the package, inside "
                  "{package}"),
    ("meshes/out", "'meshes/out' leads to {outside}, outside {package}"),  # a link out
])
def test_mcar_yaml_may_not_allow_a_folder_outside(run_mcar, tmp_path, named, why):
    """In CI the pull request writes mcar.yaml: it cannot open the runner's folders."""
    package = _ci_package(tmp_path, "")
    outside = tmp_path / "outside"
    (package / "meshes" / "out").symlink_to(outside)
    (package / "mcar.yaml").write_text(
        f"ci:\n  strict: true\nassets:\n  paths: [{named.format(outside=outside)}]\n")
    for args in (("check", "urdf/robot.urdf"), ("ci",)):
        result = run_mcar(*args, cwd=package)
        assert result.returncode == 2, result.stderr
        message = why.format(outside=outside, package=package)
        assert f"{package / 'mcar.yaml'}:4: error: assets.paths: {message} " \
               "(--asset-path names any folder)" in result.stderr.splitlines()
    assert files_holding(package, MARK) == []


@pytest.mark.parametrize("workspace", [True, False], ids=["in-ci", "control"])
def test_a_git_folder_above_the_ci_workspace_does_not_widen_mcar_yaml(run_mcar, tmp_path,
                                                                      workspace):
    """A checkout without a .git of its own (a downloaded archive) inside a folder kept in
    git: the repository mcar.yaml may name stops at the CI job's workspace. The control
    shows that without the workspace variable the parent repository is taken."""
    (tmp_path / ".git").mkdir()
    package = _ci_package(tmp_path / "work" / "checkout", "assets:\n  paths: [../../outside]\n")
    env = {"GITHUB_WORKSPACE": str(package.parent)} if workspace else {}
    result = run_mcar("check", "urdf/robot.urdf", cwd=package, env=env)
    if workspace:
        assert result.returncode == 2, result.stderr
        assert (f"{package / 'mcar.yaml'}:2: error: assets.paths: '../../outside' leads to "
                f"{tmp_path / 'work' / 'outside'}, outside {package.parent} (--asset-path "
                "names any folder)") in result.stderr.splitlines()
    else:
        assert result.returncode == 0, result.stderr


def test_a_urdf_on_stdin_is_held_to_the_working_folder_s_roots(run_mcar, robot):
    """Relative names start at the working folder (here in the package): the same W215s."""
    result = run_mcar("check", "-", input=robot.read_text(), cwd=robot.parent)
    assert result.returncode == 0, result.stderr
    found = [line for line in result.stderr.splitlines() if line.endswith("[W215]")]
    assert [int(line.split(":")[1]) for line in found] == REFUSED_LINES
    assert all(line.startswith("<stdin>:") for line in found)
    assert f"may name files in: {robot.parents[1]}, " in found[0]


def test_asset_paths_do_not_widen_what_a_sandboxed_xacro_reads(robot):
    """--asset-path is for meshes and textures: the Landlock roots of a xacro stay the
    package roots."""
    from mobile_car.packages.search import PackageSearch

    outside = robot.parents[2] / "outside"
    search = PackageSearch(origin=robot, environ={}, asset_paths=[outside])
    assert outside not in search.read_roots()
    assert outside in search.allowed_roots()
    assert search.resolve_uri(f"file://{outside}/secret.png") == outside / "secret.png"


@pytest.mark.skipif(shutil.which("roslaunch") is None, reason="ROS 1's roslaunch is not "
                    "installed")
def test_rviz_is_not_given_a_robot_naming_files_outside(run_mcar, robot):
    """RViz follows file:// and links itself: it would read what mcar refused."""
    result = run_mcar("view", "--rviz", "urdf/robot.urdf", cwd=robot.parents[1])
    assert result.returncode == 1
    assert result.stderr.splitlines()[-1] == (
        "urdf/robot.urdf: error: not opened in RViz: 9 files outside the folders a robot "
        "may name files in (W215 above), which RViz would read")
    assert result.stdout == ""  # roslaunch never ran


XACRO = """<?xml version="1.0"?>
<robot name="atk" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base">
    <visual><geometry><mesh filename="file://{outside}/secret.stl"/></geometry></visual>
  </link>
</robot>
"""


def test_a_kept_check_is_not_replayed_once_the_folder_is_no_longer_allowed(run_mcar,
                                                                            tmp_path):
    """mcar check keeps what it found of a xacro robot and replays it while its files are
    unchanged: what was allowed (--asset-path, mcar.yaml's assets.paths) is part of that."""
    repository = tmp_path / "repo"
    package = _ci_package(repository, "")
    (repository / ".git").mkdir()
    robot = package / "urdf" / "robot.urdf.xacro"
    robot.write_text(XACRO.format(outside=repository / "outside"))
    env = {"XDG_CACHE_HOME": str(tmp_path / "cache")}

    def warned(*args):
        result = run_mcar("check", *args, "urdf/robot.urdf.xacro", cwd=package, env=env)
        assert result.returncode == 0, result.stderr
        return "[W215]" in result.stderr

    assert not warned("--asset-path", "../outside")
    assert warned()  # the same files, without the folder: checked again, refused
    (package / "mcar.yaml").write_text("assets:\n  paths: [../outside]\n")
    assert not warned()
    assert not warned()  # replayed
    (package / "mcar.yaml").write_text("")
    assert warned()  # mcar.yaml was stamped with the run it allowed
