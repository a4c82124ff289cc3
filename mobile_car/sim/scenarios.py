"""The runs that prove a robot, chosen by its drive kind: drop (it stands) for every robot;
drive (it rolls straight as far as its wheels say) for every vehicle; spin (it turns in
place) for differential, skid-steer and mecanum ones (:mod:`.driving`), strafe (it moves
sideways) for mecanum ones (:mod:`.strafe`), turn (it steers round the
circle its geometry says) for Ackermann ones (:mod:`.turning`). Each returns its measured
figures against their bounds; a figure out of bounds fails the scenario."""

from __future__ import annotations

import math

import numpy as np

from .driving import DRIVE_TIME, run_drive, run_spin
from .figures import Figure, ScenarioResult, show_bound, show_value
from .model import SimModel
from .run import BOUNCE_HEIGHT, Run, command_speed
from .strafe import run_strafe
from .turning import run_turn

SCENARIOS = ("drop", "drive", "strafe", "spin", "turn")
# The scenarios each drive kind runs when none are named; a robot that is no vehicle
# runs drop.
KIND_SCENARIOS = {"differential": ("drop", "drive", "spin"),
                  "skid-steer": ("drop", "drive", "spin"),
                  "ackermann": ("drop", "drive", "turn"),
                  "mecanum": ("drop", "drive", "strafe", "spin")}
DROP_HEIGHT = 0.005      # m above the rest height it is released from
DROP_TIME = 2.0          # s
# Bounds (docs/sim.md).
REST_HEIGHT_BOUND = 0.001          # m
TILT_BOUND = 1.0                   # degrees, roll and pitch
REST_SPEED_BOUND = 0.002           # m/s at the end of the drop

__all__ = ["SCENARIOS", "KIND_SCENARIOS", "DRIVE_TIME", "Figure", "ScenarioResult",
           "command_speed", "run_scenarios", "scenarios_for", "show_bound", "show_value"]


def run_drop(sim: SimModel, frame=None) -> ScenarioResult:
    result = ScenarioResult("drop", seconds=DROP_TIME)
    run = Run(sim, lift=DROP_HEIGHT, frame=frame)
    run.step(DROP_TIME)
    roll, pitch, _ = run.euler()
    height = float(run.position[2])
    speed = float(np.linalg.norm(run.data.qvel[:3]))
    result.figures = [
        Figure("height error", float(abs(height - sim.rest_height)), REST_HEIGHT_BOUND, "m",
               detail=f"rest height {_mm(sim.rest_height)} m, measured {_mm(height)} m"),
        Figure("roll", abs(math.degrees(roll)), TILT_BOUND, "deg"),
        Figure("pitch", abs(math.degrees(pitch)), TILT_BOUND, "deg"),
        Figure("speed", speed, REST_SPEED_BOUND, "m/s"),
    ]
    for link, gap in sorted(sim.clearance.items()):
        if gap > REST_HEIGHT_BOUND:
            result.problems.append(f"{link} is {1000 * gap:.2f} mm above the floor the other "
                                   "parts rest on (geometry)")
        elif gap < -REST_HEIGHT_BOUND:
            result.problems.append(f"{link} reaches {-1000 * gap:.2f} mm below the drive "
                                   "wheels (geometry): the wheels cannot all touch")
    result.measured = {"rest_height_m": height,
                       "height_error_m": float(abs(height - sim.rest_height)),
                       "tilt_deg": max(abs(math.degrees(roll)), abs(math.degrees(pitch)))}
    touching = run.on_floor()
    wheels = sim.drive.wheels if sim.drive else []
    for wheel in wheels:  # a wheel in a small bounce still stands
        gap = run.tyre_gap(wheel)
        if gap is not None and gap <= BOUNCE_HEIGHT * wheel.radius:
            touching.add(wheel.body_id)
    expected = {w.link: w.body_id for w in wheels}
    expected.update(sim.ground_parts)
    missing = sorted(name for name, body in expected.items() if body not in touching)
    others = sorted({sim.model.body(b).name for b in touching} - set(expected))
    if missing:
        result.problems.append(f"not touching the floor: {', '.join(missing)}")
    if others:
        result.problems.append(f"resting on parts the geometry does not rest on: "
                               f"{', '.join(others)}")
    if not math.isfinite(height) or height < sim.rest_height - 0.05:
        result.problems.insert(0, "fell through the floor")
    return result


def _mm(value: float) -> str:
    """Metres to 4 decimals, never "-0.0000"."""
    return f"{round(value, 4) + 0.0:.4f}"


def scenarios_for(sim: SimModel, names=None) -> list[str]:
    """The scenarios to run: ``names`` (in SCENARIOS' order), else the drive kind's."""
    if names:
        return [n for n in SCENARIOS if n in names]
    return list(KIND_SCENARIOS.get(sim.kind, ("drop", "drive", "spin")))


def _not_for(sim: SimModel, name: str) -> str | None:
    """Why scenario ``name`` does not fit the robot's drive kind, or None."""
    if name == "spin" and sim.kind == "ackermann":
        return "an Ackermann car does not turn in place: turn proves its steering"
    if name == "turn" and sim.kind in ("differential", "skid-steer", "mecanum"):
        return f"turn steers an Ackermann car: spin proves a {sim.kind} robot's turning"
    if name == "strafe" and sim.kind != "mecanum":
        return f"strafe moves a mecanum robot sideways: a {sim.kind} robot cannot"
    return None


def run_scenarios(sim: SimModel, names=None, frame=None,
                  steering: float | None = None) -> list[ScenarioResult]:
    """Run ``names`` (default: the drive kind's); ``steering``: the turn's δ (rad)."""
    results = []
    for name in scenarios_for(sim, names):
        if name != "drop" and not sim.drives:
            results.append(ScenarioResult(name, skipped=sim.why_no_drive))
            continue
        why_not = _not_for(sim, name)
        if why_not:
            results.append(ScenarioResult(name, skipped=why_not))
        elif name == "turn":
            results.append(run_turn(sim, frame, steering))
        else:
            results.append({"drop": run_drop, "drive": run_drive, "spin": run_spin,
                            "strafe": run_strafe}[name](sim, frame))
    return results
