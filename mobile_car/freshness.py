"""Decide "nothing changed" without loading anything.

An output (a built URDF, a picture) records the files it was made from as *stamps*:
``[path, identity, sha256]``, the identity being ``[size, mtime_ns, ctime_ns, inode,
device]``, and a *key*: a hash of everything else that decides it (the command line's
arguments and overrides, the package search environment, options, mcar's version, the
record format). A later run that finds the same key and every stamped file still the
same knows the output is current. A file that would newly be included cannot appear
without a stamped file (the one including it) changing. The environment variables a
stamped file reads through xacro's ``$(env)`` and ``$(optenv)`` are stamped beside it,
with their values.

"Still the same" is decided by something an edit cannot keep. A file up to
:data:`HASHED_BYTES` (4 MiB) is hashed on every check: size and mtime alone were fooled
by a same-size edit whose mtime was put back (``cp -p``, ``rsync -t``, ``touch -r``, ``tar
x``, a restored cache), and every xacro is read whole at that size anyway (for its
``$(env)`` names); every mesh of the released TurtleBot3, Husky, Jackal, Clearpath, MiR
and Kobuki packages is below it (the largest, 3.2 MB), and SHA-256 of 4 MiB costs ~3 ms.
A larger file (a mesh) counts as unchanged when its whole identity is: the change time
cannot be set back by its owner, and a copy put in its place has another inode; when the
identity differs, its bytes are hashed, and only a changed hash means rebuilding.

Kept free of xacro, lxml, numpy and trimesh: this is what a no-op run imports.
"""

from __future__ import annotations

import functools
import hashlib
import json
import os
import re
import time
from dataclasses import dataclass, field
from pathlib import Path

from . import __version__
from .packages.asset_roots import chosen_asset_paths

# Environment that changes where $(find PKG) and package:// lead.
SEARCH_ENVIRONMENT = ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH")
# A file modified this close to (or after) the start of the run that read it may have
# changed after it was read, within one tick of the file system's clock: it gets no
# stamp, so the next run rebuilds what it made (git's "racy" files).
RACY_MARGIN_NS = 30_000_000
# Files up to this size are known by their bytes, hashed on every check (see above).
HASHED_BYTES = 4 << 20
# In every record key: bumped when stamps change shape or meaning, so that records an
# older mcar wrote are simply not matched (2: identities with ctime, inode and device,
# small files hashed on every check).
RECORD_FORMAT = 2
# What a file that is not a regular file (a FIFO, a device) is stamped with: it never
# counts as unchanged.
NOT_REGULAR = "not a regular file"
# What a file that was missing is stamped with (a mesh the check found missing, W207): the
# stamp holds while the file is still missing.
ABSENT = "absent"


def file_sha256(path: str | os.PathLike) -> str:
    digest = hashlib.sha256()
    from .errors import InputError
    from .load.bounded import open_regular

    try:
        handle = open_regular(path)
    except InputError:  # never opened for reading: a FIFO would block
        return NOT_REGULAR  # a device or FIFO never counts as unchanged
    with handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _hash_limit() -> int:
    from .load.compressed import max_mesh_bytes  # (light: the settings only)

    return max_mesh_bytes()


def key_of(*parts) -> str:
    """A hash of plain data (and mcar's version and installation): two runs with equal
    keys were asked the same thing."""
    text = json.dumps([__version__, RECORD_FORMAT, installed_stamp(), *parts], sort_keys=True,
                      default=str)
    return hashlib.sha256(text.encode()).hexdigest()


@dataclass(frozen=True)
class Basis:
    """What, besides the files a robot's expansion reads, decides what it becomes: xacro
    arguments, --set words, --config files (read, not included, so stamped here), package
    search paths (packages', assets') and environment."""

    settings: dict = field(default_factory=dict)
    files: tuple[Path, ...] = ()

    @classmethod
    def of(cls, mappings=None, sets=(), config_files=(), package_paths=(), environ=None):
        environ = os.environ if environ is None else environ
        configs = tuple(Path(os.path.abspath(p)) for p in config_files)
        settings = {"mappings": dict(sorted((mappings or {}).items())), "sets": list(sets),
                    "configs": [str(p) for p in configs],
                    "package_paths": [os.path.abspath(p) for p in package_paths],
                    # --asset-path decides which meshes are read at all (W215)
                    "asset_paths": [str(p) for p in chosen_asset_paths()],
                    "environment": {name: environ.get(name) for name in SEARCH_ENVIRONMENT}}
        return cls(settings, configs)

    def with_file(self, path: Path | None, name: str) -> Basis:
        """The basis plus one more file that is read as a setting (a ci variant)."""
        if path is None:
            return self
        absolute = Path(os.path.abspath(path))
        return Basis({**self.settings, name: str(absolute)}, (*self.files, absolute))


