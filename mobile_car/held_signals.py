"""Hold Ctrl-C, SIGTERM and SIGHUP over a few lines that must not be cut in two.

A signal that lands between ``mkstemp`` and the cleanup that owns its file would leave the
file behind; one that lands inside ``os.fork`` runs mcar's handler inside the after-fork
callbacks (logging's lock release), where Python can only print "Exception ignored".
Held, the signal is delivered the moment it is released, where the code can unwind.
"""

from __future__ import annotations

import signal

_HELD = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)


def hold_signals():
    """Block Ctrl-C, SIGTERM and SIGHUP in this thread; returns what to restore.

    Blocking stops signals still to come. One that came just before has already been
    caught, and its Python handler waits for the interpreter's next check, which could
    fall inside the held lines (in fork's after-fork callbacks, seen once in 50-run signal
    loops): it runs here instead, before anything is held, and unwinds from here."""
    try:
        held = signal.pthread_sigmask(signal.SIG_BLOCK, _HELD)
    except (AttributeError, OSError, ValueError):  # no pthread_sigmask on this platform
        return None
    try:
        _run_pending_handlers()
    except BaseException:
        release_signals(held)
        raise
    return held


def _run_pending_handlers() -> None:
    """Nothing: entering a Python function is where the interpreter runs the handlers of
    signals that have arrived (its eval-breaker check at the call's start)."""


def release_signals(held) -> None:
    if held is not None:
        signal.pthread_sigmask(signal.SIG_SETMASK, held)
