"""``mcar sweep``: explore the robot's dimensions: every variant validated, built, checked
and simulated, on this machine's cores or a Dask cluster."""

from __future__ import annotations

import click

from mobile_car.errors import UsageError

from . import streams
from .common import INPUT_HELP, handle_errors, load_inputs, robot_options
from .sim import scenario_list

HELP = f"""Sweep the robot's dimensions: every combination validated by the config
checks, then built, checked (--strict) and simulated (drop, drive, spin); one row per
point in a Parquet or CSV file, and a plot of where the dimensions work.

\b
  mcar sweep --vary wheel_radius=25mm..45mm:9 --vary track_width=0.15..0.17:5
  mcar sweep --vary wheel_radius=25mm,35mm,45mm --set wheel_mass=60g
  mcar sweep --vary track_width=0.15..0.17 --samples 200 --seed 7
  mcar sweep ... -o results.csv --plot results.png --colour yaw_rate_rad_s
  mcar sweep ... --scheduler tcp://10.0.0.5:8786        on a Dask cluster
  mcar sweep ... --resume                               finish an interrupted sweep

\b
--vary NAME=LO..HI:N  N values from LO to HI, both included (a grid: every
                      combination of the --vary values, the first changing slowest)
--vary NAME=A,B,C     those values
--vary NAME=LO..HI    with --samples N: uniform between LO and HI
Values are read as --set reads them (25mm, 0.14, 90deg). A point outside a dimension's
range, or one config.xacro's checks refuse, is a row too (status "rejected", with the
constraint that refused it): a sweep shows where the constraints bite.

\b
Each row: the point's values (SI), valid, constraint, status (ok, rejected, check
failed, sim failed, error, crashed), reason, check_errors, check_warnings,
failed_scenarios, the figures mass_kg, rest_height_m, height_error_m, tilt_deg,
speed_ratio (distance / r·ω·t), speed_m_s, lateral_drift_m, heading_change_deg,
yaw_ratio (yaw rate / 2·r·ω/track), yaw_rate_rad_s, centre_moved_m, the times
validate_s, build_s, check_s, sim_s, total_s, attempts and worker.

--specs KEY,...  adds figures of mcar specs as columns (statics.tip.left, body.mass...:
one number each), computed once the point's check passed; a point that cannot compute
one has an empty cell, and its specs_notes column says why. --colour takes their keys.

The points run on --jobs local processes (default: every core), or on the workers of
the Dask scheduler --scheduler names (each worker needs this mcar, with the sweep
extra, and the package at the same path; docs/sweep.md says how to start them). The
results file is saved with the first point, then every few seconds: Ctrl-C keeps the
finished rows, and --resume runs only the points it lacks. A point whose worker dies is
retried once, alone, then reported as "crashed".

A sweep varies one robot: the file named, or the one robot file directly in the
package's urdf/ folder.

{INPUT_HELP}

\b
Exit codes:
  0  every point evaluated (rejected points and failed checks or scenarios are results)
  1  a point could not be evaluated (an error building it, a worker that died twice)
  2  usage, I/O or environment error: bad --vary, unknown dimension, unreachable
     scheduler, workers without mcar, a results file that is not this sweep's
  130  interrupted (Ctrl-C); 143 terminated
"""


def _positive(ctx, param, value):
    if value is not None and value < 1:
        raise click.BadParameter("must be 1 or more")
    return value


@click.command("sweep", help=HELP, short_help="Sweep dimensions: build, check, simulate each.")
@click.argument("words", nargs=-1, metavar="[INPUT] [NAME:=VALUE]...")
@click.option("--vary", "varies", multiple=True, metavar="NAME=LO..HI:N",
              help="A dimension and its values; repeatable (see above).")
@click.option("--samples", type=int, callback=_positive, metavar="N",
              help="N random points instead of the grid.")
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of --samples.")
@click.option("--scenario", "scenarios", default="drop,drive,spin", show_default=True,
              callback=scenario_list, metavar="LIST", help="Scenarios to run, comma-separated.")
@click.option("--jobs", type=int, callback=_positive, metavar="N",
              help="Local worker processes  [default: every core]")
@click.option("--scheduler", metavar="tcp://HOST:PORT",
              help="Run the points on this Dask scheduler's workers.")
@click.option("-o", "--output", default="sweep.parquet", show_default=True,
              metavar="FILE", help="Results: .parquet or .csv (- for CSV on stdout).")
@click.option("--resume", is_flag=True,
              help="Keep the rows of an earlier run of this sweep in --output; run the rest.")
@click.option("--plot", metavar="FILE.png", help="Draw the points over two dimensions.")
@click.option("--plot-x", metavar="NAME", help="The plot's x axis  [default: the first --vary]")
@click.option("--plot-y", metavar="NAME", help="The plot's y axis  [default: the second --vary]")
@click.option("--colour", "colour", default="speed_m_s", show_default=True, metavar="FIGURE",
              help="The figure that colours the valid points.")
@click.option("--specs", "specs", metavar="KEY,...",
              help="mcar specs figures to add as columns (e.g. statics.tip.left,body.mass).")
