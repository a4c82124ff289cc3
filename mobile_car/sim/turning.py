"""turn: an Ackermann car at a commanded steering angle δ (the angle of a virtual wheel
midway between the front ones), turning left; a bicycle the same, its one front wheel
steered to δ and its rear wheel the centre measured. Each front wheel is steered to its
own Ackermann angle, atan(L / (R - y)) for its pivot at y, with R = L / tan δ the radius of
the rear axle's centre and L the wheelbase; each driven wheel turns at the speed of its
own circle about the turn's centre (an ideal differential), the rear axle's centre at
r·ω. The car must drive on a circle whose radius, measured at the rear axle's centre, is
within 10% of L / tan δ. Angles in rad unless named in degrees, lengths in m."""

from __future__ import annotations

import math

import numpy as np

from ..errors import UsageError
from .figures import Figure, ScenarioResult
from .model import SimModel
from .run import (
    RAMP_TIME,
    SETTLE_TIME,
    Run,
    Yaw,
    command_speed,
    forward_sign,
    ramp,
    wheel_command,
)

TURN_TIME = 3.0            # s after settling
STEADY_AFTER = RAMP_TIME + 0.5  # s into the turn when the measurement starts
DEFAULT_STEERING = math.radians(15.0)
MIN_STEERING = math.radians(1.0)
MAX_STEERING = math.radians(80.0)  # as --steering-angle allows
# The inner wheel is steered to at most this share of its joint's limit.
LIMIT_SHARE = 0.9
RADIUS_BOUND = 0.10        # of L / tan δ
STEERING_BOUND = 1.0       # degrees between a steering joint and its Ackermann angle


def steering_angle(sim: SimModel, requested: float | None = None) -> float:
    """δ for the turn: ``requested`` (rad; UsageError where a wheel's joint cannot steer
    that far), else DEFAULT_STEERING or less, so that the inner wheel stays within
    LIMIT_SHARE of its joint's limit."""
    drive = sim.drive
    base, width = drive.wheelbase, _pivot_width(sim)
    if requested is not None:
        if not 0 < requested < MAX_STEERING:
            raise UsageError(f"--steering-angle {math.degrees(requested):g}: give an angle "
                             "between 0 and 80 degrees")
        for steer, angle in wheel_angles(sim, requested):
            upper = _reach(steer, angle)
            if upper is not None and angle > upper:
                raise UsageError(f"--steering-angle {math.degrees(requested):g}: the "
                                 f"{'inner' if steer.y > 0 else 'outer'} wheel needs "
                                 f"{math.degrees(angle):.1f}°, beyond {steer.joint}'s limit "
                                 f"of {math.degrees(upper):.1f}°")
        return requested
    delta = DEFAULT_STEERING
    inner = max(drive.steering, key=lambda s: s.y)
    upper = _reach(inner, 1.0)
    if upper is not None:
        # the inner wheel's angle -> δ; a joint that turns past a right angle (steer_bot's
        # bicycle_bot: ±180°) limits nothing the turn asks (and tan would change sign)
        most = min(LIMIT_SHARE * upper, MAX_STEERING)
        if most <= MIN_STEERING:
            return MIN_STEERING  # a joint that barely steers: the turn shows it
        delta = min(delta, math.atan(base / (base / math.tan(most) + width / 2)))
    return delta


def wheel_angles(sim: SimModel, delta: float) -> list[tuple[object, float]]:
    """(steering joint, the angle its wheel must point at) for a left turn at ``delta``."""
    drive = sim.drive
    radius = drive.wheelbase / math.tan(delta)
    rear_x = float(np.mean([w.x for w in drive.rear]))
    return [(s, math.atan2(s.x - rear_x, radius - s.y)) for s in drive.steering]


