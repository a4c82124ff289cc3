"""Read a parsed ``<robot>`` into plain dataclasses: links, joints, materials, with the
first child of each name indexed (urdfdom reads only that one).

Every element of the robot is visited exactly once, here, and what does not fit the
URDF vocabulary (:mod:`mobile_car.check.urdf_vocabulary`) is noted on the way: unknown
children, unknown attributes, repeated children (a large robot's joints whose skeleton
holds nothing to note are read from their values instead: joint_skeletons.py).
:mod:`mobile_car.check.schema` turns those notes into warnings; the other checks read the
indexes. One pass matters: on a
20,000-link robot each extra Python walk over the elements costs a tenth of check_urdf's
whole run.
"""

from __future__ import annotations

from lxml import etree

from .urdf_vocabulary import COLLISION, GEOMETRY, INERTIAL, JOINT, LINK, MATERIAL, ROBOT, VISUAL

# Children of <robot> (links, joints, materials) from which joints are read by their
# skeleton (joint_skeletons.py): below, the plans cost more than they save.
SKELETONS_FROM = 400

# The classes here are plain classes with slots, not dataclasses: never compared, and a
# dataclass costs every run that imports it the compiling of its methods (values.py).


class Anomalies:
    """What the vocabulary does not expect, found while reading."""

    __slots__ = ("unknown", "attributes", "repeats")

    def __init__(self):
        self.unknown: list = []     # (element, parent element, parent spec)
        self.attributes: list = []  # elements with an unknown attribute
        self.repeats: list = []     # second <origin>, <limit>, ...


class Body:
    """A ``<visual>`` or ``<collision>``: its parts, its geometry's children, its material."""

    __slots__ = ("element", "parts", "shapes", "material")

    def __init__(self, element: etree._Element, parts: dict, shapes: list,
                 material: dict | None = None):
        self.element = element
        self.parts = parts  # name -> the first child element of that name
        self.shapes = shapes  # element children of the first <geometry>, in order
        self.material = material  # parts of its <material>, if that has children


class Link:
    """A ``<link>``: its name and element at once; what is inside it (parts, visuals,
    collisions, inertial) when first asked for.

    ``mcar check`` proves most links clean without reading them into parts
    (:mod:`mobile_car.check.plain_links`, repeats in :mod:`mobile_car.check.link_bodies`);
    a later stage (sim, sweep) that asks for a link's collisions or inertial then gets
    them read here, so that no fast path of check can hide what a link holds.
    """

    __slots__ = ("name", "element", "_parts", "_visuals", "_collisions", "_inertial")

    def __init__(self, name: str | None, element: etree._Element):
        self.name = name
        self.element = element
        self._parts: dict | None = None  # None: not read yet

    def read(self, notes: Anomalies) -> None:
        """Read what is inside the link, noting what the vocabulary does not expect."""
        _read_link(self, notes)

    def _ensure(self) -> None:
        # A link check skipped was proved clean: nothing to note (the notes are dropped).
        if self._parts is None:
            _read_link(self, Anomalies())

    @property
    def parts(self) -> dict:
        """Name -> first child (lists for visual and collision)."""
        self._ensure()
        return self._parts

    @property
    def visuals(self) -> list[Body]:
        self._ensure()
        return self._visuals

    @property
    def collisions(self) -> list[Body]:
        self._ensure()
        return self._collisions

    @property
    def inertial(self) -> dict | None:
        """Parts of the first ``<inertial>``, or None."""
        self._ensure()
        return self._inertial

    @property
    def line(self) -> int:
        return self.element.sourceline


class Joint:
    __slots__ = ("name", "type", "parent", "child", "element", "_parts", "tags", "texts")

    def __init__(self, name: str | None, type: str | None, parent: str | None,
                 child: str | None, element: etree._Element, parts: dict | None,
                 tags: frozenset | None = None, texts: tuple | None = None):
        self.name = name
        self.type = type
        self.parent = parent
        self.child = child
        self.element = element
        self._parts = parts  # None: not indexed yet (read by its skeleton: nothing to note)
        # Read by its skeleton (joint_skeletons.py): the names of its parts, and the texts
        # joint_skeletons.TEXTS names (None where absent); else None.
        self.tags = tags
        self.texts = texts

    @property
    def parts(self) -> dict:
        """Name -> the first child element of that name."""
        if self._parts is None:
            self._parts = _index(self.element, JOINT, Anomalies())
        return self._parts

    @property
    def line(self) -> int:
        return self.element.sourceline


class Robot:
    """The content of a ``<robot>``, in document order."""

    def __init__(self, name: str | None, element: etree._Element,
                 links: list[Link] | None = None, joints: list[Joint] | None = None,
                 materials: list[tuple[etree._Element, dict]] | None = None,
                 others: list[etree._Element] | None = None,
                 anomalies: Anomalies | None = None):
        self.name = name
        self.element = element
        self.links = [] if links is None else links
        self.joints = [] if joints is None else joints
        self.materials = [] if materials is None else materials
        self.others = [] if others is None else others  # other top-level elements
        self.anomalies = Anomalies() if anomalies is None else anomalies


