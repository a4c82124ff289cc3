"""``mcar sim``: prove in MuJoCo that the car stands, drives straight and turns in place."""

from __future__ import annotations

import json
import math

import click

from mobile_car.errors import EXIT_PROBLEMS, UsageError, combine_exit_codes
from mobile_car.names import json_safe, shown
from mobile_car.packages.package_config import DRIVE_KINDS

from . import streams
from .common import (
    INPUT_HELP,
    checked_robots,
    chosen_robot,
    handle_errors,
    load_inputs,
    print_diagnostic,
    robot_options,
    severity_label,
    use_color,
)

SCENARIO_NAMES = ("drop", "drive", "spin", "turn", "strafe")

HELP = f"""Simulate the robot in MuJoCo, headless, and check that it stands, drives
straight and turns as its geometry says.

\b
  mcar sim urdf/mobile_robot.xacro           drop, drive and spin, a table of figures
  mcar sim --config urdf/variants/small.yaml the same robot with other dimensions
  mcar sim ROBOT --scenario drop,spin        some of the scenarios
  mcar sim ROBOT --format junit > sim.xml    one testcase per scenario, for CI
  mcar sim [ROBOT] --record run.gif          an animation of the runs (of the
                                             package's complete robot, unless named)

\b
Scenarios (bounds in docs/sim.md):
  drop   released 5 mm above the floor, after 2 s: at rest at the geometric rest
         height (1 mm), roll and pitch under 1 degree, every wheel and castor on
         the floor
  drive  every driven wheel at one speed for 3 s: distance within 2% of r·ω·t (the
         0.5 s ramp accounted for), small drift and heading change, no wheel off
         the floor, the motors' effort limit enough for the speed
  strafe a mecanum robot, wheels set to move it left: r·ω·t to its left (5%),
         little forward drift, heading kept
  spin   left wheels forward, right wheels back: a differential robot turns at
         2·r·ω/track (5%) with its axle's centre within 1 cm; a skid-steer one
         clockwise about a point within its wheels, and the report gives its
         effective track and multiplier against its X_control package's; a
         mecanum one at r·ω/(half wheelbase + half track) (5%)
  turn   an Ackermann car, front wheels at their Ackermann angles (a bicycle,
         its front wheel at the angle): its turning radius within 10% of
         wheelbase / tan(steering angle)

\b
Drive kinds: from --left/--right or --drive, else what the package declares (its
<gazebo> drive plugin, a controller in its X_control package: diff_drive_controller,
ackermann_steering_controller...; a bicycle model's virtual joints stand for the real
wheels of their axle), else found from the tree (a wheel: a continuous joint about a
level axis whose collision touches the floor at rest); the report says where each
wheel came from:
  differential  two driven wheels (y > 0 left, y < 0 right) and any castors
  skid-steer    two or three driven wheels a side
  ackermann     two front wheels on revolute steering joints (upright axis), one
                a side; the rear wheels driven (the front too where a
                <transmission> or <ros2_control> block drives them)
  mecanum       two wheels a side, declared so (mecanum_drive_controller in its
                control package's YAML, a <gazebo> planar_move plugin, fdir1
                with mu2 0) or carrying rollers on their rims; rollers grip at
                45° (fdir1, the roller links, else the usual X pattern)
  bicycle       a single track: one wheel on a revolute steering joint (upright
                axis) in front of unsteered driven ones, all on the centre line
A vehicle of any other kind (omni rollers, wheels on one side, a tricycle) runs
drop, and its drive scenarios fail saying why (exit 1), unless only drop was asked for.
--left/--right name the driven joints of each side (A,B for a group); the other
wheels roll free. --drive picks another kind the wheels allow.

The motors' effort and speed limits come from the joint's <limit>, else its
<ros2_control> command interfaces, else the <gazebo> drive plugin, else --effort, else
a default (the torque that holds the robot on a 10 degree slope; a skid-steer or mecanum
robot's, the torque that slips its wheels on its tyres' grip; no speed limit); --speed
overrides every speed limit. A speed limit over 5 m/s at the rim (r·ω) is a placeholder:
the robot is driven as if none were given. The report says which.

Every robot is checked first, as by `mcar check`: one with errors is reported with
check's diagnostics (exit 1). The <gazebo> DiffDrive plugin's wheel separation, radius
and joints are compared with the geometry (E301-E303), and links whose mass a simulator
would invent are reported (E305, W304), as FILE:LINE: error: message [E301].

{INPUT_HELP}

\b
Exit codes:
  0  every scenario passed
  1  a scenario failed (a vehicle that could not be driven fails its drive
     scenarios), the robot fails its check, or a sim rule error (E3xx)
  2  usage, I/O or environment error: bad option, missing file, unknown scenario, a
     --record format that cannot be written, no offscreen renderer for --record
  130  interrupted (Ctrl-C); 143 terminated
"""


