"""``mcar specs``' joints section (issue 42 item 2): what gravity asks of every joint that
is not fixed and is not one of the drive's wheels (lifts, arms, steering, suspension,
a castor's swivel), in its worst pose, against the effort its ``<limit>`` declares.

The load is MuJoCo's: ``qfrc_bias`` at zero velocity is the force (prismatic, N) or torque
(revolute, N·m) that holds the joint against gravity, on a model of the robot's masses with
every joint free and its root held as it rests (:func:`mobile_car.sim.model.jointed_model`;
gravity tilted as sim's resting pose leans, upright without sim). The worst pose is searched
within the limits of the joint and of the joints beyond it: each of those at its lower,
middle and upper limit (a continuous one every quarter turn), every combination or
COMBINATIONS of them drawn at random (seeded), against the joint every COARSE_DEG; the
three worst combinations again every STEP_DEG (a prismatic joint: a twentieth of its
travel), then finer around the worst. The joints before it stay at 0 (the pose check and
render show). A ``<mimic>`` joint follows its leader's pose and is not judged itself; a
continuous joint gravity turns in no pose and that declares no effort (a castor's swivel,
a wheel rolling free) is named in a note, without figures.

A suspension joint of sim's drive is carried by a spring (:mod:`mobile_car.sim.springs`):
its figure is what the spring carries at rest under the robot's weight, and it is not
judged against its effort (a note compares them).

W501 **effort-under-gravity**: a declared effort under the worst load (0 included), at
the joint's ``<limit>``.

Keys ``joints.<joint>.gravity`` (proven by holding the joint there in a simulation:
:mod:`.joints_proof`) and ``joints.<joint>.effort``, in N·m or N.
"""

from __future__ import annotations

import math

from ..check.context import Reporter
from ..check.urdf_model import parse_number
from .figures import Figure, Section
from .joints_proof import held_load
from .lookup import written_at

STEP_DEG = 5.0
COARSE_DEG = 15.0
TRAVEL_STEPS = 20  # a prismatic joint's grid: its travel in this many steps
COMBINATIONS = 64  # descendants' poses tried at most
FINE = 10          # points on each side of the worst grid point, within a step
GRAVITY = 9.81
# A load under this (N·m or N per kg carried, times g) is a rounding's: none at all.
NOISE = 1e-9
MOVING = ("revolute", "prismatic", "continuous")


def section(context) -> Section:
    """The joints section of a :class:`mobile_car.specs.context.SpecsContext`."""
    return joints_section(context.checked, context.sim, context.options.get("proof", True))


