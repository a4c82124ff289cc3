"""Known bugs of libsdformat releases that change its verdict on a URDF, so that an error a
release gives wrongly says so (``mcar check --gazebo``, docs/gazebo.md "Which
libsdformat").

The helper reports the version it was built with (sdformat 12 has no call that tells it at
run time). A bug is matched by release and by the error codes it returns, never by what
the robot is: a matching error is still an error, since that release is what Gazebo runs.
It is named only where the URDF holds what the bug needs (``needs``, a path below
``<robot>``): the same codes also follow from an empty model (ABB's and KUKA's arms
declare no mass: Gazebo leaves out every link, and the frame graph has nothing to hang on).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from .wire import GazeboReport, Message


@dataclass(frozen=True)
class KnownBug:
    fixed_in: tuple[int, int, int]
    codes: frozenset[str]  # the helper's "where" of the errors it gives ("error code 19")
    what: str
    needs: str  # an ElementPath below <robot> that must find something for the bug to bite


KNOWN_BUGS = (
    # sdformat pull request 1089 ("Fix URDF fixed joint reduction of SDF joints"); upstream's
    # fixed_joint_reduction_joint_frame_extension.urdf gives 11 such errors in 12.3.0.
    KnownBug((12, 6, 0), frozenset(f"error code {code}" for code in (19, 20, 21, 22, 24, 25,
                                                                     27)),
             "an SDF <joint> in a <gazebo> block whose parent or child is lumped away by a "
             "fixed joint keeps the lumped link's name", "gazebo//joint"),
)

_VERSION = re.compile(r"(\d+)\.(\d+)\.(\d+)")


def release(version: str) -> tuple[int, int, int] | None:
    """(major, minor, patch) of a version such as "12.3.0" or "12.3.0~pre1"; None if it
    does not start with one."""
    match = _VERSION.match(version)
    return tuple(int(part) for part in match.groups()) if match else None


def known_bug(report: GazeboReport, message: Message, robot) -> str:
    """"" or the words that say this error of ``report`` on the URDF whose ``<robot>`` is
    ``robot`` may be a known bug of its libsdformat, fixed in a later release."""
    found = release(report.sdformat)
    if found is None:
        return ""
    for bug in KNOWN_BUGS:
        if found < bug.fixed_in and message.where in bug.codes \
                and robot.find(bug.needs) is not None:
            fixed = ".".join(map(str, bug.fixed_in))
            return (f"; maybe a bug of libsdformat before {fixed}: {bug.what} "
                    "(docs/gazebo.md)")
    return ""
