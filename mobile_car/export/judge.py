"""``mcar export --to mjcf --verify`` judges the exported model as ``mcar sim`` judges the
description: the same scenarios (:mod:`mobile_car.sim.scenarios`: drop, then drive and
spin or turn by the drive kind) with the same bounds, run on the MJCF read back from the
folder, so that an export passes only what sim would pass.

What is judged is what the file holds: its bodies, joints, contacts and the actuators
the export wrote (``mcar_motor_JOINT``, ``mcar_steer_JOINT``: their gain and force
limit); the manifest says which joints drive (sim's drive, found on the description) and
the speed to command, and which joints are sim's springs (their rest: the robot is
released there, as sim releases it). A joint the export left free stays free (an arm
folds): the export is judged as a MuJoCo user will run it.
"""

from __future__ import annotations

from lxml import etree

from ..errors import UsageError
from . import ExportError

JUDGE_FREE_JOINT = "mcar_free"  # the free joint's name sim's runs look for


def sim_model_of(mj, path, exported, label: str):
    """A :class:`~mobile_car.sim.model.SimModel` of the exported MJCF at ``path`` with the
    manifest's drive (``exported.drive``), on a floor."""
    from ..sim.drives import choose_drive, find_tree
    from ..sim.model import add_floor, lowest_points
    from .mjcf import FREE_JOINT

    spec = mj.MjSpec.from_file(str(path))
    free = spec.joint(FREE_JOINT)
    if free is None:
        raise ExportError(f"no free joint {FREE_JOINT} to drop and drive the robot on",
                          file=label)
    free.name = JUDGE_FREE_JOINT
    if not exported.floor:
        add_floor(spec, mj)
    try:
        model = spec.compile()
    except ValueError as error:
        raise ExportError(f"MuJoCo cannot compile the export on a floor: {error}",
                          file=label) from None
    data = mj.MjData(model)
    mj.mj_kinematics(model, data)
    joints = _joint_elements(mj, model, getattr(exported, "joint_types", None) or {})
    summary = exported.drive
    if summary is None:  # a vehicle sim drives no kind of: it must still stand, as in sim
        return _resting(mj, model, spec, data, None, [], {})
    # the joints the export steers steer here too (a continuous one is no castor's swivel)
    tree = find_tree(mj, model, data, joints, lowest_points(mj, model, data),
                     set(summary.get("steering") or ()))
    try:
        drive, _ = choose_drive(tree, set(), summary["left"],
                                summary["right"], summary["kind"])
    except UsageError as error:  # worded for --left/--right: the manifest named them
        raise ExportError(f"the manifest's drive does not fit the model: {error.message}",
                          file=label) from None
    drive.chosen = "the export's manifest"
    for wheel in drive.driven:
        actuator = _actuator(model, f"mcar_motor_{wheel.joint}", wheel.joint, label)
        wheel.actuator_id = actuator.id
        wheel.gain = float(actuator.gainprm[0])
        wheel.effort = float(actuator.forcerange[1]) if actuator.forcelimited[0] else None
        wheel.velocity = 2 * float(summary["speed"])  # sim commands half the limit
    for steer in drive.steering:
        steer.actuator_id = _actuator(model, f"mcar_steer_{steer.joint}", steer.joint,
                                      label).id
    springs, start = _springs(mj, model, data, getattr(exported, "springs", None) or [],
                              label)
    return _resting(mj, model, spec, data, drive, springs, start)


def _resting(mj, model, spec, data, drive, springs: list, start: dict):
    """The SimModel of the export as sim has it at rest: what touches, the pose its
    geometry rests in (leaning on a low castor; level, at the height the export placed it,
    to the last bit sim's: a run at a motor's limit amplifies 3e-10 m into millimetres),
    the springs released at their rest. Without a drive it rests on whatever touches."""
    from ..sim.model import (
        SimModel,
        colliding_geoms,
        lowest_points,
        resting_parts,
        support_geoms,
    )
    from ..sim.resting import rest_pose

    wheels = drive.wheels if drive else []
    ground, parts, clearance = resting_parts(model, lowest_points(mj, model, data), wheels,
                                             data)
    ground_geoms = [g for w in wheels for g in w.geom_ids] or colliding_geoms(model)
    supports = support_geoms(model, ground_geoms, set(parts.values()))
    root = int(model.jnt_bodyid[model.joint(JUDGE_FREE_JOINT).id])
    height = float(model.qpos0[model.jnt_qposadr[model.joint(JUDGE_FREE_JOINT).id] + 2])
    rest = rest_pose(mj, model, _posed(mj, model, start), root, supports, lowest_points)
    if rest.roll == rest.pitch == 0.0:
        rest.height = height - ground
    return SimModel(model=model, spec=spec, root=model.body(root).name, root_body=root,
                    drive=drive, why_no_drive=None if drive else "the export has no drive",
                    rest_height=rest.height, ground_parts=parts, clearance=clearance,
                    floor_geom=model.geom("mcar_floor").id, mass=float(model.body_mass.sum()),
                    ground_geoms=ground_geoms, support_geoms=supports, rest=rest,
                    springs=springs, start=start)


