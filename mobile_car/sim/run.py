"""One scenario's simulation: a fresh state with the robot at its rest height, stepped
with a control callback (the wheel and steering commands) and per-step observers (the
measurements, the recorder); and the commands every scenario shares: the wheel speed, the
0.5 s ramp up to it, which way each wheel turns forward. Times in s, speeds in rad/s."""

from __future__ import annotations

import math

import numpy as np

from .engine import mujoco
from .model import GROUND_TOLERANCE, SimModel

SETTLE_TIME = 0.5        # s on the floor before the wheels start
RAMP_TIME = 0.5          # s for the wheels' speed to ramp linearly up to the command
DEFAULT_SPEED = 10.0     # rad/s when the joints give no velocity limit ...
DEFAULT_LINEAR_SPEED = 0.5  # m/s: ... or less on large wheels, a walking pace
# A wheel is off the floor when its tyre is higher than this share of its radius above it
# for at least BOUNCE_TIME: a shorter or smaller bounce is contact noise, not a lift-off.
BOUNCE_HEIGHT = 0.01               # of the wheel radius
BOUNCE_TIME = 0.020                # s


class Run:
    """One scenario's simulation: a fresh state, the robot at rest height (+ lift),
    stepping with an optional callback per step (the recorder)."""

    def __init__(self, sim: SimModel, lift: float = 0.0, frame=None):
        self.mj = mujoco()
        self.sim, self.model = sim, sim.model
        self.data = self.mj.MjData(self.model)
        free = self.model.joint("mcar_free").id
        adr = self.model.jnt_qposadr[free]
        self.free = adr
        self.free_dof = self.model.jnt_dofadr[free]  # vx vy vz (world), wx wy wz (root)
        self.data.qpos[adr + 2] = sim.rest_height + lift
        if sim.rest is not None:  # released in the pose it rests in (leaning on a castor)
            self.data.qpos[adr + 3:adr + 7] = sim.rest.quat
        for joint, position in sim.start.items():  # the springs at rest under the weight
            self.data.qpos[self.model.jnt_qposadr[self.model.joint(joint).id]] = position
        self.rollers = getattr(sim, "rollers", None)  # mecanum: kept level every step
        if self.rollers is not None:
            self.rollers.align(self.model, self.data)
        self.mj.mj_forward(self.model, self.data)
        self.frame = frame

    def step(self, seconds: float, control=None, each=None) -> None:
        steps = int(round(seconds / self.model.opt.timestep))
        for _ in range(steps):
            if control is not None:
                control(self.data.time)
            if self.rollers is not None:
                self.rollers.align(self.model, self.data)
            self.mj.mj_step(self.model, self.data)
            if each is not None:
                each()
            if self.frame is not None:
                self.frame(self.model, self.data)

    @property
    def position(self) -> np.ndarray:
        return self.data.qpos[self.free:self.free + 3].copy()

    def euler(self) -> tuple[float, float, float]:
        """roll, pitch, yaw (rad) of the root."""
        w, x, y, z = self.data.qpos[self.free + 3:self.free + 7]
        roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
        pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
        yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
        return roll, pitch, yaw

    def yaw(self) -> float:
        """The root's yaw (rad), for the observers called every step."""
        w, x, y, z = self.data.qpos[self.free + 3:self.free + 7]
        return math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))

    def on_floor(self) -> set[int]:
        """Bodies touching the floor now."""
        touching = set()
        floor = self.sim.floor_geom
        for i in range(self.data.ncon):
            contact = self.data.contact[i]
            if contact.dist > GROUND_TOLERANCE / 3:
                continue
            if contact.geom1 == floor:
                touching.add(int(self.model.geom_bodyid[contact.geom2]))
            elif contact.geom2 == floor:
                touching.add(int(self.model.geom_bodyid[contact.geom1]))
        return touching

    def at_effort_limit(self, wheel) -> bool:
        limit = self.model.actuator_forcerange[wheel.actuator_id][1]
        return abs(float(self.data.actuator_force[wheel.actuator_id])) >= 0.99 * limit

    def tyre_gap(self, wheel) -> float | None:
        """Height of the wheel's lowest sphere (its tyre) above the floor, or None when
        its geometry is no sphere (then contacts tell)."""
        gaps = [float(self.data.geom_xpos[g][2] - self.model.geom_size[g][0])
                for g in wheel.geom_ids if int(self.model.geom_type[g]) in _tyres(self.mj)]
        return min(gaps) if gaps else None

    def wheel_speed(self, wheel) -> float:
        return float(self.data.qvel[self.model.jnt_dofadr[wheel.joint_id]])

    def joint_angle(self, joint_id: int) -> float:
        return float(self.data.qpos[self.model.jnt_qposadr[joint_id]])

    def centre_of(self, wheels) -> np.ndarray:
        """The mean of the wheels' centres (the axle centre of a differential robot)."""
        return self.data.xpos[[w.body_id for w in wheels]].mean(axis=0)


def _tyres(mj) -> tuple:
    """The geom types a wheel rolls on whose lowest point is its centre's height less its
    radius: a sphere, and a mecanum wheel's capsule, kept level (:mod:`.rollers`)."""
    return (int(mj.mjtGeom.mjGEOM_SPHERE), int(mj.mjtGeom.mjGEOM_CAPSULE))


