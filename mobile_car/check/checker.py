"""``mcar check`` as a library: one input (URDF file, ``.xacro`` file or stdin) in, a
:class:`CheckResult` out: the robot, its kinematic tree, and every diagnostic, sorted.

A ``.xacro`` input is expanded first with :func:`mobile_car.expand.xacro_build.build_file` and its
diagnostics are pointed back at the xacro source (see :mod:`mobile_car.expand.source_map`).
Reading or building failures that are not the file's fault (missing file, unknown
package) are kept as ``failure`` (exit 2), not as diagnostics.
"""

from __future__ import annotations

from pathlib import Path

from ..errors import BuildError, McarError
from ..expand.xacro_warnings import merged_warnings
from ..load.inputs import RobotInput
from ..load.robot import LoadedRobot, LoadOptions, load_robot
from ..packages.search import PackageSearch
from . import document
from .context import Reporter
from .diagnostics import Counted, Diagnostic
from .joints import check_joints
from .link_bodies import check_link_bodies
from .links import material_colours
from .masses import check_masses
from .meshes import MeshFile, check_meshes
from .plausibility import check_plausibility
from .rest_pose import rest_pose
from .rules import RULES
from .schema import check_schema
from .structure import check_names, check_tree, moving_links
from .tree import KinematicTree, build_tree
from .urdf_model import SourceLines, XmlError, axis_of, origin_of, parse_number, parse_xml
from .urdf_reader import Robot, read_robot

LARGE_ROBOT = 2000  # links: the rest pose is worked out with numpy (rest_pose_arrays.py)


class CheckResult(Counted):
    # A plain class, not a dataclass: never compared, and a dataclass costs every run
    # that imports it the compiling of its methods (values.py).
    def __init__(self, file: str, robot: Robot | None = None,
                 tree: KinematicTree | None = None, diagnostics: list[Diagnostic] | None = None,
                 failure: McarError | None = None, where: object = None,
                 loaded: LoadedRobot | None = None, mesh_files: list[MeshFile] | None = None,
                 gazebo: object = None, extents: tuple | None = None):
        self.file = file
        self.robot = robot
        self.tree = tree
        self.diagnostics = [] if diagnostics is None else diagnostics
        self.failure = failure
        self.where = where  # element -> (file, line, note), for the JSON listing
        self.loaded = loaded  # what was checked: URDF text, search, files read
        self.mesh_files = [] if mesh_files is None else mesh_files  # every <mesh>: meshes.py
        # With --gazebo: what Gazebo makes of it (gazebo.changes.GazeboView).
        self.gazebo = gazebo
        # The box around every visual and collision shape in the rest pose, (x, y, z) in
        # metres; None when the tree is not sound or no shape's size is known.
        self.extents = extents
        # That rest pose (rest_pose.RestPose, or rest_pose_arrays.ArraysPose for a large
        # robot), None where there is no extents: sim asks it which wheels reach the floor.
        self.rest = None

    @property
    def tree_is_drawable(self) -> bool:
        return (self.failure is None and self.tree is not None and self.tree.is_sound
                and not any(d.is_error and RULES[d.rule].blocks_tree for d in self.diagnostics))

    @property
    def sound(self) -> bool:
        """No error at all: what check_urdf's "Successfully Parsed" may be printed for."""
        return self.failure is None and self.errors == 0 and self.tree_is_drawable


def check_urdf_data(data: bytes, file: str, *, base: Path, search: PackageSearch,
                    locate=None, structure_only: bool = False) -> CheckResult:
    """Check URDF text; ``structure_only`` stops after names and tree (for ``mcar tree``)."""
    try:
        root = parse_xml(data)
    except XmlError as error:
        report = Reporter(file, locate)
        report.add("E100", error.line, error.message)
        return _finish(CheckResult(file=file, where=locate), report)
    line_of = SourceLines(root, data)
    result = _check_document(root, data, file, base, search, locate, line_of, structure_only,
                             quick_numbers=True)
    if result is None:  # a number float() read differently from urdfdom: read them its way
        result = _check_document(root, data, file, base, search, locate, line_of,
                                 structure_only, quick_numbers=False)
    return result


def _package_macros(base: Path):
    """The package's macro names, asked only when an unknown element is found: finding
    them imports the package discovery, which a sound robot's check does without."""
    from ..packages.discover import package_macros

    return package_macros(base)


