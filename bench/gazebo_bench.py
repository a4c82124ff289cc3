"""The `gazebo` section of bench/run.py: what `mcar check --gazebo` costs over `mcar check`,
against the bare helper (`mcar-sdformat`, libsdformat's own conversion, the floor) in the
same run; on the car and on generated trees (bench/generate.py, whose root gets a mass
here so that Gazebo keeps the robot: the generator's root has none)."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

ROOT_WITH_MASS = ('  <link name="base_link"><inertial><mass value="1"/><inertia ixx="1" '
                  'ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>\n')


def helper_path() -> Path | None:
    from mobile_car.errors import GazeboUnavailable
    from mobile_car.gazebo.helper import find_helper

    try:
        return find_helper()
    except GazeboUnavailable:
        return None


def section(rows: list[str], work: Path, quick: bool, run) -> None:
    """``run``: bench/measure.py (measure, time_cell, fmt_time, ...)."""
    import generate

    helper = helper_path()
    rows += ["## `mcar check --gazebo`", ""]
    if helper is None:
        rows += ["Not measured: the Gazebo helper is not built (`make gazebo-helper`).", ""]
        return
    runs = 0 if quick else 7  # --quick: the watched run, timed
    car = run.REPO / "urdf" / "mobile_robot.xacro"
    built = work / "mobile_robot.urdf"
    subprocess.run([run.MCAR, "build", str(car), "-o", str(built)], check=True)
    robots = [("the car (xacro, 16 links)", car, built)]
    # Not 5,000 links and more: past MCAR_GAZEBO_MEMORY_MB (bench/notes.md), and the bare
    # helper run here has no bound.
    for n in ([100] if quick else [100, 1000]):
        path = work / f"tree_{n}.urdf"
        path.write_text(generate.robot(n, "tree", "distinct").replace(
            '  <link name="base_link"/>\n', ROOT_WITH_MASS))
        robots.append((f"tree, every number distinct, {n:,} links", path, path))
    rows += ["`mcar check` and `mcar check --gazebo` of the same robot, and the helper alone "
             "on its built URDF (`mcar-sdformat < robot.urdf`: libsdformat loading the SDF "
             "spec, converting, answering). *mcar's share*: what --gazebo adds beyond the "
             "helper's own run (running it, checking its answer, comparing, locating). "
             "Target: mcar's share under a quarter of the helper's time.", "",
             "| robot | check | check --gazebo | helper alone | mcar's share | "
             "peak (--gazebo / helper) | exit | target |",
             "|---|---:|---:|---:|---:|---:|---|---|"]
    shell = shutil.which("sh") or "/bin/sh"
    for label, source, urdf in robots:
        plain = run.measure([run.MCAR, "check", "-q", str(source)], runs, budget_s=60)
        gazebo = run.measure([run.MCAR, "check", "-q", "--gazebo", str(source)], runs,
                             budget_s=90)
        alone = run.measure([shell, "-c", 'exec "$0" < "$1"', str(helper), str(urdf)], runs,
                            budget_s=60)
        share = gazebo.wall - plain.wall - alone.wall
        met = gazebo.ok and plain.ok and share < alone.wall / 4
        rows.append(f"| {label} | {run.time_cell(plain)} | {run.time_cell(gazebo)} | "
                    f"{run.time_cell(alone)} | {run.fmt_time(max(share, 0.0))} | "
                    f"{run.fmt_peak(gazebo)} / {run.fmt_peak(alone)} | "
                    f"{run.exit_text(gazebo.codes)} | {run.verdict(met)} |")
        run.progress(f"gazebo {label}: check {run.fmt_time(plain.wall)}, --gazebo "
                     f"{run.fmt_time(gazebo.wall)}, helper {run.fmt_time(alone.wall)}")
    rows.append("")
    rows += run.notes_for("gazebo")


if __name__ == "__main__":  # pragma: no cover - run through bench/run.py gazebo
    sys.exit("run: python bench/run.py gazebo")