def ramp(t: float) -> float:
    """The share of the commanded speed at time ``t``: 0 while settling, then a linear
    ramp to 1."""
    return min(1.0, max(0.0, t - SETTLE_TIME) / RAMP_TIME) if t > SETTLE_TIME else 0.0


def command_speed(sim: SimModel) -> float:
    """Half the smallest velocity limit of the driven joints (rad/s); without one (or
    where it is a placeholder, :data:`.motors.MAX_RIM_SPEED`), DEFAULT_SPEED or
    DEFAULT_LINEAR_SPEED, whichever is slower on these wheels."""
    driven = sim.drive.driven
    limits = [_usable(w) for w in driven]
    limits = [v for v in limits if v and v > 0]
    if limits:
        return 0.5 * min(limits)
    radius = max(w.radius for w in driven)
    return min(DEFAULT_SPEED, DEFAULT_LINEAR_SPEED / radius) if radius > 0 else DEFAULT_SPEED


def _usable(wheel) -> float | None:
    """The wheel's speed limit, None where its motor figures call it a placeholder."""
    motor = wheel.motor
    return motor.usable_velocity if motor is not None else wheel.velocity


def wheel_command(model, actuator: int, velocity: float) -> float:
    """What to ask of a wheel's velocity servo so that it turns at ``velocity`` against the
    losses its joint declares (``<dynamics damping friction>``, in the model as the dof's
    damping and frictionloss): a servo without integral action settles where its torque
    kv·(command − ω) equals the loss, short of the command with torque to spare; asking
    for the loss's worth more, known beforehand, settles it at ``velocity``. Its force
    range still bounds it: losses past the motor's effort still drive short, and the cause
    says so (:mod:`.causes`). An integral term did the same and wound up at the effort
    limit, making the run chaotic (1e-10 m at the start turned the car 1.5°)."""
    kv = float(model.actuator_gainprm[actuator][0])
    if kv <= 0 or velocity == 0:
        return velocity
    dof = int(model.jnt_dofadr[model.actuator_trnid[actuator][0]])
    loss = float(model.dof_damping[dof]) * velocity + \
        float(model.dof_frictionloss[dof]) * math.copysign(1.0, velocity)
    return velocity + loss / kv


def ramped(run: Run, commands):
    """The control callback driving each (actuator, speed) of ``commands`` along the ramp,
    each servo told its wheel's declared losses (:func:`wheel_command`)."""
    def control(t: float) -> None:
        share = ramp(t)
        for actuator, speed in commands:
            run.data.ctrl[actuator] = wheel_command(run.model, actuator, share * speed)
    return control


def forward_sign(run: Run, wheel) -> float:
    """+1 if turning the joint positively rolls the robot forward (+x), else -1."""
    axis = run.data.xaxis[wheel.joint_id]
    return 1.0 if axis[1] >= 0 else -1.0


def wrap(angle: float) -> float:
    return (angle + math.pi) % (2 * math.pi) - math.pi


class OffFloor:
    """Called once per step: the time the wheels spend off the floor, counting only
    lift-offs higher than BOUNCE_HEIGHT of the radius and lasting BOUNCE_TIME or more."""

    def __init__(self, run: Run, wheels):
        self.run, self.wheels = run, list(wheels)
        self.height = BOUNCE_HEIGHT * min(w.radius for w in self.wheels)
        self.step = run.model.opt.timestep
        self.current, self.total = 0, 0
        # Each wheel's tyre spheres, read at once every step (numpy, not a loop per wheel);
        # a wheel without one is judged by its contacts.
        model = run.model
        pairs = [(i, g) for i, w in enumerate(self.wheels) for g in w.geom_ids
                 if int(model.geom_type[g]) in _tyres(run.mj)]
        self.owner = np.array([i for i, _ in pairs], dtype=int)
        self.spheres = np.array([g for _, g in pairs], dtype=int)
        self.radii = model.geom_size[self.spheres, 0]
        self.rolling = np.zeros(len(self.wheels), dtype=bool)
        self.rolling[self.owner] = True
        self.contact_only = [w for i, w in enumerate(self.wheels) if not self.rolling[i]]

    def __call__(self) -> None:
        gaps = self.run.data.geom_xpos[self.spheres, 2] - self.radii
        lowest = np.full(len(self.wheels), np.inf)
        np.minimum.at(lowest, self.owner, gaps)  # each wheel's lowest sphere
        up = bool((lowest[self.rolling] > self.height).any())
        if not up and self.contact_only:
            touching = self.run.on_floor()
            up = any(w.body_id not in touching for w in self.contact_only)
        if up:
            self.current += 1
            return
        self.finish()

    def finish(self) -> None:
        if self.current * self.step >= BOUNCE_TIME - 1e-9:
            self.total += self.current
        self.current = 0

    @property
    def seconds(self) -> float:
        return self.total * self.step


class Yaw:
    """Called once per step: the yaw turned since it was made (rad, unwrapped), and how far
    ``centre()`` strayed from where it was (m, in the floor's plane)."""

    def __init__(self, run: Run, centre):
        self.run, self.centre = run, centre
        self.last = run.yaw()
        self.turned = 0.0
        self.start = centre()
        self.strayed = 0.0

    def __call__(self) -> None:
        yaw = self.run.yaw()
        self.turned += wrap(yaw - self.last)
        self.last = yaw
        self.strayed = max(self.strayed,
                           float(np.linalg.norm((self.centre() - self.start)[:2])))
