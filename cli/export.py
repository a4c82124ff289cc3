"""``mcar export``: the robot as a self-contained folder for another simulator."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from mobile_car.errors import EXIT_PROBLEMS, UsageError
from mobile_car.load.inputs import display_path
from mobile_car.names import shown

from .common import (
    INPUT_HELP,
    chosen_robot,
    handle_errors,
    load_inputs,
    print_diagnostic,
    print_warning,
    robot_options,
    stdin_for,
)

FORMATS = ("mjcf", "usd", "urdf", "sdf")

HELP = f"""Export one robot as a folder another simulator loads on a machine without
its packages: the robot file and every mesh it uses, paths relative to it.

\b
  mcar export ROBOT --to mjcf -o out/robot_mjcf         MuJoCo
  mcar export ROBOT --to mjcf -o out/m --verify         ... loaded back and checked
  mcar export ROBOT --to mjcf -o out/m --base fixed     welded to the world
  mcar export ROBOT --to usd -o out/robot_usd           OpenUSD (Isaac Sim, Newton)
  mcar export ROBOT --to urdf -o out/robot_urdf         URDF, no package:// left
  mcar export ROBOT --to sdf -o out/robot_sdf           Gazebo (libsdformat's SDF)

\b
--to mjcf: NAME.xml, written by MuJoCo from its own reading of the URDF, and
meshes/: visual geometry (geom group 2, touching nothing) and collision geometry
(group 3), the description's masses, <mimic> as equality constraints, friction
from <gazebo><mu1>, and on a vehicle the velocity servos `mcar sim` drives with
(actuators mcar_motor_JOINT: data.ctrl is each drive wheel's speed, rad/s),
sim's round tyres and castor friction.
--base floating (a free joint, the default) or fixed; --floor (the default under
a floating base) adds a floor with the robot standing on it. Meshes MuJoCo cannot
read (COLLADA, PLY, ...) are converted to STL in metres, each listed.

--to usd: the stage urdf-usd-converter writes (NAME.usda and its layers), with a
velocity drive on each drive wheel; a massless frame link's children are re-hung on
the body fixed to it, in the same place (the converter makes no body of a frame).

--to urdf: NAME.urdf with every mesh and texture below meshes/ by relative paths
(COLLADA, STL and OBJ as they are, others converted to STL), <gazebo> kept.

--to sdf: the SDF libsdformat writes from that URDF (the Gazebo helper, `make
gazebo-helper`), mesh URIs relative to it; fixed joints lumped, as Gazebo does.

Inertias MuJoCo refuses (a tensor not positive definite, principal moments that
break A + B >= C, a moving link without mass) are named link by link, with the line
that writes each (exit 1); --fix-inertia makes them physical instead, one warning per
link: the nearest physical tensor, a token mass for a frame without geometry, MuJoCo's
own fixes for the rest (balanceinertia, inertia from geometry).

--verify loads the export back from its folder with the target's engine: every
file inside the folder, the total mass within 0.1% of the description's, the same
moving joints; in MuJoCo a vehicle passes `mcar sim`'s own scenarios with sim's
bounds (drop, drive, spin or turn), judged as sim judges the description; a USD
weighs more than 0 kg; a URDF loads in yourdfpy (meshes too) and urdfdom's
check_urdf where installed; an SDF in libsdformat without errors. A mismatch is an
error naming what differs, and nothing is written.

The robot is checked first, as by `mcar check`; one with errors is not exported.
The folder is written whole or not at all (staged beside it, renamed into place);
an existing -o folder is replaced only if it is empty or an earlier export (it
holds mcar-export.json, the manifest of what was written). See docs/exports.md.

{INPUT_HELP}

\b
Exit codes:
  0  the folder was written (and verified)
  1  the robot fails its check, the target cannot take it (an inertia MuJoCo
     refuses, a robot libsdformat makes no model of), or --verify found a mismatch
  2  usage or I/O error: no -o, several robots, a folder that is not an export,
     a folder holding an input, a file that cannot be written; --to sdf without
     the Gazebo helper, --to usd without the usd extra
  130  interrupted (Ctrl-C); 143 terminated
"""


@click.command("export", help=HELP, short_help="Export a robot as a folder for another simulator.")
@click.argument("words", nargs=-1, metavar="[INPUT] [NAME:=VALUE]...")
@click.option("--to", "to", type=click.Choice(FORMATS), required=True,
              help="The format: mjcf (MuJoCo), usd (OpenUSD: Isaac Sim, Newton), urdf "
                   "(PyBullet, Genesis, ...: meshes beside it), sdf (Gazebo).")
@click.option("-o", "--output", metavar="DIR", required=True,
              help="The folder to write (made; an earlier export there is replaced).")
@click.option("--base", type=click.Choice(("floating", "fixed")), default="floating",
              show_default=True, help="mjcf: a free root (free joint) or one welded to the "
                                      "world.")
@click.option("--floor/--no-floor", default=None,
              help="mjcf: add a floor, the robot standing on it (default: with a floating "
                   "base).")
@click.option("--fix-inertia", is_flag=True,
              help="Make the inertias MuJoCo refuses physical, warning per link, instead "
                   "of failing: the nearest physical tensor for one not positive definite, "
                   "a token mass for a moving frame without mass or geometry, MuJoCo's own "
                   "fixes otherwise (balanceinertia, inertia from geometry).")
@click.option("--verify", is_flag=True,
              help="Load the export back with its engine and hold it to the description.")
@click.option("-q", "--quiet", is_flag=True, help="Print only errors and warnings.")
@robot_options
@handle_errors
def command(words, to, output, base, floor, fix_inertia, verify, quiet, package_paths, sets,
            config_files):
    from mobile_car.check.checker import check_input
    from mobile_car.check.mujoco_inertia import places
    from mobile_car.export.mjcf import MjcfOptions
    from mobile_car.export.run import export_robot

    _refuse_options_of_other_formats(to, click.get_current_context(), floor, fix_inertia)
    if to == "usd":
        from mobile_car.extras import require

        require("mcar export --to usd", "usd")

    with load_inputs(words, package_paths, sets, config_files) as (selection, options):
        inp = chosen_robot(selection, "mcar export")
        checked = check_input(inp, options, stdin=stdin_for(selection))
        if checked.failure is not None:
            raise checked.failure
        if checked.errors or not checked.tree_is_drawable:
            for diagnostic in checked.diagnostics:
                print_diagnostic(diagnostic)
            sys.exit(EXIT_PROBLEMS)
        report = export_robot(checked.loaded, Path(output), to,
                              MjcfOptions(base, floor, fix_inertia, places(checked)), verify)
    _print(report, checked.loaded.label, quiet)


# The options each format takes beyond the common ones: another is a usage error rather
# than silently ignored (--base fixed --to urdf would otherwise write a floating robot).
TAKES = {"mjcf": {"--base", "--floor", "--no-floor", "--fix-inertia"}, "usd": {"--base"},
         "urdf": set(), "sdf": set()}


def _refuse_options_of_other_formats(to: str, context, floor, fix_inertia) -> None:
    from click.core import ParameterSource

    given = []
    if context.get_parameter_source("base") == ParameterSource.COMMANDLINE:
        given.append("--base")
    if floor is not None:
        given.append("--floor" if floor else "--no-floor")
    if fix_inertia:
        given.append("--fix-inertia")
    refused = [option for option in given if option not in TAKES[to]]
    if refused:
        takers = sorted(f for f, options in TAKES.items() if refused[0] in options)
        raise UsageError(f"{refused[0]} applies to --to {' and '.join(takers)}, not to "
                         f"--to {to}")


def _print(report, label: str, quiet: bool) -> None:
    exported = report.exported
    for warning in exported.warnings:
        print_warning(label, warning)
    if quiet:
        return
    for line in exported.converted:
        click.echo(f"mcar export: converted {shown(line)}", err=True)
    for line in exported.notes:
        click.echo(f"mcar export: {shown(line)}", err=True)
    others = [m for m in exported.meshes if m != exported.robot_file]
    drive = exported.drive
    motors = (f"; {drive['kind']} drive, actuators on "
              f"{', '.join(drive['left'] + drive['right'] + drive.get('centre', []))}"
              if drive else "")
    click.echo(f"mcar export: wrote {display_path(report.folder)}/ ({report.format}): "
               f"{shown(exported.robot_file)} and {len(others)} other "
               f"file{'s' * (len(others) != 1)}; "
               f"{exported.model_mass:.6g} kg, {len(exported.moving_joints)} moving joint"
               f"{'s' * (len(exported.moving_joints) != 1)}{shown(motors)}", err=True)
    for line in report.proven:
        click.echo(f"mcar export: verified: {shown(line)}", err=True)
