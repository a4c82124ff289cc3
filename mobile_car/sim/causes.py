"""Why a robot drove short, from what was measured while it drove, not guessed from the
outcome: a watch, called every step from the start of the ramp, keeps how far the
commands would roll the wheels, how far the driven wheels rolled, how long a motor
pushed at its effort limit, and the friction force the floor put on the parts other
than the wheels (a castor) against the weight they carry, and whether the robot tipped:
a part that is neither a wheel nor a castor (its body) on the floor, or its pitch or roll
TIP_BOUND or more off the pose it rests in. :func:`why_short` names, in this order:

* tipping: the robot tipped back (or forward, or over) onto its body, or past TIP_BOUND
  (TurtleBot 4, its centre of mass 2 mm ahead of its axle at 0.13 m, tips back onto
  base_link: slip or a castor is then no cause, the body drags);
* a dragging castor: the floor holds a non-wheel part back with more than
  CASTOR_DRAG_SHARE of the robot's weight (a free-rolling ball, mu 0.01, holds back at
  most 1% even under the whole robot), whatever the wheels and motors then did;
* the effort limit: a motor at its limit for EFFORT_TIME_SHARE of the time or longer,
  and the wheels turned less than commanded;
* wheel slip: the wheels rolled further than the robot moved;
* else the wheels turned less than commanded below their effort limit (a servo too
  weak for the load), or nothing measured explains it.

Distances in m, forces in N, times in s."""

from __future__ import annotations

import math

import numpy as np

from .run import ramp

GRAVITY = 9.81
CASTOR_DRAG_SHARE = 0.02   # of the robot's weight
EFFORT_TIME_SHARE = 0.1    # of the time watched
SHORT_SHARE = 0.01         # of the distance: lag or slip below this is no cause
JOINT_LOSS_SHARE = 0.5     # of a motor's effort: its joint's declared losses are named
# The forces on the floor's parts are sampled every this many steps (10 ms): their means
# over seconds need no more, and reading contacts costs as much as a step.
CONTACT_EVERY = 10
TIP_BOUND = 3.0            # degrees of pitch or roll off the rest pose: tipped


class Watch:
    """Called once per step: ``commanded``, the distance the commanded wheel speed
    ``omega`` (along the ramp) rolls the driven wheels; ``rolled``, the distance they
    rolled (their mean speed × radius); ``clamped``, seconds a motor was at its effort
    limit; and per part on the floor that is no wheel, the mean friction and normal
    force the floor put on it."""

    def __init__(self, run, sim, omega: float):
        self.run, self.sim, self.omega = run, sim, omega
        self.driven = sim.drive.driven
        self.step = run.model.opt.timestep
        self.commanded = self.rolled = self.seconds = 0.0
        self.clamp_steps = 0
        self.parts = {body: link for link, body in sim.ground_parts.items()}
        self.friction = dict.fromkeys(self.parts, 0.0)  # N·s
        self.normal = dict.fromkeys(self.parts, 0.0)
        self._force = np.zeros(6)
        model = run.model
        self._wheels = [(int(model.jnt_dofadr[w.joint_id]), w.radius / len(self.driven))
                        for w in self.driven]
        self._limits = [(w.actuator_id, 0.99 * float(model.actuator_forcerange[w.actuator_id][1]))
                        for w in self.driven]
        self._count = 0
        self._roll = omega * sim.drive.radius * self.step  # per step at the full command
        # Tipping: the parts that may touch the floor (wheels, what hangs below them:
        # rollers, and castors), the body parts that did, and the largest tilt seen.
        self._carriers = _below_wheels(model, {w.body_id for w in sim.drive.wheels}) \
            | set(sim.ground_parts.values())
        self.touched: dict[str, float] = {}  # link -> when it first touched (s of the run)
        self.started = run.data.time  # the wheels start (the watch's first step)
        rest = sim.rest
        self._rest = (rest.roll, rest.pitch) if rest is not None else (0.0, 0.0)
        self.tilt = (0.0, 0.0, 0.0)  # (degrees off the rest pose, roll, pitch) at the most

    def __call__(self) -> None:
        run, data, step = self.run, self.run.data, self.step
        self.seconds += step
        self.commanded += self._roll * ramp(data.time)
        qvel, force = data.qvel, data.actuator_force
        self.rolled += sum(abs(qvel[dof]) * share for dof, share in self._wheels) * step
        if any(abs(force[actuator]) >= limit for actuator, limit in self._limits):
            self.clamp_steps += 1
        self._count += 1
        if self._count % CONTACT_EVERY:
            return
        roll, pitch, _ = run.euler()
        off = math.degrees(max(abs(roll - self._rest[0]), abs(pitch - self._rest[1])))
        if off > self.tilt[0]:
            self.tilt = (off, math.degrees(roll), math.degrees(pitch))
        floor, bodies, weight = self.sim.floor_geom, run.model.geom_bodyid, CONTACT_EVERY * step
        for i in range(data.ncon):
            contact = data.contact[i]
            other = contact.geom2 if contact.geom1 == floor else \
                contact.geom1 if contact.geom2 == floor else None
            body = int(bodies[other]) if other is not None else None
            if body is not None and body not in self._carriers and contact.dist <= 0:
                self.touched.setdefault(run.model.body(body).name, data.time)
            if body in self.parts:
                run.mj.mj_contactForce(run.model, data, i, self._force)
                self.normal[body] += float(self._force[0]) * weight
                self.friction[body] += math.hypot(self._force[1], self._force[2]) * weight

    @property
    def clamped(self) -> float:
        return self.clamp_steps * self.step

    def drag(self) -> list[tuple[str, float, float]]:
        """(link, mean friction force, mean normal force) of each part on the floor."""
        if not self.seconds:
            return []
        return [(link, self.friction[body] / self.seconds, self.normal[body] / self.seconds)
                for body, link in self.parts.items()]


