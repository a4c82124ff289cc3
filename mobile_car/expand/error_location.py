"""Where an xacro error is: xacro knows the file (sometimes), mcar finds the line.

xacro raises many kinds of exceptions, most with only a message; this turns each into one
:class:`~mobile_car.errors.BuildError` with ``FILE:LINE`` (found by searching the files on
xacro's macro and include stacks for the text the message quotes) and the stack itself.
"""

from __future__ import annotations

import os
import re
import xml.parsers.expat
from pathlib import Path

import xacro

from ..errors import BuildError, McarError
from ..load.bounded import NotRegularFile, read_text_quietly
from ..load.inputs import STDIN_LABEL, display_path

_QUOTED_RE = re.compile(r"'([^']+)'")
_COMMENT_RE = re.compile(r"<!--.*?-->", re.S)
_MAX_STACK_LINES = 8


def error_from(exc: BaseException, parsing: list, source: Path,
               calls: list[tuple[str, str, int]] = ()) -> McarError:
    """Turn whatever xacro raised into one located BuildError (or the McarError inside).
    ``calls``: (macro, file, line) of the macro calls being expanded, innermost first
    (see :mod:`.origins`), said in the stack."""
    inner = getattr(exc, "exc", None)
    if isinstance(inner, NotRegularFile):  # an include: said and located as a missing one
        file, line = _locate(source, [os.path.basename(inner.path)])
        return BuildError(f"cannot read {display_path(inner.path)}: {inner.message}",
                          file=file, line=line, details=_stack_details(calls))
    if isinstance(exc, McarError) or isinstance(inner, McarError):
        error = exc if isinstance(exc, McarError) else inner
        if error.file is None:  # say which file asked for the package, and where
            error.file, error.line = _locate(source, _needles(error.message))
        return error
    if isinstance(inner, OSError) and inner.filename:
        exc = BuildError(f"cannot read {display_path(inner.filename)}: "
                         f"{inner.strerror or inner}{_sandbox_hint(inner)}")
        needles = [os.path.basename(str(inner.filename))]
    else:
        needles = _needles(str(exc))
    decode = exc if isinstance(exc, UnicodeDecodeError) else inner
    if isinstance(decode, UnicodeDecodeError) and isinstance(decode.object, bytes):
        from ..load.encoding import not_utf8

        bad = parsing[-1] if parsing and parsing[-1] else str(source)
        message, line = not_utf8(decode.object, decode.start)
        return BuildError(message, file=display_path(bad), line=line, details=_stack_details(calls))
    if isinstance(exc, xml.parsers.expat.ExpatError):
        bad = parsing[-1] if parsing and parsing[-1] else str(source)
        encoding = _encoding_error(bad, exc)
        if encoding is not None:
            return BuildError(encoding[0], file=display_path(bad), line=encoding[1],
                              details=_stack_details(calls))
        message = xml.parsers.expat.ErrorString(exc.code) if exc.code else str(exc)
        nesting = _nesting_error(bad, exc, message)
        if nesting is not None:
            return BuildError(nesting[0], file=display_path(bad), line=nesting[1],
                              details=_stack_details(calls))
        return BuildError(f"XML parse error: {message} (column {exc.offset + 1})",
                          file=display_path(bad), line=exc.lineno, details=_stack_details(calls))
    if isinstance(exc, RecursionError):
        macros = list(xacro.macrostack or [])
        files = [f for f in (xacro.filestack or []) if f]
        if macros:
            needles = [f"<xacro:{macros[-1].body.getAttribute('name')}"]
        else:
            needles = [os.path.basename(files[-1])] if files else []
        file, line = _locate(source, needles)
        return BuildError("recursion too deep: a macro or an include that calls itself?",
                          file=file, line=line, details=_stack_details(calls))
    message = " ".join(str(exc).split()) or type(exc).__name__
    if isinstance(exc, xacro.XacroException):  # a call's mistake: said at the call
        from .call_errors import call_error

        at_call = call_error(message, calls, _stack_details(calls))
        if at_call is not None:
            return at_call
    if isinstance(inner, MemoryError) or isinstance(exc, MemoryError):
        message = f"out of memory {message}".strip()
    # xacro.fatal("...") is the author's own message: xacro's "when evaluating" adds noise.
    message = re.sub(r" when evaluating expression 'xacro\.fatal\(.*$", "", message)
    file, line = _locate(source, needles)
    return BuildError(message, file=file, line=line, details=_stack_details(calls))


def _locate(source: Path, needles: list[str]) -> tuple[str, int | None]:
    """The file and line an xacro error is about, as well as text search can tell."""
    # Inside a macro the faulty text is in the macro's own file; else in the current file.
    macros = list(xacro.macrostack or [])
    candidates = []
    if macros and macros[-1].history:
        candidates.append(macros[-1].history[-1][-1])
    candidates += [f for f in reversed(xacro.filestack or []) if f]
    candidates.append(str(source))
    for candidate in candidates:
        line = _find_line(candidate, needles)
        if line:
            return display_path(candidate), line
    return display_path(candidates[0]), None


