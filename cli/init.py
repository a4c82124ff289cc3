"""``mcar init``: a new robot description package, laid out as the mobile car is."""

from __future__ import annotations

from pathlib import Path

import click

from mobile_car.load.inputs import display_path

from .common import handle_errors

# mobile_car.scaffold.DRIVES' keys, here so that --help does not import the scaffold.
DRIVES = ("differential", "skid-steer", "ackermann")

HELP = """Create a robot description package at PATH, ready for mcar ci.

\b
  mcar init my_robot_description                       a two-wheeled car, a castor
  mcar init my_rover_description --drive skid-steer    four wheels, all driven
  mcar init my_car_description --drive ackermann       steered front, driven rear

\b
It follows the mobile car's layout (the seed's method):
  package.xml, CMakeLists.txt        a ROS 1 (catkin) and ROS 2 (ament_cmake) package
  urdf/define.xacro                  colours, inertia macros (box, cylinder, sphere)
  urdf/config.xacro                  the dimensions, each "UNIT LO..HI; SOURCE: meaning"
  urdf/NAME.urdf.xacro               the complete robot, which `mcar sim` drives
  urdf/wheel/, castor/, steering/    its parts: a macro each (wheel name="left"
                                     reflect="1", used once per wheel) and a test file
  launch/, rviz/, scripts/           the robot in RViz (ROS 1):
                                     roslaunch NAME display.launch
  meshes/, .gitignore
  .github/workflows/mcar.yml         CI: mcar ci on this package
  .pre-commit-config.yaml            a hook running mcar ci on this package
The workflow installs mcar from where this mcar was installed from (a git repository at
its commit, or an https URL); from a folder on this machine, or a package index (mcar is
not on PyPI), it names 'mcar @ git+https://github.com/YOUR-ORG/mcar', and init prints
FILE:LINE of that one line to change before the first push.
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
@click.option("--drive", type=click.Choice(DRIVES), default="differential",
              show_default=True,
              help="The robot's drive: differential (two driven wheels and a castor, the "
                   "mobile car's), skid-steer (four driven wheels) or ackermann (steered "
                   "front wheels, driven rear ones).")
@click.option("--name", metavar="NAME",
              help="The package's name (default: PATH's folder name); lowercase letters, "
                   "digits and underscores.")
@handle_errors
def command(path, name, drive):
    from mobile_car.scaffold import create_package
    from mobile_car.scaffold.install_source import WORKFLOW, install_source, placeholder_line

    source = install_source()
    written = create_package(Path(path), name, source.requirement, drive)
    for file in written:
        click.echo(f"created {display_path(file)}", err=True)
    if source.note:
        # The one line a first push needs changed, on stdout in the FILE:LINE: form editors
        # jump to: without it the workflow's first run fails installing mcar.
        workflow = Path(path) / WORKFLOW
        line = placeholder_line(workflow.read_text(encoding="utf-8"))
        click.echo(f"{display_path(workflow)}:{line}: replace '{source.requirement}' with "
                   f"where your CI installs mcar from ({source.note}), or CI fails "
                   "installing it")
    click.echo(f"next: cd {display_path(Path(path))} && mcar sim && mcar ci   "
               "(then `mcar new part NAME` to add a part)", err=True)
