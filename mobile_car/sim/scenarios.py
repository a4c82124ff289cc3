"""The runs that prove a robot, chosen by its drive kind: drop (it stands) for every robot;
drive (it rolls straight as far as its wheels say) for every vehicle; spin (it turns in
place) for differential, skid-steer and mecanum ones (:mod:`.driving`), strafe (it moves
sideways) for mecanum ones (:mod:`.strafe`), turn (it steers round the circle its geometry
says) for Ackermann and bicycle ones (:mod:`.turning`). Each returns its measured
figures against their bounds; a figure out of bounds fails the scenario."""

from __future__ import annotations

import math

import numpy as np

from .driving import DRIVE_TIME, run_drive, run_spin
from .figures import Figure, ScenarioResult, show_bound, show_value
from .model import SimModel, lowest_points, rest_after, resting_tyres
from .resting import RestPose
from .run import BOUNCE_HEIGHT, Run, command_speed
from .strafe import run_strafe
from .turning import run_turn

SCENARIOS = ("drop", "drive", "strafe", "spin", "turn")
# The scenarios each drive kind runs when none are named; a robot that is no vehicle
# runs drop.
KIND_SCENARIOS = {"differential": ("drop", "drive", "spin"),
                  "skid-steer": ("drop", "drive", "spin"),
                  "ackermann": ("drop", "drive", "turn"),
                  "mecanum": ("drop", "drive", "strafe", "spin"),
                  "bicycle": ("drop", "drive", "turn")}
DROP_HEIGHT = 0.005      # m above the rest height it is released from
DROP_TIME = 2.0          # s
# Bounds (docs/sim.md).
REST_HEIGHT_BOUND = 0.001          # m
TILT_BOUND = 1.0                   # degrees, roll and pitch
REST_SPEED_BOUND = 0.002           # m/s at the end of the drop
LEAN_BOUND = 2.0                   # degrees its geometry may lean it on a castor

__all__ = ["SCENARIOS", "KIND_SCENARIOS", "DRIVE_TIME", "Figure", "ScenarioResult",
           "command_speed", "run_scenarios", "scenarios_for", "show_bound", "show_value"]


def run_drop(sim: SimModel, frame=None) -> ScenarioResult:
    """Released DROP_HEIGHT above its rest, after DROP_TIME it must rest level at its rest
    height, still, on what may carry it: its wheels and castors. What touches decides: a
    castor or a free wheel that stays a few mm up is a clearance (a finding), a drive
    wheel that does not touch or a part that is neither a wheel nor a castor that does
    (a body dragging) fails it. A robot without a drive rests on whatever touches."""
    result = ScenarioResult("drop", seconds=DROP_TIME)
    run = Run(sim, lift=DROP_HEIGHT, frame=frame)
    with resting_tyres(sim):
        run.step(DROP_TIME)
    roll, pitch, _ = run.euler()
    height = float(run.position[2])
    # Sprung, the rest is the geometry's with the springs where they came to rest.
    pose = rest_after(sim, run.data) if sim.springs else sim.rest or RestPose(
        sim.rest_height, [1.0, 0.0, 0.0, 0.0], 0.0, 0.0)  # (an export judged: level)
    rest = pose.height
    speed = float(np.linalg.norm(run.data.qvel[:3]))
    detail = f"rest height {_mm(rest)} m, measured {_mm(height)} m"
    off_roll = abs(math.degrees(roll - pose.roll))
    off_pitch = abs(math.degrees(pitch - pose.pitch))
    result.figures = [
        Figure("height error", float(abs(height - rest)), REST_HEIGHT_BOUND, "m",
               detail=detail + (" (springs at their rest)" if sim.springs else "")),
        Figure("roll", off_roll, TILT_BOUND, "deg", detail=_leaning(pose.roll, roll)),
        Figure("pitch", off_pitch, TILT_BOUND, "deg", detail=_leaning(pose.pitch, pitch)),
        Figure("speed", speed, REST_SPEED_BOUND, "m/s"),
    ]
    result.measured = {"rest_height_m": height, "height_error_m": float(abs(height - rest)),
                       "tilt_deg": max(off_roll, off_pitch)}
    _leaning_geometry(sim, result)
    _what_touches(sim, run, result)
    _spring_travel(sim, run, result)
    if not math.isfinite(height) or height < rest - 0.05:
        result.problems.insert(0, "fell through the floor")
    return result


