"""The share of its grip a driven mecanum wheel pushes with in MuJoCo, measured on the robot's
own wheel alone: what the climb proof expects a mecanum robot to give out at
(docs/specs.md, "Climb").

MuJoCo's contacts, as the proofs set them, hold to Coulomb's law: on the climb proof's
parameters a block of μ 1 slides at 45.000° and a gripping capsule at 45° to the slope at
35.269° (Coulomb: 35.266°), and a sliding contact's friction is μ times its normal force
to 4 digits. A wheel that is driven at its grip is another matter: its contact slips and
sticks by turns and its normal force swings, and a lone wheel of linorobot2's climbs with
0.970 of its grip (tan θ) under its 3.2 kg share of the robot (0.977 under 1 kg, 0.920
under 10 kg). Where a mecanum robot's climb is limited by its rollers' grip, that share
of it is what MuJoCo can show.

The rig is one wheel of the robot: its radius, armature and servo (the gain the climb proof
drives with, no effort limit: the grip is measured, not the motor), its gripping capsule
and contact pair (friction, solref, solimp, margin) and the proof model's options (time
step, integrator, elliptic cone, impratio), on a carriage that carries its load and slides
up the slope and up off the floor, nothing else. It is driven up slopes as the climb proof
drives the robot (the slope from the start, SETTLE_TIME still, the ramp, the crawl, its
speed over the proof's last MEASURE s, climbing at PROGRESS of r·ω); the steepest slope it
climbs, found by BISECTIONS halvings between the slope FLOOR of its grip holds and the one
its whole grip holds, over the latter (tan θ) is the share."""

from __future__ import annotations

import math

BISECTIONS = 7   # halvings of the interval: 0.05° where the grip holds 35.3°
FLOOR = 0.8      # of the grip: the least share sought (the rig climbs there, or this is it)
GRAVITY = 9.81


def least_share(model, wheels, load: float, omega: float, stiffer: float,
                drive: tuple) -> float:
    """The least :func:`driven_share` of ``wheels`` (sim DriveWheels with a grip axis),
    each under ``load`` kg, its servo's gain in ``model`` times ``stiffer``; a rig run once
    for the wheels alike (a robot's four, as a rule)."""
    shares: dict[tuple, float] = {}
    for wheel in wheels:
        gain = float(model.actuator_gainprm[wheel.actuator_id][0]) * stiffer
        key = _Rig.parameters(model, wheel) + (gain,)
        if key not in shares:
            shares[key] = driven_share(model, wheel, load, omega, gain, drive)
    return min(shares.values())


def driven_share(model, wheel, load: float, omega: float, gain: float,
                 drive: tuple) -> float:
    """The share (0..1) of the grip along the slope that ``wheel`` (a sim DriveWheel with a
    grip axis, in ``model``, the proof's model) climbs with under ``load`` kg, driven at
    ``omega`` rad/s by a velocity servo of ``gain`` N·m·s/rad; ``drive``: the climb
    proof's (seconds driven after the settle, the last seconds measured, the share of
    r·ω that climbs)."""
    rig = _Rig(model, wheel, load, gain)
    holds = rig.coulomb()
    low, high = math.atan(FLOOR * holds), math.atan(holds)
    for _ in range(BISECTIONS):
        middle = 0.5 * (low + high)
        if rig.climbs(middle, omega, drive):
            low = middle
        else:
            high = middle
    return math.tan(low) / holds


