"""The static load on each wheel and castor at rest (N). One, two or three supports (not
in a line) carry the robot's weight in the one way the moments allow: by statics, exactly.
More (four wheels, two castors) are statically indeterminate, and a centre of mass outside
the supports rests on something else: the loads are then MuJoCo's contact forces
(mj_contactForce) once the robot has settled on its wheels and castors, which depend on
the contacts' stiffness as a real robot's depend on its tyres and frame. Either way they
sum to m·g; the source says which, and how closely."""

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
    solved, why = by_statics(points, (float(com[0]), float(com[1])), weight)
    if solved is not None:
        return Loads(solved, why)
    return _settled(sim, points, weight, why)


def by_statics(points: dict, com: tuple[float, float], weight: float):
    """(link -> N, source) where one, two or three supports carry ``weight`` in one way
    only, every force pushing up; else (None, why MuJoCo must tell)."""
    import numpy as np

    names = list(points)
    xy = np.array([points[n] for n in names], dtype=float).reshape(-1, 2)
    if len(names) == 1:
        return {names[0]: weight}, "statics: one support carries m·g (exact)"
    if len(names) == 2:
        along = xy[1] - xy[0]
        share = float(np.dot(np.asarray(com) - xy[0], along) / np.dot(along, along))
        forces = [weight * (1 - share), weight * share]
        how = ("statics: two supports share m·g as the centre of mass lies between them "
               "(balanced across their line; exact)")
    elif len(names) == 3:
        matrix = np.vstack([np.ones(3), xy.T])
        if abs(np.linalg.det(matrix)) < 1e-12:
            return None, "3 supports in a line: statically indeterminate"
        forces = list(np.linalg.solve(matrix, np.array([weight, weight * com[0],
                                                        weight * com[1]])))
        how = ("statics: three supports carry m·g with no moment about the centre of mass "
               "(exact)")
    else:
        return None, f"{len(names)} supports: statically indeterminate"
    if min(forces) < 0:
        return None, "the centre of mass is outside its supports"
    return {n: float(f) for n, f in zip(names, forces, strict=True)}, how


def _settled(sim, points: dict, weight: float, why: str) -> Loads:
    """MuJoCo's normal contact forces on each support after SETTLE_TIME at rest (``why``:
    why statics could not tell)."""
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
    result = Loads(found, f"MuJoCo contact forces after {SETTLE_TIME:g} s at rest ({why}); "
                          f"they sum to {total:.4g} N, m·g {weight:.4g} N "
                          f"({100 * off:.2f} % off)")
    if others:
        result.notes.append(f"parts other than the wheels and castors carry {others:.4g} N "
                            "at rest")
    if off > SUM_TOLERANCE:
        result.notes.append(f"the wheel and castor loads sum to {total:.4g} N, not m·g "
                            f"{weight:.4g} N (more than {100 * SUM_TOLERANCE:g} % off)")
    return result
