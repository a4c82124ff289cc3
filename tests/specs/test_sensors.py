"""mcar specs' sensors section on robots written here: a lidar and a post of known size at a
known place blocks the sector its edges subtend (atan), whether the post collides or is
only drawn; gz's <lidar> and Gazebo classic's <ray> are read with their samples, angles,
range and pose; a link named like a lidar takes the stated defaults; a camera facing a
wall sees it over the share of its image the closed form gives; MuJoCo's own rays agree;
W520 names the sectors of a lidar blocked over 10 %."""

from __future__ import annotations

import math

import pytest
import yaml
from specs.sensor_robots import (
    LIDAR_Z,
    box,
    camera_sensor,
    lidar_link,
    link,
    post,
    ray_sensor,
    robot,
    sensors_of,
    square,
    subtended,
    values,
)

from mobile_car.specs.sensors import laser_filters_fragment

STEP = 1.0  # degrees between the samples of ray_sensor's default scan
POST = ((0.20, 0.10), 0.02)  # centre (x, y), side: ahead and left of the lidar


def _one_sector(section, key="sensors.scanner.blocked"):
    sectors = values(section)[key]
    assert len(sectors) == 1, sectors
    return sectors[0]


def test_a_post_blocks_the_sector_its_edges_subtend(tmp_path):
    centre, side = POST
    _, section = sensors_of(tmp_path / "post.urdf",
                            robot(lidar_link(), post("post", centre, side),
                                  ray_sensor("lidar_link")))
    low, high = subtended(square(centre, side))
    start, end = _one_sector(section)
    # Each sample stands for half a step either side: the edges within half a step.
    assert abs(start - low) <= STEP / 2 and abs(end - high) <= STEP / 2, (start, end, low, high)
    found = values(section)
    assert found["sensors.scanner.pose"] == [0.0, 0.0, LIDAR_Z, 0.0]
    assert found["sensors.scanner.range"] == [0.1, 10.0]
    assert found["sensors.scanner.fov"] == [-180.0, 179.0]
    blocked_samples = round(end - start)
    assert found["sensors.scanner.blocked_share"] == pytest.approx(blocked_samples / 360,
                                                                 abs=1e-4)
    # MuJoCo casts the same rays on the same geometry: the same sector, within a sample.
    proof = section.figure("sensors.scanner.blocked").proof
    assert proof.agrees, proof.detail
    ((mj_start, mj_end),) = proof.measured
    assert abs(mj_start - start) <= STEP and abs(mj_end - end) <= STEP
    assert section.diagnostics == []


def test_a_post_that_is_only_drawn_still_blocks_the_laser(tmp_path):
    centre, side = POST
    drawn = post("post", centre, side, collision=False)
    _, section = sensors_of(tmp_path / "drawn.urdf",
                            robot(lidar_link(), drawn, ray_sensor("lidar_link")))
    low, high = subtended(square(centre, side))
    start, end = _one_sector(section)
    assert abs(start - low) <= STEP / 2 and abs(end - high) <= STEP / 2
    proof = section.figure("sensors.scanner.blocked").proof
    assert proof.agrees and proof.measured == [[start, end]], proof.detail
    # Control: without the post nothing blocks the scan.
    _, clear = sensors_of(tmp_path / "clear.urdf", robot(lidar_link(), ray_sensor("lidar_link")))
    assert values(clear)["sensors.scanner.blocked"] == []


def test_a_gz_lidar_block_is_read_with_its_samples_angles_range_and_pose(tmp_path):
    centre, side = POST
    # 181 samples from -90 to 90 degrees, the sensor turned 90 degrees left on its link.
    sensor = ray_sensor("lidar_link", samples=181, min_angle=-math.pi / 2,
                        max_angle=math.pi / 2, near=0.2, far=8.0, kind="gpu_lidar",
                        block="lidar", pose=f"0 0 0.01 0 0 {math.pi / 2!r}")
    _, section = sensors_of(tmp_path / "gz.urdf",
                            robot(lidar_link(), post("post", centre, side), sensor))
    found = values(section)
    assert found["sensors.scanner.pose"] == pytest.approx([0.0, 0.0, LIDAR_Z + 0.01, 90.0])
    # MuJoCo's kinematics place the sensor where the <pose> on its link does.
    pose_proof = section.figure("sensors.scanner.pose").proof
    assert pose_proof.agrees and pose_proof.measured == pytest.approx(
        [0.0, 0.0, LIDAR_Z + 0.01, 90.0])
    assert found["sensors.scanner.range"] == [0.2, 8.0]
    assert found["sensors.scanner.fov"] == [-90.0, 90.0]
    assert section.figure("sensors.scanner.fov").source == \
        f"<sensor type=\"gpu_lidar\"> on link lidar_link ({tmp_path / 'gz.urdf'}:2)"
    # In the sensor's frame the post lies 90 degrees to the right of where the body sees it.
    low, high = subtended(square(centre, side))
    start, end = _one_sector(section)
    assert abs(start - (low - 90)) <= STEP / 2 and abs(end - (high - 90)) <= STEP / 2
    assert section.figure("sensors.scanner.blocked").proof.agrees


