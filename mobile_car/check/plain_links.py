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

from .context import MAX_ANGLE, MAX_INERTIA, MAX_LENGTH, MAX_MASS, MAX_SCALE, Reporter, within
from .inertia import INERTIA, tensor_problem
from .rest_pose import ONE, ZERO, LinkShapes
from .urdf_vocabulary import COLLISION, GEOMETRY, INERTIAL, LINK, VISUAL

_LINK_PARTS = LINK.lookup
_SHAPE_ATTRS_OK = {tag: spec.attrs_ok for tag, spec in GEOMETRY.children.items()}


def plainly_clean(element, report: Reporter, materials: set[str], top_level: set,
                  moving: bool, is_root: bool) -> LinkShapes | None:
    """What the link ``element`` holds, read (:class:`~.rest_pose.LinkShapes`), if it is
    written the usual way and the full checks would find nothing in it; a colour it
    defines is then added to ``materials``, as the full checks do. None says only "not
    proved here"."""
    if not LINK.attrs_ok(element.keys()):
        return None
    defined: list[str] = []
    inertial = None
    bodies = []
    for part in element:
        tag = part.tag
        known = _LINK_PARTS.get(tag)
        if known is None:
            if tag.__class__ is str:
                return None  # an unknown element
            continue  # a comment or processing instruction
        if not known[0](part.keys()):
            return None
        if tag == "inertial":
            if inertial is not None or is_root:
                return None
            inertial = _inertial(part, report, moving)
            if inertial is None:
                return None
        else:
            body = _body(part, tag, report, materials, top_level, defined)
            if body is None:
                return None
            bodies.append(body)
    if moving and inertial is None:
        return None
    materials.update(defined)
    return LinkShapes(bodies, inertial)


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


def _origin(origin, report: Reporter) -> tuple | None:
    """(xyz, rpy) of an <origin> (zeros where absent), or None where one is not sound."""
    if origin is None:
        return ZERO, ZERO
    xyz, rpy = origin.get("xyz"), origin.get("rpy")
    xyz = ZERO if xyz is None else report.values(xyz, 3)
    if xyz is None or not within(xyz, MAX_LENGTH):
        return None
    rpy = ZERO if rpy is None else report.values(rpy, 3)
    if rpy is None or not within(rpy, MAX_ANGLE):
        return None
    return xyz, rpy


def _inertial(inertial, report: Reporter, moving: bool) -> tuple | None:
    """(element, mass, six moments, rpy) of a sound <inertial>, else None."""
    parts = _parts(inertial, INERTIAL)
    if parts is None:
        return None
    origin = _origin(parts.get("origin"), report)
    if origin is None:
        return None
    mass, inertia = parts.get("mass"), parts.get("inertia")
    if mass is None or inertia is None:
        return None
    value = report.value(mass.get("value"))
    if value is None or value < 0 or (moving and value == 0) or not within((value,), MAX_MASS):
        return None
    get, number = inertia.get, report.value
    moments = tuple([number(get(name)) for name in INERTIA])
    if None in moments or not within(moments, MAX_INERTIA) or \
            tensor_problem(*moments) is not None:
        return None
    return inertial, value, moments, origin[1]


def _body(body, kind: str, report: Reporter, materials: set[str], top_level: set,
          defined: list[str]) -> tuple | None:
    """(kind, shape element, xyz, rpy, dims) of a sound <visual> or <collision>."""
    parts = _parts(body, VISUAL if kind == "visual" else COLLISION)
    if parts is None:
        return None
    origin = _origin(parts.get("origin"), report)
    if origin is None:
        return None
    geometry = parts.get("geometry")
    if geometry is None or len(geometry) != 1:
        return None
    dims = _shape(geometry[0], report)
    if dims is None:
        return None
    material = parts.get("material")
    if material is not None and not _material(material, report, materials, top_level,
                                              defined):
        return None
    return kind, geometry[0], origin[0], origin[1], dims


def _shape(shape, report: Reporter) -> tuple | None:
    """The numbers of a sound shape: a box's size, a cylinder's (radius, length), a
    sphere's (radius,), a mesh's scale; None where it is not sound."""
    tag = shape.tag
    attrs_ok = _SHAPE_ATTRS_OK.get(tag)
    if attrs_ok is None or len(shape) or not attrs_ok(shape.keys()):
        return None
    get = shape.get
    if tag == "box":
        size = report.values(get("size"), 3)
        return size if size is not None and min(size) > 0 and max(size) <= MAX_LENGTH \
            else None
    if tag == "cylinder":
        radius, length = report.value(get("radius")), report.value(get("length"))
        return (radius, length) if (radius is not None and length is not None
                                    and 0 < radius <= MAX_LENGTH
                                    and 0 < length <= MAX_LENGTH) else None
    if tag == "sphere":
        radius = report.value(get("radius"))
        return (radius,) if radius is not None and 0 < radius <= MAX_LENGTH else None
    # A mesh: whether its file exists and loads is check_meshes' business.
    scale = get("scale")
    if get("filename") is None:
        return None
    if scale is None:
        return ONE
    values = report.values(scale, 3)
    return values if values is not None and 0 not in values and \
        within(values, MAX_SCALE) else None


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
