"""Suspension and wheel drop as MuJoCo simulates them: a ``prismatic`` or ``revolute``
joint between the body and a drive wheel (Create 3's and TurtleBot 4's
``wheel_drop_*_joint``, PMB2's suspension, Warthog's rockers) is a spring, not a weld.

Its stiffness and reference come from the description where it gives them (the joint's
``<gazebo reference="JOINT">`` block: ``<springStiffness>``, ``<springReference>``, as
Gazebo reads them), its damping from ``<dynamics damping>`` (else that block's
``<damping>``); else the spring is one that carries the wheels' share of the robot's
weight at mid-travel, its reference at the end of travel the floor pushes away from, so
that under load it rests in the middle of its limits. A joint without a travel (no
``<limit>``, or lower = upper) is held still, as before. Lengths in m, angles in rad,
stiffness in N/m or N·m/rad.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..check.urdf_model import parse_number
from .drives import UPRIGHT

GRAVITY = 9.81
# Where the description gives no damping: a fraction of critical damping for the wheel's
# share of the mass on the spring, so that a drop settles within its 2 s.
DAMPING_RATIO = 0.7
LIMIT_TIME_CONSTANT = 0.004  # s, a spring's end stops (MuJoCo's default 0.02)
# A suspension's travel is under a metre or a turn: a joint limited wider is no spring.
MAX_TRAVEL = 1.0        # m
MAX_TURN = 2 * np.pi    # rad
# A declared spring is used where MuJoCo can follow it: its period on the mass it carries
# at least this many steps, its reference within this many half-travels of the middle.
STEPS_PER_PERIOD = 10
REFERENCE_REACH = 100


@dataclass
class Spring:
    joint: str
    lower: float
    upper: float
    stiffness: float
    reference: float      # the joint position at which the spring pushes nothing
    damping: float
    source: str           # where the stiffness came from
    rest: float           # the position the spring rests at under its share of the weight
    prismatic: bool

    def as_json(self) -> dict:
        return {"joint": self.joint, "travel": [round(self.lower, 6), round(self.upper, 6)],
                "unit": "m" if self.prismatic else "rad",
                "stiffness": float(f"{self.stiffness:.6g}"),
                "damping": float(f"{self.damping:.6g}"),
                "reference": round(self.reference, 6), "rest": round(self.rest, 6),
                "source": self.source}

    def text(self) -> str:
        unit, per = ("mm", 1000) if self.prismatic else ("deg", 180 / np.pi)
        stiff = "N/m" if self.prismatic else "N·m/rad"
        return (f"{self.joint} {per * self.lower:.4g}..{per * self.upper:.4g} {unit}, "
                f"{self.stiffness:.4g} {stiff} ({self.source})")


def sprung_joints(model, data, joints: dict, wheel_bodies, not_springs: set[str]) -> list[str]:
    """The revolute and prismatic joints between the root and the bodies of
    ``wheel_bodies`` (of a compiled model, kinematics done on ``data``), except
    ``not_springs`` and upright hinges: those steer (an Ackermann car driven as
    skid-steer keeps its steering welded straight)."""
    found = []
    for body in wheel_bodies:
        body = int(model.body_parentid[body]) if body else 0
        while body > 0:
            for j in range(model.body_jntadr[body],
                           model.body_jntadr[body] + model.body_jntnum[body]):
                name = model.joint(j).name
                element = joints.get(name)
                upright = element is not None and element.get("type") == "revolute" and \
                    abs(data.xaxis[j][2]) > UPRIGHT
                if (element is not None and element.get("type") in ("revolute", "prismatic")
                        and name not in not_springs and name not in found and not upright):
                    found.append(name)
            body = int(model.body_parentid[body])
    return found


def make_springs(mj, model, data, joints: dict, names: list[str], wheels, supports: int,
                 mass: float, gazebo: dict, timestep: float) -> list[Spring]:
    """A Spring for each of ``names`` that has a travel (kinematics done on ``data``, every
    joint at 0); ``wheels``: the drive's wheels (Wheel), ``supports``: how many parts share
    the robot's weight (wheels and castors); ``gazebo``: joint -> its ``<gazebo>`` block."""
    springs = []
    share = mass * GRAVITY / max(1, supports)
    mj.mj_forward(model, data)
    for name in names:
        limit = _child(joints[name], "limit")
        lower = _number(limit, "lower")
        upper = _number(limit, "upper")
        prismatic = joints[name].get("type") == "prismatic"
        if lower is None or upper is None or not 0 < upper - lower <= (
                MAX_TRAVEL if prismatic else MAX_TURN):
            continue  # no travel, or none a suspension has: held still
        joint = model.joint(name).id
        lever = _lever(mj, model, data, joint, [w for w in wheels
                                                 if _below(model, w.body_id, joint)])
        # The floor pushes the wheels up: towards higher q where the lever is > 0.
        load = share * sum(lever)  # generalised force of the floor's push at rest
        declared = gazebo.get(name, {})
        mass_on = max(mass / max(1, supports), 1e-6)
        effective = mass_on * (max(map(abs, lever), default=1.0) ** 2 or 1.0)
        stiffness, reference, source = _declared(declared, effective, timestep, lower, upper)
        if stiffness is None:
            stiffness, reference = _default_spring(load, share, lever, lower, upper)
            source = "default: carries its share of the weight at mid-travel" + source
        rest = float(np.clip(reference + load / stiffness, lower, upper))
        damping = _number(_child(joints[name], "dynamics"), "damping")
        if damping is None or damping <= 0:
            damping = declared.get("damping")
        if damping is None or damping <= 0:
            damping = 2 * DAMPING_RATIO * np.sqrt(stiffness * effective)
        springs.append(Spring(name, lower, upper, float(stiffness), float(reference),
                              float(damping), source, rest, prismatic))
    return springs


