"""strafe: a mecanum robot moves sideways, to its left, with its wheels at the speeds
mecanum_drive_controller would command (:func:`.mecanum.mecanum_speeds`: the front left
and rear right wheels back, the others forward, each at ω). It must move r·ω·t to
its left, the 0.5 s ramp accounted for, keeping its heading and drifting little forward
or back."""

from __future__ import annotations

import math

import numpy as np

from .driving import HEADING_BOUND
from .figures import Figure, ScenarioResult
from .mecanum import mecanum_speeds
from .model import SimModel
from .run import (
    RAMP_TIME,
    SETTLE_TIME,
    OffFloor,
    Run,
    command_speed,
    forward_sign,
    ramped,
    wrap,
)

STRAFE_TIME = 3.0         # s
# Bounds (docs/sim.md): rollers roll less cleanly than tyres, so sideways is held to a
# looser share than drive's 2%.
SIDEWAYS_BOUND = 0.05     # of r·ω·t
FORWARD_BOUND = 0.02      # of the sideways distance


def mecanum_control(run: Run, sim: SimModel, omega: float, vx: float, vy: float,
                    yaw_rate: float):
    """The control callback: each wheel at its share of the body motion (vx, vy, yaw
    rate) whose fastest wheel turns at ``omega``, along the ramp."""
    speeds = mecanum_speeds(sim.drive, vx, vy, yaw_rate)
    top = max(abs(s) for s in speeds.values())
    return ramped(run, [(w.actuator_id, forward_sign(run, w) * speeds[w.joint] * omega / top)
                        for w in sim.drive.driven])


def run_strafe(sim: SimModel, frame=None) -> ScenarioResult:
    result = ScenarioResult("strafe", seconds=SETTLE_TIME + STRAFE_TIME)
    run = Run(sim, frame=frame)
    omega = command_speed(sim)
    control = mecanum_control(run, sim, omega, 0.0, 1.0, 0.0)
    run.step(SETTLE_TIME, control)
    start, (_, _, yaw0) = run.position, run.euler()
    off = OffFloor(run, sim.drive.wheels)
    run.step(STRAFE_TIME, control, off)
    off.finish()
    ideal = sim.drive.radius * omega * (STRAFE_TIME - RAMP_TIME / 2)
    moved = run.position - start
    left = np.array([-math.sin(yaw0), math.cos(yaw0)])
    sideways = float(moved[:2] @ left)
    forward = float(abs(moved[0] * math.cos(yaw0) + moved[1] * math.sin(yaw0)))
    _, _, yaw = run.euler()
    turned = abs(math.degrees(wrap(yaw - yaw0)))
    result.figures = [
        Figure("sideways error", 100 * abs(sideways - ideal) / ideal, 100 * SIDEWAYS_BOUND,
               "%", detail=f"{sideways:.4f} m to the left of r·ω·t = {ideal:.4f} m"),
        Figure("forward drift", forward, FORWARD_BOUND * ideal, "m"),
        Figure("heading change", turned, HEADING_BOUND, "deg"),
        Figure("time off the floor", off.seconds, 0.0, "s"),
    ]
    if sideways < 0:
        result.problems.append(f"moved to the right ({-sideways:.4f} m) with its wheels "
                               "set to move it left: its rollers grip the other way (an O "
                               "pattern, or grip axes read wrong)")
    result.measured = {"sideways_ratio": sideways / ideal, "forward_drift_m": forward,
                       "heading_change_deg": turned}
    return result
