"""The `floor` section of bench/run.py: issue 41's three speed ratios, each mcar command
run in turn with its yardstick (A B A B ...), the ratio taken pair by pair, so that a
change in the load of a shared machine falls on both sides of every ratio alike.

* `mcar check` of the car's URDF, cold, over `python -c "import click, lxml.etree"` (the
  same interpreter): the floor under any Python command that uses click and lxml;
* `mcar check` of the 20,000-link trees (bench/generate.py) over check_urdf;
* `mcar build` of TurtleBot3, Husky and PR2, sandbox on, over the plain `xacro` command
  (packages found through an ament prefix, as in the build section); both write to
  /dev/null, which no run can call up to date, so every run expands. A third command runs
  in the same turns: xacro's own main() after `import click` in one interpreter, unsandboxed
  (the floor of any click tool that runs xacro), shown over xacro in a row of its own and
  under mcar's in mcar's row, so that what is mcar's own overhead is seen apart from
  click's import. A fourth, bench/sandboxed_xacro.py (xacro's main() in a child confined
  by mcar's sandbox, no click), is the floor of any runner that keeps the sandbox on.

Each row shows CPU time (user + system of the command and every process it waited for,
from wait4) and wall time; the target is judged on CPU, which the load of other processes
on a shared machine moves far less than wall time.
"""

from __future__ import annotations

import os
import re
import statistics
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import generate  # noqa: E402
from measure import (  # noqa: E402
    MCAR,
    REPO,
    RUN_TIMEOUT_S,
    XACRO,
    ament_prefix,
    exit_text,
    fmt_time,
    notes_for,
    progress,
)
from sim_robots_bench import real_robots  # noqa: E402

CHECK_TARGET, TREE_TARGET, BUILD_TARGET = 1.25, 1.2, 1.3
SANDBOXED_XACRO = Path(__file__).resolve().parent / "sandboxed_xacro.py"
PR2_FOLDER = "PR2+pr2_common"  # a checkout of PR2/pr2_common (pr2_description inside)


@dataclass
class Pairs:
    """Runs of a command (A) and its yardstick (B), in turn."""

    a_cpu: list[float] = field(default_factory=list)
    a_wall: list[float] = field(default_factory=list)
    b_cpu: list[float] = field(default_factory=list)
    b_wall: list[float] = field(default_factory=list)
    codes: list[tuple] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return bool(self.codes) and all(code == (0, 0) for code in self.codes)

    def ratio(self, kind: str) -> float:
        """The median of the pairs' A/B ratios of ``kind`` (cpu or wall)."""
        a, b = getattr(self, f"a_{kind}"), getattr(self, f"b_{kind}")
        return statistics.median(x / y for x, y in zip(a, b, strict=True) if y > 0)


def run_cpu(cmd: list[str], env=None) -> tuple[float, float, int | None]:
    """Wall and CPU seconds of one run of ``cmd`` (output to /dev/null), and its exit code
    (None: killed at the time bound). The CPU time is wait4's: the command's own and that
    of every process it waited for (mcar's xacro child)."""
    start = time.perf_counter()
    process = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               stdin=subprocess.DEVNULL, env=env)
    timer = threading.Timer(RUN_TIMEOUT_S, process.kill)
    timer.start()
    _pid, status, usage = os.wait4(process.pid, 0)
    wall = time.perf_counter() - start
    timed_out = not timer.is_alive()
    timer.cancel()
    process.returncode = code = os.waitstatus_to_exitcode(status)
    return wall, usage.ru_utime + usage.ru_stime, None if timed_out else code


def measure_pairs(a_cmd: list[str], b_cmd: list[str], runs: int, b_env=None,
                  budget_s: float = 120) -> Pairs:
    """One untimed run of each, then up to ``runs`` pairs (fewer past ``budget_s``)."""
    return measure_turns([(a_cmd, None), (b_cmd, b_env)], runs, budget_s)[0]


def measure_turns(commands: list[tuple[list[str], dict | None]], runs: int,
                  budget_s: float = 120) -> list[Pairs]:
    """One untimed run of each (command, env), then up to ``runs`` turns of all of them in
    order (fewer past ``budget_s``): the Pairs of every two, (0, 1), (0, 2) ... (1, 2) ...,
    each ratio taken turn by turn."""
    for cmd, env in commands:
        run_cpu(cmd, env=env)
    runs_of: list[list[tuple[float, float, int | None]]] = [[] for _ in commands]
    started = time.perf_counter()
    for _ in range(runs):
        for (cmd, env), done in zip(commands, runs_of, strict=True):
            done.append(run_cpu(cmd, env=env))
        if time.perf_counter() - started > budget_s or any(
                done[-1][2] is None for done in runs_of):
            break
    every = []
    for i, a_runs in enumerate(runs_of):
        for b_runs in runs_of[i + 1:]:
            pairs = Pairs()
            for (a_wall, a_cpu, a_code), (b_wall, b_cpu, b_code) in zip(a_runs, b_runs,
                                                                          strict=True):
                pairs.a_wall.append(a_wall)
                pairs.a_cpu.append(a_cpu)
                pairs.b_wall.append(b_wall)
                pairs.b_cpu.append(b_cpu)
                pairs.codes.append((a_code, b_code))
            every.append(pairs)
    return every


