"""What every command shares: the package-path and asset-path options and turning errors
into exit codes."""

from __future__ import annotations

import contextlib
import functools
import os
import sys
from pathlib import Path

import click

from mobile_car.errors import EXIT_OK, EXIT_PROBLEMS, EXIT_USAGE, McarError, Terminated, UsageError
from mobile_car.names import shown

from . import streams

package_path_option = click.option(
    "--package-path", "package_paths", multiple=True, metavar="DIR",
    type=click.Path(file_okay=False, exists=True),
    help="Also look for ROS packages (package.xml) under DIR; repeatable. Searched after the "
         "package holding INPUT and before ROS_PACKAGE_PATH, AMENT_PREFIX_PATH and the "
         "bundled mobile_car_description.")


def config_options(func):
    """--set and --config: override the robot's dimensions (see `mcar config`)."""
    func = click.option(
        "--config", "config_files", multiple=True, metavar="FILE.yaml",
        type=click.Path(dir_okay=True),
        help="Dimension overrides from a YAML/JSON file: `name: value` pairs (only what "
             "differs), or a document `mcar config --format json` wrote. Repeatable; "
             "--set wins.")(func)
    func = click.option(
        "--set", "sets", multiple=True, metavar="NAME=VALUE",
        help="Override one dimension of config.xacro, e.g. --set wheel_radius=40mm. A bare "
             "number is SI (m, kg); units like mm, cm, in, g, deg are converted. Repeatable.")(
        func)
    return func


INPUT_HELP = """\b
INPUT is what every command takes: a .urdf or .xacro file, a folder (its .urdf files
and robot .xacro files, in urdf/, robots/, xacro/, description/ or itself), - for
stdin, or the name of a part folder of the package (wheel, chassis). None means the
package you stand in (the nearest package.xml above), else every package of the
workspace you stand in (here or in src/); stderr says which. Anywhere else, name the
robot, or give --bundled for the mobile car bundled with mcar. NAME:=VALUE words set
xacro arguments."""

_color: bool | None = None  # --color/--no-color of this run; None: the NO_COLOR/TTY rule
_bundled = False  # --bundled of this run: outside any package, the bundled car is meant


def _set_bundled(ctx, param, value):
    global _bundled
    _bundled = value
    return value


def working_here(package_paths):
    """What a command without INPUT (or with part names) works on: the package or workspace
    you stand in. Outside both, the bundled car only when asked for with --bundled: a CI job
    started in the wrong folder must not go green on mcar's own robot."""
    from mobile_car.load.package import working_set

    def working():
        found = working_set(Path.cwd(), package_paths)
        if found.kind == "bundled" and not _bundled:
            raise UsageError(f"no robot package here: {Path.cwd()} has no package.xml above "
                             "it and no packages in it or its src/; name a robot file or "
                             "folder, or give --bundled for the mobile car bundled with mcar")
        return found
    return working


def _set_color(ctx, param, value):
    global _color
    _color = value
    return value


def _no_sandbox(ctx, param, value):
    if value:
        from mobile_car.expand.sandbox import trust_inputs

        trust_inputs()
    return value


def _allow_asset_paths(ctx, param, value):
    from mobile_car.packages.asset_roots import allow_asset_paths

    allow_asset_paths(value)  # none too: a run in the same process starts from none
    return value


asset_path_option = click.option(
    "--asset-path", "asset_paths", multiple=True, metavar="DIR", expose_value=False,
    type=click.Path(file_okay=False, exists=True), callback=_allow_asset_paths,
    help="Also let the robot name meshes and textures under DIR; repeatable. Without it, "
         "a file outside the robot's folder and the package folders is never read nor "
         "exported (W215).")


def robot_options(func):
    """The options every command that loads a robot takes: --set, --config,
    --package-path, --asset-path, --no-sandbox, --color/--no-color."""
    func = click.option("--color/--no-color", "color", default=None, expose_value=False,
                        callback=_set_color, is_eager=True,
                        help="Colour the severity of problems (default: on a terminal, "
                             "unless NO_COLOR is set).")(func)
    func = click.option("--bundled", is_flag=True, expose_value=False, callback=_set_bundled,
                        help="With no INPUT outside any package: work on the mobile car "
                             "bundled with mcar (without it, that is an error).")(func)
    func = click.option("--no-sandbox", is_flag=True, expose_value=False,
                        callback=_no_sandbox,
                        help="Expand xacro without the sandbox (no seccomp, no Landlock): "
                             "only for trees you trust; a .xacro is code.")(func)
    return package_path_option(asset_path_option(config_options(func)))