def joints_section(checked, sim=None, proof: bool = True) -> Section:
    """The joints section of a CheckResult; ``sim``: sim's SimModel at rest (its drive's
    wheels left out, its springs, its lean), or None (every moving joint, upright);
    ``proof`` False: no MuJoCo run holding the joint (``--no-proof``, diff and sweep)."""
    from ..sim.model import SimModelError, jointed_model

    found = Section("joints")
    wheels = {w.joint for w in sim.drive.wheels} if sim is not None and sim.drive else set()
    springs = {s.joint: s for s in sim.springs} if sim is not None else {}
    judged = [j for j in checked.robot.joints if j.type in MOVING and j.name not in wheels]
    declared = _declared_beyond(checked)
    # joints beyond which only MuJoCo's token masses would hang
    massless = [j.name for j in judged if declared.get(j.child, 0.0) <= 0]
    if massless:
        many = len(massless) > 1
        found.notes.append(f"joint{'s' * many} {', '.join(massless)}: no link beyond "
                           f"{'them' if many else 'it'} has mass (<inertial>): not judged "
                           "(gravity asks nothing the description says)")
        judged = [j for j in judged if j.name not in massless]
    if not judged:
        return found
    try:
        model, notes = jointed_model(checked.loaded.urdf, checked.file)
    except SimModelError as error:
        found.notes.append(f"no joint judged: {error.message}")
        return found
    found.notes += notes
    search = PoseSearch(model, _mimics(checked.robot.joints),
                        sim.rest.quat if sim is not None and sim.rest else None)
    report = Reporter(checked.file, checked.where)
    idle = []  # continuous joints gravity never loads, declaring no effort
    for joint in judged:
        limit = joint.parts.get("limit")
        effort = parse_number(limit.get("effort")) if limit is not None else None
        unit = "N" if joint.type == "prismatic" else "N·m"
        limit_at = written_at(checked, limit if limit is not None else joint.element)
        if joint.name in search.followers:
            found.notes.append(f"joint {joint.name} follows joint "
                               f"{search.followers[joint.name][0]} (<mimic>): not judged "
                               "on its own")
            continue
        if joint.name in springs:
            _sprung(found, joint, springs[joint.name], effort, unit, limit_at)
            continue
        worst = search.worst(joint.name)
        if worst is None:
            found.notes.append(f"joint {joint.name}: not in MuJoCo's model of the robot "
                               "(read as fixed): not judged")
            continue
        load, pose, tried = worst
        carried = search.carried(joint.name)
        loaded = load > NOISE * carried * GRAVITY
        if joint.type == "continuous" and effort is None and not loaded:
            idle.append(joint.name)
            continue
        shown = ", ".join(_position(name, value, kind) for name, value, kind in pose)
        found.figures.append(Figure(
            f"joints.{joint.name}.gravity", f"gravity load on {joint.name}", load, unit,
            f"MuJoCo's gravity load (qfrc_bias at rest), worst of {tried} poses: {shown}",
            "joints before it at 0, the body as it rests; the joints beyond it each at its "
            "lower, middle and upper limit (continuous: every quarter turn)",
            held_load(search, joint.name, pose, load, unit) if proof else None))
        found.figures.append(Figure(
            f"joints.{joint.name}.effort", f"declared effort of {joint.name}", effort, unit,
            f"<limit effort> of joint {joint.name} ({limit_at})" if effort is not None else
            f"joint {joint.name} declares no <limit effort>"))
        if effort is not None and loaded and effort < load:
            report.add("W501", limit if limit is not None else joint.element,
                       f"joint '{joint.name}': <limit effort> {effort:g} {unit} is under the "
                       f"{load:.4g} {unit} gravity asks of it in its worst pose ({shown}), "
                       f"carrying {carried:.4g} kg: it cannot hold it there")
    if idle:
        many = len(idle) > 1
        found.notes.append(f"joint{'s' * many} {', '.join(idle)}: continuous, no <limit "
                           f"effort>, and gravity turns {'them' if many else 'it'} in no pose "
                           "(castor swivels, wheels rolling free): no figure")
    found.diagnostics = report.diagnostics
    return found


def _sprung(found: Section, joint, spring, effort, unit: str, limit_at: str) -> None:
    carried = abs(spring.stiffness * (spring.rest - spring.reference))
    found.figures.append(Figure(
        f"joints.{joint.name}.gravity", f"load on {joint.name} at rest", carried, unit,
        f"sim's spring on it ({spring.text()}), at rest under the robot's weight",
        "the robot resting on its wheels, its weight shared as sim shares it"))
    found.figures.append(Figure(
        f"joints.{joint.name}.effort", f"declared effort of {joint.name}", effort, unit,
        f"<limit effort> of joint {joint.name} ({limit_at})" if effort is not None else
        f"joint {joint.name} declares no <limit effort>"))
    compared = "" if effort is None else \
        f" (its <limit effort> {effort:g} {unit} is {'under' if effort < carried else 'over'} that)"
    found.notes.append(f"joint {joint.name} is a suspension: a spring carries its "
                       f"{carried:.4g} {unit} at rest, not its effort{compared}")


