"""Where each element of an expanded URDF was written: file, line, and the macro calls
that put it there, recorded while the real xacro expands.

xacro keeps no line numbers: it parses with minidom, knows the file being processed
(``filestack``) and the files a macro was defined in (``Macro.history``), and clones a
macro's body at every call. So the lines are recorded here, as xacro runs:

* each file xacro parses is parsed by minidom's own expat builder, told to mark every
  element with its line (an attribute, so that it survives xacro's ``cloneNode`` of
  macro bodies and blocks); xacro's directives (``xacro:property``, ``xacro:if``, ...)
  are left unmarked, as xacro checks their attributes;
* each macro call takes its mark off (xacro refuses unknown parameters) and becomes the
  innermost call while its body is evaluated;
* each element xacro evaluates gets, once, the calls it is evaluated in: an element
  written in a macro and expanded at four calls has four origins, one line apart in
  nothing but the call. Block arguments get theirs before the call is entered: they are
  written at the caller's.

After the expansion every element is read in document order (the order of the URDF
text) and the marks are taken out. The result, :class:`Origins`, is plain data: the
sandboxed child sends it to the parent, which checks every index and every file name
against the files the build read before using it (:func:`Origins.from_wire`).
"""

from __future__ import annotations

import os
from xml.dom import expatbuilder

from ..load.inputs import STDIN_LABEL
from ..values import Value

# The xacro elements xacro checks the attributes of: never marked. Every other element
# is (xacro:element and xacro:call too: they become elements or calls).
_UNMARKED = frozenset(f"xacro:{name}" for name in (
    "include", "property", "macro", "arg", "attribute", "if", "unless", "insert_block"))
MARK = "mcar_origin_"  # an attribute name no URDF or xacro uses
# Bounds of what may come back from the child (a PR2 has ~10,000 elements): beyond them
# the expansion comes back without origins, and diagnostics name the input file only.
MAX_ELEMENTS = 2_000_000
MAX_SITES = 1_000_000
MAX_CALLS = 500_000
MAX_FILES = 100_000
MAX_NAME_CHARS = 1024
_MAX_WIRE_INTS = 3_000_000  # ~20 MB of JSON at most; the frame's header allows 8 MB...
_MAX_HEADER_INTS = 1_000_000  # ...so the child sends at most this many


class Origins(Value):
    """Element ``i`` of the URDF (document order) was written at ``site(i)``.

    ``calls[k]`` = (file, line, macro name, outer call or -1): a macro call, at the
    file and line of its element; ``sites[k]`` = (file, line, innermost call or -1);
    ``of[i]`` = the site of element ``i``, or -1. Files are named as xacro read them.
    """

    _fields = __slots__ = ("files", "names", "calls", "sites", "of")
    files: tuple[str, ...]
    names: tuple[str, ...]
    calls: tuple[tuple[int, int, int, int], ...]
    sites: tuple[tuple[int, int, int], ...]
    of: tuple[int, ...]

    def __init__(self, files: tuple[str, ...], names: tuple[str, ...],
                 calls: tuple[tuple[int, int, int, int], ...],
                 sites: tuple[tuple[int, int, int], ...], of: tuple[int, ...]):
        self._set(files, names, calls, sites, of)

    def site(self, index: int) -> tuple[str, int, list[tuple[str, str, int]]] | None:
        """(file, line, [(macro, file, line) of each call, innermost first]) of element
        ``index``, or None when it has none."""
        if not 0 <= index < len(self.of) or self.of[index] < 0:
            return None
        file, line, call = self.sites[self.of[index]]
        chain = []
        while call >= 0:
            call_file, call_line, name, call = self.calls[call]
            chain.append((self.names[name], self.files[call_file], call_line))
        return self.files[file], line, chain

    def to_wire(self) -> dict | None:
        """A JSON value for the child's frame; None when over the bounds."""
        ints = 4 * len(self.calls) + 3 * len(self.sites) + len(self.of)
        if ints > _MAX_HEADER_INTS or len(self.files) > MAX_FILES:
            return None
        return {"files": list(self.files), "names": list(self.names),
                "calls": [n for call in self.calls for n in call],
                "sites": [n for site in self.sites for n in site], "of": list(self.of)}

    @classmethod
    def from_wire(cls, value, allowed_files: set[str]) -> Origins | None:
        """The origins the child sent, every field checked (ValueError says which is
        wrong); files must be among ``allowed_files`` (the files the build read)."""
        if value is None:
            return None
        if not isinstance(value, dict) or set(value) != {"files", "names", "calls", "sites",
                                                           "of"}:
            raise ValueError("its origins have the wrong fields")
        files, names = value["files"], value["names"]
        if not _strings(files, MAX_FILES) or not _all_read(files, allowed_files):
            raise ValueError("its origins name a file the build did not read")
        if not _strings(names, MAX_CALLS) or any(len(n) > MAX_NAME_CHARS for n in names):
            raise ValueError("its origins' macro names are not short strings")
        flat = [value["calls"], value["sites"], value["of"]]
        if not all(isinstance(v, list) for v in flat) or \
                sum(map(len, flat)) > _MAX_WIRE_INTS or \
                not all(type(n) is int for v in flat for n in v):
            raise ValueError("its origins are not lists of integers")
        calls = _rows(value["calls"], 4, MAX_CALLS)
        sites = _rows(value["sites"], 3, MAX_SITES)
        of = tuple(value["of"])
        if calls is None or sites is None or len(of) > MAX_ELEMENTS:
            raise ValueError("its origins are too many")
        for k, (file, line, name, outer) in enumerate(calls):
            # An outer call comes before its inner ones: no loop can be sent.
            if not (0 <= file < len(files) and 0 < line < 1 << 31
                    and 0 <= name < len(names) and -1 <= outer < k):
                raise ValueError("its origins hold a call out of range")
        for file, line, call in sites:
            if not (0 <= file < len(files) and 0 < line < 1 << 31 and -1 <= call < len(calls)):
                raise ValueError("its origins hold a site out of range")
        if not all(-1 <= index < len(sites) for index in of):
            raise ValueError("its origins point at no site")
        return cls(tuple(files), tuple(names), calls, sites, of)


