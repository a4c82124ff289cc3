"""The camera: fitting frames small and large models alike, and views that point the right way."""

from __future__ import annotations

import numpy as np
import pytest

from mobile_car.render.camera import MARGIN, fit_camera

VIEWS = ["iso", "front", "side", "top"]


def cloud(scale: float, offset=(0.0, 0.0, 0.0), seed=0) -> np.ndarray:
    points = np.random.default_rng(seed).uniform(-1, 1, size=(500, 3)) * [1.0, 0.6, 0.3]
    return points * scale + np.array(offset)


@pytest.mark.parametrize("view", VIEWS)
@pytest.mark.parametrize("scale", [0.01, 0.3, 20.0])  # a 2 cm caster ... a large robot
def test_fit_holds_every_point_and_fills_the_frame(view, scale):
    camera = fit_camera(view, cloud(scale, offset=(5 * scale, -2 * scale, scale)), 800, 600)
    pixels = camera.to_pixels(cloud(scale, offset=(5 * scale, -2 * scale, scale)))
    assert pixels.min() >= 0 and (pixels[:, 0] <= 800).all() and (pixels[:, 1] <= 600).all()
    used_width = np.ptp(pixels[:, 0]) / 800
    used_height = np.ptp(pixels[:, 1]) / 600
    # The tighter direction is filled up to the margin on both sides.
    assert max(used_width, used_height) == pytest.approx(1 / (1 + MARGIN), rel=1e-6)
    centre = pixels.min(axis=0) + np.ptp(pixels, axis=0) / 2
    assert centre == pytest.approx([400, 300], abs=1e-6)


def image_direction(view: str, axis) -> np.ndarray:
    """Where a world axis points in the picture, as (right, down) pixels."""
    camera = fit_camera(view, cloud(1.0), 800, 600)
    start, end = camera.to_pixels(np.array([[0.0, 0.0, 0.0], axis]))
    return np.round(end - start, 6)


def test_top_view_shows_x_right_and_y_up():
    assert image_direction("top", [1, 0, 0])[0] > 0
    assert image_direction("top", [0, 1, 0])[1] < 0


def test_front_view_looks_from_plus_x_so_the_robot_left_is_on_the_right():
    assert image_direction("front", [0, 1, 0])[0] > 0
    assert image_direction("front", [0, 0, 1])[1] < 0
    assert image_direction("front", [1, 0, 0]) == pytest.approx([0, 0])


def test_side_view_looks_from_minus_y_with_x_right():
    assert image_direction("side", [1, 0, 0])[0] > 0
    assert image_direction("side", [0, 0, 1])[1] < 0


def test_iso_view_keeps_z_up_and_shows_front_and_left():
    assert image_direction("iso", [0, 0, 1])[0] == pytest.approx(0)
    assert image_direction("iso", [0, 0, 1])[1] < 0
    camera = fit_camera("iso", cloud(1.0), 800, 600)
    towards_eye = camera.rotation[2]
    assert towards_eye[0] > 0 and towards_eye[1] > 0 and towards_eye[2] > 0


@pytest.mark.parametrize("view", VIEWS)
def test_gl_clip_matrix_and_pixel_mapping_agree(view):
    """The GL renderer and the ray caster must put every point on the same pixel."""
    points = cloud(0.5, offset=(0.1, 0.2, 0.3), seed=1)
    camera = fit_camera(view, points, 640, 480)
    homogeneous = np.c_[points, np.ones(len(points))] @ camera.clip_matrix().T
    ndc = homogeneous[:, :3] / homogeneous[:, 3:]
    from_gl = np.c_[(ndc[:, 0] + 1) / 2 * 640, (1 - ndc[:, 1]) / 2 * 480]
    assert from_gl == pytest.approx(camera.to_pixels(points), abs=1e-3)
    assert (np.abs(ndc[:, 2]) < 1).all()  # all inside the depth range: nothing clipped


def test_pixel_rays_start_at_pixel_centres_in_front_of_the_model():
    points = cloud(0.2, seed=2)
    camera = fit_camera("iso", points, 40, 30)
    origins, direction = camera.pixel_rays()
    assert origins.shape == (30, 40, 3)
    pixels = camera.to_pixels(origins.reshape(-1, 3)).reshape(30, 40, 2)
    assert pixels[0, 0] == pytest.approx([0.5, 0.5])
    assert pixels[29, 39] == pytest.approx([39.5, 29.5])
    towards_eye = -direction
    assert (origins.reshape(-1, 3) @ towards_eye).min() > (points @ towards_eye).max()


def test_an_empty_model_still_gets_a_frame():
    camera = fit_camera("iso", None, 200, 150)
    assert camera.half_height > 0 and np.isfinite(camera.clip_matrix()).all()
