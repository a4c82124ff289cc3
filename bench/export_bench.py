"""The `export` section of bench/run.py: `mcar export --to mjcf|usd|urdf|sdf` on robots
people ship (TurtleBot3 burger, built once to a URDF as its launch file does; Husky, from
its xacro in place in the shared real-robots folder), with and without --verify, next to
`mcar check` of the same robot (the floor every export stands on: it checks first). Each
run is a fresh process writing over the previous run's export folder; the commands run
in rounds so that the load of a shared machine falls on all alike. A format whose engine
is not installed here (the usd extra, the Gazebo helper) is left out, and said. --quick
measures TurtleBot3 only."""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

FORMATS = ("mjcf", "usd", "urdf", "sdf")


def _formats() -> tuple[list[str], list[str]]:
    """(formats measured, why the others are not)."""
    from gazebo_bench import helper_path

    missing = {}
    if importlib.util.find_spec("pxr") is None:
        missing["usd"] = "usd: the usd extra is not installed"
    if helper_path() is None:
        missing["sdf"] = "sdf: the Gazebo helper is not built (`make gazebo-helper`)"
    return [f for f in FORMATS if f not in missing], list(missing.values())


def _robots(mcar: str, repo: Path, work: Path) -> dict:
    """label -> the arguments naming the robot (``--package-path`` and its file)."""
    from sim_robots_bench import real_robots

    folder = real_robots(repo)
    if folder is None:
        return {}
    burger = work / "turtlebot3_burger.urdf"
    subprocess.run([mcar, "build", "--package-path", str(folder),
                    str(folder / "turtlebot3_description" / "urdf" / "turtlebot3_burger.urdf"),
                    "-o", str(burger)], check=True, capture_output=True)
    husky = folder / "husky_description" / "urdf" / "husky.urdf.xacro"
    return {"TurtleBot3 burger (built URDF)": ["--package-path", str(folder), str(burger)],
            "Husky (husky.urdf.xacro)": ["--package-path", str(folder), str(husky)]}


def section(rows: list[str], work: Path, quick: bool, run) -> None:
    """``run``: bench/measure.py (measure_rounds, fmt_time, ...)."""
    rows += ["## `mcar export`", ""]
    robots = _robots(run.MCAR, run.REPO, work)
    if not robots:
        rows += ["Not measured: no real-robots folder here (set MCAR_REAL_ROBOTS).", ""]
        return
    if quick:  # a smoke test: one robot
        robots = dict(list(robots.items())[:1])
    formats, left_out = _formats()
    runs = 0 if quick else 5
    load_before = os.getloadavg()[0]
    commands = {}
    for label, robot in robots.items():
        commands[label, "check"] = [run.MCAR, "check", "-q", *robot]
        for to in formats:
            out = str(work / f"{len(commands)}_{to}")
            commands[label, to] = [run.MCAR, "export", "-q", *robot, "--to", to, "-o", out]
            commands[label, f"{to} --verify"] = [*commands[label, to], "--verify"]
    results = run.measure_rounds(commands, runs, cwd=work)
    rows += [f"`mcar export ROBOT --to FORMAT -o DIR`, a fresh process writing over its "
             f"earlier export, without and with `--verify` (the export loaded back by its "
             f"engine: MuJoCo settling and driving it, pxr, yourdfpy and check_urdf, "
             f"libsdformat), next to `mcar check` of the same robot (an export checks "
             f"first). Medians of {runs} rounds after one untimed run each. *x check*: the "
             f"export's time over the check's. Load average (1 min) of this shared "
             f"machine: {load_before:.2f} when the section started, "
             f"{os.getloadavg()[0]:.2f} when it ended."
             + (f" Not measured: {'; '.join(left_out)}." if left_out else ""), "",
             "| robot | format | export | x check | export --verify | x check | "
             "peak (--verify) | exit |",
             "|---|---|---:|---:|---:|---:|---:|---|"]
    for label in robots:
        check = results[label, "check"]
        rows.append(f"| {label} | (`mcar check`) | {run.time_cell(check)} | 1.00 | - | - | "
                    f"{run.fmt_peak(check)} | {run.exit_text(check.codes)} |")
        for to in formats:
            plain, verified = results[label, to], results[label, f"{to} --verify"]
            rows.append(f"| {label} | {to} | {run.time_cell(plain)} | "
                        f"{_ratio(plain, check)} | {run.time_cell(verified)} | "
                        f"{_ratio(verified, check)} | {run.fmt_peak(verified)} | "
                        f"{run.exit_text(plain.codes + verified.codes)} |")
            run.progress(f"export {label} {to}: {run.fmt_time(plain.wall)}, --verify "
                         f"{run.fmt_time(verified.wall)}")
    rows.append("")
    rows += run.notes_for("export")


def _ratio(result, check) -> str:
    return f"{result.wall / check.wall:.2f}" if result.ok and check.ok else "-"


if __name__ == "__main__":  # pragma: no cover - run through bench/run.py export
    sys.exit("run: python bench/run.py export")
