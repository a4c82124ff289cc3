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

mcar never reads the key itself: a small keeper process does (:mod:`.seal_keeper`), and
mcar asks it for seals. mcar forks the children that evaluate xacro, and a fork holds
whatever its parent held: the key must not be there to find.

Kept free of anything heavy: a no-op run reads its records through this.
"""

from __future__ import annotations

import os
from pathlib import Path

CACHE_DIR_ENV = "MCAR_CACHE_DIR"
SEAL_FIELD = "seal"


def __getattr__(name: str):
    """KEY_NAME and KEY_BYTES (where the key is kept, for tests) from the keeper's module,
    imported only when asked: every check asks cache_dir() (the cache folder is one no
    robot may name a file in), and the keeper's module brings signal, select and SHA-256."""
    if name in ("KEY_NAME", "KEY_BYTES"):
        from . import seal_keeper

        return getattr(seal_keeper, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def cache_dir() -> Path:
    own = os.environ.get(CACHE_DIR_ENV, "").strip()
    if own:
        return Path(own)
    xdg = os.environ.get("XDG_CACHE_HOME", "").strip()
    return (Path(xdg) if os.path.isabs(xdg) else Path.home() / ".cache") / "mcar"


def _seal_of(section: str, entries: dict) -> str | None:
    """The seal of these entries under this user's key, from the keeper; None where no
    key can be kept."""
    # json, and hmac (which loads OpenSSL), only where a record is sealed or read:
    # every check asks cache_dir(), and a plain URDF's check touches no record.
    import json

    # Sealed as the reader will see it: after a JSON round trip, keys sorted.
    canonical = json.dumps([section, json.loads(json.dumps(entries))], sort_keys=True,
                           separators=(",", ":"), ensure_ascii=True)
    from . import seal_keeper

    return seal_keeper.seal(cache_dir(), canonical.encode("ascii"))


def sealed_text(section: str, entries: dict) -> str | None:
    """The record's file text with its seal, or None when no key can be kept."""
    seal = _seal_of(section, entries)
    if seal is None:
        return None
    import json

    document = {SEAL_FIELD: seal,
                section: dict(sorted(entries.items()))}
    return json.dumps(document, indent=1) + "\n"


def unsealed_entries(document, section: str) -> dict[str, dict] | None:
    """The entries of a parsed record whose seal this user's key made, else None."""
    if not isinstance(document, dict):
        return None
    entries, seal = document.get(section), document.get(SEAL_FIELD)
    if not isinstance(entries, dict) or not isinstance(seal, str) or not seal.isascii():
        return None
    import hmac

    expected = _seal_of(section, entries)
    if expected is None or not hmac.compare_digest(seal, expected):
        return None
    return entries
