"""The `specs` section of bench/run.py: a cold `mcar specs` with and without its MuJoCo
proofs, side by side with `mcar sim` on the same robots (issue 42: under 1 s cold without
the proof for TurtleBot3 burger), each run a fresh process, the commands in rounds so that
the load of a shared machine falls on all alike. TurtleBot3 burger comes from the shared
real-robots folder (built once to a URDF, as its launch file does); without it the car
alone is measured and the section says so."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

TARGET_S = 1.0  # `mcar specs --no-proof` of TurtleBot3 burger, cold


def commands(run, work: Path) -> tuple[dict, Path | None]:
    """(label -> command, the real-robots folder or None), in the table's order."""
    from sim_robots_bench import real_robots

    mcar = run.MCAR
    robots = [("the bundled car", str(run.REPO / "urdf" / "mobile_robot.xacro"), [])]
    folder = real_robots(run.REPO)
    if folder is not None:
        burger = work / "turtlebot3_burger.urdf"
        subprocess.run([mcar, "build", "--package-path", str(folder),
                        str(folder / "turtlebot3_description" / "urdf" /
                            "turtlebot3_burger.urdf"), "-o", str(burger)],
                       check=True, capture_output=True)
        robots.insert(0, ("TurtleBot3 burger", str(burger), ["--package-path", str(folder)]))
    timed = {}
    for name, robot, extra in robots:
        timed[f"`mcar specs --no-proof` {name}"] = [mcar, "specs", "--no-proof", *extra, robot]
        timed[f"`mcar specs` {name} (with its proofs)"] = [mcar, "specs", *extra, robot]
        timed[f"`mcar sim --scenario drop` {name}"] = [mcar, "sim", "--scenario", "drop",
                                                        *extra, robot]
        timed[f"`mcar sim` {name}"] = [mcar, "sim", *extra, robot]
    return timed, folder


def section(rows: list[str], work: Path, quick: bool, run) -> None:
    """``run``: bench/measure.py."""
    runs = 0 if quick else 7  # --quick: the watched run, timed
    load_before = os.getloadavg()[0]
    timed, folder = commands(run, work)
    results = run.measure_rounds(timed, runs, cwd=work)
    where = (f"TurtleBot3 burger from {folder} (in place, built once to a URDF) and the "
             "bundled car" if folder is not None else
             "**no real-robots folder here** (set MCAR_REAL_ROBOTS): the bundled car alone")
    rows += ["## `mcar specs`", "",
             f"A cold `mcar specs` of {where}, without its MuJoCo proofs (`--no-proof`) and "
             "with them, side by side with `mcar sim` of the same robot; each run a fresh "
             f"process, the commands in rounds (medians of {runs}, after one untimed run "
             f"each). Target: `mcar specs --no-proof` of TurtleBot3 burger under "
             f"{TARGET_S:g} s. *x sim*: the time over `mcar sim` of the same robot in this "
             f"run. Load average (1 min) of this shared machine: {load_before:.2f} when the "
             f"section started, {os.getloadavg()[0]:.2f} when it ended. An exit of 1 is a "
             "figure its proof contradicts or a W5xx error (docs/specs.md).", "",
             "| command | median | peak memory | x sim | exit | target |",
             "|---|---:|---:|---:|---|---|"]
    for label, result in results.items():
        name = label.split("` ", 1)[1].removesuffix(" (with its proofs)")
        sim = results.get(f"`mcar sim` {name}")
        ratio = (f"{result.wall / sim.wall:.2f}" if sim is not None and sim.ok and result.codes
                 else "-")
        targeted = label.startswith("`mcar specs --no-proof` TurtleBot3")
        met = (result.wall < TARGET_S and result.codes[-1] in (0, 1)) if targeted else None
        rows.append(f"| {label} | {run.fmt_time(result.wall)} | {run.fmt_peak(result)} | "
                    f"{ratio} | {run.exit_text(result.codes)} | {run.verdict(met)} |")
    rows.append("")
    rows += run.notes_for("specs")
    run.progress("specs measured")
