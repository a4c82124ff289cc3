"""``mcar check``: check_urdf's verdict and tree, plus the errors check_urdf misses."""

from __future__ import annotations

import functools
import gc
import os
import sys

import click

from mobile_car.check import replay
from mobile_car.check.diagnostics import github_annotation, size_text
from mobile_car.check.replay import ReplayedResult
from mobile_car.check.rules import NOTE
from mobile_car.errors import combine_exit_codes
from mobile_car.names import json_safe, shown

from . import signals, streams
from .common import (
    INPUT_HELP,
    handle_errors,
    input_basis,
    load_inputs,
    print_diagnostic,
    report,
    robot_options,
    stdin_for,
)

HELP = f"""Check URDF files: check_urdf's verdict and tree, and the errors it misses.

\b
  mcar check robot.urdf                  check_urdf's output, problems on stderr
  mcar check robot.urdf.xacro [N:=V]...  built first (same options as mcar build)
  mcar check urdf/ a.urdf b.urdf         many inputs; a folder means its .urdf files
                                         and robot .xacro files
  mcar check - < robot.urdf              read from stdin
  mcar check --format json robot.urdf    one JSON document on stdout
  mcar check --format github urdf/       annotations for a GitHub Actions log
  mcar check --gazebo robot.xacro        also what Gazebo changes (libsdformat's
                                         conversion): lumped and dropped links

For a sound file, stdout is byte for byte what check_urdf prints (children in
check_urdf's order: by joint name). Every problem is one line on stderr:
FILE:LINE: error: message [E104]. Rule ids and what they find: docs/rules.md.
Errors (E1xx) fail the check; warnings (W2xx) fail it only with --strict. For a
.xacro input, FILE:LINE point into the xacro sources where the element's name can
be found there, else at the input with the line of the expanded URDF.

A .xacro input checked before, with nothing it reads changed since (its files and
includes, meshes, --config files, arguments, the environment variables it names), is
not expanded again: its results are read back from the user's cache folder, the same
output and exit code (docs/check.md).

Where the robot's package ships the rest of its ROS configuration (a drive
controller's YAML in X_control, Nav2's in X_navigation), a sound robot's is compared
with it: a wheel separation, radius, wheel name or Nav2 footprint that is off is a
warning at the YAML line (W510-W513; docs/check.md).

--gazebo gives each sound robot to libsdformat, which Gazebo loads URDF with, and
reports what it changes: links lumped into their parent by fixed joints (notes,
N401), links dropped for want of mass with everything that moves below them (E150),
<gazebo reference> blocks and plugin joint names left pointing at nothing (W231,
W232), the errors libsdformat's load returns (E151: its verdict, named with its
version) and what it only printed (N404, W230), and the mass Gazebo simulates. It
needs the helper mcar-sdformat (make gazebo-helper; without it, exit 2 saying how).

{INPUT_HELP}

\b
Exit codes:
  0  every input is sound (warnings allowed unless --strict)
  1  problems found: an error, or a warning with --strict
  2  usage or I/O error: bad option, missing or unreadable file, a macro file given
     as a robot, unknown package
  130  interrupted (Ctrl-C); 143 terminated
"""

FORMATS = ("text", "json", "github")


# The checker (lxml, the schema) is imported only where an input is checked: a check
# with nothing changed reads its results back without it (mobile_car.check.replay).


def _emit_text(results: list, quiet: bool) -> None:
    many = len(results) > 1
    out = sys.stdout.buffer
    for result in results:
        if result.failure is not None:
            report(result.failure)
        if not quiet and result.sound:
            with streams.stdout_writes():
                if many:
                    out.write(f"==> {result.file} <==\n".encode())
                # check_urdf writes names byte for byte: UTF-8 whatever the locale says.
                streams.write_lines(_tree_lines(result))
        for diagnostic in result.diagnostics:
            if not (quiet and diagnostic.severity == NOTE):  # -q: only problems
                print_diagnostic(diagnostic)
        if not quiet and result.extents is not None:
            # On stderr: stdout is check_urdf's, byte for byte.
            where = f"{shown(result.file)}: " if many else ""
            click.echo(f"{where}size: {size_text(result.extents)}", err=True)
    errors = sum(r.errors for r in results)
    warnings = sum(r.warnings for r in results)
    failed = sum(1 for r in results if r.failure is not None)
    if errors or warnings or failed:
        parts = [f"{errors} error{'s' * (errors != 1)}",
                 f"{warnings} warning{'s' * (warnings != 1)}"]
        if failed:
            parts.append(f"{failed} not checked")
        click.echo(f"mcar check: {', '.join(parts)} in {len(results)} "
                   f"file{'s' * (len(results) != 1)}", err=True)


def _tree_lines(result):
    """check_urdf's tree text, made line by line as it is written (a read-back check
    has it whole: it is kept only when small, see mobile_car.check.replay)."""
    if isinstance(result, ReplayedResult):
        return [result.tree_text]
    from mobile_car.check.tree import check_urdf_lines

    return check_urdf_lines(result.robot.name, result.tree)


def _document(result) -> dict:
    if isinstance(result, ReplayedResult):
        return result.document
    from mobile_car.check.checker import as_json

    return as_json(result)


