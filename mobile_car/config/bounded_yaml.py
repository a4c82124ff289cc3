"""YAML (and JSON, which YAML reads) with the size of the document bounded as it is composed.

A config file is a few dozen numbers, but YAML aliases let 1 KB stand for billions of
nodes ("billion laughs"): whatever walks the value afterwards (an error message's repr,
a type check) walks every copy. Nesting 50,000 deep exhausts Python's recursion. So the
composer counts nodes with every alias expanded, as they are composed, and the depth, and
stops at fixed limits with a YAMLError that has a line, before anything is constructed.

Two more refusals a config file needs: a key given twice in one mapping (YAML says keys
are unique; PyYAML silently keeps the last), and, with ``numbers_as_text``, YAML's own
number syntax: plain scalars that YAML 1.1 reads as numbers (``0x10``, ``1_000``,
``.inf``, ``0o17``, ``1:30``) stay text, so the caller reads them with the grammar of
``--set`` and a file means what the same words mean on the command line.
"""

from __future__ import annotations

import reprlib

import yaml
from yaml.composer import ComposerError
from yaml.constructor import ConstructorError
from yaml.events import AliasEvent
from yaml.nodes import MappingNode, ScalarNode

MAX_NODES = 100_000  # with aliases expanded; a config file has a few hundred
MAX_DEPTH = 100

_short = reprlib.Repr()
_short.maxstring = _short.maxother = 60
_short.maxlist = _short.maxdict = _short.maxtuple = _short.maxset = 6
_short.maxlevel = 3


def short_repr(value) -> str:
    """A repr for messages, however big or deep (or self-referencing) the value is."""
    return _short.repr(value)


class TooLarge(ComposerError):
    """The document passes MAX_NODES or MAX_DEPTH: valid YAML, refused all the same."""


class DuplicateKey(ConstructorError):
    """A mapping gives the same key twice: valid to PyYAML, an error to us."""


class BoundedLoader(yaml.SafeLoader):
    """SafeLoader that refuses documents over MAX_NODES (aliases expanded) or MAX_DEPTH."""

    def __init__(self, stream):
        super().__init__(stream)
        self._expanded = 0  # nodes composed so far, each alias counting its whole subtree
        self._sizes: dict[int, int] = {}  # id(node) -> expanded size of its subtree
        self._depth = 0

    def _refuse(self, problem: str, mark) -> None:
        raise TooLarge(None, None, problem, mark)

    def compose_node(self, parent, index):
        event = self.peek_event()
        if self._depth >= MAX_DEPTH:
            self._refuse(f"nested more than {MAX_DEPTH} levels deep", event.start_mark)
        if isinstance(event, AliasEvent):
            anchored = self.anchors.get(event.anchor)
            # An alias of a node still being composed (a cycle) counts as one node.
            size = self._sizes.get(id(anchored), 1) if anchored is not None else 1
            self._count(size, event.start_mark)
            return super().compose_node(parent, index)
        before = self._expanded
        self._count(1, event.start_mark)
        self._depth += 1
        try:
            node = super().compose_node(parent, index)
        finally:
            self._depth -= 1
        self._sizes[id(node)] = self._expanded - before
        return node

    def construct_mapping(self, node, deep=False):
        if isinstance(node, MappingNode):
            first: dict[tuple[str, str], int] = {}
            for key, _value in node.value:
                if not isinstance(key, ScalarNode) or key.tag == "tag:yaml.org,2002:merge":
                    continue  # "<<" merges may override by design
                if (key.tag, key.value) in first:
                    raise DuplicateKey(None, None, f"duplicate key {short_repr(key.value)} "
                                       f"(first given on line {first[key.tag, key.value]})",
                                       key.start_mark)
                first[key.tag, key.value] = key.start_mark.line + 1
        return super().construct_mapping(node, deep)

    def _count(self, size: int, mark) -> None:
        self._expanded += size
        if self._expanded > MAX_NODES:
            self._refuse(f"more than {MAX_NODES} values with aliases expanded (an alias "
                         "bomb?)", mark)


_NUMBER_TAGS = ("tag:yaml.org,2002:int", "tag:yaml.org,2002:float")


class NumbersAsTextLoader(BoundedLoader):
    """BoundedLoader whose plain scalars are never resolved to int or float."""


NumbersAsTextLoader.yaml_implicit_resolvers = {
    first: [(tag, regexp) for tag, regexp in resolvers if tag not in _NUMBER_TAGS]
    for first, resolvers in BoundedLoader.yaml_implicit_resolvers.items()}


def compose(text: str):
    """The document's node, bounded as :func:`compose_and_load` bounds it, nothing
    constructed: for a package's ROS parameter files, which ROS reads as PyYAML does (a
    key given twice keeps its last value: Warthog's control.yaml gives ``two_d_mode``
    twice), not as mcar's own config files are held; raises yaml.YAMLError."""
    loader = BoundedLoader(text)
    try:
        return loader.get_single_node()
    finally:
        loader.dispose()


def compose_and_load(text: str, numbers_as_text: bool = False):
    """(the document's node, its value): one pass, bounded; raises yaml.YAMLError."""
    loader = (NumbersAsTextLoader if numbers_as_text else BoundedLoader)(text)
    try:
        node = loader.get_single_node()
        if node is None:
            return None, None
        try:
            return node, loader.construct_document(node)
        except ValueError as exc:  # int() of more than 4300 digits, in PyYAML's constructor
            raise ConstructorError(None, None, " ".join(str(exc).split())[:100],
                                   node.start_mark) from None
    finally:
        loader.dispose()