def _all_read(files: list[str], allowed_files: set[str]) -> bool:
    """Whether every file is one of ``allowed_files``, compared as files, not spellings:
    xacro names an include as written (``./inner.xacro``, ``sub//inner.xacro``; from stdin
    ``./inner.xacro`` for ``inner.xacro``), the list of files read may spell it otherwise.
    A name spelt as listed is taken as it is; only the others are resolved (the child
    shares the parent's working folder, so a relative name means the same file to both)."""
    resolved = None
    for name in files:
        if name in allowed_files:
            continue
        if resolved is None:
            resolved = {os.path.realpath(allowed) for allowed in allowed_files}
        if os.path.realpath(name) not in resolved:
            return False
    return True


def _strings(value, most: int) -> bool:
    return isinstance(value, list) and len(value) <= most and \
        all(isinstance(item, str) and "\0" not in item for item in value)


def _rows(flat: list[int], width: int, most: int) -> tuple | None:
    if len(flat) % width or len(flat) // width > most:
        return None
    return tuple(tuple(flat[i:i + width]) for i in range(0, len(flat), width))


class _LineBuilder(expatbuilder.ExpatBuilderNS):
    """minidom's own builder (what ``xml.dom.minidom.parse`` uses), marking elements."""

    def __init__(self, mark):
        super().__init__()
        self._mark = mark

    def start_element_handler(self, name, attributes):
        # expat names a namespaced element "URI LOCAL PREFIX": the tag is PREFIX:LOCAL.
        if " " in name:
            _, local, *prefix = name.split(" ")
            tag = f"{prefix[0]}:{local}" if prefix else local
        else:
            tag = name
        if tag not in _UNMARKED:  # the mark goes in with the element's own attributes
            attributes = [*attributes, MARK, self._mark(self._parser.CurrentLineNumber)]
        super().start_element_handler(name, attributes)


