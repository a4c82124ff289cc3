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

{EXIT_CODES}"""

PART_HELP = f"""Add a part: a macro file and a test file that builds the part alone.

\b
  mcar new part arm
  -> urdf/arm/arm.xacro              macro xacro:arm (name, reflect, parent, *origin,
                                     size, mass), documented, with an inertia from
                                     its box; its link is arm_NAME_link
  -> urdf/arm/test_arm.urdf.xacro    a left and a right arm on a base link

It prints the include line and a macro call to paste into the package's robot file
(urdf/PACKAGE.urdf.xacro): include the macro from the robot file and call it once per
use, each with its own name: <xacro:arm name="left" reflect="1" parent="base_link">
with an <origin>, and name="right" reflect="-1" for its mirror image. Nothing is
overwritten, and the two files are written both or neither. NAME may not be one of
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
@handle_errors
def part(name, package_dir):
    from mobile_car.packages.search import enclosing_package
    from mobile_car.scaffold import add_part
    from mobile_car.scaffold.part_usage import part_usage

    start = Path(package_dir) if package_dir else Path.cwd()
    own = enclosing_package(start)
    if own is None:
        raise UsageError("not inside a description package (no package.xml here or above); "
                         "give --package DIR, or start one with `mcar init`")
    written = add_part(own[1], own[0], name)
    for file in written:
        click.echo(f"created {display_path(file)}", err=True)
    # What to paste where, on stdout: the part is not in the robot until it is included
    # and called there.
    usage = part_usage(own[1], own[0], name)
    robot = display_path(usage.robot) if usage.robot else "your robot's .urdf.xacro file"
    click.echo(f"to use it, paste into {robot}, after its other includes:")
    click.echo(f"  {usage.include}")
    click.echo("and before its </robot>, once per use (a name each; reflect=\"-1\" mirrors "
               "it; the origin: where on base_link):")
    for line in usage.call:
        click.echo(f"  {line}")
