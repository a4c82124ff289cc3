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
from .rest_pose import ONE, LinkShapes
from .urdf_vocabulary import COLLISION, GEOMETRY, INERTIAL, LINK, VISUAL

_LINK_PARTS = LINK.lookup
_SHAPE_ATTRS_OK = {tag: spec.attrs_ok for tag, spec in GEOMETRY.children.items()}


def plainly_clean(element, report: Reporter, materials: set[str], top_level: set,
                  moving: bool, is_root: bool) -> LinkShapes | None:
    """What the link ``element`` holds, read (:class:`~.rest_pose.LinkShapes`), if it is
    written the usual way and the full checks would find nothing in it; a colour it
    defines is then added to ``materials``, as the full checks do. None says only "not
    proved here"."""
    gathered = gather(element)
    if gathered is None:
        return None
    return judge(gathered, report, materials, top_level, moving, is_root)


def gather(element) -> tuple | None:
    """The texts of the numbers and names of a link written the usual way, and where each
    sits, or None if it is not written so. The verdict and where each text is taken from
    depend on the link's elements and attribute names only, never on a value (but for
    whether it is there): :mod:`.link_skeletons` relies on it.

    (triples, singles, bodies, inertial, colours): ``triples`` the texts of the lists of
    three (origins' xyz and rpy, a box's size, a mesh's scale), ``singles`` of the single
    numbers (the mass and six moments, a radius, a length); ``bodies`` (kind, shape
    element, its tag, whether it has a scale, where its numbers start: in the numbers of
    the triples, in the singles) per visual and collision; ``inertial`` (element, where its
    numbers start) or None; ``colours`` (name, rgba or None for a reference by name) per
    visual's material, in order."""
    if not LINK.attrs_ok(element.keys()):
        return None
    # The walk gathers the texts of the link's numbers, the numbers are then read all at
    # once (two calls per link rather than one per attribute: on a robot whose every
    # number differs, the calls were most of this pass) and judged by where they sit.
    triples: list[str] = []
    singles: list[str] = []
    colours: list[tuple] = []
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
            if inertial is not None:
                return None
            inertial = (part, 3 * len(triples), len(singles))
            if not _inertial(part, triples, singles):
                return None
        else:
            at = 3 * len(triples), len(singles)
            shape = _body(part, tag, colours, triples, singles)
            if shape is None:
                return None
            kind = shape.tag
            bodies.append((tag, shape, kind, kind == "mesh" and shape.get("scale") is not None,
                           *at))
    return triples, singles, bodies, inertial, colours


def judge(gathered: tuple, report: Reporter, materials: set[str], top_level: set,
          moving: bool, is_root: bool, twin=None) -> LinkShapes | None:
    """The :class:`~.rest_pose.LinkShapes` of a link :func:`gather` found written the
    usual way, if its numbers and materials are sound in its place (moving or not, the
    root or not, after the materials defined so far); else None. ``twin``: the link's own
    element, when the elements gathered are another link's (:mod:`.link_skeletons`)."""
    triples, singles, bodies, inertial, colours = gathered
    if (moving and inertial is None) or (is_root and inertial is not None):
        return None
    defined: list[str] = []
    for name, rgba in colours:
        if not _colour(name, rgba, report, materials, top_level, defined):
            return None
    numbers = report.triples(triples)
    if numbers is None or not within(numbers, _TRIPLE_BOUND):
        return None
    single = report.singles(singles)
    if single is None:
        return None
    if inertial is not None:
        inertial = _inertia(inertial, numbers, single, moving)
        if inertial is None:
            return None
    read = []
    for kind, shape, tag, scaled, at, at_single in bodies:
        dims = _dims(tag, scaled, numbers, at + 6, single, at_single)
        if dims is None:
            return None
        read.append((kind, shape, numbers[at:at + 3], numbers[at + 3:at + 6], dims))
    materials.update(defined)
    return LinkShapes(read, inertial, twin)


# Every number read as one of three is a length, an angle or a scale: the smallest of
# their bounds is theirs (a bound in between would only send a link to the full checks).
_TRIPLE_BOUND = min(MAX_LENGTH, MAX_ANGLE, MAX_SCALE)
NO_TURN = "0 0 0"  # an absent xyz or rpy, read with the others


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


def _origin(origin, triples: list[str]) -> None:
    """The texts of an <origin>'s xyz and rpy (zeros where absent) onto ``triples``."""
    if origin is None:
        triples += (NO_TURN, NO_TURN)
        return
    get = origin.get
    triples += (get("xyz", NO_TURN), get("rpy", NO_TURN))


