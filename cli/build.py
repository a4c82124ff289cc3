"""``mcar build``: expand xacro into URDF with the real xacro library, without ROS."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from mobile_car.atomic import atomic_write
from mobile_car.build import build_file, display_path, parse_mapping_args
from mobile_car.discover import output_name, require_robot_files, source_base
from mobile_car.errors import EXIT_OK, EXIT_PROBLEMS, McarError, UsageError
from mobile_car.packages import PackageSearch
from mobile_car.resources import PACKAGE_NAME

from .common import (
    CONFIG_ARG,
    config_options,
    default_package,
    dimension_overrides,
    handle_errors,
    override_context,
    package_path_option,
    report,
)

HELP = """Expand xacro into URDF.

\b
  mcar build FILE.xacro [NAME:=VALUE ...]      URDF on stdout
  mcar build FILE.xacro -o OUT.urdf            URDF written to OUT.urdf
  mcar build DIR [-o OUTDIR]                   every robot file of a package
  mcar build                                   the mobile car: every robot file of
                                               mobile_car_description into build/

A robot file is a .xacro whose root is <robot name="...">; macro files (a <robot>
with no name) are only included. Built files mirror the urdf/ tree:
urdf/wheel/test_wheel.urdf.xacro -> build/wheel/test_wheel.urdf.

$(find PKG) works without ROS: PKG is looked up in the package holding INPUT, then
--package-path, ROS_PACKAGE_PATH, AMENT_PREFIX_PATH, and the bundled
mobile_car_description. package:// URIs are left as they are; absolute paths that
$(find) put into attributes are written back as package:// URIs, so the output is
the same on every machine. NAME:=VALUE sets a <xacro:arg>; a name the files never
declare is an error (plain xacro ignores it silently).

--set NAME=VALUE and --config FILE.yaml change the robot's dimensions (see
`mcar config`); they are checked before anything is built (exit 2 when they
cannot make a working robot) and apply to every file that includes config.xacro.

Outputs are written atomically: a failed build leaves an earlier output untouched.
Errors are printed as FILE:LINE: error: message, then xacro's macro/include stack.
"""


def _write_or_print(xml: str, output: str | None) -> None:
    if output is None or output == "-":
        sys.stdout.write(xml)
        sys.stdout.flush()
    else:
        atomic_write(output, xml)


def _print_deps(deps: list[Path]) -> None:
    for dep in dict.fromkeys(str(d) for d in deps):
        click.echo(dep)


def _build_tree(root: Path, outdir: Path, mappings: dict[str, str], package_paths,
                deps_only: bool, quiet: bool) -> int:
    """Build every robot file under root into outdir; go on past failures; exit code."""
    base = source_base(root)
    sources = require_robot_files(root)
    failures = 0
    for source in sources:
        search = PackageSearch(package_paths=list(package_paths), origin=source)
        try:
            # Dimension overrides reach only the files that include config.xacro.
            result = build_file(source, mappings, search, optional_args=frozenset({CONFIG_ARG}))
        except UsageError:
            raise
        except McarError as error:
            report(error)
            failures += 1
            continue
        for warning in result.warnings:
            click.echo(f"{display_path(source)}: {warning}", err=True)
        if deps_only:
            _print_deps(result.deps)
            continue
        target = outdir / output_name(source, base)
        atomic_write(target, result.xml)
        if not quiet:
            click.echo(f"built {display_path(target)}", err=True)
    if not quiet:
        click.echo(f"{len(sources) - failures} of {len(sources)} files built"
                   + ("" if deps_only else f" into {display_path(outdir)}"), err=True)
    return EXIT_PROBLEMS if failures else EXIT_OK


@click.command("build", help=HELP, short_help="Expand xacro into URDF.")
@click.argument("words", nargs=-1, metavar="[INPUT] [NAME:=VALUE]...")
@click.option("-o", "--output", metavar="OUT",
              help="Output file (with a file INPUT; default: stdout) or folder "
                   "(with a folder or no INPUT; default: build/).")
@click.option("--deps", "deps_only", is_flag=True,
              help="Print the files the expansion reads, one per line (for Make); build nothing.")
@click.option("-q", "--quiet", is_flag=True, help="Print only errors and warnings.")
@config_options
@package_path_option
@handle_errors
def command(words, output, deps_only, quiet, package_paths, sets, config_files):
    inputs = [w for w in words if ":=" not in w]
    mappings = parse_mapping_args([w for w in words if ":=" in w])
    if CONFIG_ARG in mappings and (sets or config_files):
        raise UsageError(f"{CONFIG_ARG}:= and --set/--config both give overrides; use one")
    if len(inputs) > 1:
        raise UsageError(f"one INPUT at a time, got {len(inputs)}: {' '.join(inputs)}")
    if not inputs or Path(inputs[0]).is_dir():
        if inputs:
            root = Path(inputs[0])
        else:
            root = default_package(package_paths)
        overrides = dimension_overrides(root, package_paths, sets, config_files)
        outdir = Path(output) if output else Path("build")
        with override_context(overrides) as extra:
            sys.exit(_build_tree(root, outdir, {**mappings, **extra}, package_paths,
                                 deps_only, quiet))
    source = Path(inputs[0])
    search = PackageSearch(package_paths=list(package_paths), origin=source)
    overrides = dimension_overrides(source, package_paths, sets, config_files)
    with override_context(overrides) as extra:
        result = build_file(source, {**mappings, **extra}, search,
                            optional_args=frozenset({CONFIG_ARG}))
    if overrides and CONFIG_ARG not in result.known_args:
        raise UsageError(f"--set/--config change {PACKAGE_NAME}'s config.xacro, which "
                         f"{display_path(source)} does not include")
    for warning in result.warnings:
        click.echo(f"{display_path(source)}: {warning}", err=True)
    if deps_only:
        _print_deps(result.deps)
        return
    _write_or_print(result.xml, output)