def _swapped(pairs: Pairs) -> Pairs:
    """The same runs with B as the command and A as its yardstick."""
    return Pairs(pairs.b_cpu, pairs.b_wall, pairs.a_cpu, pairs.a_wall,
                 [(b, a) for a, b in pairs.codes])


def _row(label: str, peer: str, pairs: Pairs, target: float | None,
         over_floor: Pairs | None = None) -> str:
    """One row of the table; ``target`` None: a yardstick's own row, judged on nothing;
    ``over_floor``: the same command over the click + xacro floor, said after its
    verdict."""
    if not pairs.ok:
        codes = exit_text([a for a, _ in pairs.codes]), exit_text([b for _, b in pairs.codes])
        return f"| {label} | {peer} | - | - | - | - | exit {codes[0]} / {codes[1]} | - |"
    cpu, wall = pairs.ratio("cpu"), pairs.ratio("wall")
    median = statistics.median
    verdict = "-" if target is None else (
        f"{'met' if cpu <= target else '**missed**'} (<= {target:g}x)")
    if over_floor is not None and over_floor.ok:
        verdict += f"; {over_floor.ratio('cpu'):.2f}x the click + xacro floor"
    return (f"| {label} | {peer} | {fmt_time(median(pairs.a_cpu))} / "
            f"{fmt_time(median(pairs.b_cpu))} | **{cpu:.2f}x** | "
            f"{fmt_time(median(pairs.a_wall))} / {fmt_time(median(pairs.b_wall))} | "
            f"{wall:.2f}x | {len(pairs.codes)} | {verdict} |")


def click_xacro_floor(python: str, path: Path) -> list[str]:
    """xacro's own main() run after ``import click`` in one interpreter, unsandboxed: what
    any click command that runs xacro costs at the least (xacro is run as its console
    script runs it)."""
    argv = ["xacro", str(path), "-o", os.devnull]
    return [python, "-c", f"import click, sys; sys.argv = {argv!r}; import xacro; "
            "sys.exit(xacro.main())"]


def _package_prefix(root: Path, folders: list[Path]) -> dict:
    """An environment in which the plain xacro command finds every package under
    ``folders`` the ROS 2 way, NAME from each package.xml (:func:`measure.ament_prefix`)."""
    packages: dict[str, Path] = {}
    for folder in folders:
        for manifest in sorted(folder.rglob("package.xml")):
            name = re.search(r"<name>\s*([^<\s]+)\s*</name>", manifest.read_text())
            if name:
                packages.setdefault(name.group(1), manifest.parent)
    return ament_prefix(root, packages)


def _beside_checkouts(name: str, env_name: str) -> Path | None:
    """$``env_name``, else the folder ``name`` beside this checkout's parent folder (or the
    main checkout's, for a git worktree), as sim_robots_bench finds the real robots."""
    if os.environ.get(env_name):
        return Path(os.environ[env_name])
    shared = real_robots(REPO)
    candidates = [REPO.parent / name]
    if shared is not None:
        candidates.append(shared.parent.parent / name)
    return next((c for c in candidates if c.is_dir()), None)


def _robots() -> tuple[list[tuple[str, Path, Path]], list[str]]:
    """(label, --package-path folder, robot file) of the robots found, and what is not."""
    found, missing = [], []
    shared = real_robots(REPO)
    if shared is None:
        missing.append("TurtleBot3 and Husky (no real-robots folder; set MCAR_REAL_ROBOTS)")
    else:
        found += [("TurtleBot3 burger (turtlebot3_burger.urdf)", shared,
                   shared / "turtlebot3_description" / "urdf" / "turtlebot3_burger.urdf"),
                  ("Husky (husky.urdf.xacro)", shared,
                   shared / "husky_description" / "urdf" / "husky.urdf.xacro")]
    pr2 = _beside_checkouts(f"vehicles/{PR2_FOLDER}", "MCAR_BENCH_PR2")
    if pr2 is None:
        missing.append(f"PR2 (no vehicles/{PR2_FOLDER} folder; set MCAR_BENCH_PR2 to a "
                       "checkout of PR2/pr2_common)")
    else:
        found.append(("PR2 (pr2.urdf.xacro)", pr2,
                      pr2 / "pr2_description" / "robots" / "pr2.urdf.xacro"))
    return found, missing


