"""The `robots` section of bench/run.py: a cold `mcar sim` on robots people ship (TurtleBot3
burger, built once to a URDF as its launch file does; Husky, from its xacro in place) next
to the bundled car, each a fresh process, run in rounds so that the load of a shared
machine falls on all alike; and where Husky's time goes (its `mcar check` alone, the bare
imports), to say what a miss costs. The robots come from the shared real-robots folder
(its SOURCES.md), used in place; without it the section says so and measures the car."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

TARGET_S = 1.5  # a cold `mcar sim` of each robot (issue 25)


def real_robots(repo: Path) -> Path | None:
    """$MCAR_REAL_ROBOTS, else ../shared/real-robots beside the repository (beside the main
    checkout when this is a git worktree), as the tests find it."""
    if os.environ.get("MCAR_REAL_ROBOTS"):
        candidates = [Path(os.environ["MCAR_REAL_ROBOTS"])]
    else:
        candidates = [repo.parent / "shared" / "real-robots"]
        dot_git = repo / ".git"
        if dot_git.is_file() and dot_git.read_text().startswith("gitdir:"):
            main = Path(dot_git.read_text().removeprefix("gitdir:").strip()).parents[2]
            candidates.append(main.parent / "shared" / "real-robots")
    return next((c for c in candidates if (c / "SOURCES.md").is_file()), None)


def commands(mcar: str, python: str, repo: Path, work: Path) -> tuple[dict, Path | None]:
    """(label -> command, the real-robots folder or None): the timed commands, in the
    table's order; the robots' rows only where the folder is."""
    folder = real_robots(repo)
    car = str(repo / "urdf" / "mobile_robot.xacro")
    timed = {"`mcar sim` bundled car (mobile_robot.xacro)": [mcar, "sim", car]}
    if folder is None:
        return timed, None
    burger = work / "turtlebot3_burger.urdf"
    subprocess.run([mcar, "build", "--package-path", str(folder),
                    str(folder / "turtlebot3_description" / "urdf" / "turtlebot3_burger.urdf"),
                    "-o", str(burger)], check=True, capture_output=True)
    husky = str(folder / "husky_description" / "urdf" / "husky.urdf.xacro")
    timed.update({
        "`mcar sim` TurtleBot3 burger (built URDF)": [mcar, "sim", "--package-path",
                                                      str(folder), str(burger)],
        "`mcar sim` Husky (husky.urdf.xacro)": [mcar, "sim", "--package-path", str(folder),
                                                husky],
        "`mcar check` Husky (husky.urdf.xacro)": [mcar, "check", "--package-path",
                                                  str(folder), husky],
        "`python -c 'import mujoco'`": [python, "-c", "import mujoco"],
        "`python -c 'import trimesh'`": [python, "-c", "import trimesh"],
    })
    return timed, folder


def table(results: dict, fmt_time, fmt_peak, exit_text, verdict) -> list[str]:
    """The section's rows: each command's median, memory, ratio to the car's, target."""
    car = next(iter(results.values()))
    rows = ["| command | median | peak memory | x car | exit | target |",
            "|---|---:|---:|---:|---|---|"]
    for label, result in results.items():
        targeted = label.startswith("`mcar sim`")
        met = (result.ok and result.wall < TARGET_S) if targeted else None
        ratio = f"{result.wall / car.wall:.2f}" if result.ok and car.ok else "-"
        rows.append(f"| {label} | {fmt_time(result.wall)} | {fmt_peak(result)} | {ratio} | "
                    f"{exit_text(result.codes)} | {verdict(met)} |")
    return rows


def intro(folder: Path | None, runs: int, loads: tuple[float, float]) -> list[str]:
    where = (f"the real-robots folder {folder}, in place" if folder is not None else
             "**no real-robots folder here** (set MCAR_REAL_ROBOTS): the car alone")
    return [f"A cold `mcar sim` (drop, drive, spin) of robots people ship, from {where}, "
            "next to the bundled car; each run a fresh process, the commands in rounds "
            f"(medians of {runs}, after one untimed run each). Target: each under "
            f"{TARGET_S:g} s. *x car*: the time over the car's in this run. `mcar check` "
            "of Husky and the bare imports say where Husky's time goes. Load average (1 "
            f"min) of this shared machine: {loads[0]:.2f} when the section started, "
            f"{loads[1]:.2f} when it ended.", ""]
