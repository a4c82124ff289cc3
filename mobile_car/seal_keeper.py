"""The one process that holds the record key, so that mcar itself never does.

A xacro is code, run in a child forked from mcar (:mod:`.expand.isolate`): whatever mcar
holds in memory when it forks, the child holds too, where no kernel layer stops it reading
its own memory. Were the record key (:mod:`.record_seal`) read into mcar, a xacro would
find it in ``sys.modules`` and print it in an error line, in a public CI log, and with it
anyone could seal records that make ``mcar ci`` pass a robot it never checked.

So the key is read only here: a small process, started by mcar the first time a seal is
needed, that reads the key (making it on first use) and answers one question, "the
HMAC-SHA256 of these bytes under the key in this folder", through a socket pair. mcar sends
the text to seal and gets the hex digest back; the key bytes never cross. Every process
forked later (each xacro child) is forked from mcar, which never had the key. A forked
process that needs seals itself starts its own keeper: the socket is not shared.

The keeper is a new interpreter running this module (``python -I -S``, the standard
library only), not a fork of mcar: a fork would share mcar's memory for the whole run, and every
page mcar then wrote would be copied (3,000 page faults, ~40 ms of CPU on a no-op
``mcar ci``). It leaves when mcar closes the socket or dies. Where no keeper can be
started (no ``posix_spawn``, no interpreter to run), the seal is computed in this process.
"""

from __future__ import annotations

# Only what the keeper needs, and light: it starts a new interpreter for every run that
# seals, and under load every import is wall time mcar waits for (socket, pathlib and
# threading cost it ~50 ms on a busy machine).
import _thread
import os
import select
import signal
import sys

try:  # Python's own SHA-256: the keeper starts without loading OpenSSL
    from _sha2 import sha256 as _sha256
except ImportError:
    try:
        from _sha256 import sha256 as _sha256
    except ImportError:  # pragma: no cover - a Python built without it
        from hashlib import sha256 as _sha256

KEY_NAME = "record-key"
KEY_BYTES = 32
_lock = _thread.allocate_lock()  # one question and its answer at a time on the socket
_link = -1  # mcar's end of the socket pair, a file descriptor
_keeper_pid = 0
_owner_pid = 0  # the process that started the keeper: a forked copy must not ask it


def seal(folder: str | os.PathLike, message: bytes) -> str | None:
    """The HMAC-SHA256 (hex) of ``message`` under the record key kept in ``folder``, made
    there on first use; None where no key can be kept, or the keeper cannot answer (the
    records are then neither written nor believed: the run does the work)."""
    if not hasattr(os, "posix_spawn") or not sys.executable:
        secret = load_key(folder)
        return None if secret is None else hmac_sha256(secret, message)
    request = os.fsencode(os.path.abspath(folder)) + b"\0" + message
    with _lock:
        for _attempt in range(2):  # a keeper that died (killed by hand) is started again
            try:
                link = _keeper()
                _write_all(link, len(request).to_bytes(4, "big") + request)
                answer = _read_exactly(link, 1)
                size = answer[0] if answer else None
                digest = _read_exactly(link, size) if size else b""
                if answer and (not size or len(digest) == size):
                    return digest.decode("ascii") if size else None
            except OSError:
                pass
            _forget()
    return None


def hmac_sha256(secret: bytes, message: bytes) -> str:
    """HMAC-SHA256 (RFC 2104) on Python's own SHA-256: the same digest as
    ``hmac.new(secret, message, hashlib.sha256)``."""
    block = 64
    if len(secret) > block:
        secret = _sha256(secret).digest()
    secret = secret.ljust(block, b"\0")
    inner = _sha256(bytes(b ^ 0x36 for b in secret) + message).digest()
    return _sha256(bytes(b ^ 0x5C for b in secret) + inner).hexdigest()


