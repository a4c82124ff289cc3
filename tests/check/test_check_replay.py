"""`mcar check` with nothing changed reads its results back (mobile_car/check/replay.py):
the same bytes on stdout and stderr and the same exit code, with no xacro expansion (a
plain URDF, such as the tutorial's, is checked in full each time: its check costs less
than a record); a change to any file the result depends on (an included xacro, a mesh, a --config
file), to an argument, or a record not sealed by this user's mcar, checks in full."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

MAIN = "import sys; from mobile_car.cli.main import main; sys.argv[0] = 'mcar'; main()"
HEAVY = {"xacro", "numpy", "trimesh", "mobile_car.expand.xacro_build"}


def check(*args, cwd, cache):
    """(exit code, stdout, stderr without import lines, top-level modules imported)."""
    env = {k: v for k, v in os.environ.items()
           if k not in ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH")}
    env["MCAR_CACHE_DIR"] = str(cache)
    done = subprocess.run([sys.executable, "-X", "importtime", "-c", MAIN, "check", *args],
                          cwd=cwd, env=env, capture_output=True, text=True, timeout=300)
    names = {line.split("|")[-1].strip() for line in done.stderr.splitlines()
             if line.startswith("import time:") and "|" in line}
    imported = names | {name.split(".")[0] for name in names}
    said = "".join(line + "\n" for line in done.stderr.splitlines()
                   if not line.startswith("import time:"))
    return done.returncode, done.stdout, said, imported


@pytest.mark.parametrize("form", [(), ("--format", "json"), ("--format", "github"),
                                  ("--strict", "-q")], ids=["text", "json", "github", "strict"])
def test_a_second_check_prints_the_same_without_expanding(package_copy, tmp_path, form):
    cache = tmp_path / "cache"
    first = check(*form, cwd=package_copy, cache=cache)
    assert first[0] == 0, first[2]
    assert "mobile_car.expand.xacro_build" in first[3]  # the first run expanded
    again = check(*form, cwd=package_copy, cache=cache)
    assert again[:3] == first[:3]
    assert again[3] & HEAVY == set()
    if form == ("--format", "json"):
        assert len(json.loads(again[1])["files"]) == 13


def test_a_changed_include_is_checked_again(package_copy, tmp_path):
    cache = tmp_path / "cache"
    robot = "urdf/mobile_robot.xacro"
    code, before, _, _ = check(robot, "--format", "json", cwd=package_copy, cache=cache)
    assert code == 0
    config = package_copy / "urdf" / "config.xacro"
    text = config.read_text()
    assert 'name="wheel_radius"' in text
    # The extents grow with the wheels: a result read back would not show it.
    config.write_text(text.replace('name="wheel_radius" value="0.0325"',
                                   'name="wheel_radius" value="0.05"'))
    code, after, said, imported = check(robot, "--format", "json", cwd=package_copy,
                                        cache=cache)
    assert code in (0, 1), said
    assert "mobile_car.expand.xacro_build" in imported
    extents = [json.loads(out)["files"][0]["extents"] for out in (before, after)]
    assert extents[0] != extents[1]


def test_a_changed_mesh_is_checked_again(package_copy, tmp_path):
    cache = tmp_path / "cache"
    robot = "urdf/mobile_robot.xacro"
    first = check(robot, cwd=package_copy, cache=cache)
    assert first[0] == 0, first[2]
    mesh = package_copy / "meshes" / "motor.stl"
    mesh.write_bytes(b"not a mesh at all")
    again = check(robot, cwd=package_copy, cache=cache)
    assert "mobile_car.expand.xacro_build" in again[3]
    assert "[W207]" in again[2] and mesh.name in again[2]


def test_an_argument_or_config_file_is_part_of_the_question(package_copy, tmp_path):
    cache = tmp_path / "cache"
    robot = "urdf/mobile_robot.xacro"
    sizes = tmp_path / "sizes.yaml"
    sizes.write_text("wheel_radius: 40mm\n")
    plain = check(robot, "--format", "json", cwd=package_copy, cache=cache)
    configured = check(robot, "--format", "json", "--config", sizes, cwd=package_copy,
                       cache=cache)
    assert "mobile_car.expand.xacro_build" in configured[3]
    assert json.loads(plain[1])["files"][0]["extents"] != \
        json.loads(configured[1])["files"][0]["extents"]
    sizes.write_text("wheel_radius: 45mm\n")
    edited = check(robot, "--format", "json", "--config", sizes, cwd=package_copy,
                   cache=cache)
    assert "mobile_car.expand.xacro_build" in edited[3]
    assert json.loads(edited[1])["files"][0]["extents"] != \
        json.loads(configured[1])["files"][0]["extents"]


def test_a_record_not_sealed_by_this_user_is_not_read(package_copy, tmp_path):
    cache = tmp_path / "cache"
    robot = "urdf/mobile_robot.xacro"
    assert check(robot, cwd=package_copy, cache=cache)[0] == 0
    [record] = (cache / "checks").glob("*.json")
    document = json.loads(record.read_text())
    [entry] = document["checks"].values()
    entry["diagnostics"] = [["E104", "forged.urdf", 1, "planted"]]
    record.write_text(json.dumps(document))
    code, _, said, imported = check(robot, cwd=package_copy, cache=cache)
    assert code == 0 and "planted" not in said
    assert "mobile_car.expand.xacro_build" in imported
