"""define.xacro's inertia macros against trimesh's formulas: a tiny robot file calls each
macro, mcar's build expands it with xacro, and the numbers must be trimesh's."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from lxml import etree

from tests.description.conftest import URDF

MASS = 0.37
CENTRE = (0.01, -0.02, 0.03)
PROBE = """<robot name="inertia_probe" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="{define}"/>
  <link name="probe">{call}</link>
</robot>"""


def expand(tmp_path, call: str) -> etree._Element:
    from mobile_car.expand.xacro_build import build_file
    from mobile_car.packages.search import PackageSearch

    source = tmp_path / "probe.urdf.xacro"
    source.write_text(PROBE.format(define=URDF / "define.xacro", call=call))
    # The checkout's package is named to the search, as --package-path would: the xacro
    # sandbox reads only below the package roots and the probe's own folder.
    search = PackageSearch(package_paths=[URDF.parent])
    return etree.fromstring(build_file(source, search=search).xml.encode())


def inertial_of(root: etree._Element) -> tuple[float, np.ndarray, np.ndarray]:
    inertial = root.find("link/inertial")
    i = {k: float(v) for k, v in inertial.find("inertia").attrib.items()}
    tensor = np.array([[i["ixx"], i["ixy"], i["ixz"]],
                       [i["ixy"], i["iyy"], i["iyz"]],
                       [i["ixz"], i["iyz"], i["izz"]]])
    centre = np.array([float(v) for v in inertial.find("origin").get("xyz").split()])
    return float(inertial.find("mass").get("value")), tensor, centre


def origin_block() -> str:
    return '<origin xyz="{} {} {}"/>'.format(*CENTRE)


@pytest.mark.parametrize("size", [(0.2, 0.13, 0.003), (0.03, 0.002, 0.0275), (1.0, 1.0, 1.0)])
def test_box_inertial_matches_trimesh(tmp_path, size):
    root = expand(tmp_path, f'<xacro:box_inertial mass="{MASS}" x="{size[0]}" y="{size[1]}" '
                            f'z="{size[2]}">{origin_block()}</xacro:box_inertial>')
    mass, tensor, centre = inertial_of(root)
    box = trimesh.creation.box(extents=size)
    box.density = MASS / box.volume
    assert mass == MASS
    assert np.allclose(centre, CENTRE)
    assert np.allclose(tensor, box.moment_inertia, rtol=1e-9, atol=0)


# trimesh's cylinder lies along z; these turn it onto the named link axis.
AXIS_ROTATIONS = {
    "x": trimesh.transformations.rotation_matrix(np.pi / 2, [0, 1, 0]),
    "y": trimesh.transformations.rotation_matrix(np.pi / 2, [1, 0, 0]),
    "z": np.eye(4),
}


@pytest.mark.parametrize("axis", ["x", "y", "z", None])
@pytest.mark.parametrize("radius, length", [(0.0325, 0.026), (0.00275, 0.030), (0.5, 0.01)])
def test_cylinder_inertial_matches_trimesh(tmp_path, axis, radius, length):
    axis_attribute = "" if axis is None else f' axis="{axis}"'
    root = expand(tmp_path, f'<xacro:cylinder_inertial mass="{MASS}" radius="{radius}" '
                            f'length="{length}"{axis_attribute}>{origin_block()}'
                            f'</xacro:cylinder_inertial>')
    mass, tensor, centre = inertial_of(root)
    expected = trimesh.inertia.cylinder_inertia(MASS, radius, length,
                                                transform=AXIS_ROTATIONS[axis or "z"])
    assert mass == MASS
    assert np.allclose(centre, CENTRE)
    assert np.allclose(tensor, expected, rtol=1e-9, atol=1e-15)


def test_cylinder_inertial_agrees_with_a_fine_mesh(tmp_path):
    """Independent of trimesh's closed formula: integrate a finely tessellated cylinder."""
    root = expand(tmp_path, f'<xacro:cylinder_inertial mass="{MASS}" radius="0.04" '
                            f'length="0.1" axis="y">{origin_block()}</xacro:cylinder_inertial>')
    _, tensor, _ = inertial_of(root)
    mesh = trimesh.creation.cylinder(radius=0.04, height=0.1, sections=2048,
                                     transform=AXIS_ROTATIONS["y"])
    mesh.density = MASS / mesh.volume
    assert np.allclose(tensor, mesh.moment_inertia, rtol=1e-5, atol=1e-12)


@pytest.mark.parametrize("radius", [0.0075, 0.1, 2.0])
def test_sphere_inertial_matches_trimesh(tmp_path, radius):
    root = expand(tmp_path, f'<xacro:sphere_inertial mass="{MASS}" radius="{radius}">'
                            f'{origin_block()}</xacro:sphere_inertial>')
    mass, tensor, centre = inertial_of(root)
    assert mass == MASS
    assert np.allclose(centre, CENTRE)
    assert np.allclose(tensor, trimesh.inertia.sphere_inertia(MASS, radius), rtol=1e-9, atol=0)


def test_cylinder_axis_typo_is_a_build_error(tmp_path):
    from mobile_car.errors import BuildError

    with pytest.raises(BuildError, match="axis must be x, y or z, not 'w'"):
        expand(tmp_path, f'<xacro:cylinder_inertial mass="1" radius="1" length="1" axis="w">'
                         f'{origin_block()}</xacro:cylinder_inertial>')
