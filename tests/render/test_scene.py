"""URDF -> coloured triangles: materials, meshes through the package search, errors."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mobile_car.errors import BuildError, RenderError
from mobile_car.load.inputs import RobotInput
from mobile_car.load.robot import LoadOptions, load_robot
from mobile_car.packages.search import PackageSearch
from mobile_car.render.scene import ModelSource, load_scene
from mobile_car.render.session import model_source

PKG = Path(__file__).parent / "pkg"
REPO = Path(__file__).parents[2]


def scene_of(path: Path, collision=False, text: str | None = None, frames: str = "auto"):
    search = PackageSearch(origin=path)
    if text is None:
        loaded = load_robot(RobotInput(path), LoadOptions())
        source, search = model_source(loaded), loaded.search
    else:
        source = ModelSource(text.encode(), path, lines_match=True)
    return load_scene(source, search, collision=collision, frames=frames)


def colours(scene) -> set[tuple]:
    """The distinct colours of a scene, as 8-bit RGBA."""
    return {tuple(int(v) for v in c) for c in np.rint(scene.colors * 255)}


def urdf_rgba(*rgba) -> tuple:
    """A URDF <color rgba> as yourdfpy stores it: int(255 * channel)."""
    return tuple(int(255 * c) for c in rgba)


def test_named_material_from_the_palette_colours_the_wheel():
    scene = scene_of(PKG / "urdf/wheel/test_wheel.urdf.xacro")
    assert colours(scene) == {urdf_rgba(0.1, 0.25, 0.85, 1)}  # define.xacro's blue
    radius, width = 0.033, 0.026
    assert scene.bounds[1] - scene.bounds[0] == pytest.approx([2 * radius, width, 2 * radius],
                                                              abs=1e-4)


def test_inline_material_and_a_two_centimetre_sphere():
    scene = scene_of(PKG / "urdf/caster/test_caster.urdf.xacro")
    assert colours(scene) == {urdf_rgba(0.8, 0.65, 0.2, 1)}
    assert scene.bounds == pytest.approx(np.array([[-0.01] * 3, [0.01] * 3]), abs=2e-4)


def test_every_link_is_posed_by_its_joints():
    scene = scene_of(PKG / "urdf/chassis/test_chassis.urdf.xacro")
    low, high = scene.bounds
    assert low == pytest.approx([-0.1, -0.075 - 0.013, 0.0], abs=1e-4)
    assert high == pytest.approx([0.1, 0.075 + 0.013, 0.066], abs=1e-4)
    assert len(colours(scene)) == 3  # white plate, blue wheels, grey caster


def test_collada_mesh_keeps_its_own_material_over_the_urdf_one():
    scene = scene_of(PKG / "models/red_box_dae.urdf")
    assert colours(scene) == {(217, 26, 26, 255)}  # red_box.dae's diffuse 0.85 0.1 0.1
    assert scene.bounds[1] - scene.bounds[0] == pytest.approx([0.04, 0.02, 0.01], abs=1e-6)


def test_stl_through_package_uri_takes_the_urdf_colour():
    scene = scene_of(PKG / "urdf/motor/test_motor.urdf.xacro")
    assert colours(scene) == {urdf_rgba(1.0, 0.5, 0.05, 1)}  # define.xacro's orange
    assert scene.triangle_count > 50


def test_relative_mesh_path_and_scale():
    scene = scene_of(PKG / "models/relative_mesh.urdf")
    assert scene.bounds[1] - scene.bounds[0] == pytest.approx([0.044, 0.044, 0.094], abs=1e-6)


def test_file_uri_mesh(tmp_path):
    # an absolute file:// path, in the robot's folder (one outside every allowed folder
    # is refused: tests/untrusted/test_outside_roots.py)
    mesh = tmp_path / "meshes" / "motor.stl"
    mesh.parent.mkdir()
    mesh.write_bytes((PKG / "meshes/motor.stl").read_bytes())
    urdf = tmp_path / "file_uri.urdf"
    urdf.write_text(f'<robot name="r"><link name="a"><visual><geometry>'
                    f'<mesh filename="file://{mesh}"/></geometry></visual></link></robot>')
    scene = scene_of(urdf)
    assert scene.triangle_count > 50
    assert len(colours(scene)) == 1  # no material: one neutral grey


def test_collision_geometry_takes_the_link_colour():
    visual = scene_of(PKG / "models/box_collides_as_sphere.urdf")
    collision = scene_of(PKG / "models/box_collides_as_sphere.urdf", collision=True)
    assert colours(collision) == colours(visual)
    assert collision.triangle_count != visual.triangle_count  # the box became a sphere


PLACEHOLDER = (255, 0, 255, 255)


def test_a_missing_mesh_is_a_marker_and_the_rest_is_drawn():
    """mcar check says which mesh, and where (W207); the scene draws the robot with a magenta
    box where the mesh belongs, a fifth of the rest of the robot in size."""
    text = ('<robot name="r">\n<link name="a"><visual><geometry>\n'
            '<mesh filename="package://render_test_parts/meshes/no_such_mesh.stl"/>'
            '</geometry></visual></link>\n<link name="b"><visual><geometry>'
            '<box size="1 1 1"/></geometry></visual></link>\n<joint name="j" type="fixed">'
            '<parent link="a"/><child link="b"/><origin xyz="2 0 0"/></joint></robot>')
    scene = scene_of(PKG / "models/inline.urdf", text=text)
    assert PLACEHOLDER in colours(scene)
    marker = scene.positions[np.all(np.rint(scene.colors * 255) == PLACEHOLDER, axis=1)]
    assert np.ptp(marker, axis=0) == pytest.approx([0.2, 0.2, 0.2])  # a fifth of 1 m
    assert scene.bounds == pytest.approx(np.array([[-0.1, -0.5, -0.5], [2.5, 0.5, 0.5]]))


def test_a_missing_mesh_takes_the_size_and_place_of_its_link_s_collision_shapes():
    text = ('<robot name="r"><link name="a"><visual><origin xyz="5 5 5"/><geometry>'
            '<mesh filename="package://nowhere_pkg/m.stl"/></geometry></visual>'
            '<collision><origin xyz="0 0 0.05"/><geometry><box size="0.4 0.2 0.1"/>'
            '</geometry></collision><collision><origin xyz="0.3 0 0"/><geometry>'
            '<cylinder radius="0.05" length="0.02"/></geometry></collision></link></robot>')
    scene = scene_of(PKG / "models/inline.urdf", text=text)
    assert colours(scene) == {PLACEHOLDER}
    assert scene.bounds == pytest.approx(np.array([[-0.2, -0.1, -0.01], [0.35, 0.1, 0.1]]))


def test_each_mesh_is_smoothed_once_though_a_marker_is_sized_by_the_rest(monkeypatch):
    """The marker's size needs the bounds of the other pieces: they are shaped once, not
    again for the bounds (with more meshes than the smoothing cache holds, OpenArm's
    bimanual robot smoothed every mesh twice)."""
    import mobile_car.render.scene as scene_module
    smoothed, smooth_shade = [], scene_module.smooth_shade

    def counting(mesh, angle):
        smoothed.append(len(mesh.faces))
        return smooth_shade(mesh, angle)

    monkeypatch.setattr(scene_module, "smooth_shade", counting)
    monkeypatch.setattr(scene_module, "_SMOOTHED", {})
    monkeypatch.setattr(scene_module, "_SMOOTHED_LIMIT", 1)
    monkeypatch.setattr(scene_module, "_UNIT_CORNERS", {})
    motor = ('<visual><geometry><mesh filename="package://render_test_parts/meshes/motor.stl"'
             ' scale="0.001 0.001 0.001"/></geometry><material name="{0}"><color rgba="{1}"/>'
             '</material></visual>')
    text = ('<robot name="r"><link name="a">' + motor.format("red", "1 0 0 1") + '</link>'
            '<link name="b">' + motor.format("blue", "0 0 1 1") + '</link>'
            '<link name="c"><visual><geometry><mesh filename="package://nowhere_pkg/m.stl"/>'
            '</geometry></visual></link>'
            '<joint name="j" type="fixed"><parent link="a"/><child link="b"/>'
            '<origin xyz="0.1 0 0"/></joint><joint name="k" type="fixed"><parent link="a"/>'
            '<child link="c"/></joint></robot>')
    scene = scene_of(PKG / "models/inline.urdf", text=text)
    assert {PLACEHOLDER, urdf_rgba(1, 0, 0, 1), urdf_rgba(0, 0, 1, 1)} == colours(scene)
    assert len(smoothed) == 3  # the red motor, the blue one, the marker's unit box


def test_malformed_xml_names_its_line():
    with pytest.raises(RenderError) as caught:
        scene_of(PKG / "models/inline.urdf", text='<robot name="r">\n<link name="a">\n</robot>')
    assert caught.value.line == 3 and "not well-formed" in caught.value.message


def test_a_macro_file_is_not_a_robot():
    from mobile_car.load.robot import MacroFileError

    with pytest.raises(MacroFileError) as caught:
        scene_of(PKG / "urdf/define.xacro")
    assert caught.value.message.endswith("define.xacro is a macro file: include it from a "
                                         "robot file, or build its test file")
    with pytest.raises(RenderError) as caught:  # the scene refuses it too, given as text
        scene_of(PKG / "urdf/define.xacro", text="<robot><link name='a'/></robot>")
    assert caught.value.message.startswith("<robot> has no name: a macro file is not a robot")


def test_a_joint_to_a_missing_link_is_an_error_not_a_traceback():
    text = ('<robot name="r"><link name="a"/><joint name="j" type="fixed">'
            '<parent link="a"/><child link="ghost"/></joint></robot>')
    with pytest.raises(RenderError):
        scene_of(PKG / "models/inline.urdf", text=text)


def test_broken_xacro_is_a_build_error(tmp_path):
    bad = tmp_path / "bad.urdf.xacro"
    bad.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                   '<link name="${undefined_thing}"/>\n</robot>\n')
    with pytest.raises(BuildError):
        scene_of(bad)


def test_no_visual_geometry_gives_an_empty_scene():
    scene = scene_of(REPO / "urdf/tutorial/01_skeleton.urdf", frames="none")
    assert scene.triangle_count == 0 and scene.bounds is None and scene.labels == ()


def test_no_visual_geometry_draws_the_link_frames_instead():
    scene = scene_of(REPO / "urdf/tutorial/01_skeleton.urdf")
    # three axes of 12 triangles (boxes) for each of the five frames, at the origin
    assert scene.triangle_count == 5 * 3 * 12 and scene.frames_only
    assert np.allclose(scene.bounds[0], -0.1 / 28) and np.allclose(scene.bounds[1].max(), 0.1)
    assert scene.labels == (("base_link\n  wheel_1\n  wheel_2\n  wheel_3\n  wheel_4",
                             (0.0, 0.0, 0.0)),)
