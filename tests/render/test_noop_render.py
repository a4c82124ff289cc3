"""A no-op `mcar render` decides from file stamps: nothing loaded, nothing written; a
changed input redraws exactly the pictures made from it."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

PKG = Path(__file__).parent / "pkg"
REPO = Path(__file__).parents[2]
SMALL = ("--size", "160x120")
HEAVY = ("xacro", "lxml", "numpy", "trimesh", "moderngl", "yourdfpy", "PIL.Image")
# `mcar ARGS` in a fresh interpreter, from the installed package (as the mcar script runs).
MAIN = "import sys; from mobile_car.cli.main import main; sys.argv[0] = 'mcar'; main()"


@pytest.fixture
def pkg_copy(tmp_path) -> Path:
    copy = tmp_path / "render_test_parts"
    shutil.copytree(PKG, copy)
    return copy


def stamps(folder: Path) -> dict[str, int]:
    return {p.relative_to(folder).as_posix(): p.stat().st_mtime_ns
            for p in sorted(folder.rglob("*")) if p.is_file()}


def redrawn(before: dict[str, int], folder: Path) -> set[str]:
    after = stamps(folder)
    return {name for name in after if name.endswith(".png") and name != "index.png"
            and after[name] != before.get(name)}


def imported_modules(stderr: str) -> set[str]:
    """The top-level modules `python -X importtime` reports as imported."""
    return {line.split("|")[-1].strip() for line in stderr.splitlines()
            if line.startswith("import time:") and "|" in line}


def run_traced(*args, cwd: Path):
    env = {k: v for k, v in os.environ.items()
           if k not in ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH")}
    return subprocess.run([sys.executable, "-X", "importtime", "-c", MAIN, *map(str, args)],
                          cwd=cwd, env=env, capture_output=True, text=True, timeout=120)


def test_a_no_op_render_imports_nothing_heavy_and_writes_nothing(
        run_mcar, pkg_copy, tmp_path, quiet_renderer):
    first = run_mcar("render", pkg_copy, *SMALL, *quiet_renderer, cwd=tmp_path)
    assert first.returncode == 0, first.stderr
    before = stamps(tmp_path / "renders")

    again = run_traced("render", pkg_copy, *SMALL, *quiet_renderer, cwd=tmp_path)
    assert again.returncode == 0, again.stderr
    shown = [line for line in again.stderr.splitlines() if not line.startswith("import time:")]
    assert len(shown) == 1 and re.fullmatch(
        r"5 pictures in renders: 0 rendered, 5 unchanged \+ renders/index\.png "
        r"\(\d+\.\d\d s\)", shown[0]), shown
    modules = imported_modules(again.stderr)
    assert "mobile_car.render.manifest" in modules  # the trace does list mcar's modules
    assert not {m for m in modules if m.split(".")[0] in HEAVY or m in HEAVY}
    assert stamps(tmp_path / "renders") == before  # not even the manifest is rewritten


def test_editing_one_macro_file_redraws_exactly_the_pictures_that_include_it(
        cli, pkg_copy, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    renders = tmp_path / "renders"
    assert cli("render", pkg_copy, *SMALL).exit_code == 0
    manifest = json.loads((renders / ".mcar-render.json").read_text())
    wheel = str(pkg_copy / "urdf/wheel/wheel.xacro")
    users = {name for name, entry in manifest["outputs"].items()
             if any(stamp[0] == wheel for stamp in entry.get("files") or [])}
    assert users == {"chassis/test_chassis.png", "wheel/test_wheel.png"}

    # Touched, bytes unchanged: hashed again, nothing drawn.
    before = stamps(renders)
    os.utime(pkg_copy / "urdf/wheel/wheel.xacro")
    assert "5 pictures in renders: 0 rendered, 5 unchanged" in cli(
        "render", pkg_copy, *SMALL).stderr
    assert redrawn(before, renders) == set()

    source = pkg_copy / "urdf/wheel/wheel.xacro"
    source.write_text(source.read_text().replace('length="${width}"', 'length="${2 * width}"', 1))
    before = stamps(renders)
    result = cli("render", pkg_copy, *SMALL)
    assert "5 pictures in renders: 2 rendered, 3 unchanged" in result.stderr
    assert redrawn(before, renders) == users


def test_a_mesh_an_option_or_another_mcar_version_redraws(cli, pkg_copy, tmp_path,
                                                          monkeypatch):
    monkeypatch.chdir(tmp_path)
    renders = tmp_path / "renders"
    assert cli("render", pkg_copy, *SMALL).exit_code == 0
    before = stamps(renders)
    stl = pkg_copy / "meshes/motor.stl"
    stl.write_bytes(b"Y" + stl.read_bytes()[1:])  # same shape, another header byte
    assert "1 rendered, 4 unchanged" in cli("render", pkg_copy, *SMALL).stderr
    assert redrawn(before, renders) == {"motor/test_motor.png"}

    assert "5 rendered" in cli("render", pkg_copy, "--size", "161x120").stderr
    assert "0 rendered, 5 unchanged" in cli("render", pkg_copy, "--size", "161x120").stderr

    import mobile_car.freshness

    monkeypatch.setattr(mobile_car.freshness, "__version__", "999.0.0")
    assert "5 rendered" in cli("render", pkg_copy, "--size", "161x120").stderr


def test_overrides_config_files_and_package_search_are_part_of_the_key(
        cli, package_copy, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    wheel = package_copy / "urdf/wheel/test_wheel.urdf.xacro"
    out = tmp_path / "out" / "wheel.png"

    def render(*args):
        result = cli("render", wheel, "-o", out, *SMALL, *args)
        assert result.exit_code == 0, result.output
        return result.stderr

    assert "1 rendered" in render()
    assert "0 rendered, 1 unchanged" in render()
    assert "1 rendered" in render("--set", "wheel_radius=40mm")
    assert "0 rendered, 1 unchanged" in render("--set", "wheel_radius=40mm")
    config = tmp_path / "big.yaml"
    config.write_text("wheel_radius: 0.05\n")
    assert "1 rendered" in render("--config", config)
    assert "0 rendered, 1 unchanged" in render("--config", config)
    config.write_text("wheel_radius: 0.06\n")
    assert "1 rendered" in render("--config", config)

    # Another package search may find other files: the picture is judged by loading it
    # (here the same robot comes out, so it is not drawn again, only stamped anew).
    manifest = tmp_path / "out" / ".mcar-render.json"
    key = json.loads(manifest.read_text())["outputs"]["wheel.png"]["key"]
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path))
    assert "0 rendered, 1 unchanged" in render("--config", config)
    assert json.loads(manifest.read_text())["outputs"]["wheel.png"]["key"] != key
