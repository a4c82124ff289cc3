"""A description's sensor figures size what mcar specs casts (mobile_car/specs/): a hostile
file asks for a lidar of 10^12 samples (24 TB of ray directions), for more lidars than
one robot carries, or for a camera image 1 pixel wide and 10^9 high (a grid of 6.4·10^10
rays). The count is bounded before any array is made: such a sensor is left out with a
note naming it and the bound, the rays of one robot are bounded together, a camera's grid
rows too; a figure that is no finite number leaves its sensor out. Each attack has its
control: the count at the bound is cast as written."""

from __future__ import annotations

from specs.sensor_robots import camera_sensor, lidar_link, link, ray_sensor, robot, sensors_of

from mobile_car.specs.sensor_list import MAX_SAMPLES
from mobile_car.specs.sensors import MAX_RAYS


def test_a_lidar_of_a_trillion_samples_is_left_out_with_a_note(tmp_path):
    path = tmp_path / "trillion.urdf"
    _, section = sensors_of(path, robot(lidar_link(), ray_sensor("lidar_link",
                                                                 samples=10 ** 12)))
    assert section.figures == []
    assert section.notes == [f"sensor scanner ({path}:2): 1e+12 samples, outside "
                             f"1..{MAX_SAMPLES:,}: left out"]
    # Control: the bound itself is cast, every sample.
    _, bound = sensors_of(path, robot(lidar_link(), ray_sensor("lidar_link",
                                                               samples=MAX_SAMPLES)))
    assert bound.figure("sensors.scanner.blocked").source.startswith(f"{MAX_SAMPLES} rays cast")


def test_a_resolution_that_multiplies_the_samples_past_the_bound_is_left_out(tmp_path):
    text = robot(lidar_link(), ray_sensor("lidar_link", samples=1000)).replace(
        "<resolution>1</resolution>", "<resolution>1e9</resolution>")
    _, section = sensors_of(tmp_path / "resolution.urdf", text)
    assert section.figures == []
    assert "1e+12 samples, outside 1..100,000: left out" in section.notes[0]


def test_the_rays_of_one_robot_are_bounded_together(tmp_path):
    count = MAX_RAYS // 2
    lidars = [lidar_link(f"lidar_{i}", xyz=(0.0, 0.1 * i, 0.3)) for i in range(3)]
    blocks = [ray_sensor(f"lidar_{i}", samples=count).replace('name="scanner"',
                                                              f'name="scanner_{i}"')
              for i in range(3)]
    _, section = sensors_of(tmp_path / "many.urdf", robot(*lidars, *blocks),
                            {"proof": False})
    cast = sorted({f.key.split(".")[1] for f in section.figures})
    # Control: the first two, MAX_RAYS together, are cast; the third is not.
    assert cast == ["scanner_0", "scanner_1"]
    assert section.notes == [f"sensor scanner_2: left out, its {count:,} rays past the "
                             f"{MAX_RAYS:,} cast for one robot"]


def test_a_camera_image_a_billion_pixels_high_is_cast_on_a_bounded_grid(tmp_path):
    camera = link("camera_link", "base_link", (0, 0, 0.3))
    tall = robot(camera, camera_sensor("camera_link", 1.0, width=1, height=10 ** 9))
    _, section = sensors_of(tmp_path / "tall.urdf", tall, {"proof": False})
    assert "a 64x256 grid of rays" in section.figure("sensors.eye.covered").source
    # Control: an ordinary image keeps its aspect, 64 x 48.
    _, usual = sensors_of(tmp_path / "usual.urdf",
                          robot(camera, camera_sensor("camera_link", 1.0)), {"proof": False})
    assert "a 64x48 grid of rays" in usual.figure("sensors.eye.covered").source


def test_a_sensor_figure_that_is_no_finite_number_leaves_the_sensor_out(tmp_path):
    path = tmp_path / "infinite.urdf"
    text = robot(lidar_link(), ray_sensor("lidar_link", max_angle="1e999"))
    _, section = sensors_of(path, text)
    assert section.figures == []
    assert section.notes == [f"sensor scanner ({path}:2): <max_angle> '1e999' is not a "
                             "finite number: left out"]
