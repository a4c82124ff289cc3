"""``mcar export --to mjcf``: the robot as a complete MuJoCo model, written by MuJoCo
(``MjSpec.to_xml``) into a folder with its meshes (:mod:`.assets`).

MuJoCo's own URDF importer reads the description (so its joints, limits, ``<mimic>``
equality constraints and inertias are MuJoCo's reading of them), told to keep the visuals
and every link (``discardvisual``, ``fusestatic`` off) and to take masses from the
description only (``inertiafromgeom`` off). Then, the choices of an export for people:

* visual geoms in geom group 2, touching nothing; collision geoms in group 3 (MuJoCo's
  viewer hides it until asked), colliding with the world but not with the robot itself
  (URDF's and Gazebo's default); a converted mesh without a URDF material keeps its
  own colour;
* friction from the description's ``<gazebo reference><mu1>``, with a contact priority
  so that the part's own value wins, and a part of ``<mu1>`` 0 (or under 0.001) touching
  through a frictionless contact (``condim 1``), and MuJoCo's elliptic cone for a robot
  declaring a ``<mu1>`` over 1, as sim has them; on a vehicle, sim's castor
  friction where none is given and each wheel's collision cylinder a sphere of its
  radius (a round tyre), as ``mcar sim`` has them, so that ``--verify`` judges the model sim judged;
* on a vehicle, sim's springs (:mod:`mobile_car.sim.springs`): a wheel-drop or suspension
  joint gets sim's stiffness, reference, damping, travel and end stops, and the manifest
  lists them (``springs``: the travel, the rest it settles at under the weight) so that
  ``--verify`` releases the robot with its springs at rest, as sim does;
* ``--base floating`` (a free joint ``floating_base`` on the root link) or ``fixed``
  (welded to the world, as the importer leaves it);
* ``--floor``: sim's floor and light, the robot standing on it (its lowest collision
  point at z = 0); the default under a floating base;
* the velocity servos (``mcar_motor_JOINT``), steering servos and wheel armature ``mcar
  sim`` drives with, on the drive it finds (:mod:`mobile_car.sim.servos`), and sim's
  1 ms implicit-fast step, so that ``data.ctrl`` (rad/s per drive wheel) drives at once;
* inertias MuJoCo refuses are named link by link (:mod:`.inertia`).

Lengths in m, masses in kg, the control in rad/s.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from lxml import etree

from ..check.mujoco_inertia import TOKEN_MASS, bare_massless, make_physical, refusals
from ..check.urdf_model import parse_number, parse_numbers
from ..errors import McarError
from . import ExportError
from .assets import Assets

MUJOCO_READS = (".stl", ".obj", ".msh")
VISUAL_GROUP = 2
COLLISION_GROUP = 3
FREE_JOINT = "floating_base"


@dataclass
class MjcfOptions:
    base: str = "floating"          # or "fixed"
    floor: bool | None = None       # None: a floor under a floating base
    fix_inertia: bool = False
    place: object = None            # link name -> "FILE:LINE" of its inertia, or None


@dataclass
class Exported:
    """What an export wrote and what the verification compares against."""

    robot_file: str                 # relative to the folder
    urdf_mass: float                # kg, the sum of the description's <mass>
    model_mass: float               # kg, as the target's engine reads it
    moving_joints: list[str]
    meshes: list[str] = field(default_factory=list)       # files written, relative
    converted: list[str] = field(default_factory=list)    # "uri -> relative" lines
    warnings: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)     # said, not warned: no drive, why
    drive: dict | None = None       # kind, driven joints, radius, command speed
    base: str = "floating"
    floor: bool = False
    added_mass: float = 0.0         # kg MuJoCo gave massless moving links (--fix-inertia)
    # moving joint -> its URDF type (mjcf): MuJoCo's hinge does not say whether it was a
    # revolute joint that --verify's drive finder must not take for a wheel (Hunter 2's
    # steering, limits 0 to 0, is a hinge without a range)
    joint_types: dict[str, str] = field(default_factory=dict)
    # a vehicle (:func:`mobile_car.sim.vehicle.not_a_vehicle`'s test): --verify drops one
    # that has no drive sim drives too (PR2's powered castors), as sim does
    vehicle: bool = False
    # sim's springs (Spring.as_json; its rest at full precision, where --verify starts it)
    springs: list[dict] = field(default_factory=list)


@dataclass
class Prepared:
    """A robot ready for an engine's importer: its URDF (``root``) with the simulators'
    extras taken out and every mesh pointing at its copy in ``assets.folder``."""

    root: object
    joints: dict
    sources: object       # sim's DriveSources, read before the extras went
    assets: Assets
    warnings: list[str]
    joint_blocks: dict = field(default_factory=dict)  # joint -> its <gazebo> spring numbers


def prepare(loaded, folder: Path, readable=MUJOCO_READS, keep_extras: bool = False,
            binary_stl_only: bool = True, copy_textures: bool = False) -> Prepared:
    """The robot's URDF with its meshes copied into ``folder``; the simulators' extras
    (``<gazebo>``, ``<transmission>``, ``<ros2_control>``) taken out unless ``keep_extras``
    (an importer that does not read them must not trip on them); its ``<texture>``s
    copied too with ``copy_textures``, else taken out (MuJoCo reads none): the tool given
    the URDF never reads a file the export did not measure and allow."""
    from ..check.colours import drop_unusable_colours
    from ..sim.drives import actuated_joints
    from ..sim.mecanum import urdf_declarations
    from ..sim.model import gazebo_friction
    from ..sim.servos import DriveSources
    from ..sim.springs import gazebo_joint_blocks

    root = parse_robot(loaded.urdf, loaded.label)
    joints = {j.get("name"): j for j in root if j.tag == "joint"}
    sources = DriveSources([e for e in root if e.tag in ("gazebo", "ros2_control")],
                           actuated_joints(root), gazebo_friction(root),
                           mecanum=urdf_declarations(root))
    blocks = gazebo_joint_blocks(root)  # (read before the <gazebo> blocks go)
    if not keep_extras:
        for element in list(root.iter("gazebo", "transmission", "ros2_control")):
            element.getparent().remove(element)
    assets = Assets(folder, readable, binary_stl_only)
    # As urdfdom does (W217): MuJoCo and urdf-usd-converter refuse an rgba of 3 numbers.
    warnings = drop_unusable_colours(root)
    warnings += place_meshes(root, assets, loaded)
    warnings += place_textures(root, assets, loaded, copy_textures)
    return Prepared(root, joints, sources, assets, warnings, blocks)


def mujoco_spec(mj, prepared: Prepared, label: str):
    """MuJoCo's reading of the prepared URDF (visuals and every link kept), its meshes
    found in the assets' folder."""
    from ..sim.model import compiler_extension, unique_geom_names

    root = prepared.root
    unique_geom_names(root)
    extension = compiler_extension(root, discardvisual="false")
    try:
        spec = mj.MjSpec.from_string(etree.tostring(root, encoding="unicode"))
    except ValueError as error:
        raise ExportError(f"MuJoCo cannot read the robot: {_first_line(error)}",
                          file=label) from None
    finally:
        root.remove(extension)
    spec.modelfiledir = str(prepared.assets.folder)
    return spec


