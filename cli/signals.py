"""SIGTERM and SIGHUP end mcar as Ctrl-C does, from the first moment to the last.

Installed when ``mcar`` starts, before click and the command are imported. Until a command
body runs (``arm``) there is nothing to clean up, so a signal exits at once with 128 + its
number; from then on it raises :class:`~mobile_car.errors.Terminated`, which unwinds the
command like KeyboardInterrupt (temporary files removed, the xacro child killed) and
``handle_errors`` exits with the same code. Only in mcar's own process: an embedding
program (a test runner) keeps its handlers.
"""

from __future__ import annotations

import os
import signal
import sys

_armed = False


def _on_signal(signum, frame):
    if not _armed:
        os._exit(128 + signum)
    from mobile_car.errors import Terminated

    raise Terminated(signum)


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
