"""The package's own ROS configuration compared with the robot: the drive controller's
geometry and wheel names (its control package's YAML), Nav2's footprint and radius (the
``_navigation`` sibling's, or the description package's, ``config/`` or ``params/``),
and laser_filters' angular bounds against the sectors the body blocks. A mismatch is a
warning at the YAML line that says it (rules W510-W514), for ``mcar check`` and
``mcar specs``.

The files are found by sim's one search (:func:`~mobile_car.sim.control_config.
control_packages`: links out of the repository refused, at most MAX_FILES a package,
the bounded YAML loader) and only parsed when they hold a word a reader needs; a package
without such YAML costs ``mcar check`` a few directory lookups, and MuJoCo is imported
only when there is something to compare (:func:`check_package`).

What is compared, and how: :mod:`.stack_compare`.
"""

from __future__ import annotations

from pathlib import Path

from ..check.diagnostics import Diagnostic

NAVIGATION_SUFFIXES = (None, "_navigation")  # None: the description package itself
NAVIGATION_FOLDERS = ("config", "params")
# the words a file must hold to be parsed at all, by reader
CONTROLLER_WORDS = ("wheel", "kinematics")
NAV2_WORD = "costmap"
FILTER_WORD = "AngularBoundsFilter"


class Found:
    """The package's YAML that says something about the robot: mappings (key -> (key
    node, value node)) by the file they are in."""

    def __init__(self):
        self.controllers: list[tuple[Path, dict]] = []
        self.nav2: list[tuple[Path, dict]] = []
        self.filters: list[tuple[Path, dict]] = []
        self.read: list[Path] = []
        # where a sibling package without YAML now would put its package.xml: a check's
        # record depends on their staying absent (a control package added beside it)
        self.absent: list[Path] = []
        self.problems: list[str] = []

    def __bool__(self) -> bool:
        return bool(self.controllers or self.nav2 or self.filters)


def find_package_yaml(loaded) -> Found:
    """The controller, Nav2 and laser_filters mappings of the robot's packages."""
    from ..sim.control_config import control_packages, description_packages, yaml_mappings

    found = Found()
    launches: list[Path] = []  # (what decided which variant's controllers are compared)
    packages = description_packages(loaded)  # (searched for once: the URDF's whole text)
    controls = [p for files in control_packages(loaded, found.problems, consulted=launches,
                                                packages=packages)
                for p in files]
    navigation = [p for files in control_packages(loaded, found.problems,
                                                  NAVIGATION_SUFFIXES, NAVIGATION_FOLDERS,
                                                  named_only=False, packages=packages)
                  for p in files]
    yamls = list(dict.fromkeys(controls + navigation))
    found.read = list(dict.fromkeys(yamls + launches))  # (an edit may make one relevant)
    found.absent = _absent_siblings(loaded)
    for path in yamls:
        text = _text(path)
        if text is None:
            continue
        wanted = []
        if path in controls and any(w in text for w in CONTROLLER_WORDS):
            wanted.append(found.controllers)
        if NAV2_WORD in text and ("footprint" in text or "robot_radius" in text):
            wanted.append(found.nav2)
        if FILTER_WORD in text:
            wanted.append(found.filters)
        if not wanted:
            continue
        mappings = yaml_mappings(path, found.problems)
        for bucket in wanted:
            bucket += [(path, keys) for keys in mappings]
    return found


def _absent_siblings(loaded) -> list[Path]:
    """``X_control/package.xml``... beside the robot's own ``X_description`` package that
    do not exist: where a control or navigation package added later would appear."""
    from ..packages.search import enclosing_package
    from ..sim.control_config import CONTROL_SUFFIXES, SUFFIXES

    own = enclosing_package(loaded.input.path) if loaded.input.path is not None else None
    if own is None or not own[0].endswith(SUFFIXES):
        return []
    stem = next(own[0][: -len(s)] for s in SUFFIXES if own[0].endswith(s))
    candidates = [own[1].parent / (stem + suffix) / "package.xml"
                  for suffix in CONTROL_SUFFIXES + NAVIGATION_SUFFIXES[1:]]
    return [path for path in candidates if not path.exists()]


def _text(path: Path) -> str | None:
    from ..errors import McarError
    from ..load.bounded import read_input

    try:
        return read_input(path, str(path)).decode("utf-8", "replace")
    except (OSError, McarError):
        return None  # (yaml_mappings says why, if it is ever parsed)


def check_package(checked) -> tuple[list[Diagnostic], Found]:
    """``mcar check``'s comparison: (W510-W513 diagnostics, what was found: the files
    the check's record depends on). Nothing is built, and MuJoCo not imported, for a
    robot whose packages hold no such YAML, nor for one check already failed."""
    loaded = checked.loaded
    if loaded is None or not checked.sound or checked.errors:
        return [], Found()
    found = find_package_yaml(loaded)
    if not found:
        return [], found
    sim = resting_model(checked)
    if sim is None:
        return [], found
    from .stack_compare import compare

    sections = _body_figures(sim)
    diagnostics, _notes = compare(found, checked, sim, sections)
    return diagnostics, found


def compare_package(checked, sim, sections) -> tuple[list[Diagnostic], list[str], list[Path]]:
    """``mcar specs``' comparison, with the sections computed so far."""
    if checked.loaded is None:
        return [], [], []
    from .stack_compare import compare

    found = find_package_yaml(checked.loaded)
    diagnostics, notes = compare(found, checked, sim, sections) if found else ([], [])
    return diagnostics, notes + found.problems, found.read


def resting_model(checked):
    """sim's model of the robot (its drive as the package declares it), None where
    MuJoCo cannot make one (sim reports why)."""
    from ..errors import McarError
    from ..sim.mecanum import yaml_declarations
    from ..sim.model import build_model
    from ..sim.prepare import declarations

    loaded = checked.loaded
    try:
        declared, _unread, _read = declarations(checked)
        mecanum, _ = yaml_declarations(loaded)
        sim = build_model(loaded.urdf, checked.file, loaded.base, loaded.search,
                          declared=declared, mecanum=mecanum)
    except (McarError, ValueError):
        return None
    sim.control = package_control(checked, sim)
    return sim


def package_control(checked, sim):
    """The ControlConfig (``wheel_separation_multiplier``) of the package's controller
    driving sim's wheels: sim's own where it read it (a skid-steer robot's), else read
    now (None without one, or without a drive)."""
    if getattr(sim, "control", None) is not None:
        return sim.control
    drive = getattr(sim, "drive", None)
    if drive is None or checked.loaded is None:
        return None
    from ..sim.control_config import find_control_config

    return find_control_config(checked.loaded, [w.joint for w in drive.driven])[0]


def _body_figures(sim) -> list:
    """The body figures W513 needs: specs' own outline and radius."""
    from .figures import Figure, Section
    from .outline import footprint, radii

    points = footprint(sim)
    outer, _inner = radii(points)
    return [Section("body", [Figure("body.footprint", "footprint", points, "m", ""),
                             Figure("body.radius.circumscribed", "radius", outer, "m", "")])]
