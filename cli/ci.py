"""``mcar ci``: build, check, simulate and render every robot file of a package, for CI."""

from __future__ import annotations

import sys
import time
from pathlib import Path

import click

from mobile_car.check import replay
from mobile_car.errors import UsageError
from mobile_car.load.default_outputs import default_folder
from mobile_car.load.inputs import display_path
from mobile_car.names import shown
from mobile_car.packages.bundled import PACKAGE_NAME

from .ci_report import emit
from .common import (
    INPUT_HELP,
    handle_errors,
    input_basis,
    prepared_load,
    print_warning,
    robot_options,
    say_which_package,
    select_inputs,
)

HELP = f"""Build, check, simulate and render every robot file of a description package.

\b
  mcar ci                               the package you stand in (else the
                                        bundled {PACKAGE_NAME})
  mcar ci path/to/other_description     another team's package
  mcar ci --format junit > report.xml   JUnit XML for the CI server
  mcar ci --format github               annotations on the pull request's lines

Every robot file (parts, steps, complete robots: what `mcar build` finds, see
docs/discovery.md; -v lists the files skipped as not robots, with why) is built
into --build-dir, checked as by `mcar check` (an error fails it; a warning too with
--strict, or where the package's mcar.yaml says `ci: strict: true`, as the bundled
package and those `mcar init` makes do; warnings are shown either way), simulated
as by `mcar sim` (drop, drive, spin; --no-sim skips it) and drawn into --render-dir,
mirroring urdf/; each variant urdf/variants/NAME.yaml is applied to
the top-level robot files (built into build/variants/NAME/...). A failed build or check
skips that file's later steps; the other files go on. A summary table ends the run.

Where the Gazebo helper is installed (make gazebo-helper), a robot with a <gazebo>
block is also given to libsdformat, as `mcar check --gazebo` does: with -v, one line
says what Gazebo simulates (links, lumped, mass, libsdformat's version); a link it
drops is an error, a <gazebo>
reference or plugin joint left pointing at nothing a warning (--no-gazebo: not).

Only vehicles are simulated: robots with wheels (two or more continuous joints, or
revolute ones limited to ±1e6 rad or more, about a level axis and moving collision
geometry down to the floor at rest: levers high up an arm are none) and another link
with collision geometry to stand on (a castor, a body), each with its drive kind's
scenarios. Any other robot file (a part's test file, the tutorial) is reported "not
simulated, not a vehicle", one line per kind, which does not fail the run. A vehicle sim
cannot drive (mecanum wheels, wheels on one side) fails it, saying why, unless the
package's mcar.yaml opts it out with a reason that ci prints:

\b
  sim:
    skip:
      "urdf/mecanum_base.urdf.xacro": "mecanum rollers, tested on the real robot"

Where the package's mcar.yaml has an export section, each robot it names is also
exported to each format, verified, as `mcar export --to FORMAT --verify` does, into
BUILD/exports/ROBOT/FORMAT/ (docs/exports.md):

\b
  export:
    formats: [mjcf, urdf]
    robots: ["urdf/mobile_robot.xacro"]

Exit 0 only if every step of every file passed; 1 if any file has problems; 2 if the
run could not be made (no package, no renderer: --no-render skips drawing).

--against REV compares each robot file with the same file at the git revision REV, as
`mcar diff REV FILE` does: the JUnit report gets a property mcar.diff on each of its
testcases ("3 changes", "no change", "added since REV"), --diff-report FILE.md gets the
markdown report (for a pull request's job summary). A change is not a failure: the exit
code is the build's, check's and render's.

{INPUT_HELP}

\b
Exit codes:
  0  every step of every file passed
  1  problems found: a build error, a check error (a warning too when strict), a
     failed sim scenario or sim rule, a link Gazebo drops, a robot not drawn
  2  usage, I/O or environment error: no such package, a macro file given as a robot,
     no renderer (--no-render skips drawing)
  130  interrupted (Ctrl-C); 143 terminated
"""


@click.command("ci", help=HELP, short_help="Build, check, simulate and render a package.")
@click.argument("words", nargs=-1, metavar="[INPUT]... [NAME:=VALUE]...")
@click.option("--format", "output_format", type=click.Choice(["text", "junit", "github"]),
              default="text", show_default=True,
              help="text: the summary table on stdout, problems on stderr; junit: JUnit XML "
                   "on stdout; github: workflow annotations, then the table.")
@click.option("--build-dir", type=click.Path(),
              help="Where the URDFs are written (default: build/ under the package's root; "
                   "refused if it is a link leading out of the package).")
@click.option("--render-dir", type=click.Path(),
              help="Where the PNGs and the contact sheet index.png are written (default: "
                   "renders/ under the package's root; refused if it is a link leading out of the "
                   "package).")
@click.option("--no-render", is_flag=True, help="Draw nothing.")
@click.option("--no-sim", is_flag=True, help="Simulate nothing.")
@click.option("--no-gazebo", is_flag=True,
              help="Do not ask libsdformat what Gazebo makes of the robots (done by default "
                   "where the Gazebo helper is installed).")