def _needles(message: str) -> list[str]:
    """Fragments of an xacro message worth searching the source for, most specific first."""
    needles = []
    match = re.search(r"when evaluating expression '(.+)'", message, re.S)
    if match:
        needles += ["${" + match.group(1) + "}", match.group(1)]
    match = re.search(r"Undefined substitution argument (\S+)", message)
    if match:
        needles.append(f"$(arg {match.group(1)})")
    match = re.search(r"No such file or directory: (\S+)", message)
    if match:
        needles.append(os.path.basename(match.group(1).rstrip("'")))
    match = re.search(r"unknown macro name:? (\S+)", message)
    if match:
        needles.append(f"<{match.group(1)}")
    match = re.search(r"package '([^']+)' not found", message)
    if match:
        needles.append(f"find {match.group(1)}")
    needles += [q for q in _QUOTED_RE.findall(message) if len(q) > 1]
    return needles


def _find_line(path: str | None, needles: list[str]) -> int | None:
    if not path or not needles:
        return None
    text = read_text_quietly(path)
    if text is None:
        return None
    # A comment that mentions the name is not where the error is: blank comments out,
    # keeping their newlines so line numbers stay right.
    lines = _COMMENT_RE.sub(lambda m: "\n" * m.group(0).count("\n"), text).splitlines()
    for needle in needles:
        for number, text in enumerate(lines, start=1):
            if needle in text:
                return number
    return None


def _stack_details(calls: list[tuple[str, str, int]] = ()) -> list[str]:
    """xacro's macro and include stack, innermost first, as print_location would say it,
    with the line each macro was called at."""
    details = []
    macros = list(xacro.macrostack or [])
    # Both stacks start at the outermost call; the calls may hold one more, innermost
    # (a call that failed before xacro entered it).
    outer_first = list(reversed(calls))
    for i, macro in enumerate(reversed(macros)):
        defined = macro.history[-1][-1] if macro.history else None
        verb = "when instantiating macro:" if i == 0 else "instantiated from:"
        name = macro.body.getAttribute("name")
        depth = len(macros) - 1 - i
        called = ""
        if depth < len(outer_first) and outer_first[depth][0] in (name,
                                                                  name.removeprefix("xacro:")):
            _, file, line = outer_first[depth]
            called = f", called at {display_path(file)}:{line}"
        details.append(f"{verb} {name} "
                       f"({display_path(defined) if defined else '???'}){called}")
    files = [f for f in (xacro.filestack or []) if f]
    for i, name in enumerate(reversed(files)):
        verb = ("in file:" if macros else "when processing file:") if i == 0 else "included from:"
        details.append(f"{verb} {display_path(name)}")
    return _collapse_repeats(details)


def _collapse_repeats(lines: list[str]) -> list[str]:
    """A runaway recursion repeats one stack line hundreds of times: say it once."""
    out: list[str] = []
    count = 0
    for i, line in enumerate(lines):
        count += 1
        if i + 1 < len(lines) and lines[i + 1] == line:
            continue
        out.append(line if count == 1 else f"{line} (x{count})")
        count = 0
    if len(out) > _MAX_STACK_LINES:  # a loop through several files or macros
        hidden = len(out) - _MAX_STACK_LINES + 1
        out = out[: _MAX_STACK_LINES - 1] + [f"... and {hidden} more (a loop?)"]
    return out


def _sandbox_hint(error: OSError) -> str:
    """A read the sandbox refused looks like any EACCES: say where reading is allowed."""
    import errno

    from . import sandbox

    if error.errno != errno.EACCES or sandbox.is_trusted() or not sandbox.support().landlock_abi:
        return ""
    return (" (the xacro sandbox reads only below the package roots and the input's "
            "folder; --no-sandbox for a tree you trust)")


def _encoding_error(path: str, exc) -> tuple[str, int] | None:
    """expat's "invalid token" where the real fault is a byte that is not UTF-8."""
    if exc.code != xml.parsers.expat.errors.codes[xml.parsers.expat.errors.XML_ERROR_INVALID_TOKEN]:
        return None
    from ..load.bounded import read_head
    from ..load.encoding import first_bad_offset, not_utf8

    try:
        data = read_head(path, 16 * 1024 * 1024)
    except (OSError, McarError):
        return None
    if data.startswith(b"<?xml") and b"encoding" in data[:data.find(b"?>")]:
        return None  # a declared encoding: expat decoded it as declared
    start = first_bad_offset(data)
    return None if start is None else not_utf8(data, start)


def _nesting_error(path: str, exc, message: str) -> tuple[str, int] | None:
    """A tag left open is said at the line it opened, where the mistake is (expat notices
    it at a later end tag, often the file's last line); a misspelt end tag at its own."""
    from .unclosed import find_unclosed

    if path == STDIN_LABEL:  # read once, from the pipe: a file of that name is another
        return None
    found = find_unclosed(path, exc)
    if found is None:
        return None
    if found.stray_end is not None:
        return (f"XML parse error: </{found.stray_end}> closes no open element (expected "
                f"</{found.name}>, opened at line {found.line}; {message}, column "
                f"{exc.offset + 1})", exc.lineno)
    return (f"XML parse error: <{found.name}> opened here is never closed (the parser "
            f"noticed at line {exc.lineno}: {message})", found.line)
