"""The URDF 1.0 vocabulary urdfdom 3.0 reads: which elements go where, with which attributes.

An element's vocabulary depends on its name only (a ``<material>`` in a ``<visual>`` is
spelled like a top-level one, an ``<origin>`` is the same in a joint and in a visual), so
:data:`SPECS` is keyed by element name. Extension elements (``<gazebo>``,
``<transmission>``, ``<ros2_control>``, ``<sensor>``, ``<mujoco>``) may hold anything.
"""

from __future__ import annotations

from ..values import Value


class Spec(Value):
    _fields = ("attrs", "children", "single", "repeated")
    __slots__ = (*_fields, "attrs_ok", "lookup")
    attrs: frozenset
    children: dict  # name -> Spec
    single: frozenset  # children urdfdom reads only once
    repeated: frozenset  # children that may occur many times

    def __init__(self, attrs: frozenset = frozenset(), children: dict | None = None,
                 single: frozenset = frozenset(), repeated: frozenset = frozenset()):
        children = {} if children is None else children
        self._set(attrs, children, single, repeated)
        # Made once: the reader looks these up for every element of the document.
        object.__setattr__(self, "attrs_ok", attrs.issuperset)
        object.__setattr__(self, "lookup", {tag: (child.attrs.issuperset, not child.children)
                                            for tag, child in children.items()})


def _leaf(*attrs: str) -> Spec:
    return Spec(frozenset(attrs))


# <mujoco> is MuJoCo's URDF extension (compiler, option and size for its URDF reader),
# which Unitree's G1 and H1 and Skydio's X2 carry.
EXTENSIONS = frozenset({"gazebo", "transmission", "ros2_control", "sensor", "mujoco"})
SHAPES = {"box": _leaf("size"), "cylinder": _leaf("radius", "length"), "sphere": _leaf("radius"),
          "mesh": _leaf("filename", "scale")}
ORIGIN = _leaf("xyz", "rpy")
MATERIAL = Spec(frozenset({"name"}), {"color": _leaf("rgba"), "texture": _leaf("filename")},
                frozenset({"color", "texture"}))
GEOMETRY = Spec(frozenset(), dict(SHAPES))  # its first child is the shape, whatever it is
VISUAL = Spec(frozenset({"name"}), {"origin": ORIGIN, "geometry": GEOMETRY, "material": MATERIAL},
              frozenset({"origin", "geometry", "material"}))
COLLISION = Spec(frozenset({"name"}), {"origin": ORIGIN, "geometry": GEOMETRY},
                 frozenset({"origin", "geometry"}))
INERTIAL = Spec(frozenset(), {"origin": ORIGIN, "mass": _leaf("value"),
                              "inertia": _leaf("ixx", "ixy", "ixz", "iyy", "iyz", "izz")},
                frozenset({"origin", "mass", "inertia"}))
LINK = Spec(frozenset({"name"}), {"inertial": INERTIAL, "visual": VISUAL, "collision": COLLISION},
            frozenset({"inertial"}), frozenset({"visual", "collision"}))
_JOINT_CHILDREN = {
    "origin": ORIGIN, "parent": _leaf("link"), "child": _leaf("link"), "axis": _leaf("xyz"),
    "calibration": _leaf("rising", "falling", "reference_position"),
    "dynamics": _leaf("damping", "friction"),
    "limit": _leaf("lower", "upper", "effort", "velocity"),
    "mimic": _leaf("joint", "multiplier", "offset"),
    "safety_controller": _leaf("soft_lower_limit", "soft_upper_limit", "k_position",
                               "k_velocity"),
}
JOINT = Spec(frozenset({"name", "type"}), _JOINT_CHILDREN, frozenset(_JOINT_CHILDREN))
ROBOT = Spec(frozenset({"name", "version"}), {"link": LINK, "joint": JOINT, "material": MATERIAL},
             frozenset(), frozenset({"link", "joint", "material"}))


def _all(spec: Spec, name: str):
    yield name, spec
    for tag, child in spec.children.items():
        yield from _all(child, tag)


SPECS: dict[str, Spec] = {}
for _name, _spec in _all(ROBOT, "robot"):
    assert SPECS.setdefault(_name, _spec) == _spec, _name
