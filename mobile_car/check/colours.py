"""Colours urdfdom cannot use, taken out before a drawing or an export reads the robot.

``mcar check`` reports them as W217 and goes on (only the look changes); urdfdom then drops
such a ``<color>`` and rviz draws the part in its default colour. The readers mcar hands
the robot to are stricter: yourdfpy overflows on an rgba of 2 (its 0..255 colours are
uint8), MuJoCo and urdf-usd-converter refuse an rgba of three numbers. Dropping the
colour as urdfdom does lets every one of them draw the part in its default grey. An
undefined or colourless material needs nothing: every reader already falls back.
"""

from __future__ import annotations

import re

from .urdf_model import parse_numbers

_RGBA = re.compile(rb"<color\b[^>]*?\brgba\s*=\s*(\"[^\"]*\"|'[^']*')")


def usable_rgba(text: str | None) -> bool:
    """True if urdfdom reads ``text`` as a colour: four numbers, each within 0..1."""
    values = parse_numbers(text, 4)
    return isinstance(values, tuple) and all(0.0 <= v <= 1.0 for v in values)


def has_unusable_colour(urdf: bytes) -> bool:
    """True if some ``<color rgba>`` of the document is one urdfdom drops (cheap: the
    usual file, every colour fine, is never parsed)."""
    return any(not usable_rgba(m.group(1)[1:-1].decode("utf-8", "replace"))
               for m in _RGBA.finditer(urdf))


def drop_unusable_colours(root) -> list[str]:
    """Take out, in place, each ``<color>`` (in a ``<material>``) whose rgba urdfdom
    cannot use, keeping every other element on its line; one line per material changed."""
    dropped = []
    for color in list(root.iter("color")):
        parent = color.getparent()
        if parent is None or parent.tag != "material" or usable_rgba(color.get("rgba")):
            continue
        _remove_keeping_lines(color)
        dropped.append(f"material '{parent.get('name')}': rgba=\"{color.get('rgba')}\" is "
                       "not a colour urdfdom reads (W217): left out, drawn in the default "
                       "grey")
    return dropped


def without_unusable_colours(urdf: bytes) -> bytes:
    """``urdf`` itself when every colour is usable, else the same document without the
    colours urdfdom drops (every element on the line it had)."""
    if not has_unusable_colour(urdf):
        return urdf
    from lxml import etree

    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False)
    root = etree.fromstring(urdf, parser)
    drop_unusable_colours(root)
    # The lines above the root (a declaration, comments) as blank ones: same numbering.
    return b"\n" * ((root.sourceline or 1) - 1) + etree.tostring(root, encoding="utf-8")


def _remove_keeping_lines(element) -> None:
    # The tail (the text after the element) holds the line breaks the next elements'
    # line numbers depend on: hand it to the previous sibling, or to the parent's text.
    parent, tail = element.getparent(), element.tail or ""
    previous = element.getprevious()
    if previous is not None:
        previous.tail = (previous.tail or "") + tail
    else:
        parent.text = (parent.text or "") + tail
    parent.remove(element)