class OriginRecorder:
    """Records origins during one expansion; its three hooks wrap xacro's ``parse``,
    ``handle_macro_call`` and ``eval_all`` (see :mod:`.xacro_build`'s session)."""

    def __init__(self):
        self._files: dict[str, int] = {}
        self._names: dict[str, int] = {}
        self._calls: dict[tuple, int] = {}
        self._sites: dict[tuple, int] = {}
        self._site_rows: list[tuple[int, int, int]] = []
        self._written: list[tuple[int, int]] = []  # "w<k>": (file, line) as parsed
        self._stack: list[int] = []  # the calls being expanded, innermost last
        # Every mark this recorder wrote, as written ("w12", "s3") -> ("w", 12): one
        # lookup reads a mark back (it is read at every element xacro evaluates).
        self._marks: dict[str, tuple[str, int]] = {}

    def parse(self, inp, filename, original):
        """xacro's ``parse(inp, filename)``, the elements marked with their lines."""
        if not isinstance(inp, str) and not hasattr(inp, "read"):
            return original(inp, filename)  # a document already, or xacro opens the file
        file = self._intern(self._files, filename if filename else STDIN_LABEL)

        def mark(line: int) -> str:
            self._written.append((file, line))
            text = f"w{len(self._written) - 1}"
            self._marks[text] = ("w", len(self._written) - 1)
            return text

        builder = _LineBuilder(mark)
        return builder.parseString(inp) if isinstance(inp, str) else builder.parseFile(inp)

    def handle_macro_call(self, original):
        def handle(node, macros, symbols):
            where = self._where(node) if node.tagName.startswith("xacro:") and \
                node.tagName != "xacro:call" else None  # xacro:call comes back renamed
            if where is None:
                return original(node, macros, symbols)
            node.removeAttribute(MARK)  # xacro refuses parameters it does not know
            file, line = where
            for inner in node.getElementsByTagName("*"):  # block arguments: the caller's
                self._settle(inner)
            name = self._intern(self._names, node.tagName[len("xacro:"):])
            outer = self._stack[-1] if self._stack else -1
            self._stack.append(self._intern(self._calls, (file, line, name, outer)))
            # Left on the stack when xacro fails, as xacro leaves its macrostack: the
            # error then says which calls it happened in (active_calls).
            handled = original(node, macros, symbols)
            self._stack.pop()
            return handled

        return handle

    def active_calls(self) -> list[tuple[str, str, int]]:
        """(macro, file, line) of each call being expanded, innermost first: after an
        error, the calls it happened in."""
        rows, names, files = list(self._calls), list(self._names), list(self._files)
        return [(names[rows[k][2]], files[rows[k][0]], rows[k][1])
                for k in reversed(self._stack)]

    def eval_all(self, original):
        def evaluate(node, macros, symbols):
            self._settle(node)
            return original(node, macros, symbols)

        return evaluate

    def _settle(self, node) -> None:
        """Give an element written at (file, line) the calls it is expanded in, once."""
        mark = self._mark_of(node)
        if mark is not None and mark[0] == "w":
            file, line = self._written[mark[1]]
            site = (file, line, self._stack[-1] if self._stack else -1)
            index = self._sites.get(site)
            if index is None:
                index = self._sites[site] = len(self._site_rows)
                self._site_rows.append(site)
                self._marks[f"s{index}"] = ("s", index)
            node.setAttribute(MARK, f"s{index}")

    def _where(self, node) -> tuple[int, int] | None:
        """(file, line) an element was written at, or None."""
        mark = self._mark_of(node)
        if mark is None:
            return None
        return self._written[mark[1]] if mark[0] == "w" else self._site_rows[mark[1]][:2]

    def _mark_of(self, node) -> tuple[str, int] | None:
        """("w", k) as parsed, ("s", k) settled, or None: no mark, or one that is not
        ours, as this recorder wrote it (a xacro:attribute can write any attribute: it
        moves nothing but a line)."""
        if node.nodeType != node.ELEMENT_NODE:
            return None
        return self._marks.get(node.getAttribute(MARK))

    @staticmethod
    def _intern(table: dict, key) -> int:
        index = table.get(key)
        if index is None:
            index = table[key] = len(table)
        return index

    def collect(self, document) -> Origins:
        """The origins of every element of the expanded ``document``, in document order;
        the marks are taken out of it."""
        root = document.documentElement
        of = []
        for element in [root, *root.getElementsByTagName("*")]:
            self._settle(element)  # nothing evaluated it (xacro does, all): top level
            mark = self._mark_of(element)
            if element.hasAttribute(MARK):
                element.removeAttribute(MARK)
            of.append(mark[1] if mark is not None and mark[0] == "s" else -1)
        return Origins(tuple(self._files), tuple(self._names), tuple(self._calls),
                       tuple(self._site_rows), tuple(of))
