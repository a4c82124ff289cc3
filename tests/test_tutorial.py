"""The tutorial car of seed 001, step by step, checked by the real check_urdf."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from conftest import REPO, run_check_urdf

TUTORIAL = REPO / "urdf" / "tutorial"
# The tree the seed shows for 01_skeleton.urdf, with its OCR damage cleaned.
SEED_TREE = """\
robot name is: test_robot
---------- Successfully Parsed XML ---------------
root Link: base_link has 4 child(ren)
    child(1):  wheel_1
    child(2):  wheel_2
    child(3):  wheel_3
    child(4):  wheel_4
"""


@pytest.mark.parametrize("name", ["01_skeleton.urdf", "02_visual.urdf", "03_color.urdf"])
def test_tutorial_urdf_steps_print_the_seed_tree(name, check_urdf):
    result = run_check_urdf(check_urdf, TUTORIAL / name)
    assert result.returncode == 0, result.stderr
    assert result.stdout == SEED_TREE


def test_built_xacro_step_prints_the_seed_tree_through_a_pipe(mcar_bin, check_urdf):
    # The README's one-liner: mcar build urdf/tutorial/04_xacro.xacro | check_urdf /dev/stdin
    command = f"'{mcar_bin}' build urdf/tutorial/04_xacro.xacro | '{check_urdf}' /dev/stdin"
    result = subprocess.run(["bash", "-o", "pipefail", "-c", command], cwd=REPO,
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    assert result.stdout == SEED_TREE


def test_xacro_step_matches_the_colour_step(run_mcar):
    """04_xacro.xacro is 03_color.urdf written with xacro: same links, shapes, colours."""
    from lxml import etree

    built = etree.fromstring(run_mcar("build", TUTORIAL / "04_xacro.xacro").stdout.encode())
    plain = etree.parse(str(TUTORIAL / "03_color.urdf")).getroot()

    def summary(robot):
        out = {}
        for link in robot.iter("link"):
            geometry = link.find("visual/geometry/*")
            origin = link.find("visual/origin")
            xyz = [float(v) for v in origin.get("xyz").split()]
            rpy = [round(float(v), 4) for v in origin.get("rpy").split()]
            out[link.get("name")] = (geometry.tag, dict(geometry.attrib), xyz, rpy,
                                     link.find("visual/material").get("name"))
        return out

    assert summary(built) == summary(plain)
    colours = {m.get("name"): m.find("color").get("rgba")
               for m in built.iter("material") if m.find("color") is not None}
    assert colours == {"white": "1 1 1 1", "black": "0 0 0 1"}


def test_tutorial_files_exist():
    names = sorted(p.name for p in TUTORIAL.iterdir())
    assert names == ["01_skeleton.urdf", "02_visual.urdf", "03_color.urdf", "04_xacro.xacro"]
    assert Path(TUTORIAL / "02_visual.urdf").read_text().count('<box size="0.2 0.3 0.1"/>') == 1