def _leaning(expected: float, measured: float) -> str:
    """The detail of a tilt figure where the geometry rests leaning (a castor lower than
    the wheels): the figure is the tilt off that pose."""
    if abs(math.degrees(expected)) < 0.01:
        return ""
    return (f"{math.degrees(measured):+.2f} deg; its geometry rests at "
            f"{math.degrees(expected):+.2f} deg")


def _leaning_geometry(sim: SimModel, result: ScenarioResult) -> None:
    """A robot whose geometry leans it past LEAN_BOUND on its wheels and castors (a wheel
    mounted high, a castor far below the wheels) fails, saying which parts are out of
    the wheels' plane; a lean under it (Create 3 on its retracted wheel drops, 0.6°) is
    the pose the tilt is measured against."""
    lean = math.degrees(max(abs(sim.rest.roll), abs(sim.rest.pitch))) if sim.rest else 0.0
    if lean <= LEAN_BOUND:
        return
    parts = []
    for link, gap in sorted(sim.clearance.items()):
        if gap > REST_HEIGHT_BOUND:
            parts.append(f"{link} is {1000 * gap:.2f} mm above the floor the other parts "
                         "rest on")
        elif gap < -REST_HEIGHT_BOUND:
            parts.append(f"{link} reaches {-1000 * gap:.2f} mm below the drive wheels")
    result.problems.append(f"its geometry leans it {lean:.2f} deg (bound {LEAN_BOUND:g} deg)"
                           + (": " + "; ".join(parts) if parts else ""))


def _what_touches(sim: SimModel, run: Run, result: ScenarioResult) -> None:
    touching = run.on_floor()
    wheels = sim.drive.wheels if sim.drive else []
    for wheel in wheels:  # a wheel in a small bounce still stands
        gap = run.tyre_gap(wheel)
        if gap is not None and gap <= BOUNCE_HEIGHT * wheel.radius:
            touching.add(wheel.body_id)
    if sim.drive is None:
        _tipped(sim, touching, result)
        return
    supports = {w.link: w.body_id for w in wheels} | dict(sim.ground_parts)
    missing = [w.link for w in sim.drive.driven if w.body_id not in touching]
    if missing:
        result.problems.append(f"not touching the floor: {', '.join(sorted(missing))} "
                               "(drive wheels)")
    others = sorted({sim.model.body(b).name for b in touching} - set(supports))
    if others:
        result.problems.append(f"resting on {', '.join(others)}: not a wheel or castor")
    lowest = lowest_points(run.mj, run.model, run.data)
    driven = {w.link for w in sim.drive.driven}
    gaps = {}
    for link, body in sorted(supports.items()):
        if link in driven or body in touching:
            continue
        gaps[link] = min(z for g, z in lowest.items() if run.model.geom_bodyid[g] == body)
        result.findings.append(f"{link} does not touch the floor: {1000 * gaps[link]:.2f} mm "
                               "above it at rest (its clearance)")
    if gaps:
        result.measured["clearance_m"] = max(gaps.values())


def _tipped(sim: SimModel, touching: set[int], result: ScenarioResult) -> None:
    """Why a robot without a drive did not come to rest level where its geometry rests at
    0: it tipped onto parts that do not reach the floor in that pose (a UR arm held out at
    0 has its centre of mass past its base's edge and lies down on its wrist). Said only
    where the figures already fail it."""
    if all(figure.ok for figure in result.figures):
        return
    onto = sorted(sim.model.body(b).name for b in touching - set(sim.ground_parts.values()))
    if onto:
        result.problems.append(f"tipped over onto {', '.join(onto)}, which the floor does "
                               "not reach as it rests at 0 (a robot bolted down is fixed "
                               "to a root link named world)")


def _spring_travel(sim: SimModel, run: Run, result: ScenarioResult) -> None:
    """Where each spring came to rest in its travel (a finding)."""
    for spring in sim.springs:
        joint = run.model.joint(spring.joint).id
        position = run.joint_angle(joint)
        unit, per = ("mm", 1000) if spring.prismatic else ("deg", 180 / math.pi)
        share = (position - spring.lower) / (spring.upper - spring.lower)
        result.findings.append(
            f"spring {spring.joint} rests at {per * position:.3g} {unit}, {100 * share:.0f}% "
            f"of its {per * spring.lower:.3g}..{per * spring.upper:.3g} {unit} travel")


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
    if name == "spin" and sim.kind == "bicycle":
        return "a bicycle does not turn in place: turn proves its steering"
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
