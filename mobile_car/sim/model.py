"""The robot as MuJoCo simulates it: URDF in, a compiled model on a floor out, with the
drive found (:mod:`.drives`), velocity motors on its wheels, position servos on its
steering, and the heights the scenarios measure against.

The simulation-only choices (docs/sim.md) are made here and nowhere else:

* the root link gets a free joint (MuJoCo's URDF importer otherwise welds it to the world);
* robot geoms collide with the floor only (Gazebo's default: no self-collision);
* a wheel (driven or rolling free) touches the floor through a sphere of the tyre's
  radius: a cylinder touches at both tyre edges and scrubs when the car turns in place;
  but a bicycle's keep their cylinders: their width is all that holds a single track up;
* friction comes from the description's ``<gazebo reference><mu1>``, with a contact
  priority so the part's own value wins (MuJoCo otherwise takes the larger of the pair's);
  a castor (a part other than the drive wheels that rests on the floor) without one gets
  CASTOR_FRICTION: URDF has no rolling ball, descriptions model it as a fixed block
  (TurtleBot3's box), and a block dragged at MuJoCo's default friction of 1 steers the
  robot (burger: 2.4 degrees off course in 3 s);
* contacts go through MuJoCo's pyramidal friction cone, but through its elliptic one
  where a <mu1> is over PYRAMID_MU, or where more than three parts of different friction
  rest on the floor together (:func:`shared_unevenly`: the pyramid gives a castor's
  weight to the part of lower friction);
* a link without ``<inertial>`` is massless, as URDF says (MuJoCo would invent a mass from
  its geometry; Gazebo leaves a moving one out: lint reports such links);
* a drive joint's motor figures come from the description (:mod:`.motors`), a default
  torque when it gives none; its velocity servo's gain grows with the load the wheel
  drives (:func:`.servos.servo_gain`), so that a heavy robot follows the speed ramp as the car does;
* the wheel joints get an armature, the motor's rotor inertia seen through its gearbox:
  1e-4 kg m² on a small car (JGA25-370: ~2e-7 kg m² x 21²), a quarter of the wheel's
  share of the robot (m·r²/n) on a larger one (:func:`.servos.wheel_armature`; Jackal: 0.011 kg m²),
  as motors grow with what they drive: without it light wheels chatter against the stiff
  velocity servo and the robot over-travels as the speed ramps up (the car ~7%, Jackal
  2.8%); and a 1 ms step (0.6% over-travel, 2% at MuJoCo's default 2 ms);
* a mecanum wheel touches the floor through a capsule that grips along its rollers' axis
  and rolls freely across it (:mod:`.rollers`);
* an Ackermann car's steering joints get a position servo stiff enough that a tyre's
  whole friction moves them by 0.3° at most (:func:`.servos.steering_gain`), within the joint's
  effort limit;
* a revolute or prismatic joint between the body and a drive wheel (wheel drop,
  suspension, a rocker) is a spring (:mod:`.springs`), started at its rest under the
  robot's weight; other revolute and prismatic joints (an arm, steering held straight
  when the car is driven as another kind) are welded at 0: with no motor they would
  fold; a ``<mimic>`` of a welded joint is welded with it;
* the castors are the parts other than the wheels within GROUND_TOLERANCE of the floor
  named so (CASTOR_WORDS), else the lowest of them; the robot is released in the pose
  its geometry rests in on its wheels and castors (:mod:`.resting`): leaning on a castor
  lower than its wheels, not level with the castor in the floor (Kobuki, balanced on its
  two wheels with both castors in the air, rocked and spun 254% too fast).
"""

from __future__ import annotations

from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from lxml import etree

from ..check.urdf_model import parse_number
from ..errors import EXIT_PROBLEMS, InputError, McarError
from .drives import Drive, actuated_joints
from .engine import mujoco
from .mecanum import urdf_declarations
from .resting import RestPose, rest_pose
from .rollers import Rollers, add_rollers, roller_bodies
from .servos import DriveSources, add_motors, fit_drive
from .springs import apply_springs, gazebo_joint_blocks, make_springs, sprung_joints
from .vehicle import endless

