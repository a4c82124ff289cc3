"""Read and check what is inside the links (inertials, visuals, collisions): most of a
robot's elements, read only by ``mcar check`` (``mcar tree`` needs none of it).

Robots repeat parts: wheels, fingers, track segments, the segments of a generated chain.
A link whose content (everything between ``<link ...>`` and ``</link>``) is byte for byte
that of a link already found clean, in the same role (moving or not, root or not), is
clean too: every check of a link's content depends on that content, on those two roles
and on the materials defined before it in the same robot, which only grow. Such a link is
not read again: serialising it to compare (libxml2, in C) costs a tenth of reading it. A
robot that turns out not to repeat itself is not compared any further. A link written the
usual way is proved clean by :mod:`mobile_car.check.plain_links` (on a large robot, once per
skeleton: :mod:`mobile_car.check.link_skeletons`); only the others are read into
:class:`~mobile_car.check.urdf_reader.Link` parts and put through every check, with messages.
"""

from __future__ import annotations

from lxml import etree

from .context import Reporter
from .inertia import check_inertia
from .links import check_links
from .plain_links import plainly_clean
from .rest_pose import LinkShapes, link_shapes
from .schema import report_anomalies
from .urdf_reader import Anomalies, Link, read_links
from .urdf_vocabulary import LINK

# Links looked at before giving up comparing, on a robot with fewer than 10% repeats.
_TRIAL = 500
# Links from which a robot's links are proved plain once per skeleton: below, the plans
# cost more than they save. From TWINS_FROM (checker.LARGE_ROBOT: the rest pose is worked
# out with numpy, which maps back to a link's own elements only the shapes it names), a
# link is given the elements of the first of its skeleton, its own as their twin.
SKELETONS_FROM = 200
TWINS_FROM = 2000


def check_link_bodies(links: list[Link], report: Reporter, materials: set[str],
                      top_level: set, moving: set[str], root: str | None
                      ) -> dict[str, LinkShapes]:
    """Read ``links`` and check their geometry, materials, inertia and vocabulary; return
    what each holds, read (for the rest pose: :mod:`.rest_pose`), by link name."""
    notes = Anomalies()
    held: dict[str, LinkShapes] = {}
    # Per robot: whether a material is defined depends on the robot, not on the content.
    # A clean content's shapes are those of every link with that content.
    clean: dict = {}
    compare, repeats = True, 0
    skeletons = None
    if len(links) >= SKELETONS_FROM:
        # Imported here: a small robot's check (most runs) does without the module.
        from .link_skeletons import Skeletons

        skeletons = Skeletons(len(links) >= TWINS_FROM)
    for count, link in enumerate(links):
        element = link.element
        if count == _TRIAL and repeats * 10 < _TRIAL:
            compare = False  # serialising every link would cost more than it saves
        if skeletons is not None and not skeletons.open:
            skeletons = None
        text = _serialised(element) if compare or skeletons is not None else None
        key = (_content(text), link.name in moving, link.name == root) if compare else None
        known = clean.get(key) if key is not None else None
        if known is not None:
            repeats += 1
            if not LINK.attrs_ok(element.keys()):  # the start tag is not in the key
                notes.attributes.append(element)
            held[link.name] = LinkShapes(known.bodies, known.inertial, element)
            continue
        shapes = None
        if skeletons is not None:
            shapes = skeletons.clean(element, text, report, materials, top_level,
                                     link.name in moving, root is not None and link.name == root)
        if shapes is None:
            shapes = plainly_clean(element, report, materials, top_level, link.name in moving,
                                   root is not None and link.name == root)
        if shapes:  # (None, or False where a test turns the quick proof off)
            held[link.name] = clean[key] = shapes
            continue
        before = _counts(report, notes)
        read_links([link], notes)
        check_links([link], report, materials, top_level)
        check_inertia([link], report, moving, root)
        held[link.name] = shapes = link_shapes(element)
        if key is not None and _counts(report, notes) == before:
            clean[key] = shapes
    report_anomalies(notes, report)
    return held


def _serialised(element) -> str:
    return etree.tostring(element, encoding="unicode", with_tail=False)


def _content(text: str) -> str:
    """What lies between a serialised link's start tag and its end."""
    return text[text.index(">") + 1:]


def _counts(report: Reporter, notes: Anomalies) -> tuple[int, int, int, int]:
    return (len(report.diagnostics), len(notes.unknown), len(notes.attributes),
            len(notes.repeats))
