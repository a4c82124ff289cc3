"""The three runs that prove the car: drop (it stands), drive (it rolls straight as far as
its wheels say), spin (it turns in place at the rate its track says). Each returns its
measured figures against their bounds; a figure out of bounds fails the scenario.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .engine import mujoco
from .model import GROUND_TOLERANCE, SimModel

SCENARIOS = ("drop", "drive", "spin")
DROP_HEIGHT = 0.005      # m above the rest height it is released from
DROP_TIME = 2.0          # s
SETTLE_TIME = 0.5        # s on the floor before drive and spin start
RAMP_TIME = 0.5          # s for the wheels' speed to ramp linearly up to the command
DRIVE_TIME = 3.0         # s
SPIN_TIME = 2.5          # s
DEFAULT_SPEED = 10.0     # rad/s when the joints give no velocity limit ...
DEFAULT_LINEAR_SPEED = 0.5  # m/s: ... or less on large wheels, a walking pace
# Bounds (README, "mcar sim").
REST_HEIGHT_BOUND = 0.001          # m
TILT_BOUND = 1.0                   # degrees, roll and pitch
REST_SPEED_BOUND = 0.002           # m/s at the end of the drop
DISTANCE_BOUND = 0.02              # of r·ω·t
LATERAL_BOUND = 0.01               # of the distance
HEADING_BOUND = 2.0                # degrees
WHEEL_SPEED_BOUND = 0.02           # of the command
YAW_RATE_BOUND = 0.05              # of 2·r·ω/track
CENTRE_BOUND = 0.01                # m
OFF_FLOOR_BOUND = 0.0              # s a wheel may spend off the floor while driving
# A wheel is off the floor when its tyre is higher than this share of its radius above it
# for at least BOUNCE_TIME: a shorter or smaller bounce is contact noise, not a lift-off.
BOUNCE_HEIGHT = 0.01               # of the wheel radius
BOUNCE_TIME = 0.020                # s


@dataclass
class Figure:
    name: str
    value: float
    bound: float
    unit: str
    within: str = "max"  # value <= bound ("max") or value >= bound ("min")
    detail: str = ""

    @property
    def ok(self) -> bool:
        if not math.isfinite(self.value):
            return False
        return bool(self.value <= self.bound if self.within == "max" else
                    self.value >= self.bound)

    def as_json(self) -> dict:
        return {"name": self.name, "value": _round(self.value), "bound": self.bound,
                "unit": self.unit, "within": self.within, "ok": self.ok}


@dataclass
class ScenarioResult:
    name: str
    figures: list[Figure] = field(default_factory=list)
    skipped: str | None = None   # why it did not run
    problems: list[str] = field(default_factory=list)  # what is wrong, for people
    seconds: float = 0.0         # simulated
    # Raw measurements behind the figures (SI units, degrees for angles), for mcar sweep's
    # rows: rest_height_m, speed_ratio, yaw_ratio, ...
    measured: dict[str, float] = field(default_factory=dict)

    @property
    def passed(self) -> bool:
        return self.skipped is None and not self.problems and all(f.ok for f in self.figures)

    @property
    def status(self) -> str:
        return "skipped" if self.skipped else "passed" if self.passed else "failed"

    def message(self) -> str:
        if self.skipped:
            return self.skipped
        failed = [f"{f.name} {show_value(f.value, f.unit)} (bound {show_bound(f)})"
                  for f in self.figures if not f.ok]
        return "; ".join(self.problems + failed) or "ok"

    def as_json(self) -> dict:
        return {"name": self.name, "status": self.status, "message": self.message(),
                "simulated_seconds": self.seconds,
                "figures": [f.as_json() for f in self.figures]}


def _round(value: float) -> float | None:
    return float(f"{value:.6g}") if math.isfinite(value) else None


def show_value(value: float, unit: str) -> str:
    """Lengths under a metre in mm, as people measure a small robot."""
    if unit in ("m", "m/s") and abs(value) < 1:
        return f"{1000 * value:.2f} m{unit}"
    return f"{value:.2f} {unit}"


def show_bound(f: Figure) -> str:
    return f"{'<=' if f.within == 'max' else '>='} {show_value(f.bound, f.unit)}"


class Run:
    """One scenario's simulation: a fresh state, the car at rest height (+ lift), stepping
    with an optional callback per step (the recorder)."""

    def __init__(self, sim: SimModel, lift: float = 0.0, frame=None):
        self.mj = mujoco()
        self.sim, self.model = sim, sim.model
        self.data = self.mj.MjData(self.model)
        adr = self.model.jnt_qposadr[self.model.joint("mcar_free").id]
        self.free = adr
        self.data.qpos[adr + 2] = sim.rest_height + lift
        self.mj.mj_forward(self.model, self.data)
        self.frame = frame

    def step(self, seconds: float, control=None, each=None) -> None:
        steps = int(round(seconds / self.model.opt.timestep))
        for _ in range(steps):
            if control is not None:
                control(self.data.time)
            self.mj.mj_step(self.model, self.data)
            if each is not None:
                each()
            if self.frame is not None:
                self.frame(self.model, self.data)

    @property
    def position(self) -> np.ndarray:
        return self.data.qpos[self.free:self.free + 3].copy()

    def euler(self) -> tuple[float, float, float]:
        """roll, pitch, yaw (rad) of the root."""
        w, x, y, z = self.data.qpos[self.free + 3:self.free + 7]
        roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
        pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
        yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
        return roll, pitch, yaw

    def on_floor(self) -> set[int]:
        """Bodies touching the floor now."""
        touching = set()
        floor = self.sim.floor_geom
        for i in range(self.data.ncon):
            contact = self.data.contact[i]
            if contact.dist > GROUND_TOLERANCE / 3:
                continue
            if contact.geom1 == floor:
                touching.add(int(self.model.geom_bodyid[contact.geom2]))
            elif contact.geom2 == floor:
                touching.add(int(self.model.geom_bodyid[contact.geom1]))
        return touching

    def at_effort_limit(self, wheel) -> bool:
        limit = self.model.actuator_forcerange[wheel.actuator_id][1]
        return abs(float(self.data.actuator_force[wheel.actuator_id])) >= 0.99 * limit

    def tyre_gap(self, wheel) -> float | None:
        """Height of the wheel's lowest sphere (its tyre) above the floor, or None when
        its geometry is no sphere (then contacts tell)."""
        gaps = [float(self.data.geom_xpos[g][2] - self.model.geom_size[g][0])
                for g in wheel.geom_ids
                if self.model.geom_type[g] == self.mj.mjtGeom.mjGEOM_SPHERE]
        return min(gaps) if gaps else None

    def wheel_speed(self, wheel) -> float:
        return float(self.data.qvel[self.model.jnt_dofadr[wheel.joint_id]])

    def axle_centre(self) -> np.ndarray:
        sim = self.sim
        return (self.data.xpos[sim.left.body_id] + self.data.xpos[sim.right.body_id]) / 2


def command_speed(sim: SimModel) -> float:
    """Half the smaller velocity limit of the two drive joints (rad/s); without one,
    DEFAULT_SPEED or DEFAULT_LINEAR_SPEED, whichever is slower on these wheels."""
    limits = [w.velocity for w in (sim.left, sim.right) if w.velocity and w.velocity > 0]
    if limits:
        return 0.5 * min(limits)
    radius = max(sim.left.radius, sim.right.radius)
    return min(DEFAULT_SPEED, DEFAULT_LINEAR_SPEED / radius) if radius > 0 else DEFAULT_SPEED


def run_drop(sim: SimModel, frame=None) -> ScenarioResult:
    result = ScenarioResult("drop", seconds=DROP_TIME)
    run = Run(sim, lift=DROP_HEIGHT, frame=frame)
    run.step(DROP_TIME)
    roll, pitch, _ = run.euler()
    height = float(run.position[2])
    speed = float(np.linalg.norm(run.data.qvel[:3]))
    result.figures = [
        Figure("height error", float(abs(height - sim.rest_height)), REST_HEIGHT_BOUND, "m",
               detail=f"rest height {sim.rest_height:.4f} m, measured {height:.4f} m"),
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
                                   "wheels (geometry): the wheels cannot both touch")
    result.measured = {"rest_height_m": height,
                       "height_error_m": float(abs(height - sim.rest_height)),
                       "tilt_deg": max(abs(math.degrees(roll)), abs(math.degrees(pitch)))}
    touching = run.on_floor()
    for wheel in (sim.left, sim.right):  # a wheel in a small bounce still stands
        gap = run.tyre_gap(wheel) if wheel is not None else None
        if gap is not None and gap <= BOUNCE_HEIGHT * wheel.radius:
            touching.add(wheel.body_id)
    expected = {w.link: w.body_id for w in (sim.left, sim.right) if w is not None}
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


def _drive_control(run: Run, sim: SimModel, omega: float, spin: bool):
    left, right = sim.left, sim.right
    signs = (forward_sign(run, left), -forward_sign(run, right) if spin else
             forward_sign(run, right))

    def control(t: float) -> None:
        speed = omega * min(1.0, max(0.0, t - SETTLE_TIME) / RAMP_TIME) if t > SETTLE_TIME \
            else 0.0
        run.data.ctrl[left.actuator_id] = signs[0] * speed
        run.data.ctrl[right.actuator_id] = signs[1] * speed
    return control, signs


def forward_sign(run: Run, wheel) -> float:
    """+1 if turning the joint positively rolls the car forward (+x), else -1."""
    axis = run.data.xaxis[wheel.joint_id]
    return 1.0 if axis[1] >= 0 else -1.0


class OffFloor:
    """Called once per step: the time the wheels spend off the floor, counting only
    lift-offs higher than BOUNCE_HEIGHT of the radius and lasting BOUNCE_TIME or more."""

    def __init__(self, run: Run, wheels):
        self.run, self.wheels = run, wheels
        self.height = BOUNCE_HEIGHT * min(w.radius for w in wheels)
        self.step = run.model.opt.timestep
        self.current, self.total = 0, 0

    def __call__(self) -> None:
        touching = None
        for wheel in self.wheels:
            gap = self.run.tyre_gap(wheel)
            if gap is None:
                touching = self.run.on_floor() if touching is None else touching
                up = wheel.body_id not in touching
            else:
                up = gap > self.height
            if up:
                self.current += 1
                return
        self.finish()

    def finish(self) -> None:
        if self.current * self.step >= BOUNCE_TIME - 1e-9:
            self.total += self.current
        self.current = 0

    @property
    def seconds(self) -> float:
        return self.total * self.step


def run_drive(sim: SimModel, frame=None) -> ScenarioResult:
    result = ScenarioResult("drive", seconds=SETTLE_TIME + DRIVE_TIME)
    run = Run(sim, frame=frame)
    axes = {w.joint: run.data.xaxis[w.joint_id].copy() for w in (sim.left, sim.right)}
    omega = command_speed(sim)
    control, signs = _drive_control(run, sim, omega, spin=False)
    run.step(SETTLE_TIME, control)
    start, (_, _, yaw0) = run.position, run.euler()
    off = OffFloor(run, (sim.left, sim.right))
    run.step(DRIVE_TIME - 0.5, control, off)
    late, clamped = [], {"steps": 0}

    def each_late():
        off()
        late.append((abs(run.wheel_speed(sim.left)), abs(run.wheel_speed(sim.right))))
        if any(run.at_effort_limit(w) for w in (sim.left, sim.right)):
            clamped["steps"] += 1
    run.step(0.5, control, each_late)
    off.finish()
    radius = (sim.left.radius + sim.right.radius) / 2
    ideal = radius * omega * (DRIVE_TIME - RAMP_TIME / 2)
    moved = run.position - start
    heading = np.array([math.cos(yaw0), math.sin(yaw0)])
    along = float(moved[:2] @ heading)
    lateral = float(abs(moved[0] * -heading[1] + moved[1] * heading[0]))
    _, _, yaw = run.euler()
    reached = min(np.mean([s[0] for s in late]), np.mean([s[1] for s in late])) / omega
    result.figures = [
        Figure("distance error", 100 * abs(along - ideal) / ideal, 100 * DISTANCE_BOUND, "%",
               detail=f"{along:.4f} m of r·ω·t = {ideal:.4f} m"),
        Figure("lateral drift", lateral, LATERAL_BOUND * ideal, "m"),
        Figure("heading change", abs(math.degrees(_wrap(yaw - yaw0))), HEADING_BOUND, "deg"),
        Figure("time off the floor", off.seconds, OFF_FLOOR_BOUND, "s",
               detail=f"higher than {1000 * off.height:.2f} mm for {1000 * BOUNCE_TIME:g} ms "
                      "or longer"),
        Figure("wheel speed reached", 100 * reached, 100 * (1 - WHEEL_SPEED_BOUND), "%",
               within="min", detail=f"command {omega:.4g} rad/s"),
    ]
    result.measured = {"speed_ratio": along / ideal,
                       "speed_m_s": along / (DRIVE_TIME - RAMP_TIME / 2),
                       "lateral_drift_m": lateral,
                       "heading_change_deg": abs(math.degrees(_wrap(yaw - yaw0)))}
    if reached < 1 - WHEEL_SPEED_BOUND:
        efforts = ", ".join(f"{w.joint} {w.effort if w.effort is not None else 0:g} N·m"
                            for w in (sim.left, sim.right))
        if clamped["steps"] * 2 >= len(late):  # the motors pushed at their limit
            result.problems.append(f"the motors' effort limit ({efforts}) cannot turn the "
                                   f"wheels at {omega:.4g} rad/s")
        else:
            gains = ", ".join(f"{w.gain:.4g}" for w in (sim.left, sim.right))
            result.problems.append(f"the wheels do not reach {omega:.4g} rad/s, though the "
                                   f"motors ({efforts}) are below their effort limit: "
                                   "something holds them back (a contact, a joint limit, "
                                   f"a load too heavy for the servo gain {gains} N·m·s/rad)")
    for wheel in (sim.left, sim.right):
        axis = axes[wheel.joint]
        if abs(axis[1]) < 0.9:
            result.problems.append(f"{wheel.joint} turns about ({_vector(axis)}), not across "
                                   "the car (y): the wheel does not roll forward")
    return result


def run_spin(sim: SimModel, frame=None) -> ScenarioResult:
    result = ScenarioResult("spin", seconds=SETTLE_TIME + SPIN_TIME)
    run = Run(sim, frame=frame)
    omega = command_speed(sim)
    control, _ = _drive_control(run, sim, omega, spin=True)
    run.step(SETTLE_TIME, control)
    centre0 = run.axle_centre()
    state = {"yaw": run.euler()[2], "turned": 0.0, "centre": 0.0}

    def each():
        yaw = run.euler()[2]
        state["turned"] += _wrap(yaw - state["yaw"])
        state["yaw"] = yaw
        state["centre"] = max(state["centre"],
                              float(np.linalg.norm((run.axle_centre() - centre0)[:2])))
    run.step(RAMP_TIME + 0.25, control, each)
    turned0 = state["turned"]
    steady = SPIN_TIME - RAMP_TIME - 0.25
    run.step(steady, control, each)
    rate = abs(state["turned"] - turned0) / steady
    radius = (sim.left.radius + sim.right.radius) / 2
    ideal = 2 * radius * omega / sim.track
    result.figures = [
        Figure("yaw rate error", 100 * abs(rate - ideal) / ideal, 100 * YAW_RATE_BOUND, "%",
               detail=f"{rate:.4f} rad/s of 2·r·ω/track = {ideal:.4f} rad/s "
                      f"(track {sim.track:.4f} m)"),
        Figure("centre moved", state["centre"], CENTRE_BOUND, "m"),
    ]
    result.measured = {"yaw_ratio": rate / ideal, "yaw_rate_rad_s": rate,
                       "centre_moved_m": state["centre"]}
    return result


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2 * math.pi) - math.pi


def _vector(values) -> str:
    return " ".join(f"{v:.3g}" for v in values)


RUNNERS = {"drop": run_drop, "drive": run_drive, "spin": run_spin}


def run_scenarios(sim: SimModel, names, frame=None) -> list[ScenarioResult]:
    results = []
    for name in names:
        if name != "drop" and not sim.drives:
            results.append(ScenarioResult(name, skipped=sim.why_no_drive))
            continue
        results.append(RUNNERS[name](sim, frame))
    return results
