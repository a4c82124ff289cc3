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
    """Block Ctrl-C, SIGTERM and SIGHUP in this thread; returns what to restore."""
    try:
        return signal.pthread_sigmask(signal.SIG_BLOCK, _HELD)
    except (AttributeError, OSError, ValueError):  # no pthread_sigmask on this platform
        return None


def release_signals(held) -> None:
    if held is not None:
        signal.pthread_sigmask(signal.SIG_SETMASK, held)
