"""The ``mcar`` command group. Commands are imported only when run, to keep start-up light."""

from __future__ import annotations

import gc
import importlib
import os
import sys

# The imports of a run (click, the command's modules) make tens of thousands of objects and
# no garbage cycles: the cyclic collector's passes over them cost ~2 ms of every start-up.
# It is off while they are imported, and back on (if it was on) before any work is done.
_collecting = gc.isenabled()
gc.disable()


def _imported(collecting: bool) -> None:
    """After imports made with the collector off: it goes back on (if it was on). Turned
    back on as they are, the objects the imports made are all young, and the first new
    object of the run sets off a pass over every one of them (~3.5 ms of `mcar check`,
    most of its margin over click and lxml's import). Where mcar is the program (its
    console script, not a test run or a program that imports mcar), they are frozen
    first: they live as long as the run, and no pass ever visits them again (also kept
    out of the pages a forked xacro child would copy)."""
    if not collecting:
        return
    if sys.argv and os.path.basename(sys.argv[0]).removesuffix(".exe") == "mcar":
        gc.freeze()
    gc.enable()


from . import signals  # noqa: E402

signals.install()  # before the slow imports: Ctrl-C or SIGTERM during them ends mcar at once

from . import streams  # noqa: E402

streams.open_closed_standard_fds()

import click  # noqa: E402

from mobile_car import __version__  # noqa: E402
from mobile_car.errors import EXIT_USAGE, McarError  # noqa: E402

_imported(_collecting)

# name -> (module under mobile_car.cli, one-line help shown by `mcar --help`)
COMMANDS = {
    "build": ("build", "Expand xacro into URDF (the package you stand in when no INPUT)."),
    "config": ("config", "Show the robot's dimensions, with overrides applied."),
    "render": ("render", "Draw robot descriptions as PNG pictures, headless."),
    "check": ("check", "Check URDF/xacro files: check_urdf's tree, stricter, located."),
    "sim": ("sim", "Simulate the robot in MuJoCo: it stands, drives and turns."),
    "specs": ("specs", "What the robot can do, each figure with its source and proof."),
    "ci": ("ci", "Build, check --strict and render a whole package: the CI job."),
    "export": ("export", "Export a robot as a folder MuJoCo loads, meshes and all."),
    "diff": ("diff", "Show what a change does to the robot: kinematics, masses, dimensions."),
    "sweep": ("sweep", "Sweep dimensions: build, check and simulate every variant."),
    "tree": ("tree", "Print the kinematic tree with joint types, origins and axes."),
    "init": ("init", "Create a robot description package, ready for mcar ci."),
    "new": ("new", "Add a part to the package you stand in."),
    "view": ("view", "Show the robot live in a browser: joint sliders, reload on edit."),
}

EXIT_CODES_HELP = """\b
Exit codes (every command):
  0  success
  1  problems found in the input (xacro error, failed check)
  2  usage, I/O or environment error (bad option, missing file, unknown package)
  130  interrupted (Ctrl-C); 143 terminated
"""


class LazyGroup(click.Group):
    def list_commands(self, ctx):
        return sorted(COMMANDS)

    def get_command(self, ctx, name):
        if name not in COMMANDS:
            return None
        collecting = gc.isenabled()
        gc.disable()  # while the command's modules are imported (see the top)
        try:
            module = importlib.import_module(f"mobile_car.cli.{COMMANDS[name][0]}")
        finally:
            _imported(collecting)
        return module.command

    def resolve_command(self, ctx, args):
        if args and not args[0].startswith("-") and args[0] not in COMMANDS:
            import difflib  # only on this error path

            close = difflib.get_close_matches(args[0], sorted(COMMANDS), n=1, cutoff=0.6)
            hint = f" Did you mean '{close[0]}'?" if close else ""
            ctx.fail(f"No such command '{args[0]}'.{hint} Commands: {', '.join(sorted(COMMANDS))}.")
        return super().resolve_command(ctx, args)

    # click writes --help, --version and usage errors itself, outside handle_errors: a
    # failure to write them ends the run as a failed write of a command does.
    def make_context(self, *args, **kwargs):
        with streams.stdout_writes():
            return super().make_context(*args, **kwargs)

    def invoke(self, ctx):
        with streams.stdout_writes():
            return super().invoke(ctx)

    def main(self, *args, **kwargs):
        try:
            return super().main(*args, **kwargs)
        except streams.ReaderGone:
            streams.exit_quietly(0)
        except McarError as error:
            streams.say(f"mcar: error: {error.message}")
            streams.exit_quietly(error.exit_code)
        except OSError:  # click could not write a usage error to stderr: nothing to say
            streams.exit_quietly(EXIT_USAGE)

    def format_commands(self, ctx, formatter):
        rows = [(name, COMMANDS[name][1]) for name in self.list_commands(ctx)]
        with formatter.section("Commands"):
            formatter.write_dl(rows)


@click.group(cls=LazyGroup, epilog=EXIT_CODES_HELP, invoke_without_command=True,
             context_settings={"help_option_names": ["-h", "--help"]})
@click.option("-V", "--version", "show_version", is_flag=True,
              help="Show the version and exit.")
@click.option("--verbose", is_flag=True,
              help="With --version: also what the xacro sandbox can use on this machine.")
@click.pass_context
def main(ctx, show_version, verbose):
    """mcar: build, check and render the mobile car's URDF/xacro description, without ROS.

    Run `mcar COMMAND --help` for the options of one command.
    """
    if show_version:
        click.echo(f"mcar, version {__version__}")
        if verbose:
            from mobile_car.expand.sandbox import support

            for line in support().describe():
                click.echo(line)
        ctx.exit(0)
    if ctx.invoked_subcommand is None:  # bare `mcar`: the help, as a usage error
        click.echo(ctx.get_help(), err=True)
        ctx.exit(2)
