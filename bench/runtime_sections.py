"""The sections of bench/run.py that run the robot: render, the no-op runs, sim."""

from __future__ import annotations

import json
import os
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import generate  # noqa: E402
from measure import (  # noqa: E402
    MCAR,
    REPO,
    RUN_TIMEOUT_S,
    Result,
    exit_text,
    fmt_peak,
    fmt_time,
    measure,
    measure_rounds,
    notes_for,
    progress,
    run_timed,
    time_cell,
    verdict,
)


def section_render(rows: list[str], work: Path, quick: bool) -> None:
    out = work / "renders"
    runs = 1 if quick else 3
    walls, codes = [], []
    for _ in range(runs):
        shutil.rmtree(out, ignore_errors=True)
        wall, code = run_timed([MCAR, "render", "--bundled", "--force", "-o", str(out), "--quiet"],
                               cwd=work)
        walls.append(wall)
        codes.append(code)
    images = [p for p in out.rglob("*.png") if p.name != "index.png"]
    total = statistics.median(walls)
    one = measure([MCAR, "render", str(REPO / "urdf" / "wheel" / "test_wheel.urdf.xacro"),
                   "-o", str(work / "wheel.png"), "--force"], 0 if quick else 7)
    robot = measure([MCAR, "render", str(REPO / "urdf" / "mobile_robot.xacro"),
                     "-o", str(work / "robot.png"), "--force"], 0 if quick else 7)
    pieces = json.loads(subprocess.run(
        [sys.executable, str(Path(__file__).with_name("render_bench.py")), "--json",
         "--runs", "1" if quick else "5"],
        capture_output=True, text=True, check=True, timeout=RUN_TIMEOUT_S).stdout)
    whole_ok = all(code == 0 for code in codes)
    rows += ["## `mcar render`", "",
             "800x600 PNGs. Target: every part, step and the complete robot, cold (a new "
             "process, warm disk cache), in one call, under 3 s.", "",
             "| what | median | exit | target |", "|---|---:|---|---|",
             f"| all {len(images)} pictures + contact sheet, one `mcar render --force` | "
             f"{fmt_time(total)} ({len(images) / total:.1f} pictures/s) | {exit_text(codes)} | "
             f"{verdict(whole_ok and total < 3.0)} |",
             f"| one part (`mcar render wheel/test_wheel.urdf.xacro`), whole process | "
             f"{time_cell(one)} | {exit_text(one.codes)} | - |",
             f"| complete robot (`mcar render mobile_robot.xacro`), whole process | "
             f"{time_cell(robot)} | {exit_text(robot.codes)} | - |", "",
             f"Inside one process (`bench/render_bench.py`): importing numpy, trimesh, "
             f"yourdfpy and the render modules {fmt_time(pieces['import'])}; making the "
             f"renderer {fmt_time(pieces['context'])} ({pieces['renderer']}). Then per "
             "picture (median):", "",
             "| file | triangles | expand xacro | load scene | draw | overlays + PNG | "
             "per picture |", "|---|---:|---:|---:|---:|---:|---:|"]
    for entry in pieces["files"]:
        rows.append(f"| {entry['file']} | {entry['triangles']:,} | "
                    + " | ".join(fmt_time(entry[stage])
                                 for stage in ("expand", "load", "draw", "finish", "total"))
                    + " |")
    raycast = pieces["raycast"]
    draw = next(entry["draw"] for entry in pieces["files"] if entry["file"] == raycast["file"])
    rows += ["", f"Where no OpenGL context can be made, mcar ray-casts with trimesh + embreex: "
             f"drawing {raycast['file']} takes {fmt_time(raycast['draw'])} that way, "
             f"{raycast['draw'] / draw:.0f}x OpenGL's {fmt_time(draw)}.", ""]
    rows += _big_robot_rows(work, quick)
    rows += notes_for("render")
    progress(f"render: whole set {fmt_time(total)}")


def _big_robot_rows(work: Path, quick: bool) -> list[str]:
    """Whole `mcar render` of generated 10,000-link robots (boxes and cylinders; every
    number distinct), chain and tree: drawing must scale linearly with the links. No peer
    tool draws a URDF headless, so the table gives seconds and memory, no ratio."""
    links = 2000 if quick else 10000
    rows = [f"Generated {links:,}-link robots (`bench/generate.py`, boxes and cylinders, "
            "every number distinct; check, scene and one picture, whole process). Target: "
            "under 30 s (it took 345 s and 3.35 GB before the scene was built in one pass).",
            "", "| robot | links | size | median | pictures/s | peak memory | exit | target |",
            "|---|---:|---:|---:|---:|---:|---|---|"]
    for shape in generate.SHAPES:
        path = work / f"render_{shape}_{links}.urdf"
        path.write_text(generate.robot(links, shape, "distinct", shapes=2))
        result = measure([MCAR, "render", str(path), "-o", str(work / "big.png"), "--force"],
                         1 if quick else 3, budget_s=120)
        rows.append(f"| {shape} | {links:,} | {path.stat().st_size / 1e6:.1f} MB | "
                    f"{time_cell(result)} | {1 / result.wall:.2f} | {fmt_peak(result)} | "
                    f"{exit_text(result.codes)} | "
                    f"{verdict(result.ok and result.wall < 30)} |")
        progress(f"render {shape} {links}: {fmt_time(result.wall)}")
        path.unlink()
    return [*rows, ""]


