"""The one process that holds the record key, so that mcar itself never does.

A xacro is code, run in a child forked from mcar (:mod:`.expand.isolate`): whatever mcar
holds in memory when it forks, the child holds too, where no kernel layer stops it reading
its own memory. Were the record key (:mod:`.record_seal`) read into mcar, a xacro would
find it in ``sys.modules`` and print it in an error line, in a public CI log, and with it
anyone could seal records that make ``mcar ci`` pass a robot it never checked.

So the key is read only here: a small process, forked from mcar the first time a seal is
needed, that reads the key (making it on first use) and answers one question, "the
HMAC-SHA256 of these bytes under the key in this folder", through a socket pair. mcar sends
the text to seal and gets the hex digest back; the key bytes never cross. Every process
forked later (each xacro child) is forked from mcar, which never had the key. A forked
process that needs seals itself starts its own keeper: the socket is not shared.

The keeper is forked while other threads may run: after the fork it takes no lock they
could hold (it uses Python's own SHA-256, not OpenSSL's, imported before the fork, and
only reads a file and a socket). It leaves when mcar closes the socket or dies. Where no
keeper can be started (no ``fork``), the seal is computed in this process, as before.
"""

from __future__ import annotations

import os
import secrets
import select
import signal
import socket
import struct
import threading
from pathlib import Path

try:  # Python's own SHA-256: OpenSSL's takes locks another thread may hold at the fork
    from _sha2 import sha256 as _sha256
except ImportError:
    try:
        from _sha256 import sha256 as _sha256
    except ImportError:  # pragma: no cover - a Python built without it
        from hashlib import sha256 as _sha256

KEY_NAME = "record-key"
KEY_BYTES = 32
_LENGTH = struct.Struct(">I")
_lock = threading.Lock()  # one question and its answer at a time on the socket
_link: socket.socket | None = None
_keeper_pid = 0
_owner_pid = 0  # the process that started the keeper: a forked copy must not ask it


def seal(folder: Path, message: bytes) -> str | None:
    """The HMAC-SHA256 (hex) of ``message`` under the record key kept in ``folder``, made
    there on first use; None where no key can be kept, or the keeper cannot answer (the
    records are then neither written nor believed: the run does the work)."""
    if not hasattr(os, "fork"):
        secret = load_key(folder)
        return None if secret is None else hmac_sha256(secret, message)
    request = os.fsencode(os.path.abspath(folder)) + b"\0" + message
    with _lock:
        for _attempt in range(2):  # a keeper that died (killed by hand) is started again
            try:
                link = _keeper()
                link.sendall(_LENGTH.pack(len(request)) + request)
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


def load_key(folder: Path) -> bytes | None:
    """The key kept in ``folder``, made on first use; None where none can be kept. Called
    in the keeper (or where there is no keeper): never in a process that forks xacro."""
    path = folder / KEY_NAME
    try:
        return _read_key(path)
    except FileNotFoundError:
        pass
    except OSError:
        return None
    try:
        folder.mkdir(parents=True, exist_ok=True, mode=0o700)
        # Made aside and linked into place: two runs starting at once agree on one key,
        # and neither reads a half-written one.
        temporary = folder / f".{KEY_NAME}.{os.getpid()}.{secrets.token_hex(4)}"
        descriptor = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        try:
            with os.fdopen(descriptor, "wb") as handle:
                handle.write(secrets.token_bytes(KEY_BYTES))
            try:
                os.link(temporary, path)
            except FileExistsError:
                pass
        finally:
            temporary.unlink(missing_ok=True)
        return _read_key(path)
    except OSError:
        return None


def _read_key(path: Path) -> bytes | None:
    with open(path, "rb") as handle:
        data = handle.read(KEY_BYTES + 1)
    return data if len(data) == KEY_BYTES else None


def _keeper() -> socket.socket:
    global _link, _keeper_pid, _owner_pid
    if _link is not None and _owner_pid == os.getpid():
        return _link
    _link = None
    from .held_signals import hold_signals, release_signals

    ours, theirs = socket.socketpair()
    parent = os.getpid()
    held = hold_signals()  # as isolate: no handler of mcar's runs inside the fork
    try:
        pid = os.fork()
    except BaseException:
        release_signals(held)
        ours.close()
        theirs.close()
        raise
    if pid == 0:
        status = 0
        try:
            signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is mcar's to handle
            release_signals(held)
            ours.close()
            _serve(theirs.detach(), parent)
        except BaseException:
            status = 1
        finally:
            os._exit(status)
    release_signals(held)
    theirs.close()
    _link, _keeper_pid, _owner_pid = ours, pid, parent
    return ours


def _serve(fd: int, parent: int) -> None:
    """The keeper's loop: one answer per question until mcar closes the socket or dies."""
    null = os.open(os.devnull, os.O_RDWR)
    for standard in (0, 1, 2):  # mcar's output pipes are not the keeper's to hold open
        os.dup2(null, standard)
    os.close(null)
    if fd > 3:
        os.closerange(3, fd)
    os.closerange(fd + 1, 65536)
    link = socket.socket(fileno=fd)
    while True:
        # Woken each second to see whether mcar is gone: a sibling forked from mcar
        # (a xacro child, for an instant) may still hold the other end of the socket.
        if not select.select([link], [], [], 1.0)[0]:
            if os.getppid() != parent:
                return
            continue
        prefix = _read_exactly(link, _LENGTH.size)
        if len(prefix) < _LENGTH.size:
            return
        request = _read_exactly(link, _LENGTH.unpack(prefix)[0])
        folder, _, message = request.partition(b"\0")
        secret = load_key(Path(os.fsdecode(folder)))
        digest = b"" if secret is None else hmac_sha256(secret, message).encode("ascii")
        link.sendall(bytes([len(digest)]) + digest)


def _read_exactly(link: socket.socket, size: int) -> bytes:
    data = bytearray()
    while len(data) < size:
        chunk = link.recv(size - len(data))
        if not chunk:
            break
        data += chunk
    return bytes(data)


def _forget() -> None:
    """Drop the link to the keeper (it ends when it sees the socket close) and reap it."""
    global _link, _keeper_pid
    if _link is not None and _owner_pid == os.getpid():
        _link.close()
        if _keeper_pid:
            try:
                os.waitpid(_keeper_pid, 0)
            except ChildProcessError:
                pass
    _link, _keeper_pid = None, 0


def _after_fork_in_child() -> None:
    # A forked copy of mcar (a xacro child, a launched run) closes its copy of the socket
    # at once: its questions would mix with mcar's, and a xacro must not ask at all.
    global _link, _keeper_pid
    if _link is not None:
        try:
            _link.close()
        except OSError:
            pass
    _link, _keeper_pid = None, 0


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_after_fork_in_child)