def export_mjcf(loaded, folder: Path, options: MjcfOptions) -> Exported:
    """Write the MuJoCo model of a loaded robot (a LoadedRobot) and its meshes into
    ``folder``; ExportError where MuJoCo cannot make the model asked for."""
    from ..sim.engine import mujoco
    from ..sim.model import as_urdfdom_reads

    mj = mujoco()
    prepared = prepare(loaded, folder)
    # As sim reads the robot before MuJoCo does: wheels limited to ±1e16 turn without end
    # (sim's drive finder takes continuous joints only), so the file drives as sim's model
    read_as = as_urdfdom_reads(prepared.root, made="exported")
    # What MuJoCo cannot mend itself, found and mended in the URDF first (then MuJoCo
    # reads the robot, and names the rest: refused_links).
    found = before_mujoco(prepared.root)
    mended = make_physical(prepared.root, found)
    spec = mujoco_spec(mj, prepared, loaded.label)
    exported = _complete(mj, spec, prepared, loaded, options, (found, mended))
    exported.notes[:0] = read_as
    return exported


def before_mujoco(root) -> list:
    """The inertias MuJoCo stops at without a fix of its own: a tensor that is not
    positive definite (or whose moments are under its 1e-14), a moving link without mass
    nor collision geometry to take one from (:mod:`mobile_car.check.mujoco_inertia`)."""
    tensors = [r for r in refusals(root, massless=False)
               if r.problem in ("not-positive", "tiny", "no-inertia")]
    return tensors + bare_massless(root)


