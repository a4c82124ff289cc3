"""``mcar diff``: what a change does to the robot, for code review."""

from __future__ import annotations

import contextlib
import json
import sys
from pathlib import Path

import click

from mobile_car.errors import EXIT_PROBLEMS, EXIT_USAGE, InputError, McarError, UsageError
from mobile_car.load.inputs import is_urdf_name
from mobile_car.names import shown_lines
from mobile_car.render.options import RENDERER_ENV, RENDERERS

from . import streams
from .common import (
    INPUT_HELP,
    handle_errors,
    prepared_load,
    print_warning,
    robot_options,
    start_probe,
    stdin_for,
)

HELP = f"""Compare two robots by what they are, not by their text: for code review.

\b
  mcar diff old.urdf new.urdf.xacro          two files (URDF or xacro)
  mcar diff HEAD~1                           the package at HEAD~1 against the working tree
  mcar diff main urdf/mobile_robot.xacro     one robot file, at main and now
  mcar diff v1.0 HEAD --format markdown      two revisions, as a pull-request comment
  mcar diff HEAD~1 urdf/robot.xacro --picture diff.png   and a picture of both

Links and joints are matched by name: added, removed, renamed (same content under a
new name). Per joint: type, parent, child, origin (mm, degrees), axis, limits; per
link: mass, centre of mass, principal inertia, visual and collision geometry, origin,
material; the world pose of every frame with the joints at zero, so one changed
macro shows at every frame it moves; totals: mass, centre of mass, bounding box and
footprint of the visuals; the dimensions of config.xacro when both robots have one.
Numbers within --tolerance (SI units) are equal: attribute order and number spelling
never count. Both robots must pass `mcar check`.

--picture FILE.png draws OLD (left) and NEW (right) side by side from one camera, the
links that changed (or were added, removed or renamed) in magenta and the others faded;
it draws one robot pair, so with a revision name one robot file. The renderer is chosen
as for mcar render.

--specs also compares what mcar specs computes of both robots (tip-over angles, footprint,
mass, sensors' blocked sectors...), figure by figure: "tip-over left 24.1° → 19.3°", and
the specs warnings (W5xx) that appear or go; a changed figure counts as a change.

OLD and NEW are files, or git revisions of the repository you stand in: each
revision is built from its own sources, unpacked into a temporary folder (nothing in
the working tree is touched); a single revision is compared with the working tree.
With revisions, INPUT words pick the robot files (default: the package you stand
in), and robot files are paired by their path. NAME:=VALUE, --set and --config apply
to both sides.

{INPUT_HELP}

\b
Exit codes:
  0  no change to the robot
  1  changes found (as diff(1) does)
  2  usage or I/O error, or a robot that cannot be built or does not pass mcar check
  130  interrupted (Ctrl-C); 143 terminated
"""

WORKING_TREE = "working tree"


@click.command("diff", help=HELP, short_help="Show what a change does to the robot.")
@click.argument("words", nargs=-1, metavar="OLD [NEW] [INPUT]... [NAME:=VALUE]...")
@click.option("--format", "fmt", type=click.Choice(["text", "markdown", "json"]),
              default="text", show_default=True,
              help="text for a terminal, markdown for a pull-request comment, json for scripts.")
@click.option("--tolerance", type=click.FloatRange(min=0.0), default=1e-9, show_default=True,
              help="Numbers closer than this (in m, rad, kg) are equal.")
@click.option("--picture", metavar="FILE.png", type=click.Path(dir_okay=False),
              help="Also draw OLD and NEW side by side, the changed links highlighted.")
@click.option("--renderer", type=click.Choice(RENDERERS), default="auto", show_default=True,
              envvar=RENDERER_ENV, show_envvar=True, help="For --picture: as for mcar render.")
@click.option("--specs", "with_specs", is_flag=True,
              help="Also compare the figures mcar specs computes (tip-over, footprint...).")
