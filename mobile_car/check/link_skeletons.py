"""Links that share a skeleton share the proof that they are written the usual way.

A link's skeleton is its serialisation (libxml2's, in C) with every attribute value taken
out: its elements, their attribute names in order, what lies between them. An exporter or
a xacro macro writes every link of a kind with one skeleton, so a robot of 20,000 links
has a handful. Whether a link is written the usual way (:func:`.plain_links.gather`) is a
question of its skeleton alone; it is asked once per skeleton, of a copy of the first link
with every value replaced by a marker, which also tells where each text the proof reads
sits among the values. Every other link with that skeleton has only its values split out
of its serialisation and judged by the same code (:func:`.plain_links.judge`): the walk
of a dozen elements through lxml's proxies (most of the cost of a large robot's links) is
left out.

Why the same skeleton means the same elements with the values in the same places: in
the serialisation a double quote delimits an attribute value (one inside a value is
written ``&quot;``), but a text or comment may hold one. A skeleton is used only once the
first link's quotes are proved to be delimiters (twice as many as its attributes); a
link whose bytes outside its values are the same is then read the same way from its
first byte to its last. A value is its serialised text: a name or number with ``&`` in
it (an escaped character) is not read here; float reads none, and a name with one sends
the link to the walk, which reads it as lxml does.
"""

from __future__ import annotations

from operator import itemgetter

from lxml import etree

from .context import Reporter
from .plain_links import NO_TURN, gather, judge
from .rest_pose import LinkShapes

# Skeletons looked at before giving up: a robot with more does not repeat its links' kinds,
# and a plan costs several walks of its link.
_PLANS_KEPT = 64
_UNKNOWN = object()


class Skeletons:
    """The plans of one robot's link skeletons, by skeleton (None: not written the usual
    way, or not readable this way)."""

    def __init__(self, twins: bool = False):
        self._plans: dict = {}
        # Whether a link may be given the elements of the first of its skeleton, its own
        # element as their twin (rest_pose.LinkShapes), rather than its own: on a robot
        # whose rest pose maps back only the shapes it names (rest_pose_arrays.py).
        self.twins = twins
        self.open = True  # False once _PLANS_KEPT skeletons were met: no use asking

    def clean(self, element, text: str, report: Reporter, materials: set[str],
              top_level: set, moving: bool, is_root: bool) -> LinkShapes | None:
        """As :func:`.plain_links.plainly_clean` says of the link ``element`` (whose
        serialisation is ``text``), or None where this way cannot tell."""
        pieces = text.split('"')
        skeleton = '"'.join(pieces[::2])
        plan = self._plans.get(skeleton, _UNKNOWN)
        if plan is _UNKNOWN:
            plan = self._plans[skeleton] = _Plan.of(element, len(pieces), self.twins)
            self.open = len(self._plans) < _PLANS_KEPT
        if plan is None or len(pieces) != plan.pieces:
            return None
        values = pieces[1::2]
        values.append(NO_TURN)
        return plan.read(element, values, report, materials, top_level, moving, is_root)


class _Plan:
    """Where the texts :func:`.plain_links.gather` reads sit among a link's values (by
    their index, in document order; the one past the last is an absent xyz or rpy), and
    where its shapes and inertial sit among its elements (child indices from the link)."""

    __slots__ = ("pieces", "triples", "singles", "bodies", "inertial", "colours", "twins",
                 "model")

    def __init__(self, pieces: int, triples: list, singles: list, bodies: list,
                 inertial: tuple | None, colours: list, twins: bool):
        self.pieces = pieces  # of the serialisation split at its quotes
        self.triples = _picker(triples)  # values -> the texts of the triples, in order
        self.singles = _picker(singles)
        self.bodies = bodies  # (kind, path of its shape, shape tag, scaled, at, at_single)
        self.inertial = inertial  # (index of the <inertial>, at, at_single) or None
        self.colours = colours  # (index of the name, of the rgba or None)
        # A mesh is known by its own element (its file's bounds): no twins then.
        self.twins = twins and all(body[2] != "mesh" for body in bodies)
        self.model = None  # (bodies, inertial) of the first link found clean: see twins

    @classmethod
    def of(cls, element, pieces: int, twins: bool) -> _Plan | None:
        """The plan of ``element``'s skeleton, its serialisation split at its quotes into
        ``pieces``; None if it is not written the usual way or its quotes are not only
        delimiters."""
        marked = element.__deepcopy__(None)
        index = 0
        for node in marked.iter(etree.Element):
            for key in node.keys():
                node.set(key, f"#{index}")
                index += 1
        count = index
        if pieces != 2 * count + 1:
            return None  # a quote in a text or comment, or a namespace declared here
        gathered = gather(marked)
        if gathered is None:
            return None
        triples, singles, bodies, inertial, colours = gathered
        slots = {f"#{i}": i for i in range(count)}
        slots[NO_TURN] = count
        try:
            triples = [slots[text] for text in triples]
            singles = [slots[text] for text in singles]
            colours = [(slots[name], None if rgba is None else slots[rgba])
                       for name, rgba in colours]
        except KeyError:  # None: a number that is absent, never sound
            return None
        bodies = [(kind, _path(shape), tag, scaled, at, at_single)
                  for kind, shape, tag, scaled, at, at_single in bodies]
        if inertial is not None:
            inertial = (marked.index(inertial[0]), *inertial[1:])
        return cls(pieces, triples, singles, bodies, inertial, colours, twins)

    def read(self, element, values: list, report: Reporter, materials: set[str],
             top_level: set, moving: bool, is_root: bool) -> LinkShapes | None:
        colours = []
        for name, rgba in self.colours:
            name = values[name]
            if "&" in name:
                return None  # escaped: the walk reads the name as lxml does
            colours.append((name, None if rgba is None else values[rgba]))
        model = self.model
        if model is None:
            bodies = []
            for kind, (body, geometry, shape), tag, scaled, at, at_single in self.bodies:
                bodies.append((kind, element[body][geometry][shape], tag, scaled, at,
                               at_single))
            inertial = self.inertial
            if inertial is not None:
                inertial = (element[inertial[0]], *inertial[1:])
        else:
            bodies, inertial = model
        gathered = (self.triples(values), self.singles(values), bodies, inertial, colours)
        held = judge(gathered, report, materials, top_level, moving, is_root,
                     None if model is None else element)
        if held is not None and model is None and self.twins:
            self.model = bodies, inertial
        return held


def _picker(indices: list[int]):
    """values -> the tuple of the values at ``indices`` (one C call: itemgetter, which
    gives a lone value for one index, and cannot be made for none)."""
    if len(indices) > 1:
        return itemgetter(*indices)
    if indices:
        index = indices[0]
        return lambda values: (values[index],)
    return lambda values: ()


def _path(shape) -> tuple[int, int, int]:
    """(body, geometry, shape): the child indices that lead from the link to ``shape``."""
    geometry = shape.getparent()
    body = geometry.getparent()
    return body.getparent().index(body), body.index(geometry), geometry.index(shape)
