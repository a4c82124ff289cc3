"""``mcar specs --picture``: the figures drawn over the robot, asserted on pixels.

Sections are built by hand, so each test knows where every overlay must land; the last
tests draw a robot written here under them with a real renderer."""

from __future__ import annotations

import contextlib
import io
import math
from pathlib import Path

import click
import numpy as np
import pytest
from click.testing import CliRunner
from PIL import Image

from mobile_car.specs import picture
from mobile_car.specs.figures import Figure, Section

FOOTPRINT = [[0.2, -0.15], [0.2, 0.15], [-0.2, 0.15], [-0.2, -0.15]]
SUPPORT = [[0.15, -0.12], [0.15, 0.12], [-0.15, 0.12], [-0.15, -0.12]]
COM = [0.03, 0.0, 0.1]
COM_HEIGHT = 0.15  # the floor is at z = -0.05 in the root frame
FLOOR_Z = COM[2] - COM_HEIGHT
# Right figures for that CoM: the line from each support edge at its angle meets it.
TIP_FORWARD = math.degrees(math.atan2(0.15 - COM[0], COM_HEIGHT))
TIP_BACKWARD = math.degrees(math.atan2(COM[0] + 0.15, COM_HEIGHT))
LIDAR_POSE = [0.1, 0.0, 0.2, 90.0]  # facing left
BLOCKED = [[60.0, 120.0]]  # in the sensor frame: world azimuths 150..210, behind it


def _figure(key, value):
    return Figure(key, key, value, "", "given by the test")


def sections(**changed) -> list[Section]:
    values = {"body.footprint": FOOTPRINT, "body.com": COM, "body.com_height": COM_HEIGHT,
              "statics.support": SUPPORT, "statics.tip.forward": TIP_FORWARD,
              "statics.tip.backward": TIP_BACKWARD, "sensors.lidar.pose": LIDAR_POSE,
              "sensors.lidar.range": [0.1, 12.0], "sensors.lidar.blocked": BLOCKED}
    values.update(changed)
    by_part = {}
    for key, value in values.items():
        if value is not None:
            by_part.setdefault(key.split(".")[0], []).append(_figure(key, value))
    return [Section(name, figures) for name, figures in by_part.items()]


@pytest.fixture(scope="module")
def views():
    return {view.name: view for view in picture.draw_views(sections())}


def _pixel(view, point) -> tuple[int, int]:
    (x, y), = view.camera.to_pixels(np.array([point], dtype=float))
    return int(x), int(y)


def _rgb(view, point) -> tuple[int, int, int]:
    return view.image.getpixel(_pixel(view, point))


def _near(colour, wanted, tolerance=40) -> bool:
    return max(abs(int(a) - int(b)) for a, b in zip(colour, wanted, strict=True)) <= tolerance


def test_the_footprint_outline_is_drawn_where_the_polygon_is(views):
    top = views["top"]
    for x, y in ((0.2, 0.0), (0.0, 0.15), (-0.2, 0.07), (0.1, -0.15)):
        assert _near(_rgb(top, (x, y, FLOOR_Z)), picture.FOOTPRINT_COLOUR), (x, y)
    # Inside and outside it, no outline colour.
    for x, y in ((0.17, 0.0), (0.23, 0.0)):
        assert not _near(_rgb(top, (x, y, FLOOR_Z)), picture.FOOTPRINT_COLOUR), (x, y)


def test_the_support_polygon_is_outlined_and_filled(views):
    top = views["top"]
    assert _near(_rgb(top, (0.15, 0.05, FLOOR_Z)), picture.SUPPORT_COLOUR)
    # (off the grid lines, every 10 cm)
    inside, outside = _rgb(top, (-0.07, 0.05, FLOOR_Z)), _rgb(top, (-0.17, 0.05, FLOOR_Z))
    assert inside != outside  # the light fill
    assert inside[0] > outside[0] and inside[2] < outside[2]  # towards orange


def test_the_centre_of_mass_marker_is_at_its_projected_pixel(views):
    assert _rgb(views["top"], (COM[0], COM[1], FLOOR_Z)) == picture.COM_COLOUR
    assert _rgb(views["side"], COM) == picture.COM_COLOUR


