"""The body figures of ``mcar specs``, computed first since every other section starts from
them: mass and centre of mass, the footprint and its radii, the clearance, the wheels'
radius, track and wheelbase, and the load on each wheel and castor at rest. Keys and units:
docs/specs.md. A robot MuJoCo cannot model keeps its mass and centre of mass, from the
URDF; the other figures are None, their source saying why."""

from __future__ import annotations

import math

from .figures import Figure, Section
from .outline import DIRECTIONS, footprint, hull, radii

__all__ = ["footprint", "hull", "radii", "section"]

REST = "the robot at rest on the floor, as mcar sim releases it"
# The figures (all in m) that need MuJoCo's model of the robot at rest: key -> label.
NEED_MODEL = dict(zip(
    ("body.com_height", "body.footprint", "body.radius.circumscribed", "body.radius.inscribed",
     "body.clearance", "wheels.radius", "wheels.track", "wheels.wheelbase"),
    ("centre of mass height", "footprint", "circumscribed radius", "inscribed radius",
     "ground clearance", "wheel radius", "track", "wheelbase"), strict=True))


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
        Figure("body.mass", "mass", sim.mass, "kg",
               f"<inertial><mass> of {links} link{'s' * (links != 1)}"),
        Figure("body.com", "centre of mass", com, "m",
               "<inertial> of every link, joints at 0" + (", springs at rest" if sim.springs
                                                          else "") + ", root frame"),
        Figure("body.com_height", "centre of mass height", float(com_world[2]), "m",
               "above the floor, " + REST, leaning),
    ]
    outline = footprint(sim, data)
    outer, inner = radii(outline)
    shapes = f"round shapes by their extreme points in {DIRECTIONS} directions"
    out.figures += [
        Figure("body.footprint", "footprint", [list(p) for p in outline], "m",
               "convex hull of every collision geometry at rest, projected on the floor; "
               "floor frame", shapes),
        Figure("body.radius.circumscribed", "circumscribed radius", outer, "m",
               "farthest footprint vertex from the floor frame's origin"),
        Figure("body.radius.inscribed", "inscribed radius", inner, "m",
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
    skip = {w.body_id for w in wheels} | set(sim.ground_parts.values()) | \
        roller_bodies(model, wheels)
    lowest = lowest_points(mujoco(), model, data)
    heights = [(lowest[g], g) for g in colliding_geoms(model)
               if int(model.geom_bodyid[g]) not in skip]
    if not heights:
        return Figure("body.clearance", "ground clearance", None, "m",
                      "every colliding part is a wheel or a castor")
    height, g = min(heights)
    link = model.body(int(model.geom_bodyid[g])).name
    return Figure("body.clearance", "ground clearance", float(height), "m",
                  f"lowest point of {link}, the lowest part that is no wheel or castor, "
                  + REST)


def _wheels(sim) -> list[Figure]:
    drive = sim.drive
    if drive is None:
        why = sim.why_no_drive or "no drive wheels"
        return [Figure(f"wheels.{key}", label, None, "m", f"no drive: {why}")
                for key, label in (("radius", "wheel radius"), ("track", "track"),
                                   ("wheelbase", "wheelbase"))]
    driven = ", ".join(w.joint for w in drive.driven)
    kind = f"{drive.kind} drive ({drive.chosen})"
    figures = [Figure("wheels.radius", "wheel radius", drive.radius, "m",
                      f"collision geometry of the driven wheels {driven}; {kind}")]
    if drive.left and drive.right:
        figures.append(Figure("wheels.track", "track", drive.track, "m",
                              "between the left and right driven wheels' centres"))
    else:
        figures.append(Figure("wheels.track", "track", None, "m",
                              f"a {drive.kind}: its wheels are on its centre line"))
    if drive.steering:
        figures.append(Figure("wheels.wheelbase", "wheelbase", drive.wheelbase, "m",
                              "from the rear axle to the steering pivots"))
        return figures
    axles = sorted({round(w.x, 3) for w in drive.wheels})
    if len(axles) < 2:
        figures.append(Figure("wheels.wheelbase", "wheelbase", None, "m",
                              f"one axle (x = {axles[0]:g} m): no wheelbase"))
    else:
        xs = [w.x for w in drive.wheels]
        figures.append(Figure("wheels.wheelbase", "wheelbase", max(xs) - min(xs), "m",
                              f"from the rearmost to the foremost axle ({len(axles)} axles)"))
    return figures


def _without_model(checked) -> Section:
    """What the URDF alone gives: mass and centre of mass; every other figure None."""
    from .model import urdf_mass

    out = Section("body")
    mass, com = urdf_mass(checked)
    why = "needs MuJoCo's model of the robot, which it has not (notes)"
    out.figures += [
        Figure("body.mass", "mass", mass, "kg", "<inertial><mass> of its links (URDF)"),
        Figure("body.com", "centre of mass", com, "m",
               "<inertial> of every link, joints at 0, root frame (URDF)" if com else
               "no link has mass"),
    ]
    out.figures += [Figure(key, label, None, "m", why) for key, label in NEED_MODEL.items()]
    return out
