"""One robot's simulation, start to end (lint, model, scenarios), and its three spellings:
a text table, JSON, JUnit. The library builds the strings; the command line prints them."""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from xml.etree import ElementTree as ET

from ..errors import EXIT_OK, EXIT_PROBLEMS
from .junit import junit_case, junit_document
from .lint import SimDiagnostic, link_mass, lint, moving_links_without_mass
from .scenarios import ScenarioResult, command_speed, run_scenarios, show_bound, show_value


@dataclass
class SimReport:
    file: str
    robot: str | None
    drive: dict | None = None            # left, right, radius, track, command speed
    why_no_drive: str | None = None
    diagnostics: list[SimDiagnostic] = field(default_factory=list)
    scenarios: list[ScenarioResult] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    error: str | None = None             # the model could not be made
    seconds: float = 0.0                 # wall clock
    recording: bytes | None = None       # the GIF, with record=True
    simulated: bool = True               # False: no drive wheels and only_if_drives

    @property
    def lint_errors(self) -> list[SimDiagnostic]:
        return [d for d in self.diagnostics if d.is_error]

    @property
    def exit_code(self) -> int:
        if self.error or self.lint_errors or any(s.status == "failed" for s in self.scenarios):
            return EXIT_PROBLEMS
        return EXIT_OK


def simulate(checked, names, left=None, right=None, record: bool = False,
             only_if_drives: bool = False, effort: float | None = None,
             speed: float | None = None) -> SimReport:
    """Lint and run ``names`` on a robot that passed ``mcar check`` (a CheckResult);
    ``record``: keep a GIF of the runs; ``only_if_drives``: a robot that is not a vehicle
    (:func:`not_a_vehicle`, or no drive wheel on a side) is not simulated (``simulated``
    False), as for the files of a package and in ``mcar ci``; ``effort``, ``speed``: the
    drive motors' figures where the description gives none (:mod:`.motors`)."""
    from .model import SimModelError, build_model

    started = time.perf_counter()
    loaded = checked.loaded
    report = SimReport(checked.file, checked.robot.name)
    if only_if_drives:
        why_not = not_a_vehicle(checked.robot)
        if why_not:
            report.simulated, report.why_no_drive = False, why_not
            return report
    unsimulable = _unsimulable(checked.robot)
    if unsimulable:
        report.why_no_drive = _no_drive(checked.robot)
        if only_if_drives:
            report.simulated = False
            return report
        report.scenarios = [ScenarioResult(name, problems=unsimulable) if name == "drop" else
                            ScenarioResult(name, skipped=report.why_no_drive)
                            for name in names]
        return report
    report.diagnostics = moving_links_without_mass(checked)
    if report.diagnostics:
        report.error = "a link MuJoCo must move has no mass (E305 above)"
        return report
    try:
        sim = build_model(loaded.urdf, checked.file, loaded.base, loaded.search, left, right,
                          effort, speed)
    except SimModelError as error:
        report.error = error.message
        return report
    if only_if_drives and not sim.drives:
        report.simulated, report.why_no_drive = False, sim.why_no_drive
        return report
    report.notes = list(sim.notes)
    report.diagnostics = lint(checked, sim)
    if sim.drives:
        report.drive = {"kind": sim.kind, "left": sim.left.joint, "right": sim.right.joint,
                        "wheel_radius": round(sim.left.radius, 6),
                        "track": round(sim.track, 6),
                        "command_speed": round(command_speed(sim), 6),
                        "castors": sorted(sim.ground_parts), "mass": round(sim.mass, 6),
                        "motors": {w.joint: {**w.motor.as_json(), "servo_gain": round(w.gain, 6)}
                                   for w in (sim.left, sim.right)}}
    report.why_no_drive = sim.why_no_drive
    recorder = None
    if record:
        from .record import Recorder
        from .scenarios import DRIVE_TIME

        reach = sim.left.radius * command_speed(sim) * DRIVE_TIME if sim.drives else 0.3
        recorder = Recorder(sim, reach)
    try:
        report.scenarios = run_scenarios(sim, names, recorder)
        if recorder is not None:
            report.recording = recorder.gif()
    finally:
        if recorder is not None:
            recorder.close()
    report.seconds = time.perf_counter() - started
    return report