TIMESTEP = 0.001
# Above the floor by this much, a part does not rest on it (contacts, ground parts).
GROUND_TOLERANCE = 0.003
# Within this of the lowest part that is no wheel, parts are the robot's castors where none
# is named one (a body that drags, TurtleBot3's box): what the geometry rests on.
CASTOR_TIE = 0.001
# A part named so is a castor (a ball, a skid) wherever it is: a few mm up, it is a
# clearance, not a part that should touch.
CASTOR_WORDS = ("castor", "caster", "ball")
# The wheels' contact while dropped (time constant s, damping ratio): see resting_tyres.
RESTING_SOLREF = [0.005, 1.0]
# A part of <mu1> under this touches through a frictionless contact (condim 1): MuJoCo's
# pyramid of friction directions collapses at mu 0 onto the normal, four copies of one
# row, and the solver went astray: a two-wheeler on frictionless wheels ended upside down
# in drop, and Kobuki, whose castors say mu1 0, spun 254% faster than its wheels allow
# and drifted 889 mm (thrown 12 m up at 0.95 s), or passed, as a 1e-17 rad tilt of its
# start decided. Nearly collapsed, it goes as astray: Neobotix MPO-700's wheels (mu1
# 0.0001, for Gazebo's planar_move) threw the 180 kg robot 4.7 m up in drop; at 5e-5 5 m,
# at 2e-4 to 5e-4 it hopped 2-4 mm, from 1e-3 it rests. Friction under 0.1% of the load
# changes no figure sim measures.
FRICTIONLESS = 1e-3
# mu of a castor whose description gives none: a ball that rolls freely, modelled as
# sliding (the bundled car's caster_friction).
CASTOR_FRICTION = 0.01


# A <mu1> over this sends MuJoCo's default pyramid of friction astray the other way: a
# two-wheeler of <mu1>1.5 drove 1.2% short (0.4% at 1), at 2 3.4%, from 3 it fell on its
# nose in drop; Neobotix MP-400's wheels (mu1 100, 1000 N·m motors) spun without moving
# it. A robot declaring one touches through MuJoCo's elliptic cone, Coulomb's law itself:
# at mu 3 and 100 the two-wheeler drove as at 1.
PYRAMID_MU = 1.0


# Parts within this of the drive wheels' floor (m) rest on it together.
RESTING_TIE = 1e-4


def friction_cone(mj, friction: dict[str, float]):
    """MuJoCo's friction cone for a robot of these declared <mu1>s (link -> mu): its
    default pyramid, elliptic where one is over PYRAMID_MU."""
    if any(mu > PYRAMID_MU for mu in friction.values()):
        return mj.mjtCone.mjCONE_ELLIPTIC
    return mj.mjtCone.mjCONE_PYRAMIDAL


def shared_unevenly(spec, clearance: dict[str, float]) -> bool:
    """Whether more than three parts rest on the floor together (``clearance``: link ->
    its lowest point above the wheels' floor, :func:`resting_parts`) at different friction.
    Statics cannot say how four or more supports share the weight: the contacts'
    compliance does. Under MuJoCo's pyramidal cone a contact pushes through the edges of
    its friction pyramid, whose regularisation scales with mu squared: a castor of mu 0.01
    is 2e4 times stiffer than a tyre of mu 1 and takes the whole weight. ros2_control_demos'
    diffbot, on two wheels and two castor balls level with them, left each wheel 0.5% of
    its weight: the tyres slipped at their friction and it drove 5% short (more the longer
    it drove, none at 10 rad/s); MiR's wheels carried 0.0%, its four castors the rest.
    Such a robot touches through the elliptic cone, whose normal is regularised apart from
    the friction: diffbot's wheels then carry 24% each, as four equally stiff supports do."""
    resting = {link for link, height in clearance.items() if height <= RESTING_TIE}
    if len(resting) <= 3:
        return False
    frictions = {round(float(geom.friction[0]), 9) for geom in spec.geoms
                 if geom.parent.name in resting and _touches(geom)}
    return len(frictions) > 1


def frictionless(mu: float) -> bool:
    """Whether a part of this <mu1> touches through a frictionless contact (FRICTIONLESS)."""
    return mu < FRICTIONLESS


class SimModelError(McarError):
    """MuJoCo cannot make a model of the robot (exit 1: the description's fault)."""

    exit_code = EXIT_PROBLEMS