@click.option("--left", metavar="JOINT", help="The left drive wheel's joint.")
@click.option("--right", metavar="JOINT", help="The right drive wheel's joint.")
@robot_options
@handle_errors
def command(words, varies, samples, seed, scenarios, jobs, scheduler, output, resume, plot,
            plot_x, plot_y, colour, specs, left, right, package_paths, sets, config_files):
    from mobile_car import extras
    from mobile_car.sweep.results import results_format
    from mobile_car.sweep.specs import parse_keys

    specs = parse_keys(specs)

    # The results table needs pandas (and pyarrow for Parquet); Dask and the plot only
    # when asked for.
    extras.require("mcar sweep", "sweep", ("pandas", "pyarrow")
                   + (("distributed",) if scheduler is not None else ())
                   + (("matplotlib",) if plot is not None else ()))
    if scheduler is not None:  # before anything is loaded, and before Dask connects
        from mobile_car.sweep.execute import check_scheduler_address

        check_scheduler_address(scheduler)
    if jobs and scheduler:
        raise UsageError("--jobs and --scheduler exclude each other: the scheduler's "
                         "workers set the parallelism")
    if bool(left) != bool(right):
        raise UsageError("--left and --right go together: name both drive joints")
    if resume and output == "-":
        raise UsageError("--resume reads the results file: give -o FILE, not -")
    if plot is not None and not plot.lower().endswith(".png"):
        raise UsageError(f"--plot {plot}: the plot is written as a .png")
    results_format(output)
    with load_inputs(words, package_paths, sets, config_files) as (selection, options):
        session = _session(selection, options, varies, samples, seed, scenarios, left,
                           right, output, specs)
    axes = _plot_axes(session, plot_x, plot_y, colour) if plot else None
    from pathlib import Path

    todo = session.points
    if resume:
        if Path(output).exists():
            todo = session.resume()
        else:
            click.echo(f"mcar: {output} does not exist yet: starting the sweep", err=True)
    workers = _run(session, todo, jobs, scheduler)
    table = session.table()  # built once, for the results and the plot
    if output == "-":
        from mobile_car.sweep.results import encode

        streams.write(encode(table, ".csv"))
    else:
        session.save(table)
    if plot:
        from mobile_car.sweep.plot import plot_sweep

        plot_sweep(table, axes[0], axes[1], colour, session.units, plot)
    for line in session.summary(workers):
        click.echo(line, err=True)
    where = "stdout" if output == "-" else output
    click.echo(f"mcar sweep: results in {where}" + (f", plot in {plot}" if plot else ""),
               err=True)
    raise SystemExit(session.exit_code())


def _session(selection, options, varies, samples, seed, scenarios, left, right, output,
             specs=()):
    from pathlib import Path

    from mobile_car.config.spec import config_file, load_spec
    from mobile_car.expand.sandbox import is_trusted
    from mobile_car.packages.asset_roots import chosen_asset_paths
    from mobile_car.packages.search import PackageSearch
    from mobile_car.sweep.plan import grid, read_axes
    from mobile_car.sweep.plan import samples as sample_points
    from mobile_car.sweep.point import SweepJob
    from mobile_car.sweep.session import Session, swept_robot

    robot = swept_robot(selection)
    path = robot.path.resolve()
    search = PackageSearch(package_paths=list(options.package_paths), origin=path)
    spec = load_spec(config_file(search))
    axes = read_axes(spec, varies, sampling=samples is not None)
    points = sample_points(axes, samples, seed) if samples else grid(axes)
    fixed = options.overrides.values if options.overrides is not None else {}
    varied_and_set = sorted(set(fixed) & {axis.name for axis in axes})
    if varied_and_set:
        raise UsageError(f"{', '.join(varied_and_set)} is both varied (--vary) and set "
                         "(--set/--config): drop one")
    job = SweepJob(str(path), str(robot.base) if robot.base else None,
                   tuple(str(Path(p).resolve()) for p in options.package_paths),
                   tuple(sorted(options.mappings.items())), tuple(sorted(fixed.items())),
                   tuple(scenarios), left, right, is_trusted(),
                   tuple(str(p) for p in chosen_asset_paths()), specs)
    return Session(job, [axis.name for axis in axes], points,
                   output if output != "-" else None, {axis.name: axis.unit for axis in axes})


def _run(session, todo, jobs, scheduler) -> str:
    """Run the points left, with a progress bar on a terminal; the rows are saved on the
    way out, whatever ends the run. Returns what ran them, for the summary."""
    import sys

    from mobile_car.sweep.execute import default_jobs, run_dask, run_local

    workers = f"Dask scheduler {scheduler}" if scheduler else \
        _workers(min(jobs or default_jobs(), max(1, len(todo))))
    if not todo:
        return workers
    # A bar on a terminal only: in a CI log it would be one line per redraw.
    bar = click.progressbar(length=len(todo), label="mcar sweep", file=sys.stderr,
                            show_pos=True, show_eta=True) if sys.stderr.isatty() else None

    def on_row(row):
        session.add(row)
        if bar is not None:
            bar.update(1)

    try:
        if scheduler:
            run_dask(session.job, todo, scheduler, on_row)
        else:
            run_local(session.job, todo, jobs or default_jobs(), on_row)
    except BaseException:
        if session.output and session.rows:
            session.save()
            click.echo(f"mcar sweep: {len(session.rows)} of {len(session.points)} points "
                       f"kept in {session.output}; --resume runs the rest", err=True)
        raise
    finally:
        if bar is not None:
            bar.render_finish()
    return workers


def _plot_axes(session, plot_x, plot_y, colour):
    """The plot's x and y (default: the first two --vary), checked with its colour by the
    plot's own rules on the empty table, before the sweep runs: a typo must not cost the
    whole sweep its plot."""
    from mobile_car.sweep.plot import check_columns

    names = session.names
    x = plot_x or names[0]
    y = plot_y or (names[1] if len(names) > 1 else x)
    check_columns(session.table(), x, y, colour, session.units)
    return x, y


def _workers(count: int) -> str:
    return f"{count} local worker{'s' * (count != 1)}"