def test_a_blocked_sector_is_shaded_and_the_open_ones_are_not(views):
    top = views["top"]
    x, y = LIDAR_POSE[:2]

    def at(azimuth, distance=0.12):
        a = math.radians(azimuth)
        return _rgb(top, (x + distance * math.cos(a), y + distance * math.sin(a), FLOOR_Z))

    blocked = at(180.0)  # sensor azimuth 90 + its yaw 90
    for open_azimuth in (100.0, 260.0):  # same distance, same overlays under it
        open_ = at(open_azimuth)
        assert blocked != open_
        # purple over what is there: more blue than red, less green
        assert blocked[1] < open_[1] - 30 and blocked[2] > blocked[1] + 40, (blocked, open_)


def test_the_tip_lines_run_from_the_support_edges_through_the_centre_of_mass(views):
    side = views["side"]
    for edge in (0.15, -0.15):
        for share in (0.25, 0.5, 0.75):  # along the line, short of the CoM marker
            point = (edge + share * (COM[0] - edge), 0.0, FLOOR_Z + share * COM_HEIGHT)
            assert _near(_rgb(side, point), picture.TIP_COLOUR), (edge, share)


def test_the_floor_is_a_line_at_the_floor_height(views):
    side = views["side"]
    assert _near(_rgb(side, (0.18, 0.0, FLOOR_Z)), picture.FLOOR_COLOUR, 20)
    assert not _near(_rgb(side, (0.18, 0.0, FLOOR_Z + 0.03)), picture.FLOOR_COLOUR, 20)


def test_a_figure_that_was_not_computed_is_not_drawn():
    top, side = picture.draw_views(sections(**{"statics.support": None,
                                               "statics.tip.forward": None,
                                               "sensors.lidar.blocked": None}))
    image = np.asarray(top.image).astype(int)
    orange = np.abs(image - np.array(picture.SUPPORT_COLOUR)).max(axis=2) <= 20
    assert not orange.any()
    purple = np.abs(image - np.array(picture.BLOCKED_COLOUR)).max(axis=2) <= 20
    assert not purple.any()
    # the backward line is still drawn (from the footprint's back edge), the forward not
    rise = 0.5 * COM_HEIGHT * math.tan(math.radians(TIP_BACKWARD))
    back = (-0.2 + rise, 0.0, FLOOR_Z + 0.5 * COM_HEIGHT)
    assert _near(_rgb(side, back), picture.TIP_COLOUR)
    front = (0.15 - rise, 0.0, FLOOR_Z + 0.5 * COM_HEIGHT)
    assert not _near(_rgb(side, front), picture.TIP_COLOUR)


def test_the_picture_is_the_two_views_side_by_side(views):
    png, notes = picture.specs_picture(sections())
    assert notes == []
    with Image.open(io.BytesIO(png)) as image:
        assert image.format == "PNG"
        image = image.convert("RGB")
        width, height = picture.CELL
        assert image.width == 2 * width + 3 * picture.PAD
        for index, name in enumerate(("top", "side")):
            cell = np.asarray(picture.cell(image, index))
            assert np.array_equal(cell, np.asarray(views[name].image))


# A box on four ball wheels, resting on them: the floor is at z = 0 of base_link.
CART = """<?xml version="1.0"?>
<robot name="cart">
  <link name="base_link">
    <collision><origin xyz="0 0 0.15"/><geometry><box size="0.4 0.3 0.1"/></geometry>
    </collision>
    <inertial><origin xyz="0 0 0.15"/><mass value="4"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
  </link>
""" + "".join(f"""
  <joint name="ball_{i}_joint" type="fixed"><parent link="base_link"/>
    <child link="ball_{i}"/><origin xyz="{x} {y} 0.05"/></joint>
  <link name="ball_{i}"><collision><geometry><sphere radius="0.05"/></geometry></collision>
  </link>""" for i, (x, y) in enumerate([(0.15, 0.1), (0.15, -0.1), (-0.15, 0.1),
                                         (-0.15, -0.1)])) + "\n</robot>\n"
CART_COM = [0.0, 0.0, 0.15]


def cart_sections() -> list[Section]:
    support = [[0.15, -0.1], [0.15, 0.1], [-0.15, 0.1], [-0.15, -0.1]]
    tip = math.degrees(math.atan2(0.15, 0.15))
    return sections(**{"body.com": CART_COM, "body.com_height": 0.15,
                       "statics.support": support, "statics.tip.forward": tip,
                       "statics.tip.backward": tip, "sensors.lidar.pose": None,
                       "sensors.lidar.blocked": None})


