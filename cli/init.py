"""``mcar init``: a new robot description package, laid out as the mobile car is."""

from __future__ import annotations

from pathlib import Path

import click

from mobile_car.load.inputs import display_path

from .common import handle_errors

HELP = """Create a robot description package at PATH, ready for mcar ci.

\b
  mcar init my_robot_description
  mcar init robots/arm --name arm_description

\b
It follows the mobile car's layout (the seed's method):
  package.xml, CMakeLists.txt        a ROS 1 (catkin) and ROS 2 (ament_cmake) package
  urdf/define.xacro                  colours, inertia macros (box, cylinder, sphere)
  urdf/config.xacro                  the dimensions, each "UNIT LO..HI; SOURCE: meaning"
  urdf/NAME.urdf.xacro               the complete robot
  launch/, rviz/, scripts/           the robot in RViz (ROS 1):
                                     roslaunch NAME display.launch
  meshes/, .gitignore
  .github/workflows/mcar.yml         CI: mcar ci on this package
  .pre-commit-config.yaml            a hook running mcar ci on this package
Then `mcar new part NAME` inside it adds a part folder. Nothing is overwritten: if a
file it would write exists, nothing is written; the package is written whole or not at
all (a name too long for the file system is refused before anything is written).

\b
Exit codes:
  0  the package was written
  1  (not used)
  2  usage or I/O error: an invalid or too long name, a file that exists, a folder
     not writable
  130  interrupted (Ctrl-C); 143 terminated
"""


@click.command("init", help=HELP, short_help="Create a robot description package.")
@click.argument("path", type=click.Path(file_okay=False))
@click.option("--name", metavar="NAME",
              help="The package's name (default: PATH's folder name); lowercase letters, "
                   "digits and underscores.")
@handle_errors
def command(path, name):
    from mobile_car.scaffold import create_package
    from mobile_car.scaffold.install_source import install_source

    source = install_source()
    written = create_package(Path(path), name, source.requirement)
    for file in written:
        click.echo(f"created {display_path(file)}", err=True)
    if source.note:
        click.echo(f"mcar: note: {source.note}", err=True)
    click.echo(f"next: cd {display_path(Path(path))} && mcar ci   "
               "(then `mcar new part NAME` to add a part)", err=True)
