"""A check with nothing changed reads its verdict back instead of expanding and checking.

``mcar check`` writes no output file, so its "nothing changed" lives in the user's cache
folder (:func:`mobile_car.record_seal.cache_dir`): one sealed record per checked input,
holding the *key* of the run (the input as named, the working folder, xacro arguments,
overrides, package search, the ``MCAR_*`` limits, mcar's version: see
:mod:`mobile_car.freshness`), the stamps of every file the result depends on (the input,
what xacro read, --config files, each mesh and the textures it pulls in), and what the
check found: check_urdf's tree text, the diagnostics, the robot's size and the JSON
form. A run whose key and stamps match prints that, byte for byte what the check printed,
without xacro or a sandbox. Only what xacro expands is kept: a plain URDF checks in less
time than its record would take to read, so it is checked in full every time, as is
anything else (a record damaged, forged or not sealed by this user's mcar, a file
changed, a mesh missing, ``--gazebo``, stdin).

Kept free of xacro, lxml and numpy: a no-op check reads its records through this.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

from .diagnostics import Counted, Diagnostic

if TYPE_CHECKING:
    from ..freshness import Basis, Stamper

SECTION = "checks"
FOLDER = "checks"
# A tree text above this is checked again rather than kept: a 20,000-link chain's tree
# is hundreds of megabytes of indentation, cheaper to make than to store.
MAX_KEPT_BYTES = 4 << 20
# A robot this large is checked in full every time: recording it (its tree text and JSON
# form) would cost its first check more than a no-op saves; check_urdf-size benchmarks
# are made of such robots.
MAX_KEPT_LINKS = 2000


class ReplayedResult(Counted):
    """What :func:`replay` reads back: the parts of a CheckResult the output is made of."""

    # A plain class, not a dataclass: never compared, and a dataclass costs every run
    # that imports it the compiling of its methods (values.py).
    def __init__(self, file: str, sound: bool, tree_text: bytes | None,
                 diagnostics: list[Diagnostic] | None = None, extents: tuple | None = None,
                 document: dict | None = None, failure: None = None):
        self.file = file
        self.sound = sound
        self.tree_text = tree_text
        self.diagnostics = [] if diagnostics is None else diagnostics
        self.extents = extents
        self.document = {} if document is None else document  # as_json() of the result
        self.failure = failure  # a failed load is never kept


def run_key(label: str, path: Path, basis: Basis) -> str:
    from ..freshness import key_of

    limits = {name: value for name, value in os.environ.items()
              if name.startswith("MCAR_") and name != "MCAR_CACHE_DIR"}
    return key_of("check", label, os.path.abspath(path), os.getcwd(), basis.settings, limits)


def _record_path(path: Path) -> Path:
    import hashlib

    from ..record_seal import cache_dir

    name = hashlib.sha256(os.fsencode(os.path.abspath(path))).hexdigest()[:40]
    return cache_dir() / FOLDER / f"{name}.json"


def replayable(inp) -> bool:
    """Whether the input ``inp`` can have a record to read back (what xacro expands):
    asked first, so that the check of a plain URDF needs no run key, no basis and no
    records module."""
    if inp.path is None:
        return False
    return inp.named_xacro or (_small(inp.path) and inp.xacro_use is not None)


def replay(inp, basis: Basis) -> ReplayedResult | None:
    """The recorded result of checking the input ``inp`` (a RobotInput) under ``basis``,
    if nothing it depends on changed; else None. The note a ``.urdf`` that uses xacro gets
    (:mod:`mobile_car.load.xacro_use`) is said again, as loading it says it."""
    if not replayable(inp):
        return None
    from ..freshness import read_record, stamps_current

    label, path = inp.label, inp.path
    use = None if inp.named_xacro else inp.xacro_use
    key = run_key(label, path, basis)
    entry = read_record(_record_path(path), SECTION).get(key[:40])
    if not entry or entry.get("key") != key or entry.get("compared") is not True:
        return None
    try:
        result = _from_entry(label, entry)
    except (ValueError, TypeError, KeyError):
        return None  # damaged: checked again and recorded anew
    current, _refreshed = stamps_current(entry.get("files"))
    if not current:
        return None
    if use is not None:
        from ..load.xacro_use import note_expanded

        note_expanded(label, use)
    return result


def _small(path: Path) -> bool:
    """A file not named .xacro is asked whether it uses xacro only when that is cheap: a
    large plain URDF is read once, by its check."""
    try:
        return os.stat(path).st_size <= MAX_KEPT_BYTES
    except OSError:
        return False


def record(inp, basis: Basis, result, stamper: Stamper, also=(), compared: bool = True,
           absent=()) -> None:
    """Keep the CheckResult just made of the input ``inp`` (`mcar check` and `mcar ci`
    both do, so that either's run spares the other's); a failed load, a robot too large
    to keep or a file that cannot be stamped: nothing kept. ``also``: other files the
    result depends on (the package's controller and Nav2 YAML), ``absent`` files it
    depends on staying absent (a sibling control package); ``compared`` False: that
    YAML was not compared with the robot (ci's check), so `mcar check` does not read the
    record back (mobile_car.specs.stack_check)."""
    label, path = inp.label, inp.path
    if path is None or result.failure is not None or result.loaded is None or \
            not result.loaded.from_xacro or \
            len(result.robot.links if result.robot else ()) > MAX_KEPT_LINKS or \
            any(m.path is None for m in result.mesh_files):
        return  # (a mesh whose package is unknown may appear later: nothing to stamp)
    tree_text = _tree_text(result)
    if tree_text is False:
        return
    from ..freshness import write_record

    reads = [r for m in result.mesh_files for r in m.reads]
    files = stamper.stamps([*result.loaded.deps, path, *basis.files,
                            *(m.path for m in result.mesh_files), *reads,
                            *result.loaded.search.settings_read, *also], absent=absent)
    if files is None:
        return  # a file missing now may appear later: nothing to stamp it by
    try:
        tree = None if tree_text is None else tree_text.decode("utf-8")
    except UnicodeDecodeError:
        return
    from .checker import as_json

    key = run_key(label, path, basis)
    entry = {"key": key, "files": files, "sound": bool(result.sound), "tree": tree,
             "compared": compared,
             "extents": None if result.extents is None else list(result.extents),
             "diagnostics": [[d.rule, d.file, d.line, d.message] for d in result.diagnostics],
             "document": as_json(result)}
    write_record(_record_path(path), SECTION, {key[:40]: entry})


def _tree_text(result):
    """check_urdf's tree text of a sound result (None for an unsound one), or False when
    it is too large to keep."""
    from .tree import check_urdf_lines

    if not result.sound:
        return None
    kept, size = [], 0
    for line in check_urdf_lines(result.robot.name, result.tree):
        kept.append(line)
        size += len(line)
        if size > MAX_KEPT_BYTES:
            return False
    return b"".join(kept)


def _from_entry(label: str, entry: dict) -> ReplayedResult:
    diagnostics = []
    for rule, file, line, message in entry["diagnostics"]:
        if not (isinstance(rule, str) and Diagnostic.knows(rule) and isinstance(file, str)
                and (line is None or type(line) is int) and isinstance(message, str)):
            raise ValueError("not a recorded diagnostic")
        diagnostics.append(Diagnostic(rule, file, line, message))
    tree, extents, document = entry["tree"], entry["extents"], entry["document"]
    if not (tree is None or isinstance(tree, str)) or not isinstance(document, dict) \
            or not isinstance(entry["sound"], bool):
        raise ValueError("not a recorded check")
    if extents is not None and not (isinstance(extents, list) and len(extents) == 3 and all(
            isinstance(v, (int, float)) for v in extents)):
        raise ValueError("not recorded extents")
    return ReplayedResult(label, entry["sound"], None if tree is None else tree.encode("utf-8"),
                          diagnostics, None if extents is None else tuple(extents), document)