@pytest.fixture(scope="module")
def cart(tmp_path_factory):
    from mobile_car.check.checker import check_input
    from mobile_car.load.inputs import RobotInput

    path = tmp_path_factory.mktemp("cart") / "cart.urdf"
    path.write_text(CART)
    return check_input(RobotInput(path))


@pytest.fixture(scope="module")
def cart_views(cart):
    from mobile_car.errors import RendererUnavailableError
    from mobile_car.render.backend import open_renderer

    try:
        drawer, _ = open_renderer("auto")
    except RendererUnavailableError as error:
        pytest.skip(f"no renderer here: {error.message}")
    scene = picture.robot_scene(cart)
    return {v.name: v for v in picture.draw_views(cart_sections(), scene, drawer)}


def test_the_robot_is_drawn_under_the_figures(cart_views):
    top, side = cart_views["top"], cart_views["side"]
    bare = {v.name: v for v in picture.draw_views(cart_sections())}
    # The body inside the footprint is the robot's, not the background of the bare view.
    for point in ((0.1, 0.13, 0.0), (-0.18, -0.05, 0.0)):
        assert _rgb(top, point) != _rgb(bare["top"], point)
    assert _rgb(side, (0.1, 0.0, 0.17)) != _rgb(bare["side"], (0.1, 0.0, 0.17))
    # A ball wheel stands on the floor in the side view: drawn just above the floor line.
    assert _rgb(side, (0.15, 0.0, 0.02)) != _rgb(bare["side"], (0.15, 0.0, 0.02))
    # ... and the overlays are drawn over it
    assert _near(_rgb(top, (0.2, 0.0, 0.0)), picture.FOOTPRINT_COLOUR)
    assert _rgb(top, (0.0, 0.0, 0.0)) == picture.COM_COLOUR
    assert _rgb(side, CART_COM) == picture.COM_COLOUR


def test_the_options_write_the_picture_atomically(cart, tmp_path, monkeypatch):
    from mobile_car.cli.common import start_probe
    from mobile_car.cli.specs_picture import check_picture_name, picture_options, write_picture

    from mobile_car.errors import RendererUnavailableError

    @click.command()
    @picture_options
    def command(picture, renderer):
        check_picture_name(picture)
        with contextlib.ExitStack() as stack:
            probe = start_probe(stack, renderer)
            write_picture(picture, cart_sections(), cart, renderer, probe)

    target = tmp_path / "specs.png"
    result = CliRunner().invoke(command, ["--picture", str(target)])
    if isinstance(result.exception, RendererUnavailableError):
        pytest.skip(f"no renderer here: {result.exception.message}")
    assert result.exit_code == 0, result.output
    with Image.open(target) as image:
        assert image.size == (2 * picture.CELL[0] + 3 * picture.PAD,
                              picture.CELL[1] + picture.CAPTION_SIZE + 3 * picture.PAD)

    # A drawing that fails leaves the earlier picture whole.
    before = target.read_bytes()

    def broken(*args, **kwargs):
        raise RuntimeError("the renderer died")

    monkeypatch.setattr(picture, "specs_picture", broken)
    result = CliRunner().invoke(command, ["--picture", str(target)])
    assert isinstance(result.exception, RuntimeError)
    assert target.read_bytes() == before


def test_a_picture_name_that_is_not_png_is_refused_before_any_work():
    from mobile_car.cli.specs_picture import check_picture_name

    from mobile_car.errors import UsageError

    with pytest.raises(UsageError) as caught:
        check_picture_name("specs.jpg")
    assert caught.value.message == ("--picture specs.jpg: mcar specs draws PNG pictures, "
                                    "not .jpg; name it specs.png")


def test_the_picture_is_never_written_over_the_robot(cart):
    from mobile_car.cli.specs_picture import write_picture

    from mobile_car.errors import McarError

    robot = Path(cart.loaded.input.path)
    text = robot.read_bytes()
    with pytest.raises(McarError):
        write_picture(str(robot), cart_sections(), cart)
    assert robot.read_bytes() == text