def _inertial(inertial, triples: list[str], singles: list[str]) -> bool:
    """The texts of a usual <inertial>'s numbers onto the lists; False if it is not one."""
    parts = _parts(inertial, INERTIAL)
    if parts is None:
        return False
    mass, inertia = parts.get("mass"), parts.get("inertia")
    if mass is None or inertia is None:
        return False
    _origin(parts.get("origin"), triples)
    get = inertia.get
    singles += (mass.get("value"), *[get(name) for name in INERTIA])
    return True


def _inertia(inertial: tuple, numbers: tuple, single: tuple, moving: bool) -> tuple | None:
    """(element, mass, six moments, rpy) of an <inertial> whose numbers are sound, else
    None; ``inertial`` is (element, where its numbers start: in the numbers of the triples,
    in the singles)."""
    element, at, at_single = inertial
    mass = single[at_single]
    if not 0 <= mass <= MAX_MASS or (moving and mass == 0):
        return None
    moments = single[at_single + 1:at_single + 7]
    if not within(moments, MAX_INERTIA) or tensor_problem(*moments) is not None:
        return None
    return element, mass, moments, numbers[at + 3:at + 6]


def _body(body, kind: str, colours: list[tuple], triples: list[str], singles: list[str]):
    """The shape element of a usual <visual> or <collision>, the texts of its numbers
    onto the lists, its material's onto ``colours``; None if it is not one."""
    parts = _parts(body, VISUAL if kind == "visual" else COLLISION)
    if parts is None:
        return None
    geometry = parts.get("geometry")
    if geometry is None or len(geometry) != 1:
        return None
    shape = geometry[0]
    tag = shape.tag
    attrs_ok = _SHAPE_ATTRS_OK.get(tag)
    if attrs_ok is None or len(shape) or not attrs_ok(shape.keys()):
        return None
    material = parts.get("material")
    if material is not None and not _material(material, colours):
        return None
    _origin(parts.get("origin"), triples)
    get = shape.get
    if tag == "box":
        size = get("size")
        if size is None:
            return None
        triples.append(size)
    elif tag == "cylinder":
        singles += (get("radius"), get("length"))
    elif tag == "sphere":
        singles.append(get("radius"))
    else:  # A mesh: whether its file exists and loads is check_meshes' business.
        if get("filename") is None:
            return None
        scale = get("scale")
        if scale is not None:
            triples.append(scale)
    return shape


def _dims(tag: str, scaled: bool, numbers: tuple, at: int, single: tuple,
          at_single: int) -> tuple | None:
    """The numbers of a sound shape (``tag``; ``scaled``: a mesh with a scale): a box's
    size, a cylinder's (radius, length), a sphere's (radius,), a mesh's scale; None where
    it is not sound. Every number in ``numbers`` is already within its bound."""
    if tag == "box":
        size = numbers[at:at + 3]
        return size if min(size) > 0 else None
    if tag == "cylinder":
        radius, length = single[at_single:at_single + 2]
        return (radius, length) if (0 < radius <= MAX_LENGTH
                                    and 0 < length <= MAX_LENGTH) else None
    if tag == "sphere":
        radius = single[at_single]
        return (radius,) if 0 < radius <= MAX_LENGTH else None
    if not scaled:
        return ONE
    scale = numbers[at:at + 3]
    return scale if 0 not in scale else None


def _material(material, colours: list[tuple]) -> bool:
    """A usual visual's <material>: (name, rgba) onto ``colours`` (rgba None: a reference
    by name); False if it is not written the usual way."""
    name = material.get("name")
    if name is None:
        return False
    if not len(material):  # a reference by name
        colours.append((name, None))
        return True
    if len(material) != 1:
        return False
    color = material[0]
    if color.tag != "color" or len(color) or color.keys() != ["rgba"]:
        return False
    colours.append((name, color.get("rgba")))
    return True


def _colour(name: str, rgba: str | None, report: Reporter, materials: set[str],
            top_level: set, defined: list[str]) -> bool:
    """True if a visual's material is sound where it is: a reference to a colour defined
    before it, or a colour of its own that reads (then ``name`` goes onto ``defined``)."""
    if rgba is None:
        return name in materials or name in top_level or name in defined
    values = report.values(rgba, 4)
    if values is None or min(values) < 0 or max(values) > 1:
        return False
    defined.append(name)
    return True