@dataclass
class SimModel:
    model: object       # mujoco.MjModel
    spec: object        # mujoco.MjSpec
    root: str
    root_body: int
    drive: Drive | None
    why_no_drive: str | None
    rest_height: float  # the root's height when the geometry rests on the floor
    ground_parts: dict[str, int] = field(default_factory=dict)  # link -> body id (castor)
    # link -> its lowest point above the drive wheels' floor plane (wheels, ground parts)
    clearance: dict[str, float] = field(default_factory=dict)
    floor_geom: int = 0
    notes: list[str] = field(default_factory=list)
    mass: float = 0.0   # kg, the whole robot
    held: list[str] = field(default_factory=list)  # joints held still: not the drive's
    springs: list = field(default_factory=list)  # Spring: suspension and wheel drop
    start: dict[str, float] = field(default_factory=dict)  # joint -> its position at rest
    ground_geoms: list[int] = field(default_factory=list)  # the geoms the rest height is of
    support_geoms: list[int] = field(default_factory=list)  # ... and the castors': its pose
    rest: RestPose | None = None  # how the geometry rests (leaning on a low castor)
    control: object = None  # skid-steer: its control package's ControlConfig, if found
    rollers: object = None  # mecanum: .rollers.Rollers, to align before every step
    friction: dict[str, float] = field(default_factory=dict)  # link -> its <gazebo> mu1
    # wheel link -> (radius, half length) of each collision cylinder its tyre sphere stands
    # for (round tyres, above): the shape the wheel has, for what is measured of it at rest
    tyres: dict[str, list] = field(default_factory=dict)

    @property
    def kind(self) -> str | None:
        return self.drive.kind if self.drive else None

    @property
    def drives(self) -> bool:
        return self.drive is not None

    @property
    def track(self) -> float:
        return self.drive.track


def build_model(urdf: bytes, label: str, base: Path, search, left=None, right=None,
                effort: float | None = None, speed: float | None = None,
                kind: str | None = None, declared=None, mecanum=()) -> SimModel:
    """``left``, ``right``: the driven joints of each side (a name, comma-separated names
    or a list), ``kind``: a drive kind (:mod:`.drives`), else declared or found from the
    tree; ``declared``: the package's drive declarations (:func:`.prepare.declarations`),
    None for the URDF's plugins alone;
    ``effort`` (N·m), ``speed`` (rad/s): the drive motors' figures where the description
    gives none (:mod:`.motors`); ``mecanum``: the mecanum declarations of the
    robot's control package (:func:`.mecanum.yaml_declarations`)."""
    mj = mujoco()
    root = etree.fromstring(urdf, etree.XMLParser(resolve_entities=False, no_network=True))
    read_as = as_urdfdom_reads(root)
    # The robot's own joints only: a <transmission> or <ros2_control> names joints too.
    joints = {j.get("name"): j for j in root if j.tag == "joint"}
    friction = gazebo_friction(root)
    colours = _link_colours(root)
    # The motor figures' other sources, kept before prepare_urdf takes them out of the tree.
    root_figures = [e for e in root if e.tag in ("gazebo", "ros2_control")]
    actuated = actuated_joints(root)
    joint_blocks = gazebo_joint_blocks(root)
    mecanum = urdf_declarations(root) + list(mecanum)
    notes = read_as + prepare_urdf(root, base, search)
    try:
        spec = mj.MjSpec.from_string(etree.tostring(root, encoding="unicode"))
    except ValueError as error:
        raise SimModelError(f"MuJoCo cannot read the robot: {_engine_message(error)}",
                            file=label) from None
    root_body = spec.worldbody.first_body()
    if root_body is None:
        raise SimModelError("the robot has no link MuJoCo can place", file=label)
    root_body.add_freejoint(name="mcar_free")
    spec.compiler.discardvisual = False  # (the URDF's visuals are gone; keep the floor's look)
    spec.option.timestep = TIMESTEP
    spec.option.integrator = mj.mjtIntegrator.mjINT_IMPLICITFAST
    spec.option.cone = friction_cone(mj, friction)
    add_floor(spec, mj)
    for geom in spec.geoms:
        if geom.name != "mcar_floor":
            geom.contype, geom.conaffinity = 1, 0
            if geom.parent.name in colours:
                geom.rgba = colours[geom.parent.name]
            mu = friction.get(geom.parent.name)
            if mu is not None:
                geom.friction = [mu, geom.friction[1], geom.friction[2]]
                geom.priority = 1
                if frictionless(mu):
                    geom.condim = 1
    shape = _compile(spec, label)  # once with the description's own shapes, to look at
    data = mj.MjData(shape)
    mj.mj_kinematics(shape, data)
    lowest = lowest_points(mj, shape, data)
    sources = DriveSources(root_figures, actuated, friction, declared, mecanum)
    drive, why = fit_drive(mj, shape, data, joints, sources, lowest, left, right, kind, effort,
                           speed)
    wheels = drive.wheels if drive else []
    mass = float(shape.body_mass.sum())
    robot_geoms = colliding_geoms(shape)
    if not robot_geoms:
        raise SimModelError("no link has <collision> geometry: nothing can rest on the "
                            "floor, the robot would fall through it", file=label)
    ground_geoms = [g for w in wheels for g in w.geom_ids] or robot_geoms
    springs = drive_springs(mj, shape, data, joints, drive, joint_blocks, mass, lowest)
    start = {spring.joint: spring.rest for spring in springs}
    if start:  # the geometry at rest: every spring at its rest under its share of weight
        for name, position in start.items():
            data.qpos[shape.jnt_qposadr[shape.joint(name).id]] = position
        mj.mj_kinematics(shape, data)
        lowest = lowest_points(mj, shape, data)
    _ground, parts, clearance = resting_parts(shape, lowest, wheels, data)
    supports = support_geoms(shape, ground_geoms, set(parts.values()))
    rest = rest_pose(mj, shape, data, root_body_id(shape), supports, lowest_points)
    tyres = _tyre_cylinders(mj, shape, drive)
    rolling_contacts(mj, spec, drive, parts, friction)
    if shared_unevenly(spec, clearance):
        spec.option.cone = mj.mjtCone.mjCONE_ELLIPTIC
    add_rollers(mj, spec, shape, drive, sources)
    add_motors(mj, spec, drive, mass)
    steering = drive.steering if drive else []
    apply_springs(mj, spec, springs)
    held = _hold_the_rest(spec, joints, drive, {s.joint for s in springs})
    model = _compile(spec, label)
    for wheel in wheels:  # (ids of the final model: held joints are gone from it)
        wheel.joint_id = model.joint(wheel.joint).id
    for wheel in drive.driven if drive else []:
        wheel.actuator_id = model.actuator(f"mcar_motor_{wheel.joint}").id
    for steer in steering:
        steer.joint_id = model.joint(steer.joint).id
        steer.actuator_id = model.actuator(f"mcar_steer_{steer.joint}").id
    aligned = Rollers(mj, model, drive) if drive and drive.kind == "mecanum" else None
    return SimModel(model=model, spec=spec, root=root_body.name,
                    root_body=model.body(root_body.name).id, drive=drive,
                    why_no_drive=why, rest_height=rest.height, ground_parts=parts,
                    clearance=clearance,
                    floor_geom=model.geom("mcar_floor").id, notes=notes, mass=mass, held=held,
                    springs=springs, start=start, ground_geoms=ground_geoms,
                    support_geoms=supports, rest=rest, rollers=aligned, tyres=tyres,
                    friction=friction)