def why_short(watch: Watch, moved: float, moved_what: str = "moved",
              slip_counts: bool = True) -> str | None:
    """The likely cause, from the measurements, of a robot that moved ``moved`` m (along
    its heading; for a spin, the arc its wheels' track turned through: ``moved_what``
    says which) where its wheels were commanded ``watch.commanded``; ``slip_counts``:
    False where the tyres must slide (a skid-steer spin). None when nothing measured
    stands out."""
    sim, commanded, rolled = watch.sim, watch.commanded, watch.rolled
    if commanded <= 0:
        return None
    weight = sim.mass * GRAVITY
    lag = 1 - rolled / commanded
    slip = 1 - moved / rolled if rolled > 0 else 0.0
    rolling = (f"the wheels rolled {rolled:.4f} m of the {commanded:.4f} m commanded and "
               f"the robot {moved_what} {moved:.4f} m")
    clamped = (f"; the motors were at their effort limit ({_efforts(watch.driven)}) for "
               f"{watch.clamped:.2f} s of {watch.seconds:.2f} s" if watch.clamp_steps else "")
    tipped = _tipped(watch)
    if tipped is not None:
        return f"{tipped}; {rolling}{clamped}"
    draggers = [(link, force, normal) for link, force, normal in watch.drag()
                if force > CASTOR_DRAG_SHARE * weight]
    if draggers:
        parts = "; ".join(f"{link} back with {force:.2f} N ({force / normal:.2f} × the "
                          f"{normal:.2f} N it carries, {100 * force / weight:.0f}% of the "
                          "robot's weight)" if normal > 0 else f"{link} back with {force:.2f} N"
                          for link, force, normal in draggers)
        return (f"a dragging castor: the floor holds {parts}, where a free-rolling castor "
                f"(mu 0.01) holds back under 1%; {rolling}{clamped}")
    if watch.clamped >= EFFORT_TIME_SHARE * watch.seconds and lag >= SHORT_SHARE:
        return (f"the motors' effort limit ({_efforts(watch.driven)}): at it for "
                f"{watch.clamped:.2f} s of {watch.seconds:.2f} s; {rolling} "
                f"({100 * lag:.1f}% short of the command){_joint_losses(watch)}")
    if slip >= SHORT_SHARE and slip_counts:
        return (f"wheel slip: {rolling} ({100 * slip:.1f}% less than its wheels rolled), "
                f"the motors below their effort limit; the tyres' friction "
                f"({_tyre_friction(watch)}) cannot pass the drive force to the floor")
    if lag >= SHORT_SHARE:
        gains = ", ".join(dict.fromkeys(f"{w.gain:.4g}" for w in watch.driven))
        return (f"wheels that lag their command below their effort limit: {rolling} "
                f"({100 * lag:.1f}% short); something holds them back (a contact, a "
                f"joint limit, a load too heavy for the servo gain {gains} N·m·s/rad)")
    return None