@click.option("--strict/--no-strict", default=None,
              help="--strict: a warning fails its file too, as `mcar check --strict`; "
                   "--no-strict: only errors do. Default: what the package's mcar.yaml says "
                   "(ci: strict: true, as mcar init and the bundled package say), else only "
                   "errors fail.")
@click.option("--renderer", type=click.Choice(["auto", "gl", "raycast"]), default="auto",
              show_default=True, help="As for mcar render.")
@click.option("--junit-xml", metavar="FILE", type=click.Path(dir_okay=False),
              help="Also write the JUnit XML report to FILE (whatever --format is).")
@click.option("--against", metavar="REV",
              help="Compare every robot file with the same file at this git revision.")
@click.option("--diff-report", metavar="FILE.md", type=click.Path(dir_okay=False),
              help="With --against: write the comparison as markdown to FILE.md.")
@click.option("-q", "--quiet", is_flag=True, help="text format: print only problems.")
@click.option("-v", "--verbose", is_flag=True,
              help="Also list the files found beside the robots that are not robots, one "
                   "line each with why (macro files, included files, fragments, ...), and "
                   "what Gazebo simulates of each robot (one line each).")
@robot_options
@handle_errors
def command(words, output_format, build_dir, render_dir, no_render, no_sim, no_gazebo, strict,
            renderer, junit_xml, against, diff_report, quiet, verbose, sets, config_files,
            package_paths):
    from mobile_car.ci import pipeline
    from mobile_car.ci.cache import CiCache
    from mobile_car.freshness import Basis

    started = time.perf_counter()
    # A .urdf is "built" as it is: only xacro files are expanded, as check sees them.
    selection, mappings = select_inputs(words, package_paths, sets, config_files)
    # Not named: build/ and renders/ of the output root, kept inside it (default_outputs)
    build_dir = Path(build_dir) if build_dir else \
        default_folder(selection.output_root, "build", "--build-dir")
    render_dir = Path(render_dir) if render_dir else \
        default_folder(selection.output_root, "renders", "--render-dir")
    if diff_report and not against:
        raise UsageError("--diff-report FILE needs --against REV (the revision to compare with)")
    for report_file in (junit_xml, diff_report):
        if report_file:  # the inputs now, the files they include once they are read
            from mobile_car.load.outputs import refuse_overwriting

            refuse_overwriting(report_file, [inp.path for inp in selection.inputs])
    helper = None if no_gazebo else _gazebo_helper()
    items = pipeline.plan(selection, build_dir, None if no_render else render_dir,
                          gazebo=helper is not None)
    from mobile_car.ci import simulation

    configs = simulation.package_configs(items, selection.root)
    from mobile_car.ci.exports import export_step, formats_for

    for item in items:  # mcar.yaml's export: folders made on every run (never replayed)
        item.exports = formats_for(item, configs)
        item.strict = simulation.strictness(item, configs, strict)
    revision = None
    if against:  # a wrong REV is a usage error before anything is built
        from mobile_car.ci.against import resolve_revision

        revision = resolve_revision(against, items[0].source.parent)
    # Items whose inputs, outputs and picture are unchanged are replayed from the record.
    # What decides the pictures: the same as for mcar render, so that each command's
    # pictures are current for the other. The record's basis adds what decides the sim.
    pictures = basis = input_basis(mappings, package_paths, sets, config_files)
    for home, config in configs.items():  # an mcar.yaml made, edited or gone: sim again
        name = f"package config {home}"
        basis = (basis.with_file(config.path, name) if config.path is not None else
                 Basis({**basis.settings, name: None}, basis.files))
    cache = CiCache(build_dir, helper)
    built = _BuiltFiles(build_dir, pictures)
    manifest = None
    if not no_render:
        from mobile_car.render.manifest import Manifest

        manifest = Manifest(render_dir)
    fresh = _picture_fresh(manifest, pictures, renderer)
    todo = [item for item in items
            if item.exports or not cache.replay(item, basis, item.strict, fresh,
                                                sim=not no_sim)]
    checked = []
    compared = []
    try:
        if todo or revision is not None:
            with prepared_load(selection, mappings, package_paths, sets,
                               config_files) as options:
                for item in todo:
                    passed = pipeline.build_and_check(item, options, item.strict)
                    built.note(item)
                    if item.variant is None and item.check_result is not None:
                        # what `mcar check` of the same file would find: its record too
                        found = _package_yaml(item.check_result)
                        replay.record(item.input, pictures, item.check_result, cache.stamper,
                                      also=found.read, compared=not found,
                                      absent=found.absent)
                    if passed:
                        checked.append(item)
                        if helper is not None:
                            pipeline.gazebo_step(item, item.strict)
                        if not no_sim:
                            simulation.sim_step(item, simulation.skip_reason(item, configs),
                                                simulation.drive_setting(item, configs))
                        if item.exports:
                            export_step(item, build_dir)
                    cache.record(item, basis, item.strict)
                if revision is not None:
                    from mobile_car.ci.against import diff_items

                    compared = diff_items(items, revision, options)
        else:
            say_which_package(selection)
    finally:
        cache.save()
        built.record.save()
    if manifest is not None and selection.kind in ("package", "folder"):
        # pictures of robot files since deleted leave the contact sheet (render's are kept)
        manifest.forget_orphans({manifest.key(item.png) for item in items if item.png})
    # a robot whose sim failed is drawn too: its picture is what shows why
    if manifest is not None and (checked or any(item.ok for item in items)):
        _render(checked, items, manifest, renderer, pictures)
    code = pipeline.exit_code(items)
    if junit_xml:
        from mobile_car.atomic import atomic_write
        from mobile_car.ci.junit import junit_report
        from mobile_car.load.outputs import refuse_overwriting

        read = [item.source for item in items] + [
            dep for item in items if item.ok or item.checked is not None for dep in item.deps]
        refuse_overwriting(junit_xml, read)

        atomic_write(junit_xml, junit_report(items))
    if diff_report:
        _write_diff_report(diff_report, compared, revision, items)
    skipped = pipeline.not_robots(selection)
    if verbose:
        for file in skipped:
            click.echo(f"mcar: skipped {display_path(file.path)}: {shown(file.reason)}",
                       err=True)
    emit(items, output_format, quiet, time.perf_counter() - started, no_render, no_sim,
          helper is not None, 0 if verbose else len(skipped), verbose)
    if revision is not None:
        changed = sum(1 for entry in compared if entry.diff is not None and entry.diff.changed
                      or entry.summary.startswith("added"))
        click.echo(f"mcar ci: against {revision.name}: {changed} of {len(compared)} robot "
                   "files changed", err=True)
    sys.exit(code)