def _tyre_cylinders(mj, shape, drive) -> dict[str, list]:
    """Wheel link -> (radius, half length) of its colliding cylinders, which
    :func:`rolling_contacts` rounds into spheres (a bicycle's stay cylinders)."""
    if drive is None or drive.kind == "bicycle":
        return {}
    found = {}
    for wheel in drive.wheels:
        found[wheel.link] = [(float(shape.geom_size[g][0]), float(shape.geom_size[g][1]))
                             for g in wheel.geom_ids
                             if shape.geom_type[g] == mj.mjtGeom.mjGEOM_CYLINDER]
    return found


def root_body_id(model) -> int:
    """The robot's root: the world's first child."""
    return next(b for b in range(1, model.nbody) if model.body_parentid[b] == 0)


def support_geoms(shape, ground_geoms: list[int], castor_bodies: set[int]) -> list[int]:
    """What the robot's rest pose stands on: ``ground_geoms`` (its wheels', else all it
    collides with) and its castors' colliding geoms."""
    return ground_geoms + [g for g in colliding_geoms(shape) if g not in ground_geoms
                           and shape.geom_bodyid[g] in castor_bodies]


def drive_springs(mj, shape, data, joints, drive, blocks, mass, lowest: dict) -> list:
    """The drive wheels' suspension and wheel-drop joints as springs (:mod:`.springs`),
    each carrying its share of the weight among the parts that rest on the floor with
    every joint at 0 (``lowest``: :func:`lowest_points` then); sim's model and the MJCF
    export both make them here."""
    if drive is None:
        return []
    wheel_bodies = {w.body_id for w in drive.wheels}
    robot_geoms = colliding_geoms(shape)
    ground_geoms = [g for w in drive.wheels for g in w.geom_ids] or robot_geoms
    supports = _supports(shape, lowest, ground_geoms, robot_geoms, wheel_bodies)
    ours = {s.joint for s in drive.steering} | {w.joint for w in drive.wheels}
    names = sprung_joints(shape, data, joints, [w.body_id for w in drive.wheels], ours)
    if not names:
        return []
    springs = make_springs(mj, shape, data, joints, names, drive.wheels, supports, mass,
                           blocks, TIMESTEP)
    mj.mj_kinematics(shape, data)  # (make_springs ran mj_forward: the same positions)
    return springs


