"""The exceptions the library raises, and the exit code each stands for.

Every error knows the file (and line, where known) it is about, so the command line can
print it as one ``FILE:LINE: message`` line. Exit codes: 1 means the input has problems,
2 means the command could not run (usage, I/O, environment).
"""

from __future__ import annotations

EXIT_OK = 0
EXIT_PROBLEMS = 1
EXIT_USAGE = 2


class McarError(Exception):
    """Base of every error mcar reports; ``exit_code`` says how the command ends."""

    exit_code = EXIT_USAGE

    def __init__(self, message: str, file: str | None = None, line: int | None = None,
                 details: list[str] | None = None):
        super().__init__(message)
        self.message = message
        self.file = file
        self.line = line
        self.details = list(details or [])

    def location(self) -> str:
        """``FILE:LINE``, the file's name escaped (see mobile_car.names: names are data)."""
        if self.file is None:
            return ""
        from .names import shown

        return f"{shown(self.file)}:{self.line}" if self.line else shown(self.file)

    def __str__(self) -> str:
        from .names import shown

        where = self.location()
        return f"{where}: {shown(self.message)}" if where else shown(self.message)


class UsageError(McarError):
    """The command was called wrongly (unknown argument, bad option value)."""


class InputError(McarError):
    """An input or output file cannot be read or written (missing, a directory, no permission)."""


class PackageNotFoundError(McarError):
    """``$(find PKG)`` or ``package://PKG`` names a package that is nowhere on the search path."""


class BuildError(McarError):
    """xacro could not expand the input; ``details`` holds the macro and include stack."""

    exit_code = EXIT_PROBLEMS


class RenderError(McarError):
    """A URDF cannot be drawn: broken XML, a missing or unreadable mesh, a bad joint tree."""

    exit_code = EXIT_PROBLEMS


class RendererUnavailableError(McarError):
    """Neither OpenGL (EGL) nor the ray-casting fallback can run on this machine."""


class GazeboUnavailable(McarError):
    """The Gazebo helper (mcar-sdformat, linked against libsdformat) is not installed, or
    is not one this mcar can talk to: the message says how to build it."""


class GazeboError(McarError):
    """libsdformat (through the Gazebo helper) could not make a model of the robot, or the
    helper failed on it: ran out of time or memory, crashed, or answered garbage."""

    exit_code = EXIT_PROBLEMS


class CheckFailed(McarError):
    """A robot that ``mcar check`` rejects was given to a command that uses it (render):
    its diagnostics say why, exactly as ``mcar check`` prints them."""

    exit_code = EXIT_PROBLEMS

    def __init__(self, file: str, diagnostics: list):
        super().__init__("the robot does not pass mcar check", file=file)
        self.diagnostics = list(diagnostics)


def combine_exit_codes(codes) -> int:
    """The exit code of a run over many inputs: the worst of theirs (2 > 1 > 0)."""
    return max(codes, default=EXIT_OK)


class Terminated(BaseException):
    """SIGTERM or SIGHUP arrived: unwound like Ctrl-C (a BaseException, so no ``except
    Exception`` stops it) so that temporary files are removed and children ended; the
    command then exits 128 + the signal's number (143, 129)."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.exit_code = 128 + signum
