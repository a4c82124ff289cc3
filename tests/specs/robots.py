"""Robots the specs tests measure, as URDF text, with round numbers so that every figure
can be worked out by hand in the test that checks it; made of sim's test parts
(tests/sim/robot_makers.py). Lengths in m, masses in kg."""

from __future__ import annotations

import re

from sim.robot_makers import _ball, _wheel, box_inertia, skid_steer

# A box on two wheels and a castor ball; the root frame at the axle.
BODY = (0.30, 0.20, 0.10)       # size
BODY_AT = (0.05, 0.0, 0.08)     # its centre
BODY_MASS = 4.0
WHEEL_RADIUS, WHEEL_WIDTH, WHEEL_Y, WHEEL_MASS = 0.05, 0.04, 0.13, 0.5
BALL_RADIUS, BALL_AT, BALL_MASS = 0.02, (0.15, 0.0, -0.03), 0.2


def box_on_wheels() -> str:
    """A differential car: the body box, two wheels turning about y whose outer faces
    stand out of the body's sides, a castor ball ahead reaching the wheels' floor."""
    x, y, z = BODY_AT
    body = f'<origin xyz="{x} {y} {z}"/><geometry><box size="{BODY[0]} {BODY[1]} {BODY[2]}"/>' \
        '</geometry>'
    parts = [f"""<?xml version="1.0"?>
<robot name="box_on_wheels">
  <link name="base_link">
    <collision>{body}</collision>
    <inertial><origin xyz="{x} {y} {z}"/><mass value="{BODY_MASS}"/>
      {box_inertia(BODY_MASS, *BODY)}</inertial>
  </link>"""]
    for side, sign in (("left", 1), ("right", -1)):
        parts.append(_wheel(f"wheel_{side}", "base_link", (0, sign * WHEEL_Y, 0), WHEEL_RADIUS,
                            WHEEL_WIDTH, WHEEL_MASS))
    parts.append(_ball("castor", "base_link", BALL_AT, BALL_RADIUS, BALL_MASS))
    parts.append("\n</robot>\n")
    return "".join(parts)


def without_collisions(urdf: str) -> str:
    return re.sub(r"<collision>.*?</collision>", "", urdf, flags=re.S)


PAYLOAD_MASS, PAYLOAD_X = 4.0, 0.15


def four_wheels_loaded() -> str:
    """sim's skid-steer box (20 kg, wheelbase 0.4 m) with a payload of PAYLOAD_MASS kg
    PAYLOAD_X ahead of its centre: four supports, statically indeterminate."""
    # a ball held 0.3 m above the floor: it adds mass, never a support
    payload = _ball("payload", "base_link", (PAYLOAD_X, 0, 0.2), 0.05, PAYLOAD_MASS)
    return skid_steer(extra=payload)
