"""The contact sheet captions every picture by one rule, whichever command drew it: after
`mcar ci` then `mcar render wheel chassis`, index.png is the sheet `mcar render` alone
draws (issue 14: it mixed "chassis/steps/01_plate" with "laser/test_laser.urdf.xacro")."""

from __future__ import annotations

import json
import shutil

from conftest import REPO


def _package(folder):
    for name in ("urdf", "meshes"):
        shutil.copytree(REPO / name, folder / name)
    shutil.copy(REPO / "package.xml", folder / "package.xml")
    return folder


def test_sheet_is_the_same_whichever_command_drew_the_pictures(run_mcar, tmp_path):
    ci_only = _package(tmp_path / "ci_only")
    mixed = _package(tmp_path / "mixed")
    for folder in (ci_only, mixed):
        # (what is drawn is the point: the sim and Gazebo steps are left out; the default
        # renderer, GL where it works, draws in a third of the ray caster's time)
        ci = run_mcar("ci", "--no-sim", "--no-gazebo", cwd=folder, timeout=600)
        assert ci.returncode == 0, ci.stderr
    again = run_mcar("render", "wheel", "chassis", "--force",
                     cwd=mixed, timeout=600)
    assert again.returncode == 0, again.stderr
    assert again.stdout.count("rendered") or again.stderr  # it did draw
    manifest = json.loads((mixed / "renders" / ".mcar-render.json").read_text())
    assert "wheel/test_wheel.png" in manifest["outputs"]
    # The same pictures, redrawn by another command: the same sheet, captions and all.
    for key in manifest["outputs"]:
        drawn = (mixed / "renders" / key).read_bytes()
        assert drawn == (ci_only / "renders" / key).read_bytes(), key
