"""New description packages and parts, laid out the way the mobile car is (the seed's method).

``create_package`` writes a package that ``mcar ci`` passes at once, having simulated it:
package.xml, ``urdf/define.xacro`` (colours, inertia and friction macros),
``urdf/config.xacro`` (dimensions, each with its "UNIT LO..HI; SOURCE: meaning" comment,
overridable by ``--set``, and checks that they fit together), the complete robot
``urdf/NAME.urdf.xacro``, a vehicle of the drive kind asked for (differential: two wheels
and a castor, the seed's car; skid-steer: four driven wheels; ackermann: steered front
wheels, driven rear ones, each kind one that ``mcar sim`` finds from its joints), its parts
in ``urdf/PART/`` (wheel, castor, steering: a macro taking a name, and reflect where it
has a side, with a test file that uses it), ``meshes/``, a .gitignore, a GitHub workflow
and a pre-commit config that run mcar on the package; and, as the bundled package has them,
CMakeLists.txt (catkin or ament) and the ROS 1 viewer (``launch/display.launch``,
``rviz/urdf.rviz`` and the two scripts the launch runs). ``add_part`` adds a part folder with
a documented macro (name and reflect, so that it can be used on both sides) and a test
file that builds a left and a right one alone. Neither overwrites anything: if
one file it would write exists, nothing is written.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from ..errors import UsageError
from ..names import NAME_MAX
from .placing import place, refuse_present, require_makeable, short

TEMPLATES = Path(__file__).resolve().parent / "templates"
# template -> where it goes in the package ({name}: the package's name)
PACKAGE_FILES = {
    "package/package.xml": "package.xml",
    "package/gitignore": ".gitignore",
    "package/pre-commit-config.yaml": ".pre-commit-config.yaml",
    "package/mcar-workflow.yml": ".github/workflows/mcar.yml",
    "package/mcar.yaml": "mcar.yaml",
    "package/urdf/define.xacro": "urdf/define.xacro",
    "package/urdf/config.xacro": "urdf/config.xacro",
}
# The drive kinds `mcar init --drive` makes (the first the default: the seed's car), each
# a robot file and config.xacro's own section (templates/drive/KIND/), and the parts it
# is built of (templates/drive/parts/PART.xacro and test_PART.urdf.xacro, in urdf/PART/).
DRIVES = {"differential": ("wheel", "castor"),
          "skid-steer": ("wheel",),
          "ackermann": ("wheel", "steering")}
# What base_link sits on, for the comments of config.xacro.
_AXLE = {"differential": "on the axle midpoint", "skid-steer": "midway between the axles",
         "ackermann": "midway between the axles"}
# The bundled package's own, its name and robot file replaced by the new package's: one
# copy, which tests/ros/ builds (catkin, ament) and launches in both.
BUNDLED_FILES = ("CMakeLists.txt", "launch/display.launch", "rviz/urdf.rviz",
                 "scripts/robot_description", "scripts/joint_sliders")
EXECUTABLES = frozenset({"scripts/robot_description", "scripts/joint_sliders"})
GITKEEP = "meshes/.gitkeep"
# template -> where it goes in the part's folder, urdf/PART/
PART_FILES = {"part/part.xacro": "{part}.xacro",
              "part/test_part.urdf.xacro": "test_{part}.urdf.xacro"}
# ROS package names (REP 144), and names a macro and its links can take.
_NAME_RE = re.compile(r"[a-z][a-z0-9_]*")


def create_package(path: Path, name: str | None = None,
                   requirement: str | None = None, drive: str = "differential") -> list[Path]:
    """Write a new description package at ``path`` whose robot has the ``drive`` kind
    (:data:`DRIVES`); returns the files written. Nothing is written unless all of it can
    be: see :mod:`.placing`. ``requirement``: what the GitHub workflow pip-installs mcar
    as (default: :func:`.install_source.install_source`)."""
    from .install_source import install_source

    if drive not in DRIVES:
        raise UsageError(f"--drive {short(drive)}: the drive kinds are {', '.join(DRIVES)}")
    name = name or path.resolve().name
    _require_name(name, "package", "--name")
    kind = f"drive/{drive}"
    tokens = {"NAME": name, "DRIVE": drive, "AXLE": _AXLE[drive],
              "MCAR_REQUIREMENT": requirement or install_source().requirement,
              "DRIVE_PROPERTIES": _filled(f"{kind}/properties.xacro", {}),
              "DRIVE_CHECKS": _filled(f"{kind}/checks.xacro", {})}
    files = {destination.format(name=name): _filled(template, tokens)
             for template, destination in PACKAGE_FILES.items()}
    files[f"urdf/{name}.urdf.xacro"] = _filled(f"{kind}/robot.urdf.xacro", tokens)
    for part in DRIVES[drive]:
        files[f"urdf/{part}/{part}.xacro"] = _filled(f"drive/parts/{part}.xacro", tokens)
        files[f"urdf/{part}/test_{part}.urdf.xacro"] = _filled(
            f"drive/parts/test_{part}.urdf.xacro", tokens)
    files.update(_bundled_files(name))
    files[GITKEEP] = ""
    require_makeable(path, list(files), _length_hint(name, "package", "--name", files))
    return place(path, files, optional=frozenset({GITKEEP}), executable=EXECUTABLES)


def add_part(root: Path, package: str, part: str) -> list[Path]:
    """Add ``urdf/PART/PART.xacro`` and its test file to the package at ``root``."""
    from ..check.urdf_vocabulary import EXTENSIONS, SPECS
    from .part_names import refuse_bad_part_name

    _require_name(part, "part", "NAME")
    if part in SPECS or part in EXTENSIONS:
        raise UsageError(f"a part cannot be called '{part}': a URDF element has that name, "
                         "so its macro could not be told from it")
    files = {destination.format(part=part): _filled(template, {"NAME": package, "PART": part})
             for template, destination in PART_FILES.items()}
    folder = root / "urdf" / part
    require_makeable(folder, list(files), _length_hint(part, "part", "NAME", files))
    refuse_present(folder, files)  # the part exists: that, not its names, is the news
    refuse_bad_part_name(root, part)
    return place(folder, files)


def _require_name(name: str, what: str, option: str) -> None:
    if not _NAME_RE.fullmatch(name):
        raise UsageError(f"'{short(name)}' is not a valid {what} name: lowercase letters, "
                         f"digits and underscores, starting with a letter (ROS REP 144); give "
                         f"one with {option}")


def _length_hint(name: str, what: str, option: str, files: dict[str, str]) -> str:
    """The end of a too-long-name message: how long the name may be."""
    longest = max(len(os.fsencode(part)) for rel in files for part in rel.split("/"))
    room = NAME_MAX - (longest - len(os.fsencode(name)))
    return f"give a {what} name of at most {room} characters ({option})"


def _bundled_files(name: str) -> dict[str, str]:
    from ..packages.bundled import PACKAGE_NAME, description_dir

    swaps = [("urdf/mobile_robot.xacro", f"urdf/{name}.urdf.xacro"), (PACKAGE_NAME, name),
             # RViz's camera 2.5 robot lengths away: the new robot is 30 cm, the car 20 cm
             ("      Distance: 0.5\n", "      Distance: 0.75\n")]
    files = {}
    for rel in BUNDLED_FILES:
        text = (description_dir() / rel).read_text(encoding="utf-8")
        for old, new in swaps:
            text = text.replace(old, new)
        files[rel] = text
    return files


def _filled(template: str, tokens: dict[str, str]) -> str:
    text = (TEMPLATES / template).read_text(encoding="utf-8")
    for token, value in tokens.items():
        text = text.replace(f"@{token}@", value)
    return text
