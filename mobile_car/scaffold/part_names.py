"""Which names a new part may take: its macro ``xacro:NAME`` and the links and joints its
test file makes of it (``NAME_left_link``, ``NAME_right_joint``, ...: the macro takes a
name per use) must mean that part and nothing else in the package.

A part named after one of xacro's own elements (``include``, ``macro``, ...) makes a macro
that can never be called: ``<xacro:include parent=...>`` is an include. A part whose link,
joint or macro has the name of one the package (or the part's test file) already has makes
a robot with two links of one name, or replaces a macro the package relies on.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from ..errors import UsageError
from ..names import shown

# The elements xacro itself handles before it looks for a macro of that name
# (xacro/__init__.py: eval_all and handle_macro_call; tests/untrusted/test_names.py checks
# this list against the installed xacro).
XACRO_KEYWORDS = frozenset({"arg", "attribute", "call", "element", "if", "include",
                            "insert_block", "macro", "property", "unless"})
# The names the part's test file (templates/part/test_part.urdf.xacro) calls it with.
TEST_FILE_USES = ("left", "right")

_NAMED = {kind: re.compile(rf"""<{tag}\s[^>]*?\bname\s*=\s*(["'])([^"'$]*?)\1""")
          for kind, tag in (("link", "link"), ("joint", "joint"), ("macro", "xacro:macro"))}
# A package is a few dozen files; a tree with thousands is not what `new part` scans.
_MAX_FILES = 2000


def refuse_bad_part_name(root: Path, part: str) -> None:
    """UsageError with the reason if ``part`` cannot name a new part of the package."""
    if part in XACRO_KEYWORDS:
        raise UsageError(f"a part cannot be called '{part}': <xacro:{part}> is xacro's own "
                         f"element, so the part's macro could never be called; choose "
                         "another name")
    made = [("macro", part)] + [(kind, f"{part}_{use}_{kind}") for use in TEST_FILE_USES
                                for kind in ("link", "joint")]
    for path, names in _package_names(root):
        for kind, name in made:
            if name in names[kind]:
                where = shown(path.relative_to(root).as_posix())
                if kind == "macro":
                    raise UsageError(f"a part cannot be called '{part}': {where} already "
                                     f"defines the macro xacro:{name}, which the part's "
                                     "macro would replace; choose another name")
                raise UsageError(f"a part cannot be called '{part}': its {kind} {name} "
                                 f"would clash with the {kind} {name} of {where} (a "
                                 f"robot's {kind}s need distinct names); choose another "
                                 "name")


def _package_names(root: Path):
    """(file, {"link": names, "joint": names, "macro": names}) for each xacro file of the
    package that can be read: only regular files (not a FIFO that would block), within
    the input limit; names built from expressions (``${prefix}_link``) cannot be told."""
    from ..load.bounded import read_text_quietly

    paths = sorted(Path(folder) / name for folder, _dirs, names in os.walk(root / "urdf")
                   for name in names if name.endswith(".xacro"))  # links not followed
    for path in paths[:_MAX_FILES]:
        text = read_text_quietly(path) if path.is_file() else None
        if text is not None:
            yield path, {kind: {m.group(2) for m in pattern.finditer(text)}
                         for kind, pattern in _NAMED.items()}