def _package_yaml(result):
    """The package's controller and Nav2 YAML (specs.stack_check.Found): ci's check does
    not compare it with the robot (W510-W513 are `mcar check`'s), so a record of a robot
    that has some is not one `mcar check` may read back."""
    from mobile_car.specs.stack_check import Found, find_package_yaml

    return Found() if result.loaded is None else find_package_yaml(result.loaded)


def _gazebo_helper():
    """The Gazebo helper, or None where it is not installed; one named by MCAR_SDFORMAT
    that is not there is an error (exit 2), as for mcar check --gazebo."""
    import os

    from mobile_car.errors import GazeboUnavailable
    from mobile_car.gazebo.helper import HELPER_ENV, find_helper

    try:
        return find_helper()
    except GazeboUnavailable:
        if os.environ.get(HELPER_ENV, "").strip():
            raise
        return None


def _write_diff_report(path: str, compared, revision, items) -> None:
    from mobile_car.atomic import atomic_write
    from mobile_car.ci.against import markdown_report
    from mobile_car.load.outputs import refuse_overwriting

    refuse_overwriting(path, [item.source for item in items]
                       + [dep for item in items for dep in item.deps])
    atomic_write(path, markdown_report(compared, revision))


class _BuiltFiles:
    """The build folder's record (mobile_car.load.build_record), which ci keeps as `mcar
    build` does, so that a build after ci (and ci after a build) finds its files current."""

    def __init__(self, build_dir, basis):
        from mobile_car.load.build_record import BuildRecord

        self.record, self.basis = BuildRecord(build_dir), basis

    def note(self, item) -> None:
        from mobile_car.ci.cache import item_basis
        from mobile_car.load.build_record import build_key

        if not any(step.name == "build" and step.status == "passed" for step in item.steps):
            return
        basis = item_basis(item, self.basis)
        self.record.record(item.urdf, build_key("urdf", basis.settings),
                           [*item.deps, *basis.files], item.expansion_warnings,
                           item.generated)


def _picture_fresh(manifest, basis, renderer: str):
    """Whether an item's picture is current by its stamps (nothing loaded)."""
    def fresh(item) -> bool:
        from mobile_car.ci.cache import item_basis
        from mobile_car.render.manifest import picture_key
        from mobile_car.render.options import RenderOptions

        if manifest is None:
            return True
        key = picture_key(item_basis(item, basis), RenderOptions())
        return manifest.fresh(item.png, key, renderer) is not None

    return fresh


def _render(checked, items, manifest, renderer: str, basis) -> None:
    """Draw the robots that passed their check, as they were loaded and checked, and the
    contact sheet; a run whose pictures are all current imports none of the drawing code."""
    if not checked and manifest.sheet_is_current():
        manifest.save()
        return
    from mobile_car.ci import pipeline
    from mobile_car.ci.cache import item_basis
    from mobile_car.held_signals import import_held
    from mobile_car.render.options import RenderOptions

    # Held: trimesh's import (through yourdfpy) aborts the process if a signal lands in it.
    session_module = import_held("mobile_car.render.session")
    with session_module.RenderSession(RenderOptions(), renderer=renderer) as session:
        try:
            for item in checked:
                pipeline.render_step(item, session, manifest, item_basis(item, basis))
        finally:
            manifest.save()
        if checked or any(item.ok for item in items):
            session.write_contact_sheet(manifest)
            manifest.save()
        for note in session.notes:
            print_warning("mcar", note)
