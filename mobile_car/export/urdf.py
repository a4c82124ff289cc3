"""``mcar export --to urdf`` and ``--to sdf``: the robot as plain files another tool reads
where no ROS package exists (PyBullet, Genesis, Drake, yourdfpy, Gazebo).

``--to urdf``: the URDF mcar builds (xacro expanded), every ``<mesh>`` and ``<texture>``
copied below ``meshes/`` and named by a path relative to the robot file, no
``package://`` left. Meshes are copied as they are (STL, OBJ with its ``.mtl`` and
textures, COLLADA with its images); other formats (PLY, compressed files, ...) are
converted to STL in metres, each listed (:mod:`.assets`). ``<gazebo>``,
``<transmission>`` and ``<ros2_control>`` are kept; a ``package://`` left in them (a
plugin's parameter file) is warned about, as the folder alone cannot give it.

``--to sdf``: that same URDF given to libsdformat through the Gazebo helper
(:mod:`mobile_car.gazebo.helper`), and the SDF it writes, its mesh URIs relative
(``meshes/...``, which Gazebo resolves against the SDF file's folder). libsdformat lumps
links on fixed joints into one body and leaves out a massless link on a moving joint:
what it keeps is said in the manifest's notes.

Masses in kg.
"""

from __future__ import annotations

from pathlib import Path

from lxml import etree

from .mjcf import Exported, moving_joints, prepare, robot_file_name, urdf_mass

URDF_KEEPS = (".stl", ".obj", ".dae")  # what URDF tools read: RViz, Gazebo, trimesh
PACKAGE = "package://"


def export_urdf(loaded, folder: Path, options) -> Exported:
    """Write ``NAME.urdf`` and its meshes into ``folder``."""
    root, prepared, warnings = _portable_urdf(loaded, folder)
    name = robot_file_name(root, ".urdf")
    (folder / name).write_bytes(_xml(root))
    return _exported(name, root, prepared, folder, warnings, [])


def export_sdf(loaded, folder: Path, options) -> Exported:
    """Write ``NAME.sdf`` (libsdformat's) and its meshes into ``folder``; GazeboError when
    libsdformat cannot make a model of the robot, GazeboUnavailable without the helper."""
    from ..gazebo.helper import run_helper
    from ..gazebo.includes import refuse_includes

    refuse_includes(loaded.urdf, loaded.label, loaded.locate)  # E152, at its source line
    root, prepared, warnings = _portable_urdf(loaded, folder)
    report = run_helper(_xml(root), loaded.label, with_sdf=True)
    if report.model is None or report.errors or not report.sdf:
        from ..errors import GazeboError

        first = report.errors[0].text.strip().splitlines()[0][:300] if report.errors \
            else "no model"
        raise GazeboError(f"libsdformat {report.sdformat} cannot make a Gazebo model of it: "
                          f"{first}",
                          file=loaded.label)
    # what it printed and loaded past (errors included: not in its verdict), once each
    warnings += [f"libsdformat: {m.text.strip()} ({m.where})"
                 for m in dict.fromkeys((*report.console_errors, *report.warnings))]
    notes, lost = sdf_notes(report, root)
    warnings += lost
    name = robot_file_name(root, ".sdf")
    (folder / name).write_text(report.sdf, encoding="utf-8")
    exported = _exported(name, root, prepared, folder, warnings, notes)
    exported.model_mass = report.model.mass
    return exported


def sdf_notes(report, root) -> tuple[list[str], list[str]]:
    """What Gazebo's model keeps of the URDF's links, in words: (notes, a warning for
    links it leaves out, whose mass the SDF lacks)."""
    links = [link.get("name") for link in root.iterchildren("link")
             if link.get("name") != "world"]
    notes = [f"{len(links)} URDF links become {len(report.model.links)} Gazebo "
             f"link{'s' * (len(report.model.links) != 1)}: libsdformat lumps links on fixed "
             "joints into their parent (masses and inertias summed, visuals and collisions "
             "kept, the fixed joints gone)"]
    from ..gazebo.changes import link_fates

    _lumped, lost = link_fates(links, report, None)
    warnings = [f"libsdformat leaves out {', '.join(lost)} (a link without mass and what "
                f"moves below it): the SDF has {report.model.mass:.6g} kg of the URDF's "
                f"{urdf_mass(root):.6g} kg; mcar check --gazebo says why"] if lost else []
    return notes, warnings


def _portable_urdf(loaded, folder: Path):
    prepared = prepare(loaded, folder, URDF_KEEPS, keep_extras=True, binary_stl_only=False,
                       copy_textures=True)
    root = prepared.root
    warnings = prepared.warnings
    for element in root.iter():
        said = [v for v in [*element.attrib.values(), element.text or ""] if PACKAGE in v]
        if said and element.tag not in ("mesh", "texture"):
            warnings.append(f"<{element.tag}> (line {element.sourceline}) still names "
                            f"{said[0].strip()[:200]}: the folder does not hold it")
    return root, prepared, warnings


def _xml(root) -> bytes:
    return etree.tostring(root, xml_declaration=True, encoding="utf-8") + b"\n"


def _exported(name: str, root, prepared, folder: Path, warnings, notes) -> Exported:
    mass = urdf_mass(root)
    return Exported(
        robot_file=name, urdf_mass=mass, model_mass=mass, moving_joints=moving_joints(root),
        meshes=sorted(p.relative_to(folder).as_posix() for p in folder.rglob("*")
                      if p.is_file()),
        converted=[f"{a.uri} -> {a.relative}" for a in prepared.assets.by_uri.values()
                   if a.converted],
        warnings=warnings, notes=notes, base="as described")
