"""The two ways to the rest pose give the same size and the same warnings.

A robot of checker.LARGE_ROBOT links or more has its rest pose worked out with numpy
(mobile_car/check/rest_pose_arrays.py), a smaller one link by link in Python
(rest_pose.py). Each robot here is checked both ways, the threshold moved, and the
extents and diagnostics must agree: robots generated with inertias from a thousandth to a
thousand times their shape's (wheels among them, turned about their own axis or another),
meshes in millimetres and scaled twice, the benchmark's generated trees and chains, and
the corpus's plausibility cases.
"""

from __future__ import annotations

import json
import random
import sys
from pathlib import Path

import pytest
from conftest import REPO

from mobile_car.check import checker

MESHES = REPO / "tests" / "load" / "meshes_as_rviz"
CORPUS = REPO / "tests" / "check_corpus" / "broken"
FACTORS = (1e-3, 0.02, 0.09, 0.5, 1.0, 2.0, 9.5, 11.0, 1e3)


def _robot(seed: int, links: int = 120) -> str:
    """Links of one box, cylinder, sphere or mesh each (collision, and a visual), with an
    inertia of the shape's formula times a factor of FACTORS; continuous joints along the
    cylinder's axis or across it; every origin turned at random."""
    rng = random.Random(seed)
    out = ['<robot name="r">', '<link name="base"/>']
    for i in range(links):
        kind = rng.choice(("box", "cylinder", "sphere", "mesh"))
        mass, factor = rng.uniform(0.1, 5.0), rng.choice(FACTORS)
        if kind == "box":
            x, y, z = (rng.uniform(0.01, 0.4) for _ in range(3))
            shape = f'<box size="{x:.5g} {y:.5g} {z:.5g}"/>'
            moments = [mass * (y * y + z * z) / 12, mass * (x * x + z * z) / 12,
                       mass * (x * x + y * y) / 12]
        elif kind == "cylinder":
            r, h = rng.uniform(0.01, 0.2), rng.uniform(0.01, 0.3)
            shape = f'<cylinder radius="{r:.5g}" length="{h:.5g}"/>'
            side = mass * (3 * r * r + h * h) / 12
            moments = [side, side, mass * r * r / 2]
        elif kind == "sphere":
            r = rng.uniform(0.01, 0.2)
            shape = f'<sphere radius="{r:.5g}"/>'
            moments = [0.4 * mass * r * r] * 3
        else:
            name = rng.choice(("box_mm.dae", "solid_header.stl"))
            scale = rng.choice(("", ' scale="0.001 0.001 0.001"', ' scale="1000 1000 1000"',
                                ' scale="0.5 2 1"'))
            shape = f'<mesh filename="{MESHES / name}"{scale}/>'
            moments = [mass * 0.004] * 3
        ixx, iyy, izz = (m * factor for m in moments)
        rpy = " ".join(f"{rng.choice((0, 0, 1.5708, rng.uniform(-3, 3))):.5g}"
                       for _ in range(3))
        axis = rng.choice(("0 0 1", "0 1 0", "1 0 0"))
        joint = rng.choice(("continuous", "continuous", "revolute", "fixed"))
        out.append(
            f'<link name="l{i}"><inertial><origin rpy="{rpy}"/><mass value="{mass:.5g}"/>'
            f'<inertia ixx="{ixx:.6g}" ixy="0" ixz="0" iyy="{iyy:.6g}" iyz="0" '
            f'izz="{izz:.6g}"/></inertial>'
            f'<visual><origin xyz="0 0 0.01" rpy="{rpy}"/><geometry>{shape}</geometry>'
            f'</visual><collision><origin rpy="{rpy}"/><geometry>{shape}</geometry>'
            '</collision></link>')
        parent = "base" if i == 0 else f"l{rng.randrange(i)}"
        out.append(f'<joint name="j{i}" type="{joint}"><parent link="{parent}"/>'
                   f'<child link="l{i}"/><origin xyz="{rng.uniform(-0.3, 0.3):.4g} '
                   f'{rng.uniform(-0.3, 0.3):.4g} 0.1" rpy="0 0 {rng.uniform(-3, 3):.4g}"/>'
                   f'<axis xyz="{axis}"/><limit lower="-1" upper="1" effort="1" '
                   'velocity="1"/></joint>')
    out.append("</robot>")
    return "\n".join(out)


def _both_ways(cli, path: Path, monkeypatch) -> tuple[dict, dict]:
    from mobile_car.check import replay

    monkeypatch.setattr(replay, "replay", lambda *args: None)  # each way checks in full
    found = []
    for threshold in (10**9, 0):
        monkeypatch.setattr(checker, "LARGE_ROBOT", threshold)
        # the meshes lie outside the robot's folder: named with --asset-path (else W215)
        [document] = json.loads(cli("check", "--format", "json", "--asset-path", MESHES,
                                    path).stdout)["files"]
        found.append(document)
    return found[0], found[1]


def _agree(python: dict, arrays: dict) -> None:
    assert python["diagnostics"] == arrays["diagnostics"]
    if python["extents"] is None:
        assert arrays["extents"] is None
    else:
        assert arrays["extents"] == pytest.approx(python["extents"], rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("seed", range(6))
def test_generated_robots_agree_and_are_found_wrong(cli, tmp_path, monkeypatch, seed):
    path = tmp_path / "r.urdf"
    path.write_text(_robot(seed))
    python, arrays = _both_ways(cli, path, monkeypatch)
    _agree(python, arrays)
    rules = {d["rule"] for d in python["diagnostics"]}
    assert {"W212", "W213", "W214"} <= rules  # the test has something to agree on


@pytest.mark.parametrize("shape", ["tree", "chain"])
@pytest.mark.parametrize("parts", ["distinct", "repeated"])
def test_the_benchmark_s_robots_agree(cli, tmp_path, monkeypatch, shape, parts):
    sys.path.insert(0, str(REPO / "bench"))
    import generate

    path = tmp_path / "r.urdf"
    path.write_text(generate.robot(600, shape, parts))
    _agree(*_both_ways(cli, path, monkeypatch))


@pytest.mark.parametrize("case", sorted(p.name for p in CORPUS.glob("*.urdf")
                                        if "W21" in p.read_text().split("-->")[0]))
def test_the_corpus_plausibility_cases_agree(cli, monkeypatch, case):
    _agree(*_both_ways(cli, CORPUS / case, monkeypatch))
