"""Inertias MuJoCo refuses, found link by link by MuJoCo itself, and its own fixes.

MuJoCo's compiler stops at the first body whose principal moments break the triangle
inequality (``A + B >= C``, which no rigid body breaks) or that moves without mass; ``mcar
check`` only warns of both, and PR2's description has several. Here the compiler is asked
again and again on a copy of the model, each refused body set aside, so that every link is
named at once. With the fix asked for (``mcar export --fix-inertia``), each gets MuJoCo's
own repair and one warning:

* a broken tensor: ``balanceinertia``, the three principal moments set to their mean;
* a moving link without mass: the mass and inertia MuJoCo computes from its collision
  geometry (``inertiafromgeom``, density 1000 kg/m³), for that link only (every other
  link keeps the description's figures: a link the description leaves massless on
  purpose stays so).

Moments in kg m², masses in kg.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from . import ExportError

TRIANGLE = "A + B >= C"
MASSLESS = "mass and inertia of moving bodies"
_ELEMENT = re.compile(r"Element name '([^']*)'")


@dataclass
class Refused:
    link: str
    problem: str  # "triangle" or "massless"
    moments: tuple[float, ...] = ()  # the principal moments of a broken tensor

    def describe(self) -> str:
        if self.problem == "triangle":
            a, b, c = self.moments
            return (f"link {self.link}: principal moments {_g(a)}, {_g(b)}, {_g(c)} kg m² "
                    f"break {TRIANGLE} ({_g(a)} + {_g(b)} < {_g(c)})")
        return f"link {self.link}: moves but has no mass (MuJoCo needs one)"


def refused_links(mj, spec) -> list[Refused]:
    """Every body of ``spec`` whose inertia MuJoCo refuses (``spec`` is left as it is)."""
    trial = spec.copy()
    found: list[Refused] = []
    for _ in range(len(list(trial.bodies)) + 1):
        try:
            trial.compile()
            return found
        except ValueError as error:
            text = str(error)
            name = _ELEMENT.search(text)
            if name is None or (TRIANGLE not in text and MASSLESS not in text):
                return found  # another fault: the real compile says it
            body = trial.body(name.group(1))
            if TRIANGLE in text:
                found.append(Refused(body.name, "triangle", principal_moments(body)))
            else:
                found.append(Refused(body.name, "massless"))
            body.mass = max(body.mass, 1.0)
            body.fullinertia = [math.nan] * 6
            body.inertia = [1.0, 1.0, 1.0]
            body.explicitinertial = True
    return found


def principal_moments(body) -> tuple[float, ...]:
    """A spec body's principal moments, smallest first, from its full or diagonal inertia."""
    import numpy as np

    full = list(body.fullinertia)
    if not math.isnan(full[0]):
        xx, yy, zz, xy, xz, yz = full
        tensor = np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
        return tuple(float(v) for v in np.linalg.eigvalsh(tensor))
    return tuple(sorted(float(v) for v in body.inertia))


def refuse(refused: list, label: str, place=None) -> None:
    """ExportError naming every refused link (a Refused, or a Refusal found in the URDF
    before MuJoCo read it), where its inertia is written when ``place`` (link name ->
    "FILE:LINE") knows, and the option that fixes them."""
    if not refused:
        return
    ours = [r for r in refused if not isinstance(r, Refused)]
    fixes = "MuJoCo's own fixes (balanceinertia, inertia from geometry)"
    if ours:
        fixes = ("the nearest physical tensor, a token mass for a bare frame, and " + fixes)
    details = []
    for item in refused:
        where = place(item.link) if place is not None else None
        details.append(item.describe() + (f" ({where})" if where else ""))
    raise ExportError(f"MuJoCo refuses the inertia of {len(refused)} "
                      f"link{'s' * (len(refused) != 1)} "
                      f"({', '.join(r.link for r in refused)}); --fix-inertia applies "
                      f"{fixes}", file=label, details=details)


def apply_fixes(mj, spec, refused: list[Refused], label: str) -> None:
    """MuJoCo's fixes on ``spec``: balanceinertia for broken tensors (it touches no other
    body), and for each massless moving link the inertia MuJoCo computes from its
    colliding geoms; ExportError for one that has none."""
    if any(r.problem == "triangle" for r in refused):
        spec.compiler.balanceinertia = True
    massless = [r.link for r in refused if r.problem == "massless"]
    if not massless:
        return
    # (the bare ones have their token mass from mujoco_inertia before MuJoCo reads them)
    bare = [name for name in massless
            if not any(g.contype or g.conaffinity for g in spec.body(name).geoms)]
    if bare:
        raise ExportError(f"{len(bare)} moving link{'s' * (len(bare) != 1)} without mass "
                          "and without collision geometry to take one from: "
                          f"{', '.join(bare)}; give them an <inertial>", file=label)
    geometric = spec.copy()
    geometric.compiler.inertiafromgeom = mj.mjtInertiaFromGeom.mjINERTIAFROMGEOM_TRUE
    geometric.compiler.balanceinertia = True
    model = geometric.compile()
    for name in massless:
        found = model.body(name)
        body = spec.body(name)
        body.mass = float(found.mass[0])
        body.ipos = [float(v) for v in found.ipos]
        body.iquat = [float(v) for v in found.iquat]
        body.inertia = [float(v) for v in found.inertia]
        body.fullinertia = [math.nan] * 6
        body.explicitinertial = True


def fix_warnings(model, refused: list[Refused]) -> list[str]:
    """One line per fixed link, saying what MuJoCo made of it (``model``: compiled)."""
    lines = []
    for item in refused:
        body = model.body(item.link)
        if item.problem == "triangle":
            mean = float(body.inertia[0])
            lines.append(f"link {item.link}: inertia balanced by MuJoCo (balanceinertia): "
                         f"principal moments {', '.join(_g(m) for m in item.moments)} -> "
                         f"{_g(mean)} each kg m²")
        else:
            lines.append(f"link {item.link}: moves without mass; MuJoCo gave it "
                         f"{_g(float(body.mass[0]))} kg and its inertia from its collision "
                         "geometry (inertiafromgeom, 1000 kg/m³)")
    return lines


def _g(value: float) -> str:
    return f"{value:.4g}"