def drive_options(func):
    """The options that make sim's model of the robot, which mcar specs takes too:
    --left, --right, --drive, --effort, --speed, --fix-inertia."""
    options = [
        click.option("--left", metavar="JOINT[,JOINT]", help="The left driven wheels' joints."),
        click.option("--right", metavar="JOINT[,JOINT]",
                     help="The right driven wheels' joints."),
        click.option("--drive", "kind", type=click.Choice(DRIVE_KINDS), default=None,
                     help="The drive kind (default: declared by the package, else found "
                          "from the tree)."),
        click.option("--effort", type=click.FloatRange(min=0), metavar="N·M",
                     help="The drive motors' effort limit where the description gives "
                          "none."),
        click.option("--speed", type=click.FloatRange(min=0, min_open=True), metavar="RAD/S",
                     help="The drive motors' speed limit, over any the description gives."),
        click.option("--fix-inertia", is_flag=True,
                     help="Make the inertias MuJoCo refuses physical (the nearest tensor that "
                          "satisfies the triangle inequality; a token mass for a moving link "
                          "without one), saying what changed, instead of failing (E305, "
                          "E310)."),
    ]
    for option in reversed(options):
        func = option(func)
    return func


def require_both_sides(left, right) -> None:
    if bool(left) != bool(right):
        raise UsageError("--left and --right go together: name both drive joints")


def scenario_list(ctx, param, value):
    """--scenario LIST: known names, in the order drop, drive, spin, turn; None: the
    drive kind's."""
    if value is None:
        return None
    names = [n.strip() for n in value.split(",") if n.strip()]
    unknown = [n for n in names if n not in SCENARIO_NAMES]
    if unknown or not names:
        raise click.BadParameter(f"{', '.join(unknown) or 'none given'}: the scenarios are "
                                 f"{', '.join(SCENARIO_NAMES)} (comma-separated)")
    return [n for n in SCENARIO_NAMES if n in names]


@click.command("sim", help=HELP, short_help="Simulate the robot: drop, drive, spin or turn.")
@click.argument("words", nargs=-1, metavar="[INPUT]... [NAME:=VALUE]...")
@click.option("--scenario", "scenarios", default=None, callback=scenario_list, metavar="LIST",
              help="Scenarios to run, comma-separated (default: the drive kind's: drop, "
                   "drive, spin; an Ackermann car's drop, drive, turn).")
@click.option("--format", "output_format", type=click.Choice(("text", "json", "junit")),
              default="text", show_default=True,
              help="text: a table on stdout, problems on stderr; json: one document; "
                   "junit: JUnit XML, one testcase per scenario.")
@click.option("--record", metavar="FILE.gif",
              help="Write an animation of the runs (one INPUT only); MP4 is refused.")
@click.option("--record-size", metavar="WxH", default="640x480", show_default=True,
              help="The animation's size in pixels; the camera follows the robot, an "
                   "arrow over each driven wheel shows its command.")
@click.option("--steering-angle", type=click.FloatRange(min=0, max=80, min_open=True,
                                                        max_open=True), metavar="DEG",
              help="turn: the Ackermann steering angle (default 15, less where the joints' "
                   "limits say so).")
