"""The geometry of a robot on a slope, from its contacts (:mod:`.support`): the support
polygon, the slope it tips at towards each azimuth, how its weight shares out between its
contacts, and the slope it slides at. Plain math, so that the figures are checked by
hand: lengths in m, angles in rad, azimuths measured from forward (x) towards left (y).

On a slope of angle θ whose downhill direction is u, gravity's line through the centre
of mass (height h above the floor, projection c) meets the floor at p = c + h·tan θ·u:
the robot stands while p is inside its support polygon and tips when p crosses its edge,
at θ = atan(d / h), d the distance from c to the edge along u. The contacts carry the
normal load as a rigid body on springs does (each its stiffness times a plane through
them, exact for three whatever the stiffness), over the contacts that touch at rest
until the weight's line leaves them and the robot rocks onto a castor a few mm up.
Friction holds while the contacts can resist the slope's pull m·g·sin θ along u at the
centre of mass, forces and the moment about the vertical balanced, each contact within
its friction: a held contact's μᵢ·Nᵢ in any direction, a free wheel's along its axle
only, a swivel castor's none (:func:`holding`: the largest such pull, from the support
function of the set of wrenches the contacts can make)."""

from __future__ import annotations

import math

STEP = math.radians(0.05)  # the slope search's step, then bisected
STEEPEST = math.radians(89.0)
BISECTIONS = 9  # of a 2° bracket: 0.004°


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
    for (ax, ay), (bx, by) in zip(polygon, polygon[1:] + polygon[:1], strict=True):
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
    for (ax, ay), (bx, by) in zip(polygon, polygon[1:] + polygon[:1], strict=True):
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
    for (ax, ay), (bx, by) in zip(polygon, polygon[1:] + polygon[:1], strict=True):
        length = math.hypot(bx - ax, by - ay)
        distance = ((bx - ax) * (y - ay) - (by - ay) * (x - ax)) / length
        outward = math.atan2(-(bx - ax), by - ay)  # the edge's outward normal
        best = min(best, (distance, outward))
    return math.atan2(best[0], h), best[1] % (2 * math.pi)


def loads_of(contacts, p) -> list[float]:
    """:func:`loads` over the contacts that touch at rest while the weight's line
    meets the floor within them; past an edge of theirs the robot rocks about it onto
    the castors a few mm up on that side, and the ones beyond the edge lift."""
    touching = [i for i, c in enumerate(contacts) if c.touching]
    if len(touching) == len(contacts) or not touching:
        return loads([(c.x, c.y) for c in contacts], p, [c.stiffness for c in contacts])
    polygon = hull([(contacts[i].x, contacts[i].y) for i in touching])
    if not inside(polygon, p):
        active = _rocked(contacts, touching, polygon, p)
    else:
        active = touching
    shares = loads([(contacts[i].x, contacts[i].y) for i in active], p,
                   [contacts[i].stiffness for i in active])
    out = [0.0] * len(contacts)
    for i, share in zip(active, shares, strict=True):
        out[i] = share
    return out


def _rocked(contacts, touching, polygon, p) -> list[int]:
    """The contacts the robot stands on once it rocked over the edge of ``polygon`` that
    ``p`` is beyond: the touching ones on that edge and the others past it."""
    edges = list(zip(polygon, polygon[1:] + polygon[:1], strict=True)) if len(polygon) >= 3 else \
        [tuple(polygon), tuple(reversed(polygon))] if len(polygon) == 2 else []
    best, edge = -math.inf, None
    for a, b in edges:
        length = math.hypot(b[0] - a[0], b[1] - a[1]) or 1.0
        out = -((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])) / length
        if out > best:
            best, edge = out, (a, b, length)
    if edge is None:
        return list(range(len(contacts)))
    a, b, length = edge

    def beyond(c):
        return -((b[0] - a[0]) * (c.y - a[1]) - (b[1] - a[1]) * (c.x - a[0])) / length

    on_edge = [i for i in touching if abs(beyond(contacts[i])) < 1e-6]
    past = [i for i, c in enumerate(contacts) if not c.touching and beyond(c) > 0]
    return on_edge + past if past else list(range(len(contacts)))


