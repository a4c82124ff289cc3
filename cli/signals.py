"""SIGTERM and SIGHUP end mcar as Ctrl-C does, from the first moment to the last.

Installed when ``mcar`` starts, before click and the command are imported. Until a command
body runs (``arm``) and after it ends (``disarm``) there is nothing to clean up, so a
signal exits at once with 128 + its number; while it runs it raises
:class:`~mobile_car.errors.Terminated`, which unwinds the command like KeyboardInterrupt
(temporary files removed, the xacro child killed) and ``handle_errors`` exits with the same
code. Only in mcar's own process: an embedding
program (a test runner) keeps its handlers.
"""

from __future__ import annotations

import os
import signal
import sys

_armed = False
_received: list[int] = []  # the signals that arrived, even if a library swallowed them


def _on_signal(signum, frame):
    if not _armed:  # before or after the command: nothing half-done to clean up
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except Exception:  # noqa: BLE001 - a closed pipe must not stop the exit
                pass
        os._exit(128 + signum)
    _received.append(signum)
    from mobile_car.errors import Terminated

    raise Terminated(signum)


def received() -> int | None:
    """The signal that arrived, if any. Some libraries catch BaseException around their
    optional imports (trimesh does), swallowing Terminated and failing later in odd ways;
    this lets the command line still end as terminated."""
    return _received[0] if _received else None


def install() -> None:
    if sys.stdout is not sys.__stdout__:
        return
    for signum in (signal.SIGTERM, signal.SIGHUP):
        try:
            signal.signal(signum, _on_signal)
        except ValueError:  # not the main thread
            return


def arm() -> None:
    """From now on a signal unwinds the command instead of ending the process."""
    global _armed
    _armed = True


def disarm() -> None:
    """The command is over (its outputs written or cleaned up): a signal ends mcar."""
    global _armed
    _armed = False
