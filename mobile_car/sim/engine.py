"""Import MuJoCo the one way mcar uses it: headless, rendering (if asked) through EGL."""

from __future__ import annotations

import os

from ..errors import McarError


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
    return module