def _check_document(root, data: bytes, file: str, base: Path, search: PackageSearch, locate,
                    line_of: SourceLines, structure_only: bool,
                    quick_numbers: bool) -> CheckResult | None:
    """The checks of a parsed document; None if the quick reading of numbers fails its proof."""
    report = Reporter(file, locate, line_of, quick_numbers=quick_numbers)
    result = CheckResult(file=file, where=locate or (lambda element: (file, line_of(element), "")))
    document.check_doctype(data, report)
    document.normalise_default_namespace(root)
    if not document.check_root(root, report) or \
            document.check_xacro_leftovers(root, data, report):
        return _finish(result, report)
    robot = result.robot = read_robot(root)
    check_names(robot, report)
    tree = result.tree = build_tree(robot)
    check_tree(robot, tree, report)
    if structure_only:
        return _finish(result, report)
    document.check_raw_whitespace(root, data, report)
    origins = check_joints(robot, report)  # joint -> (xyz, rpy), of the joints proved plain
    check_schema(robot, report, lambda: _package_macros(base))
    materials = material_colours(robot, report)
    top_level = {element.get("name") for element, _ in robot.materials}
    moving, root_link = moving_links(tree), tree.root if len(tree.roots) == 1 else None
    held = check_link_bodies(robot.links, report, materials, top_level, moving, root_link)
    result.mesh_files = check_meshes(root, base, search, report)
    # Size and plausibility on a robot without errors: a number beyond any robot's (E117)
    # or unreadable (E114) would only be said again, less clearly.
    if tree.is_sound and not any(d.is_error for d in report.diagnostics):
        bounds = {mesh.element: mesh.bounds for mesh in result.mesh_files}
        pose = None
        if len(robot.links) >= LARGE_ROBOT:  # numpy pays for its import from here on
            from .rest_pose_arrays import rest_pose_arrays

            pose = rest_pose_arrays(robot, tree, held, bounds, origins)
        if pose is None:
            pose = rest_pose(robot, tree, held, bounds)
        result.extents, result.rest = pose.extents(), pose
        check_plausibility(robot, tree, pose, report)
        check_masses(robot, tree, held, bounds, report)
    if not report.numbers_confirmed():
        return None
    return _finish(result, report)


def _finish(result: CheckResult, report: Reporter) -> CheckResult:
    result.diagnostics = sorted(set(report.diagnostics), key=Diagnostic.sort_key)
    return result


def check_input(inp: RobotInput, options: LoadOptions | None = None, stdin=None,
                structure_only: bool = False) -> CheckResult:
    """Load one input (see :func:`~mobile_car.load.robot.load_robot`) and check it."""
    try:
        loaded = load_robot(inp, options or LoadOptions(), stdin)
    except BuildError as error:
        message = "; ".join([error.message, *error.details])
        diagnostic = Diagnostic("E140", error.file or inp.label, error.line, message)
        return CheckResult(file=inp.label, diagnostics=[diagnostic])
    except McarError as error:
        return CheckResult(file=inp.label, failure=error)
    return check_loaded(loaded, structure_only)


def check_loaded(loaded: LoadedRobot, structure_only: bool = False) -> CheckResult:
    """Check a loaded robot; xacro's warnings become W220."""
    result = check_urdf_data(loaded.urdf, loaded.label, base=loaded.base, search=loaded.search,
                             locate=loaded.locate, structure_only=structure_only)
    result.loaded = loaded
    if loaded.warnings:
        warnings = [Diagnostic("W220", loaded.label, None, f"xacro: {text}")
                    for text in merged_warnings(loaded.warnings)]
        result.diagnostics = sorted(result.diagnostics + warnings, key=Diagnostic.sort_key)
    return result


def as_json(result: CheckResult) -> dict:
    """The JSON form of one checked input: robot, root, tree, links, joints, diagnostics."""
    robot, tree = result.robot, result.tree
    document = {"file": result.file, "robot": robot.name if robot else None,
                "root": tree.root if tree and len(tree.roots) == 1 else None,
                "ok": result.failure is None and result.errors == 0,
                "errors": result.errors, "warnings": result.warnings,
                "extents": None if result.extents is None else
                [round(v, 6) for v in result.extents],
                "tree": None, "links": [], "joints": [],
                "diagnostics": [d.as_json() for d in result.diagnostics]}
    if result.failure is not None:
        document["failure"] = {"message": result.failure.message,
                               "exit_code": result.failure.exit_code}
    if result.gazebo is not None:
        document["gazebo"] = result.gazebo.as_json()
    if robot is None or tree is None:
        return document
    document["tree"] = {link: [j.child for j in joints] for link, joints in tree.children.items()}
    for link in robot.links:
        parents = tree.parent_joints.get(link.name, [])
        file, line, _ = result.where(link.element)
        document["links"].append({
            "name": link.name, "file": file, "line": line,
            "parent_joint": parents[0].name if len(parents) == 1 else None,
            "children": [j.child for j in tree.children.get(link.name, [])]})
    for joint in robot.joints:
        file, line, _ = result.where(joint.element)
        limit = joint.parts.get("limit")
        document["joints"].append({
            "name": joint.name, "type": joint.type, "parent": joint.parent,
            "child": joint.child, "file": file, "line": line,
            "origin": {k: list(v) for k, v in origin_of(joint.element).items()},
            "axis": list(axis) if (axis := axis_of(joint)) is not None else None,
            "limit": {k: parse_number(v) for k, v in limit.items()}
            if limit is not None else None})
    return document