@robot_options
@handle_errors
def command(words, fmt, tolerance, picture, renderer, with_specs, package_paths, sets,
            config_files):
    if picture:
        _refuse_other_formats(picture)
    try:
        diffs, only_old, only_new = _compare(words, tolerance, package_paths, sets,
                                             config_files, picture, renderer, with_specs)
    except McarError as error:
        error.exit_code = EXIT_USAGE  # 1 means "the robots differ": any failure is 2
        raise
    if fmt == "json":
        from mobile_car.diff.report import as_json

        robots = []
        for d in diffs:
            robots.append(as_json(d))
            if d.specs is not None:
                from mobile_car.diff.specs import as_json as specs_json

                robots[-1]["specs"] = specs_json(d.specs)
        document = {"changed": bool(only_old or only_new or any(_changed(d) for d in diffs)),
                    "robots": robots, "removed_files": only_old, "added_files": only_new}
        streams.echo(json.dumps(document, indent=2))
    else:
        from mobile_car.diff import report

        write = report.markdown if fmt == "markdown" else report.text
        parts, listed = [], []  # config.xacro's changes are listed once, where first shown
        for d in diffs:
            key = [(c.field, c.old, c.new) for c in d.dimensions or ()] if d.changed else None
            parts.append(write(d, dimensions=key not in listed))
            if d.specs is not None:
                from mobile_car.diff import specs

                parts.append((specs.markdown if fmt == "markdown" else specs.text)(d.specs))
            if key:
                listed.append(key)
        parts += [f"robot file removed: {name}\n" for name in only_old]
        parts += [f"robot file added: {name}\n" for name in only_new]
        if fmt == "markdown":
            parts.insert(0, "## mcar diff\n")
        streams.echo(shown_lines("\n".join(parts)), nl=False)  # names: mobile_car.names
    if only_old or only_new or any(_changed(d) for d in diffs):
        sys.exit(EXIT_PROBLEMS)


def _changed(diff) -> bool:
    """The robot changed, or (with --specs) one of its figures did."""
    return diff.changed or (diff.specs is not None and diff.specs.changed)


def _refuse_other_formats(picture: str) -> None:
    suffix = Path(picture).suffix
    if suffix.lower() != ".png":
        shown = suffix or "a name without .png"
        raise UsageError(f"--picture {picture}: mcar diff draws PNG pictures, not {shown}; "
                         f"name it {Path(picture).with_suffix('.png')}")


def _compare(words, tolerance, package_paths, sets, config_files, picture=None,
             renderer="auto", with_specs=False):
    from mobile_car.diff import compare, describe
    from mobile_car.diff.revisions import is_revision
    from mobile_car.load.inputs import split_words
    from mobile_car.load.robot import LoadOptions, load_robot, refuse_unused_arguments
    from mobile_car.load.selection import Selection

    names, mappings = split_words(words)
    cwd = Path.cwd()
    revisions = []
    for name in names[:2]:
        if Path(name).exists() or not is_revision(name, cwd):
            break
        revisions.append(name)
    rest = names[len(revisions):]
    with contextlib.ExitStack() as stack:
        if revisions:
            old_side, new_side = _revision_sides(stack, revisions, rest, cwd, package_paths)
        else:
            old_side, new_side = _file_sides(rest, package_paths)
        inputs = [inp for inp, _ in [*new_side.values(), *old_side.values()]]
        refuse_unused_arguments(inputs, LoadOptions(mappings),
                                overriding=bool(sets or config_files))
        selection = Selection("files", inputs, output_root=cwd)
        pairs = [key for key in new_side if key in old_side]
        if picture and len(pairs) != 1:
            raise UsageError(f"--picture draws one robot, but {len(pairs)} robot files are "
                             "compared; name one robot file")
        probe = start_probe(stack, renderer) if picture else None
        diffs = []
        with prepared_load(selection, mappings, package_paths, sets, config_files) as options:
            dimension_args = options.overrides.mappings if options.overrides else {}
            stdin = stdin_for(selection)
            for key in pairs:
                loaded = [load_robot(inp, options, stdin) for inp, _ in (old_side[key],
                                                                          new_side[key])]
                facts = [describe(robot, label, dimension_args) for robot, (_, label)
                         in zip(loaded, (old_side[key], new_side[key]), strict=True)]
                diffs.append(compare(*facts, tolerance))
                if with_specs:
                    diffs[-1].specs = _specs_diff(loaded, facts, tolerance)
                if picture:
                    _draw(picture, loaded, diffs[-1], renderer, probe)
    only_old = [str(k) for k in old_side if k not in new_side]
    only_new = [str(k) for k in new_side if k not in old_side]
    return diffs, only_old, only_new


