"""The drive's motors as MuJoCo actuators, the same in ``mcar sim`` and ``mcar export --to
mjcf``: a velocity servo on each drive wheel (limited to its motor's effort, N·m), a
position servo on each Ackermann steering joint, and the wheels' armature (kg m²), the
motor's rotor inertia seen through its gearbox. The choices are explained in
:mod:`.model`'s docstring.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .drives import Drive, choose_drive, find_tree
from .motors import motor_figures
from .rollers import tyre_grip

# kv of the wheel motors' velocity servo (N m s/rad) for a wheel driving up to
# SERVO_REFERENCE_INERTIA: stiff enough to follow a ramp of a few rad/s², within the effort
# limit, which clamps it. Heavier loads get a gain in proportion (servo_gain), so the
# servo's time constant stays under 1 ms on every robot (implicitfast integrates the gain
# implicitly: stable at any size). The reference is above the bundled car's 4.7e-4 kg m²
# (0.71 kg on 32.5 mm wheels) and its variants', which keep the gain they were tuned with.
SERVO_GAIN = 0.5
SERVO_REFERENCE_INERTIA = 1e-3  # kg m²
WHEEL_ARMATURE = 1e-4  # kg m², the least, see model.py's docstring ...
ARMATURE_SHARE = 0.25  # ... and of the wheel's share of the robot's m·r², if more
STEER_STIFFNESS = 0.005  # rad a steering servo yields to a tyre's full friction
GRAVITY = 9.81


@dataclass
class DriveSources:
    """What a drive's motor figures and friction are read from, kept from the URDF before
    anything is taken out of it: its top-level ``<gazebo>`` and ``<ros2_control>``
    elements, the joints a transmission drives, link -> ``<mu1>``; and ``declared``, the
    drive declarations (:mod:`.declared`: the URDF's plugins, located, then the controllers
    its control package configures), None for the URDF's plugins alone."""

    figures: list
    actuated: set[str]
    friction: dict[str, float]
    declared: list | None = None
    mecanum: list = field(default_factory=list)  # .mecanum.Declaration: what says mecanum

    def declarations(self, joints: dict) -> list:
        """The drive declarations that are this robot's, the URDF's plugins first."""
        from .declared import in_urdf, meant_for

        found = in_urdf(self.figures) if self.declared is None else self.declared
        return [d for d in found if meant_for(d, joints)]


def fit_drive(mj, shape, data, joints: dict, sources: DriveSources, lowest: dict, left=None,
              right=None, kind=None, effort=None,
              speed=None) -> tuple[Drive | None, str | None]:
    """The drive of a compiled model (kinematics done on ``data``; ``lowest``: its geoms'
    lowest points, :func:`.model.lowest_points`) with its driven wheels' motor figures and
    servo gains, or (None, why there is none); what ``mcar export --to mjcf`` gives MuJoCo
    users too."""
    tree = find_tree(mj, shape, data, joints, lowest, sources.actuated)
    drive, why = choose_drive(tree, sources.actuated, left, right, kind,
                              sources.declarations(joints), sources.mecanum)
    if drive is not None:
        drive.not_wheels = dict(tree.not_wheels)
    mass = float(shape.body_mass.sum())
    for wheel in drive.driven if drive else []:
        slip = sources.friction.get(wheel.link, 1.0) if drive.kind == "skid-steer" else None
        if drive.kind == "mecanum":  # its tyre's grip, not its rollers' free roll
            slip = tyre_grip(wheel, sources)[0]
        wheel.motor = motor_figures(sources.figures, joints[wheel.joint], wheel.radius,
                                    len(drive.driven), mass, effort, speed, slip, drive.kind)
        wheel.effort, wheel.velocity = wheel.motor.effort, wheel.motor.velocity
        wheel.gain = servo_gain(mass, wheel.radius, len(drive.driven),
                                wheel_armature(mass, drive.radius, len(drive.wheels)))
    return drive, why


def add_motors(mj, spec, drive: Drive | None, mass: float) -> None:
    """The armature on every wheel and steering joint, a velocity servo (``mcar_motor_J``)
    on each driven wheel and a position servo (``mcar_steer_J``) on each steering joint."""
    if drive is None:
        return
    armature = wheel_armature(mass, drive.radius, len(drive.wheels))
    for wheel in drive.wheels:
        spec.joint(wheel.joint).armature = armature
    for wheel in drive.driven:
        actuator = spec.add_actuator(name=f"mcar_motor_{wheel.joint}", target=wheel.joint,
                                     trntype=mj.mjtTrn.mjTRN_JOINT)
        actuator.set_to_velocity(kv=wheel.gain)
        _limit_force(actuator, wheel.effort)
    for steer in drive.steering:
        spec.joint(steer.joint).armature = armature
        actuator = spec.add_actuator(name=f"mcar_steer_{steer.joint}", target=steer.joint,
                                     trntype=mj.mjtTrn.mjTRN_JOINT)
        actuator.set_to_position(kp=steering_gain(mass, drive.radius, len(drive.wheels)),
                                 dampratio=1.0)
        if steer.effort is not None:
            _limit_force(actuator, steer.effort)


def _limit_force(actuator, effort: float | None) -> None:
    # MuJoCo refuses an empty range: a motor of no effort gets a vanishing one.
    effort = max(effort if effort is not None else 0.0, 1e-12)
    actuator.forcelimited = True
    actuator.forcerange = [-effort, effort]


def steering_gain(mass: float, radius: float, wheels: int) -> float:
    """kp of a steering servo (N·m/rad): a tyre's whole friction (mu 1) on its share of
    the weight, pushing at the wheel's radius from the pivot, turns it by STEER_STIFFNESS
    rad at most."""
    return mass * GRAVITY * max(radius, 1e-3) / max(1, wheels) / STEER_STIFFNESS


def wheel_armature(mass: float, radius: float, wheels: int) -> float:
    """A wheel joint's armature (kg m²): WHEEL_ARMATURE, or ARMATURE_SHARE of the wheel's
    share of the robot's m·r² where that is more."""
    return max(WHEEL_ARMATURE, ARMATURE_SHARE * mass * radius ** 2 / max(1, wheels))


def servo_gain(mass: float, radius: float, drive_wheels: int,
               armature: float = WHEEL_ARMATURE) -> float:
    """kv for a wheel that accelerates its share of the robot: SERVO_GAIN up to the
    reference load, in proportion above it."""
    load = mass * radius ** 2 / max(1, drive_wheels) + armature
    return SERVO_GAIN * max(1.0, load / SERVO_REFERENCE_INERTIA)