def test_a_link_named_like_a_lidar_takes_the_stated_defaults(tmp_path):
    centre, side = POST
    _, section = sensors_of(tmp_path / "named.urdf",
                            robot(lidar_link("hokuyo_link"), post("post", centre, side)))
    found = values(section)
    assert found["sensors.hokuyo_link.range"] == [0.12, 12.0]
    assert found["sensors.hokuyo_link.fov"] == [-180.0, 179.0]
    source = section.figure("sensors.hokuyo_link.blocked_share").source
    assert source.startswith("360 rays cast")
    assert "named like a lidar, no <sensor>: default 360 samples from -180° to 179°, " \
           "range 0.12..12 m" in section.figure("sensors.hokuyo_link.range").source
    low, high = subtended(square(centre, side))
    start, end = _one_sector(section, "sensors.hokuyo_link.blocked")
    assert abs(start - low) <= STEP / 2 and abs(end - high) <= STEP / 2


def test_a_camera_facing_a_wall_sees_it_over_the_share_the_closed_form_gives(tmp_path):
    # The camera at 0.3 m looks along x; a wall 0.5 m ahead covers y >= 0.05 (its left),
    # from the floor to far above: the columns left of atan(0.05 / 0.5) are covered.
    hfov = math.radians(80)
    wall = link("wall", "base_link", (0.55, 0.05 + 1.0, 0.5), box((0.1, 2.0, 4.0)),
                mass=500)
    camera = link("camera_link", "base_link", (0, 0, 0.3), box((0.02, 0.05, 0.02)))
    _, section = sensors_of(tmp_path / "camera.urdf",
                            robot(camera, wall, camera_sensor("camera_link", hfov)))
    expected = (1 - (0.05 / 0.5) / math.tan(hfov / 2)) / 2
    covered = values(section)["sensors.eye.covered"]
    # 64 columns: within one column of the closed form.
    assert covered == pytest.approx(expected, abs=1 / 64)
    assert values(section)["sensors.eye.fov"] == [-40.0, 40.0]
    figure = section.figure("sensors.eye.covered")
    assert "64x48 grid" in figure.source
    assert figure.proof.agrees and figure.proof.measured == pytest.approx(covered, abs=0.02)


def test_a_lidar_blocked_over_ten_percent_is_w520_with_its_sectors(tmp_path):
    # A 0.2 m wide plate 0.1 m behind the lidar hides 90 degrees of the scan.
    plate = link("plate", "base_link", (-0.15, 0, 0.35), box((0.02, 0.2, 0.3)))
    text = robot(lidar_link(), plate, ray_sensor("lidar_link"))
    checked, section = sensors_of(tmp_path / "hidden.urdf", text)
    (diagnostic,) = section.diagnostics
    sectors = values(section)["sensors.scanner.blocked"]
    assert diagnostic.rule == "W520"
    assert diagnostic.file == str(checked.file) == str(tmp_path / "hidden.urdf")
    assert diagnostic.line == 2
    share = values(section)["sensors.scanner.blocked_share"]
    assert diagnostic.text().startswith(f"{tmp_path / 'hidden.urdf'}:2: warning: ")
    assert "[W520]" in diagnostic.text()
    shown = ", ".join(f"{a:g}..{b:g}°" for a, b in sectors)
    assert diagnostic.message == (f"lidar scanner: the robot blocks {share:.0%} of its "
                                  f"samples, over 10% of its field of view: sectors {shown}")
    # Behind the lidar: from 180 - atan(0.1/0.14) around through the scan's ends.
    edge = 180 - math.degrees(math.atan2(0.1, 0.14))
    assert sectors[0][0] == -180.5 and sectors[-1][1] == 179.5
    assert abs(sectors[0][1] + edge) <= STEP / 2 and abs(sectors[-1][0] - edge) <= STEP / 2
    # Control: a threshold of 50 % lets the same robot pass.
    _, lenient = sensors_of(tmp_path / "hidden.urdf", None, {"sensor_blocked_share": 0.5})
    assert lenient.diagnostics == []