@contextlib.contextmanager
def load_inputs(words, package_paths, sets, config_files, through_xacro: bool = False):
    """What the user named, ready to load: yields (Selection, LoadOptions).

    Arguments the inputs cannot take are refused here, before anything is loaded; the
    overrides are validated and written once, for every input, and removed afterwards.
    """
    selection, mappings = select_inputs(words, package_paths, sets, config_files, through_xacro)
    with prepared_load(selection, mappings, package_paths, sets, config_files,
                       through_xacro) as options:
        yield selection, options


def select_inputs(words, package_paths, sets, config_files, through_xacro: bool = False):
    """The first half of :func:`load_inputs`, which loads nothing: (Selection, mappings)."""
    from mobile_car.load.inputs import split_words
    from mobile_car.load.robot import CONFIG_ARG, LoadOptions, refuse_unused_arguments
    from mobile_car.load.selection import select

    names, mappings = split_words(words)
    if CONFIG_ARG in mappings and (sets or config_files):
        raise UsageError(f"{CONFIG_ARG}:= and --set/--config both give overrides; use one")
    selection = select(names, working_here(package_paths))
    refuse_unused_arguments(selection.inputs, LoadOptions(
        mappings, through_xacro=through_xacro), overriding=bool(sets or config_files))
    return selection, mappings


def input_basis(mappings, package_paths, sets, config_files):
    """What, besides the files they read, decides how the inputs load (see freshness)."""
    from mobile_car.freshness import Basis

    return Basis.of(mappings, sets, config_files, package_paths)


@contextlib.contextmanager
def prepared_load(selection, mappings, package_paths, sets, config_files,
                  through_xacro: bool = False):
    """The second half of :func:`load_inputs`: the overrides validated, the LoadOptions."""
    from mobile_car.load.robot import LoadOptions

    if not sets and not config_files:
        say_which_package(selection)
        yield LoadOptions(mappings, [Path(p) for p in package_paths],
                          through_xacro=through_xacro)
        return
    from mobile_car.config.overrides import prepared_overrides
    from mobile_car.packages.search import PackageSearch

    xacros = [inp.path for inp in selection.inputs if inp.is_xacro]
    origin = xacros[0] if xacros else (selection.root or Path.cwd())
    search = PackageSearch(package_paths=list(package_paths), origin=origin)
    with prepared_overrides(search, sets, config_files) as overrides:
        say_which_package(selection)
        yield LoadOptions(mappings, [Path(p) for p in package_paths], overrides, through_xacro)


def say_which_package(selection) -> None:
    """One line on stderr naming the package a command without INPUT works on: a green
    run must never be a run over the wrong robot without saying so."""
    if selection.working is not None:
        click.echo(f"mcar: {selection.working.describe()}", err=True)


def stdin_for(selection):
    """The binary stdin stream when an input is ``-``, else None."""
    return sys.stdin.buffer if selection.reads_stdin else None


def use_color() -> bool | None:
    """--color/--no-color when given; else False with NO_COLOR set (https://no-color.org);
    else None: click colours a terminal only."""
    if _color is not None:
        return _color
    return False if os.environ.get("NO_COLOR") else None


_SEVERITY_COLOURS = {"error": "red", "warning": "yellow", "note": "cyan"}


def severity_label(severity: str) -> str:
    """``error:`` in red, ``warning:`` in yellow, ``note:`` in cyan (the styling is dropped
    off a TTY)."""
    return click.style(f"{severity}:", fg=_SEVERITY_COLOURS.get(severity, "yellow"), bold=True)


def print_diagnostic(diagnostic) -> None:
    """One ``FILE:LINE: error: message [E104]`` line on stderr, the severity coloured."""
    click.echo(f"{diagnostic.location()}: {severity_label(diagnostic.severity)} "
               f"{shown(diagnostic.message)} [{diagnostic.rule}]", err=True, color=use_color())


def print_warning(where: str, message: str) -> None:
    click.echo(f"{shown(where)}: {severity_label('warning')} {shown(message)}", err=True,
               color=use_color())


def chosen_robot(selection, command: str):
    """The one robot a single-robot command works on (see one_robot); when it was chosen
    among several found (no INPUT, or a folder), one stderr line says which, so that
    what is shown is never a guess the user cannot see."""
    from mobile_car.load.selection import one_robot

    inp = one_robot(selection, command)
    if len(selection.inputs) > 1:
        click.echo(f"mcar: {shown(inp.label)}, the one complete robot here "
                   "(an INPUT names another)", err=True)
    return inp


def checked_robots(selection, options, codes: list, inputs=None):
    """(input, CheckResult) of each input of ``selection`` (or of ``inputs``, some of
    them) that passes ``mcar check``, checked as it does; one whose load or check fails
    is reported here (check's own diagnostics) and its exit code added to ``codes``: what
    sim and specs do first."""
    from mobile_car.check.checker import check_input

    stdin = stdin_for(selection)
    for inp in selection.inputs if inputs is None else inputs:
        checked = check_input(inp, options, stdin=stdin)
        if checked.failure is not None:
            report(checked.failure)
            codes.append(checked.failure.exit_code)
            continue
        if checked.errors or not checked.tree_is_drawable:
            for diagnostic in checked.diagnostics:
                print_diagnostic(diagnostic)
            codes.append(EXIT_PROBLEMS)
            continue
        yield inp, checked


