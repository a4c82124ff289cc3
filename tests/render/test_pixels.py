"""What the pictures show, read from their pixels: size, framing, colours, orientation."""

from __future__ import annotations

import numpy as np
import pytest

PKG = "tests/render/pkg"
TUTORIAL = "urdf/tutorial/03_color.urdf"
CHASSIS = f"{PKG}/urdf/chassis/test_chassis.urdf.xacro"
PLAIN = ("--no-grid", "--no-axes", "--background", "white")


@pytest.mark.parametrize("size", ["200x150", "321x123", "64x480"])
def test_picture_has_the_requested_size(render, size):
    width, height = map(int, size.split("x"))
    assert render(TUTORIAL, "--size", size).shape == (height, width, 3)


def test_view_all_keeps_the_requested_size_and_fills_four_frames(render, px):
    picture = render(TUTORIAL, "--view", "all", "--size", "400x300", *PLAIN)
    assert picture.shape == (300, 400, 3)
    for quarter in (picture[:150, :200], picture[:150, 200:], picture[150:, :200],
                    picture[150:, 200:]):
        share = px.foreground(quarter).mean()
        assert 0.1 < share < 0.9


@pytest.mark.parametrize("model", [TUTORIAL, CHASSIS, f"{PKG}/urdf/caster/test_caster.urdf.xacro",
                                   f"{PKG}/urdf/motor/test_motor.urdf.xacro"])
@pytest.mark.parametrize("view", ["iso", "front", "side", "top"])
def test_model_fills_the_frame_whatever_its_size(render, px, model, view):
    mask = px.foreground(render(model, "--view", view, "--size", "200x150", *PLAIN))
    left, top, width, height = px.silhouette_box(mask)
    # Fitted: the silhouette spans the frame in at least one direction, within the margin,
    assert width >= 0.85 * 200 or height >= 0.85 * 150
    # and it is not cut off at the edges.
    assert left > 0 and top > 0 and left + width < 200 and top + height < 150
    assert 0.05 < mask.mean() < 0.95


def test_wheel_shows_its_material_colour(render):
    picture = render(f"{PKG}/urdf/wheel/test_wheel.urdf.xacro", "--size", "200x150", *PLAIN)
    red, green, blue = (picture[..., i].astype(int) for i in range(3))
    wheel_blue = (blue > red + 60) & (blue > green + 40)  # define.xacro: rgba 0.1 0.25 0.85
    assert wheel_blue.mean() > 0.3