def test_the_laser_filters_fragment_removes_exactly_the_blocked_samples(tmp_path):
    centre, side = POST
    plate = link("plate", "base_link", (-0.15, 0, 0.35), box((0.02, 0.2, 0.3)))
    _, section = sensors_of(tmp_path / "two.urdf",
                            robot(lidar_link(), post("post", centre, side), plate,
                                  ray_sensor("lidar_link")))
    sectors = values(section)["sensors.scanner.blocked"]
    assert len(sectors) == 3  # the post; behind, on either end of the scan
    fragment = laser_filters_fragment([section])
    read = yaml.safe_load(yaml.safe_dump(fragment))
    assert read == fragment
    chain = read["scan_to_scan_filter_chain"]["ros__parameters"]
    assert list(chain) == ["filter1", "filter2", "filter3"]
    for (low, high), entry in zip(sectors, chain.values(), strict=True):
        assert entry["type"] == "laser_filters/LaserScanAngularBoundsFilterInPlace"
        assert entry["params"] == {"lower_angle": round(math.radians(low), 6),
                                   "upper_angle": round(math.radians(high), 6)}
    # The filter removes a reading strictly between its bounds (laser_filters'
    # angular_bounds_filter_in_place): applied to the scan, exactly the blocked samples go.
    angle_min, increment = math.radians(-180), math.radians(1)
    removed = {i for i in range(360) for entry in chain.values()
               if entry["params"]["lower_angle"] < angle_min + i * increment
               < entry["params"]["upper_angle"]}
    blocked = {i for i in range(360) if any(low < -180 + i < high for low, high in sectors)}
    assert removed == blocked and len(blocked) == round(
        values(section)["sensors.scanner.blocked_share"] * 360)
    ros1 = yaml.safe_load(yaml.safe_dump(laser_filters_fragment([section], ros=1)))
    assert ros1 == {"scan_filter_chain": list(chain.values())}


def test_no_proof_when_asked_for_none_and_nothing_blocked_gives_no_filter(tmp_path):
    _, section = sensors_of(tmp_path / "bare.urdf", robot(lidar_link(), ray_sensor("lidar_link")),
                            {"proof": False})
    assert all(figure.proof is None for figure in section.figures)
    assert values(section)["sensors.scanner.blocked"] == []
    assert laser_filters_fragment([section]) == {}


def test_a_robot_without_sensors_has_an_empty_section(tmp_path):
    _, section = sensors_of(tmp_path / "blind.urdf", robot())
    assert (section.name, section.figures, section.notes, section.diagnostics) == \
        ("sensors", [], [], [])


def _mesh_link(tmp_path, name: str, mesh) -> str:
    """A link holding ``mesh`` (a trimesh, written as STL beside the robot) as a visual
    0.2 m ahead of the lidar, centred in its scan plane."""
    mesh.export(tmp_path / f"{name}.stl")
    visual = (f'<visual><origin xyz="0.2 0 {LIDAR_Z}"/><geometry>'
              f'<mesh filename="{name}.stl"/></geometry></visual>')
    return link(name, "base_link", (0, 0, 0), visual)


def test_a_mesh_of_two_posts_blocks_two_sectors_and_the_gap_between_stays_open(tmp_path):
    import trimesh

    posts = []
    for y in (0.05, -0.05):
        post_mesh = trimesh.creation.box((0.02, 0.02, 0.2))
        post_mesh.apply_translation((0, y, 0))
        posts.append(post_mesh)
    two = _mesh_link(tmp_path, "two", trimesh.util.concatenate(posts))
    _, section = sensors_of(tmp_path / "two.urdf",
                            robot(lidar_link(), two, ray_sensor("lidar_link")))
    (right, left) = values(section)["sensors.scanner.blocked"]
    low, high = subtended(square((0.2, 0.05), 0.02))
    assert abs(left[0] - low) <= STEP / 2 and abs(left[1] - high) <= STEP / 2
    assert right == [-left[1], -left[0]]
    # MuJoCo casts on the mesh's triangles, not its convex hull: the gap is open there too.
    proof = section.figure("sensors.scanner.blocked").proof
    assert proof.agrees and proof.measured == [right, left], proof.detail


