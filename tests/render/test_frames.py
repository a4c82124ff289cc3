"""Link frames drawn as RViz's TF display draws them: the tutorial's skeleton, which has no
geometry, shows its frames' red, green and blue axes and the five link names, in tree order;
robots with geometry keep their picture unless --frames asks for more."""

from __future__ import annotations

import numpy as np
import pytest

SKELETON = "urdf/tutorial/01_skeleton.urdf"
CAR_PART = "tests/render/pkg/urdf/wheel/test_wheel.urdf.xacro"
PLAIN = ("--no-grid", "--no-axes", "--background", "white", "--size", "400x300")


def axis_pixels(picture: np.ndarray) -> dict[str, float]:
    """Share of the picture in each axis colour (frames.AXIS_RGBA, lit or shaded)."""
    red, green, blue = (picture[..., i].astype(int) for i in range(3))
    return {"x": ((red > green + 80) & (red > blue + 80)).mean(),
            "y": ((green > red + 60) & (green > blue + 40)).mean(),
            "z": ((blue > red + 60) & (blue > green + 40)).mean()}


def label_pixels(picture: np.ndarray) -> np.ndarray:
    """Dark text pixels: what the link names are written in."""
    return picture.max(axis=2) < 100


def test_the_skeleton_shows_its_frames_and_names(render):
    picture = render(SKELETON, *PLAIN)
    shares = axis_pixels(picture)
    assert all(share > 0.003 for share in shares.values()), shares
    text = label_pixels(picture)
    assert text.sum() > 300  # five names of ~8 letters
    # the names sit beside the frames' common origin, where the three axes meet
    rows, cols = np.nonzero(text)
    assert 0.2 * 300 < np.median(rows) < 0.8 * 300 and 0.2 * 400 < np.median(cols) < 0.8 * 400


def test_frames_none_leaves_the_skeleton_empty(render, px):
    picture = render(SKELETON, *PLAIN, "--frames", "none")
    assert not px.foreground(picture).any()


def test_the_skeleton_label_lists_the_tree_in_order():
    from mobile_car.render.frames import Frame, labels

    eye = np.eye(4)
    moved = np.eye(4)
    moved[0, 3] = 0.5
    frames = [Frame("base_link", eye, 0), Frame("wheel_1", eye, 1), Frame("hub", eye, 2),
              Frame("arm", moved, 1)]
    assert labels(frames) == (("base_link\n  wheel_1\n    hub", (0.0, 0.0, 0.0)),
                              ("arm", (0.5, 0.0, 0.0)))


def test_a_robot_with_geometry_is_drawn_as_before(render):
    auto = render(CAR_PART, *PLAIN)
    none = render(CAR_PART, *PLAIN, "--frames", "none")
    assert np.array_equal(auto, none)


@pytest.mark.parametrize("choice", ["bare", "all"])
def test_frames_can_be_asked_for_on_a_robot_with_geometry(render, choice):
    plain = render(CAR_PART, *PLAIN, "--frames", "none")
    framed = render(CAR_PART, *PLAIN, "--frames", choice)
    assert not np.array_equal(plain, framed)
    assert label_pixels(framed).sum() > label_pixels(plain).sum()


def test_an_unknown_frames_choice_is_a_usage_error(render):
    result = render(SKELETON, "--frames", "some", expect_exit=2)
    assert "Invalid value for '--frames'" in result.output
