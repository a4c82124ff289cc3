"""Choose the renderer: OpenGL on EGL when a context can be made, else ray casting.

Making an EGL context can fail (no libEGL, no Mesa driver, no access to /dev/dri) and,
on a broken driver, could block forever inside C code where no Python timeout reaches.
So a child process tries first (:class:`GLProbe`), started as early as possible so that it
runs on the other core while the parent imports numpy and expands xacro; the parent waits
for it at most :data:`PROBE_TIMEOUT` seconds and only then makes its own context.

This module imports nothing heavy: the command line can start the probe before numpy.
"""

from __future__ import annotations

import os
import subprocess
import sys

from ..errors import RendererUnavailableError

PROBE_TIMEOUT = 20.0
PROBE_TIMEOUT_ENV = "MCAR_GL_TIMEOUT"
GL_DEBIAN_PACKAGES = "libegl1 libegl-mesa0 libgl1-mesa-dri libgl1"
GL_PIP_PACKAGES = "moderngl glcontext"
RAYCAST_PIP_PACKAGES = "embreex"

_PROBE_CODE = """
import sys
import moderngl
ctx = moderngl.create_context(standalone=True, backend="egl", require=330)
sys.stdout.write(ctx.info["GL_RENDERER"])
"""


def _last_line(text: str) -> str:
    lines = [line.strip() for line in text.strip().splitlines() if line.strip()]
    return lines[-1] if lines else "no error message"


def probe_timeout() -> float:
    """Seconds to wait for an EGL context: MCAR_GL_TIMEOUT, else PROBE_TIMEOUT."""
    from ..settings import env_number

    return env_number(PROBE_TIMEOUT_ENV, PROBE_TIMEOUT, 0.1, 600, "seconds")


# The one OpenGL renderer of this process: a context is made once and reused by every
# session (tests and library users render many times in one process).
_gl_renderer = None


class GLProbe:
    """Tries to make an EGL context in a child process; ``wait()`` says why not, or None.

    Nothing is started when this process already holds a working context.
    """

    def __init__(self, timeout: float | None = None):
        self.timeout = probe_timeout() if timeout is None else timeout
        self._reason: str | None = None
        self._done = _gl_renderer is not None
        self._process = None
        if self._done:
            return
        env = dict(os.environ)
        env.setdefault("EGL_LOG_LEVEL", "fatal")  # Mesa's own chatter is not our message
        try:
            self._process = subprocess.Popen(
                [sys.executable, "-c", _PROBE_CODE], stdin=subprocess.DEVNULL,
                stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env, text=True)
        except OSError as exc:
            self._process = None
            self._done, self._reason = True, f"cannot start a probe process: {exc}"

    def wait(self) -> str | None:
        """None if OpenGL works here; otherwise a one-line reason."""
        if self._done:
            return self._reason
        try:
            _out, err = self._process.communicate(timeout=self.timeout)
        except subprocess.TimeoutExpired:
            self._stop()
            self._reason = f"making an EGL context did not finish within {self.timeout:g} s"
        else:
            if self._process.returncode != 0:
                self._reason = _last_line(err)
        self._done = True
        return self._reason

    def _stop(self) -> None:
        self._process.kill()
        self._process.communicate()

    def cancel(self) -> None:
        """Stop the probe if its answer is no longer needed (nothing left to render, Ctrl-C)."""
        if not self._done and self._process is not None:
            self._stop()
            self._done, self._reason = True, "cancelled"


def _gl_unavailable(reason: str) -> str:
    return (f"OpenGL (EGL) is not available: {reason}. Install the Debian packages "
            f"{GL_DEBIAN_PACKAGES} (and the pip packages {GL_PIP_PACKAGES})")


def _open_gl(probe: GLProbe | None):
    global _gl_renderer
    if _gl_renderer is not None:
        return _gl_renderer
    reason = (probe or GLProbe()).wait()
    if reason is not None:
        raise RendererUnavailableError(_gl_unavailable(reason))
    try:
        from .gl import GLRenderer

        _gl_renderer = GLRenderer()
        return _gl_renderer
    except Exception as exc:  # the driver refused something the probe did not try
        raise RendererUnavailableError(
            _gl_unavailable(f"{type(exc).__name__}: {_last_line(str(exc))}")) from None


def _open_raycast():
    try:
        from .raycast import RaycastRenderer
    except ImportError as exc:
        raise RendererUnavailableError(
            f"the ray-casting renderer needs embreex ({exc}); install it with "
            f"pip install {RAYCAST_PIP_PACKAGES}") from None
    return RaycastRenderer()


def open_renderer(choice: str, probe: GLProbe | None = None):
    """The renderer for ``choice`` (auto, gl, raycast) and notes for the user.

    ``auto`` falls back to ray casting when OpenGL is unavailable, with a note saying why;
    RendererUnavailableError (exit 2) names what to install when nothing can run.
    """
    if choice == "raycast":
        return _open_raycast(), []
    if choice == "gl":
        return _open_gl(probe), []
    try:
        return _open_gl(probe), []
    except RendererUnavailableError as gl_error:
        try:
            renderer = _open_raycast()
        except RendererUnavailableError as raycast_error:
            raise RendererUnavailableError(
                f"no renderer can run here. {gl_error.message}; or {raycast_error.message}"
            ) from None
        return renderer, [f"{gl_error.message}; using the ray-casting fallback instead"]
