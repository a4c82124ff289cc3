"""What the page may send to ``mcar view``: a value for one of its controls, of the control's
type and within its range, and nothing else.

viser stores whatever the page sends as a control's new state (a slider at 1e308, NaN, a
string; any other property of it, even its callbacks), tells every other page, and only
then runs the callbacks. So every update is checked here first, in front of viser's own
handler: a bad one is dropped, with one warning line per control (a page may send
hundreds a second), and never reaches viser's state or the model. An exception in a
callback of ours, or in viser's handler, is a warning too; no message the page sends can
stop the server serving its other pages or later ones.
"""

from __future__ import annotations

import logging
import math
import reprlib
import threading
from collections.abc import Callable

import viser

from ..errors import UsageError

# The overrides YAML the page shows, with room to spare: a longer text is no edit a
# person made.
MAX_TEXT = 100_000
# Distinct warnings of one kind said before the rest of that kind go without a word.
MAX_WARNINGS = 20


class OncePer:
    """``warn(text)`` once per key, for at most ``MAX_WARNINGS`` keys of each kind (the
    key's first item), so that a page cannot flood the terminal, nor use up every
    warning with one kind (thread-safe)."""

    def __init__(self, warn: Callable[[str], None]):
        self._warn = warn
        self._said: dict[object, set] = {}
        self._lock = threading.Lock()

    def __call__(self, key: tuple, text: str) -> None:
        with self._lock:
            said = self._said.setdefault(key[0], set())
            if key in said or len(said) >= MAX_WARNINGS:
                return
            said.add(key)
        self._warn(text)


def shown(value, limit: int = 60) -> str:
    """``value`` as Python writes it (control characters escaped), cut short: it came
    from the page (up to 50 MB of it), and goes to the terminal."""
    short = reprlib.Repr()
    short.maxstring = short.maxother = limit
    short.maxlevel = 2
    return short.repr(value)


def refusal(handle, updates, bounds: tuple[float, float] | None = None) -> str | None:
    """Why ``updates`` (from the page) is no value of ``handle``, or None when it is; a
    slider's value must be within ``bounds`` when given, else within the slider."""
    if not isinstance(updates, dict) or list(updates) != ["value"]:
        keys = sorted(map(str, updates)) if isinstance(updates, dict) else updates
        return f"it may change only its value, not {shown(keys)}"
    value = updates["value"]
    if isinstance(handle, viser.GuiButtonHandle):
        return None if value is True else f"{shown(value)} is no button press"
    if isinstance(handle, viser.GuiCheckboxHandle):
        return None if isinstance(value, bool) else f"{shown(value)} is not true or false"
    if isinstance(handle, viser.GuiSliderHandle):
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            return f"{shown(value)} is not a number"
        low, high = bounds if bounds is not None else (handle.min, handle.max)
        if not (math.isfinite(value) and low <= value <= high):
            return f"{shown(value)} is not within {low:g}..{high:g}"
        return None
    if isinstance(handle, viser.GuiTextHandle):
        if not isinstance(value, str):
            return f"{shown(value)} is not text"
        return None if len(value) <= MAX_TEXT else f"{len(value)} characters is too long"
    return "it takes no value from the page"


def _kind(handle) -> str:
    for kind, cls in (("button", viser.GuiButtonHandle), ("checkbox", viser.GuiCheckboxHandle),
                      ("slider", viser.GuiSliderHandle), ("text", viser.GuiTextHandle)):
        if isinstance(handle, cls):
            return kind
    return "control"


def _uuid(handle) -> str:
    return handle._impl.uuid  # (viser names a control by it on the wire; no public name)