@functools.lru_cache(maxsize=1)
def installed_stamp() -> list:
    """When this mcar was installed: the stat of its package and of the wheel's RECORD.
    A reinstall of the same version number (a developer's, a git checkout's) can change
    every rule, so no record made before it counts."""
    package = Path(__file__).resolve().parent
    stamp = []
    for path in (package / "__init__.py",
                 package.parent / f"mcar-{__version__}.dist-info" / "RECORD"):
        try:
            info = os.stat(path)
        except OSError:
            continue
        stamp.append([str(path), info.st_size, info.st_mtime_ns])
    return stamp


def identity(info: os.stat_result) -> list[int]:
    """What a file's stat says of its content: ``[size, mtime_ns, ctime_ns, inode,
    device]``. Size and mtime can be put back after an edit; ctime cannot (but by
    changing the clock), and a copy renamed into place has another inode."""
    return [info.st_size, info.st_mtime_ns, info.st_ctime_ns, info.st_ino, info.st_dev]


class Stamper:
    """Stamps files read by one run (started when the Stamper was made)."""

    def __init__(self):
        self.started_ns = time.time_ns()

    def stamps(self, paths, skip=(), absent=()) -> list[list] | None:
        """Stamps of the files (each once, ``skip`` left out); None if one is missing,
        but for those of ``absent``: stamped as missing (current while they are)."""
        skipped = {os.path.abspath(p) for p in skip if p is not None}
        may_miss = {os.path.abspath(p) for p in absent}
        result, names = [], set()
        for path in dict.fromkeys(os.path.abspath(p) for p in [*paths, *absent]):
            if path in skipped:
                continue
            if path in may_miss and not os.path.lexists(path):
                result.append([path, None, ABSENT])
                continue
            try:
                info = os.stat(path)
                digest = _digest_and_names(path, info.st_size, names)
            except OSError:
                return None
            # A change since the run started with its mtime put back is racy too (its
            # ctime says so). Without the margin: a checkout or copy made just before the
            # run changed ctimes, not mtimes, and must not make every stamp racy.
            if info.st_mtime_ns >= self.started_ns - RACY_MARGIN_NS or \
                    info.st_ctime_ns >= self.started_ns:
                result.append([path, [-1], ""])  # never matches: rebuilt next time
            else:
                result.append([path, identity(info), digest])
        return result + [[ENV_STAMP, name, os.environ.get(name), ""] for name in sorted(names)]


# A stamp of an environment variable a stamped file reads through xacro's $(env NAME) or
# $(optenv NAME ...) (Husky's and Jackal's accessories): [ENV_STAMP, NAME, value or None,
# ""]. The files are stamped, so the names they read cannot change unseen; the values can.
ENV_STAMP = "$(env)"
_ENV_USE = re.compile(rb"\$\(\s*(?:env|optenv)\s+([A-Za-z_][A-Za-z0-9_]*)")
_ENV_SCAN_BYTES = 4 << 20  # larger files are meshes, not xacro


def _digest_and_names(path: str, size: int, names: set[str]) -> str:
    """The file's SHA-256 ("" over the mesh cap: a mesh not read, drawn as a marker, is
    stamped by size and time only, hashing gigabytes would cost more than the redraw),
    adding to ``names`` the variables it names in xacro's ``$(env)`` and ``$(optenv)``;
    a file small enough to be xacro is read once for both."""
    if size > _ENV_SCAN_BYTES:
        return file_sha256(path) if size <= _hash_limit() else ""
    from .errors import InputError
    from .load.bounded import open_regular

    try:
        handle = open_regular(path)
    except InputError:  # never opened for reading: a FIFO would block
        return NOT_REGULAR  # as file_sha256 says: never counts as unchanged
    with handle:
        data = handle.read()
    names.update(name.decode("ascii") for name in _ENV_USE.findall(data))
    return hashlib.sha256(data).hexdigest() if size <= _hash_limit() else ""


def is_environment_stamp(stamp) -> bool:
    return isinstance(stamp, list) and len(stamp) == 4 and stamp[0] == ENV_STAMP


def output_stamp(path: str | os.PathLike, digest: str) -> list | None:
    """``[identity, sha256]`` of a file this run just wrote (its hash is known)."""
    try:
        info = os.stat(path)
    except OSError:
        return None
    return [identity(info), digest]


def stamps_current(stamps) -> tuple[bool, bool]:
    """(current, refreshed): whether every stamped file still has its recorded content,
    and whether a stamp was brought up to date (same bytes, new identity: a touch, a
    fresh checkout)."""
    refreshed = False
    if not isinstance(stamps, list):
        return False, False
    for stamp in stamps:
        ok, changed = stamp_current(stamp)
        if not ok:
            return False, refreshed
        refreshed = refreshed or changed
    return True, refreshed


