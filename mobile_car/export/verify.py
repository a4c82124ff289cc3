"""``mcar export --verify``: an export loaded back by its own engine from its folder alone,
and held to the description. A mismatch is an ExportError naming what differs; what was
proven comes back as lines for the report.

For every format: each file the robot file names is a relative path inside the folder
(so the folder loads on a machine without the packages), the total mass equals the
description's within :data:`MASS_TOLERANCE`, and the moving joints are the description's.
For USD, a physics asset, the total mass is above 0 too.
For MuJoCo, a vehicle (a floating base with a drive) is also judged as ``mcar sim`` judges
the description, by the same scenarios and bounds (:mod:`.judge`), on a floor
(``mcar_floor``, added for the judging when the export has none).

Masses in kg, lengths in m, times in s, speeds in rad/s.
"""

from __future__ import annotations

import os
from pathlib import Path

from lxml import etree

from . import ExportError

MASS_TOLERANCE = 0.001       # of the description's mass
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
    if exported.base == "floating" and (exported.drive or exported.vehicle):
        from .judge import judge

        proven += judge(mj, path, exported, str(label))
    return proven


def _has_mass(mass: float, label: Path) -> None:
    """A USD asset is for physics (Isaac Sim, Newton): a stage whose rigid bodies weigh
    nothing in all is no robot there, even when the description (a visual-only URDF for
    RViz) weighs nothing too; each engine would make its masses up from the colliders."""
    if not mass > 0:
        raise ExportError(f"total mass {mass:.6g} kg: no rigid body of the stage has a mass "
                          "(the description gives no link an <inertial> mass), so a physics "
                          "engine would make every mass up from the colliders' volume",
                          file=str(label))


def verify_usd(folder: Path, exported, shown: str | None = None) -> list[str]:
    """Open the stage with ``pxr`` from the folder alone and hold it to ``exported``:
    every layer and asset it depends on inside the folder, metres, kilograms and Z-up,
    a total mass above 0 and equal to the description's, the moving joints, a rigid body
    at each end of each moving joint, and a drive on each drive wheel."""
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

    _has_mass(stage_mass(stage), label)
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
