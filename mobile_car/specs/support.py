"""What a robot stands on, read from sim's model at rest: the points where its wheels and
castors (and any other part resting on the floor) touch it, each with the friction it
holds with and the way it may roll, and its centre of mass above the floor. The statics
(:mod:`.statics`) and their proofs (:mod:`.proof_tilt`) start from this.

Frames: the floor frame of docs/specs.md (x forward, y left, origin below the root's
origin at rest). Lengths in m. A geom counts as resting when its lowest point is within
sim's GROUND_TOLERANCE of the floor (a castor a few mm up: the robot rocks onto it before
it tips); it touches along the patch within FLAT of its own lowest point (a wheel's one
point, a bicycle tyre's width, a block's bottom face)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

# m: the points of a geom this close to its lowest one touch the floor with it (a
# bicycle's tyre across its width, a block's bottom face: equal but for rounding); no
# more: TurtleBot3's castor block, leaning back with the robot at rest, touches by its
# back edge, and its front edge 0.1 mm up counted as touching put the castor's load
# 15 mm ahead of where MuJoCo carries it (its slide figure 1.7° off); and that edge is
# itself askew (its rpy -1.57, not -π/2): one corner 16 µm over the other, which MuJoCo,
# sinking 2 µm under the castor's load, never touches. Counted, the castor's load sat
# on the centre line, not on the corner: the wheels' shares 0.374 each where MuJoCo
# gives 0.390 and 0.359, and the slide figure 1° off towards azimuth 195°.
FLAT = 0.000002
# m: a geom whose lowest point is this close to the floor at rest touches it
TOUCHING = 0.0001
# A declared μ over this is no tyre's (rubber on concrete: ~1; MuJoCo went NaN in its
# first step on 1e300): not used, as sim leaves out a spring no suspension has.
MAX_FRICTION = 10.0
# A castor (a cylinder standing upright, a puck) touches along its rim: so many points.
RIM_POINTS = 16


@dataclass
class Contact:
    """One point the robot touches the floor at (floor frame, m): ``hold`` says how it
    resists sliding: "held" in every direction (a braked drive wheel, a block),
    "axle" only along ``axis`` (a wheel rolling free: it rolls across its axle), "free"
    not at all (a castor wheel on a swivel); ``mu`` its friction coefficient and
    ``mu_from`` where that comes from."""

    x: float
    y: float
    link: str
    body: int
    role: str          # "driven", "free wheel", "castor", "part"
    hold: str
    mu: float
    mu_from: str
    axis: tuple[float, float] = (0.0, 0.0)
    touching: bool = True  # at rest (not a castor a few mm up, which it rocks onto)
    stiffness: float = 1.0  # its share of the load, where several share it, goes by it


@dataclass
class Stance:
    """The robot at rest on the floor: its contacts, centre of mass (floor frame, its
    height above the floor), mass (kg), and the rest pose's root height."""

    contacts: list[Contact]
    com: tuple[float, float, float]
    mass: float
    notes: list[str] = field(default_factory=list)

    @property
    def points(self) -> list[tuple[float, float]]:
        return [(c.x, c.y) for c in self.contacts]


def rest_data(sim):
    """A MjData of ``sim`` in its rest pose (as sim's runs release it), forward done."""
    from ..sim.engine import mujoco

    mj = mujoco()
    model, data = sim.model, mj.MjData(sim.model)
    free = int(model.jnt_qposadr[model.joint("mcar_free").id])
    data.qpos[free + 2] = sim.rest_height
    if sim.rest is not None:
        data.qpos[free + 3:free + 7] = sim.rest.quat
    for joint, position in sim.start.items():
        data.qpos[model.jnt_qposadr[model.joint(joint).id]] = position
    mj.mj_forward(model, data)
    return data