def section_floor(rows: list[str], work: Path, quick: bool) -> None:
    runs = 1 if quick else 15  # --quick: a smoke test, small trees, one pair each
    rows += ["## At the floor: mcar beside its yardsticks", "",
             "Issue 41's speed targets. Each mcar command runs in turn with its yardstick, "
             f"A B A B ... ({runs} pairs after one untimed run of each; fewer where a "
             "budget of two minutes runs out), and each ratio is the median of the pairs' "
             "ratios. *CPU*: user + system time of the command and every process it waited "
             "for (wait4), the figure the target is judged on: the load of other processes "
             "on a shared machine moves it far less than wall time. *mcar / peer*: the "
             "medians of each. `mcar check` of the car is over `python -c \"import click, "
             "lxml.etree\"` (the same interpreter); the trees over check_urdf; `mcar "
             "build` (sandbox on) over the plain `xacro` command, both to /dev/null (no "
             "run is a no-op), xacro finding the packages through an ament prefix. Each "
             "build runs in turn with a third command, `python -c \"import click, sys; "
             "sys.argv = [...]; import xacro; sys.exit(xacro.main())\"` (same interpreter "
             "and environment as xacro, unsandboxed): click's import and xacro's run, the "
             "floor of any click tool that runs xacro. Its row shows it over xacro; "
             "mcar's row ends with mcar's CPU over it, which is mcar's own overhead. A "
             "fourth command in the same turns, `python bench/sandboxed_xacro.py` (xacro's "
             "main() in a child forked and confined by mcar's sandbox, its output back "
             "through a pipe; no click, no checks), is the floor of any tool that keeps "
             "the sandbox on, shown over xacro in a row of its own.", "",
             "| mcar command | yardstick | CPU, mcar / peer | CPU ratio | wall, mcar / peer "
             "| wall ratio | pairs | target (CPU) |",
             "|---|---|---:|---:|---:|---:|---:|---|"]
    python = sys.executable
    car = work / "mobile_robot.urdf"
    subprocess.run([MCAR, "build", str(REPO / "urdf" / "mobile_robot.xacro"), "-o", str(car)],
                   check=True, capture_output=True)
    pairs = measure_pairs([MCAR, "check", str(car)],
                          [python, "-c", "import click, lxml.etree"], runs * 2)
    rows.append(_row("`mcar check` the car (mobile_robot.urdf)",
                     "`python -c \"import click, lxml.etree\"`", pairs, CHECK_TARGET))
    progress(f"floor: check the car {pairs.ratio('cpu') if pairs.ok else '-'}")
    size = 500 if quick else 20000
    for parts in generate.PARTS:
        tree = work / f"tree_{parts}_{size}.urdf"
        tree.write_text(generate.robot(size, "tree", parts))
        pairs = measure_pairs([MCAR, "check", str(tree)], ["check_urdf", str(tree)],
                              1 if quick else 7)
        rows.append(_row(f"`mcar check` {size:,}-link tree, {parts}", "`check_urdf`",
                         pairs, TREE_TARGET))
        progress(f"floor: tree {parts} {pairs.ratio('cpu') if pairs.ok else '-'}")
        tree.unlink()
    robots, missing = _robots()
    env = _package_prefix(work / "ament", [folder for _l, folder, _p in robots])
    for label, folder, path in robots:
        sandboxed_env = {**env, "MCAR_BENCH_READ_ROOTS": str(folder)}
        (mcar_floor, mcar_xacro, _mcar_sandboxed, floor_xacro, _floor_sandboxed,
         _xacro_sandboxed) = measure_turns(
            [([MCAR, "build", "--package-path", str(folder), str(path), "-o", os.devnull],
              None),
             (click_xacro_floor(python, path), env),
             ([XACRO, str(path), "-o", os.devnull], env),
             ([python, str(SANDBOXED_XACRO), str(path)], sandboxed_env)], runs)
        sandboxed_xacro = _swapped(_xacro_sandboxed)
        name = label.split(" (")[0]
        rows.append(_row(f"`mcar build` {label}", "`xacro`", mcar_xacro, BUILD_TARGET,
                         over_floor=mcar_floor))
        rows.append(_row(f"click + xacro, unsandboxed (the floor of any click tool), "
                         f"{name}", "`xacro`", floor_xacro, None))
        rows.append(_row(f"xacro in mcar's sandbox, no click (the floor of any sandboxed "
                         f"runner), {name}", "`xacro`", sandboxed_xacro, None))
        progress(f"floor: build {label} "
                 f"{mcar_xacro.ratio('cpu') if mcar_xacro.ok else '-'}, over the floor "
                 f"{mcar_floor.ratio('cpu') if mcar_floor.ok else '-'}, sandboxed xacro "
                 f"{sandboxed_xacro.ratio('cpu') if sandboxed_xacro.ok else '-'}")
    rows.append("")
    if missing:
        rows += ["Not measured: " + "; ".join(missing) + ".", ""]
    rows += notes_for("floor")
