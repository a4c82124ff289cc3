"""``mcar specs``' statics: what the robot stands on and the slopes it tips, slides and
climbs at, its top speed and its turning radius, each figure with its source; the rules
W502-W505 and E503 judge them (docs/rules.md), and MuJoCo proves the slopes
(:mod:`.proof_tilt`, :mod:`.proof_climb`) unless ``options["proof"]`` is False.

The geometry is :mod:`.slopes`'; the contacts and friction :mod:`.support`'s. Angles are
given in degrees, azimuths from forward (0) towards left (90)."""

from __future__ import annotations

import math
from functools import cached_property

from .figures import Figure, Section
from .slopes import first_failure, hull, least_tip, loads_of, slide_angle, tip_angle
from .slopes import grip as grip_along

AZIMUTH_STEP = 15       # deg between the tip polar's rays
DIRECTIONS = {"forward": 0, "left": 90, "backward": 180, "right": 270}
GRAVITY = 9.81


def section(context) -> Section:
    """The statics section of ``mcar specs`` (specs-core's SpecsContext)."""
    return statics_section(context.checked, context.sim, context.options)


def statics_section(checked, sim, options: dict | None = None) -> Section:
    """The statics of a checked robot (a CheckResult) and sim's model of it at rest;
    ``options``: ``friction`` (the tyres' mu where the description gives none),
    ``proof`` (False: no MuJoCo runs)."""
    from ..sim.vehicle import FIXED_TO_THE_WORLD, anchored, not_a_vehicle
    from .support import stance

    options = options or {}
    if sim is None:  # (the body section's notes say why MuJoCo has no model of it)
        return Section("statics", notes=["no statics: MuJoCo has no model of the robot"])
    fixed = anchored(checked.robot)
    if fixed is not None:  # no slope tips or slides what is bolted down
        return Section("statics", notes=[f"no statics: {FIXED_TO_THE_WORLD} ({fixed})"])
    found = stance(sim, sim.friction, options.get("friction"))
    result = Section("statics", notes=list(found.notes))
    statics = Statics(found, sim)
    result.figures = statics.figures()
    if options.get("proof", True) and sim.drive is not None:
        from .proof_climb import prove_climb
        from .proof_tilt import prove_tilt

        prove_tilt(sim, found, result, statics)
        prove_climb(sim, found, result, statics)
    elif sim.drive is None:
        # a vehicle sim drives no kind of (Curiosity's four steered corners) is still one
        what = "not a vehicle" if not_a_vehicle(checked.robot, checked.rest) is not None \
            else f"no drive sim drives ({sim.why_no_drive})"
        result.notes.append(f"{what}: no tilt or climb proof (they hold and drive its "
                            "wheels)")
    from .statics_rules import judge

    result.diagnostics = judge(checked, sim, result)
    return result


