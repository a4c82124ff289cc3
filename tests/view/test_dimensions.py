"""The viewer's dimension sliders through viser's own API: one per dimension `mcar config`
gives a range, a moved slider rebuilds the robot as --set would, a value config.xacro
refuses keeps the last good robot, and the copied YAML is a file --config reads."""

from __future__ import annotations

import html
import json

import pytest

pytest.importorskip("viser", reason='viser is not installed (pip install "mcar[view]"; '
                                    "`make test` installs it)")

from mobile_car.config.spec import load_spec  # noqa: E402
from mobile_car.load.inputs import RobotInput  # noqa: E402
from mobile_car.load.robot import LoadOptions  # noqa: E402
from mobile_car.view.dimensions import robot_dimensions  # noqa: E402
from mobile_car.view.model import load_model  # noqa: E402
from mobile_car.view.server import RobotView  # noqa: E402


def _wheel_radius(view: RobotView) -> float:
    (collision,) = view.model.urdf.link_map["wheel_left_link"].collisions
    return collision.geometry.cylinder.radius


def _base_height(view: RobotView) -> float:
    return float(view.model.urdf.joint_map["base_joint"].origin[2, 3])


def test_the_panel_has_a_slider_per_dimension_config_gives_a_range(car, run_mcar, repo):
    result = run_mcar("config", "--format", "json", cwd=repo)
    assert result.returncode == 0, result.stderr
    table = json.loads(result.stdout)
    baked = {d.name for d in load_spec(repo / "urdf" / "config.xacro").base() if d.baked}
    assert baked  # the car has dimensions baked into meshes: they get no slider
    expected = {name: tuple(item["range"]) for name, item in table["dimensions"].items()
                if "range" in item and name not in baked}
    sliders = car.dimension_sliders
    assert set(sliders) == set(expected)
    assert not set(sliders) & (set(table["derived"]) | baked)
    for item in car.dimensions.ranges:
        slider, value = sliders[item.name], table["dimensions"][item.name]["value"]
        low, high = expected[item.name]
        # the box takes the plausible range, in the slider's unit
        assert item.bounds() == (item.shown(low), item.shown(high))
        assert slider.value == item.shown(value)
        # the slider spans a neighbourhood of the value: half to twice it, within the range
        assert item.shown(low) <= slider.min <= slider.value <= slider.max <= item.shown(high)
        if low > 0:
            assert slider.min <= item.shown(value) / 2 + slider.step
            assert slider.max >= min(item.shown(value) * 2, item.shown(high)) - slider.step
            assert slider.max / slider.min <= 4.2  # never the hundredfold of the range
        assert (slider.max - slider.min) / slider.step >= 100  # a drag lands on round values
    assert sliders["wheel_radius"].step == 0.0002  # 0.2 mm in 16.2..65 mm
    assert sliders["laser_samples"].step == 2


def test_a_slider_is_in_the_unit_config_xacro_writes_its_range_in(car):
    items = {item.name: item for item in car.dimensions.ranges}
    # motor_no_load_speed: rad/s in SI, written "10rpm..20000rpm": its slider is in rpm
    speed = car.dimension_sliders["motor_no_load_speed"]
    assert speed.label == "motor_no_load_speed (rpm)"
    assert round(speed.value, 3) == 279.794  # 29.3 rad/s
    assert (speed.min, speed.max, speed.step) == (138, 560, 2)
    assert items["motor_no_load_speed"].bounds() == (10, 20000)
    # plate_thickness "0.5mm..50mm": mm; wheel_radius "5mm..0.5m" (mixed): its SI unit
    assert car.dimension_sliders["plate_thickness"].label == "plate_thickness (mm)"
    assert car.dimension_sliders["plate_thickness"].value == 3.0
    assert car.dimension_sliders["wheel_radius"].label == "wheel_radius (m)"
    # 300 rpm on the slider is exactly --set motor_no_load_speed=300rpm
    from mobile_car.config.spec import parse_set_options

    speed.value = 300
    assert car.errors == []
    assert car.dimensions.values == parse_set_options(car.dimensions.spec,
                                                      ["motor_no_load_speed=300rpm"])
    # and the slider back at the default's rpm is no override (not 29.300000000000004)
    speed.value = items["motor_no_load_speed"].shown(29.3)
    assert car.dimensions.values == {}


def test_a_value_typed_past_the_slider_s_end_is_taken_and_the_slider_follows(car):
    wheel = car.dimension_sliders["wheel_radius"]
    assert wheel.max == 0.065
    # the page may send any value of the plausible range (the box), not only the slider's
    from viser._messages import GuiUpdateMessage

    inbound = car._inbound
    assert inbound.admits(GuiUpdateMessage(wheel._impl.uuid, {"value": 0.1}))
    assert not inbound.admits(GuiUpdateMessage(wheel._impl.uuid, {"value": 0.6}))
    wheel.value = 0.1  # (as viser applies what the page sent)
    assert car.errors == [] and _wheel_radius(car) == 0.1
    assert (wheel.min, wheel.max, wheel.value) == (0.05, 0.2, 0.1)  # around the new value
    # a drag within the slider leaves its span as it is
    wheel.value = 0.15
    assert (wheel.min, wheel.max) == (0.05, 0.2) and _wheel_radius(car) == 0.15