def _supports(shape, lowest, ground_geoms, robot_geoms, wheel_bodies) -> int:
    """How many parts share the robot's weight, every joint at 0: the wheels and the
    bodies within GROUND_TOLERANCE of their floor."""
    ground = min(lowest[g] for g in ground_geoms)
    others = {int(shape.geom_bodyid[g]) for g in robot_geoms
              if lowest[g] <= ground + GROUND_TOLERANCE} - wheel_bodies
    return len(wheel_bodies) + len(others)


def rest_after(sim: SimModel, data) -> RestPose:
    """How the geometry rests with the joints where ``data`` has them (the springs'
    travel after a drop)."""
    mj = mujoco()
    scratch = mj.MjData(sim.model)
    scratch.qpos[:] = data.qpos
    return rest_pose(mj, sim.model, scratch, sim.root_body, sim.support_geoms, lowest_points)


def _hold_the_rest(spec, joints: dict, drive, springs: set[str]) -> list[str]:
    """Revolute and prismatic joints that are not the drive's (an arm, a lift, steering
    held straight) nor its ``springs`` are welded at 0, the pose check and render show:
    with no motor they would fold under gravity. Continuous joints stay free (castor
    swivels, rollers, a spinning sensor)."""
    ours = {s.joint for s in drive.steering} | {w.joint for w in drive.wheels} if drive \
        else set()
    held = [name for name, element in joints.items()
            if element.get("type") in ("revolute", "prismatic") and name not in ours
            and name not in springs]
    # A <mimic> of a held joint is held with it: MuJoCo's importer made the mimic an
    # equality naming both joints, and refuses a model whose equality names a joint gone.
    for name, element in joints.items():
        mimic = next((c for c in element if c.tag == "mimic"), None)
        if mimic is not None and mimic.get("joint") in held and name not in held \
                and name not in ours:
            held.append(name)
    for equality in list(spec.equalities):
        if equality.name1 in held or equality.name2 in held:
            spec.delete(equality)
    for name in held:
        joint = spec.joint(name)
        if joint is not None:
            spec.delete(joint)
    return held


def as_urdfdom_reads(root, made: str = "simulated") -> list[str]:
    """Rewrite, in place, what urdfdom reads with a warning into the form it reads it in,
    so that MuJoCo simulates the robot RViz and Gazebo show; the notes say what changed
    (``made``: what the robot is made into, "simulated" by sim, "exported" by export).

    * a revolute joint limited to ±UNLIMITED or more (swerve bases write ±1e16) turns
      without end, as urdfdom and KDL read it (:func:`.vehicle.endless`): a ``continuous``
      joint, so that a wheel on it is a wheel (:mod:`.drives` finds wheels on continuous
      joints);
    * an ``<axis>`` without ``xyz`` (``xzy="0 1 0"``): urdfdom keeps the axis it cleared,
      0 0 0, a joint that cannot move; MuJoCo refuses the element. It is fixed."""
    notes = []
    for joint in root.iterchildren("joint"):
        kind, name = joint.get("type"), joint.get("name")
        limit = next((c for c in joint if c.tag == "limit"), None)
        if kind == "revolute" and endless(kind, limit):
            lower, upper = (parse_number(limit.get(key)) for key in ("lower", "upper"))
            joint.set("type", "continuous")
            for key in ("lower", "upper"):
                limit.attrib.pop(key, None)
            notes.append(f"joint {name}: revolute limited to {lower:g}..{upper:g} rad "
                         f"turns without end, as urdfdom and KDL read it: {made} "
                         "continuous")
        axis = next((c for c in joint if c.tag == "axis"), None)
        if kind not in ("fixed", "floating") and axis is not None and axis.get("xyz") is None:
            joint.set("type", "fixed")
            joint.remove(axis)
            notes.append(f"joint {name}: <axis> has no xyz, urdfdom reads 0 0 0, a joint "
                         "that cannot move: simulated fixed")
    return notes


def gazebo_friction(root) -> dict[str, float]:
    """link -> mu1 of its ``<gazebo reference="link"><mu1>``."""
    found = {}
    for gazebo in root.iter("gazebo"):
        mu = gazebo.find("mu1")
        value = parse_number(mu.text.strip()) if mu is not None and mu.text else None
        if gazebo.get("reference") and value is not None and value >= 0:
            found[gazebo.get("reference")] = value
    return found


