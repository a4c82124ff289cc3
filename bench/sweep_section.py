"""The sweep section of bench/run.py: `mcar sweep` with 1 and 2 local workers and on a
2-worker Dask cluster, against a shell loop of `mcar sim` over the same points."""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from measure import (  # noqa: E402
    MCAR,
    REPO,
    RUN_TIMEOUT_S,
    exit_text,
    fmt_ratio,
    fmt_time,
    measure_rounds,
    notes_for,
    progress,
    speedup,
    time_cell,
    verdict,
)


def section_sweep(rows: list[str], work: Path, quick: bool) -> None:
    """`mcar sweep` with 1 and 2 local workers and on a 2-worker Dask cluster, against a
    shell loop of `mcar sim` over the same points; then where one point's time goes."""
    import sweep_bench

    robot = str(REPO / "urdf" / "mobile_robot.xacro")
    runs = 0 if quick else 5  # --quick: the one watched run is timed (measure.py)
    load_before = os.getloadavg()[0]
    plan = sweep_bench.sweeps(quick)
    workers = {"jobs 1": 1, "jobs 2": 2, "dask": 2, "loop": 1}
    outputs, commands = {}, {}
    with sweep_bench.dask_cluster() as (scheduler, why_not):
        for sweep in plan:
            runners = [("jobs 1", ["--jobs", "1"]), ("jobs 2", ["--jobs", "2"])]
            runners += [("dask", ["--scheduler", scheduler])] if scheduler else []
            for runner, extra in runners:
                out = outputs[sweep.label, runner] = work / f"{len(outputs)}.csv"
                commands[sweep.label, runner] = [MCAR, "sweep", robot, *sweep.args(), *extra,
                                                 "-o", str(out)]
            if sweep.loop:  # the loop runs the points a first sweep reports, values as is
                subprocess.run(commands[sweep.label, "jobs 1"], capture_output=True,
                               cwd=work, timeout=RUN_TIMEOUT_S)
                commands[sweep.label, "loop"] = sweep_bench.loop_script(
                    work / "loop.sh", MCAR, robot,
                    sweep_bench.read_rows(outputs[sweep.label, "jobs 1"]))
        one, two = sweep_bench.burn_commands(sys.executable)
        commands["machine", "one"], commands["machine", "two"] = one, two
        progress(f"sweep: {runs} rounds of {len(commands)} commands")
        timed = measure_rounds(commands, runs, cwd=work)
    results: dict = {}  # (sweep label, runner) -> (Result, rows of its last run, workers)
    for key, result in timed.items():
        if key[0] != "machine":
            rows_out = sweep_bench.read_rows(outputs[key]) if key in outputs else []
            results[key] = (result, rows_out, workers[key[1]])
            progress(f"sweep {key[0]} {key[1]}: {fmt_time(result.wall)}")
    alone, together = timed["machine", "one"], timed["machine", "two"]
    load_after = os.getloadavg()[0]

    first, mixed = plan[0], plan[-1]
    rows += ["## `mcar sweep`", "",
             "The bundled car swept over wheel radius and track width, each point validated, "
             "built, checked (`--strict`) and simulated (drop, drive, spin) in a worker; each "
             "`mcar sweep` is a whole process writing its results to a CSV file. "
             f"*{first.label}*: `{' '.join(first.args())}`; *{mixed.label}*: "
             f"`{' '.join(mixed.args())}`, where config.xacro rejects the narrow and wide "
             "tracks. Peer: what a user does without sweep, a shell loop of one `mcar sim "
             "--set wheel_radius=R --set track_width=T` per point (a fresh process each, "
             "the values the sweep's results file has). *Dask*: `--scheduler` on a "
             "LocalCluster of 2 single-thread worker processes on 127.0.0.1, started by the "
             "bench and kept up across the runs, so its workers are warm after the first. "
             "The commands run in rounds, each command once a round (medians over "
             f"{runs} rounds, after one untimed run each), so that a change in the load "
             "of this shared machine falls on all of them alike. *Points*: what the results "
             "file of the last run holds (in bold where it differs from `--jobs 1`'s). "
             "*Outside the points*: wall - (sum of the points' total_s) / workers: start-up, "
             "starting the workers, the wait for the last point, writing the results. "
             "Target: 2 workers at least 1.6x the points/s of 1 (the `--jobs 2` rows). "
             f"Load average (1 min) of this shared machine: {load_before:.2f} when the "
             f"section started, {load_after:.2f} when it ended.", "",
             "| sweep | runner | points | wall | points/s | over 1 worker | loop / this "
             "| median ok point | outside the points | exit | target |",
             "|---|---|---|---:|---:|---:|---:|---:|---:|---|---|"]
    names = {"jobs 1": "`--jobs 1`", "jobs 2": "`--jobs 2`",
             "dask": "`--scheduler`, Dask (2 workers)",
             "loop": "shell loop of `mcar sim`, one per point"}
    for sweep in plan:
        one = results[sweep.label, "jobs 1"][0]
        loop = results.get((sweep.label, "loop"), (None,))[0]
        for runner in ("jobs 1", "jobs 2", "dask", "loop"):
            if (sweep.label, runner) not in results:
                continue
            result, points, workers = results[sweep.label, runner]
            rate = f"{sweep.points / result.wall:.2f}" if result.ok else "-"
            if runner == "loop":
                rows.append(f"| {sweep.label} | {names[runner]} | {sweep.points} processes | "
                            f"{time_cell(result)} | {rate} | - | - | - | - | "
                            f"{exit_text(result.codes)} | - |")
                continue
            counted = sweep_bench.statuses(points)
            if counted != sweep_bench.statuses(results[sweep.label, "jobs 1"][1]):
                counted = f"**{counted}**"
            if len(points) != sweep.points:
                counted = f"**{len(points)} rows of {sweep.points}**: {counted}"
            over_one = speedup(result, one) if runner != "jobs 1" else None
            busy = sum(sweep_bench.seconds(points, "total_s")) / workers
            outside = result.walls[-1] - busy  # the last run wrote the results file
            outside_cell = f"{fmt_time(outside)} ({outside / result.walls[-1]:.0%})"
            median_ok = sweep_bench.median_ok_point(points)
            target = verdict(over_one is not None and over_one >= 1.6) \
                if runner == "jobs 2" else "-"
            rows.append(
                f"| {sweep.label} | {names[runner]} | {counted} | {time_cell(result)} | "
                f"{rate} | {fmt_ratio(over_one)} | "
                f"{fmt_ratio(speedup(result, loop)) if loop else '-'} | "
                f"{'-' if median_ok is None else fmt_time(median_ok)} | "
                f"{outside_cell} | {exit_text(result.codes)} | {target} |")
    if not any(runner == "dask" for _, runner in results):
        rows += ["", f"(No Dask row: {why_not}.)"]
    machine_scaling = speedup(together, alone)
    rows += ["", "The machine in the same run: a CPU-bound pure-Python process alone "
             f"{time_cell(alone)}, two at once {time_cell(together)}: two busy processes "
             "get "
             f"{'-' if machine_scaling is None else f'{2 * machine_scaling:.2f}x'} "
             "the throughput of one (2.00x if both cores were free), the ceiling of the "
             "2-worker rows.", ""]
    rows += _sweep_split_rows(results, first, mixed)
    rows += notes_for("sweep")
    progress("sweep measured")


