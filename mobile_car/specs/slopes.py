"""The geometry of a robot on a slope, from its contacts (:mod:`.support`): the support
polygon, the slope it tips at towards each azimuth, how its weight shares out between its
contacts, and the slope it slides at. Plain math, so that the figures are checked by
hand: lengths in m, angles in rad, azimuths measured from forward (x) towards left (y).

On a slope of angle θ whose downhill direction is u, gravity's line through the centre of
mass (height h above the floor, projection c) meets the floor at p = c + h·tan θ·u: the
robot stands while p is inside its support polygon and tips when p crosses its edge, at
θ = atan(d / h), d the distance from c to the edge along u. The contacts carry the normal
load as a rigid body on equally stiff contacts does (the load a plane through them,
exact for three); friction holds while m·g·sin θ ≤ Σ μᵢ·Nᵢ along u (each contact's
friction that points along u: all of a held contact's, the part of a free wheel's along
its axle, none of a swivel castor's). The moments the contacts' friction makes about the
vertical are not balanced: equal in every held contact, as on four braked wheels, they
need not be."""

from __future__ import annotations

import math

STEP = math.radians(0.05)  # the slope search's step, then bisected
STEEPEST = math.radians(89.0)


def hull(points: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """The convex hull, counter-clockwise from the lowest-leftmost point (Andrew's
    monotone chain); collinear points dropped."""
    pts = sorted(set((round(x, 9), round(y, 9)) for x, y in points))
    if len(pts) <= 2:
        return pts

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 1e-12:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 1e-12:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def reach(polygon, c: tuple[float, float], azimuth: float) -> float:
    """How far from ``c`` along ``azimuth`` the polygon's edge is (m); 0 when ``c`` is
    outside it or on its edge, or the polygon has no area."""
    if len(polygon) < 3 or not inside(polygon, c):
        return 0.0
    ux, uy = math.cos(azimuth), math.sin(azimuth)
    best = math.inf
    for (ax, ay), (bx, by) in zip(polygon, polygon[1:] + polygon[:1]):
        ex, ey = bx - ax, by - ay
        denominator = ux * ey - uy * ex
        if abs(denominator) < 1e-15:
            continue
        t = ((ax - c[0]) * ey - (ay - c[1]) * ex) / denominator
        s = ((ax - c[0]) * uy - (ay - c[1]) * ux) / denominator
        if t >= 0 and -1e-12 <= s <= 1 + 1e-12:
            best = min(best, t)
    return 0.0 if best is math.inf else best


def inside(polygon, p, margin: float = 1e-12) -> bool:
    """Whether ``p`` is inside the counter-clockwise convex ``polygon`` (not on its edge)."""
    for (ax, ay), (bx, by) in zip(polygon, polygon[1:] + polygon[:1]):
        if (bx - ax) * (p[1] - ay) - (by - ay) * (p[0] - ax) <= margin:
            return False
    return len(polygon) >= 3


def tip_angle(polygon, com, azimuth: float) -> float:
    """The slope (rad) at which the robot tips towards ``azimuth``: atan(d / h)."""
    x, y, h = com
    return math.atan2(reach(polygon, (x, y), azimuth), h) if h > 0 else math.pi / 2


def least_tip(polygon, com) -> tuple[float, float]:
    """(the least tip angle, its azimuth), both rad: the nearest edge, which the centre
    of mass's projection reaches square to it."""
    x, y, h = com
    if len(polygon) < 3 or not inside(polygon, (x, y)):
        return 0.0, 0.0
    best = (math.inf, 0.0)
    for (ax, ay), (bx, by) in zip(polygon, polygon[1:] + polygon[:1]):
        length = math.hypot(bx - ax, by - ay)
        distance = ((bx - ax) * (y - ay) - (by - ay) * (x - ax)) / length
        outward = math.atan2(-(bx - ax), by - ay)  # the edge's outward normal
        best = min(best, (distance, outward))
    return math.atan2(best[0], h), best[1] % (2 * math.pi)


def loads(points, p) -> list[float]:
    """Each point's share of the normal load (summing to 1) when the weight's line meets
    the floor at ``p``: a plane N = a + b·x + c·y through the points, as equally stiff
    contacts under a rigid body share it; a point the plane gives less than nothing
    lifts, and the others share the load again. Points on one line share by the lever."""
    import numpy as np

    active = list(range(len(points)))
    while active:
        xy = np.array([points[i] for i in active], dtype=float)
        a = np.column_stack([np.ones(len(active)), xy])
        # Σ N = 1, Σ N x = p_x, Σ N y = p_y with N = A·k: (Aᵀ A) k = (1, p)
        k = np.linalg.pinv(a.T @ a) @ np.array([1.0, p[0], p[1]])
        shares = a @ k
        if shares.min() >= -1e-12 or len(active) == 1:
            out = [0.0] * len(points)
            total = float(shares.clip(min=0).sum()) or 1.0
            for i, share in zip(active, shares.clip(min=0)):
                out[i] = float(share) / total
            return out
        active.pop(int(shares.argmin()))
    return [0.0] * len(points)


def grip(contact, ux: float, uy: float) -> float:
    """The friction coefficient ``contact`` holds with along (ux, uy)."""
    if contact.hold == "held":
        return contact.mu
    if contact.hold == "axle":
        return contact.mu * abs(contact.axis[0] * ux + contact.axis[1] * uy)
    return 0.0


def slide_angle(contacts, polygon, com, azimuth: float, limit: float = STEEPEST) -> float:
    """The slope (rad) at which the robot slides towards ``azimuth``: the least θ with
    tan θ > Σ μᵢ·shareᵢ(θ) along it; ``limit`` if none below it (the weight's line is
    kept within the polygon: past the tip angle the robot would be held up)."""
    x, y, h = com
    ux, uy = math.cos(azimuth), math.sin(azimuth)
    points = [(c.x, c.y) for c in contacts]
    mus = [grip(c, ux, uy) for c in contacts]
    edge = reach(polygon, (x, y), azimuth)

    def holds(theta: float) -> bool:
        d = min(h * math.tan(theta), max(0.0, edge - 1e-9))
        shares = loads(points, (x + d * ux, y + d * uy))
        return math.tan(theta) <= sum(m * s for m, s in zip(mus, shares))

    return first_failure(holds, limit)


def first_failure(holds, limit: float = STEEPEST) -> float:
    """The least angle in [0, limit] where ``holds`` turns False (STEP, then bisected),
    ``limit`` if it never does."""
    if not holds(0.0):
        return 0.0
    theta = 0.0
    while theta < limit:
        upper = min(theta + 20 * STEP, limit)
        if not holds(upper):
            low, high = theta, upper
            for _ in range(30):
                middle = (low + high) / 2
                low, high = (middle, high) if holds(middle) else (low, middle)
            return low
        theta = upper
    return limit
