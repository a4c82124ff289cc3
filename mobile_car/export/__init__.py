"""``mcar export``: a robot as a self-contained folder another simulator loads (MuJoCo's
MJCF, OpenUSD, Gazebo's SDF, or URDF with its meshes), proven by loading it back in that
simulator's own engine (docs/exports.md).

Imports nothing heavy: each format's module imports its engine when it runs.
"""

from __future__ import annotations

from ..errors import EXIT_PROBLEMS, McarError

FORMATS = ("mjcf", "usd", "urdf", "sdf")


class ExportError(McarError):
    """The robot cannot be exported as asked, or its export does not load back as the
    description says (exit 1: the description's fault, or the target's limits)."""

    exit_code = EXIT_PROBLEMS