def stance(sim, described: dict[str, float], friction: float | None) -> Stance:
    """The robot's stance at rest. ``described``: link -> the ``<mu1>`` its description
    gives (:func:`mobile_car.sim.model.gazebo_friction`); ``friction``: the tyres' mu
    where it gives none (``--friction``), else MuJoCo's default, 1."""
    from ..sim.model import GROUND_TOLERANCE

    model = sim.model
    data = rest_data(sim)
    origin = data.xpos[sim.root_body]
    drive = sim.drive
    driven = {w.body_id: w for w in drive.driven} if drive else {}
    free_wheels = {w.body_id: w for w in drive.free} if drive else {}
    contacts, notes = [], []
    skip = set()
    if drive is not None and drive.kind == "mecanum":
        contacts, skip = _mecanum(sim, data, origin)
    for g in sim.support_geoms:
        if int(model.geom_bodyid[g]) in skip:
            continue
        points = _lowest_patch(model, data, g)
        if not points or min(p[2] for p in points) > GROUND_TOLERANCE:
            continue
        body = int(model.geom_bodyid[g])
        link = model.body(body).name
        mu, mu_from = _friction(model, sim.floor_geom, g, link, described,
                                friction if (body in driven or body in free_wheels) else None,
                                notes)
        if body in driven:
            role, hold, axis = "driven", "held", (0.0, 0.0)
        elif body in free_wheels:
            role, hold = "free wheel", "axle"
            axis = _axle(data, free_wheels[body].joint_id)
        else:
            role = _role(sim, link)
            hold, axis = _how_it_holds(sim, data, body)
        touching = min(p[2] for p in points) <= TOUCHING
        for x, y, _z in points:
            contacts.append(Contact(float(x - origin[0]), float(y - origin[1]), link, body,
                                    role, hold, mu, mu_from, axis, touching,
                                    _stiffness(model, body)))
    com = data.subtree_com[sim.root_body]
    return Stance(contacts, (float(com[0] - origin[0]), float(com[1] - origin[1]),
                             float(com[2])), float(sim.mass), notes)


def _role(sim, link: str) -> str:
    """What a resting part other than a wheel is: one of sim's castors on a robot with a
    drive, or one named a castor (PR2's, which sim does not drive); on a robot without
    drive wheels nothing else is a castor (UR5e's base_link_inertia, Go1's feet): a
    "part". (Which part is its base cannot be told from sim's model: the joints it holds
    still weld Go1's feet to its trunk as its fixed joints weld UR5e's base.)"""
    from ..sim.model import CASTOR_WORDS

    if link in sim.ground_parts and (sim.drive is not None
                                     or any(w in link.lower() for w in CASTOR_WORDS)):
        return "castor"
    return "part"


def _stiffness(model, body: int) -> float:
    """A contact's stiffness, as MuJoCo's soft contacts have it: in proportion to the
    mass its body moves (1 / its translational inverse weight, ``body_invweight0``: the
    constraint's regularisation goes by it). Where more contacts than three share the
    load (MiR's two wheels and four castors) it decides their shares: its castor wheels,
    light on their swivels, carry 9% each in MuJoCo, its wheels 31%; equally stiff
    contacts would have put 17% on each."""
    weight = float(model.body_invweight0[body][0])
    return 1.0 / weight if weight > 0 else 1.0


def _mecanum(sim, data, origin) -> tuple[list[Contact], set[int]]:
    """A mecanum wheel touches below its hub (sim's capsule, :mod:`mobile_car.sim.rollers`)
    and holds only along its rollers' grip axis, braked or not (they roll across it);
    its own geometry and its rollers' are off the floor (the bodies to skip)."""
    from ..sim.rollers import roller_bodies

    drive, contacts = sim.drive, []
    for wheel in drive.wheels:
        x, y = data.xpos[wheel.body_id][:2]
        gx, gy = wheel.grip if wheel.grip is not None else (1.0, 0.0)
        norm = math.hypot(gx, gy) or 1.0
        mu, _across, source = drive.grip_mu.get(wheel.joint, (1.0, 0.0, "MuJoCo's default"))
        contacts.append(Contact(float(x - origin[0]), float(y - origin[1]), wheel.link,
                                wheel.body_id, "driven" if wheel in drive.driven else
                                "free wheel", "axle", float(mu), f"mecanum grip ({source})",
                                (gx / norm, gy / norm), True,
                                _stiffness(sim.model, wheel.body_id)))
    skip = {w.body_id for w in drive.wheels} | roller_bodies(sim.model, drive.wheels)
    return contacts, skip


