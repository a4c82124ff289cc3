"""The records mcar keeps between runs count only when this user's mcar wrote them.

The render manifest and the ci record say "this output was made from these files, and
passed": a run that trusts one skips the work. They live beside the outputs, in the
checkout, where a pull request can add a forged one (stamps copied from its own files, a
verdict of "passed"), and ``mcar ci`` would replay a green result for a robot it never
checked. So each record carries an HMAC-SHA256 of its content under a key that only this
user's mcar has: 32 random bytes made once, mode 0600, in the user's cache folder
(``$XDG_CACHE_HOME/mcar`` or ``~/.cache/mcar``; ``MCAR_CACHE_DIR`` moves it), never in a
checkout. A record without a valid seal is ignored and the run does the work. Where no
key can be kept (no writable cache folder), records are neither written nor reused.

Kept free of anything heavy: a no-op run reads its records through this.
"""

from __future__ import annotations

import hashlib
import hmac
import json
import os
import secrets
from functools import lru_cache
from pathlib import Path

CACHE_DIR_ENV = "MCAR_CACHE_DIR"
KEY_NAME = "record-key"
KEY_BYTES = 32
SEAL_FIELD = "seal"


def cache_dir() -> Path:
    own = os.environ.get(CACHE_DIR_ENV, "").strip()
    if own:
        return Path(own)
    xdg = os.environ.get("XDG_CACHE_HOME", "").strip()
    return (Path(xdg) if os.path.isabs(xdg) else Path.home() / ".cache") / "mcar"


@lru_cache(maxsize=4)
def _key_in(folder: Path) -> bytes | None:
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


def key() -> bytes | None:
    """This user's record key, made on first use; None where none can be kept."""
    return _key_in(cache_dir())


def _seal_of(section: str, entries: dict, secret: bytes) -> str:
    # Sealed as the reader will see it: after a JSON round trip, keys sorted.
    canonical = json.dumps([section, json.loads(json.dumps(entries))], sort_keys=True,
                           separators=(",", ":"), ensure_ascii=True)
    return hmac.new(secret, canonical.encode("ascii"), hashlib.sha256).hexdigest()


def sealed_text(section: str, entries: dict) -> str | None:
    """The record's file text with its seal, or None when no key can be kept."""
    secret = key()
    if secret is None:
        return None
    document = {SEAL_FIELD: _seal_of(section, entries, secret),
                section: dict(sorted(entries.items()))}
    return json.dumps(document, indent=1) + "\n"


def unsealed_entries(document, section: str) -> dict[str, dict] | None:
    """The entries of a parsed record whose seal this user's key made, else None."""
    if not isinstance(document, dict):
        return None
    entries, seal = document.get(section), document.get(SEAL_FIELD)
    secret = key()
    if secret is None or not isinstance(entries, dict) or not isinstance(seal, str):
        return None
    if not hmac.compare_digest(seal, _seal_of(section, entries, secret)):
        return None
    return entries