class Statics:
    """The figures of one stance; angles kept in rad until shown. After :meth:`figures`,
    ``slide_at`` and ``stand_at`` are the azimuths (deg) of the statics.slide and
    statics.stand figures, which the tilt proof runs towards, and ``grip_binds`` whether
    the climb figure is limited by traction alone (the climb proof's servos and share)."""

    directions = DIRECTIONS  # the tip figures' (and the tilt proof's) named azimuths

    def __init__(self, found, sim):
        self.found, self.sim = found, sim
        self.polygon = hull(found.points)
        self.com = found.com
        self._slides: dict[float, float] = {}  # azimuth (deg) -> slide angle: a search each
        self.slide_at = self.stand_at = None
        self.grip_binds = False  # after figures(): the climb is the driven wheels' grip's

    def tip(self, azimuth_deg: float) -> float:
        return tip_angle(self.polygon, self.com, math.radians(azimuth_deg))

    def slide(self, azimuth_deg: float) -> float:
        if azimuth_deg not in self._slides:
            self._slides[azimuth_deg] = slide_angle(self.found.contacts, self.polygon,
                                                    self.com, math.radians(azimuth_deg))
        return self._slides[azimuth_deg]

    def figures(self) -> list[Figure]:
        found, com = self.found, self.com
        out = [Figure("statics.support", "support polygon", [[_m(x), _m(y)] for x, y in
                                                              self.polygon], "m",
                      "the contacts of " + _parts(found.contacts) + " at rest",
                      f"the centre of mass {_m(com[2])} m above the floor, at "
                      f"[{_m(com[0])}, {_m(com[1])}]; rigid: springs and tyres do not give")]
        polar = [[a, _deg(self.tip(a))] for a in range(0, 360, AZIMUTH_STEP)]
        tip_source = "atan(d / h): d from the centre of mass to the support polygon's edge"
        out.append(Figure("statics.tip.polar", "tip-over angle by azimuth", polar, "deg",
                          tip_source + f", every {AZIMUTH_STEP}° (0 forward, 90 left)",
                          "the wheels held"))
        for name, azimuth in DIRECTIONS.items():
            out.append(Figure(f"statics.tip.{name}", f"tip-over angle {name}",
                              _deg(self.tip(azimuth)), "deg", tip_source, "the wheels held"))
        least, where = least_tip(self.polygon, com)
        out.append(Figure("statics.tip.min", "least tip-over angle", _deg(least), "deg",
                          f"{tip_source}: the nearest edge, towards azimuth "
                          f"{math.degrees(where):.1f}°", "the wheels held"))
        slides = {a: self.slide(a) for a in range(0, 360, AZIMUTH_STEP)}
        worst = self.slide_at = min(slides, key=slides.get)
        out.append(Figure("statics.slide", "slides at", _deg(slides[worst]), "deg",
                          f"the contacts' friction at their share of the load holds the "
                          f"slope's pull (forces and turning balanced) up to tan θ, worst "
                          f"towards azimuth {worst}°; {_frictions(found.contacts)}",
                          "the drive wheels braked; free wheels roll, swivel castors turn"))
        stands = {a: min(slides[a], self.tip(a)) for a in slides}
        stands[round(math.degrees(where))] = min(least, self.slide(math.degrees(where)))
        low = self.stand_at = min(stands, key=stands.get)
        what = "tips" if self.tip(low) <= slides.get(low, math.inf) else "slides"
        out.append(Figure("statics.stand", "steepest slope it stands on", _deg(stands[low]),
                          "deg", f"the least of tip-over and slide angles: {what} towards "
                          f"azimuth {low}°", "parked: the drive wheels braked"))
        out.append(self.climb())
        out.append(top_speed(self.sim))
        out.append(turning_radius(self.sim))
        return out

    def climb(self) -> Figure:
        """The steepest slope its driven wheels hold and climb, facing up it: each wheel
        pushes the least of its motor's (effort − joint friction) / r and μ·its load, the
        slope asks m·g·sin θ and the castors' drag."""
        sim = self.sim
        label = "steepest slope it climbs"
        if sim.drive is None:
            return Figure("statics.climb", label, None, "deg",
                          f"not a vehicle: {sim.why_no_drive or 'no drive wheels'}")
        wheels = _motor_forces(sim)  # body -> (N its motor pushes, wheel)
        weight = self.found.mass * GRAVITY
        climb = self.climb_angle()
        by_motors = self.climb_angle(traction=False)
        by_traction = self.climb_angle(motors=False)
        if abs(climb - by_motors) < 1e-4:
            limit = "the motors"
        elif abs(climb - by_traction) < 1e-4:
            limit = "traction"
            self.grip_binds = True
            if sim.drive.kind == "mecanum":  # what binds is not the least-loaded wheel
                limit += (" (every driven wheel at its grip along its rollers, μ·its load/√2"
                          " up the slope, front and rear alike: the load the slope moves"
                          " onto the rear wheels leaves the sum as it is)")
        else:  # the loaded wheels push their motor's most, the others slip
            limit = "the motors and traction together"
        force = sum(f for f, _ in wheels.values())
        efforts = "; ".join(sorted({f"{w.motor.effort:.4g} N·m ({w.motor.effort_from})"
                                    for _, w in wheels.values()}))
        return Figure("statics.climb", label, _deg(climb), "deg",
                      f"limited by {limit}: the motors hold {_most(by_motors)} "
                      f"(Σ effort/r = {force:.4g} N of m·g = {weight:.4g} N; effort "
                      f"{efforts}), the driven wheels' grip {_most(by_traction)}",
                      "facing straight up the slope; castors drag with their μ")

    def climb_angle(self, motors: bool = True, traction: bool = True,
                    grip_share: float = 1.0) -> float:
        """The steepest slope (rad) the driven wheels climb, each pushing the least of its
        motor's force and ``grip_share`` of its grip (its μ·load, along its rollers for a
        mecanum wheel); ``motors``/``traction`` False: that limit left out."""
        found = self.found
        wheels = _motor_forces(self.sim)
        weight = found.mass * GRAVITY

        def push(theta) -> float:
            shares, total = self.loads_at(theta), 0.0
            per_body: dict[int, float] = {}
            for contact, share in zip(found.contacts, shares, strict=True):
                if contact.role == "driven":  # (a mecanum wheel grips along its rollers)
                    per_body[contact.body] = per_body.get(contact.body, 0.0) + grip_share * \
                        grip_along(contact, 1.0, 0.0) * share * math.cos(theta)
                elif contact.hold == "held":
                    total -= contact.mu * share * math.cos(theta)  # a dragging castor
            for body, grip in per_body.items():
                motor = wheels[body][0] / weight if body in wheels else 0.0
                total += min(motor if motors else math.inf, grip if traction else math.inf)
            return total - math.sin(theta)

        return first_failure(lambda t: push(t) >= 0)

    def loads_at(self, theta: float) -> list[float]:
        """Each contact's share of the weight on a slope of ``theta`` (rad) faced
        straight up: the centre of mass moved back by h·tan θ, at most to the polygon's
        rear edge."""
        x, y, h = self.com
        shift = min(h * math.tan(theta), max(0.0, self._rear_reach - 1e-9))
        return loads_of(self.found.contacts, (x - shift, y))

    @cached_property
    def _rear_reach(self) -> float:  # (the slope searches ask it at every step)
        return _reach_back(self)


