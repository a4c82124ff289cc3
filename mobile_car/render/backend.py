"""Choose the renderer: OpenGL on EGL when a context can be made, else ray casting.

Either draws in a drawing process (:mod:`.drawing`), where a draw that takes minutes can
be stopped at once. Making an EGL context can fail (no libEGL, no Mesa driver, no access to
/dev/dri) and, on a broken driver, could block forever inside C code; so the GL drawing
process is started as early as possible (:class:`GLProbe`), to make its context on the
other core while the parent imports numpy and expands xacro, and the parent waits for it
at most :data:`PROBE_TIMEOUT` seconds. Once it answers, the same process draws.

This module imports nothing heavy: the command line can start the probe before numpy.
"""

from __future__ import annotations

from ..errors import RendererUnavailableError

PROBE_TIMEOUT = 20.0
PROBE_TIMEOUT_ENV = "MCAR_GL_TIMEOUT"
# Importing trimesh and embreex in the ray-casting process: seconds, minutes at most.
RAYCAST_START_TIMEOUT = 120.0
GL_DEBIAN_PACKAGES = "libegl1 libegl-mesa0 libgl1-mesa-dri libgl1"
GL_PIP_PACKAGES = "moderngl glcontext"
RAYCAST_PIP_PACKAGES = "embreex"


def probe_timeout() -> float:
    """Seconds to wait for an EGL context: MCAR_GL_TIMEOUT, else PROBE_TIMEOUT."""
    from ..settings import env_number

    return env_number(PROBE_TIMEOUT_ENV, PROBE_TIMEOUT, 0.1, 600, "seconds")


# The renderers of this process, by kind: their drawing processes serve every session
# (tests and library users render many times in one process).
_renderers: dict = {}


class GLProbe:
    """Starts the GL drawing process; ``wait()`` says why it cannot draw, or None.

    Nothing is started when this process already has a GL renderer. A probe whose
    process is not taken by a renderer (:meth:`take`) is ended by :meth:`cancel`.
    """

    mode = "gl"

    def __init__(self, timeout: float | None = None):
        self.timeout = self._default_timeout() if timeout is None else timeout
        self.answer: dict | None = None  # the drawing process's first word
        self._reason: str | None = None
        self._done = self.mode in _renderers
        self._process = None
        if self._done:
            return
        from .drawing import DrawingProcess

        self.start_error: OSError | None = None
        try:
            self._process = DrawingProcess(self.mode)
        except OSError as exc:
            self.start_error = exc
            self._done, self._reason = True, f"cannot start a probe process: {exc}"

    @staticmethod
    def _default_timeout() -> float:
        return probe_timeout()

    def _timed_out(self) -> str:
        return f"making an EGL context did not finish within {self.timeout:g} s"

    def wait(self) -> str | None:
        """None if the renderer works here; otherwise a one-line reason."""
        if self._done:
            return self._reason
        from .drawing import DrawingFailed

        try:
            self.answer = self._process.first_answer(self.timeout)
        except TimeoutError:
            self._reason = self._timed_out()
        except DrawingFailed as exc:
            self._reason = str(exc)
        else:
            if not self.answer["ok"]:
                self._reason = self.answer.get("error") or "no error message"
        if self._reason is not None:
            self._process = None  # (killed)
        self._done = True
        return self._reason

    def take(self):
        """The drawing process that answered, for the renderer that draws with it."""
        process, self._process = self._process, None
        return process

    def cancel(self) -> None:
        """Stop the probe if its answer is no longer needed (nothing left to render, Ctrl-C)."""
        if self._process is not None:
            self._process.kill()
            self._process = None
        if not self._done:
            self._done, self._reason = True, "cancelled"


class RaycastProbe(GLProbe):
    """Starts the ray-casting drawing process early, as :class:`GLProbe` does for OpenGL:
    it imports trimesh and embreex on the other core while mcar loads the robot."""

    mode = "raycast"

    @staticmethod
    def _default_timeout() -> float:
        return RAYCAST_START_TIMEOUT

    def _timed_out(self) -> str:
        return f"it did not start within {self.timeout:g} s"


def start_probe(choice: str) -> GLProbe:
    """The drawing process ``choice`` (auto, gl, raycast) will most likely draw with, started
    now; give it to :func:`open_renderer`."""
    return RaycastProbe() if choice == "raycast" else GLProbe()


def _gl_unavailable(reason: str) -> str:
    return (f"OpenGL (EGL) is not available: {reason}. Install the Debian packages "
            f"{GL_DEBIAN_PACKAGES} (and the pip packages {GL_PIP_PACKAGES})")


def _open_gl(probe: GLProbe | None):
    if "gl" in _renderers:
        return _renderers["gl"]
    if probe is None or probe.mode != "gl":
        probe = GLProbe()
    reason = probe.wait()
    if reason is not None:
        raise RendererUnavailableError(_gl_unavailable(reason))
    from .drawing import RemoteRenderer

    _renderers["gl"] = RemoteRenderer(probe.take(), probe.timeout)
    return _renderers["gl"]


def _open_raycast(probe: GLProbe | None = None):
    """The ray-casting renderer and notes for the user: in its drawing process, or, where
    no process can be started (a Python this user may run but not start again, a sandbox
    that forbids it), in this one, where a draw cannot be cut short by a signal."""
    if "raycast" in _renderers:
        return _renderers["raycast"], []
    if probe is None or probe.mode != "raycast":
        probe = RaycastProbe()
    reason = probe.wait()
    if reason is None:
        from .drawing import RemoteRenderer

        _renderers["raycast"] = RemoteRenderer(probe.take(), probe.timeout)
        return _renderers["raycast"], []
    if getattr(probe, "start_error", None) is not None:
        try:
            from .raycast import RaycastRenderer
        except ImportError as exc:
            reason = f"{reason}; and in this process: {exc}"
        else:
            _renderers["raycast"] = RaycastRenderer()
            return _renderers["raycast"], [
                f"the drawing process could not be started ({probe.start_error}); drawing "
                "in this process, where Ctrl-C waits for the picture being drawn"]
    if probe.answer is not None and probe.answer.get("kind") == "import":
        raise RendererUnavailableError(
            f"the ray-casting renderer needs embreex ({probe.answer.get('import_error')}); "
            f"install it with pip install {RAYCAST_PIP_PACKAGES}")
    raise RendererUnavailableError(f"the ray-casting renderer cannot run: {reason}")


def open_renderer(choice: str, probe: GLProbe | None = None):
    """The renderer for ``choice`` (auto, gl, raycast) and notes for the user.

    ``auto`` falls back to ray casting when OpenGL is unavailable, with a note saying why;
    RendererUnavailableError (exit 2) names what to install when nothing can run.
    """
    if choice == "raycast":
        return _open_raycast(probe)
    if choice == "gl":
        return _open_gl(probe), []
    try:
        return _open_gl(probe), []
    except RendererUnavailableError as gl_error:
        try:
            renderer, notes = _open_raycast()
        except RendererUnavailableError as raycast_error:
            raise RendererUnavailableError(
                f"no renderer can run here. {gl_error.message}; or {raycast_error.message}"
            ) from None
        return renderer, [f"{gl_error.message}; using the ray-casting fallback instead",
                          *notes]
