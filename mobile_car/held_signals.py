"""Hold Ctrl-C, SIGTERM and SIGHUP over a few lines that must not be cut in two.

A signal that lands between ``mkstemp`` and the cleanup that owns its file would leave the
file behind; one that lands inside ``os.fork`` runs mcar's handler inside the after-fork
callbacks (logging's lock release), where Python can only print "Exception ignored".
Held, the signal is delivered the moment it is released, where the code can unwind.
"""

from __future__ import annotations

import _thread
import os
import signal

_HELD = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
_MAIN = _thread.get_ident()  # Python runs signal handlers in the main thread only
_depth = 0  # holds open in the main thread
_deferred: list[tuple[int, int, object]] = []  # (pid, signum, handler) that came meanwhile


class Hold:
    """What :func:`release_signals` restores: the thread's mask (None where
    pthread_sigmask does not exist), and whether the hold was taken in the main thread
    (then a handler arriving meanwhile is deferred)."""

    __slots__ = ("mask", "counted")

    def __init__(self, mask, counted: bool):
        self.mask = mask
        self.counted = counted


def hold_signals() -> Hold:
    """Hold Ctrl-C, SIGTERM and SIGHUP in this thread; returns what to restore.

    Blocking stops signals still to come to this thread, but not to the others (numpy's
    BLAS threads, the picture-finishing pool): the kernel hands the signal to one of them,
    and Python still runs the handler in the main thread, inside the held lines. So mcar's
    handler also asks :func:`defer`, and a signal that came while the main thread holds is
    raised when the last hold is released. One that came just before has already been
    caught, and its Python handler waits for the interpreter's next check, which could
    fall inside the held lines (in fork's after-fork callbacks, seen once in 50-run signal
    loops): it runs here instead, before anything is held, and unwinds from here."""
    global _depth
    try:
        mask = signal.pthread_sigmask(signal.SIG_BLOCK, _HELD)
    except (AttributeError, OSError, ValueError):  # no pthread_sigmask on this platform
        mask = None
    try:
        _run_pending_handlers()
    except BaseException:
        if mask is not None:
            signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        raise
    counted = _thread.get_ident() == _MAIN
    if counted:
        _depth += 1
    return Hold(mask, counted)


def _run_pending_handlers() -> None:
    """Nothing: entering a Python function is where the interpreter runs the handlers of
    signals that have arrived (its eval-breaker check at the call's start)."""


def defer(signum: int, handler) -> bool:
    """For a signal handler: True (and the signal kept for the release) while the main
    thread holds signals; then the handler must return without raising."""
    if _depth > 0:
        _deferred.append((os.getpid(), signum, handler))
        return True
    return False


def release_signals(held: Hold | None) -> None:
    """Undo :func:`hold_signals`; at the outermost release of the main thread, run the
    handler of a signal that came meanwhile (it raises here, where the code can unwind).
    A forked child inherits the parent's list but never runs the parent's signals."""
    global _depth
    if held is None:
        return
    if held.mask is not None:
        signal.pthread_sigmask(signal.SIG_SETMASK, held.mask)
    if not held.counted:
        return
    _depth -= 1
    if _depth == 0 and _deferred:
        mine = [(signum, handler) for pid, signum, handler in _deferred
                if pid == os.getpid()]
        _deferred.clear()
        if mine:
            signum, handler = mine[0]
            handler(signum, None)


def import_held(name: str):
    """The module ``name``, imported with the signals held. For trimesh: its import starts
    manifold3d, a nanobind module that aborts the process (SIGABRT, a C++ traceback) when
    Ctrl-C or SIGTERM lands in its start; held, the signal lands after, where mcar
    unwinds as usual (and not inside trimesh's optional-import guards, which swallow it)."""
    import importlib

    held = hold_signals()
    try:
        return importlib.import_module(name)
    finally:
        release_signals(held)
