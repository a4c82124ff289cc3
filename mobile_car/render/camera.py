"""The four standard views and an orthographic camera fitted to the model's bounds.

Views use ROS axes (x forward, y left, z up) and are named as in CAD drawings:

* ``iso``: from front-left-above, the direction rviz's default orbit camera looks from;
* ``front``: from +x looking back at the robot's face (its left side on the image right);
* ``side``: from the robot's right (-y), x pointing right;
* ``top``: from above, x pointing right and y up, as on a map.

The projection is orthographic, like a drawing: sizes can be compared across the image,
and fitting is exact for a 2 cm caster as well as for the whole robot. Both renderers use
:meth:`Camera.clip_matrix` / :meth:`Camera.pixel_rays`, which agree on where every pixel
centre lies, so their pictures line up pixel for pixel.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# view -> (direction from the model towards the eye, the world axis that should point up)
VIEW_DIRECTIONS = {
    "iso": ((1.0, 1.0, 1.0), (0.0, 0.0, 1.0)),
    "front": ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
    "side": ((0.0, -1.0, 0.0), (0.0, 0.0, 1.0)),
    "top": ((0.0, 0.0, 1.0), (0.0, 1.0, 0.0)),
}
# Free space around the model, as a fraction of the frame's half size.
MARGIN = 0.08
# Size used when there is nothing to draw (a URDF without visual geometry).
EMPTY_HALF_SIZE = 0.1


def view_rotation(view: str) -> np.ndarray:
    """3x3 matrix whose rows are the image's right, up and towards-the-eye world vectors."""
    back, up_hint = (np.array(v, dtype=float) for v in VIEW_DIRECTIONS[view])
    back /= np.linalg.norm(back)
    right = np.cross(up_hint, back)
    right /= np.linalg.norm(right)
    up = np.cross(back, right)
    return np.array([right, up, back])


@dataclass(frozen=True)
class Camera:
    """An orthographic camera: ``rotation`` (rows right, up, back), ``center`` (world point
    at the image centre), ``half_height`` (metres from centre to top edge), the image size in
    pixels, and the depth range (``depth_near`` > ``depth_far``, along ``back``)."""

    rotation: np.ndarray
    center: np.ndarray
    half_height: float
    width: int
    height: int
    depth_near: float
    depth_far: float

    @property
    def half_width(self) -> float:
        return self.half_height * self.width / self.height

    @property
    def pixel_size(self) -> float:
        """Metres covered by one pixel at any depth (orthographic)."""
        return 2.0 * self.half_height / self.height

    def to_view(self, points: np.ndarray) -> np.ndarray:
        """World points (N, 3) as (right, up, back) coordinates around ``center``."""
        return (np.asarray(points, dtype=float) - self.center) @ self.rotation.T

    def to_pixels(self, points: np.ndarray) -> np.ndarray:
        """World points (N, 3) as image coordinates (N, 2): x right, y down, in pixels."""
        view = self.to_view(points)
        x = (view[:, 0] / self.half_width + 1.0) * 0.5 * self.width
        y = (1.0 - view[:, 1] / self.half_height) * 0.5 * self.height
        return np.stack([x, y], axis=1)

    def clip_matrix(self) -> np.ndarray:
        """4x4 world -> OpenGL clip space (float32, row-major; transpose for GL uniforms)."""
        scale = np.diag([1.0 / self.half_width, 1.0 / self.half_height, 1.0])
        depth_mid = 0.5 * (self.depth_near + self.depth_far)
        depth_half = 0.5 * (self.depth_near - self.depth_far)
        linear = scale @ self.rotation
        linear[2] = -self.rotation[2] / depth_half  # nearer (larger back) -> smaller depth
        matrix = np.eye(4)
        matrix[:3, :3] = linear
        matrix[:3, 3] = -linear @ self.center
        matrix[2, 3] += depth_mid / depth_half
        return matrix.astype(np.float32)

    def pixel_rays(self, samples: int = 1) -> tuple[np.ndarray, np.ndarray]:
        """Ray origins (H*s, W*s, 3) on the near plane, and the one shared direction (3,).

        ``samples`` > 1 splits each pixel into samples x samples evenly spaced sub-pixels.
        """
        columns = (np.arange(self.width * samples) + 0.5) / (self.width * samples)
        rows = (np.arange(self.height * samples) + 0.5) / (self.height * samples)
        x = (columns * 2.0 - 1.0) * self.half_width
        y = (1.0 - rows * 2.0) * self.half_height
        right, up, back = self.rotation
        origins = (self.center + back * self.depth_near
                   + x[None, :, None] * right + y[:, None, None] * up)
        return origins, -back


def fit_camera(view: str, points: np.ndarray | None, width: int, height: int) -> Camera:
    """The camera for ``view`` whose frame holds every point with a small margin."""
    rotation = view_rotation(view)
    if points is None or len(points) == 0:
        points = np.array([[-EMPTY_HALF_SIZE] * 3, [EMPTY_HALF_SIZE] * 3])
    points = np.asarray(points, dtype=float)
    view_points = points @ rotation.T
    low, high = view_points.min(axis=0), view_points.max(axis=0)
    mid = 0.5 * (low + high)
    half = 0.5 * (high - low)
    aspect = width / height
    # A flat part seen edge-on still gets a frame: at least 1 % of its largest size.
    floor = max(1e-2 * float(half.max()), 1e-6)
    half_height = max(half[1], half[0] / aspect, floor) * (1.0 + MARGIN)
    depth_pad = max(0.01 * float(half.max()), 1e-6)
    center = mid[0] * rotation[0] + mid[1] * rotation[1]  # depth centre is irrelevant
    return Camera(rotation=rotation, center=center, half_height=float(half_height),
                  width=width, height=height,
                  depth_near=float(high[2] + depth_pad), depth_far=float(low[2] - depth_pad))