def _specs_diff(loaded, facts, tolerance):
    """Both robots' specs figures compared (mcar specs' computation, default options)."""
    from mobile_car.diff.specs import compare_specs, specs_sections

    old, new = (specs_sections(robot) for robot in loaded)
    return compare_specs(old, new, tolerance, facts[0].label, facts[1].label)



def _draw(picture: str, loaded, diff, renderer: str, probe) -> None:
    from mobile_car.atomic import atomic_write
    from mobile_car.diff.picture import diff_picture
    from mobile_car.load.outputs import refuse_overwriting

    for robot in loaded:
        refuse_overwriting(picture, [robot.input.path, *robot.deps])
    png, notes = diff_picture(*loaded, diff, renderer, probe)
    for note in notes:
        print_warning("mcar", note)
    atomic_write(picture, png)


def _file_sides(names, package_paths):
    from mobile_car.load.selection import select

    from .common import working_here

    if len(names) != 2:
        raise UsageError("give OLD and NEW: two robot files, or a git revision "
                         "(mcar diff HEAD~1)")
    sides = []
    for name in names:
        selection = select([name], working_here(package_paths))
        if len(selection.inputs) != 1:
            raise UsageError(f"{name} holds {len(selection.inputs)} robot files; OLD and NEW "
                             "are one robot each (with a git revision, a folder may hold many)")
        inp = selection.inputs[0]
        sides.append({"robot": (inp, inp.label)})
    return sides


def _revision_sides(stack, revisions, names, cwd, package_paths):
    """{path in the repository: (input, label)} for OLD and NEW, each from its own tree."""
    from mobile_car.diff.revisions import repository_top, revision_tree

    top = repository_top(cwd).resolve()
    inside = cwd.resolve().relative_to(top)
    trees = [(stack.enter_context(revision_tree(rev, cwd)), rev) for rev in revisions]
    if len(trees) == 1:
        trees.append((top, WORKING_TREE))
    for name in names:
        path = (cwd / name).resolve()
        if _looks_like_file(name, cwd) and path.is_relative_to(top) and not any(
                (root / path.relative_to(top)).exists() for root, _ in trees):
            raise InputError(f"no such file at {' nor at '.join(rev for _, rev in trees)}",
                             file=name)
    return [_side_inputs(root, rev, inside, top, names, cwd, package_paths)
            for root, rev in trees]


def _side_inputs(root: Path, rev: str, inside: Path, top: Path, names, cwd, package_paths):
    from mobile_car.load.inputs import STDIN, display_path
    from mobile_car.load.package import working_set
    from mobile_car.load.selection import select

    folder = root / inside

    def working():
        found = working_set(folder, package_paths)
        if found.kind == "bundled":
            raise UsageError(f"{display_path(cwd)} is in no package of the repository: "
                             "stand in one, or name its robot files")
        return found

    words = []
    for name in names:
        if name == STDIN:
            raise UsageError("- (stdin) has no git revision: give files of the repository")
        path = (cwd / name).resolve() if _looks_like_file(name, cwd) else None
        if path is None:
            words.append(name)  # a part name
            continue
        if not path.is_relative_to(top):
            raise UsageError(f"{name} is outside the git repository {top}")
        mirrored = root / path.relative_to(top)
        if mirrored.exists():  # absent on this side: an added or removed robot file
            words.append(str(mirrored))
    if names and not words:
        return {}
    selection = select(words, working)
    side = {}
    for inp in selection.inputs:
        key = inp.path.resolve().relative_to(root.resolve())
        label = display_path(inp.path) if rev == WORKING_TREE else f"{key}@{rev}"
        side[key] = (inp, label)
    return side


def _looks_like_file(name: str, cwd: Path) -> bool:
    """A path (in this tree or another side's), not a part name."""
    return (cwd / name).exists() or "/" in name or name.endswith(".xacro") or \
        is_urdf_name(name)
