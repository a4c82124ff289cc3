"""``mcar specs``: what the robot can do, each figure with its source and assumptions,
proven in MuJoCo where physics can show it."""

from __future__ import annotations

import contextlib
import json

import click

from mobile_car.errors import combine_exit_codes
from mobile_car.names import json_safe, shown

from . import streams
from .common import (
    INPUT_HELP,
    checked_robots,
    chosen_robot,
    handle_errors,
    load_inputs,
    robot_options,
    start_probe,
)
from .sim import drive_options, drive_setting, require_both_sides
from .specs_picture import check_picture_name, picture_options, write_picture
from .specs_stack import stack_options, write_stack_files

HELP = f"""What the robot can do: its size, weight and balance, the slopes it stands
and climbs, its joints' loads, what its sensors see, the Nav2 and controller settings
that follow; each figure with its source and what it assumes, and MuJoCo's
measurement beside it where physics can prove it.

\b
  mcar specs urdf/mobile_robot.xacro          a table per section
  mcar specs ROBOT --format json > specs.json  figures by key, for scripts
  mcar specs ROBOT --format markdown           for a pull request
  mcar specs ROBOT --no-proof                  computed figures only: no MuJoCo runs
  mcar specs [ROBOT] --picture specs.png       the figures drawn over the robot (of
                                               the package's complete robot, unless named)

\b
Frames: the root frame is the robot's root link at rest; the floor frame its
projection on the floor (x forward, y left, z up; origin below the root's origin), as
Nav2's base_footprint. Units: m, kg, N, N·m, m/s; angles in degrees.

\b
Sections, computed in this order (every key: docs/specs.md):
  body     mass, centre of mass (root frame) and its height, the footprint (convex
           outline of the collision geometry at rest, floor frame) and its
           circumscribed and inscribed radii, ground clearance; the wheels' radius,
           track and wheelbase; the load on each wheel and castor at rest (by
           statics on three supports, else MuJoCo's contact forces)
  statics  the support polygon, the tip angle in every direction, the slope it
           slides on, stands on and climbs, top speed, turning radius
  joints   each joint's gravity load in its worst pose against its effort limit
  sensors  each sensor's pose, range and field of view, and what of it the robot
           itself blocks
  stack    the Nav2, controller and laser-filter settings these figures give
  inertia  each link's inertia from its geometry and mass, against the declared one

\b
Sources, in the order they are used: the description (collision geometry,
<inertial>, <limit>, sensors), what its package declares (drive plugins,
controllers, mcar.yaml sim.drive), the options (--friction, --effort, --speed), then
defaults, named as such. The robot is the one `mcar sim` simulates (same drive,
motors, castors, rest pose, --fix-inertia); a robot MuJoCo cannot model still gets
its mass and centre of mass from the URDF, and a note why the rest is missing.

Every robot is checked first, as by `mcar check`: one with errors is reported with
check's diagnostics (exit 1). Notes and rule warnings (W5xx) go to stderr, as
FILE:LINE: warning: message [W501].

{INPUT_HELP}

\b
Exit codes:
  0  every figure computed agrees with its proof
  1  the robot fails its check, a specs rule error (E5xx), or a figure that
     disagrees with MuJoCo's measurement (said on stderr)
  2  usage, I/O or environment error: bad option, missing file
  130  interrupted (Ctrl-C); 143 terminated
"""


@click.command("specs", help=HELP, short_help="What the robot can do, with sources.")
@click.argument("words", nargs=-1, metavar="[INPUT]... [NAME:=VALUE]...")
@click.option("--format", "output_format", type=click.Choice(("text", "json", "markdown")),
              default="text", show_default=True,
              help="text: a table per section on stdout, notes on stderr; json: one "
                   "document, figures by key; markdown: for a pull request.")
@click.option("--no-proof", is_flag=True,
              help="Compute the figures only: no MuJoCo runs to prove them (the sensors' "
                   "rays are cast by MuJoCo alone, unchecked).")
@click.option("--friction", type=click.FloatRange(min=0), metavar="MU",
              help="The tyres' friction with the floor where the description gives none "
                   "(default 1.0, MuJoCo's).")
@picture_options
@stack_options
@drive_options
@robot_options
@handle_errors
def command(words, output_format, no_proof, friction, picture, renderer, stack_dir,
            stack_distro, effort, speed, left, right, kind, fix_inertia, package_paths, sets,
            config_files):
    require_both_sides(left, right)
    check_picture_name(picture)
    options = {"proof": not no_proof, "friction": friction, "effort": effort, "speed": speed,
               "left": left, "right": right, "kind": kind, "fix_inertia": fix_inertia}
    reports, codes = [], []
    with contextlib.ExitStack() as stack, \
            load_inputs(words, package_paths, sets, config_files) as (selection, load_options):
        from mobile_car.specs.compute import computed
        from mobile_car.specs.report import SpecsReport

        # --picture and --stack are of one robot: the one named, or the package's complete one
        one = "mcar specs --picture" if picture else "mcar specs --stack"
        inputs = [chosen_robot(selection, one)] if picture or stack_dir else None
        probe = start_probe(stack, renderer) if picture else None
        for inp, checked in checked_robots(selection, load_options, codes, inputs):
            context = computed(checked, {**options, "setting": drive_setting(inp)})
            sections = context.sections
            result = SpecsReport(checked.file, checked.robot.name, sections)
            reports.append(result)
            codes.append(result.exit_code)
            if picture:
                write_picture(picture, sections, checked, renderer, probe)
            if stack_dir is not None:
                write_stack_files(stack_dir, stack_distro, sections, context.sim, checked)
    _emit(reports, output_format, combine_exit_codes(codes))
    raise SystemExit(combine_exit_codes(codes))


def _emit(reports, output_format: str, exit_code: int) -> None:
    """Notes, diagnostics and disagreements on stderr; the figures on stdout."""
    from mobile_car.specs.report import as_json, disagreement_lines, markdown, text_table

    from .common import print_diagnostic, severity_label, use_color

    for result in reports:
        for section in result.sections:
            for diagnostic in section.diagnostics:
                print_diagnostic(diagnostic)
            for note in section.notes:
                click.echo(f"mcar: {shown(result.file)}: {shown(note)}", err=True)
        for line in disagreement_lines(result):
            click.echo(f"{shown(result.file)}: {severity_label('error')} {shown(line)}",
                       err=True, color=use_color())
    if output_format == "json":
        document = {"files": [as_json(r) for r in reports], "exit_code": exit_code}
        streams.write(json_safe(json.dumps(document, indent=1, ensure_ascii=False)).encode()
                      + b"\n")
        return
    spell = markdown if output_format == "markdown" else text_table
    blocks = ["\n".join(map(shown, spell(result))) for result in reports]
    if blocks:
        streams.echo("\n\n".join(blocks))
