"""``mcar render``: robot descriptions as PNG pictures, offscreen, for shells and CI."""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import click

from mobile_car.errors import EXIT_OK, UsageError, combine_exit_codes
from mobile_car.load.default_outputs import default_folder
from mobile_car.names import shown
from mobile_car.packages.bundled import PACKAGE_NAME
from mobile_car.render.options import (
    DEFAULT_BACKGROUND,
    FRAME_CHOICES,
    RENDERER_ENV,
    RENDERERS,
    VIEW_CHOICES,
    RenderOptions,
    check_pixels,
    parse_color,
    parse_size,
)

from . import signals, streams
from .common import (
    INPUT_HELP,
    handle_errors,
    input_basis,
    prepared_load,
    print_diagnostic,
    print_warning,
    report,
    robot_options,
    say_which_package,
    select_inputs,
    stdin_for,
)

HELP = f"""Draw robot descriptions as PNG pictures, with no display and no GPU.

\b
  mcar render                        every robot file of the package you
                                     stand in (else the bundled {PACKAGE_NAME})
                                     into its renders/, plus the contact sheet
                                     renders/index.png
  mcar render wheel chassis          only the files of those part folders
  mcar render DIR [-o OUTDIR]        every robot file of a folder
  mcar render FILE [-o OUT.png]      one .urdf or .xacro file (default:
                                     renders/NAME.png; -o - writes to stdout;
                                     -o DIR/ writes DIR/NAME.png)
  mcar build X.xacro | mcar render -   a URDF from stdin (renders/stdin.png)

Every robot is checked first, as by `mcar check`: one with errors, or with a missing
mesh in the geometry to draw, is reported with check's diagnostics (exit 1) and
nothing is drawn for it.

Pictures mirror the urdf/ tree: urdf/wheel/test_wheel.urdf.xacro ->
renders/wheel/test_wheel.png. A picture whose inputs (URDF, meshes, options) have not
changed since it was drawn is not drawn again (--force draws it anyway); the record is
renders/.mcar-render.json.

Views are orthographic, in ROS axes (x forward, y left, z up): iso (front-left-above,
like rviz), front (from +x), side (from -y), top (x right, y up); all = the four in
a 2x2 picture. The camera fits the model; a ground grid (spacing printed in the
corner) and an x/y/z triad (red/green/blue) show scale and orientation. URDF material
colours are used; COLLADA meshes keep their own; meshes (package://, file://,
relative paths) are found as by mcar build.

--set NAME=VALUE and --config FILE.yaml change the robot's dimensions as for mcar build
(see `mcar config`); they are validated before anything is drawn.

Renderer: OpenGL through EGL (Mesa's llvmpipe on machines with no GPU; Debian packages
libegl1 libegl-mesa0 libgl1-mesa-dri libgl1). With --renderer auto, if no OpenGL context
can be made within a few seconds, pictures are ray-cast with trimesh + embreex instead
(same camera and lighting).

{INPUT_HELP}

\b
Exit codes:
  0  every picture was drawn (or was up to date)
  1  a robot has problems: check's errors, a missing mesh; nothing drawn for it
  2  usage, I/O or environment error: bad option, missing file, a macro file given as
     a robot, no renderer can run (the message names what to install)
  130  interrupted (Ctrl-C); 143 terminated
"""


def _size(ctx, param, value):
    try:
        return parse_size(value)
    except UsageError as error:
        raise click.BadParameter(error.message.split(" ", 1)[1]) from None


def _color(ctx, param, value):
    if value is None:
        return DEFAULT_BACKGROUND
    try:
        return parse_color(value)
    except UsageError as error:
        raise click.BadParameter(error.message.split(" ", 1)[1]) from None


def _joints(ctx, param, value):
    if not value:
        return ()
    from mobile_car.render.pose import parse_joint_word

    try:
        return tuple(parse_joint_word(word) for word in value)
    except UsageError as error:
        raise click.BadParameter(error.message.removeprefix("--joint ")) from None


