"""A description may not name mcar's own cache folder, where the record key lives.

Found by the attack pass on issue 39: a CI job that restores its cache inside the workspace
(``MCAR_CACHE_DIR=$PWD/.cache/mcar``, as actions/cache users often do) puts the record key
inside the package. A texture naming it, with ``export:`` in the pull request's mcar.yaml,
copied the key byte for byte into build/exports/, the folder CI uploads; with the key a
later pull request on a restored cache can seal records that replay "passed". The name must
be W215 at its line and the key in no output; the control names the same bytes in a folder
that is not the cache, and sees them exported.
"""

from __future__ import annotations

from pathlib import Path

from hostile import PACKAGE_XML, files_holding

ROBOT = """<?xml version="1.0"?>
<robot name="atk">
  <link name="foot"/>
  <joint name="j" type="fixed"><parent link="foot"/><child link="base"/></joint>
  <link name="base">
    <visual><geometry><box size="0.1 0.1 0.1"/></geometry>
      <material name="a"><texture filename="package://atk/{folder}/record-key"/></material>
    </visual>
    <inertial><mass value="1"/>
      <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
</robot>
"""
KEY = b"MCAR-KEY-BYTES-9f3c1a27-not-a-picture"


def _package(root: Path, folder: str) -> Path:
    (root / "urdf").mkdir(parents=True)
    (root / "package.xml").write_text(PACKAGE_XML)
    (root / "urdf" / "robot.urdf").write_text(ROBOT.format(folder=folder))
    (root / "mcar.yaml").write_text("export: {formats: [urdf]}\n")
    (root / folder).mkdir(parents=True)
    (root / folder / "record-key").write_bytes(KEY)
    return root


def test_a_texture_naming_the_cache_folder_is_refused_and_not_exported(run_mcar, tmp_path):
    package = _package(tmp_path / "repo", "cache/mcar")
    cache = {"MCAR_CACHE_DIR": str(package / "cache" / "mcar")}
    strict = run_mcar("ci", "--strict", "--no-render", "--no-sim", cwd=package, env=cache)
    assert strict.returncode == 1, strict.stdout + strict.stderr
    assert (f"urdf/robot.urdf:7: warning: texture 'package://atk/cache/mcar/record-key' "
            f"lies in mcar's own cache folder ({package}/cache/mcar), which holds the key "
            "that seals its records, not the robot's files; not read [W215]"
            ) in strict.stderr.splitlines()
    lenient = run_mcar("ci", "--no-render", "--no-sim", cwd=package, env=cache)
    assert lenient.returncode == 0, lenient.stdout + lenient.stderr
    assert (package / "build" / "exports").is_dir()
    assert files_holding(package / "build", KEY) == []


def test_control_the_same_bytes_elsewhere_in_the_package_are_exported(run_mcar, tmp_path):
    package = _package(tmp_path / "repo", "textures")
    result = run_mcar("ci", "--strict", "--no-render", "--no-sim", cwd=package,
                      env={"MCAR_CACHE_DIR": str(tmp_path / "cache")})
    assert result.returncode == 0, result.stdout + result.stderr
    assert files_holding(package / "build", KEY) != []
