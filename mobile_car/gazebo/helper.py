"""Find the Gazebo helper (``mcar-sdformat``) and run it on a URDF, within bounds.

The helper is a C++ program linked against libsdformat, so it is not part of the wheel:
``make install`` (or ``make gazebo-helper``) builds it beside the ``mcar`` command, in the
virtualenv's ``bin``, when g++, pkg-config and libsdformat-dev are there. mcar looks for it
at ``MCAR_SDFORMAT`` (a path), then beside the Python scripts of the running interpreter
(where ``mcar`` itself was installed), then on ``PATH``; the working folder is never
searched.

The URDF it is given may come from an untrusted xacro, and libsdformat parses it in C++, so
the helper is run as something less trusted than mcar: a URDF with an ``<include>``, which
libsdformat would read from disk, is refused before it starts (:mod:`.includes`, E152), and
the helper confines itself once set up (a seccomp filter: no file lookups, programs or
sockets); it gets the URDF's bytes on stdin (never a path), an environment of PATH and
LC_ALL only (no HOME: libsdformat keeps no log),
``/`` as its working folder, ``MCAR_GAZEBO_MEMORY_MB`` of address space and
``MCAR_GAZEBO_TIMEOUT`` seconds (the kernel's CPU limit backs the deadline up even if mcar
dies); at most ``MCAR_GAZEBO_OUTPUT_MB`` of its answer is read, and then checked field by
field (:mod:`.wire`). Any failure is one :class:`~mobile_car.errors.GazeboError` naming the
robot, never a traceback.
"""

from __future__ import annotations

import math
import os
import select
import shutil
import signal
import subprocess
import sys
import sysconfig
import time
from pathlib import Path

from ..errors import GazeboError, GazeboUnavailable
from ..held_signals import hold_signals, release_signals

HELPER_NAME = "mcar-sdformat"
HELPER_ENV = "MCAR_SDFORMAT"
TIMEOUT_ENV = "MCAR_GAZEBO_TIMEOUT"
MEMORY_ENV = "MCAR_GAZEBO_MEMORY_MB"
OUTPUT_ENV = "MCAR_GAZEBO_OUTPUT_MB"
DEFAULT_TIMEOUT = 60.0  # libsdformat's cost per link: docs/benchmarks.md
DEFAULT_MEMORY_MB = 4096
DEFAULT_OUTPUT_MB = 256
STDERR_KEPT = 2000  # characters of the helper's stderr quoted when it fails
CHUNK = 1 << 20

INSTALL_HINT = (
    f"the Gazebo helper {HELPER_NAME} is not installed: it is built from mcar's source "
    "with g++, pkg-config and libsdformat-dev (sudo apt-get install g++ pkg-config "
    "libsdformat-dev), by `make gazebo-helper` (or `make install`) in mcar's source folder, "
    f"beside the mcar command; or set {HELPER_ENV} to a built {HELPER_NAME}")


def helper_places() -> list[Path]:
    """The folders searched for the helper, after MCAR_SDFORMAT: where this interpreter's
    scripts (``mcar``) are installed, then beside the interpreter (a virtualenv's bin)."""
    places = [Path(sysconfig.get_path("scripts")), Path(sys.executable).parent]
    return list(dict.fromkeys(places))


def find_helper() -> Path:
    """The helper's path; GazeboUnavailable (exit 2) saying how to install it."""
    named = os.environ.get(HELPER_ENV, "").strip()
    if named:
        path = Path(named)
        if not (path.is_file() and os.access(path, os.X_OK)):
            raise GazeboUnavailable(f"{HELPER_ENV}={named}: not an executable file; "
                                    f"{INSTALL_HINT.split(': ', 1)[1]}")
        return path
    for folder in helper_places():
        path = folder / HELPER_NAME
        if path.is_file() and os.access(path, os.X_OK):
            return path
    # PATH only as the user set it: an empty entry would mean the working folder.
    search = os.pathsep.join(p for p in os.environ.get("PATH", "").split(os.pathsep)
                             if p and os.path.isabs(p))
    found = shutil.which(HELPER_NAME, path=search) if search else None
    if found:
        return Path(found)
    raise GazeboUnavailable(INSTALL_HINT)


def run_helper(urdf: bytes, label: str, with_sdf: bool = False, helper: Path | None = None):
    """libsdformat's report on ``urdf`` (a :class:`~.wire.GazeboReport`; with ``with_sdf``
    also the SDF it writes). ``label`` names the robot in errors. Raises GazeboUnavailable
    (no helper, or one built for another interface) or GazeboError (it failed on this
    robot)."""
    from ..settings import env_number
    from . import wire
    from .includes import refuse_includes

    # Every caller refuses an <include> first, at its source line; this is the last guard
    # before libsdformat, for one that did not.
    refuse_includes(urdf, label)
    helper = helper or find_helper()
    timeout = env_number(TIMEOUT_ENV, DEFAULT_TIMEOUT, 0.1, 86400, "seconds")
    memory_mb = int(env_number(MEMORY_ENV, DEFAULT_MEMORY_MB, 64, 1e7, "MB"))
    output_mb = env_number(OUTPUT_ENV, DEFAULT_OUTPUT_MB, 0.001, 1e6, "MB")
    answer, stderr, status = _run(helper, ["--sdf"] if with_sdf else [], urdf, timeout,
                                  memory_mb, int(output_mb * 1024 * 1024), label)
    if status != 0:
        raise GazeboError(f"the Gazebo helper {_ended(status, memory_mb)}"
                          + _quoted(stderr), file=label)
    try:
        return wire.read_report(answer, with_sdf)
    except wire.OtherInterface as error:
        raise GazeboUnavailable(f"{helper} answers in format {error.interface}, and this "
                                f"mcar reads format {wire.INTERFACE}: rebuild it (make "
                                "gazebo-helper in mcar's source folder)") from None
    except wire.MalformedReport as error:
        raise GazeboError(f"the Gazebo helper sent back something that is not a report "
                          f"({error.reason})", file=label) from None