def _progress(jobs, quiet: bool):
    """A progress bar on stderr, only on a terminal and not with --quiet."""
    stream = sys.stderr
    if quiet or len(jobs) < 2 or not stream.isatty():
        return None
    return click.progressbar(length=len(jobs), label="rendering", file=stream,
                             show_pos=True, item_show_func=lambda name: name)


@click.command("render", help=HELP, short_help="Draw robot descriptions as PNG pictures.")
@click.argument("words", nargs=-1, metavar="[INPUT]... [NAME:=VALUE]...")
@click.option("-o", "--output", metavar="OUT",
              help="Output PNG (one FILE; '-' for stdout) or folder (default: renders/, refused "
                   "if it is a link leading out of the package or working folder).")
@click.option("--view", type=click.Choice(VIEW_CHOICES), default="iso", show_default=True,
              help="Camera direction; 'all' draws the four views in a 2x2 picture.")
@click.option("--size", "size", default="800x600", show_default=True, callback=_size,
              metavar="WxH", help="Picture size in pixels.")
@click.option("--collision", is_flag=True,
              help="Draw the <collision> geometry instead of the <visual> geometry.")
@click.option("--background", default=None, callback=_color, metavar="COLOR",
              help="Background colour: a name or #rrggbb (default: light slate grey).")
@click.option("--grid/--no-grid", default=True, show_default=True,
              help="Draw a ground grid under the model.")
@click.option("--axes/--no-axes", default=True, show_default=True,
              help="Draw the x/y/z axis triad in the corner.")
@click.option("--renderer", type=click.Choice(RENDERERS), default="auto", show_default=True,
              envvar=RENDERER_ENV, show_envvar=True,
              help="OpenGL (gl), ray casting (raycast), or gl with raycast as fallback (auto).")
@click.option("--joint", "joints", multiple=True, metavar="NAME=VALUE", callback=_joints,
              help="Draw a joint turned or shifted: radians or metres, or with a unit "
                   "(--joint shoulder=30deg, --joint lift=5cm); within the joint's limits. "
                   "Repeatable; other joints stay at zero. One robot file only.")
@click.option("--frames", type=click.Choice(FRAME_CHOICES), default="auto", show_default=True,
              help="Link frames drawn as RViz's TF display draws them (red/green/blue x/y/z "
                   "axes and the link's name): auto (every link, when the robot has no "
                   "geometry to draw, like the tutorial's skeleton), bare (links without "
                   "geometry), all, none.")