def rows_over_version(cases, version: Result, peak: bool = False) -> list[str]:
    """Table rows of (label, result, target seconds or None): the median (and peak
    memory), the ratio to `mcar --version` measured in the same run, exit, verdict."""
    rows = []
    for label, result, limit in cases:
        met = None if limit is None else (result.ok and result.wall < limit)
        memory = f" {fmt_peak(result)} |" if peak else ""
        rows.append(f"| {label} | {time_cell(result)} |{memory} "
                    f"{result.wall / version.wall:.1f} | {exit_text(result.codes)} | "
                    f"{verdict(met)} |")
    return rows


def section_noop(rows: list[str], work: Path, quick: bool) -> None:
    """`mcar render`, `ci`, `build` and `check` of the bundled package with nothing
    changed (the pre-commit hook's case), and with one part file edited (only its
    pictures redrawn)."""
    package = work / "mobile_car_description"
    for name in ("urdf", "meshes"):
        shutil.copytree(REPO / name, package / name)
    for name in ("package.xml", "mcar.yaml"):
        shutil.copy(REPO / name, package / name)
    runs = 5 if quick else 11
    motor = package / "urdf" / "motor" / "motor.xacro"
    original = motor.read_text(encoding="utf-8")
    edits = iter(range(10**6))

    def edit_motor() -> None:  # a new comment each time: new bytes, same robot
        motor.write_text(original + f"<!-- edit {next(edits)} -->\n", encoding="utf-8")
        time.sleep(0.05)  # older than the run's start, as an edit before a commit is

    def timed_after(prepare, cmd) -> Result:
        result = Result()
        for _ in range(runs):
            prepare()
            wall, code = run_timed(cmd, cwd=package)
            result.walls.append(wall)
            result.codes.append(code)
        return result

    version = measure([MCAR, "--version"], runs)
    subprocess.run([MCAR, "render"], cwd=package, capture_output=True, check=True)
    subprocess.run([MCAR, "ci"], cwd=package, capture_output=True, check=True)
    cases = [
        ("no-op `mcar render` (13 pictures unchanged)", measure([MCAR, "render"], runs,
                                                               cwd=package), 0.2),
        ("no-op `mcar ci` (15 files replayed)", measure([MCAR, "ci"], runs, cwd=package), 0.3),
        ("no-op `mcar build` (13 files unchanged)", measure([MCAR, "build"], runs,
                                                          cwd=package), 0.3),
        ("no-op `mcar check` (13 results read back, the first from ci's)",
         measure([MCAR, "check"], runs, cwd=package), 0.3),
        ("`mcar render`, motor.xacro edited (2 of 13 pictures redrawn)",
         timed_after(edit_motor, [MCAR, "render"]), None),
        ("`mcar ci`, motor.xacro edited (4 of 15 files built again)",
         timed_after(edit_motor, [MCAR, "ci"]), None),
        ("`mcar render --force` (all 13 drawn)", measure([MCAR, "render", "--force"],
                                                         3 if quick else 5, cwd=package), None),
    ]
    rows += ["## Nothing changed", "",
             "The bundled package, rendered and built once, then run again (the pre-commit "
             "hook's `mcar ci`). Targets: no-op `mcar render` under 200 ms, no-op `mcar ci`, "
             "`build` and `check` under 300 ms (before: 1.5-2.4 s; `check` 0.45 s). "
             "*x --version*: the time over `mcar --version` in this run "
             f"({fmt_time(version.wall)}).", "",
             "| what | median | x --version | exit | target |", "|---|---:|---:|---|---|"]
    rows += rows_over_version(cases, version)
    rows.append("")
    rows += notes_for("noop")
    progress("no-op measured")


def section_sim(rows: list[str], work: Path, quick: bool) -> None:
    """A cold `mcar sim` of the car (a fresh process: MuJoCo imported, the model made,
    drop, drive and spin run), against `mcar --version` and the bare MuJoCo import."""
    runs = 0 if quick else 11  # --quick: the watched run, timed
    robot = str(REPO / "urdf" / "mobile_robot.xacro")
    version = measure([MCAR, "--version"], runs)
    cases = [
        ("`mcar --version`", version, None),
        ("`python -c 'import mujoco'`", measure([sys.executable, "-c", "import mujoco"], runs),
         None),
        ("`mcar sim mobile_robot.xacro` (drop, drive, spin)",
         measure([MCAR, "sim", robot], runs, cwd=work), 1.5),
        ("`mcar sim mobile_robot.xacro --scenario drop`",
         measure([MCAR, "sim", robot, "--scenario", "drop"], runs, cwd=work), None),
    ]
    rows += ["## `mcar sim`", "",
             "The complete car simulated in MuJoCo, headless, each run a fresh process. "
             "Target: `mcar sim` of the car under 1.5 s. *x --version*: the time over "
             f"`mcar --version` in this run ({fmt_time(version.wall)}).", "",
             "| command | median | peak memory | x --version | exit | target |",
             "|---|---:|---:|---:|---|---|"]
    rows += rows_over_version(cases, version, peak=True)
    rows.append("")
    rows += notes_for("sim")
    progress("sim measured")



def section_robots(rows: list[str], work: Path, quick: bool) -> None:
    """A cold `mcar sim` of TurtleBot3 burger and Husky next to the car (the commands and
    the table: bench/sim_robots_bench.py)."""
    import sim_robots_bench as robots

    runs = 0 if quick else 7
    load_before = os.getloadavg()[0]
    commands, folder = robots.commands(MCAR, sys.executable, REPO, work)
    results = measure_rounds(commands, runs, cwd=work)
    rows += ["## `mcar sim` on real robots", ""]
    rows += robots.intro(folder, runs, (load_before, os.getloadavg()[0]))
    rows += robots.table(results, fmt_time, fmt_peak, exit_text, verdict)
    rows.append("")
    rows += notes_for("robots")
    progress("robots measured")
