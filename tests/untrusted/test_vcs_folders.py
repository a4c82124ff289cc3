"""A description may not get its checkout's ``.git`` folder into an export.

The attack, found after issue 39 was merged: a package at the root of its repository (as
most are: package.xml beside .git) names ``package://pkg/.git/config`` as a texture, or
``../.git/config`` from its urdf/ folder, or an OBJ at the root names it as its material
library. Every one of those lies inside the package, so the resolver allowed it, and
``mcar ci --strict`` with ``export:`` in the pull request's mcar.yaml passed and copied the
file into build/exports/, the folder CI uploads. On GitHub, ``actions/checkout`` keeps the
job's token in that file (``http.<url>.extraheader``). Each form must now be W215 at its
line and absent from every output; the controls name the same bytes in a folder called
``git`` (no dot): exported, so the tests can see a copy.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from hostile import PACKAGE_XML, files_holding

MARK = b"MCAR-TOKEN-5d1e0b"  # the "token": what must never reach an output
ROBOT = """<?xml version="1.0"?>
<robot name="atk">
  <link name="foot"/>
  <joint name="j" type="fixed"><parent link="foot"/><child link="base"/></joint>
  <link name="base">
    <visual><geometry><box size="0.1 0.1 0.1"/></geometry>
      <material name="a"><texture filename="package://atk/{vcs}/config"/></material>
    </visual>
    <visual><geometry><box size="0.1 0.1 0.1"/></geometry>
      <material name="b"><texture filename="../{vcs}/config"/></material>
    </visual>
    <visual><geometry><mesh filename="package://atk/quad.obj"/></geometry></visual>
    <inertial><mass value="1"/>
      <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
</robot>
"""
OBJ = """mtllib {vcs}/config
mtllib local.mtl
v 0 0 0
v 0.1 0 0
v 0 0.1 0
v 0 0 0.1
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
"""


def _checkout(root: Path, vcs: str) -> Path:
    """A repository whose root is the package, its token in ``vcs``/config: the root."""
    (root / vcs).mkdir(parents=True)
    (root / vcs / "config").write_bytes(
        b'[http "https://github.com/"]\n\textraheader = AUTHORIZATION: basic ' + MARK + b"\n")
    (root / "urdf").mkdir()
    (root / "package.xml").write_text(PACKAGE_XML)
    (root / "urdf" / "robot.urdf").write_text(ROBOT.format(vcs=vcs))
    (root / "quad.obj").write_text(OBJ.format(vcs=vcs))
    (root / "local.mtl").write_text(f"newmtl skin\nKd 1 1 1\nmap_Kd {vcs}/config\n")
    (root / "mcar.yaml").write_text("export: {formats: [urdf]}\n")
    return root


def test_ci_strict_refuses_the_checkout_s_git_folder(run_mcar, tmp_path):
    package = _checkout(tmp_path / "repo", ".git")
    strict = run_mcar("ci", "--strict", cwd=package)
    assert strict.returncode == 1, strict.stdout + strict.stderr
    refused = [line for line in strict.stderr.splitlines() if line.endswith("[W215]")]
    assert refused == [
        f"urdf/robot.urdf:7: warning: texture 'package://atk/.git/config' lies in a "
        f"version-control folder ({package}/.git/config), which holds the checkout's "
        "files, not the robot's; not read [W215]",
        f"urdf/robot.urdf:10: warning: texture '../.git/config' lies in a version-control "
        f"folder ({package}/.git/config), which holds the checkout's files, not the "
        "robot's; not read [W215]"]
    lenient = run_mcar("ci", cwd=package)  # warnings pass: exported, without the token
    assert lenient.returncode == 0, lenient.stdout + lenient.stderr
    exported = package / "build" / "exports" / "robot" / "urdf"
    assert (exported / "mcar-export.json").is_file()
    assert [p for p in files_holding(package, MARK) if not p.startswith(".git/")] == []
    # the OBJ and its .mtl are copied naming only what the folder holds
    copied = {p.name: p.read_text() for p in exported.rglob("*") if p.suffix in (".obj", ".mtl")}
    assert ".git" not in copied["quad.obj"] and "mtllib local.mtl" in copied["quad.obj"]
    assert "map_" not in copied["local.mtl"]


def test_control_the_same_bytes_outside_a_git_folder_are_exported(run_mcar, tmp_path):
    """Without the boundary (the folder not one of version control) the same robot's
    export holds the token three ways: the test above would see them."""
    package = _checkout(tmp_path / "repo", "git")
    result = run_mcar("ci", "--strict", cwd=package)
    assert result.returncode == 0, result.stdout + result.stderr
    assert len([p for p in files_holding(package / "build", MARK) if "config" in p]) == 3


@pytest.mark.parametrize("name", [".git", ".GIT", ".hg", ".svn"])
def test_the_resolver_refuses_every_version_control_folder(tmp_path, name):
    from mobile_car.packages.asset_roots import OutsideRootsError
    from mobile_car.packages.search import PackageSearch

    package = _checkout(tmp_path / "repo", name)
    (package / "link").symlink_to(package / name / "config")  # a link in: refused too
    search = PackageSearch(origin=package / "urdf" / "robot.urdf", environ={})
    for uri in (f"package://atk/{name}/config", f"../{name}/config", "package://atk/link",
                f"file://{package}/{name}/config"):
        with pytest.raises(OutsideRootsError, match="lies in a version-control folder"):
            search.resolve_uri(uri, package / "urdf")
    assert search.resolve_uri("package://atk/quad.obj") == package / "quad.obj"


GLTF_ROBOT = """<?xml version="1.0"?>
<robot name="atk"><link name="base">
  <visual><geometry><mesh filename="package://atk/buffer.gltf"/></geometry></visual>
  <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
  </inertial></link></robot>
