"""xacro's macro-call errors, said at the call and in the caller's words.

xacro checks a call's attributes and blocks against the macro's ``params`` and says
``Invalid parameter "radus"``, ``Undefined parameters [reflect]`` (older xacro:
``Parameters [reflect] were not set``), ``Not enough blocks`` or ``Unused block "x"``,
all raised while the macro is on its stack, so a location found by text search lands in
the macro's own file, on no line. The mistake is the call's: this names the call's file
and line (recorded as xacro ran, see :mod:`.origins`), the macro, a did-you-mean for a
misspelt parameter, and what a block is for a missing one.
"""

from __future__ import annotations

import difflib
import re

import xacro

from ..errors import BuildError
from ..load.inputs import display_path

_INVALID = re.compile(r'^Invalid parameter "([^"]+)"')
_UNDEFINED = re.compile(r"^(?:Undefined parameters|Parameters) \[([^\]]*)\]")
_UNUSED_BLOCK = re.compile(r'^Unused block "([^"]+)"')
_NOT_ENOUGH = "Not enough blocks"


def call_error(message: str, calls: list[tuple[str, str, int]],
               details: list[str]) -> BuildError | None:
    """The BuildError for one of xacro's call errors, located at the call; None for any
    other message, or when the failing call's place is not known."""
    macros = list(xacro.macrostack or [])
    if not macros or not calls:
        return None
    macro = macros[-1]
    name = macro.body.getAttribute("name")
    called, file, line = calls[0]
    if called.removeprefix("xacro:") != name.removeprefix("xacro:"):
        return None  # the innermost call recorded is not the one that failed
    params = list(macro.params)
    defaults = getattr(macro, "defaultmap", {}) or {}
    # A parameter with a default is shown as the macro's params="..." writes it.
    plain = [_with_default(p, defaults.get(p)) for p in params if not p.startswith("*")]
    blocks = [p for p in params if p.startswith("*")]
    text = _said(message, name, plain, blocks)
    if text is None:
        return None
    return BuildError(text, file=display_path(file), line=line, details=details)


def _with_default(param: str, default) -> str:
    """"axis:=z" for a parameter with a default, as a macro's params="..." writes it."""
    if not default:
        return param
    forward, value = default  # xacro's parse_macro_arg: p:=d, p:=^|d, p:=^
    if forward is None:
        return f"{param}:={value}"
    return f"{param}:=^|{value}" if value is not None else f"{param}:=^"


def _said(message: str, name: str, plain: list[str], blocks: list[str]) -> str | None:
    call = f"<xacro:{name}>"
    if match := _INVALID.match(message):
        wrong = match.group(1)
        close = difflib.get_close_matches(wrong, [p.partition(":=")[0] for p in plain], n=1)
        hint = f" (did you mean '{close[0]}'?)" if close else ""
        return (f"{call} sets '{wrong}', which macro '{name}' does not take{hint}; "
                f"it takes {_listed(plain, blocks)}")
    if match := _UNDEFINED.match(message):
        missing = [p.strip() for p in match.group(1).split(",") if p.strip()]
        words = ", ".join(f"{p}=" for p in missing)
        return (f"{call} does not set {words}: macro '{name}' needs "
                f"{'it' if len(missing) == 1 else 'them'} (it takes {_listed(plain, blocks)})")
    if message.startswith(_NOT_ENOUGH):
        single = [b for b in blocks if not b.startswith("**")]
        wanted = ", ".join(single) or "a block"
        element = single[0].lstrip("*") if single else "origin"
        return (f"{call} gives fewer blocks than macro '{name}' takes ({wanted}): a block "
                f"is an element written inside the call, e.g. <xacro:{name} ...> "
                f"<{element} .../> </xacro:{name}>, one per block, in order")
    if match := _UNUSED_BLOCK.match(message):
        takes = f"its blocks: {', '.join(blocks)}" if blocks else "it takes no block"
        return (f"{call} holds <{match.group(1)}>, one element more than macro '{name}' "
                f"takes as blocks ({takes})")
    return None


def _listed(plain: list[str], blocks: list[str]) -> str:
    """"name, reflect, parent and block *origin"."""
    words = list(plain)
    if blocks:
        words.append(f"block{'s' if len(blocks) > 1 else ''} {', '.join(blocks)}")
    if not words:
        return "nothing"
    return words[0] if len(words) == 1 else ", ".join(words[:-1]) + " and " + words[-1]