def _complete(mj, spec, prepared, loaded, options, mended_first):
    from ..sim.model import (
        TIMESTEP,
        add_floor,
        friction_cone,
        frictionless,
        lowest_points,
        resting_parts,
        rolling_contacts,
        shared_unevenly,
    )
    from ..sim.servos import add_motors, fit_drive
    from ..sim.vehicle import aloft_bodies
    from .inertia import apply_fixes, fix_warnings, refuse, refused_links

    root, joints, sources = prepared.root, prepared.joints, prepared.sources
    assets, warnings = prepared.assets, prepared.warnings
    found, mended = mended_first
    root_body = spec.worldbody.first_body()
    if root_body is None:
        raise ExportError("the robot has no link MuJoCo can place", file=loaded.label)
    if options.base == "floating":
        # before the inertias are judged: a floating root moves, and MuJoCo then needs its
        # mass (ABB's massless base_link passed the judging, then failed the compile)
        root_body.add_freejoint(name=FREE_JOINT)
    refused = refused_links(mj, spec)
    if not options.fix_inertia:
        refuse(found + refused, loaded.label, options.place)
    warnings += mended
    apply_fixes(mj, spec, refused, loaded.label)
    _add_missing_mimics(spec, root, mj)
    for geom in spec.geoms:
        if geom.contype == 0 and geom.conaffinity == 0:
            geom.group = VISUAL_GROUP
            continue
        geom.group, geom.contype, geom.conaffinity = COLLISION_GROUP, 1, 0
        mu = sources.friction.get(geom.parent.name)
        if mu is not None:
            geom.friction = [mu, geom.friction[1], geom.friction[2]]
            geom.priority = 1
            if frictionless(mu):  # sim's frictionless contact
                geom.condim = 1
    spec.option.timestep = TIMESTEP
    spec.option.integrator = mj.mjtIntegrator.mjINT_IMPLICITFAST
    spec.option.cone = friction_cone(mj, sources.friction)  # as sim has it
    shape = _compile(spec, loaded.label)
    data = mj.MjData(shape)
    mj.mj_kinematics(shape, data)
    points = lowest_points(mj, shape, data)
    drive, why = fit_drive(mj, shape, data, joints, sources, points)
    mass = float(shape.body_mass.sum())
    add_motors(mj, spec, drive, mass)
    springs = _springs(mj, spec, shape, data, prepared, drive, mass, points)
    if drive is not None:  # sim's castor friction and round tyres: what --verify judges
        rest = {s.joint: s.rest for s in springs}  # (the castors sim finds at that rest)
        _, parts, clearance = resting_parts(
            shape, _lowest_at(mj, shape, data, rest) if rest else points, drive.wheels, data)
        rolling_contacts(mj, spec, drive, parts, sources.friction)
        if shared_unevenly(spec, clearance):  # as sim has it
            spec.option.cone = mj.mjtCone.mjCONE_ELLIPTIC
    mecanum = _mecanum_tyres(spec, drive, sources)
    floor = options.floor if options.floor is not None else options.base == "floating"
    if floor:
        lowest = [z for g, z in points.items()
                  if shape.geom_contype[g] or shape.geom_conaffinity[g]]
        if lowest:
            root_body.pos = [root_body.pos[0], root_body.pos[1], root_body.pos[2] - min(lowest)]
        add_floor(spec, mj)
    model = _compile(spec, loaded.label)
    name = robot_file_name(root)
    (Path(spec.modelfiledir) / name).write_text(spec.to_xml(), encoding="utf-8")
    warnings += fix_warnings(model, refused)
    added = sum(float(model.body(r.link).mass[0]) for r in refused if r.problem == "massless")
    tokens = TOKEN_MASS * sum(r.problem == "massless" for r in found)
    return Exported(
        robot_file=name, urdf_mass=urdf_mass(root) - tokens,
        model_mass=float(model.body_mass.sum()),
        moving_joints=moving_joints(root), meshes=sorted(assets.taken),
        converted=[f"{a.uri} -> {a.relative}" for a in assets.by_uri.values() if a.converted],
        warnings=warnings, notes=([f"no drive actuators: {why}"] if drive is None and why
                                  else []) + mecanum,
        drive=drive_summary(drive), base=options.base, floor=floor, added_mass=added + tokens,
        vehicle=is_vehicle(root, aloft_bodies(shape, data, points)),
        springs=[_spring_json(s) for s in springs],
        joint_types={j.get("name"): j.get("type") for j in root.iterchildren("joint")
                     if j.get("type") != "fixed"})


