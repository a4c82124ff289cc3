"""Inertias MuJoCo refuses, found in the URDF before MuJoCo reads it, and made physical.

MuJoCo stops at the first body whose tensor is not positive definite ("inertia must have
positive eigenvalues", PMB2's antennas; a moment under MUJOCO_EPS is not positive to it
either: Valkyrie's virtual frames, 3.3e-22 kg m²), whose principal moments break the triangle
inequality (``A + B >= C``, which no rigid body breaks: PR2's), or that moves without mass
(PR2's ``*_gripper_l_finger_tip_frame``, frames on a prismatic joint). ``mcar check`` only
warns of the first two (W204, W205): urdfdom, rviz and Gazebo load them. Here each link is
found at once, so that ``mcar sim`` and ``mcar export`` name every one of them, and
:func:`make_physical` gives each, on ``--fix-inertia``, what it lacks:

* a tensor MuJoCo refuses: the nearest physical one, its principal moments moved the
  least distance that satisfies the triangle inequality (which makes them positive too)
  on the same principal axes, then a thousandth of the way to their mean so that none is
  on the edge (MuJoCo wants them strictly positive);
* a moving link without mass and nothing fixed to it that has one: a token mass,
  TOKEN_MASS kg with the inertia of a solid sphere of TOKEN_RADIUS, small beside any part
  and enough for MuJoCo to move it;
* a moving link with a mass but a tensor of zeros (and nothing fixed to it with one):
  the inertia of a solid sphere of its mass and TOKEN_RADIUS;
* a tensor whose moments are positive but under MUJOCO_EPS: the same sphere's, at least
  SMALLEST_FIX about each axis.

A tensor of all zeros is a massless frame's, which MuJoCo accepts on a link that does not
move. Masses in kg, moments in kg m², lengths in m.
"""

from __future__ import annotations

from dataclasses import dataclass

from .inertia import INERTIA, principal_moments
from .urdf_model import parse_number

TOKEN_MASS = 0.001
TOKEN_RADIUS = 0.01
# MuJoCo's URDF reader gives every tensor as fullinertia, whose smallest principal moment
# must be at least mjEPS (mjuu_fullInertia in user_util.cc: "inertia must have positive
# eigenvalues", on a link that does not move too; 1e-14 compiles, 1e-15 does not).
MUJOCO_EPS = 1e-14
SMALLEST_FIX = 100 * MUJOCO_EPS
_INSIDE = 1e-3  # how far towards the mean a projected tensor is moved off the edge


@dataclass
class Refusal:
    link: str
    problem: str  # "not-positive", "tiny", "triangle", "no-inertia" or "massless"
    element: object  # the <inertia> (a tensor), or the <link> (no mass)
    moments: tuple[float, ...] = ()

    def describe(self) -> str:
        if self.problem == "massless":
            return f"link {self.link}: moves but has no mass (MuJoCo needs one)"
        if self.problem == "no-inertia":
            return (f"link {self.link}: moves with a mass but an inertia of zeros (MuJoCo "
                    "needs it positive)")
        shown = ", ".join(_g(m) for m in self.moments)
        if self.problem == "not-positive":
            return (f"link {self.link}: inertia is not positive definite (principal moments "
                    f"{shown} kg m²)")
        if self.problem == "tiny":
            return (f"link {self.link}: principal moments {shown} kg m², the smallest under "
                    f"the {MUJOCO_EPS:g} MuJoCo takes as positive")
        a, b, c = self.moments
        return (f"link {self.link}: principal moments {shown} kg m² break A + B >= C "
                f"({_g(a)} + {_g(b)} < {_g(c)})")