def test_a_dimension_slider_rebuilds_the_robot_with_that_override(car):
    assert (_wheel_radius(car), _base_height(car)) == (0.0325, 0.0325)
    car.dimension_sliders["wheel_radius"].value = 0.04
    assert car.errors == [] and car.reloads == 1
    assert (_wheel_radius(car), _base_height(car)) == (0.04, 0.04)
    assert car.dimensions.values == {"wheel_radius": 0.04}
    # Back at its default, the dimension is no override any more.
    car.dimension_sliders["wheel_radius"].value = 0.0325
    assert car.dimensions.values == {} and _wheel_radius(car) == 0.0325


def test_a_value_config_xacro_refuses_keeps_the_last_good_robot(car):
    car.dimension_sliders["wheel_radius"].value = 0.04
    shown = car.model
    car.dimension_sliders["track_width"].value = 0.3  # the brackets end up off the plate
    message = ("error: the dimensions do not fit together: the motor brackets stick out "
               "of the plate: their outer face at y = 0.132 m (from track_width, wheel_width, "
               "wheel_hub_length, wheel_hub_clearance) must be within plate_width / 2 "
               "(0.065 m)")
    assert car.errors == [message]
    assert html.escape(message) in car.error_box.content
    assert "showing the last good model" in car.status.content
    assert car.model is shown and car.reloads == 1
    assert car.dimensions.values == {"wheel_radius": 0.04}
    assert car.dimension_sliders["track_width"].value == 0.165  # put back
    # The next good value builds and clears the message.
    car.dimension_sliders["track_width"].value = 0.16
    assert car.errors == [] and car.dimensions.values == {"wheel_radius": 0.04,
                                                          "track_width": 0.16}


def test_a_value_outside_its_range_gets_the_set_message(car):
    error = car.set_dimension("wheel_radius", 0.6)  # (a slider stops at 0.5)
    # exactly what `mcar build --set wheel_radius=0.6` says (no unit guessed: 0.6 m is a
    # wheel a bit too big, not 0.6 cm)
    assert car.errors == ["error: --set wheel_radius=0.6: wheel_radius = 0.6 m is outside "
                          "5 mm..0.5 m"]
    assert error is not None and car.reloads == 0


def test_the_overrides_yaml_round_trips_through_config_and_build(car, run_mcar, repo,
                                                                  tmp_path):
    assert car.overrides_yaml.visible is False
    car.dimension_sliders["wheel_radius"].value = 0.04
    car.dimension_sliders["laser_samples"].value = 720
    text = car.show_overrides_yaml()
    assert car.overrides_yaml.visible is True and car.overrides_yaml.value == text
    path = tmp_path / "car.yaml"
    path.write_text(text)
    result = run_mcar("config", "--config", path, "--format", "json", cwd=repo)
    assert result.returncode == 0, result.stderr
    table = json.loads(result.stdout)["dimensions"]
    overridden = {name: item["value"] for name, item in table.items() if item.get("overridden")}
    assert overridden == {"wheel_radius": 0.04, "laser_samples": 720}
    out = tmp_path / "car.urdf"
    result = run_mcar("build", "urdf/mobile_robot.xacro", "--config", path, "-o", out, cwd=repo)
    assert result.returncode == 0, result.stderr
    assert '<cylinder length="0.026" radius="0.04"/>' in out.read_text()
    assert "<samples>720</samples>" in out.read_text()


def test_a_robot_without_a_config_xacro_has_no_panel(arm_copy, serve):
    inp, options = RobotInput(arm_copy), LoadOptions()
    assert robot_dimensions(inp, options, load_model(inp, options)) is None
    view = serve(inp, options)
    assert view.dimensions is None and view.dimension_sliders == {}
    assert view.overrides_yaml is None


def test_the_sliders_start_from_the_command_line_s_overrides(repo, serve):
    from mobile_car.config.overrides import prepared_overrides
    from mobile_car.packages.search import PackageSearch

    robot = repo / "urdf" / "mobile_robot.xacro"
    with prepared_overrides(PackageSearch(origin=robot), ["wheel_radius=40mm"], []) as given:
        view = serve(RobotInput(robot), LoadOptions(overrides=given))
    assert view.dimension_sliders["wheel_radius"].value == 0.04
    assert _wheel_radius(view) == 0.04
    assert view.show_overrides_yaml() == "wheel_radius: 0.04\n"
    view.rebuild()  # as live reload does: the overrides stay applied
    assert view.errors == [] and _wheel_radius(view) == 0.04
