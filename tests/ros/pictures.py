"""What a screenshot of RViz shows, for tests/ros/: its 3D view, the pixels of a material's
colour (by hue, which RViz's lighting leaves alone), and the joint slider window."""

from __future__ import annotations

from typing import NamedTuple

BACKGROUND = (48, 48, 48)  # rviz/urdf.rviz's Background Color


def view_box(image) -> tuple[int, int, int, int]:
    """(left, top, right, bottom) of RViz's 3D view: the rows and columns that are mostly
    its background colour (stray pixels of that colour elsewhere, in the slider window's
    text, do not count)."""
    import numpy as np

    background = np.all(np.asarray(image) == BACKGROUND, axis=-1)
    columns = np.nonzero(background.mean(axis=0) > 0.2)[0]
    rows = np.nonzero(background.mean(axis=1) > 0.2)[0]
    if len(columns) == 0 or len(rows) == 0:
        return (0, 0, 0, 0)
    return (int(columns.min()), int(rows.min()), int(columns.max()) + 1, int(rows.max()) + 1)


class Patch(NamedTuple):
    """The pixels of one colour: how many, their centre and bounds (pixels)."""

    count: int
    x: float = 0.0
    y: float = 0.0
    bounds: tuple[int, int, int, int] = (0, 0, 0, 0)


def coloured(image, rgba, box, hue_tolerance: float = 12.0) -> Patch:
    """The pixels in ``box`` with the hue of the material colour ``rgba`` (0..1) as the
    lighting leaves it (shading changes brightness, not hue); saturated, not dark."""
    import colorsys

    import numpy as np

    left, top, right, bottom = box
    hsv = np.asarray(image.crop(box).convert("HSV")).astype(float) / 255
    wanted = colorsys.rgb_to_hsv(*rgba[:3])[0]
    distance = np.abs((hsv[..., 0] - wanted + 0.5) % 1 - 0.5) * 360  # degrees
    ys, xs = np.nonzero((distance < hue_tolerance) & (hsv[..., 1] > 0.2) & (hsv[..., 2] > 0.15))
    if len(xs) == 0:
        return Patch(0)
    return Patch(len(xs), left + float(xs.mean()), top + float(ys.mean()),
                 (left + int(xs.min()), top + int(ys.min()),
                  left + int(xs.max()) + 1, top + int(ys.max()) + 1))


def assert_framed(patch: Patch, box, least: int = 2000) -> None:
    """The robot's main colour fills a good part of RViz's view, centred in its middle
    third, and clear of its edges: the camera frames the whole robot."""
    left, top, right, bottom = box
    assert patch.count > least, patch
    assert abs(patch.x - (left + right) / 2) < (right - left) / 6, (patch, box)
    assert abs(patch.y - (top + bottom) / 2) < (bottom - top) / 6, (patch, box)
    inside = (patch.bounds[0] > left, patch.bounds[1] > top,
              patch.bounds[2] < right, patch.bounds[3] < bottom)
    assert all(inside), f"the robot runs off the view: {patch.bounds} in {box}"


SLIDER = (56, 161, 227)  # Qt's Fusion highlight: the filled part of a QSlider's groove


def slider_bars(image, right: int) -> int:
    """How many horizontal sliders (their filled grooves, 40 pixels or longer) the
    picture shows left of x = ``right``: the joint slider window, where RViz is not."""
    import numpy as np

    pixels = np.asarray(image)[:, :right].astype(int)
    rows = (np.all(np.abs(pixels - SLIDER) < 30, axis=-1).sum(axis=1) >= 40)
    return int(rows[0] + np.sum(rows[1:] & ~rows[:-1]))  # bands of neighbouring rows