def _link_colours(root) -> dict[str, list[float]]:
    """link -> the rgba of its first visual's material, so a recording shows the colours."""
    named = {}
    for material in root.findall("material"):
        colour = material.find("color")
        if colour is not None and material.get("name"):
            named[material.get("name")] = colour.get("rgba")
    found = {}
    for link in root.iterchildren("link"):
        for material in link.iterfind("visual/material"):
            colour = material.find("color")
            text = colour.get("rgba") if colour is not None else named.get(material.get("name"))
            values = [parse_number(v) for v in (text or "").split()]
            if len(values) == 4 and None not in values:
                found[link.get("name")] = values
                break
    return found


def prepare_urdf(root, base: Path, search) -> list[str]:
    """Strip what MuJoCo must not read (visuals, Gazebo and ros2_control extras), point
    collision meshes at files MuJoCo reads (:mod:`.meshes`: converted where needed, in
    metres); the notes say what was left out. (mcar specs' ray proof calls it on a tree
    whose visuals it made collisions, to cast against both.)"""
    from .meshes import mujoco_mesh

    notes = []
    for element in list(root.iter("visual", "gazebo", "transmission", "ros2_control")):
        element.getparent().remove(element)
    for mesh in list(root.iter("mesh")):
        collision = mesh.getparent().getparent()
        filename = mesh.get("filename") or ""
        try:
            path = search.resolve_uri(filename, base)
            if not path.is_file():
                raise InputError("no such file", file=str(path))
            mesh.set("filename", str(mujoco_mesh(path).resolve()))
        except (McarError, OSError) as error:
            why = error.message if isinstance(error, McarError) else error.strerror or error
            link = collision.getparent()
            notes.append(f"link {link.get('name')}: collision mesh {filename} left out: {why}")
            link.remove(collision)
    unique_geom_names(root)
    _compiler_options(root)
    return notes


def unique_geom_names(root) -> None:
    """Drop the name of a <collision> or <visual> that repeats an earlier one's: MuJoCo
    makes that geom unnamed anyway, and says so on its own stderr, past mcar's messages
    ("WARNING: Geom with duplicate name 'caster_wheel' encountered in URDF": Neobotix
    MP-400's four castors, three such lines in every mcar specs and export)."""
    seen = set()
    for element in root.iter("collision", "visual"):
        name = element.get("name")
        if name is not None and name in seen:
            del element.attrib["name"]
        seen.add(name)


def _compiler_options(root) -> None:
    """The description's own masses and every link a body: no inertia from geometry, no
    fixed link fused into its parent, no tensor balanced behind the user's back."""
    compiler_extension(root, discardvisual="true")


def compiler_extension(root, **options: str):
    """mcar's ``<mujoco><compiler/></mujoco>`` in the URDF ``root`` (``options`` over the
    description's own masses and links, as :func:`_compiler_options` says), in place of
    any the description has: MuJoCo refuses two ("repeated element: 'mujoco'"), and
    Unitree's G1 and H1 carry one for their own meshdir, which mcar's mesh paths replace.
    Returns the element added."""
    for element in root.findall("mujoco"):
        root.remove(element)
    extension = etree.SubElement(root, "mujoco")
    etree.SubElement(extension, "compiler", **{
        "discardvisual": "true", "fusestatic": "false", "inertiafromgeom": "false",
        "balanceinertia": "false", "strippath": "false", **options})
    return extension


def jointed_model(urdf: bytes, label: str) -> tuple[object, list[str]]:
    """(the robot's masses on their joints as MuJoCo reads them, notes): every joint free,
    the root fixed to the world, no geometry. What gravity asks of a joint (``mcar specs``,
    :mod:`mobile_car.specs.joints`) depends on masses, centres of mass and the joints'
    kinematics only, where sim's model holds the joints that are not the drive's still
    (:func:`_hold_the_rest`). A tensor MuJoCo refuses is made physical
    (:func:`~mobile_car.check.mujoco_inertia.make_physical`: a tensor changes no gravity
    load), a moving link without mass gets a token one (the notes say which). Each hinge
    and slide joint has an equality ``mcar_hold_<joint>``, off: switched on
    (``data.eq_active``) it holds the joint where its ``eq_data[0]`` says, a lock the
    proof of a figure puts on the joints it does not measure."""
    from ..check.mujoco_inertia import make_physical, refusals

    mj = mujoco()
    root = etree.fromstring(urdf, etree.XMLParser(resolve_entities=False, no_network=True))
    notes = as_urdfdom_reads(root)
    for element in list(root.iter("visual", "collision", "gazebo", "transmission",
                                  "ros2_control")):
        element.getparent().remove(element)
    notes += make_physical(root, refusals(root))
    _compiler_options(root)
    try:
        spec = mj.MjSpec.from_string(etree.tostring(root, encoding="unicode"))
    except ValueError as error:
        raise SimModelError(f"MuJoCo cannot read the robot: {_engine_message(error)}",
                            file=label) from None
    for joint in list(spec.joints):
        if joint.type in (mj.mjtJoint.mjJNT_HINGE, mj.mjtJoint.mjJNT_SLIDE):
            hold = spec.add_equality(name=f"mcar_hold_{joint.name}", type=mj.mjtEq.mjEQ_JOINT,
                                     objtype=mj.mjtObj.mjOBJ_JOINT, name1=joint.name)
            hold.active = False
    return _compile(spec, label), notes


