"""``mcar export --verify``: an export loaded back by its own engine from its folder alone,
and held to the description. A mismatch is an ExportError naming what differs; what was
proven comes back as lines for the report.

For every format: each file the robot file names is a relative path inside the folder
(so the folder loads on a machine without the packages), the total mass equals the
description's within :data:`MASS_TOLERANCE`, and the moving joints are the description's.
For MuJoCo, a vehicle also settles on a floor (``mcar_floor``, added for the check when the
export has none) and drives forward under its own actuators.

Masses in kg, lengths in m, times in s, speeds in rad/s.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

from lxml import etree

from . import ExportError

MASS_TOLERANCE = 0.001       # of the description's mass
SETTLE_TIME = 1.0
SETTLED_SPEED = 0.02         # m/s: the root slower than this after SETTLE_TIME
UPRIGHT_DEGREES = 5.0        # roll and pitch after settling
DRIVE_TIME = 2.0
DRIVE_SHARE = (0.5, 1.1)     # of r·ω·t the robot must cover: forward, not faster
MJCF_FILE_ATTRIBUTES = {"mesh": "file", "texture": "file", "hfield": "file", "skin": "file",
                        "include": "file", "model": "file"}


def files_inside(folder: Path, label: Path, names: list[tuple[str, str]]) -> None:
    """ExportError unless each (what, path) is relative, stays in ``folder`` and exists."""
    root = Path(os.path.realpath(folder))
    for what, name in names:
        path = Path(name)
        real = Path(os.path.realpath(root / path))
        if "://" in name or path.is_absolute() or root not in real.parents or \
                not real.is_file():
            why = ("a URI, not a path in the folder" if "://" in name else
                   "an absolute path" if path.is_absolute() else
                   "outside the folder" if root not in real.parents else "missing")
            raise ExportError(f"{what} {name}: {why}; the folder would not load elsewhere",
                              file=str(label))


def mass_matches(model_mass: float, described: float, folder: Path, added: float = 0.0) -> str:
    """The total mass against the description's (plus what --fix-inertia ``added``)."""
    expected = described + added
    difference = abs(model_mass - expected) / expected if expected > 0 else abs(model_mass)
    theirs = f"the description's {described:.6g} kg" + (
        f" + {added:.6g} kg given to massless links" if added else "")
    if difference > MASS_TOLERANCE:
        raise ExportError(f"total mass {model_mass:.6g} kg, {theirs} ({100 * difference:.3g}% "
                          f"apart, more than {100 * MASS_TOLERANCE:g}%)", file=str(folder))
    return f"mass {model_mass:.6g} kg, {theirs}"


def joints_match(found: list[str], expected: list[str], folder: Path) -> str:
    missing = [j for j in expected if j not in found]
    extra = [j for j in found if j not in expected]
    if missing or extra:
        parts = ([f"missing {', '.join(missing)}"] if missing else []) + \
                ([f"not in the description: {', '.join(extra)}"] if extra else [])
        raise ExportError(f"moving joints differ: {'; '.join(parts)}", file=str(folder))
    return f"{len(found)} moving joint{'s' * (len(found) != 1)}"


def verify_mjcf(folder: Path, exported, shown: str | None = None) -> list[str]:
    """Load ``folder/exported.robot_file`` with MuJoCo and hold it to ``exported``;
    ``shown``: the folder's name in messages (the target, where ``folder`` is staged)."""
    from ..sim.engine import mujoco
    from .mjcf import FREE_JOINT

    mj = mujoco()
    label = Path(shown or folder)
    path = folder / exported.robot_file
    document = etree.parse(str(path), etree.XMLParser(resolve_entities=False,
                                                      no_network=True)).getroot()
    files_inside(folder, label, [(element.tag, element.get(attribute))
                          for tag, attribute in MJCF_FILE_ATTRIBUTES.items()
                          for element in document.iter(tag) if element.get(attribute)])
    try:
        spec = mj.MjSpec.from_file(str(path))
        model = spec.compile()
    except ValueError as error:
        raise ExportError(f"MuJoCo cannot load the export: {str(error).strip()}",
                          file=str(label / exported.robot_file)) from None
    proven = ["MuJoCo loads it from the folder alone"]
    proven.append(mass_matches(float(model.body_mass.sum()), exported.urdf_mass, label,
                               exported.added_mass))
    names = [model.joint(j).name for j in range(model.njnt)
             if model.joint(j).name != FREE_JOINT]
    proven.append(joints_match(names, exported.moving_joints, label))
    if exported.base == "floating" and exported.drive:
        if not exported.floor:
            from ..sim.model import add_floor

            add_floor(spec, mj)
            model = spec.compile()
        proven += _settles_and_drives(mj, model, exported.drive, label)
    return proven