class _Rig:
    """The lone wheel on its carriage, compiled once, driven up one slope a run."""

    def __init__(self, model, wheel, load: float, gain: float):
        import numpy as np

        from ..sim.engine import mujoco

        self.mj = mj = mujoco()
        pair = model.pair(f"mcar_grip_{wheel.joint}").id
        capsule = model.geom(f"mcar_grip_{wheel.joint}").id
        dof = model.jnt_dofadr[wheel.joint_id]
        self.grip = (wheel.grip[0], wheel.grip[1])
        self.mu = (float(model.pair_friction[pair][0]), float(model.pair_friction[pair][1]))
        self.radius = float(wheel.radius)
        spec = mj.MjSpec()
        spec.option.timestep = model.opt.timestep
        spec.option.integrator = model.opt.integrator
        spec.option.cone = mj.mjtCone.mjCONE_ELLIPTIC
        spec.option.impratio = model.opt.impratio
        floor = spec.worldbody.add_geom(name="floor", type=mj.mjtGeom.mjGEOM_PLANE,
                                        size=[1, 1, 1], contype=0, conaffinity=0)
        cart = spec.worldbody.add_body(name="cart", pos=[0, 0, self.radius])
        cart.add_joint(type=mj.mjtJoint.mjJNT_SLIDE, axis=[1, 0, 0])
        cart.add_joint(type=mj.mjtJoint.mjJNT_SLIDE, axis=[0, 0, 1])
        spinning = float(model.body_mass[wheel.body_id])
        cart.add_geom(type=mj.mjtGeom.mjGEOM_SPHERE, size=[0.01, 0, 0], contype=0,
                      conaffinity=0, mass=max(load - spinning, 1e-3))
        body = cart.add_body(name="wheel", mass=max(spinning, 1e-3),
                             inertia=[float(v) for v in model.body_inertia[wheel.body_id]])
        body.add_joint(name="axle", type=mj.mjtJoint.mjJNT_HINGE, axis=[0, 1, 0],
                       armature=float(model.dof_armature[dof]))
        size = model.geom_size[capsule]
        along = np.zeros(4)
        mj.mju_quatZ2Vec(along, np.array([self.grip[0], self.grip[1], 0.0]))
        tyre = body.add_geom(name="tyre", type=mj.mjtGeom.mjGEOM_CAPSULE,
                             size=[float(size[0]), float(size[1]), 0], quat=along,
                             contype=0, conaffinity=0, mass=0)
        spec.add_pair(geomname1=tyre.name, geomname2=floor.name,
                      condim=int(model.pair_dim[pair]),
                      friction=[float(v) for v in model.pair_friction[pair]],
                      solref=[float(v) for v in model.pair_solref[pair]],
                      solimp=[float(v) for v in model.pair_solimp[pair]],
                      margin=float(model.pair_margin[pair]), gap=float(model.pair_gap[pair]))
        servo = spec.add_actuator(target="axle", trntype=mj.mjtTrn.mjTRN_JOINT)
        servo.set_to_velocity(kv=gain)
        self.model = spec.compile()
        self.tyre = self.model.geom("tyre").id
        self.rest = self.model.geom_quat[self.tyre].copy()

    @staticmethod
    def parameters(model, wheel) -> tuple:
        """What the rig reads of ``wheel`` in ``model``, as numbers (two wheels alike give
        the same rig)."""
        name = f"mcar_grip_{wheel.joint}"
        pair, capsule = model.pair(name).id, model.geom(name).id
        dof = model.jnt_dofadr[wheel.joint_id]
        return (round(abs(wheel.grip[0]), 9), round(abs(wheel.grip[1]), 9),
                float(wheel.radius), float(model.body_mass[wheel.body_id]),
                *(float(v) for v in model.body_inertia[wheel.body_id]),
                float(model.dof_armature[dof]), *(float(v) for v in model.geom_size[capsule]),
                int(model.pair_dim[pair]),
                *(float(v) for v in model.pair_friction[pair]),
                *(float(v) for v in model.pair_solref[pair]),
                *(float(v) for v in model.pair_solimp[pair]),
                float(model.pair_margin[pair]), float(model.pair_gap[pair]))

    def coulomb(self) -> float:
        """tan of the slope the capsule's grip holds driving straight up it: its friction
        ellipse's reach along the slope."""
        gx, gy = self.grip
        return math.hypot(self.mu[0] * gx, self.mu[1] * gy) / math.hypot(gx, gy)

    def climbs(self, slope: float, omega: float, drive: tuple) -> bool:
        """Whether the rig goes up ``slope`` (rad) as the climb proof's ``drive``
        (:func:`driven_share`) judges the robot."""
        import numpy as np

        from ..sim.run import SETTLE_TIME, ramp

        seconds, measure, progress = drive
        mj, model = self.mj, self.model
        data = mj.MjData(model)
        model.opt.gravity[:] = [-GRAVITY * math.sin(slope), 0.0, -GRAVITY * math.cos(slope)]
        turn, turned = np.zeros(4), np.zeros(4)
        steps = int(round((SETTLE_TIME + seconds) / model.opt.timestep))
        measured = steps - int(round(measure / model.opt.timestep))
        start = 0.0
        for step in range(steps):
            if step == measured:
                start = float(data.qpos[0])
            data.ctrl[0] = ramp(data.time) * omega  # about +y: rolls it up the slope (+x)
            half = -0.5 * float(data.qpos[2])  # the capsule turned back by the wheel's angle
            turn[0], turn[2] = math.cos(half), math.sin(half)
            mj.mju_mulQuat(turned, turn, self.rest)
            model.geom_quat[self.tyre] = turned
            mj.mj_step(model, data)
        expected = self.radius * omega * measure
        return (float(data.qpos[0]) - start) >= progress * expected
