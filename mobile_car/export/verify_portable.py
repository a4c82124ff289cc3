"""``mcar export --verify`` for the plain-file formats: a URDF folder read back by yourdfpy
(and by urdfdom's ``check_urdf`` where it is installed), an SDF folder by libsdformat
through the Gazebo helper, each from the folder alone, and held to the description.

The helper reads the SDF from stdin (it never opens files) and libsdformat does not open
meshes, so for SDF the files are proven the way every format's are: each ``<uri>`` is a
relative path to a file inside the folder (:func:`.verify.files_inside`).

Masses in kg.
"""

from __future__ import annotations

import contextlib
import logging
import shutil
import subprocess
from pathlib import Path

from lxml import etree

from . import ExportError
from .verify import files_inside, joints_match, mass_matches

CHECK_URDF_TIMEOUT = 60.0  # s


def verify_urdf(folder: Path, exported, shown: str | None = None) -> list[str]:
    """Load ``folder/exported.robot_file`` with yourdfpy, meshes included, resolving file
    names against the folder only; with urdfdom's ``check_urdf`` too where installed."""
    import yourdfpy

    label = Path(shown or folder)
    path = folder / exported.robot_file
    document = _parse(path, label / exported.robot_file)
    files_inside(folder, label, [(element.tag, element.get("filename"))
                                 for element in document.iter("mesh", "texture")
                                 if element.get("filename") is not None])
    handler = _only_in(folder, yourdfpy)
    with _kept_logs("yourdfpy") as said:
        try:
            robot = yourdfpy.URDF.load(str(path), load_meshes=True, build_scene_graph=True,
                                       load_collision_meshes=True,
                                       build_collision_scene_graph=True,
                                       filename_handler=handler)
        except Exception as error:  # yourdfpy and trimesh raise anything on a bad file
            raise ExportError(f"yourdfpy cannot load the export: {str(error)[:300]}",
                              file=str(label / exported.robot_file)) from None
    if said:  # yourdfpy only logs a mesh it cannot find or read, and goes on without it
        raise ExportError(f"yourdfpy: {said[0][:300]}", file=str(label / exported.robot_file))
    mass = sum(float(link.inertial.mass or 0.0) for link in robot.robot.links
               if link.inertial is not None)
    meshes = sum(1 for _ in document.iter("mesh"))
    proven = [f"yourdfpy loads it and its {meshes} mesh{'es' * (meshes != 1)} from the "
              "folder alone, without a warning",
              mass_matches(mass, exported.urdf_mass, label),
              joints_match([j.name for j in robot.robot.joints if j.type != "fixed"],
                           exported.moving_joints, label)]
    check_urdf = shutil.which("check_urdf")
    if check_urdf is not None:
        proven.append(_check_urdf(check_urdf, path, label / exported.robot_file))
    return proven


def verify_sdf(folder: Path, exported, shown: str | None = None) -> list[str]:
    """Load ``folder/exported.robot_file`` with libsdformat (the Gazebo helper): no
    errors, every ``<uri>`` a file inside the folder, the URDF's mass and moving joints."""
    from ..gazebo.helper import run_helper

    label = Path(shown or folder)
    path = folder / exported.robot_file
    # libsdformat writes plugin elements with an undeclared prefix (ignition::...): lxml
    # recovers them; libsdformat itself judges the file below
    document = _parse(path, label / exported.robot_file, recover=True)
    files_inside(folder, label, [("mesh uri", (element.text or "").strip())
                                 for element in document.iter("uri")
                                 if element.getparent().tag == "mesh"
                                 or "package://" in (element.text or "")
                                 or "model://" in (element.text or "")])
    report = run_helper(path.read_bytes(), str(label / exported.robot_file))
    if report.errors or report.model is None:
        first = report.errors[0].text.strip().splitlines()[0][:300] if report.errors \
            else "no model in it"
        raise ExportError(f"libsdformat cannot load the export: {first}",
                          file=str(label / exported.robot_file))
    model = report.model
    moving = [j.name for j in model.joints if j.type != "fixed"]
    return [f"libsdformat {report.sdformat} loads it without errors, every mesh URI a file "
            "in the folder",
            mass_matches(model.mass, exported.urdf_mass, label),
            joints_match(moving, exported.moving_joints, label),
            f"{len(model.links)} Gazebo links (fixed joints lumped: not compared link by "
            "link)"]


def _parse(path: Path, label: Path, recover: bool = False):
    try:
        return etree.parse(str(path), etree.XMLParser(resolve_entities=False, no_network=True,
                                                      recover=recover)).getroot()
    except (etree.XMLSyntaxError, OSError) as error:
        raise ExportError(f"cannot read the export: {error}", file=str(label)) from None


def _only_in(folder: Path, yourdfpy):
    """yourdfpy's file name handler, looking in ``folder`` and nowhere else."""
    import functools

    return functools.partial(yourdfpy.filename_handler_relative, dir=str(folder))


@contextlib.contextmanager
def _kept_logs(name: str):
    """What the logger ``name`` says, kept in a list instead of printed on stderr."""
    said: list[str] = []

    class Keep(logging.Handler):
        def emit(self, record):
            if record.levelno >= logging.WARNING:
                said.append(record.getMessage())

    logger = logging.getLogger(name)
    handler, propagate = Keep(), logger.propagate
    logger.addHandler(handler)
    logger.propagate = False
    try:
        yield said
    finally:
        logger.removeHandler(handler)
        logger.propagate = propagate


def _check_urdf(program: str, path: Path, label: Path) -> str:
    try:
        done = subprocess.run([program, str(path)], capture_output=True, text=True,
                              timeout=CHECK_URDF_TIMEOUT, cwd="/", stdin=subprocess.DEVNULL)
    except (OSError, subprocess.TimeoutExpired) as error:
        raise ExportError(f"check_urdf did not finish: {error}", file=str(label)) from None
    if done.returncode != 0:
        words = (done.stderr or done.stdout).strip().splitlines()
        raise ExportError(f"urdfdom's check_urdf refuses the export: "
                          f"{words[0][:300] if words else f'exit {done.returncode}'}",
                          file=str(label))
    return "urdfdom's check_urdf parses it"
