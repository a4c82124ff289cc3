"""The static load on each wheel and castor at rest (N). Three supports that are not in a
line carry the robot's weight in the one way the moments allow: by statics, exactly.
Any other number (four wheels, a sprung pair) is statically indeterminate: the loads are
then MuJoCo's contact forces (mj_contactForce) once the robot has settled on its wheels
and castors, which depend on the contacts' stiffness as a real robot's depend on its
tyres and frame. Either way they sum to m·g; the source says which, and how closely."""

from __future__ import annotations

from dataclasses import dataclass, field

GRAVITY = 9.81
SETTLE_TIME = 1.0   # s: released at rest, then still within a few mN on a car or a Husky
# The loads must sum to m·g within this share, else a note says how far (a part other
# than a wheel or castor carries the rest, or the robot never came still).
SUM_TOLERANCE = 0.01


@dataclass
class Loads:
    by_link: dict[str, float] = field(default_factory=dict)  # link -> N
    source: str = ""
    notes: list[str] = field(default_factory=list)


def support_points(sim, data) -> dict[str, tuple[float, float]]:
    """Link -> (x, y) where each wheel and castor touches the floor, floor frame: below a
    wheel's centre, below the lowest colliding geometry of a castor."""
    from ..sim.engine import mujoco
    from ..sim.model import colliding_geoms, lowest_points

    root = data.xpos[sim.root_body]
    points = {}
    for wheel in sim.drive.wheels if sim.drive else []:
        x, y = data.xpos[wheel.body_id][:2] - root[:2]
        points[wheel.link] = (float(x), float(y))
    lowest = lowest_points(mujoco(), sim.model, data)
    for link, body in sim.ground_parts.items():
        geoms = [g for g in colliding_geoms(sim.model) if sim.model.geom_bodyid[g] == body]
        if geoms:
            g = min(geoms, key=lambda g: lowest[g])
            x, y = data.geom_xpos[g][:2] - root[:2]
            points[link] = (float(x), float(y))
    return points


def loads(sim, data) -> Loads:
    """The load on each wheel and castor of ``sim`` at rest (``data``: at rest)."""
    points = support_points(sim, data)
    weight = sim.mass * GRAVITY
    com = data.subtree_com[sim.root_body][:2] - data.xpos[sim.root_body][:2]
    if len(points) == 3:
        solved = _three_points(points, (float(com[0]), float(com[1])), weight)
        if solved is not None:
            return Loads(solved, "statics: three supports carry m·g with no moment about "
                                 "the centre of mass (exact)")
    return _settled(sim, points, weight)


def _three_points(points: dict, com: tuple[float, float], weight: float) -> dict | None:
    """Forces F on three supports: ΣF = W, Σx·F = W·x_com, Σy·F = W·y_com; None when the
    points are in a line (no unique answer)."""
    import numpy as np

    names = list(points)
    matrix = np.array([[1.0] * 3, [points[n][0] for n in names], [points[n][1] for n in names]])
    if abs(np.linalg.det(matrix)) < 1e-12:
        return None
    forces = np.linalg.solve(matrix, np.array([weight, weight * com[0], weight * com[1]]))
    return {n: float(f) for n, f in zip(names, forces, strict=True)}


def _settled(sim, points: dict, weight: float) -> Loads:
    """MuJoCo's normal contact forces on each support after SETTLE_TIME at rest."""
    import numpy as np

    from ..sim.model import resting_tyres
    from ..sim.run import Run

    run = Run(sim)
    with resting_tyres(sim):
        run.step(SETTLE_TIME)
    model, data = sim.model, run.data
    mj = run.mj
    wheel_of = {w.body_id: w.link for w in sim.drive.wheels} if sim.drive else {}
    link_of = {**{b: n for n, b in sim.ground_parts.items()}, **wheel_of}
    found = {name: 0.0 for name in points}
    others = 0.0
    force = np.zeros(6)
    for i in range(data.ncon):
        contact = data.contact[i]
        if sim.floor_geom not in (contact.geom1, contact.geom2):
            continue
        other = contact.geom2 if contact.geom1 == sim.floor_geom else contact.geom1
        mj.mj_contactForce(model, data, i, force)
        link = link_of.get(int(model.geom_bodyid[other]))
        if link is None:
            others += float(force[0])
        else:
            found[link] = found.get(link, 0.0) + float(force[0])
    total = sum(found.values())
    off = abs(total - weight) / weight if weight else 0.0
    result = Loads(found, f"MuJoCo contact forces after {SETTLE_TIME:g} s at rest "
                          f"({len(points)} supports: statically indeterminate); they sum to "
                          f"{total:.4g} N, m·g {weight:.4g} N ({100 * off:.2f} % off)")
    if others:
        result.notes.append(f"parts other than the wheels and castors carry {others:.4g} N "
                            "at rest")
    if off > SUM_TOLERANCE:
        result.notes.append(f"the wheel and castor loads sum to {total:.4g} N, not m·g "
                            f"{weight:.4g} N (more than {100 * SUM_TOLERANCE:g} % off)")
    return result
