"""drive (every driven wheel at one speed: the robot rolls straight as far as its wheels
say) and spin (the left wheels forward, the right ones back: it turns in place, clockwise
seen from above). A differential robot spins at 2·r·ω/track; a skid-steer one slower, its
wheels sliding sideways, and spin measures by how much: the effective track 2·r·ω / yaw
rate, and the multiplier (effective / geometric track) its controller needs, against the
one its control package ships (:mod:`.control_config`)."""

from __future__ import annotations

import contextlib
import math

import numpy as np

from .causes import Watch, why_short
from .engine import mujoco
from .figures import Figure, ScenarioResult
from .mecanum import half_spans
from .model import SimModel
from .run import (
    BOUNCE_TIME,
    RAMP_TIME,
    SETTLE_TIME,
    OffFloor,
    Run,
    Yaw,
    command_speed,
    forward_sign,
    ramped,
    wrap,
)

DRIVE_TIME = 3.0         # s
SPIN_TIME = 2.5          # s
# Bounds (docs/sim.md).
DISTANCE_BOUND = 0.02              # of r·ω·t
LATERAL_BOUND = 0.01               # of the distance
HEADING_BOUND = 2.0                # degrees
WHEEL_SPEED_BOUND = 0.02           # of the command
OFF_FLOOR_BOUND = 0.0              # s a wheel may spend off the floor while driving
YAW_RATE_BOUND = 0.05              # of 2·r·ω/track (differential)
CENTRE_BOUND = 0.01                # m the axle's centre may stray while spinning
# A skid-steer robot's tyres during spin (see sliding_tyres): a contact time constant (s)
# and the friction's impedance against the normal's.
TYRE_TIME_CONSTANT = 0.05
FRICTION_RATIO = 0.03
# A skid-steer robot turns in place in the commanded direction at this share of
# 2·r·ω/track at least: an effective track up to 5 times the geometric one (real ones
# ship multipliers of 1.5 to 2).
SKID_YAW_SHARE = 0.2


def wheel_control(run: Run, sim: SimModel, omega: float, spin: bool):
    """The control callback: every driven wheel forward at ``omega`` (the right ones back
    when ``spin``), after settling, along the ramp."""
    drive = sim.drive
    return ramped(run, [(w.actuator_id, omega * forward_sign(run, w) * (
        -1.0 if spin and w in drive.right else 1.0)) for w in drive.driven])


def run_drive(sim: SimModel, frame=None) -> ScenarioResult:
    result = ScenarioResult("drive", seconds=SETTLE_TIME + DRIVE_TIME)
    run = Run(sim, frame=frame)
    driven = sim.drive.driven
    axes = {w.joint: run.data.xaxis[w.joint_id].copy() for w in driven}
    omega = command_speed(sim)
    control = wheel_control(run, sim, omega, spin=False)
    run.step(SETTLE_TIME, control)
    start, (_, _, yaw0) = run.position, run.euler()
    off = OffFloor(run, sim.drive.wheels)
    watch = Watch(run, sim, omega)
    run.step(DRIVE_TIME - 0.5, control, lambda: (off(), watch()))
    late, clamped = [], {"steps": 0}

    def each_late():
        off()
        watch()
        late.append([abs(run.wheel_speed(w)) for w in driven])
        if any(run.at_effort_limit(w) for w in driven):
            clamped["steps"] += 1
    run.step(0.5, control, each_late)
    off.finish()
    ideal = sim.drive.radius * omega * (DRIVE_TIME - RAMP_TIME / 2)
    moved = run.position - start
    heading = np.array([math.cos(yaw0), math.sin(yaw0)])
    along = float(moved[:2] @ heading)
    lateral = float(abs(moved[0] * -heading[1] + moved[1] * heading[0]))
    _, _, yaw = run.euler()
    reached = float(np.mean(late, axis=0).min()) / omega
    turned = abs(math.degrees(wrap(yaw - yaw0)))
    result.figures = [
        Figure("distance error", 100 * abs(along - ideal) / ideal, 100 * DISTANCE_BOUND, "%",
               detail=f"{along:.4f} m of r·ω·t = {ideal:.4f} m"),
        Figure("lateral drift", lateral, LATERAL_BOUND * ideal, "m"),
        Figure("heading change", turned, HEADING_BOUND, "deg"),
        Figure("time off the floor", off.seconds, OFF_FLOOR_BOUND, "s",
               detail=f"higher than {1000 * off.height:.2f} mm for {1000 * BOUNCE_TIME:g} ms "
                      "or longer"),
        Figure("wheel speed reached", 100 * reached, 100 * (1 - WHEEL_SPEED_BOUND), "%",
               within="min", detail=f"command {omega:.4g} rad/s"),
    ]
    result.measured = {"speed_ratio": along / ideal,
                       "speed_m_s": along / (DRIVE_TIME - RAMP_TIME / 2),
                       "lateral_drift_m": lateral, "heading_change_deg": turned}
    short = reached < 1 - WHEEL_SPEED_BOUND or not result.figures[0].ok
    cause = why_short(watch, along) if short else None
    if cause is not None:
        result.problems.append(f"drove short; likely cause: {cause}")
    elif reached < 1 - WHEEL_SPEED_BOUND:
        result.problems.append(_why_slow(driven, omega, clamped["steps"] * 2 >= len(late)))
    for wheel in driven:
        axis = axes[wheel.joint]
        if abs(axis[1]) < 0.9:
            result.problems.append(f"{wheel.joint} turns about ({_vector(axis)}), not across "
                                   "the car (y): the wheel does not roll forward")
    return result


