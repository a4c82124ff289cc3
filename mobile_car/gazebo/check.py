"""The ``--gazebo`` stage of ``mcar check`` (and the gazebo step of ``mcar ci``): a robot
that passed its check is given to libsdformat, and what it changes joins the check's
diagnostics (see :mod:`.changes`)."""

from __future__ import annotations

from ..check.diagnostics import Diagnostic
from ..errors import GazeboError


def check_in_gazebo(result) -> None:
    """Add what Gazebo changes to a CheckResult, in place: its ``gazebo`` view and
    diagnostics. A robot with errors is not converted (libsdformat would only repeat
    them); the helper failing on this robot is E151; a robot that would make libsdformat
    read a file (an ``<include>``) is E152, and is not given to it. GazeboUnavailable passes
    through."""
    from .changes import gazebo_view
    from .helper import run_helper
    from .includes import RULE, includes, refusal

    if not result.sound or result.loaded is None:
        return
    refused = []
    for element in includes(result.robot.element.getroottree().getroot()):
        file, line, note = result.where(element)
        refused.append(Diagnostic(RULE, file, line, refusal(element) + note))
    if refused:
        result.diagnostics = sorted([*result.diagnostics, *refused], key=Diagnostic.sort_key)
        return
    try:
        report = run_helper(result.loaded.urdf, result.file)
    except GazeboError as error:
        file, line, note = result.where(result.robot.element)
        result.diagnostics = sorted(
            [*result.diagnostics, Diagnostic("E151", file, line, error.message + note)],
            key=Diagnostic.sort_key)
        return
    result.gazebo = gazebo_view(result, report)
    result.diagnostics = sorted(set(result.diagnostics) | set(result.gazebo.diagnostics),
                                key=Diagnostic.sort_key)