def read_robot(root) -> Robot:
    """The robot in ``root`` (the caller checked that it is a ``<robot>``).

    Links are read by name only; :func:`read_links` reads what is inside them, which is
    most of the document, so that it can be left out (``mcar tree``) or shared out.
    """
    robot = Robot(name=root.get("name"), element=root)
    notes = robot.anomalies
    if not ROBOT.attrs_ok(root.keys()):
        notes.attributes.append(root)
    links, joints = robot.links, robot.joints
    skeletons = None
    if len(root) >= SKELETONS_FROM:
        # Imported here: a small robot's reading (most runs) does without the module.
        from .joint_skeletons import JointSkeletons

        skeletons = JointSkeletons(_quiet_parts)
    for top in root:
        tag = top.tag
        if tag == "link":
            links.append(Link(top.get("name"), top))
        elif tag == "joint":
            if skeletons is not None and not skeletons.open:
                skeletons = None
            read = skeletons.read(top) if skeletons is not None else None
            if read is not None:
                name, kind, parent, child, tags, texts = read
                joints.append(Joint(name, kind, parent, child, top, None, tags, texts))
                continue
            if not JOINT.attrs_ok(top.keys()):
                notes.attributes.append(top)
            parts = _index(top, JOINT, notes)
            parent, child = parts.get("parent"), parts.get("child")
            joints.append(Joint(top.get("name"), top.get("type"),
                                None if parent is None else parent.get("link"),
                                None if child is None else child.get("link"), top, parts))
        elif tag == "material":
            if not MATERIAL.attrs_ok(top.keys()):
                notes.attributes.append(top)
            robot.materials.append((top, _index(top, MATERIAL, notes)))
        elif tag.__class__ is str:
            robot.others.append(top)
    return robot


def _quiet_parts(joint) -> frozenset | None:
    """The names of the parts of the ``<joint>`` ``joint`` if reading it notes nothing."""
    if not JOINT.attrs_ok(joint.keys()):
        return None
    notes = Anomalies()
    parts = _index(joint, JOINT, notes)
    return None if notes.unknown or notes.attributes or notes.repeats else frozenset(parts)


def _index(element, spec, notes: Anomalies) -> dict:
    """Name -> the first child of that name; unknown, repeated, odd children noted.

    Children that may repeat (``visual``) are indexed as lists. This loop runs for almost
    every element of the document, so it keeps to the fewest operations.
    """
    parts = {}
    lookup = spec.lookup.get
    for child in element:
        tag = child.tag
        known = lookup(tag)
        if known is None:
            if tag.__class__ is str:
                notes.unknown.append((child, element, spec))
            continue
        attrs_ok, leaf = known
        if not attrs_ok(child.keys()):
            notes.attributes.append(child)
        if tag not in parts:
            parts[tag] = [child] if tag in spec.repeated else child
        elif tag in spec.repeated:
            parts[tag].append(child)
        elif tag in spec.single:
            notes.repeats.append(child)
        if leaf and len(child):
            for grandchild in child.iterchildren(etree.Element):  # a leaf with children
                notes.unknown.append((grandchild, child, spec.children[tag]))
    return parts


def read_links(links: list[Link], notes: Anomalies) -> None:
    """Read the inertial, visuals and collisions of each link into it."""
    for link in links:
        _read_link(link, notes)


def _read_link(link: Link, notes: Anomalies) -> None:
    element = link.element
    if not LINK.attrs_ok(element.keys()):
        notes.attributes.append(element)
    parts = _index(element, LINK, notes)
    link._visuals = [_read_body(visual, VISUAL, notes) for visual in parts.get("visual", ())]
    link._collisions = [_read_body(collision, COLLISION, notes)
                        for collision in parts.get("collision", ())]
    inertial = parts.get("inertial")
    link._inertial = _index(inertial, INERTIAL, notes) if inertial is not None else None
    link._parts = parts


def _read_body(element, spec, notes: Anomalies) -> Body:
    parts = _index(element, spec, notes)
    geometry = parts.get("geometry")
    shapes = []
    if geometry is not None:
        # urdfdom takes the first child element as the shape, whatever its name; an
        # unknown one is E111, so it is not noted as an unknown element here.
        for shape in geometry.iterchildren(etree.Element):
            shapes.append(shape)
            shape_spec = GEOMETRY.children.get(shape.tag)
            if shape_spec is not None:
                if not shape_spec.attrs_ok(shape.keys()):
                    notes.attributes.append(shape)
                if len(shape):
                    for grandchild in shape.iterchildren(etree.Element):
                        notes.unknown.append((grandchild, shape, shape_spec))
    body = Body(element, parts, shapes)
    material = parts.get("material")
    if material is not None and len(material):
        body.material = _index(material, MATERIAL, notes)
    return body