@drive_options
@robot_options
@handle_errors
def command(words, scenarios, output_format, record, record_size, left, right, kind,
            steering_angle, effort, speed, fix_inertia, package_paths, sets, config_files):
    size = None
    if record:
        from mobile_car.sim.record import parse_size, require_format

        require_format(record)
        size = parse_size(record_size)
    require_both_sides(left, right)
    steering = None if steering_angle is None else math.radians(steering_angle)
    reports, codes, skipped = [], [], []
    with load_inputs(words, package_paths, sets, config_files) as (selection, options):
        # --record writes one animation: of the one robot named, or the complete robot
        inputs = [chosen_robot(selection, "mcar sim --record")] if record else selection.inputs
        explicit = selection.kind == "files"
        from mobile_car.sim.report import simulate

        passed = 0
        for inp, checked in checked_robots(selection, options, codes, inputs):
            passed += 1
            result = simulate(checked, scenarios, left, right, record=size,
                              only_if_drives=not explicit, effort=effort, speed=speed,
                              kind=kind, steering=steering, fix_inertia=fix_inertia,
                              setting=drive_setting(inp))
            if not result.simulated:
                skipped.append((result.file, result.not_a_vehicle))
                continue
            reports.append(result)
            codes.append(result.exit_code)
        unchecked = len(inputs) - passed  # their load or check failed: reported above
    say_not_simulated(skipped)
    if record:
        _write_recording(record, reports, codes)
    _emit(reports, output_format, combine_exit_codes(codes), unchecked)
    raise SystemExit(combine_exit_codes(codes))


def drive_setting(inp):
    """The package's mcar.yaml ``sim.drive`` for the input, or None (stdin, no package)."""
    from mobile_car.packages.package_config import load_package_config
    from mobile_car.packages.search import enclosing_package

    found = enclosing_package(inp.path) if inp.path is not None else None
    return load_package_config(found[1]).sim_drive_for(inp.path) if found else None


def say_not_simulated(skipped) -> None:
    """One line per kind of robot not simulated, naming its files (and, for one file,
    the detail)."""
    from mobile_car.sim.vehicle import grouped

    for reason, files in grouped(skipped):
        if len(files) == 1:
            why = next(w for f, w in skipped if f == files[0])
            click.echo(f"mcar: {shown(files[0])}: not simulated: {shown(str(why))}", err=True)
            continue
        click.echo(f"mcar: not simulated, {shown(reason)}: {len(files)} files: "
                   f"{', '.join(shown(f) for f in files)}", err=True)


def _write_recording(record: str, reports, codes) -> None:
    """Write the animation, or say why there is none (the exit code is the failure's)."""
    from mobile_car.atomic import atomic_write

    if reports and reports[0].recording is not None:
        atomic_write(record, reports[0].recording)
        return
    failed = [s.message() for r in reports for s in r.scenarios if s.status == "failed"]
    why = ("the robot was not simulated" if not reports else
           reports[0].error or (failed[0] if failed else "nothing was simulated to record"))
    click.echo(f"mcar: --record {shown(record)}: not written: {shown(why)}", err=True)
    if not any(codes):
        codes.append(EXIT_PROBLEMS)


def _emit(reports, output_format: str, exit_code: int, unchecked: int = 0) -> None:
    from mobile_car.sim.report import as_json, failure_lines, junit, text_table

    for result in reports:
        for diagnostic in result.diagnostics:
            print_diagnostic(diagnostic)
        for line in failure_lines(result):
            click.echo(f"{result.file}: {severity_label('error')} {shown(line)}", err=True,
                       color=use_color())
    if output_format == "json":
        document = {"files": [as_json(r) for r in reports], "exit_code": exit_code}
        streams.write(json_safe(json.dumps(document, indent=1, ensure_ascii=False)).encode()
                      + b"\n")
        return
    if output_format == "junit":
        streams.write(junit(reports).encode())
        return
    for result in reports:
        for note in result.notes:
            click.echo(f"mcar: {result.file}: {shown(note)}", err=True)
        streams.echo("\n".join(map(shown, text_table(result))))
    counts = {"passed": 0, "failed": 0, "skipped": 0}
    for result in reports:
        for scenario in result.scenarios:
            counts[scenario.status] += 1
    errors = sum(len(r.lint_errors) for r in reports)
    lint = f", {errors} lint error{'s' * (errors != 1)}" if errors else ""
    click.echo(f"mcar sim: {counts['passed']} passed, {counts['failed']} failed, "
               f"{counts['skipped']} skipped{lint} in {len(reports)} "
               f"file{'s' * (len(reports) != 1)}{_not_checked(unchecked)}", err=True)


def _not_checked(count: int) -> str:
    if not count:
        return ""
    return (f"; {count} file{'s' * (count != 1)} not simulated: "
            f"{'its' if count == 1 else 'their'} load or check failed (above)")