def _unsimulable(robot) -> list[str]:
    """Why the robot cannot even be dropped (the tutorial's visual-only car), or []."""
    problems = []
    if not any(link.collisions for link in robot.links):
        problems.append("no link has <collision> geometry: nothing can rest on the floor, "
                        "the robot would fall through it")
    if sum(link_mass(link) for link in robot.links) <= 0:
        problems.append("no link has mass (<inertial>): there is nothing to simulate")
    return problems


def not_a_vehicle(robot) -> str | None:
    """Why a robot of a package is not simulated, or None: a vehicle has two or more
    continuous joints moving collision geometry (drive wheels) and a third link with
    collision geometry to stand on (a castor, a body). A part's test file (the wheel pair
    on a bare base_link) is not one; a car whose castor is set too high still is, so that
    drop fails it. Mass is not asked for here: a car that lost an <inertial> must fail
    (E305), not go unsimulated."""
    colliding = {link.name for link in robot.links if link.collisions}
    wheels = {j.child for j in robot.joints if j.type == "continuous" and j.child in colliding}
    if len(wheels) < 2:
        return _no_drive(robot)
    if not colliding - wheels:
        return (f"not a vehicle: nothing but the wheels ({', '.join(sorted(wheels))}) has "
                "collision geometry, no castor or body to stand on")
    return None


def _no_drive(robot) -> str:
    continuous = [j.name for j in robot.joints if j.type == "continuous"]
    if continuous:
        return (f"no drive wheels: continuous joints {', '.join(continuous)}, not a pair "
                "with collision geometry")
    joints = ", ".join(f"{j.name} ({j.type})" for j in robot.joints[:6])
    return f"no drive wheels: no continuous joint{': ' + joints if joints else ''}"


def as_json(report: SimReport) -> dict:
    return {"file": report.file, "robot": report.robot, "drive": report.drive,
            "why_no_drive": report.why_no_drive, "error": report.error,
            "diagnostics": [d.as_json() for d in report.diagnostics],
            "scenarios": [s.as_json() for s in report.scenarios],
            "notes": report.notes, "exit_code": report.exit_code}


def text_table(report: SimReport) -> list[str]:
    """The figures of each scenario against their bounds, one line each."""
    lines = [f"{report.file} ({report.robot})"]
    if report.drive:
        d = report.drive
        castors = ", ".join(d["castors"]) or "none"
        lines.append(f"  {d['kind']} drive wheels {d['left']} (left), {d['right']} (right): "
                     f"radius {d['wheel_radius']:g} m, track {d['track']:g} m, command "
                     f"{d['command_speed']:g} rad/s; on the floor too: {castors}; "
                     f"mass {d['mass']:.4g} kg")
        for joint, motor in d["motors"].items():
            speed = ("no limit" if motor["velocity"] is None else
                     f"{motor['velocity']:g} rad/s ({motor['velocity_from']})")
            lines.append(f"  motor {joint}: {motor['effort']:.4g} N·m ({motor['effort_from']}), "
                         f"{speed}, servo gain {motor['servo_gain']:.4g} N·m·s/rad")
    elif report.why_no_drive:
        lines.append(f"  {report.why_no_drive}: drop only")
    if report.lint_errors or report.error:
        lines.append(f"  lint   FAILED  {report.error or ''}" + "; ".join(
            f"{d.rule} {d.message}" for d in report.lint_errors))
    for scenario in report.scenarios:
        lines.append(f"  {scenario.name:<6} {scenario.status.upper()}"
                     + (f"  {scenario.message()}" if scenario.status != "passed" else ""))
        for f in scenario.figures:
            detail = f"  ({f.detail})" if f.detail else ""
            lines.append(f"    {f.name:<20} {show_value(f.value, f.unit):>14}  {show_bound(f):<14} "
                         f"{'ok' if f.ok else 'FAIL'}{detail}")
    return lines


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