def _sweep_split_rows(results: dict, first, mixed) -> list[str]:
    """Where one point's time goes: medians over the points of the `--jobs 1` run of the
    all-valid sweep, from its results file's timing columns."""
    import sweep_bench

    result, points, _ = results[first.label, "jobs 1"]
    if not any(row["status"] == "ok" for row in points):
        return [f"(No split: the `--jobs 1` run of the {first.label} sweep has no ok point, "
                f"exit {exit_text(result.codes)}.)", ""]
    labels = {"validate_s": "validate (ranges, config.xacro's checks)",
              "build_s": "build (expand the xacro, load the URDF)",
              "check_s": "check (`--strict`)",
              "sim_s": "sim (MuJoCo model; drop, drive, spin)",
              "other": "other (mass, the row)", "total_s": "**total** (`total_s`)"}
    text = [f"Per point, {first.label} sweep, `--jobs 1` (medians over its {len(points)} "
            "points; share: that stage's sum over the points' sum of total_s):", "",
            "| stage | median per point | share |", "|---|---:|---:|"]
    for stage, median, share in sweep_bench.split(points):
        text.append(f"| {labels[stage]} | {median * 1000:.1f} ms | {share:.0%} |")
    busy = sum(sweep_bench.seconds(points, "total_s"))
    wall = result.walls[-1]
    slowest = max(sweep_bench.seconds(points, "total_s"))
    text += ["", f"That run: wall {fmt_time(wall)}, of which the points {fmt_time(busy)} "
             f"and outside them {fmt_time(wall - busy)} ({(wall - busy) / wall:.0%}: "
             f"start-up share). The slowest point, the worker's first (its imports), took "
             f"{fmt_time(slowest)}."]
    _, mixed_points, _ = results[mixed.label, "jobs 1"]
    rejected = [row for row in mixed_points if row["status"] == "rejected"]
    ok_median = sweep_bench.median_ok_point(mixed_points)
    if rejected and ok_median:
        cost = statistics.median(sweep_bench.seconds(rejected, "total_s"))
        text[-1] += (f" In the {mixed.label} sweep (`--jobs 1`), a rejected point took "
                     f"{fmt_time(cost)} (median), an ok one {fmt_time(ok_median)}.")
    return [*text, ""]


