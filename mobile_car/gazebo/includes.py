"""What in a robot would make libsdformat read a file, refused before the Gazebo helper runs.

libsdformat (12) copies each ``<gazebo>`` block of a URDF into the SDF it makes, then reads
that SDF as it reads any: an ``<include>`` there names a model (a path, a ``file://`` or
``model://`` URI, a name on ``SDF_PATH``) that it looks up on disk, opens and merges into
the robot (``parser.cc``, ``readXml``), and an ``<include>`` of a file that is not a model
(``/etc/passwd``) still gets opened and its parse error says it exists. Nothing else a URDF
can hold makes it open a file: mesh, texture and plugin names are copied as text for
Gazebo to load later. mcar's helper reads no file (docs/security.md), so a robot with an
``<include>`` anywhere is refused here with its line (rule E152) and never reaches
libsdformat; the helper's own seccomp filter (helpers/mcar-sdformat.cc) would refuse the
open anyway, silently.

Any element whose local name is ``include`` counts, in any namespace: tinyxml2, which
libsdformat uses, does not know namespaces, so ``<include xmlns="...">`` is an include to
it. A URDF lxml cannot parse is searched as bytes: what libsdformat would still read must
not slip through because mcar's parser gave up first.
"""

from __future__ import annotations

import re

from ..errors import GazeboError

RULE = "E152"
# "<include" or "<prefix:include" followed by what may end an XML name.
_INCLUDE_BYTES = re.compile(rb"<\s*(?:[^\s<>/:=\"']+:)?include(?=[\s/>])")


def includes(root) -> list:
    """The elements of the tree under ``root`` (an lxml element) named ``include``."""
    return [element for element in root.iter()
            if isinstance(element.tag, str) and element.tag.rpartition("}")[2] == "include"]


def refusal(element) -> str:
    """Why ``element`` (an ``<include>``) is refused: what it names, and what to do."""
    uri = (element.findtext("uri") or element.findtext("{*}uri") or "").strip()
    named = f" of {uri}" if uri else ""
    if len(named) > 200:
        named = named[:200] + "..."
    return (f"<include>{named}: libsdformat would read that file or model folder from "
            "disk into the robot, and mcar's Gazebo helper reads no file; include the "
            "model from the Gazebo world or launch file instead")


def refuse_includes(urdf: bytes, label: str, locate=None) -> None:
    """GazeboError (exit 1) at the first ``<include>`` of ``urdf``, located through
    ``locate`` (element -> (file, line, note), a built xacro's source map) where given,
    else at its line in ``urdf`` itself."""
    from ..check.urdf_model import XmlError, parse_xml

    try:
        root = parse_xml(urdf)
    except XmlError:
        found = _INCLUDE_BYTES.search(urdf)
        if found:
            line = urdf.count(b"\n", 0, found.start()) + 1
            raise GazeboError(f"<include>: libsdformat would read a file or model folder "
                              f"from disk, and mcar's Gazebo helper reads no file [{RULE}]",
                              file=label, line=line) from None
        return
    found = includes(root)
    if not found:
        return
    file, line, note = locate(found[0]) if locate else (label, found[0].sourceline, "")
    raise GazeboError(f"{refusal(found[0])}{note} [{RULE}]", file=file, line=line)
