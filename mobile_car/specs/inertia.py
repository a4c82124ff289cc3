"""``mcar specs``' inertia section (issue 42 item 5): the inertia each link's geometry gives
it with its declared mass, and, where the declared tensor is implausible, the ``<inertial>``
to write instead, at the xacro line the user edits.

For each link with a mass: its collision shapes (its visual shapes where it has none,
said) as one solid of uniform density (:mod:`.solids`), about the declared ``<inertial>``
origin and in its axes: key ``inertia.<link>``, [ixx, ixy, ixz, iyy, iyz, izz] kg m².
Works from the URDF alone (``checked``), with or without sim's model: a robot sim cannot
simulate gets its inertias too.

W530 **inertia-implausible**: the declared tensor is one MuJoCo refuses
(:func:`mobile_car.check.mujoco_inertia.refusals`: not positive definite, or breaking the
triangle inequality), or off the geometry's by more than FACTOR on a principal axis of
the geometry's tensor (the declared tensor's moment about that axis against the
geometry's: a swapped axis is caught as well as a wrong size); not said of a link whose
shapes all fit in a 2 cm cube (check.masses.PLACEHOLDER: a sensor's stand-in, as
mass-implausible leaves them too). The message gives both
figures and the ``<inertial>`` to put in place of the declared one, located through the
source map at the ``<inertia>`` the user wrote (a macro file's line, and the call).
"""

from __future__ import annotations

from ..check.context import Reporter
from ..check.masses import PLACEHOLDER
from ..check.mujoco_inertia import refusals
from ..check.rest_pose import ZERO, link_shapes, own_box
from ..check.urdf_model import parse_number
from .figures import Figure, Section
from .lookup import written_at

FACTOR = 3.0  # a declared principal moment over FACTOR times, or under 1/FACTOR, the geometry's
ASSUMED = ("uniform density over the shapes (overlaps count twice), about the declared "
           "<inertial> origin and axes")


def section(context) -> Section:
    """The inertia section of a :class:`mobile_car.specs.context.SpecsContext`."""
    return inertia_section(context.checked, context.options.get("proof", True))


def inertia_section(checked, proof: bool = True) -> Section:
    """The inertia section of a CheckResult (``checked.robot``: the URDF as read);
    ``proof`` False: no MuJoCo proof (``--no-proof``, diff and sweep)."""
    from . import solids

    found = Section("inertia")
    report = Reporter(checked.file, checked.where)
    meshes = {m.element: m for m in checked.mesh_files}
    bounds = {element: mesh.bounds for element, mesh in meshes.items()}
    refused = {r.link: r for r in refusals(checked.robot.element, massless=False)}
    for link in checked.robot.links:
        inertial = link.inertial
        mass = _mass(inertial)
        if not mass:
            continue
        shapes = link_shapes(link.element)
        kind = "collision" if any(b[0] == "collision" for b in shapes.bodies) else "visual"
        bodies = [b for b in shapes.bodies if b[0] == kind]
        if not bodies:
            found.notes.append(f"link {link.name}: {mass:g} kg but no geometry to take an "
                               "inertia from")
            continue
        placed = []
        for _kind, shape, xyz, rpy, dims in bodies:
            try:
                solid = _solid(shape, dims, meshes, solids)
            except solids.NoVolume as error:
                found.notes.append(f"link {link.name}: {kind} {_named(shape)} {error}; no "
                                   "inertia from its geometry")
                placed = None
                break
            placed.append(solids.placed(solid, xyz, rpy))
        if not placed:
            continue
        xyz, rpy = _origin(inertial)
        tensor = solids.tensor_about(placed, mass, xyz, rpy)
        values = solids.six(tensor)
        hulls = [_named(b[1]) for b, s in zip(bodies, placed, strict=True) if s.hull]
        where = written_at(checked, inertial.get("mass", link.element))
        shown = ", ".join(_named(b[1]) for b in bodies)
        source = f"{kind} geometry ({shown}), declared mass {mass:g} kg ({where})"
        if kind == "visual":
            source += ": no collision geometry, the visual's taken"
        if hulls:
            source += f"; not watertight, its convex hull taken: {', '.join(hulls)}"
        paths = [meshes[b[1]].path if b[1].tag == "mesh" else None for b in bodies]
        proven = _proof(bodies, paths, [s.hull for s in placed], mass, (xyz, rpy),
                        values) if proof else None
        found.figures.append(Figure(f"inertia.{link.name}", f"inertia of {link.name}",
                                    values, "kg m²", source, ASSUMED, proven))
        if _placeholder(bodies, bounds):
            continue
        _judge(link, values, tensor, refused.get(link.name), (xyz, rpy, mass),
               written_at(checked, link.parts["inertial"]), report)
    found.diagnostics = report.diagnostics
    return found


