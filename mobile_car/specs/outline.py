"""The robot's outline on the floor: every collision geometry at rest projected on the
floor frame (x forward, y left, origin below the root's origin), its convex hull (the
footprint Nav2 takes, counter-clockwise) and the radii about the origin. Lengths in m.

A round shape is not a polygon: it contributes its exact extreme point in each of
DIRECTIONS directions, so a box, a wheel's rectangle seen from above and a cylinder's
extremes along the frame's axes are exact, and a circle's outline lies at most
1 - cos(180°/DIRECTIONS) (0.2 %) inside the true one between those directions. The
wheels are the cylinders the description gives, not the spheres sim rolls them on
(:data:`mobile_car.sim.model.SimModel.tyres`)."""

from __future__ import annotations

import math

DIRECTIONS = 48
# m: a point this near the line of its neighbours is no vertex of the footprint
STRAIGHT = 1e-8


def footprint(sim, data=None) -> list[tuple[float, float]]:
    """The convex outline, counter-clockwise from the rearmost right point, of every
    colliding geometry of ``sim`` at rest (``data``: :func:`.model.at_rest`'s, made when
    not given) projected on the floor."""
    import numpy as np

    from ..sim.engine import mujoco
    from ..sim.model import colliding_geoms
    from .model import at_rest

    mj = mujoco()
    data = at_rest(sim) if data is None else data
    root = data.xpos[sim.root_body]
    points = [shape_points(mj, sim, data, g) for g in colliding_geoms(sim.model)]
    flat = np.concatenate(points)[:, :2] - root[:2] if points else np.zeros((0, 2))
    return hull([(float(x), float(y)) for x, y in flat])


def shape_points(mj, sim, data, g):
    """Points of geom ``g`` (world frame, N x 3) whose hull, seen from above, is its
    outline: a box's corners, a mesh's vertices, a round shape's extreme points in
    DIRECTIONS horizontal directions."""
    import numpy as np

    model = sim.model
    centre, rot = data.geom_xpos[g], data.geom_xmat[g].reshape(3, 3)
    size = model.geom_size[g]
    kind = mj.mjtGeom(int(model.geom_type[g]))
    angles = np.arange(DIRECTIONS) * (2 * math.pi / DIRECTIONS)
    directions = np.stack([np.cos(angles), np.sin(angles), np.zeros(DIRECTIONS)], axis=1)
    if kind == mj.mjtGeom.mjGEOM_BOX:
        signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
        return centre + (signs * size) @ rot.T
    if kind == mj.mjtGeom.mjGEOM_MESH:
        mesh = model.geom_dataid[g]
        start, count = model.mesh_vertadr[mesh], model.mesh_vertnum[mesh]
        return centre + model.mesh_vert[start:start + count] @ rot.T
    if kind == mj.mjtGeom.mjGEOM_SPHERE:
        cylinder = _tyre(sim, model, g, size[0])
        if cylinder is None:
            return centre + size[0] * directions
        return _discs(centre, rot[:, 2], cylinder, directions)
    if kind == mj.mjtGeom.mjGEOM_CYLINDER:
        return _discs(centre, rot[:, 2], (size[0], size[1]), directions)
    if kind == mj.mjtGeom.mjGEOM_CAPSULE:
        ends = [centre + s * size[1] * rot[:, 2] for s in (-1, 1)]
        return np.concatenate([end + size[0] * directions for end in ends])
    if kind == mj.mjtGeom.mjGEOM_ELLIPSOID:
        # the support point of x'S⁻²x = 1 in direction d: R S² Rᵀd / |S Rᵀd|
        local = directions @ rot
        stretched = local * size ** 2 / np.linalg.norm(local * size, axis=1)[:, None]
        return centre + stretched @ rot.T
    return centre + model.geom_rbound[g] * directions


def _tyre(sim, model, g, radius) -> tuple[float, float] | None:
    """(radius, half length) of the wheel cylinder the sphere ``g`` rolls for, or None."""
    link = model.body(int(model.geom_bodyid[g])).name
    for cylinder in sim.tyres.get(link, ()):
        if abs(cylinder[0] - radius) <= 1e-9 * max(1.0, radius):
            return cylinder
    return None


def _discs(centre, axis, cylinder, directions):
    """The extreme points, in each direction, of a cylinder's two end discs: the support
    point of a disc of normal n in direction d is r·(d - (d·n)n)/|d - (d·n)n| from its
    centre (its centre where d is along n)."""
    import numpy as np

    radius, half = cylinder
    across = directions - (directions @ axis)[:, None] * axis
    length = np.linalg.norm(across, axis=1)
    keep = length > 1e-9
    rim = radius * across[keep] / length[keep][:, None]
    ends = [centre + s * half * axis for s in (-1, 1)]
    return np.concatenate([np.concatenate([end + rim, end[None, :]]) for end in ends])


def hull(points) -> list[tuple[float, float]]:
    """The convex hull of 2-D ``points``, counter-clockwise, no collinear vertices
    (Andrew's monotone chain), starting from the lowest x (then lowest y)."""
    unique = sorted(set((round(x, 12), round(y, 12)) for x, y in points))
    if len(unique) <= 2:
        return unique

    def inward(o, a, b) -> bool:
        """Whether ``a`` is no vertex between ``o`` and ``b``: right of the line o-b, or
        within STRAIGHT of it (a wheel on rpy="1.5707963" pokes a disc's rim 1e-9 m out)."""
        turn = (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
        return turn <= STRAIGHT * math.hypot(b[0] - o[0], b[1] - o[1])

    lower, upper = [], []
    for p in unique:
        while len(lower) >= 2 and inward(lower[-2], lower[-1], p):
            lower.pop()
        lower.append(p)
    for p in reversed(unique):
        while len(upper) >= 2 and inward(upper[-2], upper[-1], p):
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def radii(points) -> tuple[float, float]:
    """(circumscribed, inscribed) radius about the floor frame's origin of the convex
    polygon ``points`` (counter-clockwise): the farthest vertex, and the nearest edge
    (0 when the origin is not inside the polygon)."""
    if not points:
        return 0.0, 0.0
    outer = max(math.hypot(x, y) for x, y in points)
    if len(points) < 3:
        return outer, 0.0
    inner = math.inf
    for (x1, y1), (x2, y2) in zip(points, points[1:] + points[:1], strict=True):
        edge = math.hypot(x2 - x1, y2 - y1)
        if edge == 0:
            continue
        # signed distance of the origin to the edge's left (inside, counter-clockwise)
        inside = (x2 - x1) * (0 - y1) - (y2 - y1) * (0 - x1)
        if inside < 0:
            return outer, 0.0
        inner = min(inner, inside / edge)
    return outer, (0.0 if inner == math.inf else inner)
