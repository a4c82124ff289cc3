"""Find the robot files of a description package: what ``mcar build`` builds by default.

A robot file is a ``.xacro`` whose root is ``<robot name="...">``. Macro libraries
(``define.xacro``, ``wheel/wheel.xacro``) have a nameless ``<robot>`` root: they are
included, never built alone. Deciding by content, not by file name, lets another team's
package work with no configuration.
"""

from __future__ import annotations

from pathlib import Path


def is_robot_file(path: Path) -> bool:
    """True if the file's root element is a ``<robot>`` with a ``name`` attribute."""
    from lxml import etree  # only folder builds need it: keep one-file builds light

    try:
        for _event, element in etree.iterparse(str(path), events=("start",),
                                               resolve_entities=False, no_network=True):
            return etree.QName(element).localname == "robot" and bool(element.get("name"))
    except (etree.XMLSyntaxError, OSError):
        # A broken robot file is still a robot file: building it reports the error.
        try:
            head = path.read_text(encoding="utf-8", errors="replace")[:4096]
        except OSError:
            return False
        return "<robot" in head and "name=" in head.split("<robot", 1)[1].split(">", 1)[0]
    return False


def source_base(root: Path) -> Path:
    """The folder holding a package's robot files: its ``urdf/``, or the folder itself."""
    return root / "urdf" if (root / "urdf").is_dir() else root


def require_robot_files(root: Path) -> list[Path]:
    """robot_files(root), or a UsageError naming the folder when there is none."""
    files = robot_files(root)
    if not files:
        from .build import display_path
        from .errors import UsageError

        raise UsageError("no robot files (.xacro with <robot name=...>) in this folder",
                         file=display_path(source_base(root)))
    return files


def robot_files(root: Path) -> list[Path]:
    """Every robot xacro below ``root`` (its ``urdf/`` folder if it has one), sorted."""
    return sorted(p for p in source_base(root).rglob("*.xacro")
                  if p.is_file() and is_robot_file(p))


def output_name(source: Path, base: Path) -> Path:
    """Where a built file goes, relative to the output folder: ``wheel/test_wheel.urdf``."""
    relative = source.relative_to(base)
    name = relative.name[: -len(".xacro")] if relative.name.endswith(".xacro") else relative.name
    if not name.endswith(".urdf"):
        name += ".urdf"
    return relative.with_name(name)