def _springs(mj, model, data, records: list[dict], label: str):
    """(sim's Spring of each of the manifest's ``records``, joint -> its rest), with
    ``data``'s kinematics redone at that rest: sim measures the resting geometry and
    releases the robot there. The stiffness, damping and travel are the file's own."""
    from ..sim.springs import Spring

    springs = []
    for record in records:
        try:
            joint = model.joint(record["joint"]).id
        except KeyError:
            raise ExportError(f"the manifest's spring {record['joint']} is no joint of the "
                              "export", file=label) from None
        lower, upper = (float(x) for x in model.jnt_range[joint])
        springs.append(Spring(record["joint"], lower, upper, float(model.jnt_stiffness[joint]),
                              float(model.qpos_spring[model.jnt_qposadr[joint]]),
                              float(model.dof_damping[model.jnt_dofadr[joint]]),
                              record["source"], float(record["rest"]),
                              model.jnt_type[joint] == mj.mjtJoint.mjJNT_SLIDE))
    start = {s.joint: s.rest for s in springs}
    for name, position in start.items():
        data.qpos[model.jnt_qposadr[model.joint(name).id]] = position
    mj.mj_kinematics(model, data)
    return springs, start


def _posed(mj, model, start: dict):
    """Fresh data with the joints of ``start`` there (the rest pose's search starts it)."""
    data = mj.MjData(model)
    for name, position in start.items():
        data.qpos[model.jnt_qposadr[model.joint(name).id]] = position
    return data


def judge(mj, path, exported, label: str) -> list[str]:
    """Run sim's scenarios for the drive kind on the exported model: a line per scenario
    passed, or ExportError with why the first failed scenario failed, as sim says it,
    naming the others that failed."""
    from ..sim.scenarios import run_scenarios, show_bound, show_value

    sim = sim_model_of(mj, path, exported, label)
    # A file holds no mecanum rollers (sim re-aligns their contact every step: a file
    # cannot): a mecanum export's wheels grip as tyres, judged on drop and drive only.
    results = run_scenarios(sim, ("drop",) if sim.drive is None else
                            ("drop", "drive") if sim.kind == "mecanum" else None)
    failed = [r for r in results if r.status == "failed"]
    if failed:  # one line: the first failure in full, the others by name
        others = f" ({' and '.join(r.name for r in failed[1:])} failed too)" \
            if failed[1:] else ""
        raise ExportError(f"{failed[0].name} failed as mcar sim judges it: "
                          f"{failed[0].message()}{others}", file=label)
    return [f"{r.name} passed as mcar sim judges it: " + ", ".join(
        f"{f.name} {show_value(f.value, f.unit)} ({show_bound(f)})" for f in r.figures)
        for r in results if r.status == "passed"]


def _actuator(model, name: str, joint: str, label: str):
    try:
        return model.actuator(name)
    except KeyError:
        raise ExportError(f"drive joint {joint} has no actuator {name}", file=label) from None


def _joint_elements(mj, model, types: dict[str, str]) -> dict:
    """The model's joints as the URDF elements sim's drive finder reads: the type the
    description gave (``types``, the manifest's), else a hinge without a range is
    ``continuous``, with one ``revolute``, and a slide ``prismatic``."""
    joints = {}
    for j in range(model.njnt):
        kind = model.jnt_type[j]
        if kind == mj.mjtJoint.mjJNT_HINGE:
            name = "revolute" if model.jnt_limited[j] else "continuous"
        elif kind == mj.mjtJoint.mjJNT_SLIDE:
            name = "prismatic"
        else:
            continue
        name = types.get(model.joint(j).name, name)
        element = etree.Element("joint", name=model.joint(j).name, type=name)
        if model.jnt_limited[j]:
            low, high = model.jnt_range[j]
            etree.SubElement(element, "limit", lower=repr(float(low)), upper=repr(float(high)))
        joints[model.joint(j).name] = element
    return joints
