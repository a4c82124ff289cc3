"""``mcar new part NAME``: a part folder in the package you stand in."""

from __future__ import annotations

from pathlib import Path

import click

from mobile_car.errors import UsageError
from mobile_car.load.inputs import display_path

from .common import handle_errors

EXIT_CODES = """\b
Exit codes:
  0  the files were written
  1  (not used)
  2  usage or I/O error: not inside a package, an invalid, too long or clashing
     name, a file that exists
  130  interrupted (Ctrl-C); 143 terminated
"""

HELP = f"""Add something new to the description package you stand in.

\b
  mcar new part arm      urdf/arm/arm.xacro and urdf/arm/test_arm.urdf.xacro
  mcar new part arm --into urdf/my_robot.urdf.xacro     and the arm in the robot

{EXIT_CODES}"""

PART_HELP = f"""Add a part: a macro file and a test file that builds the part alone.

\b
  mcar new part arm
  -> urdf/arm/arm.xacro              macro xacro:arm (name, reflect, parent, *origin,
                                     size, mass), documented, with an inertia from
                                     its box; its link is arm_NAME_link
  -> urdf/arm/test_arm.urdf.xacro    a left and a right arm on a base link

It prints the include line and a macro call to paste into the package's robot file
(urdf/PACKAGE.urdf.xacro), or with --into ROBOT adds them to ROBOT: include the macro
from the robot file and call it once per use, each with its own name:
<xacro:arm name="left" reflect="1" parent="base_link"> with an <origin>, and
name="right" reflect="-1" for its mirror image. Nothing is overwritten, and the two
files are written both or neither (and ROBOT is changed only if they are). NAME may not be one of
xacro's own elements (include, macro, property, arg, if, ...) nor give a macro, or a
link or joint of its test file, that the package already has.

{EXIT_CODES}"""


@click.group("new", help=HELP, short_help="Add a part to the package you stand in.")
def command():
    pass


@command.command("part", help=PART_HELP, short_help="Add a part folder.")
@click.argument("name")
@click.option("--package", "package_dir", metavar="DIR", type=click.Path(file_okay=False),
              help="The package (default: the one holding the current folder).")
@click.option("--into", "into", metavar="ROBOT", type=click.Path(dir_okay=False),
              help="Also add the include line and a macro call (on base_link) to the robot "
                   "file ROBOT, instead of printing them; nothing is written if it cannot be.")
@handle_errors
def part(name, package_dir, into):
    from mobile_car.atomic import atomic_write
    from mobile_car.packages.search import enclosing_package
    from mobile_car.scaffold import add_part
    from mobile_car.scaffold.part_usage import part_usage, with_part

    start = Path(package_dir) if package_dir else Path.cwd()
    own = enclosing_package(start)
    if own is None:
        raise UsageError("not inside a description package (no package.xml here or above); "
                         "give --package DIR, or start one with `mcar init`")
    usage = part_usage(own[1], own[0], name)
    robot_text = with_part(Path(into), usage) if into else None  # refused before writing
    written = add_part(own[1], own[0], name)
    for file in written:
        click.echo(f"created {display_path(file)}", err=True)
    if into:
        atomic_write(into, robot_text)
        click.echo(f"added {name} to {display_path(Path(into))}: {usage.include} and "
                   f"<xacro:{name} name=\"left\" ...> on base_link", err=True)
        return
    # What to paste where, on stdout: the part is not in the robot until it is included
    # and called there.
    robot = display_path(usage.robot) if usage.robot else "your robot's .urdf.xacro file"
    click.echo(f"to use it, paste into {robot}, after its other includes:")
    click.echo(f"  {usage.include}")
    click.echo("and before its </robot>, once per use (a name each; reflect=\"-1\" mirrors "
               "it; the origin: where on base_link):")
    for line in usage.call:
        click.echo(f"  {line}")