def add_floor(spec, mj) -> None:
    """A 20 m checkered floor at z = 0 (geom ``mcar_floor``, colliding with everything)
    and a light above it; ``mcar export --to mjcf --floor`` adds the same."""
    texture = spec.add_texture(name="mcar_checker", type=mj.mjtTexture.mjTEXTURE_2D,
                               builtin=mj.mjtBuiltin.mjBUILTIN_CHECKER, width=256, height=256,
                               rgb1=[0.82, 0.84, 0.86], rgb2=[0.42, 0.45, 0.5])
    material = spec.add_material(name="mcar_floor")
    textures = list(material.textures)
    textures[mj.mjtTextureRole.mjTEXROLE_RGB] = texture.name
    material.textures = textures
    material.texrepeat = [100, 100]  # 0.2 m squares over the 20 m floor (2 per repeat)
    spec.worldbody.add_geom(name="mcar_floor", type=mj.mjtGeom.mjGEOM_PLANE,
                            size=[10, 10, 0.05], material="mcar_floor", contype=1,
                            conaffinity=1)
    spec.worldbody.add_light(pos=[0, 0, 3], dir=[0, 0, -1], diffuse=[0.8, 0.8, 0.8])


def _compile(spec, label):
    try:
        return spec.compile()
    except ValueError as error:
        raise SimModelError(f"MuJoCo cannot simulate the robot: {_engine_message(error)}",
                            file=label) from None


def _engine_message(error) -> str:
    text = str(error).strip().splitlines()
    return (text[0] if text else type(error).__name__).removeprefix("Error: ")


def lowest_points(mj, model, data) -> dict[int, float]:
    """geom -> the z of its lowest point (the root at the origin, every joint at 0)."""
    lowest = {}
    for g in range(model.ngeom):
        if model.geom_bodyid[g] == 0:
            continue
        centre, rot = data.geom_xpos[g], data.geom_xmat[g].reshape(3, 3)
        size = model.geom_size[g]
        kind = mj.mjtGeom(int(model.geom_type[g]))  # (a numpy int is never `in` enum tuples)
        up = abs(rot[2])  # |z component| of each local axis
        if kind == mj.mjtGeom.mjGEOM_SPHERE:
            drop = size[0]
        elif kind == mj.mjtGeom.mjGEOM_CYLINDER:
            drop = size[0] * np.sqrt(max(0.0, 1 - up[2] ** 2)) + size[1] * up[2]
        elif kind == mj.mjtGeom.mjGEOM_CAPSULE:
            drop = size[0] + size[1] * up[2]
        elif kind in (mj.mjtGeom.mjGEOM_BOX, mj.mjtGeom.mjGEOM_ELLIPSOID):
            drop = float(up @ size) if kind == mj.mjtGeom.mjGEOM_BOX else float(
                np.sqrt((up ** 2) @ (size ** 2)))
        elif kind == mj.mjtGeom.mjGEOM_MESH:
            mesh = model.geom_dataid[g]
            start, count = model.mesh_vertadr[mesh], model.mesh_vertnum[mesh]
            verts = model.mesh_vert[start:start + count] @ rot.T
            drop = -float(verts[:, 2].min())
        else:
            drop = model.geom_rbound[g]
        lowest[g] = float(centre[2] - drop)
    return lowest


