"""``mcar tree``: the kinematic tree with each joint's type, origin, axis and limits."""

from __future__ import annotations

import sys

import click

from mobile_car.checker import STDIN, check_input
from mobile_car.errors import EXIT_PROBLEMS, UsageError
from mobile_car.graphviz import write_graph
from mobile_car.tree import graphviz_dot, rich_text

from .check import split_words
from .common import handle_errors, package_path_option

HELP = """Print the kinematic tree of a URDF or xacro file, with its joints.

\b
  mcar tree robot.urdf
  mcar tree robot.urdf.xacro [NAME:=VALUE]...
  mcar tree robot.urdf --graphviz tree.svg     also draw it (.dot, .gv, .svg, .png, .pdf)

Each link is shown under its parent with the joint that carries it: name, type,
origin (xyz, rpy), axis and limits. Children are in check_urdf's order (by joint
name). Drawing .svg, .png or .pdf needs Graphviz's `dot` (Debian package graphviz);
a .dot file needs nothing. Only the tree is checked here; `mcar check` checks the rest.

\b
Exit codes:
  0  the tree was printed (and drawn)
  1  there is no single tree: two parents, a cycle, a stray link, a broken file
  2  usage or I/O error, or `dot` missing or failing
"""


@click.command("tree", help=HELP, short_help="Print the kinematic tree with its joints.")
@click.argument("words", nargs=-1, metavar="INPUT [NAME:=VALUE]...")
@click.option("--graphviz", "graph_output", metavar="OUT",
              help="Also write the tree as Graphviz: OUT.dot/.gv (text) or OUT.svg/.png/.pdf "
                   "(drawn by `dot`).")
@click.option("-q", "--quiet", is_flag=True, help="Do not print the tree (with --graphviz).")
@package_path_option
@handle_errors
def command(words, graph_output, quiet, package_paths):
    inputs, mappings = split_words(words)
    if len(inputs) != 1:
        raise UsageError(f"one INPUT at a time, got {len(inputs)}: {' '.join(inputs)}")
    stdin = click.get_binary_stream("stdin") if inputs[0] == STDIN else None
    result = check_input(inputs[0], mappings, package_paths, stdin=stdin, structure_only=True)
    if result.failure is not None:
        raise result.failure
    for diagnostic in result.diagnostics:
        click.echo(diagnostic.text(), err=True)
    if not result.tree_is_drawable:
        click.echo(f"mcar tree: {result.file} has no single kinematic tree", err=True)
        sys.exit(EXIT_PROBLEMS)
    if not quiet:
        sys.stdout.buffer.write(rich_text(result.tree).encode("utf-8"))
        sys.stdout.flush()
    if graph_output:
        written = write_graph(graphviz_dot(result.robot.name, result.tree), graph_output)
        click.echo(f"wrote {written}", err=True)