def test_a_flat_mesh_mujoco_refuses_is_left_out_of_the_proof_which_says_so(tmp_path):
    import trimesh

    flat = trimesh.Trimesh(vertices=[[0, -0.05, -0.05], [0, 0.05, -0.05], [0, -0.05, 0.05],
                                     [0, 0.05, 0.05]], faces=[[0, 1, 2], [1, 3, 2]])
    decal = _mesh_link(tmp_path, "decal", flat)
    _, section = sensors_of(tmp_path / "decal.urdf",
                            robot(lidar_link(), decal, ray_sensor("lidar_link")))
    # trimesh sees the decal, +-atan(0.05 / 0.2) ahead...
    ((start, end),) = values(section)["sensors.scanner.blocked"]
    edge = math.degrees(math.atan2(0.05, 0.2))
    assert abs(start + edge) <= STEP / 2 and abs(end - edge) <= STEP / 2
    # ... MuJoCo cannot make a hull of it: the proof leaves it out, disagrees, and says why.
    proof = section.figure("sensors.scanner.blocked").proof
    assert not proof.agrees and proof.measured == []
    assert proof.detail == "MuJoCo mj_multiRay from the same origin and azimuths: 29 of 360 " \
                           "samples differ"
    assert section.notes == [f"sensors' proof: link decal: mesh {tmp_path / 'decal.stl'} left "
                             "out of the proof: mesh 'decal' has coplanar vertices, cannot "
                             "compute convex hull. Consider using a primitive geom type "
                             "(plane or thin box) instead"]


def test_what_a_declared_lidar_leaves_out_is_taken_by_default_and_said(tmp_path):
    sensor = ('<gazebo reference="lidar_link"><sensor name="scanner" type="gpu_lidar"><lidar>'
              "<scan><horizontal><samples>90</samples></horizontal></scan></lidar></sensor>"
              "</gazebo>")
    path = tmp_path / "sparse.urdf"
    _, section = sensors_of(path, robot(lidar_link(), sensor))
    assert values(section)["sensors.scanner.range"] == [0.12, 12.0]
    assert values(section)["sensors.scanner.fov"] == [-180.0, 179.0]
    assert section.figure("sensors.scanner.range").source == (
        f'<sensor type="gpu_lidar"> on link lidar_link ({path}:2); not given, taken as '
        "min_angle -180°, max_angle 179°, range min 0.12 m, range max 12 m")
    assert section.figure("sensors.scanner.blocked").source.startswith("90 rays cast")


def test_without_embree_trimesh_own_ray_test_finds_the_same_sector(tmp_path, monkeypatch):
    import trimesh

    centre, side = POST
    text = robot(lidar_link(), post("post", centre, side), ray_sensor("lidar_link"))
    _, with_embree = sensors_of(tmp_path / "post.urdf", text, {"proof": False})
    monkeypatch.setattr(trimesh.ray, "has_embree", False)
    _, without = sensors_of(tmp_path / "post.urdf", None, {"proof": False})
    assert values(without)["sensors.scanner.blocked"] == \
        values(with_embree)["sensors.scanner.blocked"] != []


def test_a_part_nearer_than_range_min_is_not_seen_as_gazebo_starts_its_rays_there(tmp_path):
    centre, side = POST  # 0.2 m ahead, 0.22 m away at most
    _, section = sensors_of(tmp_path / "near.urdf",
                            robot(lidar_link(), post("post", centre, side),
                                  ray_sensor("lidar_link", near=0.25)))
    assert values(section)["sensors.scanner.blocked"] == []
    proof = section.figure("sensors.scanner.blocked").proof
    assert proof.agrees and proof.measured == []
    assert "each ray starts at range min" in section.figure("sensors.scanner.blocked").assumption
    # Control: from 0.1 m the post is seen, in both engines.
    _, seen = sensors_of(tmp_path / "near.urdf", robot(lidar_link(), post("post", centre, side),
                                                       ray_sensor("lidar_link", near=0.1)))
    assert len(values(seen)["sensors.scanner.blocked"]) == 1
    assert seen.figure("sensors.scanner.blocked").proof.measured == \
        values(seen)["sensors.scanner.blocked"]