def _tipped(watch: Watch) -> str | None:
    """``tipped back onto base_link: pitch -4.88 deg (3.81 deg off its rest) ...`` where
    a body part touched the floor or the tilt passed TIP_BOUND, else None."""
    off, roll, pitch = watch.tilt
    if not watch.touched and off < TIP_BOUND:
        return None
    rest_roll, rest_pitch = (math.degrees(a) for a in watch._rest)
    if abs(pitch - rest_pitch) >= abs(roll - rest_roll):  # x forward: nose up is negative
        way, angle = ("back" if pitch < rest_pitch else "forward"), f"pitch {pitch:.2f} deg"
    else:
        way, angle = "over sideways", f"roll {roll:.2f} deg"
    parts = sorted(watch.touched, key=watch.touched.get)
    onto = f" onto {', '.join(parts)}" if parts else ""
    after = watch.touched[parts[0]] - watch.started if parts else 0.0
    when = ("" if not parts else ", on the floor as the wheels started"
            if after <= CONTACT_EVERY * watch.step + 1e-9 else
            f", on the floor {after:.2f} s after the wheels started")
    return (f"tipped {way}{onto}: {angle} ({off:.2f} deg off the pose it rests in, bound "
            f"{TIP_BOUND:g} deg){when}; {_balance(watch)}")


def _balance(watch: Watch) -> str:
    """Where the centre of mass stands over the driven wheels' axle in the pose it rests
    in: ``its centre of mass 2.1 mm ahead of its axle, 0.131 m above the floor``."""
    from .run import Run

    rest = Run(watch.sim)
    model, data = rest.model, rest.data
    root = int(model.jnt_bodyid[model.joint("mcar_free").id])
    com = data.subtree_com[root]
    wheels = watch.driven
    axle = np.mean([data.xpos[w.body_id] for w in wheels], axis=0)
    floor = float(np.mean([data.xpos[w.body_id][2] - w.radius for w in wheels]))
    ahead = 1000 * float(com[0] - axle[0])  # the robot rests facing +x
    return (f"its centre of mass {abs(ahead):.1f} mm {'ahead of' if ahead >= 0 else 'behind'} "
            f"its axle, {com[2] - floor:.3f} m above the floor")


def _below_wheels(model, wheels: set[int]) -> set[int]:
    """The wheel bodies and every body below one (a mecanum wheel's rollers)."""
    found = set(wheels)
    for body in range(1, model.nbody):
        parent = body
        while parent > 0 and parent not in wheels:
            parent = int(model.body_parentid[parent])
        if parent > 0:
            found.add(body)
    return found


def _joint_losses(watch: Watch) -> str:
    """Where the wheel joints' own declared ``<dynamics>`` (damping × the commanded
    speed + friction) take JOINT_LOSS_SHARE of a motor's effort or more, the clause that
    says so (PMB2: damping 1 N·m·s/rad and friction 2 N·m take 7.08 N·m at 5.08 rad/s,
    over its 6 N·m), else ''."""
    model = watch.run.model
    found = []
    for wheel in watch.driven:
        dof = int(model.jnt_dofadr[wheel.joint_id])
        damping, friction = float(model.dof_damping[dof]), float(model.dof_frictionloss[dof])
        loss = damping * watch.omega + friction
        if wheel.effort and loss >= JOINT_LOSS_SHARE * wheel.effort and loss > 0:
            found.append(f"{wheel.joint}'s declared damping {damping:g} N·m·s/rad and "
                         f"friction {friction:g} N·m take {loss:.3g} N·m at "
                         f"{watch.omega:.3g} rad/s, {100 * loss / wheel.effort:.0f}% of its "
                         f"{wheel.effort:g} N·m")
    return "; " + "; ".join(dict.fromkeys(found)) if found else ""


def _efforts(driven) -> str:
    return ", ".join(f"{w.joint} {w.effort if w.effort is not None else 0:g} N·m"
                     for w in driven)


def _tyre_friction(watch: Watch) -> str:
    model = watch.run.model
    values = {f"{model.geom_friction[g][0]:g}" for w in watch.driven
              for g in range(model.ngeom) if model.geom_bodyid[g] == w.body_id
              and (model.geom_contype[g] or model.geom_conaffinity[g])}
    return "mu " + ", ".join(sorted(values)) if values else "unknown"