def resting_parts(shape, lowest: dict[int, float], wheels,
                  data=None) -> tuple[float, dict, dict]:
    """(the floor's z under the robot: the drive wheels' lowest point, else the lowest
    colliding geom's; its castors, link -> body id (:func:`_castors`); link -> its lowest
    point above that floor, for the wheels and the links within GROUND_TOLERANCE of it),
    the joints where ``lowest`` was measured (every one at 0, or sim's springs at rest).
    Shared by ``mcar sim`` and ``mcar export --verify``, which judge alike; a geom that
    touches nothing (an export's visual) rests on nothing. A mecanum wheel's roller links
    are its own (its capsule touches for them, :mod:`.rollers`); a mecanum hub without
    geometry of its own reaches its radius below its centre (``data``: the kinematics)."""
    robot_geoms = colliding_geoms(shape)
    wheels_lowest = [lowest[g] for w in wheels for g in w.geom_ids]
    if data is not None:
        wheels_lowest += [float(data.xpos[w.body_id][2]) - w.radius for w in wheels
                          if not w.geom_ids]
    ground = min(wheels_lowest) if wheels_lowest else min(lowest[g] for g in robot_geoms)
    wheel_bodies = {w.body_id for w in wheels}
    rollers = roller_bodies(shape, wheels)
    near, clearance = {}, {}
    for g in robot_geoms:
        body = int(shape.geom_bodyid[g])
        if body in rollers:
            continue
        name = shape.body(body).name
        if body in wheel_bodies or lowest[g] <= ground + GROUND_TOLERANCE:
            clearance[name] = min(clearance.get(name, np.inf), lowest[g] - ground)
        if body not in wheel_bodies and lowest[g] <= ground + GROUND_TOLERANCE:
            near[name] = body
    return ground, _castors(near, clearance), clearance


def _castors(near: dict, clearance: dict) -> dict:
    """Of the parts other than the wheels within GROUND_TOLERANCE of the floor (``near``,
    link -> body), the castors: those named so (CASTOR_WORDS); where none is, the lowest
    ones (within CASTOR_TIE): what the robot rests on besides its wheels. A bracket or
    motor housing a few mm up is then neither a castor nor a part that must touch the
    floor (the car on 15 mm wheels)."""
    named = {n: b for n, b in near.items() if any(w in n.lower() for w in CASTOR_WORDS)}
    if named or not near:
        return named
    least = min(clearance[n] for n in near)
    return {n: b for n, b in near.items() if clearance[n] <= least + CASTOR_TIE}


def rolling_contacts(mj, spec, drive, parts: dict, friction: dict) -> None:
    """Sim's contact choices for a vehicle (the module's docstring), which ``mcar export
    --to mjcf`` writes too: a castor's friction where the description gives none, and
    round tyres."""
    if drive is None:
        return
    for geom in spec.geoms:
        if geom.parent.name in parts and geom.parent.name not in friction and _touches(geom):
            geom.friction = [CASTOR_FRICTION, geom.friction[1], geom.friction[2]]
            geom.priority = 1
    if drive.kind == "bicycle":
        # A single track stands on its tyres' width: on spheres' points it would balance
        # on a knife edge and fall outward in the first turn. It never turns in place,
        # where a cylinder scrubs.
        return
    for wheel in drive.wheels:
        _round_tyre(spec, wheel, mj)


def colliding_geoms(shape) -> list[int]:
    """The robot's geoms that collide (every one in sim; not an export's visuals)."""
    return [g for g in range(shape.ngeom) if shape.geom_bodyid[g] != 0
            and (shape.geom_contype[g] or shape.geom_conaffinity[g])]


def _touches(geom) -> bool:
    return bool(geom.contype or geom.conaffinity)


def _round_tyre(spec, wheel, mj) -> None:
    """The wheel's colliding cylinders touch the floor through a sphere of the same
    radius (an export's visual cylinder stays one)."""
    for geom in spec.geoms:
        if geom.parent.name == wheel.link and geom.type == mj.mjtGeom.mjGEOM_CYLINDER \
                and _touches(geom):
            geom.type = mj.mjtGeom.mjGEOM_SPHERE
            geom.size = [geom.size[0], 0, 0]


@contextmanager
def resting_tyres(sim: SimModel):
    """The wheels' contacts at RESTING_SOLREF while the robot is dropped, as they were
    after. MuJoCo's default 0.02 s lets a wheel under a heavy robot sink ~0.8 mm into the
    floor: TurtleBot 4, whose centre of mass is 2 mm ahead of its axle when it leans on
    its castor, then tipped back onto its body. Only for the drop: the tyres' grip while
    driving and spinning is what the drive figures were measured with."""
    wheels = {w.body_id for w in sim.drive.wheels} if sim.drive else set()
    model = sim.model
    geoms = [g for g in range(model.ngeom) if model.geom_bodyid[g] in wheels]
    kept = model.geom_solref[geoms].copy(), model.geom_priority[geoms].copy()
    model.geom_solref[geoms] = RESTING_SOLREF
    # Over the floor's priority: MuJoCo takes the contact settings of the geom of higher
    # priority, and mixes the pair's where they are equal (a tyre without <mu1>).
    model.geom_priority[geoms] = 2
    try:
        yield
    finally:
        model.geom_solref[geoms], model.geom_priority[geoms] = kept