def stamp_current(stamp) -> tuple[bool, bool]:
    """One ``[path, identity, sha256]`` stamp: (current, refreshed in place); or an
    environment variable's (:data:`ENV_STAMP`). A stamp of another shape (an older
    mcar's ``[path, size, mtime_ns, sha256]``) is not current."""
    if is_environment_stamp(stamp):
        return isinstance(stamp[1], str) and os.environ.get(stamp[1]) == stamp[2], False
    try:
        path, recorded, digest = stamp
        if digest == ABSENT and recorded is None:
            return not os.path.lexists(path), False
        info = os.stat(path)
    except (OSError, ValueError, TypeError):
        return False, False
    if not isinstance(digest, str) or digest == NOT_REGULAR:
        return False, False
    now = identity(info)
    # (no digest: a file over the mesh cap, never read, is known by its identity alone)
    if (info.st_size > HASHED_BYTES or not digest) and now == recorded:
        return True, False
    if not isinstance(recorded, list) or not recorded or info.st_size != recorded[0] \
            or not digest:
        return False, False
    try:
        if file_sha256(path) != digest:
            return False, False
    except OSError:
        return False, False
    if now == recorded:
        return True, False
    stamp[1] = now
    return True, True


def output_current(path: str | os.PathLike, stamp) -> tuple[bool, bool]:
    """Whether an output still holds what was written (``[identity, sha256]``), and
    whether its stamp was refreshed in place (same bytes, new identity)."""
    if not isinstance(stamp, list) or len(stamp) != 2:
        return False, False
    full = [os.fspath(path), *stamp]
    ok, refreshed = stamp_current(full)
    stamp[0] = full[1]
    return ok, refreshed


def diagnostics_data(diagnostics) -> list[dict]:
    """Diagnostics as plain data; file names made absolute, to be shown relative to the
    working folder of the run that replays them (as they were shown when found)."""
    return [{"rule": d.rule, "file": os.path.abspath(d.file) if os.path.exists(d.file)
             else d.file, "line": d.line, "message": d.message} for d in diagnostics]


def diagnostics_from(data, kind=None) -> list:
    """The Diagnostics :func:`diagnostics_data` recorded (``kind``: the class, Diagnostic
    by default, whose rule table they name); ValueError if ``data`` is not what it wrote:
    a damaged or forged record is rebuilt, never trusted."""
    from .check.diagnostics import Diagnostic
    from .load.inputs import display_path

    kind = kind or Diagnostic
    if not isinstance(data, list):
        raise ValueError("recorded diagnostics are not a list")
    found = []
    for d in data:
        rule, file, line = (d.get("rule"), d.get("file"), d.get("line")) \
            if isinstance(d, dict) else (None, None, None)
        if not (isinstance(rule, str) and kind.knows(rule) and isinstance(file, str)
                and (line is None or type(line) is int) and isinstance(d.get("message"), str)):
            raise ValueError(f"not a recorded diagnostic: {d!r:.80}")
        found.append(kind(rule, display_path(file) if os.path.isabs(file) else file, line,
                          d["message"]))
    return found


def read_record(path: Path, section: str) -> dict[str, dict]:
    """The entries under ``section`` of a JSON record (the render manifest, the ci
    record), or none when it is missing, damaged, not a record, or not sealed by this
    user's mcar (a record in a checkout may have come with a pull request: see
    :mod:`.record_seal`). Read within the input limit: the record may be a link to
    /dev/zero, or a FIFO. UsageError for a record in a default output folder that is a
    link leading out of the checkout (:mod:`.load.default_outputs`): never followed."""
    from .errors import InputError
    from .load.bounded import read_input
    from .load.default_outputs import placed
    from .record_seal import unsealed_entries

    path, _ = placed(path)
    try:
        data = json.loads(read_input(path))
    except (OSError, ValueError, RecursionError, InputError):
        return {}
    entries = unsealed_entries(data, section)
    if entries is None:
        return {}
    return {key: value for key, value in entries.items()
            if isinstance(value, dict) and _is_record_name(key)}


def write_record(path: Path, section: str, entries: dict[str, dict]) -> None:
    """Write a record :func:`read_record` will take back, sealed; nothing where this
    user has no record key (the next run then does the work again)."""
    from .atomic import atomic_write
    from .record_seal import sealed_text

    text = sealed_text(section, entries)
    if text is not None:
        atomic_write(path, text)


def _is_record_name(key: str) -> bool:
    """A record names its outputs by their paths below its folder: one that names a file
    elsewhere (absolute, ``..``) or none at all (NUL) was not written by mcar."""
    parts = key.split("/")
    return bool(key) and "\0" not in key and not key.startswith("/") and ".." not in parts