def _checked(inputs, options, stdin, basis, keep: bool) -> list:
    """Each input's result: read back where nothing changed since it was last checked
    (mobile_car.check.replay), else checked and, where ``keep``, recorded. ``basis()``
    gives the run's Basis, made (with the records' modules) only for an input that can
    have a record: a plain URDF cannot."""
    stamper = None
    results = []
    for inp in inputs:
        replayable = keep and replay.replayable(inp)
        replayed = replay.replay(inp, basis()) if replayable else None
        if replayed is not None:
            results.append(replayed)
            continue
        from mobile_car.check.checker import check_input

        result = check_input(inp, options, stdin=stdin)
        read, absent = _compare_package_yaml(result)
        results.append(result)
        if replayable:
            if stamper is None:
                from mobile_car.freshness import Stamper

                stamper = Stamper()
            replay.record(inp, basis(), result, stamper, also=read, absent=absent)
    return results


def _compare_package_yaml(result) -> tuple[list, list]:
    """The robot's package's own controller and Nav2 YAML compared with it (W510-W513,
    mobile_car.specs.stack_check), added to its diagnostics; (the YAML files looked at,
    the sibling packages that are not there): its record depends on both. A package
    without such YAML builds nothing."""
    if result.loaded is None or result.failure is not None:
        return [], []
    from mobile_car.check.diagnostics import Diagnostic
    from mobile_car.specs.stack_check import check_package

    diagnostics, found = check_package(result)
    if diagnostics:
        result.diagnostics = sorted(result.diagnostics + diagnostics, key=Diagnostic.sort_key)
    return found.read, found.absent


def _emit_github(results: list) -> None:
    for result in results:
        if result.failure is not None:
            streams.echo(github_annotation("error", result.file, result.failure.line, None,
                                         result.failure.message))
        for diagnostic in result.diagnostics:
            streams.echo(diagnostic.github())


def _emit_json(results: list, exit_code: int) -> None:
    document = {"files": [_document(r) for r in results],
                "errors": sum(r.errors for r in results),
                "warnings": sum(r.warnings for r in results),
                "exit_code": exit_code}
    streams.write_lines(_json_pieces(document))


def _json_pieces(document: dict):
    """``json.dumps(document, indent=1, ensure_ascii=False)`` made safe (json_safe) and
    UTF-8, with its newline, in pieces of about 64 KB. dumps gathers every token of the
    text in one list before joining it: for a 10,000-link robot, 9 MB of JSON held as a
    million small strings, ~80 MB. (json_safe works character by character: the pieces
    may be cut anywhere.)"""
    import json

    piece: list[str] = []
    size = 0
    for token in json.JSONEncoder(indent=1, ensure_ascii=False).iterencode(document):
        piece.append(token)
        size += len(token)
        if size >= 1 << 16:
            yield json_safe("".join(piece)).encode("utf-8")
            piece, size = [], 0
    piece.append("\n")
    yield json_safe("".join(piece)).encode("utf-8")


def overall_exit(results: list, strict: bool) -> int:
    return combine_exit_codes(r.exit_code(strict) for r in results)


@click.command("check", help=HELP, short_help="Check URDF files (a stricter check_urdf).")
@click.argument("words", nargs=-1, metavar="[INPUT]... [NAME:=VALUE]...")
@click.option("--format", "output_format", type=click.Choice(FORMATS), default="text",
              show_default=True, help="text: check_urdf's output on stdout, problems on "
              "stderr; json: one JSON document on stdout; github: workflow annotations.")
@click.option("--strict", is_flag=True, help="Warnings fail the check too (exit 1).")
@click.option("--gazebo", is_flag=True,
              help="Also report what Gazebo changes in the robot (libsdformat's URDF "
                   "conversion): lumped and dropped links, dangling <gazebo> references.")
@click.option("-q", "--quiet", is_flag=True,
              help="text format: print only problems (errors and warnings), not "
                   "check_urdf's tree, the size or notes.")
@robot_options
@handle_errors
def command(words, output_format, strict, gazebo, quiet, package_paths, sets, config_files):
    if gazebo:  # said before anything is loaded: exit 2 with how to install it
        from mobile_car.gazebo.helper import find_helper

        find_helper()
    # One short run builds hundreds of thousands of objects and no garbage cycles worth
    # collecting; the cyclic collector's passes over them cost much of the run.
    gc.disable()
    try:
        with load_inputs(words, package_paths, sets, config_files) as (selection, options):
            basis = functools.cache(lambda: input_basis(options.mappings, package_paths,
                                                        sets, config_files))
            results = _checked(selection.inputs, options, stdin_for(selection), basis,
                               keep=not gazebo)
        if gazebo:
            from mobile_car.gazebo.check import check_in_gazebo

            for result in results:
                check_in_gazebo(result)
        exit_code = overall_exit(results, strict)
        if output_format == "json":
            _emit_json(results, exit_code)
        elif output_format == "github":
            _emit_github(results)
        else:
            _emit_text(results, quiet)
    finally:
        if not own_process():
            gc.enable()  # the caller (a test) goes on in this process
    if own_process() and not signals.received():
        # Freeing a 20,000-link robot's lxml tree and model at interpreter exit takes a
        # good part of the run, for nothing: everything is printed, so leave at once.
        streams.flush()
        sys.stderr.flush()
        os._exit(exit_code)
    sys.exit(exit_code)


def own_process() -> bool:
    """True when mcar is its own process (not under click's CliRunner, as in tests)."""
    return sys.stdout is sys.__stdout__ and sys.stderr is sys.__stderr__