def report(error: McarError) -> None:
    """Print an error as one `FILE:LINE: error: message` line, then its context lines; a
    robot that failed its check prints the check's diagnostics instead. Names in it are
    escaped (mobile_car.names): a file called "x\\n" cannot add a line of its own."""
    for diagnostic in getattr(error, "diagnostics", ()):
        print_diagnostic(diagnostic)
    if getattr(error, "diagnostics", None):
        return
    where = error.location()
    prefix = f"{where}: " if where else "mcar: "
    click.echo(f"{prefix}{severity_label('error')} {shown(error.message)}", err=True,
               color=use_color())
    for line in error.details:
        click.echo(f"  {shown(line)}", err=True)


def _say_if_unconfined() -> None:
    """Once per run, if xacro was expanded without the kernel's confinement."""
    sandbox = sys.modules.get("mobile_car.expand.sandbox")  # not imported: nothing expanded
    notice = sandbox.unconfined_notice() if sandbox is not None else None
    if notice is not None:
        print_warning("mcar", notice)


def _say_xacro_use(label: str, use: str) -> None:
    """The note for a .urdf expanded because it uses xacro (once per file and run)."""
    from mobile_car.load.xacro_use import note_text

    if label not in _said_xacro_use:
        _said_xacro_use.add(label)
        click.echo(f"mcar: {shown(label)}: {shown(note_text(use))}", err=True)


_said_xacro_use: set[str] = set()


def handle_errors(func):
    """Run a command body and end the run: McarError becomes its message and exit code,
    Ctrl-C exits 130 and SIGTERM 143 whenever it came, a closed stdout pipe exits 0
    quietly, and a failed write to stdout or stderr is an I/O error (exit 2)."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        from mobile_car.load import xacro_use
        from mobile_car.load.default_outputs import forget_default_folders

        from . import signals

        try:
            forget_default_folders()
            signals.arm()
            _said_xacro_use.clear()
            xacro_use.listen(_say_xacro_use)
            try:
                result = func(*args, **kwargs)
                streams.flush()
            finally:
                xacro_use.listen(None)
                # The body has unwound (temporary files gone, children ended): from here
                # on a signal ends mcar at once, even while the lines below print.
                signals.disarm()
        except SystemExit as exit_:
            code = EXIT_OK if exit_.code is None else exit_.code
        except BaseException as error:
            code = _exit_code_of(error)
        else:
            code = None
        try:
            _say_if_unconfined()
        except OSError:  # stderr is gone: nowhere to say it
            pass
        if signals.received():  # it may have been swallowed by a library: it still counts
            streams.say(signals.announcement(signals.received()))
            code = 128 + signals.received()
        if code is None:
            return result
        streams.exit_quietly(code)

    return wrapper


def _exit_code_of(error: BaseException) -> int:
    """Say what ended the command (unless a signal did: said by the caller); its code."""
    from . import signals

    if isinstance(error, McarError):
        if not signals.received():
            try:
                report(error)
            except OSError:  # stderr is full or closed: nowhere left to say it
                pass
        return error.exit_code
    if isinstance(error, KeyboardInterrupt):
        if not signals.received():  # no handler of ours (an embedding program)
            streams.say("mcar: interrupted")
        return 130
    if isinstance(error, Terminated):
        if not signals.received():
            streams.say("mcar: terminated")
        return error.exit_code
    if isinstance(error, streams.ReaderGone):  # `mcar tree | head -1`: the reader wanted no more
        return 0
    if not isinstance(error, Exception) or signals.received():
        return EXIT_USAGE  # an odd BaseException; or a swallowed signal made this mess
    if os.environ.get("MCAR_DEBUG"):
        raise error
    # If the failure was a write to stderr, this line cannot be written either: exit 2.
    streams.say(f"mcar: internal error: {type(error).__name__}: {shown(str(error))} "
                "(set MCAR_DEBUG=1 for a traceback, and please report it)")
    return EXIT_USAGE


def start_probe(stack, renderer: str):
    """Try OpenGL in its drawing process now, while the robots load and their figures are
    computed (mcar diff --picture, mcar specs --picture); ``stack`` (an ExitStack) ends
    it if it is not used. None for the ray-casting renderer."""
    if renderer == "raycast":
        return None
    from mobile_car.render.backend import GLProbe

    probe = GLProbe()
    stack.callback(probe.cancel)
    return probe