def load_key(folder: str | os.PathLike) -> bytes | None:
    """The key kept in ``folder``, made on first use; None where none can be kept. Called
    in the keeper (or where there is no keeper): never in a process that forks xacro."""
    path = os.path.join(folder, KEY_NAME)
    try:
        return _read_key(path)
    except FileNotFoundError:
        pass
    except OSError:
        return None
    try:
        os.makedirs(folder, mode=0o700, exist_ok=True)
        # Made aside and linked into place: two runs starting at once agree on one key,
        # and neither reads a half-written one.
        temporary = os.path.join(folder, f".{KEY_NAME}.{os.getpid()}.{os.urandom(4).hex()}")
        descriptor = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        try:
            with os.fdopen(descriptor, "wb") as handle:
                handle.write(os.urandom(KEY_BYTES))
            try:
                os.link(temporary, path)
            except FileExistsError:
                pass
        finally:
            try:
                os.unlink(temporary)
            except FileNotFoundError:
                pass
        return _read_key(path)
    except OSError:
        return None


def _read_key(path: str) -> bytes | None:
    with open(path, "rb") as handle:
        data = handle.read(KEY_BYTES + 1)
    return data if len(data) == KEY_BYTES else None


# The keeper imports this file as a module of its own (its compiled form is cached, where
# running it as a script compiles it each time), after the standard library on the path.
_START = ("import sys; sys.path.append(sys.argv[1]); import seal_keeper; "
          "seal_keeper._serve(int(sys.argv[2]), int(sys.argv[3]))")


def _keeper() -> int:
    """mcar's end of the socket to its keeper, started on first use."""
    global _link, _keeper_pid, _owner_pid
    if _link >= 0 and _owner_pid == os.getpid():
        return _link
    _link = -1
    import socket

    ours, theirs = (end.detach() for end in socket.socketpair())
    try:
        os.set_inheritable(theirs, True)
        null = [(os.POSIX_SPAWN_OPEN, fd, os.devnull, os.O_RDWR, 0) for fd in (0, 1, 2)]
        pid = os.posix_spawn(sys.executable, [sys.executable, "-I", "-S", "-c", _START,
                                              os.path.dirname(__file__), str(theirs),
                                              str(os.getpid())],
                             os.environ, file_actions=null)
    except BaseException:
        os.close(ours)
        raise
    finally:
        os.close(theirs)
    _link, _keeper_pid, _owner_pid = ours, pid, os.getpid()
    return ours


def _serve(link: int, parent: int) -> None:
    """The keeper's loop: one answer per question until mcar closes the socket or dies."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is mcar's to handle
    if link > 3:  # what mcar holds open and did not mark close-on-exec is not ours
        os.closerange(3, link)
    os.closerange(link + 1, 65536)
    while True:
        # Woken each second to see whether mcar is gone: a process forked from mcar
        # (a xacro child, for an instant) may still hold the other end of the socket.
        if not select.select([link], [], [], 1.0)[0]:
            if os.getppid() != parent:
                return
            continue
        prefix = _read_exactly(link, 4)
        if len(prefix) < 4:
            return
        request = _read_exactly(link, int.from_bytes(prefix, "big"))
        folder, _, message = request.partition(b"\0")
        secret = load_key(os.fsdecode(folder))
        digest = b"" if secret is None else hmac_sha256(secret, message).encode("ascii")
        _write_all(link, bytes([len(digest)]) + digest)


def _read_exactly(fd: int, size: int) -> bytes:
    data = bytearray()
    while len(data) < size:
        chunk = os.read(fd, size - len(data))
        if not chunk:
            break
        data += chunk
    return bytes(data)


def _write_all(fd: int, data: bytes) -> None:
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view):]


def _forget() -> None:
    """Drop the link to the keeper (it ends when it sees the socket close) and reap it."""
    global _link, _keeper_pid
    if _link >= 0 and _owner_pid == os.getpid():
        os.close(_link)
        if _keeper_pid:
            try:
                os.waitpid(_keeper_pid, 0)
            except ChildProcessError:
                pass
    _link, _keeper_pid = -1, 0


def _after_fork_in_child() -> None:
    # A forked copy of mcar (a xacro child, a launched run) closes its copy of the socket
    # at once: its questions would mix with mcar's, and a xacro must not ask at all.
    global _link, _keeper_pid
    if _link >= 0:
        try:
            os.close(_link)
        except OSError:
            pass
    _link, _keeper_pid = -1, 0


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_after_fork_in_child)
