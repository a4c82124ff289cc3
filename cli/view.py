"""``mcar view``: the robot live in a browser, with joint sliders, reloading as you edit."""

from __future__ import annotations

import sys
import time

import click

from mobile_car.errors import McarError, UsageError

from . import signals, streams
from .common import (
    INPUT_HELP,
    chosen_robot,
    handle_errors,
    load_inputs,
    report,
    robot_options,
    stdin_for,
)

HELP = f"""Show a robot in the browser: turn its joints, see every edit at once.

\b
  mcar view                          the package's robot (its one top-level robot
                                     file, else name one), else the bundled car
  mcar view robot.urdf.xacro [N:=V]  one file (same options as mcar build)
  mcar view --port 8081 --no-browser serve only; open the printed URL yourself
  mcar view --rviz [INPUT] [N:=V]    in ROS 1's RViz instead, with joint sliders

The robot is checked first, as by `mcar check`: one with errors is reported with
check's diagnostics (exit 1) and not served. The page has a slider for every movable
joint (the URDF's limits; continuous joints -pi..pi; mimic joints follow), a reset
button, and switches for visual and collision geometry and link frames. A robot built
from a config.xacro also gets a slider per dimension (`mcar config`; the range LO..HI
of each): moving one rebuilds the robot with that override, checked as --set is (a
value config.xacro refuses is shown and not applied), and a button shows the
overrides as a file that --config reads.

Live reload: whenever a file the robot was built from changes (the xacro files it
includes, its meshes), it is built and checked again and the page shows the new
robot. An edit that does not build is shown in the page and on stderr, and the last
good robot stays on screen.

Unlike `mcar render` (still pictures at joint zero, for files and CI), view is for a
person at a browser. It serves on 127.0.0.1 only, unless --host says otherwise; Ctrl-C
stops it. It needs the optional extra: pip install "mcar[view]".

With --rviz the robot opens in RViz (ROS 1) through the bundled
launch/display.launch, as `roslaunch mobile_car_description display.launch
model:=FILE` would: roslaunch, robot_state_publisher, the joint sliders, RViz fitted
to the robot (its root as fixed frame, the camera on it). It needs Debian's ROS 1
(python3-roslaunch ros-robot-state-publisher joint-state-publisher-gui rviz; `make
rviz` installs them), not viser; it runs until RViz is closed or Ctrl-C.

It answers only its own page: a request whose Host is not the address served on
(127.0.0.1:PORT or localhost:PORT; with --host, that host), or a connection from a
page of another Origin (any other site open in the browser), gets 403 Forbidden.
What the page sends is checked before it touches the robot: a joint or dimension
value must be a finite number within its slider's range, a switch true or false.
Anything else is dropped, with one warning line on stderr per control.

{INPUT_HELP}

\b
Exit codes:
  0  not used: view serves until it is stopped (--rviz: RViz was closed)
  1  the robot has problems (check's errors, a missing mesh): not served
  2  usage, I/O or environment error: bad option, missing file, port in use,
     the view extra not installed (--rviz: no roslaunch, or roslaunch failed)
  130  interrupted (Ctrl-C); 143 terminated
"""

# How often the robot's files are looked at for edits.
POLL_SECONDS = 0.3


def _require_viser() -> None:
    from mobile_car import extras

    extras.require("mcar view", "view")


@click.command("view", help=HELP, short_help="Show the robot in a browser, live.")
@click.argument("words", nargs=-1, metavar="[INPUT] [NAME:=VALUE]...")
@click.option("--host", default="127.0.0.1", show_default=True,
              help="Address to serve on; 0.0.0.0 lets other machines connect.")
@click.option("--port", type=click.IntRange(0, 65535), default=8080, show_default=True,
              help="Port to serve on (0: any free port).")
@click.option("--no-browser", is_flag=True, help="Do not open a browser; only print the URL.")
@click.option("--rviz", is_flag=True,
              help="Open the robot in ROS 1's RViz (roslaunch) instead of the browser.")
@robot_options
@handle_errors
def command(words, host, port, no_browser, rviz, package_paths, sets, config_files):
    if rviz:
        from mobile_car.view.rviz import require_roslaunch

        require_roslaunch()
    else:
        _require_viser()
    with load_inputs(words, package_paths, sets, config_files) as (selection, options):
        inp = chosen_robot(selection, "mcar view")
        if rviz:
            return _in_rviz(inp, options, sets, config_files)
        from mobile_car.view.dimensions import robot_dimensions
        from mobile_car.view.model import load_model

        signals.raise_if_received()  # trimesh's import guards swallow Ctrl-C and SIGTERM
        model = load_model(inp, options, stdin=stdin_for(selection))
        for warning in model.warnings:
            click.echo(warning.text(), err=True)
        dimensions = robot_dimensions(inp, options, model)
        reload = dimensions.load if dimensions is not None else lambda: load_model(inp, options)
        view = _serve(model, reload, host, port, dimensions)
        try:
            with streams.stdout_writes():
                click.echo(f"mcar view: {inp.label} at {view.url} (Ctrl-C stops)")
                sys.stdout.flush()
            if not no_browser:
                import webbrowser

                webbrowser.open(view.url)
            _watch(view)
        finally:
            view.stop()


def _in_rviz(inp, options, sets, config_files) -> None:
    """Check the robot as view does, then run roslaunch until RViz is closed."""
    from mobile_car.view import rviz
    from mobile_car.view.model import load_model

    model = load_model(inp, options)
    for warning in model.warnings:
        click.echo(warning.text(), err=True)
    rviz.refuse_unbounded(inp, model.warnings)
    click.echo(f"mcar view: {inp.label} in RViz (roslaunch; close RViz or Ctrl-C to stop)",
               err=True)
    code = rviz.show(rviz.require_roslaunch(), inp, model, options, sets, config_files)
    if code != 0:
        raise UsageError(f"roslaunch ended with exit code {code} (its messages are above)")


def _serve(model, reload, host: str, port: int, dimensions):
    from mobile_car.view.server import RobotView

    try:
        view = RobotView(model, reload, host=host, port=port, dimensions=dimensions,
                         warn=_warn)
    except OSError as error:  # a host that is no address of this machine
        raise UsageError(f"cannot serve on {host}:{port}: {error.strerror or error}") from None
    if port and view.port != port:  # viser moves on to the next free port: say it is taken
        view.stop()
        raise UsageError(f"port {port} is in use; choose another with --port (0: any)")
    return view


def _warn(text: str) -> None:
    """What the server refused from a browser (said from viser's threads)."""
    click.echo(text, err=True)


def _watch(view) -> None:
    """Rebuild on every edit until Ctrl-C (which raises KeyboardInterrupt here)."""
    while True:
        time.sleep(POLL_SECONDS)
        changed, error = view.reload_if_changed()
        if not changed:
            continue
        if error is not None:
            _report_kept(error)
        else:
            from mobile_car.load.inputs import display_path

            click.echo(f"mcar view: reloaded ({display_path(changed[0])} changed)", err=True)


def _report_kept(error: McarError) -> None:
    report(error)
    click.echo("mcar view: the last good robot stays on the page", err=True)