def _ended(status: int, memory_mb: int) -> str:
    if status < 0:
        try:
            name = signal.Signals(-status).name
        except ValueError:
            name = f"signal {-status}"
        if -status == signal.SIGXCPU:
            return f"ran out of CPU time ({TIMEOUT_ENV} raises the limit)"
        return (f"was ended by {name} (libsdformat crashed, or needed more than "
                f"{MEMORY_ENV}={memory_mb})")
    return f"failed (exit status {status})"


def _quoted(stderr: bytes) -> str:
    from ..names import shown

    text = stderr.decode("utf-8", "replace").strip()
    if not text:
        return ""
    text = text if len(text) <= STDERR_KEPT else text[:STDERR_KEPT] + "..."
    return f": {shown(text)}"


def _limits(timeout: float, memory_mb: int):
    """The child's limits, set between fork and exec: address space, CPU seconds (so that
    it ends even if mcar is killed first), no core file."""
    import resource

    def apply() -> None:
        memory = memory_mb * 1024 * 1024
        for limit, value in ((resource.RLIMIT_AS, memory),
                             (resource.RLIMIT_CPU, math.ceil(timeout) + 1),
                             (resource.RLIMIT_CORE, 0)):
            hard = resource.getrlimit(limit)[1]
            if hard != resource.RLIM_INFINITY:
                value = min(value, hard)  # a lower hard limit (ulimit) is kept
            resource.setrlimit(limit, (value, value))

    return apply


def _environment() -> dict:
    env = {"PATH": os.defpath, "LC_ALL": "C"}
    if os.environ.get("LD_LIBRARY_PATH"):  # a libsdformat installed outside the system's
        env["LD_LIBRARY_PATH"] = os.environ["LD_LIBRARY_PATH"]
    return env


def _run(helper: Path, args: list[str], data: bytes, timeout: float, memory_mb: int,
         most: int, label: str) -> tuple[bytes, bytes, int]:
    """(stdout, the first bytes of stderr, exit status) of the helper fed ``data``."""
    held = hold_signals()  # a signal now would leave a child nobody knows about
    try:
        try:
            popen = subprocess.Popen(
                [str(helper), *args], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                stderr=subprocess.PIPE, env=_environment(), cwd="/",
                preexec_fn=_limits(timeout, memory_mb), close_fds=True)
        except OSError as error:
            raise GazeboUnavailable(f"cannot run {helper}: {error.strerror or error}") \
                from None
        except subprocess.SubprocessError as error:  # its limits could not be set
            raise GazeboUnavailable(f"cannot run {helper}: {error}") from None
    finally:
        release_signals(held)
    try:
        return _exchange(popen, data, timeout, most, label)
    finally:
        if popen.poll() is None:
            popen.kill()
        popen.wait()
        for stream in (popen.stdin, popen.stdout, popen.stderr):
            if not stream.closed:
                stream.close()


def _exchange(popen, data: bytes, timeout: float, most: int,
              label: str) -> tuple[bytes, bytes, int]:
    """Write ``data`` and read the answer at once (either may fill a pipe), within the
    deadline and ``most`` bytes; poll, not select: mcar may hold fds past 1024."""
    deadline = time.monotonic() + timeout
    pending = memoryview(data)
    answer, stderr = bytearray(), bytearray()
    streams = {popen.stdout.fileno(): answer, popen.stderr.fileno(): stderr}
    writer = popen.stdin.fileno()
    os.set_blocking(writer, False)
    if not pending:
        popen.stdin.close()
    while streams:
        poller = select.poll()
        for fd in streams:
            poller.register(fd, select.POLLIN)
        if not popen.stdin.closed:
            poller.register(writer, select.POLLOUT)
        left = deadline - time.monotonic()
        ready = dict(poller.poll(max(0, math.ceil(left * 1000)))) if left > 0 else {}
        if not ready:
            raise GazeboError(f"libsdformat took longer than {TIMEOUT_ENV}={timeout:g} s",
                              file=label)
        if not popen.stdin.closed and writer in ready:
            try:
                pending = pending[os.write(writer, pending[:CHUNK]):]
            except BlockingIOError:
                pass
            except (BrokenPipeError, ConnectionResetError):
                pending = pending[:0]  # it stopped reading: its status says why
            if not pending:
                popen.stdin.close()
        for fd in [fd for fd in streams if fd in ready]:
            chunk = os.read(fd, CHUNK)
            if not chunk:
                del streams[fd]
            elif streams[fd] is answer:
                answer += chunk
                if len(answer) > most:
                    raise GazeboError(f"the Gazebo helper sent more than {OUTPUT_ENV}="
                                      f"{most / 1024 / 1024:g}", file=label)
            elif len(stderr) < STDERR_KEPT * 4:
                stderr += chunk
    left = max(0.1, deadline - time.monotonic())
    try:
        status = popen.wait(left)
    except subprocess.TimeoutExpired:
        raise GazeboError(f"libsdformat took longer than {TIMEOUT_ENV}={timeout:g} s",
                          file=label) from None
    return bytes(answer), bytes(stderr), status