@click.option("--force", is_flag=True, help="Draw every picture, even if unchanged.")
@click.option("-q", "--quiet", is_flag=True, help="Print only errors and warnings.")
@robot_options
@handle_errors
def command(words, output, view, size, collision, background, grid, axes, renderer, joints,
            frames, force, quiet, package_paths, sets, config_files):
    started = time.perf_counter()
    options = RenderOptions(view=view, width=size[0], height=size[1], collision=collision,
                            background=background, grid=grid, axes=axes, joints=joints,
                            frames=frames)
    check_pixels(*size, renderer)
    selection, mappings = select_inputs(words, package_paths, sets, config_files)
    if joints and len(selection.inputs) != 1:
        raise UsageError(f"--joint poses one robot, and there are {len(selection.inputs)} "
                         "robot files to draw: name one INPUT file")
    jobs, outdir, sheet = _plan(selection, output)
    basis = input_basis(mappings, package_paths, sets, config_files)
    for job in jobs:
        job.basis = basis
    if not force and outdir is not None and _nothing_changed(selection, jobs, outdir, sheet,
                                                             options, renderer):
        if not quiet:
            _summary(None, _Outcome(counts={"rendered": 0, "unchanged": len(jobs),
                                            "failed": 0}),
                     len(jobs), outdir, sheet, time.perf_counter() - started)
        sys.exit(EXIT_OK)
    with prepared_load(selection, mappings, package_paths, sets, config_files) as load:
        load = load.replace(size_limited=True)
        if len(jobs) == 1 and not sheet:
            from mobile_car.render.jobs import check_first

            failed = check_first(jobs[0], load, collision, stdin_for(selection))
            if failed is not None:  # nothing to draw: no drawing process, no trimesh
                outcome = _run([failed], [], jobs, quiet)
                if not quiet:
                    _summary(None, outcome, 1, outdir, sheet, time.perf_counter() - started)
                sys.exit(outcome.exit_code)
        # Start the drawing process now (OpenGL, or the ray caster), while numpy, trimesh
        # and xacro load here.
        from mobile_car.held_signals import hold_signals, release_signals
        from mobile_car.render.backend import start_probe

        probe = start_probe(renderer)
        try:
            # Held over the imports: trimesh imports manifold3d, a nanobind module whose
            # start aborts the process (SIGABRT, a C++ traceback) when Ctrl-C lands in it.
            held = hold_signals()
            try:
                from mobile_car.render.manifest import Manifest
                from mobile_car.render.session import RenderSession
            finally:
                release_signals(held)  # a signal that came meanwhile unwinds from here
            signals.raise_if_received()  # trimesh's import guards swallow Ctrl-C and SIGTERM
        except BaseException:  # the probe child must not outlive the command
            probe.cancel()
            raise
        with RenderSession(options, renderer=renderer, load=load, force=force, probe=probe,
                           stdin=stdin_for(selection)) as session:
            # (closing the session stops the drawing process's probe if it was not needed)
            manifest = Manifest(outdir) if outdir is not None else None
            outcome = _run(session.run(jobs, manifest), session.notes, jobs, quiet)
            if output == "-" and outcome.last_png is not None:
                streams.write(outcome.last_png)
            if sheet:
                if selection.kind in ("package", "folder"):
                    manifest.forget_orphans({manifest.key(job.target) for job in jobs})
                session.write_contact_sheet(manifest)
            if not quiet:
                _summary(session, outcome, len(jobs), outdir, sheet,
                         time.perf_counter() - started)
    sys.exit(outcome.exit_code)


def _nothing_changed(selection, jobs, outdir: Path, sheet: bool, options, renderer) -> bool:
    """True, after showing the warnings the pictures were drawn with, if every picture
    and the contact sheet are current by the stamps of the files they were made from:
    the whole run, decided without loading a robot or importing xacro, numpy or GL."""
    from mobile_car.freshness import diagnostics_from
    from mobile_car.render.manifest import Manifest, picture_key

    manifest = Manifest(outdir)
    if not manifest.entries:
        return False
    entries = []
    for job in jobs:
        if job.input.path is None or job.target is None:
            return False
        entry = manifest.fresh(job.target, picture_key(job.basis, options), renderer)
        if entry is None:
            return False
        entries.append(entry)
    if sheet:
        listed = {manifest.key(job.target) for job in jobs}
        if selection.kind in ("package", "folder") and manifest.orphans(listed):
            return False  # pictures of robots since removed: the sheet changes
        if not manifest.sheet_is_current():
            return False
    manifest.save()  # stamps brought up to date (a file touched, its bytes the same)
    say_which_package(selection)
    for entry in entries:
        for diagnostic in diagnostics_from(entry.get("warnings") or []):
            print_diagnostic(diagnostic)
    return True


def _plan(selection, output: str | None):
    """The jobs, the output folder (None for stdout) and whether to make a contact sheet;
    no picture may be written over an input, nor two inputs to one picture."""
    jobs, outdir, sheet = _jobs(selection, output)
    from mobile_car.load.outputs import refuse_clashes, refuse_overwriting_each

    pictures = [(job.target, job.input.path) for job in jobs if job.target is not None]
    refuse_clashes(pictures)
    refuse_overwriting_each([target for target, _source in pictures],
                            [inp.path for inp in selection.inputs])
    if output and len(jobs) == 1 and jobs[0].target == Path(output):
        _refuse_other_formats(output)  # (after: overwriting an input is the worse mistake)
    return jobs, outdir, sheet