def test_black_wheels_stay_dark_but_show_their_shape(render):
    picture = render(TUTORIAL, "--view", "side", "--size", "200x150", *PLAIN).astype(int)
    dark = picture.max(axis=2) < 90
    assert dark.mean() > 0.1  # the black wheels are there, and dark
    shades = np.unique(picture[dark].sum(axis=1) // 6)
    assert len(shades) > 5  # not a flat silhouette: lighting varies across the tyre


@pytest.mark.parametrize("view, across, down", [
    ("top", 0.2, 0.176),        # x right, y up: plate length 0.2 m, wheel span 0.176 m
    ("front", 0.176, 0.066),    # y right, z up: wheel span, height to the wheel tops
    ("side", 0.2, 0.066),       # x right, z up
])
def test_silhouette_has_the_model_proportions(render, px, view, across, down):
    mask = px.foreground(render(CHASSIS, "--view", view, "--size", "400x300", *PLAIN))
    _, _, width, height = px.silhouette_box(mask)
    assert width / height == pytest.approx(across / down, rel=0.03)


def test_top_view_of_the_car_is_wider_than_tall_along_x(render, px):
    """The chassis is longer in x than in y; x points right in the top view."""
    mask = px.foreground(render(CHASSIS, "--view", "top", "--size", "300x300", *PLAIN))
    _, _, width, height = px.silhouette_box(mask)
    assert width > height


def grey_pixels(image: np.ndarray) -> np.ndarray:
    """The caster ball: unsaturated mid greys (the plate is near white, the wheels blue)."""
    image = image.astype(int)
    return (np.ptp(image, axis=2) < 12) & (image.max(axis=2) < 200) & (image.max(axis=2) > 40)


def test_side_view_shows_the_caster_at_the_front_on_the_right(render):
    """The caster ball sits at +x under the plate; x points right in the side view."""
    _, cols = np.nonzero(grey_pixels(render(CHASSIS, "--view", "side", "--size", "400x300",
                                               *PLAIN)))
    assert len(cols) > 50 and cols.min() > 300


def test_front_view_shows_the_caster_in_the_middle(render):
    _, cols = np.nonzero(grey_pixels(render(CHASSIS, "--view", "front", "--size", "400x300",
                                               *PLAIN)))
    assert len(cols) > 50 and cols.mean() == pytest.approx(200, abs=5)


def test_two_views_differ(render, px):
    iso = render(TUTORIAL, "--size", "200x150")
    top = render(TUTORIAL, "--view", "top", "--size", "200x150")
    assert px.differing_pixels(iso, top).mean() > 0.2


def test_collision_differs_from_visual_only_where_the_geometry_differs(render, px):
    """box_collides_as_sphere: the box collides as a sphere, the post as itself."""
    model = f"{PKG}/models/box_collides_as_sphere.urdf"
    visual = render(model, "--view", "top", "--size", "300x300", *PLAIN)
    collision = render(model, "--view", "top", "--size", "300x300", "--collision", *PLAIN)
    changed = px.differing_pixels(visual, collision)
    assert changed.mean() > 0.01
    # Top view, y up: the post (y = 0.15) is the upper part, the box/sphere the lower part.
    post_rows = slice(0, 110)
    assert not changed[post_rows].any()
    assert px.foreground(visual[post_rows]).mean() > 0.02  # the post is really up there
    def teal(image):
        return (image[..., 1].astype(int) > image[..., 0] + 40).sum()

    assert teal(collision) < teal(visual)  # a disc covers less than the square around it


def test_collision_equal_to_visual_gives_the_same_picture(render):
    model = f"{PKG}/urdf/wheel/test_wheel.urdf.xacro"
    visual = render(model, "--size", "200x150")
    collision = render(model, "--size", "200x150", "--collision")
    assert np.array_equal(visual, collision)


def test_background_option_and_grid_and_axes(render, px):
    plain = render(TUTORIAL, "--size", "200x150", *PLAIN)
    assert (plain[0, 0] == [255, 255, 255]).all()
    with_grid = render(TUTORIAL, "--size", "200x150", "--no-axes", "--background", "white")
    grid_lines = px.differing_pixels(plain, with_grid, tolerance=20)
    assert grid_lines.mean() > 0.01
    with_axes = render(TUTORIAL, "--size", "200x150", "--no-grid", "--background", "white")
    corner = with_axes[110:, :50].astype(int)
    red_x = (corner[..., 0] > 150) & (corner[..., 1] < 100) & (corner[..., 2] < 100)
    blue_z = (corner[..., 2] > 150) & (corner[..., 0] < 100)
    assert red_x.any() and blue_z.any()
    plain_corner = plain[110:, :50].astype(int)
    assert not ((plain_corner[..., 0] > 150) & (plain_corner[..., 1] < 100)).any()


def test_same_input_gives_identical_png_bytes(cli, in_repo, tmp_path):
    first, second = tmp_path / "a.png", tmp_path / "b.png"
    assert cli("render", CHASSIS, "-o", first).exit_code == 0
    assert cli("render", CHASSIS, "-o", second).exit_code == 0
    assert first.read_bytes() == second.read_bytes()


def test_library_render_file_gives_the_same_bytes_as_the_command(cli, in_repo, tmp_path):
    from mobile_car.render import RenderOptions, render_file

    png = render_file(TUTORIAL, RenderOptions(view="side", width=120, height=90))
    out = tmp_path / "cli.png"
    assert cli("render", TUTORIAL, "--view", "side", "--size", "120x90", "-o", out).exit_code == 0
    assert png == out.read_bytes()