def test_an_inertia_mujoco_refuses_does_not_cost_the_sensors_their_proof(tmp_path):
    # izz over ixx + iyy: MuJoCo refuses the tensor (sim's E310); the proof needs no mass.
    text = robot(lidar_link(), post("post", *POST), ray_sensor("lidar_link")).replace(
        'iyy="0.01" iyz="0" izz="0.01"', 'iyy="0.01" iyz="0" izz="0.05"', 1)
    assert 'izz="0.05"' in text
    _, section = sensors_of(tmp_path / "refused.urdf", text)
    proof = section.figure("sensors.scanner.blocked").proof
    assert proof is not None and proof.agrees
    assert proof.measured == values(section)["sensors.scanner.blocked"] != []
    assert section.notes == []


def test_a_sensor_on_no_link_is_left_out_with_a_note(tmp_path):
    path = tmp_path / "floating.urdf"
    text = robot(lidar_link(), ray_sensor("lidar_link").replace(
        '<gazebo reference="lidar_link">', "<gazebo>"))
    _, section = sensors_of(path, text)
    assert section.figures == []
    assert section.notes == [f"sensor scanner ({path}:2): in a <gazebo> block without a "
                             "reference, on no link: left out"]


def test_a_shape_around_the_lidar_is_its_housing_one_that_only_boxes_it_in_is_not(tmp_path):
    import trimesh

    # A closed shell around the scanner, on a link of its own: its housing, left out.
    shell = _mesh_link(tmp_path, "shell", trimesh.creation.box((0.1, 0.1, 0.1)))
    shell = shell.replace('<origin xyz="0.2 0 ', '<origin xyz="0 0 ')
    _, housed = sensors_of(tmp_path / "housed.urdf",
                           robot(lidar_link(), shell, ray_sensor("lidar_link")))
    assert values(housed)["sensors.scanner.blocked"] == []
    assert "(its housing left out: links lidar_link, shell)" in \
        housed.figure("sensors.scanner.blocked").source
    # Two rails either side of it, one mesh: its box holds the scanner, but rays ahead and
    # behind leave it; each rail blocks the sector its edges subtend, in both engines.
    posts = []
    for y in (0.1, -0.1):
        rail = trimesh.creation.box((0.02, 0.02, 0.2))
        rail.apply_translation((-0.2, y, 0))  # (_mesh_link puts it 0.2 m ahead)
        posts.append(rail)
    rails = _mesh_link(tmp_path, "rails", trimesh.util.concatenate(posts))
    _, boxed = sensors_of(tmp_path / "boxed.urdf",  # (its range from 1 cm: the rails are near)
                          robot(lidar_link(), rails, ray_sensor("lidar_link", near=0.01)))
    right, left = values(boxed)["sensors.scanner.blocked"]
    low, high = subtended(square((0.0, 0.1), 0.02))
    assert abs(left[0] - low) <= STEP / 2 and abs(left[1] - high) <= STEP / 2
    assert right == [-left[1], -left[0]]
    assert "(its housing left out: link lidar_link)" in \
        boxed.figure("sensors.scanner.blocked").source
    assert boxed.figure("sensors.scanner.blocked").proof.agrees


def test_sectors_agree_within_one_sample_and_across_the_ends_of_a_full_turn():
    from mobile_car.specs.sensors import within_one_sample

    ours = [False, True, True, True, False, False]
    assert within_one_sample(ours, [False, False, True, True, True, False])  # shifted by one
    assert not within_one_sample(ours, [False, True, True, True, False, True])  # one apart
    assert not within_one_sample(ours, [False] * 6)
    # The first and last samples of a full turn are neighbours; of a part scan they are not.
    first, last = [True] + [False] * 5, [False] * 5 + [True]
    assert within_one_sample(first, last, around=True)
    assert not within_one_sample(first, last)


BAXTER_ARM = [  # (xyz, rpy) of each joint down Baxter's right arm to its hand camera's axis
    ("0.024645 -0.219645 0.118588", "0 0 -0.7854"), ("0.055695 0 0.011038", "0 0 0"),
    ("0.069 0 0.27035", "-1.57079632679 0 0"), ("0.102 0 0", "1.57079632679 0 1.57079632679"),
    ("0.069 0 0.26242", "-1.57079632679 -1.57079632679 0"),
    ("0.10359 0 0", "1.57079632679 0 1.57079632679"),
    ("0.01 0 0.2707", "-1.57079632679 -1.57079632679 0"),
    ("0.115975 0 0", "1.57079632679 0 1.57079632679"), ("0 0 0.11355", "0 0 0"),
    ("0.03825 0.012 0.015355", "0 0 0")]


