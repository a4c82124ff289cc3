"""``mcar tree``: the kinematic tree with each joint's type, origin, axis and limits."""

from __future__ import annotations

import sys

import click

from mobile_car.check.checker import check_input
from mobile_car.check.graphviz import write_graph
from mobile_car.check.tree import rich_lines
from mobile_car.check.tree_dot import graphviz_dot
from mobile_car.errors import EXIT_PROBLEMS, UsageError

from . import streams
from .common import (
    INPUT_HELP,
    chosen_robot,
    handle_errors,
    load_inputs,
    print_diagnostic,
    robot_options,
    stdin_for,
)

HELP = f"""Print the kinematic tree of one robot (a URDF or xacro file), with its joints.

\b
  mcar tree                                    the package's complete robot
  mcar tree robot.urdf
  mcar tree robot.urdf.xacro [NAME:=VALUE]...
  mcar tree robot.urdf --graphviz tree.svg     also draw it (.dot, .gv, .svg, .png, .pdf)
  mcar tree robot.urdf --graphviz tree.svg --fold-fixed
                                               ...only the moving joints between boxes

Each link is shown under its parent with the joint that carries it: name, type,
origin (xyz, rpy), axis and limits. Children are in check_urdf's order (by joint
name). Drawing .svg, .png or .pdf needs Graphviz's `dot` (Debian package graphviz);
a .dot file needs nothing. In the drawing, fixed joints are dashed and grey, moving
ones solid and bold; --fold-fixed draws each group of links held together by fixed joints
as one box (named after its top link, listing the others), so that the degrees of freedom
are what remains. Only the tree is checked here; `mcar check` checks the rest.
One robot at a time: with no INPUT (or a folder) it is the package's complete robot
(its one robot file directly in urdf/, not the parts' test files); with several, each
is listed: name one.

{INPUT_HELP}

\b
Exit codes:
  0  the tree was printed (and drawn)
  1  there is no single tree: two parents, a cycle, a stray link, a broken file
  2  usage or I/O error (a macro file given as a robot, several robots), or `dot`
     missing or failing
  130  interrupted (Ctrl-C); 143 terminated
"""


@click.command("tree", help=HELP, short_help="Print the kinematic tree with its joints.")
@click.argument("words", nargs=-1, metavar="[INPUT] [NAME:=VALUE]...")
@click.option("--graphviz", "graph_output", metavar="OUT",
              help="Also write the tree as Graphviz: OUT.dot/.gv (text) or OUT.svg/.png/.pdf "
                   "(drawn by `dot`).")
@click.option("--fold-fixed", is_flag=True,
              help="With --graphviz: one box per group of links joined by fixed joints; "
                   "only moving joints are drawn.")
@click.option("-q", "--quiet", is_flag=True, help="Do not print the tree (with --graphviz).")
@robot_options
@handle_errors
def command(words, graph_output, fold_fixed, quiet, package_paths, sets, config_files):
    if fold_fixed and not graph_output:
        raise UsageError("--fold-fixed folds the --graphviz drawing: give --graphviz OUT too")
    with load_inputs(words, package_paths, sets, config_files) as (selection, options):
        inp = chosen_robot(selection, "mcar tree")
        result = check_input(inp, options, stdin=stdin_for(selection), structure_only=True)
    if result.failure is not None:
        raise result.failure
    for diagnostic in result.diagnostics:
        print_diagnostic(diagnostic)
    if not result.tree_is_drawable:
        why = ("has no single kinematic tree" if result.tree is not None else
               "was not read into a robot (the error above)")
        click.echo(f"mcar tree: {result.file} {why}", err=True)
        sys.exit(EXIT_PROBLEMS)
    if not quiet:
        # Written as it is made: a deep chain's text is hundreds of megabytes.
        streams.write_lines(rich_lines(result.tree))
    if graph_output:
        written = write_graph(graphviz_dot(result.robot.name, result.tree, fold_fixed),
                              graph_output)
        click.echo(f"wrote {written}", err=True)
