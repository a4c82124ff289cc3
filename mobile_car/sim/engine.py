"""Import MuJoCo the one way mcar uses it: headless, rendering (if asked) through EGL."""

from __future__ import annotations

import os
from collections import deque

from ..errors import McarError

# MuJoCo's own warnings ("Nan, Inf or huge value in QACC ..."), the latest kept here: by
# default MuJoCo appends each to MUJOCO_LOG.TXT in the working folder, which is the user's
# package (a file a `git add -A` then commits) and prints it; mcar judges the run by what the
# robot did, and its scenarios name an unstable one.
WARNINGS: deque[str] = deque(maxlen=100)


class EngineUnavailableError(McarError):
    """MuJoCo cannot be imported on this machine (exit 2: an environment problem)."""


def mujoco():
    """The ``mujoco`` module; MUJOCO_GL must be set before its first import, or it looks
    for a display (GLFW) when asked to render."""
    os.environ.setdefault("MUJOCO_GL", "egl")
    try:
        import mujoco as module
    except ImportError as error:  # pragma: no cover - a broken install
        raise EngineUnavailableError(f"cannot import MuJoCo ({error}); reinstall mcar, "
                                     "which depends on the mujoco package") from None
    module.set_mju_user_warning(WARNINGS.append)
    return module
