"""Joints that share a skeleton are read once per skeleton, as links are
(:mod:`.link_skeletons`, which says what a skeleton is and why it may stand for each joint
that has it).

A joint whose skeleton holds only what the URDF vocabulary expects (known children, each
once, with known attributes, nothing inside them) has nothing to note while reading: its
name, type, parent and child come from its values, its parts are indexed only when
something asks for them (:class:`~.urdf_reader.Joint`), and the texts the joint checks
read first (:data:`TEXTS`) come out of its values in one call. The lxml walk and the ten or
so attribute fetches a joint cost before are left out. Anything else is read element by
element, as before.
"""

from __future__ import annotations

from operator import itemgetter

from lxml import etree

# What the joint checks' quick proof reads (joints._plainly_sound), in this order.
TEXTS = (("origin", "xyz"), ("origin", "rpy"), ("axis", "xyz"), ("limit", "effort"),
         ("limit", "velocity"), ("limit", "lower"), ("limit", "upper"),
         ("dynamics", "damping"), ("dynamics", "friction"))
AXIS_XYZ = TEXTS.index(("axis", "xyz"))
_NAMES = ((None, "name"), (None, "type"), ("parent", "link"), ("child", "link"))
_PLANS_KEPT = 64  # as for links: a robot with more skeletons does not repeat its joints
_UNKNOWN = object()


class JointSkeletons:
    """The plans of one robot's joint skeletons (None: read element by element).
    ``quiet_parts(element)``: the names of a ``<joint>``'s parts if reading it notes
    nothing (urdf_reader's reading, asked of the first joint of each skeleton), else
    None."""

    def __init__(self, quiet_parts):
        self._plans: dict = {}
        self._quiet_parts = quiet_parts
        self.open = True  # False once _PLANS_KEPT skeletons were met

    def read(self, element) -> tuple | None:
        """(name, type, parent, child, tags of its parts, TEXTS) of the ``<joint>``
        ``element`` (None where absent), or None if this way cannot tell."""
        text = etree.tostring(element, encoding="unicode", with_tail=False)
        pieces = text.split('"')
        skeleton = '"'.join(pieces[::2])
        plan = self._plans.get(skeleton, _UNKNOWN)
        if plan is _UNKNOWN:
            plan = self._plans[skeleton] = _plan(element, len(pieces),
                                                 self._quiet_parts(element))
            self.open = len(self._plans) < _PLANS_KEPT
        if plan is None or len(pieces) != plan[0]:
            return None
        values = pieces[1::2]
        values.append(None)  # what an absent attribute reads
        names = plan[1](values)
        if "&" in text:  # (one scan of the text: most joints have no escape anywhere)
            for name in names:
                if name is not None and "&" in name:
                    return None  # escaped: read as lxml reads it
        return (*names, plan[2], plan[3](values))


def _plan(element, pieces: int, parts: frozenset | None) -> tuple | None:
    """(pieces, names getter, tags of the parts, TEXTS getter) for ``element``'s skeleton,
    ``parts`` the names of its parts (None: reading it notes something); None if a joint
    of it would have something noted, or its quotes are not only delimiters."""
    if parts is None:
        return None
    index, slots = 0, {}
    for node in element.iter(etree.Element):
        tag = None if node is element else node.tag
        for key in node.keys():
            slots[tag, key] = index
            index += 1
    if pieces != 2 * index + 1:
        return None  # a quote in a comment or text, or a namespace declared here
    absent = index  # the None appended after the values

    def getter(wanted):
        return itemgetter(*[slots.get(key, absent) for key in wanted])

    return pieces, getter(_NAMES), parts, getter(TEXTS)