def refusals(root, massless: bool = True) -> list[Refusal]:
    """Every link of the URDF ``root`` whose inertia MuJoCo refuses, in document order;
    with ``massless`` False only the tensors (the export leaves a massless link with
    collision geometry to MuJoCo's inertia from geometry: :func:`bare_massless`)."""
    found = []
    for link in root.iterchildren("link"):
        inertia = link.find("inertial/inertia")
        values = _tensor(inertia)
        if values is None or not any(values):
            continue
        moments = principal_moments(*values)
        a, b, c = moments
        scale = max(-a, c) or 1.0
        # MuJoCo compares its moments exactly (c a trillionth over a + b is refused): a
        # diagonal tensor's are exact here too, others carry the rounding of their
        # eigenvalues (check's W205 allows a millionth, a rounding in the file)
        diagonal = values[1] == values[2] == values[4] == 0
        if a <= 1e-12 * scale:
            found.append(Refusal(link.get("name"), "not-positive", inertia, moments))
        elif a < MUJOCO_EPS:
            found.append(Refusal(link.get("name"), "tiny", inertia, moments))
        elif a + b < (c if diagonal else c * (1 - 1e-9)):
            found.append(Refusal(link.get("name"), "triangle", inertia, moments))
    for name, link, problem in _moving_without(root):
        if problem == "no-inertia":
            found.append(Refusal(name, problem, link.find("inertial/inertia")))
        elif massless:
            found.append(Refusal(name, problem, link))
    return found


def bare_massless(root) -> list[Refusal]:
    """The moving links without mass that have no collision geometry either: MuJoCo has
    nothing to take a mass from (PR2's finger-tip frames)."""
    return [Refusal(name, problem, element) for name, element, problem in _moving_without(root)
            if problem == "massless" and element.find("collision") is None]


def make_physical(root, found: list[Refusal]) -> list[str]:
    """Give each link of ``found`` (by name, in the URDF ``root``) what MuJoCo needs, in
    place; one line per link saying what changed."""
    links = {link.get("name"): link for link in root.iterchildren("link")}
    lines = []
    for item in found:
        link = links.get(item.link)
        if link is None:
            continue
        if item.problem == "massless":
            _give_token_mass(link)
            lines.append(f"link {item.link}: moves without mass; given a token "
                         f"{TOKEN_MASS * 1000:g} g (the inertia of a {TOKEN_RADIUS * 100:g} cm "
                         "solid sphere), as MuJoCo needs a mass to move it")
            continue
        inertia = link.find("inertial/inertia")
        if item.problem in ("no-inertia", "tiny"):
            element = link.find("inertial/mass")
            # (its mass may be on a link fixed below it: a token's then, all the same)
            mass = (parse_number(element.get("value")) if element is not None else 0) or 0.0
            mass = mass if mass > 0 else TOKEN_MASS
            moment = 0.4 * mass * TOKEN_RADIUS ** 2
            if item.problem == "tiny":
                moment = max(moment, SMALLEST_FIX)
            for name in INERTIA:
                inertia.set(name, f"{moment:.9g}" if name in ("ixx", "iyy", "izz") else "0")
            what = ("moves with {:g} kg but an inertia of zeros" if item.problem == "no-inertia"
                    else "has {:g} kg and principal moments under MuJoCo's " +
                    f"{MUJOCO_EPS:g} kg m²").format(mass)
            lines.append(f"link {item.link}: {what}; given that of a {TOKEN_RADIUS * 100:g} cm "
                         f"solid sphere of its mass ({moment:.4g} kg m² about each axis)")
            continue
        values = _tensor(inertia)
        if values is None:
            continue
        fixed, moments = nearest_physical(values)
        for name, value in zip(INERTIA, fixed, strict=True):
            inertia.set(name, f"{value:.9g}")
        what = ("not positive definite" if item.problem == "not-positive" else
                "breaks A + B >= C")
        lines.append(f"link {item.link}: inertia {what} (principal moments "
                     f"{', '.join(_g(m) for m in item.moments)}) -> the nearest physical "
                     f"tensor, principal moments {', '.join(_g(m) for m in moments)} kg m² "
                     "on the same axes")
    return lines


def nearest_physical(values) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """(ixx, ixy, ixz, iyy, iyz, izz) nearest to ``values`` whose principal moments
    satisfy the triangle inequality strictly, and those moments (ascending)."""
    import numpy as np

    xx, xy, xz, yy, yz, zz = values
    tensor = np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]], dtype=float)
    moments, axes = np.linalg.eigh(tensor)
    projected = _onto_triangle_cone(moments)
    if projected.sum() <= 0:  # nothing physical near: the size of what was written
        projected = np.full(3, np.abs(moments).max())
    projected = (1 - _INSIDE) * projected + _INSIDE * projected.mean()
    rebuilt = axes @ np.diag(projected) @ axes.T
    fixed = (rebuilt[0, 0], rebuilt[0, 1], rebuilt[0, 2], rebuilt[1, 1], rebuilt[1, 2],
             rebuilt[2, 2])
    return tuple(float(v) for v in fixed), tuple(float(v) for v in sorted(projected))


