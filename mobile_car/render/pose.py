"""``mcar render --joint NAME=VALUE``: the joint positions a picture is drawn with.

Values take units as ``--set`` does (``30deg``, ``5cm``; a bare number is radians or
metres, by the joint's type); a joint the robot lacks, a fixed or mimic joint, and a value
outside the joint's limits are usage errors naming the robot's file.
"""

from __future__ import annotations

import difflib
from typing import TYPE_CHECKING

from ..errors import UsageError

if TYPE_CHECKING:
    import yourdfpy

MOVING = ("revolute", "continuous", "prismatic")


def parse_joint_word(word: str) -> tuple[str, str]:
    """``"shoulder=30deg"`` -> ``("shoulder", "30deg")``; UsageError otherwise."""
    name, sep, value = word.partition("=")
    if not sep or not name.strip() or not value.strip():
        raise UsageError(f"--joint '{word}' is not NAME=VALUE (e.g. --joint shoulder=30deg)")
    return name.strip(), value.strip()


def joint_positions(robot: yourdfpy.Robot, requests, file: str) -> dict[str, float]:
    """The positions ``requests`` ((name, text) pairs) give, checked against ``robot``."""
    from ..config.units import parse_quantity

    joints = {joint.name: joint for joint in robot.joints}
    positions: dict[str, float] = {}
    for name, text in requests:
        joint = joints.get(name)
        if joint is None:
            close = difflib.get_close_matches(name, sorted(joints), n=1, cutoff=0.6)
            hint = f"; did you mean '{close[0]}'?" if close else ""
            movable = sorted(j.name for j in robot.joints if j.type in MOVING and j.mimic is None)
            listed = f" (movable joints: {', '.join(movable)})" if movable and not close else ""
            raise UsageError(f"--joint {name}: no joint of that name{hint}{listed}", file=file)
        if joint.type not in MOVING:
            raise UsageError(f"--joint {name}: a {joint.type} joint; only revolute, continuous "
                             "and prismatic joints move", file=file)
        if joint.mimic is not None:
            raise UsageError(f"--joint {name}: it mimics '{joint.mimic.joint}'; "
                             "set that joint instead", file=file)
        unit = "m" if joint.type == "prismatic" else "rad"
        try:
            value = parse_quantity(text, unit, f"--joint {name}")
        except UsageError as error:
            raise UsageError(error.message, file=file) from None
        limit = joint.limit
        if joint.type != "continuous" and limit is not None and None not in (limit.lower,
                                                                             limit.upper):
            if not limit.lower <= value <= limit.upper:
                raise UsageError(f"--joint {name}: {text} is outside the joint's limits, "
                                 f"{limit.lower:g} to {limit.upper:g} {unit}", file=file)
        positions[name] = value
    return positions