def _declared(declared: dict, effective: float, timestep: float, lower: float,
              upper: float) -> tuple[float | None, float, str]:
    """(stiffness, reference, '') of the joint's <gazebo> spring, or (None, 0, why it is
    not used): a stiffness MuJoCo cannot step (its period under STEPS_PER_PERIOD steps on
    the mass it carries) or a reference over REFERENCE_REACH half-travels from the
    middle would throw the robot into the air (1e300 N/m: NaN in one step)."""
    stiffness = declared.get("springStiffness")
    if stiffness is None or stiffness <= 0:
        return None, 0.0, ""
    reference = declared.get("springReference", 0.0)
    most = effective * (2 * np.pi / (STEPS_PER_PERIOD * timestep)) ** 2
    if stiffness > most:
        return None, 0.0, (f" (<gazebo> springStiffness {stiffness:g} is over the {most:.4g} "
                           "a 1 ms step can follow)")
    middle, half = (lower + upper) / 2, (upper - lower) / 2
    if abs(reference - middle) > REFERENCE_REACH * half:
        return None, 0.0, (f" (<gazebo> springReference {reference:g} is far outside its "
                           f"{lower:g}..{upper:g} travel)")
    return stiffness, reference, "<gazebo> springStiffness"


def _default_spring(load, share, lever, lower, upper) -> tuple[float, float]:
    """(stiffness, reference) of a spring that rests at mid-travel under ``load``: its
    reference at the end of travel the floor pushes away from. A rocker's wheels push
    it both ways (load ~0): a spring centred on its middle, as stiff as one wheel's share
    would need over half the travel, so that it still follows the floor."""
    middle, half = (lower + upper) / 2, (upper - lower) / 2
    single = share * max((abs(x) for x in lever), default=0.0)
    if abs(load) < 0.1 * single or single <= 0:
        return max(single, 1e-6) / half, middle
    return abs(load) / half, lower if load > 0 else upper


def apply_springs(mj, spec, springs: list[Spring]) -> None:
    for spring in springs:
        joint = spec.joint(spring.joint)
        # (MuJoCo 4 takes stiffness and damping as polynomials: the linear term first.)
        joint.stiffness = [spring.stiffness, 0.0, 0.0]
        joint.springref = spring.reference
        joint.damping = [spring.damping, 0.0, 0.0]
        joint.limited = mj.mjtLimited.mjLIMITED_TRUE  # its travel is the joint's limits
        joint.range = [spring.lower, spring.upper]
        # A wheel drop bottoms out under a heavy robot (TurtleBot 4: 25 N a wheel on a
        # spring that gives 13.5 N): MuJoCo's soft default limit lets it sink ~1 mm past
        # its stop, tilting the robot 0.5 degrees more than its geometry does.
        joint.solref_limit = [LIMIT_TIME_CONSTANT, 1.0]


def gazebo_joint_blocks(root) -> dict[str, dict[str, float]]:
    """joint -> the numbers of its ``<gazebo reference="JOINT">`` block (springStiffness,
    springReference, damping), read before the blocks are taken out of the tree."""
    joints = {j.get("name") for j in root if j.tag == "joint"}
    found: dict[str, dict[str, float]] = {}
    for gazebo in root.iter("gazebo"):
        name = gazebo.get("reference")
        if name not in joints:
            continue
        for key in ("springStiffness", "springReference", "damping"):
            element = gazebo.find(key)
            value = parse_number(element.text.strip()) if element is not None and \
                element.text else None
            if value is not None:
                found.setdefault(name, {})[key] = value
    return found


def _lever(mj, model, data, joint: int, wheels) -> list[float]:
    """For each wheel under ``joint``: how much its contact point rises per unit of the
    joint (m/m or m/rad), the robot's body held still."""
    dof = int(model.jnt_dofadr[joint])
    levers = []
    for wheel in wheels:
        point = data.xpos[wheel.body_id].copy()
        point[2] -= wheel.radius
        jacp = np.zeros((3, model.nv))
        mj.mj_jac(model, data, jacp, None, point, wheel.body_id)
        levers.append(float(jacp[2, dof]))
    return levers


def _below(model, body: int, joint: int) -> bool:
    owner = int(model.jnt_bodyid[joint])
    while body > 0:
        if body == owner:
            return True
        body = int(model.body_parentid[body])
    return False


def _number(element, key):
    return parse_number(element.get(key)) if element is not None and element.get(key) else None


def _child(element, tag):
    for child in element:
        if child.tag == tag:
            return child
    return None
