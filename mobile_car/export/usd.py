"""``mcar export --to usd``: the robot as an OpenUSD asset (Isaac Sim / Isaac Lab, Newton),
written by the Newton project's ``urdf-usd-converter`` and completed with ``pxr``.

Measured before choosing it (docs/exports.md): on the bundled car, TurtleBot3 burger, Husky
and Jackal it keeps every mass exactly, states metres, kilograms and Z-up in the stage,
writes meshes as ``UsdGeom.Mesh``, links as ``UsdPhysics`` rigid bodies with their mass
and inertia, collision APIs, and joints with their limits. What it lacks is added here:

* the converter reads only files mcar measured and wrote: the URDF it is given is mcar's
  (extras stripped, a plain file name), and its meshes are copies within the mesh limits,
  COLLADA and other formats converted to STL in metres by mcar's reader (:mod:`.assets`);
* drives: each drive wheel's joint gets an angular velocity drive with the damping of the
  velocity servo ``mcar sim`` drives it with (kv, N·m·s/rad, written per degree as USD
  wants) and its effort limit (:mod:`mobile_car.sim.servos`, found on MuJoCo's model);
* a massless frame link (the car's ``base_link``) gets no rigid body from the converter:
  its children are re-hung on the nearest massed link fixed to it first (:mod:`.massless`);
* ``--base floating``: a fixed joint holds the robot to the stage, either the converter's
  own ``root_joint`` (a root link with something in it, Husky's) or the URDF's fixed joint
  from an empty root link, which the converter ties to the stage in that link's place
  (Jackal's ``base_link_joint``); that joint is deactivated, and the note says which.

Masses in kg, lengths in m.
"""

from __future__ import annotations

import math
import tempfile
from pathlib import Path

from lxml import etree

from ..errors import McarError
from . import ExportError
from .massless import rehang_on_bodies
from .mjcf import Exported, moving_joints, prepare, robot_file_name, urdf_mass

USD_READS = (".stl", ".obj")


def export_usd(loaded, folder: Path, options) -> Exported:
    """Write the USD asset of a loaded robot into ``folder``."""
    from pxr import Usd

    with tempfile.TemporaryDirectory(prefix=".mcar-usd-sources-", dir=folder.parent) as scratch:
        # its textures too: the converter reads what the URDF names (never a file outside)
        prepared = prepare(loaded, Path(scratch), USD_READS, copy_textures=True)
        root = prepared.root
        rehung = rehang_on_bodies(root)
        stem = robot_file_name(root, "")
        root.set("name", stem)
        source = Path(scratch) / f"{stem}.urdf"
        source.write_bytes(etree.tostring(root, xml_declaration=True, encoding="utf-8"))
        drive = _drive(loaded, prepared)
        from pxr import UsdUtils
        from urdf_usd_converter import Converter

        # USD's diagnostics (status lines, the converter's warnings) are kept, not printed
        # on stderr: a library does not print; the warnings join the export's.
        said = UsdUtils.CoalescingDiagnosticDelegate()
        try:
            asset = Converter(layer_structure=True, scene=True).convert(str(source),
                                                                          str(folder))
        except (ValueError, RuntimeError, OSError) as error:
            raise ExportError(f"urdf-usd-converter cannot convert the robot: {error}",
                              file=loaded.label) from None
        finally:
            told = [d for d in said.TakeUncoalescedDiagnostics()
                    if "Warning" in str(d.diagnosticCodeString)]
            del said
        prepared.warnings += [f"urdf-usd-converter: {d.commentary}" for d in told]
        converted = [f"{a.uri} -> {a.relative} (then into the USD layers)"
                     for a in prepared.assets.by_uri.values() if a.converted]
    path = Path(str(asset.path))
    stage = Usd.Stage.Open(str(path))
    notes = rehung + _complete(stage, drive, options.base, _fixed_joint_parents(root))
    stage.Save()
    return Exported(
        robot_file=path.relative_to(folder).as_posix(), urdf_mass=urdf_mass(root),
        model_mass=stage_mass(stage), moving_joints=moving_joints(root),
        meshes=sorted(p.relative_to(folder).as_posix() for p in folder.rglob("*")
                      if p.is_file()),
        converted=converted, warnings=prepared.warnings, notes=notes, drive=drive,
        base=options.base)


