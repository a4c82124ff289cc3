"""Unknown elements and attributes (likely typos), and repeated elements urdfdom ignores.

urdfdom reads the elements it knows and skips the rest without a word, so ``<visul>`` or
``<origin xzy=...>`` silently becomes "no visual" or "origin at zero". The reader notes
everything outside the URDF 1.0 vocabulary (:mod:`mobile_car.check.urdf_vocabulary`) while it
reads; this module words the notes, with a did-you-mean from difflib. The contents of
extension elements (``<gazebo>``, ``<transmission>``, ``<ros2_control>``, ``<sensor>``)
and of other XML namespaces (``xacro:`` is E105) are not checked.
"""

from __future__ import annotations

from .context import Reporter
from .urdf_model import tag_name
from .urdf_reader import Anomalies, Robot
from .urdf_vocabulary import EXTENSIONS, ROBOT, SPECS


def _suggest(name: str, known) -> str:
    import difflib  # only for a name it does not know

    close = difflib.get_close_matches(name, sorted(known), n=1, cutoff=0.6)
    return f"; did you mean '{close[0]}'?" if close else ""


def check_schema(robot: Robot, report: Reporter, macros=frozenset) -> None:
    """W201 unknown element, W202 unknown attribute, W209 repeated element.

    ``macros()`` gives the names of the xacro macros of the package the file lies in
    (asked only when an element is unknown): a top-level element named like one is a
    macro call xacro 2 left unexpanded, and the message says so."""
    top_level = set(ROBOT.children) | EXTENSIONS
    for element in robot.others:
        if element.tag in EXTENSIONS:
            continue
        if element.tag in macros():
            report.add("W201", element, f"unknown element <{element.tag}> in <robot>: the "
                                        f"macro '{element.tag}' of this package, called "
                                        "without the xacro: prefix? xacro 2 copies such "
                                        f"calls unexpanded: write <xacro:{element.tag} ...>")
            continue
        _unknown(element, robot.element, top_level, report)
    report_anomalies(robot.anomalies, report)


def report_anomalies(notes: Anomalies, report: Reporter) -> None:
    """Word what the reader noted (:class:`~mobile_car.check.urdf_reader.Anomalies`)."""
    for element, parent, spec in notes.unknown:
        _unknown(element, parent, spec.children, report)
    for element in notes.attributes:
        known = SPECS[element.tag].attrs
        for attr in element.keys():
            if attr not in known and attr[0] != "{":  # other namespaces: not URDF's
                report.add("W202", element, f"<{tag_name(element)}> has unknown attribute "
                                            f"'{attr}'{_suggest(attr, known)}")
    for element in notes.repeats:
        report.add("W209", element, f"second <{element.tag}> in "
                                    f"<{tag_name(element.getparent())}>; urdfdom reads only "
                                    "the first")


def _unknown(element, parent, known, report: Reporter) -> None:
    tag = element.tag
    if tag[0] == "{":  # xacro:... is E105; other namespaces are extensions
        return
    report.add("W201", element, f"unknown element <{tag}> in <{tag_name(parent)}>"
                                f"{_suggest(tag, known)}")