class Inbound:
    """The controls that take values from the page, and the check in front of viser."""

    def __init__(self, warn: Callable[[str], None]):
        self.warn = OncePer(warn)
        self._controls: dict[str, tuple] = {}  # uuid -> (handle, bounds or None)
        self._lock = threading.Lock()

    def accept(self, handle, bounds: tuple[float, float] | None = None):
        """Let the page set ``handle``'s value (checked); returns ``handle``. A slider
        takes values within ``bounds`` when given (a dimension's box takes any value of
        its plausible range, beyond the neighbourhood its slider spans)."""
        with self._lock:
            self._controls[_uuid(handle)] = (handle, bounds)
        return handle

    def forget(self, handles) -> None:
        with self._lock:
            for handle in handles:
                self._controls.pop(_uuid(handle), None)

    def admits(self, message) -> bool:
        """Whether viser may apply this GUI update; warns (once per control) when not.
        A control not (or no longer) offered is dropped quietly: a page may still drag
        a slider a reload has just replaced."""
        with self._lock:
            handle, bounds = self._controls.get(getattr(message, "uuid", None), (None, None))
        if handle is None:
            return False
        reason = refusal(handle, getattr(message, "updates", None), bounds)
        if reason is not None:
            self.warn(("value", _uuid(handle)),
                      f"mcar view: ignored what the page sent for the {_kind(handle)} "
                      f"{handle.label!r}: {reason} (more from it are ignored silently)")
        return reason is None

    def guarded(self, callback: Callable, what: str) -> Callable:
        """``callback`` that cannot raise: a failure is one warning per ``what``."""

        def run(*args):
            try:
                callback(*args)
            except Exception as error:  # noqa: BLE001 - viser would print a traceback
                self.warn(("callback", what), f"mcar view: {what} failed: "
                                              f"{type(error).__name__}: {shown(str(error), 200)}")

        return run

    def install(self, server: viser.ViserServer) -> None:
        """Put :meth:`admits` in front of viser's handler of the page's GUI updates.

        viser registers ``server.gui._handle_gui_updates`` for ``GuiUpdateMessage`` with
        its WebSocket server (``server._websock_server``), which awaits it for every
        update, for any control; it has no public way to check a value before storing
        it. So that handler is swapped for one that checks first; if viser's insides are
        not as described, mcar view refuses to serve rather than serve unchecked."""
        from viser._messages import GuiUpdateMessage

        try:
            connection = server._websock_server
            handler = server.gui._handle_gui_updates
            connection.unregister_handler(GuiUpdateMessage, handler)
        except (AttributeError, AssertionError, KeyError, ValueError):
            raise UsageError(f"mcar view cannot check what the page sends to viser "
                             f"{viser.__version__}: install viser 1.x") from None

        async def checked(client_id, message) -> None:
            try:
                if self.admits(message):
                    await handler(client_id, message)
            except Exception as error:  # noqa: BLE001 - it would end up as a traceback
                self.warn(("handler", type(error)),
                          f"mcar view: dropped an update from the page: "
                          f"{type(error).__name__}: {shown(str(error), 200)}")

        connection.register_handler(GuiUpdateMessage, checked)
        _drop_unused_kinds(connection)


# Messages viser handles that mcar's page never needs to send (it has no upload, form or
# command control): an upload started against a slider's id would buffer whatever parts
# follow. With no handler, viser drops such a message unread.
_UNUSED_KINDS = ("FileTransferStartUpload", "FileTransferPart", "GuiFormSubmitMessage",
                 "GuiFormDirtyMessage", "CommandTriggerMessage", "GuiButtonHoldMessage")


def _drop_unused_kinds(connection) -> None:
    from viser import _messages

    for name in _UNUSED_KINDS:
        kind = getattr(_messages, name, None)
        if kind is None:
            continue  # not in this viser: nothing to drop
        try:
            connection.unregister_handler(kind)
        except (AssertionError, KeyError):
            pass  # none registered


class UnreadableMessages(logging.Filter):
    """websockets' log of a connection that ended in an exception (a message viser could
    not decode: that connection closes, the others go on), as one warning line instead
    of a traceback per message."""

    def __init__(self, warn: OncePer):
        super().__init__()
        self._warn = warn

    def filter(self, record: logging.LogRecord) -> bool:
        if record.getMessage() != "connection handler failed":
            return True
        error = record.exc_info[1] if record.exc_info else None
        self._warn(("unreadable",), "mcar view: closed a connection that sent a message viser "
                   f"cannot read ({type(error).__name__}: {shown(str(error), 200)})")
        return False