def _onto_triangle_cone(moments):
    """The Euclidean projection of three moments onto {each <= the sum of the others}
    (which holds only for moments >= 0): the nearest point over the faces and edges of
    that cone, tried each in turn (eight, the apex included)."""
    import itertools

    import numpy as np

    normals = np.array([[1.0, 1.0, -1.0], [1.0, -1.0, 1.0], [-1.0, 1.0, 1.0]])
    if (normals @ moments >= 0).all():
        return moments.copy()
    best, best_distance = np.zeros(3), float(np.linalg.norm(moments))
    for size in (1, 2):
        for active in itertools.combinations(range(3), size):
            n = normals[list(active)]
            # x = m - nᵀ (n nᵀ)⁻¹ n m: m projected onto the plane(s) n x = 0
            candidate = moments - n.T @ np.linalg.solve(n @ n.T, n @ moments)
            if (normals @ candidate >= -1e-12 * np.abs(moments).max()).all():
                distance = float(np.linalg.norm(candidate - moments))
                if distance < best_distance:
                    best, best_distance = candidate, distance
    return best


def places(checked):
    """link name -> "FILE:LINE" of its <inertia> (of the link when it has none) in the
    files the user wrote (a xacro's source line), from a CheckResult; None if unknown."""
    links = {link.name: link for link in checked.robot.links}

    def place(name: str) -> str | None:
        link = links.get(name)
        if link is None:
            return None
        inertial = link.inertial
        element = (inertial or {}).get("inertia", link.element)
        file, line, _note = checked.where(element)
        return f"{file}:{line}" if line is not None else None

    return place


def _moving_without(root):
    """(name, <link>, "massless" or "no-inertia") of each link a non-fixed joint moves
    whose mass, with that of the links fixed below it, is 0, or whose tensors there are
    all zeros (MuJoCo adds those up)."""
    links = {link.get("name"): link for link in root.iterchildren("link")}
    joints = list(root.iterchildren("joint"))
    fixed_children: dict[str, list[str]] = {}
    moved = []
    for joint in joints:
        parent, child = joint.find("parent"), joint.find("child")
        if parent is None or child is None:
            continue
        if joint.get("type") == "fixed":
            fixed_children.setdefault(parent.get("link"), []).append(child.get("link"))
        elif joint.get("type") is not None:
            moved.append(child.get("link"))
    for name in moved:
        if name not in links:
            continue
        mass, inertia = _fixed_mass(name, links, fixed_children)
        if mass <= 0:
            yield name, links[name], "massless"
        elif not inertia and links[name].find("inertial/inertia") is not None:
            yield name, links[name], "no-inertia"


def _fixed_mass(name: str, links: dict, fixed_children: dict) -> tuple[float, bool]:
    """The mass of ``name`` and the links fixed below it, and whether any of them has a
    tensor that is not all zeros."""
    total, inertia, todo, seen = 0.0, False, [name], set()
    while todo:
        current = todo.pop()
        if current in seen:
            continue
        seen.add(current)
        mass = links[current].find("inertial/mass") if current in links else None
        total += (parse_number(mass.get("value")) or 0.0) if mass is not None else 0.0
        tensor = _tensor(links[current].find("inertial/inertia")) if current in links else None
        inertia = inertia or bool(tensor and any(tensor))
        todo += fixed_children.get(current, [])
    return total, inertia


def _give_token_mass(link) -> None:
    from lxml import etree

    old = link.find("inertial")
    if old is not None:
        link.remove(old)
    inertial = etree.SubElement(link, "inertial")
    etree.SubElement(inertial, "mass", value=f"{TOKEN_MASS:g}")
    moment = f"{0.4 * TOKEN_MASS * TOKEN_RADIUS ** 2:g}"
    etree.SubElement(inertial, "inertia", ixx=moment, ixy="0", ixz="0", iyy=moment, iyz="0",
                     izz=moment)


def _tensor(inertia) -> tuple[float, ...] | None:
    if inertia is None:
        return None
    values = tuple(parse_number(inertia.get(name)) for name in INERTIA)
    return None if None in values else values


def _g(value: float) -> str:
    return f"{value:.4g}"