def _springs(mj, spec, shape, data, prepared, drive, mass: float, points: dict) -> list:
    """Sim's springs of the drive's wheel-drop and suspension joints (sim's own
    functions, on the same compiled shape, every joint at 0), applied to ``spec``."""
    from ..sim.model import drive_springs
    from ..sim.springs import apply_springs

    springs = drive_springs(mj, shape, data, prepared.joints, drive, prepared.joint_blocks,
                            mass, points)
    apply_springs(mj, spec, springs)
    return springs


def _lowest_at(mj, shape, data, positions: dict) -> dict:
    """The geoms' lowest points with the joints of ``positions`` there (``data`` is
    left with them)."""
    from ..sim.model import lowest_points

    for name, position in positions.items():
        data.qpos[shape.jnt_qposadr[shape.joint(name).id]] = position
    mj.mj_kinematics(shape, data)
    return lowest_points(mj, shape, data)


def _spring_json(spring) -> dict:
    """The manifest's record of a spring: sim's, its rest unrounded (--verify releases
    the robot there, as sim does: a run at a motor's limit amplifies a rounding)."""
    return {**spring.as_json(), "rest": spring.rest}


def _mecanum_tyres(spec, drive, sources) -> list[str]:
    """A mecanum robot's wheels grip as tyres in the file (their tyre's friction, not the
    rollers' free roll of a planar_move robot's <mu1> 0.01): a file cannot hold the
    rollers mcar sim models (their contact is re-aligned every step, sim/rollers.py), so
    it drives forward and turns, but does not strafe; the note says so."""
    from ..sim.rollers import tyre_grip

    if drive is None or drive.kind != "mecanum":
        return []
    grips = {w.link: tyre_grip(w, sources)[0] for w in drive.wheels}
    for geom in spec.geoms:
        if geom.parent.name in grips and (geom.contype or geom.conaffinity):
            geom.friction = [grips[geom.parent.name], geom.friction[1], geom.friction[2]]
            geom.priority = 1
    return ["mecanum wheels: their rollers are not in the file (mcar sim models them); "
            "each wheel grips as a tyre of mu " + ", ".join(sorted({f"{g:g}" for g in
                                                                  grips.values()}))
            + ": the robot drives and turns, but does not strafe"]


def is_vehicle(root, aloft: set[str] = frozenset()) -> bool:
    """Whether the URDF ``root`` is a vehicle as sim decides it before any engine runs: two
    or more joints turning without end (continuous, or revolute limited to ±UNLIMITED or
    more) about a level axis moving collision geometry down to the floor (not the links of
    ``aloft``: :func:`mobile_car.sim.vehicle.aloft_bodies`), and another link with some to
    stand on."""
    from ..sim.vehicle import endless, lacks, level_turning

    colliding = {link.get("name") for link in root.iterchildren("link")
                 if link.find("collision") is not None}
    elements = list(root.iterchildren("joint"))
    joints = [(joint.get("type"), _link_of(joint, "parent"), _link_of(joint, "child"),
               joint.find("origin"), _axis(joint)) for joint in elements]
    level = level_turning(joints)
    wheels = {child for element, (kind, _parent, child, _origin, _axis_xyz)
              in zip(elements, joints, strict=True)
              if endless(kind, element.find("limit")) and child in colliding
              and child in level and child not in aloft}
    return lacks(colliding, wheels) is None


def _link_of(joint, tag: str) -> str | None:
    element = joint.find(tag)
    return element.get("link") if element is not None else None


def _axis(joint) -> tuple | None:
    """The joint's axis as urdfdom reads it (1 0 0 without an <axis>, 0 0 0 unreadable)."""
    axis = joint.find("axis")
    if axis is None:
        return (1.0, 0.0, 0.0)
    value = parse_numbers(axis.get("xyz"), 3)
    return value if isinstance(value, tuple) else (0.0, 0.0, 0.0)


def parse_robot(urdf: bytes, label: str):
    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                             huge_tree=False, remove_comments=True, remove_pis=True)
    try:
        return etree.fromstring(urdf, parser)
    except etree.XMLSyntaxError as error:
        raise ExportError(f"not well-formed XML: {error.msg}", file=label,
                          line=error.lineno) from None