def _lowest_patch(model, data, g) -> list[tuple[float, float, float]]:
    """The points of geom ``g`` (world, at rest) within FLAT of its lowest point."""
    import numpy as np

    from ..sim.engine import mujoco

    mj = mujoco()
    kind = mj.mjtGeom(int(model.geom_type[g]))
    centre = np.array(data.geom_xpos[g])
    rot = np.array(data.geom_xmat[g]).reshape(3, 3)
    size = model.geom_size[g]
    down = np.array([0.0, 0.0, -1.0])
    if kind == mj.mjtGeom.mjGEOM_SPHERE:
        candidates = [centre + size[0] * down]
    elif kind in (mj.mjtGeom.mjGEOM_CAPSULE, mj.mjtGeom.mjGEOM_CYLINDER):
        axis = rot[:, 2]
        ends = [centre + size[1] * axis, centre - size[1] * axis]
        if kind == mj.mjtGeom.mjGEOM_CAPSULE:
            candidates = [end + size[0] * down for end in ends]
        else:
            across = down - axis * float(down @ axis)  # down, square to the axis
            if np.linalg.norm(across) < 1e-6:  # upright: its whole rim touches
                u, v = rot[:, 0], rot[:, 1]
                candidates = [end + size[0] * (math.cos(t) * u + math.sin(t) * v)
                              for end in ends for t in
                              (2 * math.pi * k / RIM_POINTS for k in range(RIM_POINTS))]
            else:
                across /= np.linalg.norm(across)
                candidates = [end + size[0] * across for end in ends]
    elif kind == mj.mjtGeom.mjGEOM_BOX:
        candidates = [centre + rot @ (size * np.array(signs)) for signs in
                      ((a, b, c) for a in (-1, 1) for b in (-1, 1) for c in (-1, 1))]
    elif kind == mj.mjtGeom.mjGEOM_MESH:
        mesh = model.geom_dataid[g]
        start, count = model.mesh_vertadr[mesh], model.mesh_vertnum[mesh]
        candidates = list(model.mesh_vert[start:start + count] @ rot.T + centre)
    elif kind == mj.mjtGeom.mjGEOM_ELLIPSOID:
        shape = rot @ np.diag(size ** 2) @ rot.T
        candidates = [centre + shape @ down / math.sqrt(float(down @ shape @ down))]
    else:
        candidates = [centre + model.geom_rbound[g] * down]
    lowest = min(float(p[2]) for p in candidates)
    return [(float(p[0]), float(p[1]), float(p[2])) for p in candidates
            if p[2] <= lowest + FLAT]


def _friction(model, floor: int, g: int, link: str, described: dict, friction,
              notes: list):
    """(mu, its source) of geom ``g`` on the floor, as MuJoCo mixes them: the geom's own
    where its priority is higher (a declared ``<mu1>``, sim's castor friction), else the
    larger of the two. A declared μ over MAX_FRICTION is no tyre's: not used."""
    if link in described and described[link] <= MAX_FRICTION:
        return described[link], f"<gazebo reference=\"{link}\"> mu1"
    if link in described:
        note = (f"link {link}: <mu1> {described[link]:g} is no tyre's (over "
                f"{MAX_FRICTION:g}): not used")
        if note not in notes:
            notes.append(note)
        own = float(model.geom_friction[floor][0])
        return (float(friction), "--friction") if friction is not None else \
            (own, f"MuJoCo's default {own:g} (its <mu1> not used)")
    if friction is not None:
        return float(friction), "--friction"
    own = float(model.geom_friction[g][0])
    if model.geom_priority[g] > model.geom_priority[floor]:
        return own, "sim's castor friction (a ball that rolls, modelled as sliding)"
    mu = max(own, float(model.geom_friction[floor][0]))
    return mu, f"MuJoCo's default {mu:g} (no <mu1> given)"


def _axle(data, joint_id: int) -> tuple[float, float]:
    """The horizontal direction of a wheel's axle (a free wheel resists only along it)."""
    axis = data.xaxis[joint_id]
    norm = math.hypot(axis[0], axis[1])
    return (float(axis[0] / norm), float(axis[1] / norm)) if norm > 1e-9 else (0.0, 0.0)


def _how_it_holds(sim, data, body: int) -> tuple[str, tuple[float, float]]:
    """(hold, axis) of a part that is no drive wheel, from the hinge joints between it and
    the root: an axle (a horizontal hinge) lets it roll across the axle ("axle"), an axle
    on a swivel (a vertical one) lets it roll every way ("free": a castor wheel); a
    swivel alone only turns it (a ball on a swivel slides: "held"), as does no joint.
    Sprung joints carry the weight and count as rigid."""
    from ..sim.engine import mujoco

    mj = mujoco()
    model = sim.model
    sprung = {s.joint for s in sim.springs}
    axles, swivels = [], 0
    while body not in (0, sim.root_body):
        for j in range(model.body_jntadr[body], model.body_jntadr[body] + model.body_jntnum[body]):
            if model.jnt_type[j] != mj.mjtJoint.mjJNT_HINGE or model.joint(j).name in sprung:
                continue
            if abs(float(data.xaxis[j][2])) > 0.5:
                swivels += 1
            else:
                axles.append(j)
        body = int(model.body_parentid[body])
    if axles and swivels:
        return "free", (0.0, 0.0)
    if axles:
        return "axle", _axle(data, axles[0])
    return "held", (0.0, 0.0)