def _why_slow(driven, omega: float, clamped: bool) -> str:
    efforts = ", ".join(f"{w.joint} {w.effort if w.effort is not None else 0:g} N·m"
                        for w in driven)
    if clamped:  # the motors pushed at their limit
        return f"the motors' effort limit ({efforts}) cannot turn the wheels at {omega:.4g} rad/s"
    gains = ", ".join(dict.fromkeys(f"{w.gain:.4g}" for w in driven))
    return (f"the wheels do not reach {omega:.4g} rad/s, though the motors ({efforts}) are "
            "below their effort limit: something holds them back (a contact, a joint limit, "
            f"a load too heavy for the servo gain {gains} N·m·s/rad)")


def run_spin(sim: SimModel, frame=None) -> ScenarioResult:
    result = ScenarioResult("spin", seconds=SETTLE_TIME + SPIN_TIME)
    drive = sim.drive
    skid = drive.kind == "skid-steer"
    with sliding_tyres(sim, skid):
        run = Run(sim, frame=frame)
        omega = command_speed(sim)
        control = wheel_control(run, sim, omega, spin=True)
        run.step(SETTLE_TIME, control)
        yaw = Yaw(run, lambda: run.centre_of(drive.driven))
        watch = Watch(run, sim, omega)
        run.step(RAMP_TIME + 0.25, control, lambda: (yaw(), watch()))
        turned0 = yaw.turned
        steady = SPIN_TIME - RAMP_TIME - 0.25
        centre = TurningCentre(run, drive.driven)
        run.step(steady, control, lambda: (yaw(), centre(), watch()))
    # Left wheels forward, right wheels back: clockwise, a negative yaw rate.
    rate = -(yaw.turned - turned0) / steady
    ideal = 2 * drive.radius * omega / drive.track
    detail = (f"{rate:.4f} rad/s of 2·r·ω/track = {ideal:.4f} rad/s "
              f"(track {drive.track:.4f} m)")
    lever = drive.track / 2  # the arc a wheel's rolling turns the robot through, per rad
    if drive.kind == "mecanum":  # each wheel's grip pushes at 45°: r·ω / (a + b)
        a, b = half_spans(drive)
        ideal, lever = drive.radius * omega / (a + b), a + b
        detail = (f"{rate:.4f} rad/s of r·ω/(a + b) = {ideal:.4f} rad/s (half wheelbase "
                  f"{a:.4f} m, half track {b:.4f} m)")
    if skid:
        offset, (x, y) = centre.offset()
        footprint = min(max(w.x for w in drive.driven) - min(w.x for w in drive.driven),
                        drive.track) / 2
        result.figures = [
            Figure("yaw rate", rate, SKID_YAW_SHARE * ideal, "rad/s", within="min",
                   detail=detail + ", clockwise"),
            Figure("turning centre", offset, footprint, "m",
                   detail=f"x {x:+.4f} m, y {y:+.4f} m from the wheels' centre: within "
                          "their footprint")]
        result.findings = _effective_track(sim, rate, ideal)
    else:
        result.figures = [Figure("yaw rate error", 100 * abs(rate - ideal) / ideal,
                                 100 * YAW_RATE_BOUND, "%", detail=detail),
                          Figure("centre moved", yaw.strayed, CENTRE_BOUND, "m")]
    if rate < 0:
        result.problems.append(f"turned the wrong way ({-rate:.4f} rad/s counter-clockwise) "
                               "with its left wheels forward and its right wheels back")
    if not all(f.ok for f in result.figures) or rate < 0:
        # the arc each wheel's track turned through, against what its wheels rolled
        cause = why_short(watch, -yaw.turned * lever, "turned them through an arc of",
                          slip_counts=not skid)
        if cause is not None:
            result.problems.append(f"turned short; likely cause: {cause}")
    result.measured = {"yaw_ratio": rate / ideal, "yaw_rate_rad_s": rate,
                       "centre_moved_m": yaw.strayed}
    if skid and rate > 0:
        result.measured.update({"effective_track_m": ideal / rate * drive.track,
                                "track_multiplier": ideal / rate})
    return result


