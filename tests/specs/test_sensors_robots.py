"""The sensors section on the bundled car and on robots people ship (TurtleBot3 burger and
waffle, Husky and Jackal with their front laser, read in place from the shared
real-robots folder, skipped where it is absent): where each lidar sits, what of the robot
it sees, and MuJoCo's rays agreeing.

The bundled car's laser scans 41 mm above its top plate: its standoffs, between the two
plates, are out of its plane and it sees nothing of the car. Lowered into the standoffs'
plane, its range from 5 cm (the control: they are 0.108 m away, nearer than its 0.15 m
range min, where its rays start), it sees the four of them, each over the sector its
radius subtends.
"""

from __future__ import annotations

import math

import pytest
from conftest import REPO
from lxml import etree
from sim.test_sim_real_robots import FOLDER, needs_folder
from specs.sensor_robots import sensors_of, values

CAR = REPO / "urdf" / "mobile_robot.xacro"
STEP = 1.0  # the car's laser: 360 samples, one a degree from -180


def test_the_bundled_car_laser_sees_nothing_of_the_car():
    _, section = sensors_of(CAR, package_paths=[REPO])
    found = values(section)
    assert found["sensors.laser.blocked"] == [] and found["sensors.laser.blocked_share"] == 0
    assert found["sensors.laser.range"] == [0.15, 12.0]
    assert found["sensors.laser.fov"] == [-180.0, 179.0]
    # base_footprint -> base_link 0.0325 -> laser_link (0.04, 0, 0.092)
    assert found["sensors.laser.pose"] == pytest.approx([0.04, 0.0, 0.1245, 0.0])
    assert "mobile_robot.gazebo.xacro:" in section.figure("sensors.laser.fov").source
    proof = section.figure("sensors.laser.blocked").proof
    assert proof.agrees and proof.measured == []
    assert section.diagnostics == []


def _standoffs(root) -> list[tuple[float, float]]:
    """Each standoff's (x, y) in base_link: body_joint's origin plus its own (no rotations
    on the way)."""
    joints = {j.find("child").get("link"): j for j in root.iter("joint")}

    def xyz(link):
        origin = joints[link].find("origin")
        assert origin.get("rpy") in (None, "0 0 0")
        return [float(v) for v in origin.get("xyz").split()]

    body = xyz("body_link")
    return [(body[0] + xyz(name)[0], body[1] + xyz(name)[1])
            for name in joints if name.startswith("standoff_")]


def test_the_car_laser_lowered_into_the_standoffs_plane_sees_the_four(tmp_path):
    checked, _ = sensors_of(CAR, package_paths=[REPO], options={"proof": False})
    root = etree.fromstring(checked.loaded.urdf)
    laser = next(j for j in root.iter("joint") if j.get("name") == "laser_joint")
    x, y, _ = (float(v) for v in laser.find("origin").get("xyz").split())
    # Halfway up the standoffs: body_link at 0.015, standoffs from 0.003 above it, 0.03 long.
    laser.find("origin").set("xyz", f"{x} {y} {0.015 + 0.003 + 0.015}")
    # ... and its range from 5 cm: the standoffs are 0.108 m away, nearer than its 0.15.
    scanner = next(s for s in root.iter("sensor") if s.get("name") == "laser")
    scanner.find("lidar/range/min").text = "0.05"
    lowered = tmp_path / "lowered.urdf"
    lowered.write_bytes(etree.tostring(root))
    _, section = sensors_of(lowered, package_paths=[REPO])
    sectors = values(section)["sensors.laser.blocked"]
    expected = []
    for sx, sy in _standoffs(root):
        distance = math.hypot(sx - x, sy - y)
        centre = math.degrees(math.atan2(sy - y, sx - x))
        half = math.degrees(math.asin(0.00275 / distance))  # the standoff's radius
        expected.append((centre - half, centre + half))
    assert len(sectors) == 4
    for (start, end), (low, high) in zip(sectors, sorted(expected), strict=True):
        assert abs(start - low) <= STEP / 2 and abs(end - high) <= STEP / 2, (sectors, expected)
    proof = section.figure("sensors.laser.blocked").proof
    assert proof.agrees, proof.detail


# robot -> (main file, xacro arguments, environment, lidar, its pose, samples, {camera:
# (share of its image the robot covers, its housing)})
REAL = {
    "burger": ("turtlebot3_description/urdf/turtlebot3_burger.urdf", {}, {}, "base_scan",
               [-0.032, 0.0, 0.182, 0.0], 360, {}),
    # The camera frames sit in camera_link's body (its housing) and look out of it.
    "waffle": ("turtlebot3_description/urdf/turtlebot3_waffle.urdf", {}, {}, "base_scan",
               [-0.064, 0.0, 0.132, 0.0], 360,
               {"camera_rgb_frame": (0.0, "links camera_rgb_frame, camera_link"),
                "camera_depth_frame": (0.0, "links camera_depth_frame, camera_link")}),
    # Husky's Blackfly, at its default place, looks into the back of the front laser's
    # mount 0.10 m ahead (Gazebo, clipping at 0.5 m, draws past it).
    "husky": ("husky_description/urdf/husky.urdf.xacro",
              {"laser_enabled": "1", "blackfly_enabled": "1"}, {}, "front_laser",
              [0.337, 0.0, 0.30795, 0.0], 720,
              {"camera": (0.9336, "links blackfly_optical, blackfly_lens")}),
    "jackal": ("jackal_description/urdf/jackal.urdf.xacro", {}, {"JACKAL_LASER": "1"},
               "front_laser", [0.12, 0.0, 0.333, 0.0], 720, {}),
}


@needs_folder
@pytest.mark.parametrize("name", sorted(REAL))
def test_what_a_shipped_robots_sensors_see_of_it_mujoco_agreeing(name, monkeypatch):
    main, arguments, environment, lidar, pose, samples, cameras = REAL[name]
    for key, value in environment.items():
        monkeypatch.setenv(key, value)
    _, section = sensors_of(FOLDER / main, package_paths=[FOLDER], mappings=arguments)
    found = values(section)
    assert found[f"sensors.{lidar}.pose"] == pytest.approx(pose, abs=1e-6)
    assert section.figure(f"sensors.{lidar}.pose").proof.agrees
    assert f"{samples} rays cast" in section.figure(f"sensors.{lidar}.blocked").source
    # Each lidar stands clear of its robot: on TurtleBot3's top, on Husky's and Jackal's
    # sensor towers.
    assert found[f"sensors.{lidar}.blocked"] == []
    proof = section.figure(f"sensors.{lidar}.blocked").proof
    assert proof.agrees and proof.measured == [], proof.detail
    assert section.diagnostics == []
    assert sorted(key for key in found if key.endswith(".covered")) == \
        sorted(f"sensors.{camera}.covered" for camera in cameras)
    for camera, (covered, housing) in cameras.items():
        figure = section.figure(f"sensors.{camera}.covered")
        assert figure.value == pytest.approx(covered, abs=1e-4)
        assert f"(its housing left out: {housing})" in figure.source
        assert figure.proof.agrees, figure.proof.detail