def _motor_forces(sim) -> dict:
    """driven wheel body -> (the force its motor pushes at the rim, N: (effort − the
    joint's declared friction) / r, at least 0, the wheel)."""
    model = sim.model
    out = {}
    for wheel in sim.drive.driven:
        loss = float(model.dof_frictionloss[model.jnt_dofadr[wheel.joint_id]])
        effort = wheel.motor.effort if wheel.motor is not None else (wheel.effort or 0.0)
        out[wheel.body_id] = (max(0.0, effort - loss) / wheel.radius if wheel.radius > 0
                              else 0.0, wheel)
    return out


def _reach_back(statics: Statics) -> float:
    from .slopes import reach

    x, y, _ = statics.com
    return reach(statics.polygon, (x, y), math.pi)


def top_speed(sim) -> Figure:
    """The driven wheels' least speed limit at the rim (m/s), none where it is a
    placeholder (over sim's MAX_RIM_SPEED) or not given."""
    label = "top speed"
    if sim.drive is None:
        return Figure("statics.top_speed", label, None, "m/s", "not a vehicle")
    motors = [(w, w.motor) for w in sim.drive.driven if w.motor is not None]
    placeholder = next((m.placeholder for _, m in motors if m.placeholder), None)
    if placeholder:
        return Figure("statics.top_speed", label, None, "m/s",
                      f"the speed limit is {placeholder}")
    given = [(m.velocity * w.radius, w, m) for w, m in motors if m.velocity is not None]
    if not given:
        return Figure("statics.top_speed", label, None, "m/s",
                      "no speed limit given (joint <limit velocity>, <ros2_control>, a drive "
                      "plugin or --speed)")
    speed, wheel, motor = min(given, key=lambda g: g[0])
    return Figure("statics.top_speed", label, round(speed, 6), "m/s",
                  f"{motor.velocity:g} rad/s ({motor.velocity_from} of {wheel.joint}) × "
                  f"wheel radius {wheel.radius:.4g} m", "no load: the motor's limit")


def turning_radius(sim) -> Figure:
    """0 for a drive that turns in place; an Ackermann car's or bicycle's least radius at
    its rear axle's centre, from its wheelbase and its steering joints' limits."""
    from ..sim.turning import _reach

    label = "least turning radius"
    drive = sim.drive
    if drive is None:
        return Figure("statics.turning_radius", label, None, "m", "not a vehicle")
    if drive.kind not in ("ackermann", "bicycle"):
        return Figure("statics.turning_radius", label, 0.0, "m",
                      f"turns in place ({drive.kind} drive)")
    rear_x = sum(w.x for w in drive.rear) / len(drive.rear)
    radii, limits = [], []
    for turn in (1.0, -1.0):  # left, right
        needed = 0.0
        for steer in drive.steering:
            reach = _reach(steer, turn)
            reach = math.pi / 2 if reach is None else min(reach, math.pi / 2)
            ahead = steer.x - rear_x
            lever = 0.0 if reach >= math.pi / 2 - 1e-9 else ahead / math.tan(max(reach, 1e-9))
            needed = max(needed, turn * steer.y + lever)
            limits.append(f"{steer.joint} {math.degrees(reach):.1f}°")
        radii.append(needed)
    radius = min(radii)
    return Figure("statics.turning_radius", label, round(radius, 6), "m",
                  f"wheelbase {drive.wheelbase:.4g} m over the steering limits "
                  f"({', '.join(dict.fromkeys(limits))}), at the rear axle's centre, turning "
                  f"{'left' if radii[0] <= radii[1] else 'right'}",
                  "the steered wheels at their Ackermann angles, no slip")


def _parts(contacts) -> str:
    names = list(dict.fromkeys(f"{c.link} ({c.role})" for c in contacts))
    return ", ".join(names) if names else "nothing"


def _frictions(contacts) -> str:
    seen = dict.fromkeys(f"{c.link} μ {c.mu:g} ({c.mu_from})" for c in contacts)
    return "; ".join(seen)


def _most(angle: float) -> str:
    """An angle the search found no limit under: "any slope" past STEEPEST."""
    from .slopes import STEEPEST

    return "any slope" if angle >= STEEPEST - 1e-9 else f"{_deg(angle)}°"


def _deg(angle: float) -> float:
    return round(math.degrees(angle), 4)


def _m(value: float) -> float:
    return round(value, 6)
