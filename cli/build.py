"""``mcar build``: expand xacro into URDF with the real xacro library, without ROS."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from mobile_car.atomic import atomic_write
from mobile_car.errors import EXIT_OK, McarError, UsageError, combine_exit_codes
from mobile_car.expand.xacro_warnings import merged_warnings
from mobile_car.load.default_outputs import default_folder
from mobile_car.load.inputs import display_path
from mobile_car.names import shown
from mobile_car.packages.discover import output_name

from . import streams
from .common import (
    INPUT_HELP,
    handle_errors,
    input_basis,
    load_inputs,
    print_warning,
    report,
    robot_options,
    stdin_for,
)

HELP = f"""Expand xacro into URDF (or into Gazebo's SDF, --format sdf).

\b
  mcar build FILE.xacro [NAME:=VALUE ...]      URDF on stdout
  mcar build FILE.xacro -o OUT.urdf            URDF written to OUT.urdf
  mcar build FILE.xacro -o OUTDIR/             URDF written to OUTDIR/FILE.urdf
  mcar build - < FILE.xacro                    xacro text from stdin
  mcar build DIR [-o OUTDIR]                   every robot file of a package
  mcar build wheel chassis                     the robot files of those parts
  mcar build                                   every robot file of the package you
                                               stand in, into its build/
  mcar build FILE.xacro --format sdf -o R.sdf  the SDF Gazebo spawns (libsdformat's)

A robot file is a .xacro whose root is <robot name="...">; macro files (a <robot>
with no name) are only included. Built files mirror the urdf/ tree:
urdf/wheel/test_wheel.urdf.xacro -> build/wheel/test_wheel.urdf.

$(find PKG) works without ROS: PKG is looked up in the package holding INPUT, then
--package-path, ROS_PACKAGE_PATH, AMENT_PREFIX_PATH, and the bundled
mobile_car_description; a file the package's source folder lacks is looked up
where its CMakeLists.txt installs it from ($(find PKG)/urdf/x.xacro of a package
that installs description/urdf). package:// URIs are left as they are; absolute paths that
$(find) put into attributes are written back as package:// URIs, so the output is
the same on every machine. NAME:=VALUE sets a <xacro:arg>; a name the files never
declare is an error (plain xacro ignores it silently).

--set NAME=VALUE and --config FILE.yaml change the robot's dimensions (see
`mcar config`); they are checked before anything is built (exit 2 when they
cannot make a working robot) and apply to every file that includes config.xacro.

Outputs are written atomically: a failed build leaves an earlier output untouched,
and a rebuilt file keeps its permissions. -o ending in / is a folder; -o OUT.urdf
needs exactly one robot to build.

For MuJoCo (and other simulators), `mcar export ROBOT --to mjcf -o DIR` writes a
folder with the model and its meshes.

--format sdf writes the SDF Gazebo would spawn from the URDF, as libsdformat (Gazebo's
URDF reader) converts and writes it: fixed joints lumped, links without mass left out
(a warning says so; `mcar check --gazebo` says what is lost). It needs the helper
mcar-sdformat (make gazebo-helper; without it, exit 2 saying how). A robot libsdformat
cannot load is an error (exit 1); built files are named .sdf.

--deps prints the files the expansion reads (the input first, then includes and
loaded YAML), relative to the current folder (--absolute: absolute). Alone it builds
nothing; with -o it writes the outputs too, so one run both builds and tells Make
what to rebuild on.
Errors are printed as FILE:LINE: error: message, then xacro's macro/include stack.

{INPUT_HELP}

\b
Exit codes:
  0  every input was built
  1  xacro could not expand an input (its error is printed, located); with
     --format sdf, libsdformat cannot load it
  2  usage or I/O error: bad option or argument, missing or unreadable file, a macro
     file given as a robot, overrides the input cannot take, unknown package; with
     --format sdf, no Gazebo helper
  130  interrupted (Ctrl-C); 143 terminated
"""


def _print_deps(deps: list[Path], absolute: bool) -> None:
    from mobile_car.load.outputs import shown_dep

    for dep in dict.fromkeys(shown_dep(d, absolute) for d in deps):
        streams.echo(shown(dep))


SUFFIXES = {"urdf": ".urdf", "sdf": ".sdf"}


def _output(loaded, output_format: str) -> bytes:
    """What is written of a loaded robot: its URDF, or the SDF libsdformat writes of it (its
    warnings printed)."""
    if output_format == "sdf":
        from mobile_car.gazebo.sdf import sdf_of

        sdf, warnings = sdf_of(loaded)
        for warning in warnings:
            print_warning(loaded.label, warning)
        return sdf
    return loaded.urdf


def _format(ctx, param, value: str) -> str:
    if value == "mjcf":  # one way to MuJoCo: a folder with its meshes, not one file
        raise click.BadParameter("MuJoCo's model is written by `mcar export ROBOT --to mjcf "
                                 "-o DIR`, a folder with the model and its meshes")
    return value


def _build_one(inp, options, stdin, output: str | None, deps: str | None,
               output_format: str) -> None:
    """One file (or stdin) to stdout or to ``-o OUT``; ``deps`` None, "relative" or
    "absolute": print the files read (and, with -o, write the output too)."""
    from mobile_car.load.robot import load_robot

    loaded = load_robot(inp, options, stdin)
    for warning in merged_warnings(loaded.warnings):
        print_warning(inp.label, f"xacro: {warning}")
    writes = deps is None or (output is not None and output != "-")
    written = _output(loaded, output_format) if writes else b""
    if output is not None and output != "-":
        from mobile_car.load.outputs import refuse_overwriting

        refuse_overwriting(output, [inp.path, *loaded.deps])
        atomic_write(output, written)
    if deps:
        _print_deps(loaded.deps, deps == "absolute")
    elif output is None or output == "-":
        streams.write(written)


def _build_many(inputs, options, outdir: Path | None, deps: str | None, quiet: bool,
                output_format: str, basis) -> int:
    """Build every input into outdir, mirrored below its folder; go on past failures.
    An output whose build record says it is current is kept, unread and unexpanded."""
    from mobile_car.load.build_record import BuildRecord, build_key
    from mobile_car.load.outputs import (
        refuse_clashes,
        refuse_overwriting_each,
    )

    deps_only = outdir is None  # --deps without -o: print, build nothing
    suffix = SUFFIXES[output_format]
    targets = [(outdir or Path()) / output_name(inp.path, inp.base or inp.path.parent)
               .with_suffix(suffix) for inp in inputs]
    if not deps_only:
        refuse_clashes(zip(targets, (inp.path for inp in inputs), strict=True))
        refuse_overwriting_each(targets, [inp.path for inp in inputs])
    record = BuildRecord(outdir) if outdir is not None and not deps else None
    key = build_key(output_format, basis.settings)
    generated = [options.overrides.path] if options.overrides is not None else []
    codes, kept = [], 0
    try:
        for inp, target in zip(inputs, targets, strict=True):
            warnings = record.fresh(target, key) if record is not None else None
            if warnings is not None:
                for warning in warnings:
                    print_warning(inp.label, warning)
                kept += 1
                if not quiet:
                    click.echo(f"unchanged {display_path(target)}", err=True)
                continue
            code = _build_into(inp, None if deps_only else target, options, deps,
                               output_format, quiet,
                               (record, key, basis.files, generated))
            if code:
                codes.append(code)
    finally:
        if record is not None:
            record.save()
    if not quiet:
        click.echo(f"{len(inputs) - len(codes)} of {len(inputs)} files built"
                   + ("" if deps_only else f" into {display_path(outdir)}")
                   + (f" ({kept} unchanged)" if kept else ""), err=True)
    return combine_exit_codes(codes) if codes else EXIT_OK


def _build_into(inp, target: Path, options, deps: str | None, output_format: str,
                quiet: bool, recording) -> int:
    """Build one input of many into ``target`` (with --deps and no folder, only list what
    it reads); ``recording``: (BuildRecord or None, key, setting files, generated files).
    Returns the exit code of its failure, or 0."""
    from mobile_car.load.outputs import refuse_overwriting
    from mobile_car.load.robot import load_robot

    record, key, setting_files, generated = recording
    try:
        loaded = load_robot(inp, options)
        written = b"" if target is None else _output(loaded, output_format)
    except UsageError:
        raise  # the command line is wrong for every file alike
    except McarError as error:
        report(error)
        return error.exit_code
    for warning in merged_warnings(loaded.warnings):
        print_warning(inp.label, f"xacro: {warning}")
    if target is not None:
        refuse_overwriting(target, loaded.deps)
        atomic_write(target, written)
        if record is not None:
            record.record(target, key, [*loaded.deps, *setting_files], loaded.warnings,
                          generated)
    if deps:
        _print_deps(loaded.deps, deps == "absolute")
    if target is not None and not quiet:
        click.echo(f"built {display_path(target)}", err=True)
    return 0


@click.command("build", help=HELP, short_help="Expand xacro into URDF.")
@click.argument("words", nargs=-1, metavar="[INPUT]... [NAME:=VALUE]...")
@click.option("-o", "--output", metavar="OUT",
              help="Output file (one file INPUT; default: stdout) or folder "
                   "(a folder, parts, several files or no INPUT; default: build/ under the "
                   "package's root, or here for files outside a package; refused if it is a "
                   "link leading out of there, unless named here).")
@click.option("--deps", "deps", is_flag=True,
              help="Print the files the expansion reads, one per line (for Make); without "
                   "-o build nothing, with -o write the outputs too.")
@click.option("--absolute", is_flag=True, help="--deps prints absolute paths (default: "
                                                "relative to the current folder).")
@click.option("--format", "output_format", type=click.Choice(("urdf", "mjcf", "sdf")),
              default="urdf", show_default=True, callback=_format,
              help="urdf: the expanded URDF; sdf: the SDF Gazebo spawns, written by "
                   "libsdformat (built files named .sdf). MuJoCo's model: `mcar export --to "
                   "mjcf`.")
@click.option("-q", "--quiet", is_flag=True, help="Print only errors and warnings.")
@robot_options
@handle_errors
def command(words, output, deps, absolute, output_format, quiet, package_paths, sets,
            config_files):
    from mobile_car.load.outputs import names_folder

    if absolute and not deps:
        raise UsageError("--absolute goes with --deps")
    if deps and output == "-":
        raise UsageError("--deps prints to stdout: give -o a file, not -")
    deps = ("absolute" if absolute else "relative") if deps else None
    if output_format == "sdf" and not deps:  # before anything is built: how to install it
        from mobile_car.gazebo.helper import find_helper

        find_helper()
    with load_inputs(words, package_paths, sets, config_files, through_xacro=True) as (
            selection, options):
        inputs = selection.inputs
        names_file = bool(output) and output.endswith(tuple(SUFFIXES.values()))
        if len(inputs) == 1 and (selection.kind == "files" or names_file) and not (
                output and names_folder(output)):
            _build_one(inputs[0], options, stdin_for(selection), output, deps, output_format)
            return
        if selection.reads_stdin:
            raise UsageError("- (stdin) is built alone, to stdout or to -o FILE")
        if output == "-":
            raise UsageError("-o - (stdout) works with one file INPUT only")
        if names_file:
            raise UsageError(f"-o {output} is one file, but there are {len(inputs)} robot "
                             "files to build; name one INPUT file, or give -o a folder")
        outdir = Path(output) if output else None if deps else \
            default_folder(selection.output_root, "build", "-o")
        basis = input_basis(options.mappings, package_paths, sets, config_files)
        sys.exit(_build_many(inputs, options, outdir, deps, quiet, output_format, basis))