def _jobs(selection, output: str | None):
    from mobile_car.load.outputs import names_folder
    from mobile_car.render.jobs import file_job, selection_jobs

    inputs = selection.inputs
    names_file = bool(output) and output != "-" and not names_folder(output) and (
        Path(output).suffix != "" and not Path(output).is_dir())
    if names_file:
        if len(inputs) > 1:
            raise UsageError(f"-o {output} is one picture, but there are {len(inputs)} robot "
                             "files to draw; name one INPUT file, or give -o a folder")
    if names_file:  # (a folder or part with one robot file, too)
        return [file_job(inputs[0], Path(output))], Path(output).parent, False
    if selection.kind == "files":
        if output == "-" and len(inputs) != 1:
            raise UsageError("-o - (stdout) works with one INPUT only")
        if len(inputs) == 1 and output and (output == "-" or not (
                names_folder(output) or Path(output).is_dir())):
            target = None if output == "-" else Path(output)
            return [file_job(inputs[0], target)], None if target is None else target.parent, False
        outdir = Path(output) if output else default_folder(selection.output_root,
                                                            "renders", "-o")
        jobs = selection_jobs(selection, outdir)
        names = [job.target.name for job in jobs]
        clashes = sorted({name for name in names if names.count(name) > 1})
        if clashes:
            raise UsageError(f"several inputs would all be drawn to {', '.join(clashes)}; "
                             "render them one at a time with -o")
        return jobs, outdir, False
    if output == "-":
        raise UsageError("-o - (stdout) works with one INPUT only")
    outdir = Path(output) if output else default_folder(selection.output_root, "renders",
                                                        "-o")
    return selection_jobs(selection, outdir), outdir, True


def _refuse_other_formats(output: str) -> None:
    """mcar render writes PNG: a picture named .jpg, .svg, ... would hold PNG bytes."""
    suffix = Path(output).suffix
    if suffix and suffix.lower() != ".png":  # (no suffix: /dev/null, /dev/stdout, a pipe)
        png = Path(output).with_suffix(".png")
        raise UsageError(f"-o {output}: mcar render writes PNG pictures, not {suffix}; "
                         f"name it {png}, or end a folder's name with /")


@dataclass
class _Outcome:
    exit_code: int = EXIT_OK
    counts: dict = field(default_factory=lambda: {"rendered": 0, "unchanged": 0, "failed": 0})
    last_png: bytes | None = None


def _run(results, notes: list, jobs, quiet: bool) -> _Outcome:
    """Print each job's result as it comes (errors, warnings, and the renderer's notes,
    which ``notes`` gathers meanwhile); the counts and exit code."""
    outcome = _Outcome()
    bar = _progress(jobs, quiet)
    if bar is not None:
        bar.__enter__()
    try:
        for result in results:
            signals.raise_if_received()  # swallowed by a library's import guard: stop here
            outcome.counts[result.status] += 1
            if bar is not None:
                bar.update(1, shown(result.job.caption))
            for note in notes:
                print_warning("mcar", note)
            notes.clear()
            for warning in result.warnings:
                if isinstance(warning, str):
                    print_warning(result.job.input.label, warning)
                else:
                    print_diagnostic(warning)
            if result.error is not None:
                if bar is not None:
                    click.echo("", err=True)
                report(result.error)
                outcome.exit_code = combine_exit_codes([outcome.exit_code,
                                                        result.error.exit_code])
            if result.png is not None:
                outcome.last_png = result.png
    finally:
        if bar is not None:
            bar.__exit__(None, None, None)
    return outcome


def _summary(session, outcome: _Outcome, total: int, outdir, sheet: bool,
             seconds: float) -> None:
    from mobile_car.load.inputs import display_path

    counts = outcome.counts
    where = f" in {display_path(outdir)}" if outdir is not None else ""
    parts = [f"{counts['rendered']} rendered"]
    if counts["unchanged"]:
        parts.append(f"{counts['unchanged']} unchanged")
    if counts["failed"]:
        parts.append(f"{counts['failed']} failed")
    line = f"{total} picture{'s' if total != 1 else ''}{where}: {', '.join(parts)}"
    if sheet:
        line += f" + {display_path(Path(outdir) / 'index.png')}"
    line += f" ({seconds:.2f} s"
    if session is not None and session.renderer_description:
        line += f", {session.renderer_description}"
    click.echo(line + ")", err=True)
