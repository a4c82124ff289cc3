"""xacro's warnings as mcar shows them: one line each, the "when processing file: ..."
line xacro prints after a warning folded into it, said the same by every command
(``mcar check``'s W220, ``mcar build``'s warnings)."""

from __future__ import annotations

_CONTEXT_PREFIXES = ("when processing file", "when instantiating", "included from",
                     "instantiated from", "in file")


def merged_warnings(lines: list[str]) -> list[str]:
    """xacro's warning lines, each with its context lines in brackets after it."""
    merged: list[str] = []
    for line in lines:
        text = line.strip()
        if merged and text.startswith(_CONTEXT_PREFIXES):
            merged[-1] += f" ({text})"
        else:
            merged.append(text.removeprefix("warning:").strip())
    return merged
