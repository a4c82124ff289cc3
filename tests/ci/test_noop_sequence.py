"""After one full `mcar ci`, build, check, render and ci with nothing changed are no-ops for
each other in any order: each decides from the stamps alone (no xacro, lxml, numpy or GL
imported), writes no file, and render and ci keep the same contact sheet (ci's variant
pictures included). Before, each command's run made the other's record stale: render forgot
ci's variant pictures, so the next ci built and drew them again (3.1 s), render then redrew
the sheet (1.2 s), and build expanded and wrote every file each time."""

from __future__ import annotations

import os
import subprocess
import sys

HEAVY = {"xacro", "lxml", "numpy", "trimesh", "moderngl", "yourdfpy", "mujoco"}
MAIN = "import sys; from mobile_car.cli.main import main; sys.argv[0] = 'mcar'; main()"


def files(package):
    return {p.relative_to(package).as_posix(): (p.stat().st_mtime_ns, p.stat().st_ino)
            for folder in ("build", "renders") for p in (package / folder).rglob("*")
            if p.is_file()}


def traced(*args, cwd):
    env = {k: v for k, v in os.environ.items()
           if k not in ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH")}
    done = subprocess.run([sys.executable, "-X", "importtime", "-c", MAIN, *args], cwd=cwd,
                          env=env, capture_output=True, text=True, timeout=300)
    names = {line.split("|")[-1].strip() for line in done.stderr.splitlines()
             if line.startswith("import time:") and "|" in line}
    imported = names | {name.split(".")[0] for name in names}
    said = [line for line in done.stderr.splitlines() if not line.startswith("import time:")]
    return done.returncode, imported, said


def test_render_and_ci_are_no_ops_for_each_other(run_mcar, package_copy):
    full = run_mcar("ci", cwd=package_copy, timeout=300)
    assert full.returncode == 0, full.stderr
    before = files(package_copy)
    assert any(name.startswith("renders/variants/") for name in before)
    for command in ("render", "ci", "check", "build", "render", "render", "check", "build", "ci",
                    "ci", "render", "check", "build"):
        code, imported, said = traced(command, cwd=package_copy)
        assert code == 0, said
        # check reads the tutorial's plain URDFs again (lxml): no expansion, though
        heavy = HEAVY - {"lxml"} | {"mobile_car.expand.xacro_build"} if command == "check" \
            else HEAVY
        assert imported & heavy == set(), (command, imported & heavy)
        assert files(package_copy) == before, command
        if command == "render":
            assert said[-1].startswith("13 pictures in renders: 0 rendered, 13 unchanged"), said
        elif command == "build":
            assert said[-1] == "13 of 13 files built into build (13 unchanged)", said
        elif command == "check":  # ci's check of each file is check's too
            assert said[0].startswith("mcar: package mobile_car_description"), said
            # every file but the tutorial skeleton (no shapes) has a size
            assert len([line for line in said if ": size: " in line]) == 12, said
        else:
            assert said[-1].startswith("mcar ci: 15 of 15 files passed"), said


def test_a_change_rebuilds_exactly_what_depends_on_it(run_mcar, package_copy):
    assert run_mcar("ci", cwd=package_copy, timeout=300).returncode == 0
    before = files(package_copy)
    wheel = package_copy / "urdf" / "wheel" / "wheel.xacro"
    wheel.write_text(wheel.read_text().replace("<!--", "<!-- edited:", 1))  # same robot
    built = run_mcar("build", cwd=package_copy)
    assert built.returncode == 0, built.stderr
    changed = {name for name, stamp in files(package_copy).items() if before[name] != stamp}
    # the files that include the wheel macro were expanded and written again; no other
    assert changed == {"build/wheel/test_wheel.urdf", "build/mobile_robot.urdf",
                       "build/.mcar-build.json"}, changed
    assert "13 of 13 files built into build (11 unchanged)" in built.stderr


def test_a_deleted_robot_file_leaves_the_contact_sheet_of_both(run_mcar, package_copy):
    assert run_mcar("ci", cwd=package_copy, timeout=300).returncode == 0
    (package_copy / "urdf" / "tutorial" / "02_visual.urdf").unlink()
    sheet = (package_copy / "renders" / "index.png").stat().st_mtime_ns
    assert run_mcar("render", cwd=package_copy).returncode == 0
    after_render = (package_copy / "renders" / "index.png").stat().st_mtime_ns
    assert after_render != sheet  # redrawn without the deleted robot's picture
    manifest = (package_copy / "renders" / ".mcar-render.json").read_text()
    assert "tutorial/02_visual.png" not in manifest
    code, imported, _ = traced("ci", cwd=package_copy)
    assert code == 0 and "xacro" not in imported  # the rest is replayed
    assert (package_copy / "renders" / "index.png").stat().st_mtime_ns == after_render
