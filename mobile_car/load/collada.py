"""COLLADA read as RViz and Gazebo read it, before pycollada (through trimesh) sees it.

ROS draws COLLADA with assimp, which forgives what pycollada refuses. Three things differ,
each found in released description packages:

* **Not well-formed XML.** velodyne_description's meshes name a node
  ``id="<STL_BINARY>"`` (assimp's name for the binary STL they were converted from); an
  XML parser stops at the ``<``, assimp's does not. Such a file is parsed again with
  libxml2's recovery (``<`` in a value is kept as text), and pycollada gets the repaired
  document.
* **A colour that is not four numbers.** TurtleBot4's rplidar.dae had
  ``<color>0.0 0.0 0.01.0</color>``: pycollada drops the effect, then every geometry bound
  to it, and the mesh is empty. assimp reads numbers the way ``strtod`` does, one after
  the other (``0.01`` then ``.0``); here too, and the colour gets its fourth component
  (alpha 1) when it has three.
* **Units.** ``<asset><unit meter="0.0254"/>`` scales the geometry to metres: RViz
  (``getMeshUnitRescale``) and Gazebo apply it, trimesh only notes it. TurtleBot3's
  r200.dae is in units of 2.54 mm; read in metres it is a 51 m slab.

``<up_axis>`` is read and **not** applied: RViz drops the root transform assimp adds for it
(mesh_loader.cpp, ``buildMesh``) and Gazebo never reads it, so ROS robots are drawn with
their COLLADA files' coordinates as they are, whatever the tag says. velodyne's meshes
say ``Y_UP`` over Z-up data; turning them would lay the lidar on its side.

The document is parsed without entities, DTD or network, within libxml2's default depth
and size limits, and only its root element is handed on (no DOCTYPE): a file whose
entities pycollada's parser would expand reaches it with the references unexpanded.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from lxml import etree

from ..errors import InputError

_NUMBER_TEXT = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


@dataclass(frozen=True)
class ColladaDocument:
    """What pycollada is given (``data``), the factor from the file's unit to metres, its
    up axis as written (informative: not applied), and what was repaired on the way."""

    data: bytes
    unit: float = 1.0
    up_axis: str | None = None
    repaired: tuple[str, ...] = ()


def _parser(recover: bool) -> etree.XMLParser:
    return etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                           huge_tree=False, remove_comments=True, remove_pis=True,
                           recover=recover)


def readable_collada(data: bytes, shown: str) -> ColladaDocument:
    """The COLLADA document in ``data`` as pycollada can read it and assimp would; an
    InputError naming ``shown`` when even recovery finds no ``<COLLADA>`` in it."""
    repaired = []
    try:
        root = etree.fromstring(data, _parser(recover=False))
    except etree.XMLSyntaxError as error:
        root = etree.fromstring(data, _parser(recover=True))
        repaired.append(f"not well-formed XML ({error.msg}), read as assimp reads it")
    if root is None or etree.QName(root).localname != "COLLADA":
        raise InputError("not a COLLADA document (no <COLLADA> root)", file=shown)
    fixed = sum(_repair_numbers(element) for element in root.iter(_tag(root, "color")))
    if fixed:
        repaired.append(f"{fixed} colour{'s' * (fixed != 1)} not four numbers, read as "
                        "assimp reads them")
    unit, up_axis = _asset(root)
    return ColladaDocument(etree.tostring(root), unit, up_axis, tuple(repaired))


def _tag(root, name: str) -> str:
    namespace = etree.QName(root).namespace
    return f"{{{namespace}}}{name}" if namespace else name


def _repair_numbers(element) -> bool:
    """Rewrite a ``<color>`` whose text is not 3 or 4 numbers as assimp reads it; True if
    it was rewritten."""
    text = element.text or ""
    words = text.split()
    try:
        values = [float(word) for word in words]
        if len(values) in (3, 4) and all(map(math.isfinite, values)):
            if len(values) == 3:
                element.text = f"{text.strip()} 1"
                return True
            return False
    except ValueError:
        pass
    values = [float(match) for match in _NUMBER_TEXT.findall(text)][:4]
    values += [0.0] * (3 - len(values)) if len(values) < 3 else []
    if len(values) == 3:
        values.append(1.0)
    element.text = " ".join(f"{value:.9g}" for value in values)
    return True


def _asset(root) -> tuple[float, str | None]:
    """(metres per unit, up axis) from the first ``<asset>``: a unit that is not a
    positive finite number counts as metres, as RViz takes it."""
    asset = root.find(_tag(root, "asset"))
    if asset is None:
        return 1.0, None
    unit, up_axis = 1.0, None
    found = asset.find(_tag(root, "unit"))
    if found is not None:
        try:
            value = float(found.get("meter", "1"))
        except ValueError:
            value = 1.0
        if math.isfinite(value) and value > 0:
            unit = value
    axis = asset.find(_tag(root, "up_axis"))
    if axis is not None and axis.text:
        up_axis = axis.text.strip()
    return unit, up_axis
