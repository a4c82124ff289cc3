"""meshes/ is what scripts/make_meshes.py makes: regenerating gives the committed bytes, and
the motor mesh is a closed solid at true size that fits the motor's collision cylinder."""

from __future__ import annotations

import subprocess
import sys

import pytest
import trimesh

from tests.description.conftest import REPO

SCRIPT = REPO / "scripts" / "make_meshes.py"
MESHES = REPO / "meshes"


@pytest.fixture(scope="module")
def regenerated(tmp_path_factory):
    if not SCRIPT.is_file():
        pytest.skip(f"{SCRIPT} is not in this tree (an sdist without scripts/?)")
    out = tmp_path_factory.mktemp("meshes")
    done = subprocess.run([sys.executable, str(SCRIPT), "--output-dir", str(out)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return out


def test_script_makes_exactly_the_committed_meshes(regenerated):
    made = sorted(p.name for p in regenerated.iterdir())
    committed = sorted(p.name for p in MESHES.iterdir() if p.suffix != ".md")  # not its README
    assert made == committed
    for name in made:
        assert (regenerated / name).read_bytes() == (MESHES / name).read_bytes(), (
            f"meshes/{name} is stale: run `python scripts/make_meshes.py` and commit it")


def test_motor_mesh_is_a_closed_binary_stl():
    data = (MESHES / "motor.stl").read_bytes()
    triangles = int.from_bytes(data[80:84], "little")
    assert len(data) == 84 + 50 * triangles  # binary STL: header, count, 50 bytes a facet
    mesh = trimesh.load(str(MESHES / "motor.stl"), force="mesh")
    assert mesh.is_watertight and mesh.volume > 0


def test_motor_mesh_fits_its_collision_cylinder(complete_robot, posed):
    """True size in metres: across the axle the mesh is exactly as wide as the collision
    cylinder; along it, the body spans the cylinder and only the shaft sticks out."""
    visuals, collisions = posed(complete_robot, "visual"), posed(complete_robot, "collision")
    for side, sign in (("left", 1), ("right", -1)):
        link = f"motor_{side}_link"
        (mesh,) = [e for e in visuals if e.link == link]
        (body,) = [e for e in collisions if e.link == link]
        # directions in the motor's own frame (x forward, y along the axle, z up)
        axes = complete_robot.get_transform(link, complete_robot.base_link)[:3, :3]
        for direction in ([1, 0, 0], [-1, 0, 0], [0, 0, 1], [0, 0, -1], [0, -sign, 0]):
            world = axes @ direction
            assert mesh.support(world) == pytest.approx(body.support(world), abs=1e-6)
        # outwards, the shaft goes past the body (by the shaft length: millimetres, not metres)
        outwards = axes @ [0, sign, 0]
        beyond = mesh.support(outwards) - body.support(outwards)
        assert 0.002 < beyond < 0.05