def _settles_and_drives(mj, model, drive: dict, folder: Path) -> list[str]:
    data = mj.MjData(model)
    root = int(model.jnt_bodyid[_free(mj, model)])
    steps = round(SETTLE_TIME / model.opt.timestep)
    mj.mj_step(model, data, nstep=steps)
    free = model.jnt_dofadr[_free(mj, model)]
    speed = float(sum(v * v for v in data.qvel[free:free + 3]) ** 0.5)
    roll, pitch = _tilt(data.xquat[root])
    if speed > SETTLED_SPEED or max(abs(roll), abs(pitch)) > UPRIGHT_DEGREES:
        raise ExportError(f"does not settle on the floor: after {SETTLE_TIME:g} s it moves at "
                          f"{speed:.3g} m/s, roll {roll:.1f}°, pitch {pitch:.1f}°",
                          file=str(folder))
    start = data.xpos[root].copy()
    heading = data.xmat[root].reshape(3, 3)[:, 0].copy()
    omega = float(drive["speed"])
    for joint in drive["left"] + drive["right"]:
        actuator = model.actuator(f"mcar_motor_{joint}").id
        axis = data.xaxis[model.joint(joint).id]
        data.ctrl[actuator] = omega if axis[1] >= 0 else -omega
    mj.mj_step(model, data, nstep=round(DRIVE_TIME / model.opt.timestep))
    moved = data.xpos[root] - start
    along = float(moved[:2] @ heading[:2]) / max(1e-12, float(math.hypot(*heading[:2])))
    ideal = float(drive["radius"]) * omega * DRIVE_TIME
    low, high = DRIVE_SHARE
    if not low * ideal <= along <= high * ideal:
        raise ExportError(f"does not drive forward under its actuators: {along:.3g} m in "
                          f"{DRIVE_TIME:g} s at {omega:.3g} rad/s, where r·ω·t is {ideal:.3g} m "
                          f"(between {low:.0%} and {high:.0%} of it expected)",
                          file=str(folder))
    return [f"settled on the floor (roll {roll:.1f}°, pitch {pitch:.1f}°)",
            f"drove {along:.3g} m forward in {DRIVE_TIME:g} s under its actuators "
            f"({along / ideal:.0%} of r·ω·t)"]


def _free(mj, model) -> int:
    for j in range(model.njnt):
        if model.jnt_type[j] == mj.mjtJoint.mjJNT_FREE:
            return j
    raise ExportError("no free joint to settle and drive on", file=None)


def _tilt(quat) -> tuple[float, float]:
    """Roll and pitch (degrees) of a unit quaternion (w, x, y, z)."""
    w, x, y, z = (float(v) for v in quat)
    roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
    return math.degrees(roll), math.degrees(pitch)


def verify_usd(folder: Path, exported, shown: str | None = None) -> list[str]:
    """Open the stage with ``pxr`` from the folder alone and hold it to ``exported``:
    every layer and asset it depends on inside the folder, metres, kilograms and Z-up,
    the total mass, the moving joints, a rigid body at each end of each moving joint,
    and a drive on each drive wheel."""
    from pxr import Usd, UsdGeom, UsdPhysics, UsdUtils

    label = Path(shown or folder)
    path = folder / exported.robot_file
    layers, assets, unresolved = UsdUtils.ComputeAllDependencies(str(path))
    if unresolved:
        raise ExportError(f"the stage names files that are not there: "
                          f"{', '.join(map(str, unresolved))}", file=str(label))
    root = Path(os.path.realpath(folder))
    files = [layer.realPath for layer in layers] + [str(a) for a in assets]
    files_inside(folder, label, [("USD file", os.path.relpath(f, root)) for f in files])
    stage = Usd.Stage.Open(str(path))
    if stage is None:
        raise ExportError("pxr cannot open the stage", file=str(label / exported.robot_file))
    units = (UsdGeom.GetStageMetersPerUnit(stage), UsdPhysics.GetStageKilogramsPerUnit(stage),
             UsdGeom.GetStageUpAxis(stage))
    if units != (1.0, 1.0, "Z"):
        raise ExportError(f"the stage says {units[0]} m and {units[1]} kg a unit, "
                          f"{units[2]}-up (metres, kilograms, Z-up expected)", file=str(label))
    from .usd import stage_mass

    proven = ["pxr opens it from the folder alone (metres, kilograms, Z-up)",
              mass_matches(stage_mass(stage), exported.urdf_mass, label)]
    moving = [p for p in stage.Traverse() if p.IsA(UsdPhysics.Joint) and p.IsActive()
              and not p.IsA(UsdPhysics.FixedJoint)]
    proven.append(joints_match([p.GetName() for p in moving], exported.moving_joints, label))
    for prim in moving:
        joint = UsdPhysics.Joint(prim)
        for rel in (joint.GetBody0Rel(), joint.GetBody1Rel()):
            targets = rel.GetTargets()
            body = stage.GetPrimAtPath(targets[0]) if targets else None
            if not (body and body.HasAPI(UsdPhysics.RigidBodyAPI)):
                raise ExportError(f"joint {prim.GetName()} moves no rigid body at "
                                  f"{targets[0] if targets else 'one end'}", file=str(label))
    bodies = sum(1 for p in stage.Traverse() if p.HasAPI(UsdPhysics.RigidBodyAPI))
    proven.append(f"{bodies} rigid bodies, each moving joint between two")
    wheels = list((exported.drive or {}).get("motors") or {})
    driven = [p.GetName() for p in moving if p.GetName() in wheels and
              p.HasAPI(UsdPhysics.DriveAPI, "angular")]
    if sorted(driven) != sorted(wheels):
        raise ExportError(f"drive wheels without a drive: "
                          f"{', '.join(sorted(set(wheels) - set(driven)))}", file=str(label))
    if wheels:
        proven.append(f"a velocity drive on each drive wheel ({', '.join(sorted(wheels))})")
    return proven
