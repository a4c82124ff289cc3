"""How a new part is used in the robot: the include line and a macro call, to paste into
the package's robot file (``urdf/PACKAGE.urdf.xacro``, which ``mcar init`` writes), so
that a part made by ``mcar new part`` is one paste away from the robot it was made for."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True)
class PartUsage:
    robot: Path | None  # the package's robot file, when it has the one init writes
    include: str        # after the robot file's other includes
    call: list[str]     # before its </robot>: one use of the part, on base_link


def part_usage(root: Path, package: str, part: str) -> PartUsage:
    """The lines that put ``part`` into the robot of the package at ``root``."""
    robot = root / "urdf" / f"{package}.urdf.xacro"
    # name and reflect as the macro's documentation gives them for a left-hand use; the
    # origin a place above base_link that the user moves to where the part goes.
    call = [f'<xacro:{part} name="left" reflect="1" parent="base_link">',
            '  <origin xyz="0 0 0.1" rpy="0 0 0"/>',
            f"</xacro:{part}>"]
    return PartUsage(robot if robot.is_file() else None,
                     f'<xacro:include filename="$(find {package})/urdf/{part}/{part}.xacro"/>',
                     call)
