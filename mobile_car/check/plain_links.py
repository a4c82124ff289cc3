"""A quick proof that a link written the usual way is clean, so that the full reading and
checking (:mod:`mobile_car.check.urdf_reader`, :mod:`mobile_car.check.links`,
:mod:`mobile_car.check.inertia`) runs only for the other links.

"The usual way" is what URDF exporters and xacro macros write: a link with at most one
``<inertial>`` (origin, mass, the six moments), any number of ``<visual>`` and
``<collision>`` (origin, one box, cylinder, sphere or mesh, and for a visual a material
named before or given a colour here), every element and attribute from the URDF
vocabulary, each once, every number readable, sizes positive, the inertia physical.

Every condition here is one the full checks also require. A link that fails one is not
judged here: it goes to the full checks, which alone word diagnostics. So this module can
make a clean link cheaper (a third of the time, on a robot whose every number differs),
never hide a problem; ``tests/check/test_plain_links.py`` holds it to that on the whole check
corpus and on mutated robots.
"""

from __future__ import annotations

from math import inf

from .context import MAX_ANGLE, MAX_INERTIA, MAX_LENGTH, MAX_MASS, MAX_SCALE, Reporter, within
from .inertia import INERTIA, tensor_problem
from .urdf_vocabulary import COLLISION, GEOMETRY, INERTIAL, LINK, VISUAL

_LINK_PARTS = LINK.lookup
_SHAPE_ATTRS_OK = {tag: spec.attrs_ok for tag, spec in GEOMETRY.children.items()}


def plainly_clean(element, report: Reporter, materials: set[str], top_level: set,
                  moving: bool, is_root: bool) -> bool:
    """True if the link ``element`` is written the usual way and the full checks would
    find nothing in it; a colour it defines is then added to ``materials``, as the full
    checks do. False says only "not proved here"."""
    if not LINK.attrs_ok(element.keys()):
        return False
    defined: list[str] = []
    has_inertial = False
    for part in element:
        tag = part.tag
        known = _LINK_PARTS.get(tag)
        if known is None:
            if tag.__class__ is str:
                return False  # an unknown element
            continue  # a comment or processing instruction
        if not known[0](part.keys()):
            return False
        if tag == "inertial":
            if has_inertial or is_root or not _inertial(part, report, moving):
                return False
            has_inertial = True
        elif not _body(part, tag == "visual", report, materials, top_level, defined):
            return False
    if moving and not has_inertial:
        return False
    materials.update(defined)
    return True


def _parts(element, spec) -> dict | None:
    """Name -> child for an element whose children are known leaves, each once; else None."""
    parts = {}
    lookup = spec.lookup
    for child in element:
        tag = child.tag
        known = lookup.get(tag)
        if known is None or tag in parts or not known[0](child.keys()):
            return None
        if known[1] and len(child):  # a leaf with something inside
            return None
        parts[tag] = child
    return parts


def _origin(origin, report: Reporter) -> bool:
    if origin is None:
        return True
    xyz, rpy = origin.get("xyz"), origin.get("rpy")
    return ((xyz is None or within(report.values(xyz, 3) or (inf,), MAX_LENGTH))
            and (rpy is None or within(report.values(rpy, 3) or (inf,), MAX_ANGLE)))


def _inertial(inertial, report: Reporter, moving: bool) -> bool:
    parts = _parts(inertial, INERTIAL)
    if parts is None or not _origin(parts.get("origin"), report):
        return False
    mass, inertia = parts.get("mass"), parts.get("inertia")
    if mass is None or inertia is None:
        return False
    value = report.value(mass.get("value"))
    if value is None or value < 0 or (moving and value == 0) or not within((value,), MAX_MASS):
        return False
    get, number = inertia.get, report.value
    moments = [number(get(name)) for name in INERTIA]
    return (None not in moments and within(moments, MAX_INERTIA)
            and tensor_problem(*moments) is None)


def _body(body, is_visual: bool, report: Reporter, materials: set[str], top_level: set,
          defined: list[str]) -> bool:
    parts = _parts(body, VISUAL if is_visual else COLLISION)
    if parts is None or not _origin(parts.get("origin"), report):
        return False
    geometry = parts.get("geometry")
    if geometry is None or len(geometry) != 1 or not _shape(geometry[0], report):
        return False
    material = parts.get("material")
    return material is None or _material(material, report, materials, top_level, defined)


def _shape(shape, report: Reporter) -> bool:
    tag = shape.tag
    attrs_ok = _SHAPE_ATTRS_OK.get(tag)
    if attrs_ok is None or len(shape) or not attrs_ok(shape.keys()):
        return False
    get = shape.get
    if tag == "box":
        size = report.values(get("size"), 3)
        return size is not None and min(size) > 0 and max(size) <= MAX_LENGTH
    if tag == "cylinder":
        radius, length = report.value(get("radius")), report.value(get("length"))
        return (radius is not None and length is not None and 0 < radius <= MAX_LENGTH
                and 0 < length <= MAX_LENGTH)
    if tag == "sphere":
        radius = report.value(get("radius"))
        return radius is not None and 0 < radius <= MAX_LENGTH
    # A mesh: whether its file exists and loads is check_meshes' business.
    scale = get("scale")
    if get("filename") is None:
        return False
    if scale is None:
        return True
    values = report.values(scale, 3)
    return values is not None and 0 not in values and within(values, MAX_SCALE)


def _material(material, report: Reporter, materials: set[str], top_level: set,
              defined: list[str]) -> bool:
    name = material.get("name")
    if name is None:
        return False
    if not len(material):  # a reference by name
        return name in materials or name in top_level or name in defined
    if len(material) != 1:
        return False
    color = material[0]
    if color.tag != "color" or len(color) or color.keys() != ["rgba"]:
        return False
    rgba = report.values(color.get("rgba"), 4)
    if rgba is None or min(rgba) < 0 or max(rgba) > 1:
        return False
    defined.append(name)
    return True
