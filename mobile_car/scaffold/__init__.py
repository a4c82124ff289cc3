"""New description packages and parts, laid out the way the mobile car is (the seed's method).

``create_package`` writes a package that ``mcar ci`` passes at once: package.xml and
CMakeLists.txt, ``urdf/define.xacro`` (colours and inertia macros), ``urdf/config.xacro``
(dimensions, each with its "UNIT LO..HI; SOURCE: meaning" comment, overridable by ``--set``),
the complete robot ``urdf/NAME.urdf.xacro``, ``meshes/``, a .gitignore, a GitHub workflow
and a pre-commit config that run mcar on the package. ``add_part`` adds a part folder with
a documented macro and a test file that builds it alone. Neither overwrites anything: if
one file it would write exists, nothing is written.
"""

from __future__ import annotations

import re
from pathlib import Path

from ..errors import UsageError

TEMPLATES = Path(__file__).resolve().parent / "templates"
# template -> where it goes in the package ({name}: the package's name)
PACKAGE_FILES = {
    "package/package.xml": "package.xml",
    "package/CMakeLists.txt": "CMakeLists.txt",
    "package/gitignore": ".gitignore",
    "package/pre-commit-config.yaml": ".pre-commit-config.yaml",
    "package/mcar-workflow.yml": ".github/workflows/mcar.yml",
    "package/urdf/define.xacro": "urdf/define.xacro",
    "package/urdf/config.xacro": "urdf/config.xacro",
    "package/urdf/robot.urdf.xacro": "urdf/{name}.urdf.xacro",
}
PART_FILES = {"part/part.xacro": "urdf/{part}/{part}.xacro",
              "part/test_part.urdf.xacro": "urdf/{part}/test_{part}.urdf.xacro"}
# ROS package names (REP 144), and names a macro and its links can take.
_NAME_RE = re.compile(r"[a-z][a-z0-9_]*")


def create_package(path: Path, name: str | None = None) -> list[Path]:
    """Write a new description package at ``path``; returns the files written."""
    name = name or path.resolve().name
    _require_name(name, "package", "--name")
    written = _write(path, PACKAGE_FILES, {"NAME": name}, {"name": name})
    meshes = path / "meshes"
    meshes.mkdir(exist_ok=True)
    (meshes / ".gitkeep").touch()
    return [*written, meshes / ".gitkeep"]


def add_part(root: Path, package: str, part: str) -> list[Path]:
    """Add ``urdf/PART/PART.xacro`` and its test file to the package at ``root``."""
    from ..check.urdf_vocabulary import EXTENSIONS, SPECS

    _require_name(part, "part", "NAME")
    if part in SPECS or part in EXTENSIONS:
        raise UsageError(f"a part cannot be called '{part}': a URDF element has that name, "
                         "so its macro could not be told from it")
    return _write(root, PART_FILES, {"NAME": package, "PART": part}, {"part": part})


def _require_name(name: str, what: str, option: str) -> None:
    if not _NAME_RE.fullmatch(name):
        raise UsageError(f"'{name}' is not a valid {what} name: lowercase letters, digits and "
                         f"underscores, starting with a letter (ROS REP 144); give one with "
                         f"{option}")


def _write(root: Path, files: dict[str, str], tokens: dict[str, str],
           names: dict[str, str]) -> list[Path]:
    from ..atomic import atomic_write

    targets = {template: root / destination.format(**names)
               for template, destination in files.items()}
    present = [target for target in targets.values() if target.exists()]
    if present:
        raise UsageError("will not overwrite " + ", ".join(str(p) for p in present))
    for template, target in targets.items():
        text = (TEMPLATES / template).read_text(encoding="utf-8")
        for token, value in tokens.items():
            text = text.replace(f"@{token}@", value)
        atomic_write(target, text)
    return list(targets.values())