def _proof(bodies, paths, hulls, mass, origin, values):
    """MuJoCo's proof of the figure (:mod:`.inertia_proof`); a mesh MuJoCo cannot be
    given (its cache copy not written) leaves it unproven, said."""
    from ..errors import McarError
    from .figures import Proof
    from .inertia_proof import mujoco_proof, shown_tolerance

    try:
        return mujoco_proof(bodies, paths, hulls, mass, *origin, values)
    except (McarError, OSError) as error:
        why = error.message if isinstance(error, McarError) else error.strerror or error
        return Proof(None, False, shown_tolerance(),
                     f"MuJoCo was not given the meshes: {why}")


def _placeholder(bodies: list, bounds: dict) -> bool:
    """Whether the shapes all fit in a PLACEHOLDER cube: a stand-in for a sensor or a
    mount, not a claim about the part's size (as mass-implausible judges them, E119);
    ``bounds``: each mesh element's box."""
    across = 0.0
    for _kind, shape, _xyz, _rpy, dims in bodies:
        box = own_box(shape.tag, dims, shape, bounds)
        if box is None:
            return False
        low, high = box[1]
        across = max(across, *(h - lo for lo, h in zip(low, high, strict=True)))
    return across <= PLACEHOLDER  # fits in the cube, its side included


def _mass(inertial) -> float | None:
    element = (inertial or {}).get("mass")
    value = parse_number(element.get("value")) if element is not None else None
    return value if value is not None and value > 0 else None


def _origin(inertial) -> tuple[tuple, tuple]:
    origin = inertial.get("origin")
    if origin is None:
        return ZERO, ZERO
    xyz = tuple(parse_number(v) for v in (origin.get("xyz") or "0 0 0").split())
    rpy = tuple(parse_number(v) for v in (origin.get("rpy") or "0 0 0").split())
    # (check reported numbers it cannot read, E114: they are taken as urdfdom would, 0)
    return (xyz if len(xyz) == 3 and None not in xyz else ZERO,
            rpy if len(rpy) == 3 and None not in rpy else ZERO)


def _solid(shape, dims: tuple, meshes: dict, solids):
    tag = shape.tag
    if min(dims) <= 0 and tag != "mesh":
        raise solids.NoVolume("has no size")
    if tag == "box":
        return solids.box(*dims)
    if tag == "cylinder":
        return solids.cylinder(*dims)
    if tag == "sphere":
        return solids.sphere(dims[0])
    known = meshes.get(shape)
    if known is None or known.path is None or not known.sound or known.over_limit:
        raise solids.NoVolume("is not read (mcar check says why)")
    return solids.mesh(known.path, dims)


def _named(shape) -> str:
    if shape.tag == "mesh":
        return f"mesh {shape.get('filename')}"
    return f"<{shape.tag}>"



def _judge(link, values: list, tensor, refusal, inertial: tuple, block_at: str,
           report: Reporter) -> None:
    """W530 at the declared <inertia>, when it is refused or off by FACTOR; ``inertial``
    is the declared (xyz, rpy, mass), ``block_at`` where its <inertial> starts."""
    import numpy as np

    from .solids import matrix

    element = link.inertial.get("inertia")
    if element is None:
        return  # E115
    declared = [parse_number(element.get(name)) for name in
                ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")]
    if None in declared:
        return  # E114, E115
    moments, axes = np.linalg.eigh(tensor)
    along = [float(a @ matrix(declared) @ a) for a in axes.T]
    off = [d / g for d, g in zip(along, moments, strict=True) if g > 0]
    worst = max(off, key=lambda r: max(r, 1 / r) if r > 0 else float("inf"), default=1.0)
    if refusal is None and 1 / FACTOR <= worst <= FACTOR:
        return
    why = (f"MuJoCo refuses it ({refusal.describe().split(': ', 1)[1]})" if refusal
           else f"{_times(worst)} the geometry's about one of its principal axes (over "
                f"{FACTOR:g} times off)")
    xyz, rpy, mass = inertial
    report.add("W530", element, f"link '{link.name}': declared inertia "
               f"[{_list(declared)}] kg m² is implausible: {why}; its geometry with "
               f"{mass:g} kg gives [{_list(values)}]; put in place of the <inertial> at "
               f"{block_at}: {_block(xyz, rpy, mass, values)}")


def _times(ratio: float) -> str:
    if ratio <= 0:
        return f"{ratio:.3g} times"
    return f"{ratio:.3g} times" if ratio >= 1 else f"1/{1 / ratio:.3g} of"


def _list(values) -> str:
    return ", ".join(f"{v:.4g}" for v in values)


def _block(xyz: tuple, rpy: tuple, mass: float, values: list) -> str:
    """The corrected ``<inertial>``, on one line (a diagnostic is one line)."""
    names = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
    small = 1e-12 * max(abs(v) for v in values)  # a rounding's noise off a zero
    inertia = " ".join(f'{n}="{_number(v, small)}"' for n, v in zip(names, values,
                                                                   strict=True))
    return (f'<inertial><origin xyz="{" ".join(map(_number, xyz))}" '
            f'rpy="{" ".join(map(_number, rpy))}"/><mass value="{mass:g}"/>'
            f"<inertia {inertia}/></inertial>")


def _number(value: float, small: float = 1e-12) -> str:
    """Six significant digits; under ``small`` is 0."""
    return "0" if abs(value) < small else f"{value:.6g}"
