"""How a new part is used in the robot: the include line and a macro call, to paste into
the package's robot file (``urdf/PACKAGE.urdf.xacro``, which ``mcar init`` writes), so
that a part made by ``mcar new part`` is one paste away from the robot it was made for;
or, with ``--into ROBOT``, pasted by mcar (:func:`with_part`)."""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from ..errors import InputError, UsageError
from ..load.inputs import display_path


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


_INCLUDE = re.compile(r"<xacro:include\b[^>]*>")
_ROBOT_OPEN = re.compile(r"<robot\b[^>]*>")
_ROBOT_CLOSE = re.compile(r"</robot\s*>")


def with_part(robot: Path, usage: PartUsage) -> str:
    """The text of ``robot`` with ``usage`` pasted in as a person would: the include after
    its last include (or its <robot> tag), the call before its </robot>. Raises before
    anything is written, so that ``new part --into`` refuses a robot file it cannot change
    before it writes the part."""
    from ..load.bounded import read_input

    shown = display_path(robot)
    try:
        text = read_input(robot, shown).decode("utf-8")
    except OSError as exc:
        raise InputError(f"cannot read: {exc.strerror or exc}", file=shown) from None
    except UnicodeDecodeError:
        raise InputError("not UTF-8 text", file=shown) from None
    if usage.include in text:
        raise UsageError(f"it includes {usage.include} already", file=shown)
    closes = list(_ROBOT_CLOSE.finditer(text))
    anchor = (list(_INCLUDE.finditer(text)) or list(_ROBOT_OPEN.finditer(text)))[-1:]
    if not closes or not anchor or anchor[0].end() > closes[-1].start():
        raise InputError("no <robot> ... </robot> to add the part into", file=shown)
    end, after = closes[-1].start(), anchor[0].end()
    call = "".join(f"  {line}\n" for line in usage.call)
    return f"{text[:after]}\n  {usage.include}{text[after:end]}{call}{text[end:]}"