def place_meshes(root, assets: Assets, loaded) -> list[str]:
    """Point every ``<mesh>`` at its copy in the folder; a mesh that cannot be copied is
    left out with its visual or collision, and a warning says so."""
    warnings = []
    # the links' own meshes only: a <gazebo> block kept for SDF holds SDF, not URDF
    found = [(link, part, mesh) for link in root.iterchildren("link") for part in link
             if part.tag in ("visual", "collision") for mesh in part.findall("geometry/mesh")]
    for link, holder, mesh in found:
        uri = mesh.get("filename") or ""
        try:
            asset = assets.add(uri, loaded.search, loaded.base, loaded.label)
        except McarError as error:
            warnings.append(f"link {link.get('name')}: {holder.tag} left out: {error.message}")
            link.remove(holder)
            continue
        mesh.set("filename", asset.relative)
        if holder.tag == "visual" and asset.colour is not None and \
                _child(holder, "material") is None:
            material = etree.SubElement(holder, "material", name=f"mcar_colour_{asset.relative}")
            etree.SubElement(material, "color", rgba=" ".join(f"{c:.4g}" for c in asset.colour))
    return warnings


def place_textures(root, assets: Assets, loaded, copy: bool) -> list[str]:
    """Point every ``<texture>`` at its copy in the folder (``copy``), or take it out; one
    that cannot be copied (outside the allowed folders, missing) is taken out with a
    warning."""
    warnings = []
    for texture in list(root.iter("texture")):
        uri = texture.get("filename")
        if copy and not uri:
            continue  # names no file
        if copy:
            try:
                texture.set("filename", assets.add_file(uri, loaded.search, loaded.base,
                                                        loaded.label))
                continue
            except McarError as error:
                warnings.append(f"texture left out: {error.message}")
        texture.getparent().remove(texture)
    return warnings


def _add_missing_mimics(spec, root, mj) -> None:
    """A ``<mimic>`` the importer left out becomes the equality constraint newer MuJoCo
    makes of it: joint = offset + multiplier * followed joint."""
    have = {(e.name1, e.name2) for e in spec.equalities}
    for joint in root.iter("joint"):
        mimic = _child(joint, "mimic")
        if mimic is None or (joint.get("name"), mimic.get("joint")) in have:
            continue
        if spec.joint(joint.get("name")) is None or spec.joint(mimic.get("joint")) is None:
            continue
        multiplier = parse_number(mimic.get("multiplier")) if mimic.get("multiplier") else 1.0
        offset = parse_number(mimic.get("offset")) if mimic.get("offset") else 0.0
        spec.add_equality(type=mj.mjtEq.mjEQ_JOINT, name1=joint.get("name"),
                          name2=mimic.get("joint"),
                          data=[offset or 0.0, 1.0 if multiplier is None else multiplier,
                                0, 0, 0, 0, 0, 0, 0, 0, 0])


def _compile(spec, label: str):
    try:
        return spec.compile()
    except ValueError as error:
        raise ExportError(f"MuJoCo cannot compile the robot: {_first_line(error)}",
                          file=label) from None


def _first_line(error) -> str:
    text = str(error).strip().splitlines()
    return (text[0] if text else type(error).__name__).removeprefix("Error: ")


def _child(element, tag: str):
    return next((c for c in element if c.tag == tag), None)


def robot_file_name(root, suffix: str = ".xml") -> str:
    """``NAME.xml`` after the robot's name, where that is a plain file name."""
    from ..names import component_problem

    name = (root.get("name") or "").strip()
    if not name or component_problem(name + suffix) or name.startswith(".") or "\\" in name:
        name = "robot"
    return name + suffix


def urdf_mass(root) -> float:
    """The sum of the links' ``<inertial><mass value>`` (kg)."""
    total = 0.0
    for link in root.iterchildren("link"):
        mass = link.find("inertial/mass")
        value = parse_number(mass.get("value")) if mass is not None else None
        total += value or 0.0
    return total


def moving_joints(root) -> list[str]:
    """The robot's joints that move (every type but ``fixed``)."""
    return [j.get("name") for j in root.iterchildren("joint") if j.get("type") != "fixed"]


def drive_summary(drive) -> dict | None:
    """What the manifest says of the drive, and what ``--verify`` commands."""
    if drive is None:
        return None
    from types import SimpleNamespace

    from ..sim.run import command_speed

    return {"kind": drive.kind, "left": [w.joint for w in drive.left],
            "right": [w.joint for w in drive.right], "radius": drive.radius,
            "speed": command_speed(SimpleNamespace(drive=drive)),  # it reads .drive only
            "steering": [s.joint for s in drive.steering],
            "motors": {w.joint: {"kv": w.gain, "effort": w.effort} for w in drive.driven},
            **({"centre": [w.joint for w in drive.centre]} if drive.centre else {})}