def loads(points, p, stiffness=None) -> list[float]:
    """Each point's share of the normal load (summing to 1) when the weight's line meets
    the floor at ``p``: as contacts of the given ``stiffness`` (equal where None) under a
    rigid body share it, each its stiffness times a plane a + b·x + c·y; a point given
    less than nothing lifts, and the others share the load again. Points on one line
    share by the lever."""
    import numpy as np

    active = list(range(len(points)))
    weights = np.ones(len(points)) if stiffness is None else np.asarray(stiffness, float)
    while active:
        xy = np.array([points[i] for i in active], dtype=float)
        a = np.column_stack([np.ones(len(active)), xy])
        w = weights[active][:, None]
        # Σ N = 1, Σ N x = p_x, Σ N y = p_y with N = W·A·k: (Aᵀ W A) k = (1, p)
        k = np.linalg.pinv(a.T @ (w * a)) @ np.array([1.0, p[0], p[1]])
        shares = (w * a) @ k
        if shares.min() >= -1e-12 or len(active) == 1:
            out = [0.0] * len(points)
            total = float(shares.clip(min=0).sum()) or 1.0
            for i, share in zip(active, shares.clip(min=0), strict=True):
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
    tan θ > :func:`holding` at the loads of θ; ``limit`` if none below it (the weight's
    line is kept within the polygon: past the tip angle the robot would be held up)."""
    x, y, h = com
    ux, uy = math.cos(azimuth), math.sin(azimuth)
    edge = reach(polygon, (x, y), azimuth)

    known: dict[float, float] = {}

    def held(theta: float) -> float:  # the slope the loads of theta hold
        d = min(h * math.tan(theta), max(0.0, edge - 1e-9))
        # Past the tip angle the weight's line stays at the edge: the same loads, the
        # same answer (TurtleBot3 burger: 120 of its 287 searches), asked once.
        if d not in known:
            shares = loads_of(contacts, (x + d * ux, y + d * uy))
            known[d] = math.atan(holding(contacts, shares, (x, y), azimuth))
        return known[d]

    # The loads shift slowly with the slope: the slope the level loads hold is close to
    # the answer; from it, 2° steps to the first slope that is not held, then halved.
    low, probe = 0.0, min(held(0.0), limit)
    while probe < limit and held(probe) >= probe:
        low, probe = probe, min(limit, probe + math.radians(2.0))
    if probe >= limit and held(limit) >= limit:
        return limit
    high = probe
    for _ in range(BISECTIONS):
        middle = (low + high) / 2
        low, high = (middle, high) if held(middle) >= middle else (low, middle)
    return low


# Directions of the twists :func:`holding` searches first (a Fibonacci sphere), then
# REFINE rounds about the best, each SHRINK times narrower.
TWISTS = 300
REFINE, SHRINK, AROUND = 8, 0.4, 40
_searched: list = []  # (the sphere, every round's draws): the same for every call


def _twists():
    """(the Fibonacci sphere of TWISTS directions, REFINE x AROUND x 3 normal draws of a
    fixed seed: the same figure every run), made once: a slide search asks ~300 times."""
    if not _searched:
        import numpy as np

        k = np.arange(TWISTS) + 0.5
        polar, turn = np.arccos(1 - 2 * k / TWISTS), math.pi * (1 + 5 ** 0.5) * k
        sphere = np.column_stack([np.sin(polar) * np.cos(turn),
                                  np.sin(polar) * np.sin(turn), np.cos(polar)])
        # (one draw of them all is the stream REFINE draws of AROUND would take)
        draws = np.random.default_rng(0).standard_normal((REFINE, AROUND, 3))
        _searched[:] = [sphere, draws]
    return _searched


def holding(contacts, shares, c, azimuth: float) -> float:
    """The largest pull along ``azimuth`` at ``c``, as a share of the normal load, that
    the contacts' friction resists with the forces and the moment about the vertical
    balanced. The wrenches (fx, fy, mz) the contacts can make are a convex set whose
    support function in a direction t = (vx, vy, ω), a twist of the robot on the floor,
    is Σ μᵢ·Nᵢ·|vᵢ| (vᵢ the contact's velocity under t; its axle's component for a free
    wheel); the pull's wrench w stays inside while s ≤ h(t) / (t·w) for every t: the
    least of that ratio is the answer. All held with one μ: μ (the contacts slide
    together, their friction's centre on the pull's line)."""
    import numpy as np

    loaded = [(ct, s) for ct, s in zip(contacts, shares, strict=True) if s > 1e-12]
    if not loaded:
        return 0.0
    if all(ct.hold == "held" for ct, _ in loaded) and len({ct.mu for ct, _ in loaded}) == 1:
        return loaded[0][0].mu
    ux, uy = math.cos(azimuth), math.sin(azimuth)
    xs = np.array([ct.x - c[0] for ct, _ in loaded])
    ys = np.array([ct.y - c[1] for ct, _ in loaded])
    force = np.array([ct.mu * s for ct, s in loaded])
    held = np.array([ct.hold == "held" for ct, _ in loaded])
    axle = np.array([ct.hold == "axle" for ct, _ in loaded])
    axes = np.array([ct.axis for ct, _ in loaded])
    scale = max(float(np.hypot(xs, ys).max()), 1e-3)  # ω in units of 1/scale
    pull = np.array([ux, uy, 0.0])  # its moment about c is 0

    def ratio(t):  # t: K x 3, (vx, vy, ω·scale)
        omega = t[:, 2:3] / scale
        vx = t[:, 0:1] - omega * ys
        vy = t[:, 1:2] + omega * xs
        speed = np.where(held, np.hypot(vx, vy), 0.0) + \
            np.where(axle, np.abs(vx * axes[:, 0] + vy * axes[:, 1]), 0.0)
        along = t @ pull
        value = (speed * force).sum(axis=1) / np.where(along > 1e-12, along, np.nan)
        return np.where(along > 1e-12, value, np.inf)

    t, draws = _twists()
    values = ratio(t)
    first = values.min()
    best, width = t[int(np.argmin(values))], 0.2
    for draw in draws:
        around = best + width * draw
        around = np.vstack([best, around / np.linalg.norm(around, axis=1, keepdims=True)])
        values = ratio(around)
        best, width = around[int(np.argmin(values))], width * SHRINK
    return float(min(ratio(best[None, :])[0], first))


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
