"""The share of its grip a driven mecanum wheel, or tyre, pushes with in MuJoCo, measured on
the robot's own wheel alone: what the climb proof expects a mecanum robot, or one whose
climb its grip binds, to give out at (docs/specs.md, "Climb").

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
its whole grip holds, over the latter (tan θ) is the share.

A tyre (:func:`tyre_share`, for a robot whose climb its grip binds) is rigged the same
way with the wheel's own colliding geoms (the sphere sim rounds a cylinder into, a mesh
tyre's mesh) and each one's contact settings against a floor with the model's floor's,
which MuJoCo mixes as on the robot, and its joint's damping and friction. It gives out
short of its grip as a mecanum wheel does: Panther's climbs with 0.977 of it under a
quarter of the robot and 0.943 under the 25 kg its rear wheel carries at 45°, Leo's
with 0.983 under 2.4 kg, on servos 5 times sim's gain; at 20 times, under a quarter of
the robot, Panther's with 0.937 and Leo's with 0.951 (docs/specs.md, "Grip-bound
climb")."""

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
    return _share(lambda slope: rig.climbs(slope, omega, drive), rig.coulomb())


def _share(climbs, holds: float) -> float:
    """tan of the steepest slope ``climbs(slope rad)`` is true of, bisected between the
    slopes FLOOR of ``holds`` (tan θ) and ``holds`` hold, over ``holds``."""
    low, high = math.atan(FLOOR * holds), math.atan(holds)
    for _ in range(BISECTIONS):
        middle = 0.5 * (low + high)
        if climbs(middle):
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
        spec = _spec(mj, model, mj.mjtCone.mjCONE_ELLIPTIC)
        floor = spec.worldbody.add_geom(name="floor", type=mj.mjtGeom.mjGEOM_PLANE,
                                        size=[1, 1, 1], contype=0, conaffinity=0)
        body = _carriage(mj, spec, model, wheel, load)
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

        turn, turned = np.zeros(4), np.zeros(4)

        def roller(data) -> None:  # the capsule turned back by the wheel's angle
            half = -0.5 * float(data.qpos[2])
            turn[0], turn[2] = math.cos(half), math.sin(half)
            self.mj.mju_mulQuat(turned, turn, self.rest)
            self.model.geom_quat[self.tyre] = turned

        return _climbs(self.mj, self.model, self.radius, slope, omega, drive, roller)


def _climbs(mj, model, radius: float, slope: float, omega: float, drive: tuple,
            each_step=None) -> bool:
    """Whether a rig (a carriage sliding along x and z, its wheel's servo the first
    actuator) goes up ``slope`` (rad) as the climb proof's ``drive`` judges the robot;
    ``each_step(data)`` before every step."""
    from ..sim.run import SETTLE_TIME, ramp

    seconds, measure, progress = drive
    data = mj.MjData(model)
    model.opt.gravity[:] = [-GRAVITY * math.sin(slope), 0.0, -GRAVITY * math.cos(slope)]
    steps = int(round((SETTLE_TIME + seconds) / model.opt.timestep))
    measured = steps - int(round(measure / model.opt.timestep))
    start = 0.0
    for step in range(steps):
        if step == measured:
            start = float(data.qpos[0])
        data.ctrl[0] = ramp(data.time) * omega  # about +y: rolls it up the slope (+x)
        if each_step is not None:
            each_step(data)
        mj.mj_step(model, data)
    expected = radius * omega * measure
    return (float(data.qpos[0]) - start) >= progress * expected


def tyre_share(model, sim, wheel, load: float, omega: float, gain: float,
               drive: tuple) -> float:
    """:func:`driven_share` for a wheel that rolls on its own geoms (a tyre, not a
    mecanum wheel's gripping capsule): the share (0..1) of its grip, the friction its
    geoms have in ``model``, that it climbs with under ``load`` kg. ``sim``: the SimModel
    (its floor and the geoms the robot stands on)."""
    rig = _TyreRig(model, sim, wheel, load, gain)
    return _share(lambda slope: _climbs(rig.mj, rig.model, rig.radius, slope, omega, drive),
                  rig.mu)


