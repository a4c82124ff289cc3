"""The body figures of ``mcar specs``, computed first since every other section starts from
them: mass and centre of mass, the footprint and its radii, the clearance, the wheels'
radius, track and wheelbase, and the load on each wheel and castor at rest. Keys and units:
docs/specs.md. A robot MuJoCo cannot model keeps its mass and centre of mass, from the
URDF; the other figures are None, their source saying why."""

from __future__ import annotations

import math

from .figures import Figure, Section
from .outline import DIRECTIONS, footprint, radii

REST = "the robot at rest on the floor, as mcar sim releases it"
# key -> (label, unit) of every body figure but the loads (``loads.<link>``, N)
FIGURES = {
    "body.mass": ("mass", "kg"), "body.com": ("centre of mass", "m"),
    "body.com_height": ("centre of mass height", "m"), "body.footprint": ("footprint", "m"),
    "body.radius.circumscribed": ("circumscribed radius", "m"),
    "body.radius.inscribed": ("inscribed radius", "m"),
    "body.clearance": ("ground clearance", "m"), "wheels.radius": ("wheel radius", "m"),
    "wheels.track": ("track", "m"), "wheels.wheelbase": ("wheelbase", "m"),
}
# What the URDF alone gives; the others need MuJoCo's model of the robot at rest.
FROM_URDF = ("body.mass", "body.com")


def _figure(key: str, value, source: str, assumption: str = "") -> Figure:
    label, unit = FIGURES[key]
    return Figure(key, label, value, unit, source, assumption)


def section(context) -> Section:
    """The body Section of ``context`` (a :class:`~.context.SpecsContext`; its ``body`` is
    not needed: this is what makes it)."""
    sim = context.sim
    if sim is None:
        return _without_model(context.checked)
    from .loads import loads
    from .model import at_rest

    data = at_rest(sim)
    out = Section("body")
    root = data.xpos[sim.root_body]
    rotation = data.xmat[sim.root_body].reshape(3, 3)
    com_world = data.subtree_com[sim.root_body]
    com = [float(v) for v in rotation.T @ (com_world - root)]
    leaning = _leaning(sim)
    links = sum(1 for b in range(1, sim.model.nbody) if sim.model.body_mass[b] > 0)
    out.figures += [
        _figure("body.mass", sim.mass, f"<inertial><mass> of {links} link{'s' * (links != 1)}"),
        _figure("body.com", com, "<inertial> of every link, joints at 0"
                + (", springs at rest" if sim.springs else "") + ", root frame"),
        _figure("body.com_height", float(com_world[2]), "above the floor, " + REST, leaning),
    ]
    outline = footprint(sim, data)
    outer, inner = radii(outline)
    shapes = f"round shapes by their extreme points in {DIRECTIONS} directions"
    out.figures += [
        _figure("body.footprint", [list(p) for p in outline],
                "convex hull of every collision geometry at rest, projected on the floor; "
                "floor frame", shapes),
        _figure("body.radius.circumscribed", outer,
                "farthest footprint vertex from the floor frame's origin"),
        _figure("body.radius.inscribed", inner,
                "nearest footprint edge to the floor frame's origin" if inner or outer == 0
                else "the floor frame's origin is outside the footprint"),
        _clearance(sim, data),
    ]
    out.figures += _wheels(sim)
    if sim.drive is not None or sim.ground_parts:
        found = loads(sim, data)
        out.figures += [Figure(f"loads.{link}", f"load on {link}", value, "N", found.source,
                               leaning) for link, value in found.by_link.items()]
        out.notes += found.notes
    else:
        out.notes.append("no wheel or castor rests on the floor: no loads")
    return out


def _leaning(sim) -> str:
    rest = sim.rest
    if rest is None or (rest.roll == 0 and rest.pitch == 0):
        return ""
    return (f"leaning as its geometry rests: pitch {math.degrees(rest.pitch):.3g}°, roll "
            f"{math.degrees(rest.roll):.3g}°")


def _clearance(sim, data) -> Figure:
    """The lowest point at rest of what is neither a wheel nor a castor."""
    from ..sim.engine import mujoco
    from ..sim.model import colliding_geoms, lowest_points
    from ..sim.rollers import roller_bodies

    model = sim.model
    wheels = sim.drive.wheels if sim.drive else []
    touching = {w.body_id for w in wheels} | set(sim.ground_parts.values())
    skip = touching | roller_bodies(model, wheels) | _carriers(model, touching, sim.root_body)
    lowest = lowest_points(mujoco(), model, data)
    heights = [(lowest[g], g) for g in colliding_geoms(model)
               if int(model.geom_bodyid[g]) not in skip]
    if not heights:
        return _figure("body.clearance", None,
                       "every colliding part is a wheel or a castor")
    height, g = min(heights)
    link = model.body(int(model.geom_bodyid[g])).name
    return _figure("body.clearance", float(height),
                   f"lowest point of {link}, the lowest part that is no wheel or castor, "
                   + REST)


def _carriers(model, touching: set[int], root: int) -> set[int]:
    """The bodies that move with what touches the floor: those above a wheel or castor
    on a joint of their own (a castor's swivel fork, a wheel-drop arm), which ride at its
    height; a part fixed to the body (Jackal's chassis) is the body's."""
    found = set()
    for body in touching:
        parent = int(model.body_parentid[body])
        while parent not in (0, root):
            if model.body_jntnum[parent] > 0:
                found.add(parent)
            parent = int(model.body_parentid[parent])
    return found


def _wheels(sim) -> list[Figure]:
    drive = sim.drive
    if drive is None:
        why = sim.why_no_drive or "no drive wheels"
        return [_figure(key, None, why) for key in FIGURES
                if key.startswith("wheels.")]
    driven = ", ".join(w.joint for w in drive.driven)
    kind = f"{drive.kind} drive ({drive.chosen})"
    figures = [_figure("wheels.radius", drive.radius,
                       f"collision geometry of the driven wheels {driven}; {kind}")]
    if drive.left and drive.right:
        figures.append(_figure("wheels.track", drive.track,
                               "between the left and right driven wheels' centres"))
    else:
        figures.append(_figure("wheels.track", None,
                               f"a {drive.kind}: its wheels are on its centre line"))
    if drive.steering:
        figures.append(_figure("wheels.wheelbase", drive.wheelbase,
                               "from the rear axle to the steering pivots"))
        return figures
    axles = sorted({round(w.x, 3) for w in drive.wheels})
    if len(axles) < 2:
        figures.append(_figure("wheels.wheelbase", None,
                               f"one axle (x = {axles[0]:g} m): no wheelbase"))
    else:
        xs = [w.x for w in drive.wheels]
        figures.append(_figure("wheels.wheelbase", max(xs) - min(xs),
                               f"from the rearmost to the foremost axle ({len(axles)} axles)"))
    return figures


def _without_model(checked) -> Section:
    """What the URDF alone gives: mass and centre of mass; every other figure None."""
    from .model import urdf_mass

    out = Section("body")
    mass, com = urdf_mass(checked)
    why = "needs MuJoCo's model of the robot, which it has not (notes)"
    out.figures += [
        _figure("body.mass", mass, "<inertial><mass> of its links (URDF)"),
        _figure("body.com", com,
                "<inertial> of every link, joints at 0, root frame (URDF)" if com else
                "no link has mass"),
    ]
    out.figures += [_figure(key, None, why) for key in FIGURES if key not in FROM_URDF]
    return out