def _drive(loaded, prepared) -> dict | None:
    """The drive ``mcar sim`` finds on MuJoCo's reading of the robot, with its servos'
    gains, or None where MuJoCo cannot read it (the USD then has no drives)."""
    from ..sim.engine import mujoco
    from ..sim.model import lowest_points
    from ..sim.servos import fit_drive
    from .mjcf import drive_summary, mujoco_spec

    mj = mujoco()
    try:
        spec = mujoco_spec(mj, prepared, loaded.label)
        spec.compiler.balanceinertia = True  # the drive's figures do not depend on it
        spec.worldbody.first_body().add_freejoint()
        shape = spec.compile()
    except (McarError, ValueError, AttributeError):
        return None
    data = mj.MjData(shape)
    mj.mj_kinematics(shape, data)
    drive, _ = fit_drive(mj, shape, data, prepared.joints, prepared.sources,
                         lowest_points(mj, shape, data))
    return drive_summary(drive)


def _fixed_joint_parents(root) -> dict[str, str]:
    """The URDF's fixed joints: name -> parent link (what a note about one names)."""
    parents = {}
    for joint in root.iter("joint"):
        parent = joint.find("parent")
        if joint.get("type") == "fixed" and parent is not None:
            parents[joint.get("name")] = parent.get("link")
    return parents


def _complete(stage, drive: dict | None, base: str, urdf_fixed: dict[str, str]) -> list[str]:
    from pxr import UsdPhysics

    notes = []
    joints = {p.GetName(): p for p in stage.Traverse() if p.IsA(UsdPhysics.Joint)}
    if base == "floating":
        for name, prim in joints.items():
            if _welds_to_stage(stage, prim):
                prim.SetActive(False)
                notes.append(f"joint {name} ({_weld_origin(prim, name, urdf_fixed)}) "
                             "deactivated: the base floats")
    for joint, motor in ((drive or {}).get("motors") or {}).items():
        prim = joints.get(joint)
        if prim is None:
            continue
        api = UsdPhysics.DriveAPI.Apply(prim, "angular")
        api.CreateTypeAttr("force")
        api.CreateStiffnessAttr(0.0)
        api.CreateDampingAttr(float(motor["kv"]) * math.pi / 180)  # per degree
        api.CreateTargetVelocityAttr(0.0)
        if motor.get("effort") is not None:
            api.CreateMaxForceAttr(float(motor["effort"]))
    return notes


def _weld_origin(prim, name: str, urdf_fixed: dict[str, str]) -> str:
    """Whose joint holds the robot to the stage: a joint the URDF has is the robot's own,
    tied to the stage because its parent link is empty (the converter makes no body of
    it); any other is the converter's. The prim's name may be a USD-safe spelling of the
    URDF's, which the converter then keeps as its display name."""
    urdf_name = prim.GetMetadata("displayName") or name
    parent = urdf_fixed.get(urdf_name)
    if parent is None:
        return "the converter's weld of the root link to the stage"
    return (f"the URDF's fixed joint from {parent}, a link with nothing in it, which the "
            f"converter ties to the stage")


def _welds_to_stage(stage, prim) -> bool:
    """A fixed joint whose first body is no rigid body (the stage itself)."""
    from pxr import UsdPhysics

    if not prim.IsA(UsdPhysics.FixedJoint):
        return False
    targets = UsdPhysics.Joint(prim).GetBody0Rel().GetTargets()
    if not targets:
        return True
    body = stage.GetPrimAtPath(targets[0])
    return not (body and body.HasAPI(UsdPhysics.RigidBodyAPI))


def stage_mass(stage) -> float:
    """The sum of the masses the stage's MassAPIs give (kg)."""
    from pxr import UsdPhysics

    return float(sum(UsdPhysics.MassAPI(p).GetMassAttr().Get() or 0.0
                     for p in stage.Traverse() if p.HasAPI(UsdPhysics.MassAPI)))