def _declared_beyond(checked) -> dict[str, float]:
    """link -> the mass its ``<inertial>`` and those of every link below it declare, kg.
    MuJoCo's model gives a moving link without mass a token gram
    (:func:`~mobile_car.sim.model.jointed_model`): a load of token grams alone is no
    figure of the robot, and no effort is under it (ABB's and Franka's kinematic
    descriptions have no <inertial> at all)."""
    from ..sim.lint import link_mass

    own = {link.name: max(link_mass(link), 0.0) for link in checked.robot.links}
    children = checked.tree.children
    order, stack = [], [checked.tree.root]
    while stack:
        link = stack.pop()
        order.append(link)
        stack += [joint.child for joint in children.get(link, ())]
    total: dict[str, float] = {}
    for link in reversed(order):  # children before their parent
        total[link] = own.get(link, 0.0) + sum(total.get(joint.child, 0.0)
                                               for joint in children.get(link, ()))
    return total


def _mimics(joints) -> dict:
    """follower -> (leader, multiplier, offset) of each <mimic>."""
    found = {}
    for joint in joints:
        mimic = joint.parts.get("mimic")
        if mimic is None or not mimic.get("joint"):
            continue
        multiplier = parse_number(mimic.get("multiplier") or "1")
        offset = parse_number(mimic.get("offset") or "0")
        found[joint.name] = (mimic.get("joint"), 1.0 if multiplier is None else multiplier,
                             0.0 if offset is None else offset)
    return found


def _position(name: str, value: float, kind: str) -> str:
    if kind == "prismatic":
        return f"{name} {value:.4g} m"
    return f"{name} {math.degrees(value):.4g}°"



