"""Who may talk to ``mcar view``: only its own page, at the address it serves on.

Binding 127.0.0.1 keeps other machines out, but not other web pages in the user's own
browser: a page may open a WebSocket to 127.0.0.1 (the browser sends its ``Origin``, but
nothing refuses it), and a page whose DNS name is made to point at 127.0.0.1 (DNS
rebinding) is, to the browser, same-origin with whatever answers there. Every request
is therefore checked before viser sees it: its ``Host`` must name the address served on
and the port bound, and an ``Origin``, when the browser sends one, must be the viewer's
own page (``http://`` that same host and port). Anything else gets HTTP 403.

viser builds its server with websockets' ``serve`` and its ``process_request`` hook, and
offers no way to add to that hook; :func:`guarding_requests` wraps it while the server
starts (see there why, and what it relies on).
"""

from __future__ import annotations

import contextlib
import http
import ipaddress
import socket
import threading
from collections.abc import Callable, Iterator
from urllib.parse import urlsplit

# Hosts that mean "any address of this machine": other machines reach it by one of its
# addresses or its name, so those are what the page is served at.
_ANY_ADDRESS = {"", "0.0.0.0", "::"}
# The names a browser on this machine uses for a loopback bind ("localhost" resolves to
# both 127.0.0.1 and ::1; a browser tries each).
_LOOPBACK_NAMES = {
    "127.0.0.1": {"127.0.0.1", "localhost"},
    "::1": {"::1", "localhost"},
    "localhost": {"localhost", "127.0.0.1", "::1"},
}
REFUSED_TEXT = "Forbidden: mcar view answers only its own page.\n"


class PageOrigin:
    """The addresses the page is served at, for ``host`` as given to --host."""

    def __init__(self, host: str):
        name = host.strip().strip("[]").lower()
        self.any_address = name in _ANY_ADDRESS
        self.names = set(_LOOPBACK_NAMES.get(name, {name}))
        if self.any_address:
            # Its names too; an address literal (see allows) can never be a rebound name.
            self.names |= {"localhost", socket.gethostname().lower(), socket.getfqdn().lower()}

    def allows(self, name: str) -> bool:
        if name in self.names:
            return True
        if not self.any_address:
            return False
        try:
            ipaddress.ip_address(name)
        except ValueError:
            return False
        return True

    def refusal(self, headers, port: int) -> str | None:
        """Why a request with these headers, to a socket bound to ``port``, is not the
        viewer's own page (a short phrase for the warning), or None when it is."""
        hosts = headers.get_all("Host")
        where = _host_and_port(hosts[0]) if len(hosts) == 1 else None
        if where is None or where[1] != port or not self.allows(where[0]):
            shown = hosts[0] if len(hosts) == 1 else ", ".join(hosts) or "(none)"
            return f"Host {shown!r} is not this viewer's address"
        origins = headers.get_all("Origin")
        if not origins:  # not sent by a browser: a program on this machine
            return None
        if len(origins) > 1 or _origin_host_and_port(origins[0]) != where:
            return f"a page at Origin {', '.join(origins)!r} is not the viewer's own page"
        return None


def _host_and_port(value: str) -> tuple[str, int] | None:
    """``name:port`` (``[v6]:port``; port 80 when absent) as (lowercase name, port)."""
    try:
        parts = urlsplit("//" + value)
        port = parts.port
    except ValueError:
        return None
    if not parts.hostname or parts.netloc != value or "@" in value:
        return None
    return parts.hostname, 80 if port is None else port


def _origin_host_and_port(value: str) -> tuple[str, int] | None:
    try:
        parts = urlsplit(value)
    except ValueError:
        return None
    if parts.scheme != "http" or parts.path or parts.query or parts.fragment:
        return None
    return _host_and_port(parts.netloc)


def guarded(process_request, page: PageOrigin, refused: Callable[[str], None]):
    """``process_request`` (viser's: it serves the page's files) behind the check: a
    request that is not from the page gets 403 and ``refused(reason)``."""

    def process(connection, request):
        reason = page.refusal(request.headers, connection.local_address[1])
        if reason is not None:
            refused(reason)
            return connection.respond(http.HTTPStatus.FORBIDDEN, REFUSED_TEXT)
        return process_request(connection, request) if process_request is not None else None

    return process


_SERVE_LOCK = threading.Lock()


@contextlib.contextmanager
def guarding_requests(page: PageOrigin, refused: Callable[[str], None]) -> Iterator[list]:
    """While the block runs, every server websockets' ``serve`` starts checks each
    request (HTTP and the WebSocket handshake) with ``page`` first. Yields a list that
    holds one entry per server so guarded: empty after the block means the server was
    started some other way and is NOT guarded (the caller must then refuse to serve).

    Why a patch: viser (1.x) starts its server on its own thread with
    ``websockets.asyncio.server.serve(..., process_request=<its file server>)``, called
    through the module attribute, and offers no parameter or hook to check requests;
    websockets' own ``origins=`` check would cover Origin only. So ``serve`` is
    replaced, for the time it takes ViserServer() to start (it returns once bound), by
    a function that wraps the ``process_request`` it is given; the lock keeps two starts
    from stacking patches."""
    import websockets.asyncio.server as websockets_server

    original = websockets_server.serve
    installed: list = []

    def serve(*args, process_request=None, **kwargs):
        installed.append(True)
        return original(*args, process_request=guarded(process_request, page, refused),
                        **kwargs)

    with _SERVE_LOCK:
        websockets_server.serve = serve
        try:
            yield installed
        finally:
            websockets_server.serve = original
