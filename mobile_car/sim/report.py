"""One robot's simulation, start to end (lint, model, scenarios), and its three spellings:
a text table, JSON, JUnit. The library builds the strings; the command line prints them."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from xml.etree import ElementTree as ET

from ..errors import EXIT_OK, EXIT_PROBLEMS
from .junit import junit_case, junit_document
from .lint import SimDiagnostic, lint
from .prepare import prepare
from .rollers import mecanum_lines, mecanum_summary
from .scenarios import (
    ScenarioResult,
    command_speed,
    run_scenarios,
    scenarios_for,
    show_bound,
    show_value,
)
from .vehicle import FIXED_TO_THE_WORLD, NotAVehicle, not_a_vehicle, unsimulable


@dataclass
class SimReport:
    file: str
    robot: str | None
    drive: dict | None = None            # kind, wheel groups, radius, track, command speed
    why_no_drive: str | None = None
    diagnostics: list[SimDiagnostic] = field(default_factory=list)
    scenarios: list[ScenarioResult] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    error: str | None = None             # the model could not be made
    seconds: float = 0.0                 # wall clock
    recording: bytes | None = None       # the GIF, with record=True
    simulated: bool = True               # False: not a vehicle, and only_if_drives
    not_a_vehicle: NotAVehicle | None = None
    held: list[str] = field(default_factory=list)  # joints welded still: not the drive's
    reads: list = field(default_factory=list)      # files read besides the robot's (Paths)

    @property
    def lint_errors(self) -> list[SimDiagnostic]:
        return [d for d in self.diagnostics if d.is_error]

    @property
    def exit_code(self) -> int:
        if self.error or self.lint_errors or any(s.status == "failed" for s in self.scenarios):
            return EXIT_PROBLEMS
        return EXIT_OK


def simulate(checked, names=None, left=None, right=None,
             record: bool | tuple[int, int] = False,
             only_if_drives: bool = False, effort: float | None = None,
             speed: float | None = None, kind: str | None = None,
             steering: float | None = None, fix_inertia: bool = False,
             setting=None) -> SimReport:
    """Lint and run ``names`` (default: the drive kind's scenarios) on a robot that passed
    ``mcar check`` (a CheckResult); ``left``/``right``: the driven joints of each side,
    ``kind``: the drive kind (:mod:`.drives`; both else found from the tree); ``record``:
    keep a GIF of the runs (True, or its size in pixels, width x height);
    ``only_if_drives``: a robot that is not a vehicle
    (:func:`.vehicle.not_a_vehicle`) is not simulated (``simulated`` False), as for the
    files of a package and in ``mcar ci``; ``effort``, ``speed``: the drive motors'
    figures where the description gives none (:mod:`.motors`); ``steering``: the turn's
    steering angle (rad); ``setting``: ({kind, left, right}, where) of the package's
    mcar.yaml ``sim.drive``
    (:meth:`~mobile_car.packages.package_config.PackageConfig.sim_drive_for`), which the
    options override."""
    started = time.perf_counter()
    loaded = checked.loaded
    report = SimReport(checked.file, checked.robot.name)
    why_not = not_a_vehicle(checked.robot, checked.rest)
    if only_if_drives and why_not:
        report.simulated, report.not_a_vehicle = False, why_not
        report.why_no_drive = str(why_not)
        return report
    if why_not is not None and why_not.kind == FIXED_TO_THE_WORLD:
        report.why_no_drive, report.not_a_vehicle = str(why_not), why_not
        report.scenarios = [ScenarioResult(name, skipped=report.why_no_drive)
                            for name in (names or ("drop", "drive", "spin"))]
        return report
    problems = unsimulable(checked.robot)
    if problems:
        report.why_no_drive = str(why_not) if why_not else "no drive wheels: " + problems[0]
        report.scenarios = [ScenarioResult(name, problems=problems) if name == "drop" else
                            ScenarioResult(name, skipped=report.why_no_drive)
                            for name in (names or ("drop", "drive", "spin"))]
        return report
    prepared = prepare(checked, left, right, kind, effort, speed, fix_inertia, setting)
    report.diagnostics, report.reads = prepared.diagnostics, prepared.reads
    if prepared.sim is None:
        report.error = prepared.error
        return report
    sim = prepared.sim
    report.notes = prepared.notes
    report.held = list(sim.held)
    report.diagnostics = lint(checked, sim, prepared.declared)
    report.why_no_drive = str(why_not) if why_not else sim.why_no_drive
    delta = None
    if sim.drives:
        report.drive = drive_summary(sim)
        if sim.kind == "skid-steer":
            from .control_config import find_control_config

            sim.control, unread = find_control_config(loaded, [w.joint for w in sim.drive.driven])
            report.notes = list(dict.fromkeys(report.notes + unread))
            if sim.control is not None and sim.control.file not in report.reads:
                report.reads.append(sim.control.file)
        if sim.kind in ("ackermann", "bicycle") and "turn" in scenarios_for(sim, names):
            from .turning import steering_angle

            delta = steering_angle(sim, steering)
            report.drive["steering_angle_deg"] = round(math.degrees(delta), 6)
    recorder = None
    if record:
        from .record import Recorder

        recorder = Recorder(sim, scenarios_for(sim, names),
                            record if isinstance(record, tuple) else None)
    try:
        report.scenarios = run_scenarios(sim, names, recorder, delta)
        if not sim.drives and why_not is None:
            undriven(report.scenarios)
        if recorder is not None:
            report.recording = recorder.gif()
    finally:
        if recorder is not None:
            recorder.close()
    report.seconds = time.perf_counter() - started
    return report


def undriven(scenarios) -> None:
    """A vehicle that could not be driven is not a pass: the drive scenarios it was asked
    for fail, with the reason (drop alone, asked for, still passes)."""
    for scenario in scenarios:
        if scenario.name != "drop" and scenario.skipped:
            scenario.problems = [f"cannot drive this vehicle: {scenario.skipped}"]
            scenario.skipped = None


def drive_summary(sim) -> dict:
    """The drive as the report gives it: kind, wheel groups, sizes, motors (JSON-ready)."""
    drive = sim.drive
    summary = {"kind": drive.kind, "chosen": drive.chosen,
               "left": [w.joint for w in drive.left], "right": [w.joint for w in drive.right],
               "free": [w.joint for w in drive.free],
               "steering": [s.joint for s in drive.steering],
               "wheel_radius": round(drive.radius, 6), "track": round(drive.track, 6),
               "command_speed": round(command_speed(sim), 6),
               "castors": sorted(set(sim.ground_parts) - {w.link for w in drive.wheels}),
               "mass": round(sim.mass, 6),
               "motors": {w.joint: {**w.motor.as_json(), "servo_gain": round(w.gain, 6)}
                          for w in drive.driven},
               "sources": {w.joint: drive.sources.get(w.joint, drive.chosen)
                           for w in drive.driven},
               "not_wheels": dict(drive.not_wheels)}
    if drive.kind in ("ackermann", "bicycle"):
        summary["wheelbase"] = round(drive.wheelbase, 6)
    if drive.centre:
        summary["centre"] = [w.joint for w in drive.centre]
    if drive.kind == "mecanum":
        summary.update(mecanum_summary(sim))
    summary["sprung"] = [s.as_json() for s in sim.springs]  # suspension, wheel drop
    return summary


def as_json(report: SimReport) -> dict:
    return {"file": report.file, "robot": report.robot, "drive": report.drive,
            "why_no_drive": report.why_no_drive, "held": report.held, "error": report.error,
            "diagnostics": [d.as_json() for d in report.diagnostics],
            "scenarios": [s.as_json() for s in report.scenarios],
            "notes": report.notes, "exit_code": report.exit_code}


def text_table(report: SimReport) -> list[str]:
    """The drive, then the figures of each scenario against their bounds, one line each."""
    lines = [f"{report.file} ({report.robot})"]
    if report.drive:
        lines += _drive_lines(report.drive)
    elif report.why_no_drive:
        fixed = report.not_a_vehicle and report.not_a_vehicle.kind == FIXED_TO_THE_WORLD
        lines.append(f"  {report.why_no_drive}{'' if fixed else ': drop only'}")
    if report.held:
        lines.append(f"  held still at 0, not simulated: {', '.join(report.held)}")
    if report.lint_errors or report.error:
        lines.append("  lint   FAILED  " + "; ".join(
            ([report.error] if report.error else [])
            + [f"{d.rule} {d.message}" for d in report.lint_errors]))
    for scenario in report.scenarios:
        lines.append(f"  {scenario.name:<6} {scenario.status.upper()}"
                     + (f"  {scenario.message()}" if scenario.status != "passed" else ""))
        for f in scenario.figures:
            detail = f"  ({f.detail})" if f.detail else ""
            lines.append(f"    {f.name:<20} {show_value(f.value, f.unit):>14}  {show_bound(f):<14} "
                         f"{'ok' if f.ok else 'FAIL'}{detail}")
        lines += [f"    {finding}" for finding in scenario.findings]
    return lines


def _drive_lines(d: dict) -> list[str]:
    kind = d["kind"] + ("" if d["chosen"] == "found from the tree" else f" ({d['chosen']})")
    wheels = (f"{', '.join(d['centre'])} (centre line)" if "centre" in d else
              f"{', '.join(d['left'])} (left), {', '.join(d['right'])} (right)")
    if d["free"]:
        wheels += f", rolling free {', '.join(d['free'])}"
    if d["steering"]:
        wheels += f"; steering {', '.join(d['steering'])}"
    sizes = f"radius {d['wheel_radius']:g} m" + ("" if "centre" in d else
                                                  f", track {d['track']:g} m")
    if "wheelbase" in d:
        sizes += f", wheelbase {d['wheelbase']:g} m"
    if "steering_angle_deg" in d:
        sizes += f", steering angle {d['steering_angle_deg']:.4g}°"
    castors = ", ".join(d["castors"]) or "none"
    lines = [f"  {kind} drive wheels {wheels}: {sizes}, command {d['command_speed']:g} rad/s; "
             f"on the floor too: {castors}; mass {d['mass']:.4g} kg"]
    by_source: dict[str, list[str]] = {}  # one line per place the wheels came from
    for joint, source in d.get("sources", {}).items():
        by_source.setdefault(source, []).append(joint)
    lines += [f"  wheels {', '.join(joints)} from {source}"
              for source, joints in by_source.items()]
    if d.get("not_wheels"):
        lines.append("  not wheels: " + "; ".join(f"{joint}: {why}" for joint, why
                                                   in d["not_wheels"].items()))
    alike: dict[str, list[str]] = {}  # one line for the motors that share their figures
    for joint, motor in d["motors"].items():
        speed = ("no limit" if motor["velocity"] is None else
                 f"{motor['velocity']:g} rad/s ({motor['velocity_from']})")
        if motor.get("placeholder"):
            speed += f", {motor['placeholder']}: driven as if no limit were given"
        text = (f"{motor['effort']:.4g} N·m ({motor['effort_from']}), {speed}, servo gain "
                f"{motor['servo_gain']:.4g} N·m·s/rad")
        alike.setdefault(text, []).append(joint)
    lines += [f"  motor {', '.join(joints)}: {text}" for text, joints in alike.items()]
    if "rollers" in d:
        lines += mecanum_lines(d)
    lines += [f"  sprung {_spring_text(s)}" for s in d.get("sprung", [])]
    return lines


def _spring_text(spring: dict) -> str:
    """``JOINT 0..30 mm, 400 N/m (source)``: a sprung joint's travel and stiffness."""
    prismatic = spring["unit"] == "m"
    per, unit = (1000, "mm") if prismatic else (180 / math.pi, "deg")
    lower, upper = (per * v for v in spring["travel"])
    return (f"{spring['joint']}: travel {lower:.4g}..{upper:.4g} {unit}, "
            f"{spring['stiffness']:.4g} {'N/m' if prismatic else 'N·m/rad'} "
            f"({spring['source']})")


def failure_lines(report: SimReport) -> list[str]:
    """One ``FILE: error: ...`` line per failed scenario (the lint prints its own)."""
    lines = []
    if report.error:
        lines.append(report.error)
    for scenario in report.scenarios:
        if scenario.status == "failed":
            lines.append(f"{scenario.name} failed: {scenario.message()}")
    return lines


def junit_cases(report: SimReport) -> list[dict]:
    """The robot's testcases: ``lint``, then one per scenario, each a dict of name, status
    (passed, failed, skipped), message and text (the figures against their bounds)."""
    lint_status = "failed" if report.lint_errors or report.error else "passed"
    lint_message = "; ".join([report.error] if report.error else []
                             + [d.text() for d in report.lint_errors]) or "ok"
    cases = [{"name": "lint", "status": lint_status, "message": lint_message,
              "text": "\n".join(d.text() for d in report.diagnostics)}]
    for s in report.scenarios:
        body = "\n".join(f"{f.name}: {f.value:.6g} {f.unit} (bound "
                         f"{'<=' if f.within == 'max' else '>='} {f.bound:g} {f.unit}) "
                         f"{'ok' if f.ok else 'FAIL'}" for f in s.figures)
        cases.append({"name": s.name, "status": s.status, "message": s.message(),
                      "text": body})
    return cases


def junit(reports: list[SimReport]) -> str:
    """One ``<testcase>`` per scenario (and one ``lint``) per robot file."""
    cases = [(report, case) for report in reports for case in junit_cases(report)]
    failures = sum(1 for _, c in cases if c["status"] == "failed")
    skipped = sum(1 for _, c in cases if c["status"] == "skipped")
    root = ET.Element("testsuites", tests=str(len(cases)), failures=str(failures),
                      errors="0", skipped=str(skipped))
    suite = ET.SubElement(root, "testsuite", name="mcar sim", tests=str(len(cases)),
                          failures=str(failures), errors="0", skipped=str(skipped))
    for report, case in cases:
        junit_case(suite, case, classname=f"mcar.sim.{report.robot}", name=case["name"],
                   file=report.file)
    return junit_document(root)