class PoseSearch:
    """The worst gravity load of each joint of a jointed MuJoCo model (see the module's
    docstring); ``quat``: the root's resting orientation (w, x, y, z), or None."""

    def __init__(self, model, mimics: dict, quat=None):
        import numpy as np

        from ..sim.engine import mujoco

        self.mj, self.model = mujoco(), model
        self.data = self.mj.MjData(model)
        self.followers = {f: m for f, m in mimics.items() if self._joint(f) is not None
                          and self._joint(m[0]) is not None}
        if quat is not None:  # gravity in the root's frame, as the robot rests
            rotation = np.zeros(9)
            self.mj.mju_quat2Mat(rotation, np.array(quat, dtype=float))
            model.opt.gravity[:] = rotation.reshape(3, 3).T @ np.array([0, 0, -GRAVITY])
        else:
            model.opt.gravity[:] = [0, 0, -GRAVITY]
        self.rng = np.random.default_rng(0)

    def _joint(self, name: str) -> int | None:
        try:
            return int(self.model.joint(name).id)
        except KeyError:
            return None

    def carried(self, name: str) -> float:
        """The mass the joint carries, kg."""
        return float(self.model.body_subtreemass[self.model.jnt_bodyid[self._joint(name)]])

    def worst(self, name: str):
        """(the largest |load|, the pose it is at: [(joint, position, kind)], poses tried)
        of joint ``name``, or None where the model has no such joint."""
        import itertools

        joint = self._joint(name)
        if joint is None:
            return None
        beyond = self._beyond(joint)
        choices = [self._samples(j) for j in beyond]
        combos = list(itertools.islice(itertools.product(*choices), COMBINATIONS + 1))
        if len(combos) > COMBINATIONS:  # too many: draw them (the first, all at the lower)
            combos = [combos[0]] + [tuple(c[self.rng.integers(len(c))] for c in choices)
                                    for _ in range(COMBINATIONS - 1)]
        low, high, step = self._range(joint)
        tried = 0
        coarse = self._grid(low, high, max(step, self._step(joint, COARSE_DEG)))
        scored = []
        for combo in combos:
            loads = [self._load(joint, q, beyond, combo) for q in coarse]
            tried += len(loads)
            scored.append((max(loads), combo))
        scored.sort(key=lambda s: -s[0])
        best = (-1.0, 0.0, combos[0])
        for _score, combo in scored[:3]:
            for q in self._grid(low, high, step):
                tried += 1
                load = self._load(joint, q, beyond, combo)
                if load > best[0]:
                    best = (load, q, combo)
        _load, q, combo = best
        for fine in self._grid(max(low, q - step), min(high, q + step), step / FINE):
            tried += 1
            load = self._load(joint, fine, beyond, combo)
            if load > best[0]:
                best = (load, fine, combo)
        load, q, combo = best
        pose = [(name, q, self._kind(joint))] + [
            (self.model.joint(j).name, v, self._kind(j)) for j, v in zip(beyond, combo,
                                                                         strict=True)]
        return load, pose, tried

    def _kind(self, joint: int) -> str:
        return "prismatic" if self.model.jnt_type[joint] == self.mj.mjtJoint.mjJNT_SLIDE \
            else "revolute"

    def _beyond(self, joint: int) -> list[int]:
        """The joints carried by ``joint``'s body, but followers (they follow)."""
        model = self.model
        top = int(model.jnt_bodyid[joint])
        found = []
        # (ints: a numpy int is never `in` a tuple of MuJoCo's enums)
        turning = (int(self.mj.mjtJoint.mjJNT_HINGE), int(self.mj.mjtJoint.mjJNT_SLIDE))
        for j in range(model.njnt):
            if j == joint or model.joint(j).name in self.followers \
                    or int(model.jnt_type[j]) not in turning:  # (a floating joint's body)
                continue
            body = int(model.jnt_bodyid[j])
            while body > top:
                body = int(model.body_parentid[body])
            if body == top and int(model.jnt_bodyid[j]) != top:
                found.append(j)
        return found

    def _range(self, joint: int) -> tuple[float, float, float]:
        low, high = self._limits(joint)
        if self._kind(joint) == "prismatic":
            return low, high, (high - low) / TRAVEL_STEPS or 1.0
        return low, high, math.radians(STEP_DEG)

    def _step(self, joint: int, degrees: float) -> float:
        return 0.0 if self._kind(joint) == "prismatic" else math.radians(degrees)

    def _limits(self, joint: int) -> tuple[float, float]:
        model = self.model
        if model.jnt_limited[joint]:
            low, high = (float(v) for v in model.jnt_range[joint])
            return low, high
        return -math.pi, math.pi  # continuous: a whole turn

    def _samples(self, joint: int) -> tuple[float, ...]:
        if not self.model.jnt_limited[joint]:
            return (0.0, math.pi / 2, math.pi, -math.pi / 2)
        low, high = self._limits(joint)
        return (low, (low + high) / 2, high)

    @staticmethod
    def _grid(low: float, high: float, step: float) -> list[float]:
        if high <= low or step <= 0:
            return [low]
        count = math.ceil((high - low) / step - 1e-9)
        return [low + (high - low) * i / count for i in range(count + 1)]

    def pose(self, data, values: dict) -> None:
        """``data`` at rest (qpos0, still) but for the joints of ``values`` (name ->
        position) and their followers."""
        self._set(data, [(self._joint(name), value) for name, value in values.items()])

    def _set(self, data, pairs) -> None:
        model = self.model
        data.qpos[:] = model.qpos0
        data.qvel[:] = 0
        for joint, value in pairs:
            data.qpos[model.jnt_qposadr[joint]] = value
        for follower, (leader, multiplier, offset) in self.followers.items():
            source = data.qpos[model.jnt_qposadr[model.joint(leader).id]]
            data.qpos[model.jnt_qposadr[model.joint(follower).id]] = multiplier * source + offset

    def _load(self, joint: int, q: float, beyond: list[int], combo: tuple) -> float:
        """|qfrc_bias| of ``joint`` at zero velocity with it at ``q``, ``beyond`` at
        ``combo``, the rest at 0 (qpos0) and each follower where its leader puts it."""
        mj, model, data = self.mj, self.model, self.data
        self._set(data, [(joint, q), *zip(beyond, combo, strict=True)])
        mj.mj_kinematics(model, data)
        mj.mj_comPos(model, data)
        mj.mj_comVel(model, data)
        mj.mj_rne(model, data, 0, data.qfrc_bias)
        return abs(float(data.qfrc_bias[model.jnt_dofadr[joint]]))
