"""Joint markers: what makes a moving joint visible when it moves.

A wheel is a plain cylinder turning about its own axis: drawn alone, turning it changes
no pixel. Each joint a slider moves gets a marker in its child link's frame (the joint's
frame): a line along the joint's axis, long enough to stick out of the part, and at each
end a spoke square to it, which turns with the link like a crank handle (for a prismatic
joint, a cross-bar that slides with it). The viewer moves the markers with the links.
"""

from __future__ import annotations

import numpy as np

# The axis's half-length and the spoke's length, as fractions of the robot's size (the
# diagonal of its bounding box): long enough to reach out of a wheel, short enough not to
# cross the robot.
AXIS_HALF = 0.2
SPOKE = 0.12
AXIS_RGB = (250, 200, 0)  # amber: no URDF colour of the test robots or the car
SPOKE_RGB = (220, 0, 180)  # magenta, as against the amber axis
THICKNESS_PX = 4.0


def perpendicular(axis: np.ndarray) -> np.ndarray:
    """A unit vector square to ``axis``: the one in the plane of the axis and z that
    points most up (for a wheel's y axis, z: the spoke starts upright, as a clock hand
    at twelve); for an axis along z, x."""
    axis = np.asarray(axis, dtype=float)
    for reference in (np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0])):
        side = np.cross(axis, reference)
        if np.linalg.norm(side) > 1e-6:
            spoke = np.cross(side, axis)  # in the plane of axis and reference
            spoke = spoke if np.linalg.norm(spoke) > 1e-6 else side
            return spoke / np.linalg.norm(spoke)
    return np.array([1.0, 0.0, 0.0])


def marker_segments(axis, kind: str, size: float) -> tuple[np.ndarray, np.ndarray]:
    """The marker of a joint with ``axis`` (in its child's frame) on a robot ``size`` m
    across: line segments (N, 2, 3) and their colours (N, 2, 3)."""
    axis = np.asarray(axis, dtype=float)
    length = np.linalg.norm(axis)
    axis = axis / length if length > 1e-12 else np.array([1.0, 0.0, 0.0])
    half, spoke = AXIS_HALF * size * axis, SPOKE * size * perpendicular(axis)
    if kind == "prismatic":  # a cross-bar through the origin slides with the link
        spokes = [(-spoke / 2, spoke / 2)]
    else:  # a spoke at each end turns with it
        spokes = [(half, half + spoke), (-half, -half + spoke)]
    segments = np.array([(-half, half), *spokes], dtype=np.float32)
    colours = np.array([(AXIS_RGB, AXIS_RGB)] + [(SPOKE_RGB, SPOKE_RGB)] * len(spokes),
                       dtype=np.uint8)
    return segments, colours