@contextlib.contextmanager
def sliding_tyres(sim: SimModel, on: bool):
    """A skid-steer robot turns on sliding tyres, which MuJoCo's stiff default contact
    gets wrong: the sliding tyres lift the robot (it hops 2-3 mm at ~50 Hz) and resist
    the slide 2 to 4 times as much as Coulomb friction would (Husky's multiplier 6.5).
    Compliant tyres with a soft friction constraint (TYRE_TIME_CONSTANT, FRICTION_RATIO,
    elliptic cones) slide as Coulomb's law says: the multiplier within 5% of the quasi-
    static Coulomb solution for Husky (1.94 of 2.02), Jackal (1.52 of 1.49) and a 4-wheel
    box (1.85 of 1.79). Only for this run: a rolling tyre would creep on them (Jackal
    drives 7% short)."""
    if not on:
        yield
        return
    mj, model = mujoco(), sim.model
    geoms = [g for w in sim.drive.wheels for g in w.geom_ids]
    saved = (model.opt.cone, model.opt.impratio, model.geom_solref[geoms].copy(),
             model.geom_priority[geoms].copy())
    model.opt.cone, model.opt.impratio = mj.mjtCone.mjCONE_ELLIPTIC, FRICTION_RATIO
    model.geom_solref[geoms] = [TYRE_TIME_CONSTANT, 1.0]
    model.geom_priority[geoms] = 2  # the tyre's contact settings, not the floor's
    try:
        yield
    finally:
        model.opt.cone, model.opt.impratio = saved[0], saved[1]
        model.geom_solref[geoms], model.geom_priority[geoms] = saved[2], saved[3]


class TurningCentre:
    """Called once per step: the wheels' centre velocity and the yaw rate, in the robot's
    frame, whose means give the point the robot turns about."""

    def __init__(self, run: Run, wheels):
        self.run, self.wheels = run, wheels
        self.velocity, self.rate, self.count = np.zeros(2), 0.0, 0

    def __call__(self) -> None:
        data = self.run.data
        yaw = self.run.yaw()
        # the root's linear velocity (world) and yaw rate, carried to the wheels' centre
        root = data.qpos[self.run.free:self.run.free + 3]
        rate = float(data.qvel[self.run.free_dof + 5])
        offset = self.run.centre_of(self.wheels) - root
        world = data.qvel[self.run.free_dof:self.run.free_dof + 2] + rate * np.array(
            [-offset[1], offset[0]])
        c, s = math.cos(yaw), math.sin(yaw)
        self.velocity += [c * world[0] + s * world[1], -s * world[0] + c * world[1]]
        self.rate += rate
        self.count += 1

    def offset(self) -> tuple[float, tuple[float, float]]:
        """(distance, (x, y)) of the turning centre from the wheels' centre (m, robot
        frame): the point where the mean velocity vanishes, z × v / ω."""
        if not self.count or abs(self.rate) < 1e-9:
            return math.inf, (math.inf, math.inf)
        vx, vy = self.velocity / self.count
        rate = self.rate / self.count
        x, y = -vy / rate, vx / rate
        return math.hypot(x, y), (x, y)


def _effective_track(sim: SimModel, rate: float, ideal: float) -> list[str]:
    """The sentences a skid-steer spin adds: its effective track and multiplier, and the
    control config's multiplier where the package has one."""
    if rate <= 0:
        return []
    track = sim.drive.track
    multiplier = ideal / rate
    lines = [f"effective track {multiplier * track:.4f} m = {multiplier:.3f} × the "
             f"{track:.4f} m between the wheels (wheel_separation_multiplier {multiplier:.3f})"]
    control = getattr(sim, "control", None)
    if control is not None:
        off = 100 * (multiplier - control.multiplier) / control.multiplier
        lines.append(f"{control.where}: wheel_separation_multiplier {control.multiplier:g}; "
                     f"measured {abs(off):.1f}% {'over' if off >= 0 else 'under'} it")
    return lines


def _vector(values) -> str:
    return " ".join(f"{v:.3g}" for v in values)
