"""The parts a drive is made of: its wheels, steering joints, the drive (its kind and
wheel groups) and the tree they were found in. Kept apart from :mod:`.drives`, which finds
them, so that :mod:`.mecanum` can make a Drive without importing its finder."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass
class Wheel:
    joint: str
    link: str
    joint_id: int
    body_id: int
    geom_ids: list[int]
    radius: float       # m
    x: float            # wheel centre in the root frame (m)
    y: float
    effort: float | None = None
    velocity: float | None = None
    actuator_id: int = -1
    motor: object = None  # MotorFigures: effort and speed limits with their sources
    gain: float = 0.0     # the velocity servo's kv (N·m·s/rad)
    steering: str | None = None  # the revolute joint that steers it
    grip: tuple[float, float] | None = None  # mecanum: its rollers' grip axis (.mecanum)


@dataclass
class Steering:
    """A steering joint and the wheel it turns; ``sign`` is +1 when a positive joint angle
    turns the wheel to the left (its axis points up), -1 when it points down."""

    joint: str
    joint_id: int
    wheel: Wheel
    x: float            # pivot in the root frame (m)
    y: float
    sign: float
    lower: float | None  # rad, the joint's <limit>
    upper: float | None
    effort: float | None  # N·m, the joint's <limit effort>, None when it gives none
    actuator_id: int = -1


@dataclass
class Drive:
    kind: str
    left: list[Wheel]    # the driven wheels, by side
    right: list[Wheel]
    free: list[Wheel] = field(default_factory=list)  # wheels that roll undriven
    steering: list[Steering] = field(default_factory=list)  # ackermann: left, right
    chosen: str = "found from the tree"  # or "declared", "--drive", "--left/--right"
    sources: dict = field(default_factory=dict)  # driven joint -> where it came from
    not_wheels: dict = field(default_factory=dict)  # Tree.not_wheels, for the report
    declared: str = ""   # mecanum: the declaration that made it so, or the rollers
    grip_from: str = ""  # mecanum: where the rollers' grip axes came from
    grip_mu: dict = field(default_factory=dict)  # mecanum: joint -> (mu, mu across, source)
    centre: list[Wheel] = field(default_factory=list)  # bicycle: the driven centre-line wheels

    @property
    def driven(self) -> list[Wheel]:
        return self.left + self.right + self.centre

    @property
    def wheels(self) -> list[Wheel]:
        """Every wheel that rolls on the floor, driven or not."""
        return self.driven + self.free

    @property
    def track(self) -> float:
        """The distance between the left and right driven wheels' centre lines (m); 0 for
        a bicycle, whose wheels are all on the centre line."""
        if not (self.left and self.right):
            return 0.0
        return float(np.mean([w.y for w in self.left]) - np.mean([w.y for w in self.right]))

    @property
    def radius(self) -> float:
        return float(np.mean([w.radius for w in self.driven]))

    @property
    def rear(self) -> list[Wheel]:
        """Ackermann and bicycle: the unsteered wheels (their axle is the turn's reference)."""
        return [w for w in self.wheels if w.steering is None]

    @property
    def wheelbase(self) -> float:
        """Ackermann and bicycle: from the rear axle (wheel) to the steering pivots (m)."""
        return float(np.mean([s.x for s in self.steering]) - np.mean([w.x for w in self.rear]))


@dataclass
class Tree:
    """What was found of the robot's wheels before a kind is chosen."""

    wheels: list[Wheel]            # drive candidates: neither rollers nor castors
    steering: list[Steering]       # revolute upright joints, each above one wheel
    rollers: list[str]             # wheels below another wheel
    castor_wheels: list[str]       # links of wheels on a swivel
    odd_steering: list[str] = field(default_factory=list)  # above several wheels
    joints: dict = field(default_factory=dict)  # URDF joint name -> element
    make: object = None            # joint name -> Wheel, for a wheel named on the command line
    # continuous joints moving collision geometry that are no wheel: joint -> why (for notes)
    not_wheels: dict = field(default_factory=dict)
    roller_grip: dict = field(default_factory=dict)  # hub joint -> its rollers' grip axis
