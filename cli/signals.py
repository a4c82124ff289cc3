"""Ctrl-C, SIGTERM and SIGHUP end mcar the same way, from the first moment to the last.

Installed when ``mcar`` starts, before click and the command are imported. Until a command
body runs (``arm``) and after it ends (``disarm``) there is nothing to clean up, so a
signal exits at once with 128 + its number (130 for Ctrl-C) and says so; while it runs,
Ctrl-C raises KeyboardInterrupt and SIGTERM/SIGHUP raise
:class:`~mobile_car.errors.Terminated`, which unwind the command (temporary files removed,
the xacro child killed) and ``handle_errors`` exits with the same code. Every signal is
also recorded, because some libraries swallow it (see :func:`received`). Only in mcar's own
process: an embedding program (a test runner) keeps its handlers.
"""

from __future__ import annotations

import _signal as signal  # the C half: `signal` costs 6 ms (enum) before install() runs
import os
import sys

_armed = False
_received: list[int] = []  # the signals that arrived, even if a library swallowed them


def announcement(signum: int) -> str:
    return "mcar: interrupted" if signum == signal.SIGINT else "mcar: terminated"


def _on_signal(signum, frame):
    # Nothing is imported here: the signal may have come in the middle of an import.
    # Not loaded, or still being imported (the signal came during its own imports, when
    # `defer` is not defined yet): nothing is held.
    defer = getattr(sys.modules.get("mobile_car.held_signals"), "defer", None)
    if defer is not None and defer(signum, _on_signal):
        return  # a few lines that must not be cut in two: raised when they are done
    if not _armed:  # before or after the command: nothing half-done to clean up
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except Exception:  # noqa: BLE001 - a closed pipe must not stop the exit
                pass
        try:  # os.write: the handler may have interrupted a write to the stderr object
            os.write(2, f"{announcement(signum)}\n".encode())
        except OSError:
            pass
        os._exit(128 + signum)
    if not _received:
        _start_watchdog(signum)
    _received.append(signum)
    if signum == signal.SIGINT:
        raise KeyboardInterrupt
    from mobile_car.errors import Terminated

    raise Terminated(signum)


# Unwinding removes temporary files and ends children in milliseconds; a run that has not
# ended this long after the signal is stuck (a lock left held by the interrupted thread
# pool, a C call that never returns to Python): it ends anyway.
WATCHDOG_SECONDS = 10.0


def _start_watchdog(signum: int) -> None:
    import threading

    timer = threading.Timer(WATCHDOG_SECONDS, _give_up, args=(signum,))
    timer.daemon = True
    timer.start()


def _give_up(signum: int) -> None:
    try:
        os.write(2, f"{announcement(signum)} (cleanup did not end within "
                    f"{WATCHDOG_SECONDS:g} s)\n".encode())
    except OSError:
        pass
    os._exit(128 + signum)


def received() -> int | None:
    """The signal that arrived, if any. Some libraries catch BaseException around their
    optional imports (trimesh does), swallowing the KeyboardInterrupt or Terminated and
    failing later in odd ways, or not at all; this lets the command line still end as
    interrupted or terminated."""
    return _received[0] if _received else None


def _unraisable(info) -> None:
    """A signal's exception raised where Python cannot raise it (a weakref callback of
    the import system, fork's after-fork callbacks, a ``__del__``) is lost with an
    "Exception ignored" traceback. The signal is recorded all the same and ends the run
    at the next check (:func:`raise_if_received`, the command's end): the traceback is
    noise, and only for mcar's own signals is it left out."""
    if _received and type(info.exc_value).__name__ in ("KeyboardInterrupt", "Terminated"):
        return
    sys.__unraisablehook__(info)


def install() -> None:
    if sys.stdout is not sys.__stdout__:
        return
    sys.unraisablehook = _unraisable
    for signum in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
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


def raise_if_received() -> None:
    """Unwind now if a signal came and a library swallowed it (trimesh's import guards
    catch BaseException): without this the command would carry on to the end."""
    signum = received()
    if signum is None:
        return
    if signum == signal.SIGINT:
        raise KeyboardInterrupt
    from mobile_car.errors import Terminated

    raise Terminated(signum)