def test_a_camera_looking_straight_down_agrees_with_mujoco_whatever_its_yaw_rounds_to(
        tmp_path):
    # Baxter's hand camera looks straight down: the yaw of its x axis is atan2 of two
    # rounding errors (26.56° computed, 26.57° by MuJoCo), and the proof failed, exit 1,
    # on frames that agree to 1e-12.
    parts, parent = [], "base_link"
    for number, (xyz, rpy) in enumerate(BAXTER_ARM):
        child = "hand_camera_axis" if number == len(BAXTER_ARM) - 1 else f"arm_{number}"
        parts.append(f'<joint name="j{number}" type="fixed"><parent link="{parent}"/>'
                     f'<child link="{child}"/><origin xyz="{xyz}" rpy="{rpy}"/></joint>'
                     f'<link name="{child}"/>')
        parent = child
    _, section = sensors_of(tmp_path / "baxter_arm.urdf", robot(lidar_link(), *parts))
    pose = section.figure("sensors.hand_camera_axis.pose")
    assert pose.value[:3] == pytest.approx([0.8168, -0.9948, 0.2827], abs=1e-4)
    assert pose.proof.agrees, (pose.value, pose.proof.measured)


def test_the_pose_proof_still_sees_a_thousandth_of_a_degree_about_any_axis():
    import numpy as np

    from mobile_car.specs.sensors import POSE_TOLERANCE, _turned

    def turned(axis, degrees):
        x, y, z = axis
        c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
        k = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
        frame = np.eye(4)
        frame[:3, :3] = np.eye(3) * c + s * k + (1 - c) * np.outer(axis, axis)
        return frame

    for axis in ((0, 0, 1), (1, 0, 0), (0, 1, 0)):
        assert _turned(np.eye(4), turned(axis, 1e-3)) == pytest.approx(1e-3, rel=1e-6)
        assert _turned(np.eye(4), turned(axis, 1e-3)) > POSE_TOLERANCE
    assert _turned(turned((0, 0, 1), 30), turned((0, 0, 1), 30)) == 0
    assert _turned(np.eye(4), turned((0, 0, 1), 180)) == pytest.approx(180)


@pytest.fixture
def made(monkeypatch) -> list[int]:
    """The triangle counts of every ray scene built (self_view._intersector) in the test."""
    from mobile_car.specs import self_view

    counts = []
    intersector = self_view._intersector
    monkeypatch.setattr(self_view, "_intersector",
                        lambda triangles: counts.append(len(triangles)) or intersector(triangles))
    return counts


def test_each_link_is_made_ray_ready_once_for_every_sensor_each_seeing_the_other(
        tmp_path, made):
    # Two scanners 0.3 m apart on the y axis, each housed in its own 4 cm box: each one's
    # housing is left out of its own view and blocks the other's, over the sector the
    # box's near face subtends.
    text = robot(lidar_link("left_link", (0, 0.15, LIDAR_Z)),
                 lidar_link("right_link", (0, -0.15, LIDAR_Z)),
                 ray_sensor("left_link").replace('name="scanner"', 'name="left"'),
                 ray_sensor("right_link").replace('name="scanner"', 'name="right"'))
    _, section = sensors_of(tmp_path / "pair.urdf", text)
    found = values(section)
    # The far face of the other box is hidden behind its near one: the near face's edges.
    low, high = subtended([(-0.02, -0.28), (0.02, -0.28)])
    ((start, end),) = found["sensors.left.blocked"]
    assert abs(start - low) <= STEP / 2 and abs(end - high) <= STEP / 2, (start, end, low, high)
    assert found["sensors.right.blocked"] == [[-end, -start]]
    # base_link (the rest of the robot), left_link and right_link (each a housing), each
    # made once: a box drawn and colliding, 12 triangles each. (A scene of the robot
    # without each one's housing: 48, 48.)
    assert made == [24, 24, 24]


def test_the_links_no_sensor_can_be_housed_in_are_made_ray_ready_together(tmp_path, made):
    posts = [post(f"post{n}", (0.2, y), 0.02) for n, y in enumerate((-0.1, 0.0, 0.1))]
    _, section = sensors_of(tmp_path / "posts.urdf",
                            robot(lidar_link(), *posts, ray_sensor("lidar_link")))
    assert len(values(section)["sensors.scanner.blocked"]) == 3
    # The body and the three posts at once (4 boxes drawn and colliding); the scanner's
    # own box, its housing, is never cast on.
    assert made == [96]