def run_turn(sim: SimModel, frame=None, delta: float | None = None) -> ScenarioResult:
    result = ScenarioResult("turn", seconds=SETTLE_TIME + TURN_TIME)
    drive = sim.drive
    delta = steering_angle(sim) if delta is None else delta
    run = Run(sim, frame=frame)
    omega = command_speed(sim)
    geometric = drive.wheelbase / math.tan(delta)
    rear_x = float(np.mean([w.x for w in drive.rear]))
    targets = [(s, s.sign * angle) for s, angle in wheel_angles(sim, delta)]
    wheels = []
    for wheel in drive.driven:  # its pivot's distance to the turn's centre, over R
        x, y = (next(s.x for s in drive.steering if s.joint == wheel.steering), wheel.y) \
            if wheel.steering else (wheel.x, wheel.y)
        share = math.hypot(x - rear_x, geometric - y) / geometric
        wheels.append((wheel.actuator_id, forward_sign(run, wheel) * share))

    def control(t: float) -> None:
        steer = min(1.0, t / SETTLE_TIME)  # steered while standing, then driven
        for s, target in targets:
            run.data.ctrl[s.actuator_id] = steer * target
        speed = omega * ramp(t)
        for actuator, share in wheels:
            run.data.ctrl[actuator] = wheel_command(run.model, actuator, share * speed)
    run.step(SETTLE_TIME + STEADY_AFTER, control)
    yaw = Yaw(run, lambda: run.centre_of(drive.rear))
    path, errors = [], []

    def each():
        yaw()
        if len(errors) % 10 == 0:
            path.append(run.centre_of(drive.rear)[:2].copy())
        errors.append(max(abs(run.joint_angle(s.joint_id) - target) for s, target in targets))
    run.step(TURN_TIME - STEADY_AFTER, control, each)
    measured = _circle_radius(np.array(path))
    error = 100 * abs(measured - geometric) / geometric
    steering_error = math.degrees(float(np.mean(errors)))
    angles = ", ".join(f"{s.joint} {math.degrees(a):.2f}°" for s, a in wheel_angles(sim, delta))
    result.figures = [
        Figure("radius error", error, 100 * RADIUS_BOUND, "%",
               detail=f"{measured:.4f} m of wheelbase / tan δ = {drive.wheelbase:.4f} m / "
                      f"tan {math.degrees(delta):.2f}° = {geometric:.4f} m"),
        Figure("steering error", steering_error, STEERING_BOUND, "deg",
               detail=f"{'steering' if drive.kind == 'bicycle' else 'Ackermann'} angles "
                      f"{angles}"),
    ]
    if yaw.turned <= 0:
        result.problems.append("did not turn left with its wheels steered left")
    if steering_error > STEERING_BOUND:
        efforts = ", ".join(f"{s.joint} {s.effort:g} N·m" for s in drive.steering
                            if s.effort is not None)
        result.problems.append("the steering joints do not hold their angles"
                               + (f" (effort limits {efforts})" if efforts else ""))
    result.measured = {"turn_radius_m": measured, "turn_radius_ratio": measured / geometric,
                       "steering_angle_deg": math.degrees(delta)}
    return result


def _circle_radius(points: np.ndarray) -> float:
    """The radius of the circle through ``points`` (N x 2), by least squares (Kåsa's fit:
    x² + y² + D x + E y + F = 0, linear in D, E, F); inf for a straight line."""
    if len(points) < 3:
        return math.inf
    a = np.column_stack([points, np.ones(len(points))])
    b = -(points ** 2).sum(axis=1)
    (d, e, f), *_ = np.linalg.lstsq(a, b, rcond=None)
    square = d * d / 4 + e * e / 4 - f
    return math.sqrt(square) if square > 0 else math.inf


def _pivot_width(sim: SimModel) -> float:
    ys = [s.y for s in sim.drive.steering]
    return max(ys) - min(ys)


def _reach(steer, angle: float) -> float | None:
    """How far the joint lets its wheel turn the way ``angle`` asks (rad), or None when
    it sets no limit."""
    joint_angle = steer.sign * angle
    bound = steer.upper if joint_angle > 0 else steer.lower
    if bound is None:
        return None
    return max(0.0, bound if joint_angle > 0 else -bound)