"""


@pytest.mark.parametrize("vcs", [".git", "git"])  # "git": the control, exported
def test_a_gltf_buffer_in_the_git_folder_is_not_read(run_mcar, tmp_path, vcs):
    """A glTF names its buffer ``.git/config``: trimesh read the token as vertices, and the
    export (which converts glTF to STL) wrote them, byte for byte, into its STL."""
    package = _checkout(tmp_path / "repo", vcs)
    config = package / vcs / "config"
    config.write_bytes(config.read_bytes() + (MARK + b" ") * 8)  # a copy in every alignment
    size = len(config.read_bytes()) // 36 * 36  # whole triangles of float32 corners
    (package / "buffer.gltf").write_text(json.dumps({
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "buffers": [{"uri": f"{vcs}/config", "byteLength": size}],
        "bufferViews": [{"buffer": 0, "byteLength": size}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": size // 12,
                       "type": "VEC3"}]}))
    (package / "urdf" / "robot.urdf").write_text(GLTF_ROBOT)
    result = run_mcar("export", "urdf/robot.urdf", "--to", "urdf", "-o", "out", cwd=package)
    assert result.returncode == 0, result.stderr
    if vcs == "git":
        assert files_holding(package / "out", MARK) == ["meshes/atk/buffer.gltf.stl"]
        return
    assert files_holding(package / "out", MARK) == []
    assert "urdf/robot.urdf: warning: link base: visual left out: mesh " \
        "package://atk/buffer.gltf: cannot be read: .git/config" in result.stderr.splitlines()


# The sandbox's own attack (tests/expand/sandbox/read_secret.xacro) aimed at the token.
LEAK = """<?xml version="1.0"?>
<robot name="atk" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base_link"/>
  <link name="${{[g['__builtins__']['open'](xacro.abs_filename('{name}')).read().split()[-1]
    for g in [c.__init__.__globals__ for x in [()] for c in x.__class__.__base__.__subclasses__()
    if c.__name__ == '_wrap_close']][0]}}"/>
</robot>
"""


def _landlock() -> bool:
    from mobile_car.expand.sandbox import support

    return bool(support().landlock_abi)


@pytest.mark.skipif(not _landlock(), reason="the kernel offers no Landlock: a xacro's reads "
                    "are not confined here (docs/security.md)")
@pytest.mark.parametrize("vcs, name, readable", [
    (".git", "../.git/config", False),
    (".git", "../cfg", False),  # a link in the package to the token: the kernel follows it
    ("git", "../git/config", True),  # the control: the same bytes in any other folder
])
def test_a_xacro_cannot_read_its_checkout_s_git_folder(run_mcar, tmp_path, vcs, name,
                                                       readable):
    """A xacro reads below its package's root, which here holds .git: it got the token
    into the URDF mcar built (and into exports and error lines, in the CI log)."""
    package = _checkout(tmp_path / "repo", vcs)
    (package / "cfg").symlink_to(package / vcs / "config")
    (package / "urdf" / "leak.urdf.xacro").write_text(LEAK.format(name=name))
    result = run_mcar("build", "urdf/leak.urdf.xacro", "-o", "out.urdf", cwd=package)
    if readable:
        assert result.returncode == 0, result.stderr
        assert MARK in (package / "out.urdf").read_bytes()
        return
    assert result.returncode == 1
    assert result.stderr.splitlines()[0] == (
        f"urdf/leak.urdf.xacro:4: error: cannot read {name[3:]}: Permission denied (the "
        "xacro sandbox reads only below the package roots and the input's folder; "
        "--no-sandbox for a tree you trust)")
    assert not (package / "out.urdf").exists() and MARK not in result.stderr.encode()
    # the rest of the root stays readable: the package's own files beside .git
    (package / "urdf" / "ok.urdf.xacro").write_text(
        '<robot name="ok" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        "<xacro:property name=\"t\" value=\"${xacro.load_yaml('../mcar.yaml')}\"/>"
        '<link name="${sorted(t)[0]}"/></robot>')
    ok = run_mcar("build", "urdf/ok.urdf.xacro", "-o", "ok.urdf", cwd=package)
    assert ok.returncode == 0, ok.stderr
    assert b'<link name="export"/>' in (package / "ok.urdf").read_bytes()