class _TyreRig:
    """A lone wheel on its carriage as :class:`_Rig`, touching the floor with the wheel's
    own geoms (the spheres sim rounds cylinders into, its meshes), each with its contact
    settings, on a floor with the model's floor's: MuJoCo mixes them as on the robot. The
    axle keeps the joint's damping and friction (Leo's 0.31 N·m)."""

    def __init__(self, model, sim, wheel, load: float, gain: float):
        import numpy as np

        from ..sim.engine import mujoco

        self.mj = mj = mujoco()
        self.radius = float(wheel.radius)
        dof = model.jnt_dofadr[wheel.joint_id]
        geoms = [g for g in sim.support_geoms if model.geom_bodyid[g] == wheel.body_id]
        self.mu = max(float(model.geom_friction[g][0]) for g in geoms)
        spec = _spec(mj, model, model.opt.cone)
        floor = spec.worldbody.add_geom(type=mj.mjtGeom.mjGEOM_PLANE, size=[1, 1, 1])
        _contact_like(floor, model, sim.floor_geom)
        body = _carriage(mj, spec, model, wheel, load)
        body.add_joint(name="axle", type=mj.mjtJoint.mjJNT_HINGE, axis=[0, 1, 0],
                       armature=float(model.dof_armature[dof]),
                       damping=float(model.dof_damping[dof]),
                       frictionloss=float(model.dof_frictionloss[dof]))
        # The wheel's frame turned so that its joint's axis is the rig's y, the geoms
        # placed from the joint's anchor.
        onto_z, turn = np.zeros(4), np.zeros(4)
        mj.mju_quatZ2Vec(onto_z, np.array(model.jnt_axis[wheel.joint_id], float))
        mj.mju_negQuat(onto_z, onto_z)
        mj.mju_mulQuat(turn, np.array([math.sqrt(0.5), -math.sqrt(0.5), 0.0, 0.0]), onto_z)
        anchor = model.jnt_pos[wheel.joint_id]
        for g in geoms:
            pos, quat = np.zeros(3), np.zeros(4)
            mj.mju_rotVecQuat(pos, model.geom_pos[g] - anchor, turn)
            mj.mju_mulQuat(quat, turn, model.geom_quat[g])
            tyre = body.add_geom(type=mj.mjtGeom(int(model.geom_type[g])), mass=0,
                                 size=[float(v) for v in model.geom_size[g]],
                                 pos=[float(v) for v in pos], quat=[float(v) for v in quat])
            if model.geom_type[g] == mj.mjtGeom.mjGEOM_MESH:
                mesh = model.geom_dataid[g]
                first, count = model.mesh_vertadr[mesh], model.mesh_vertnum[mesh]
                spec.add_mesh(name=f"tyre{g}", uservert=[
                    float(v) for v in model.mesh_vert[first:first + count].ravel()])
                tyre.meshname = f"tyre{g}"
            _contact_like(tyre, model, g)
        servo = spec.add_actuator(target="axle", trntype=mj.mjtTrn.mjTRN_JOINT)
        servo.set_to_velocity(kv=gain)
        self.model = spec.compile()


def _spec(mj, model, cone):
    """An empty MjSpec with the proof model's time step, integrator and impratio, and
    ``cone``."""
    spec = mj.MjSpec()
    spec.option.timestep = model.opt.timestep
    spec.option.integrator = model.opt.integrator
    spec.option.cone = cone
    spec.option.impratio = model.opt.impratio
    return spec


def _carriage(mj, spec, model, wheel, load: float):
    """The carriage every rig runs on, at the wheel's radius above the floor, sliding
    along the slope (x) and off it (z), carrying ``load`` kg with the wheel: the wheel's
    body (its mass and inertia), its axle still to add."""
    cart = spec.worldbody.add_body(name="cart", pos=[0, 0, float(wheel.radius)])
    cart.add_joint(type=mj.mjtJoint.mjJNT_SLIDE, axis=[1, 0, 0])
    cart.add_joint(type=mj.mjtJoint.mjJNT_SLIDE, axis=[0, 0, 1])
    spinning = float(model.body_mass[wheel.body_id])
    cart.add_geom(type=mj.mjtGeom.mjGEOM_SPHERE, size=[0.01, 0, 0], contype=0,
                  conaffinity=0, mass=max(load - spinning, 1e-3))
    return cart.add_body(name="wheel", mass=max(spinning, 1e-3),
                         inertia=[float(v) for v in model.body_inertia[wheel.body_id]])


def _contact_like(geom, model, g: int) -> None:
    """Give the spec's ``geom`` the contact settings of ``model``'s geom ``g``."""
    geom.contype, geom.conaffinity = int(model.geom_contype[g]), int(model.geom_conaffinity[g])
    geom.condim, geom.priority = int(model.geom_condim[g]), int(model.geom_priority[g])
    geom.friction = [float(v) for v in model.geom_friction[g]]
    geom.solref = [float(v) for v in model.geom_solref[g]]
    geom.solimp = [float(v) for v in model.geom_solimp[g]]
    geom.margin, geom.gap = float(model.geom_margin[g]), float(model.geom_gap[g])
    geom.solmix = float(model.geom_solmix[g])
