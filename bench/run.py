"""mcar against the tools a user would use instead, on the same inputs, in one run.

    python bench/run.py [--quick] [-o docs/benchmarks.md] [SECTION...]

Every time is the median wall time of several runs of a whole command (a fresh process,
as in a shell script or CI) with its output going to /dev/null, and every ratio compares
two commands measured in the same run. Before the timed runs, each command runs once more
under GNU time for its peak resident memory, with its output piped into a hash, so the
table can say whether the peer and mcar printed the same bytes; every exit code is shown.
Peers: urdfdom's C++ check_urdf (Debian liburdfdom-tools) and the plain `xacro` command
(PyPI xacro, the same library mcar calls). The inputs are generated (bench/generate.py).
bench/notes.md holds the explanations printed under the tables (profiles of the misses).
"""

from __future__ import annotations

import argparse
import datetime
import hashlib
import importlib.metadata
import json
import os
import platform
import re
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import generate  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
BIN = Path(sys.executable).parent
MCAR = str(BIN / "mcar")
XACRO = str(BIN / "xacro")
GNU_TIME = "/usr/bin/time"
RUN_TIMEOUT_S = 180
NOTES = Path(__file__).resolve().parent / "notes.md"


def progress(text: str) -> None:
    print(f"bench: {text}", file=sys.stderr, flush=True)


# ---------------------------------------------------------------------------------------
# Running commands


@dataclass
class Result:
    """Timed runs of one command, and the one run that was watched for memory and output."""

    walls: list[float] = field(default_factory=list)
    codes: list[int] = field(default_factory=list)
    peak_mib: float | None = None
    digest: str | None = None

    @property
    def wall(self) -> float:
        return statistics.median(self.walls)

    @property
    def ok(self) -> bool:
        return all(code == 0 for code in self.codes)


def exit_text(codes) -> str:
    """Exit codes as shown in the tables: 0, 1, SIGSEGV, timeout."""
    names = []
    for code in dict.fromkeys(codes):
        if code is None:
            names.append("timeout")
        elif code < 0:
            try:
                names.append(signal.Signals(-code).name)
            except ValueError:
                names.append(f"signal {-code}")
        else:
            names.append(str(code))
    return ", ".join(names)


def run_timed(cmd: list[str], env=None, cwd=None) -> tuple[float, int | None]:
    """Wall seconds and exit code (negative: killed by that signal; None: timed out)."""
    start = time.perf_counter()
    process = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               stdin=subprocess.DEVNULL, env=env, cwd=cwd)
    # Popen.wait(timeout=...) polls with sleeps of up to 50 ms, which would round every
    # time up to its schedule; a blocking waitpid returns the moment the child exits.
    timer = threading.Timer(RUN_TIMEOUT_S, process.kill)
    timer.start()
    _pid, status = os.waitpid(process.pid, 0)
    wall = time.perf_counter() - start
    timed_out = not timer.is_alive()
    timer.cancel()
    process.returncode = code = os.waitstatus_to_exitcode(status)
    return wall, None if timed_out else code


def run_watched(cmd: list[str], env=None, cwd=None) -> tuple[float | None, int | None, str]:
    """Peak resident MiB (from GNU time), exit code, and SHA-256 of what cmd printed.

    The peak cannot come from this process's wait4(): a child forked from a big Python
    process starts with that process's resident size, and Linux keeps it as the child's
    peak across exec. GNU time is small, so the peak it reports is the command's own.
    """
    digest = hashlib.sha256()
    with tempfile.NamedTemporaryFile("r") as report:
        watched = [GNU_TIME, "-f", "%M", "-o", report.name, *cmd] if HAVE_GNU_TIME else cmd
        process = subprocess.Popen(watched, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                                   stdin=subprocess.DEVNULL, env=env, cwd=cwd)
        timer = threading.Timer(RUN_TIMEOUT_S, process.kill)
        timer.start()
        while chunk := process.stdout.read(1 << 20):
            digest.update(chunk)
        code = process.wait()
        timer.cancel()
        peak = None
        if HAVE_GNU_TIME:
            numbers = re.findall(r"^(\d+)$", report.read(), re.M)
            peak = int(numbers[-1]) / 1024 if numbers else None
            # GNU time exits with the command's code, or 128 + the signal that killed it.
            if code > 128 and "terminated by signal" in Path(report.name).read_text():
                code = -(code - 128)
    return peak, code, digest.hexdigest()


def measure(cmd: list[str], runs: int, env=None, cwd=None, budget_s: float = 60) -> Result:
    """One watched run, then ``runs`` timed runs (fewer if they exceed ``budget_s``)."""
    result = Result()
    result.peak_mib, code, result.digest = run_watched(cmd, env=env, cwd=cwd)
    result.codes.append(code)
    for _ in range(runs):
        wall, code = run_timed(cmd, env=env, cwd=cwd)
        result.walls.append(wall)
        result.codes.append(code)
        if sum(result.walls) > budget_s or code is None:
            break
    return result


def measure_rounds(commands: dict, runs: int, cwd=None) -> dict:
    """Like measure() for several commands, interleaved: one watched run of each, then
    ``runs`` rounds that run each command once, so that a change in the load of a shared
    machine falls on every command alike, not on whichever ran while it lasted."""
    results = {key: Result() for key in commands}
    for key, cmd in commands.items():
        results[key].peak_mib, code, results[key].digest = run_watched(cmd, cwd=cwd)
        results[key].codes.append(code)
    for _ in range(runs):
        for key, cmd in commands.items():
            wall, code = run_timed(cmd, cwd=cwd)
            results[key].walls.append(wall)
            results[key].codes.append(code)
    return results


def _gnu_time_works() -> bool:
    try:
        return subprocess.run([GNU_TIME, "-f", "%M", "true"], capture_output=True,
                              timeout=10).returncode == 0
    except (OSError, subprocess.TimeoutExpired):
        return False


HAVE_GNU_TIME = _gnu_time_works()


# ---------------------------------------------------------------------------------------
# Formatting


def fmt_time(seconds: float) -> str:
    if seconds < 0.01:
        return f"{seconds * 1000:.1f} ms"
    return f"{seconds * 1000:.0f} ms" if seconds < 10 else f"{seconds:.1f} s"


def fmt_peak(result: Result) -> str:
    return "-" if result.peak_mib is None else f"{result.peak_mib:.0f} MiB"


def time_cell(result: Result) -> str:
    text = fmt_time(result.wall)
    return text if result.ok else f"{text} (exit {exit_text(result.codes)})"


def speedup(ours: Result, theirs: Result) -> float | None:
    """Peer time / mcar time, or None when either did not run cleanly."""
    if not (ours.ok and theirs.ok) or ours.wall <= 0:
        return None
    return theirs.wall / ours.wall


def fmt_ratio(value: float | None) -> str:
    return "-" if value is None else f"{value:.2f}x"


def verdict(met: bool | None) -> str:
    return {True: "met", False: "**missed**", None: "-"}[met]


def notes_for(section: str) -> list[str]:
    """The hand-written explanation of a section (bench/notes.md, `<!-- NAME -->` blocks)."""
    if not NOTES.is_file():
        return []
    blocks = re.split(r"^<!-- (\w+) -->\n", NOTES.read_text(encoding="utf-8"), flags=re.M)
    texts = dict(zip(blocks[1::2], blocks[2::2], strict=True))
    text = texts.get(section, "").strip()
    return [text, ""] if text else []


def machine() -> str:
    cpu = "unknown CPU"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    memory = ""
    try:
        kib = int(Path("/proc/meminfo").read_text().split()[1])
        memory = f", {kib / 1024 / 1024:.0f} GiB RAM"
    except (OSError, ValueError, IndexError):
        pass
    system = platform.platform()
    try:
        release = dict(line.split("=", 1) for line in
                       Path("/etc/os-release").read_text().splitlines() if "=" in line)
        system = f"{release['PRETTY_NAME'].strip(chr(34))}, Linux {platform.release()}"
    except (OSError, KeyError):
        pass
    return f"{cpu}, {os.cpu_count()} cores{memory}; {system}; Python {platform.python_version()}"


def versions() -> str:
    parts = []
    try:
        urdfdom = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "liburdfdom-tools"],
                                 capture_output=True, text=True, timeout=10).stdout.strip()
        if urdfdom:
            parts.append(f"check_urdf (liburdfdom-tools) {urdfdom}")
    except (OSError, subprocess.TimeoutExpired):
        pass
    for name in ("mcar", "xacro", "lxml", "click", "mujoco", "distributed", "pandas"):
        try:
            parts.append(f"{name} {importlib.metadata.version(name)}")
        except importlib.metadata.PackageNotFoundError:
            pass
    return ", ".join(parts)


# ---------------------------------------------------------------------------------------
# Sections


def section_check(rows: list[str], work: Path, quick: bool) -> None:
    sizes = [10, 100, 1000] if quick else [10, 100, 1000, 5000, 20000]
    rows += ["## `mcar check` vs `check_urdf`", "",
             "Generated robots (`bench/generate.py`): every link with an inertial, a visual "
             "and a collision, revolute/continuous/prismatic/fixed joints with origins, axes, "
             "limits and dynamics. *distinct*: every number differs (a CAD export); "
             "*repeated*: copies of four part models. *tree*: each link hangs from a random "
             "earlier one (about 2.7 ln n deep); *chain*: one line, whose check_urdf tree "
             "print grows as n² (4 spaces more per generation: 800 MB at 20,000). "
             "Target: mcar faster from 1,000 links up, at least 2x at 20,000.", "",
             "| robot | links | size | check_urdf | mcar check | speed-up | check_urdf peak "
             "| mcar peak | exit codes (check_urdf / mcar) | same output | target |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---|---|---|"]
    for shape in generate.SHAPES:
        for parts in generate.PARTS:
            for n in sizes:
                path = work / f"{shape}_{parts}_{n}.urdf"
                path.write_text(generate.robot(n, shape, parts))
                runs = 3 if quick or n >= 20000 else (5 if n >= 5000 else 9)
                peer = measure(["check_urdf", str(path)], runs, budget_s=40)
                ours = measure([MCAR, "check", str(path)], runs, budget_s=40)
                ratio = speedup(ours, peer)
                target = None if n < 1000 else (
                    ratio is not None and ratio >= (2.0 if n >= 20000 else 1.0))
                same = "yes" if peer.digest == ours.digest else "**no**"
                rows.append(
                    f"| {shape}, {parts} | {n:,} | {path.stat().st_size / 1e6:.1f} MB | "
                    f"{time_cell(peer)} | {time_cell(ours)} | {fmt_ratio(ratio)} | "
                    f"{fmt_peak(peer)} | {fmt_peak(ours)} | {exit_text(peer.codes)} / "
                    f"{exit_text(ours.codes)} | {same} | {verdict(target)} |")
                progress(f"check {shape} {parts} {n}: check_urdf {fmt_time(peer.wall)}, "
                         f"mcar {fmt_time(ours.wall)}")
                path.unlink()
    rows.append("")
    rows += notes_for("check")


def _ament_prefix(root: Path) -> dict:
    """Let the plain xacro command find mobile_car_description the ROS 2 way (ament index)."""
    shim = root / "shim" / "ament_index_python"
    shim.mkdir(parents=True)
    (shim / "__init__.py").write_text("")
    (shim / "packages.py").write_text(
        "import os\n"
        "def get_package_share_directory(name):\n"
        "    for prefix in os.environ.get('AMENT_PREFIX_PATH', '').split(os.pathsep):\n"
        "        share = os.path.join(prefix, 'share', name)\n"
        "        if os.path.isfile(os.path.join(share, 'package.xml')):\n"
        "            return share\n"
        "    raise LookupError(name)\n")
    share = root / "prefix" / "share"
    share.mkdir(parents=True)
    (share / "mobile_car_description").symlink_to(REPO)
    env = dict(os.environ)
    env["PYTHONPATH"] = str(root / "shim")
    env["AMENT_PREFIX_PATH"] = str(root / "prefix")
    return env


_BANNER_RE = re.compile(rb"<!-- \|\s+This document was autogenerated by xacro from .*?-->")


def _same_urdf(peer_cmd, ours_cmd, work: Path, env) -> bool:
    """True if both commands write the same URDF, apart from the banner naming the input."""
    outputs = []
    for name, cmd in (("xacro.urdf", peer_cmd), ("mcar.urdf", ours_cmd)):
        target = work / name
        subprocess.run([*cmd, "-o", str(target)], env=env if cmd is peer_cmd else None,
                       capture_output=True, timeout=RUN_TIMEOUT_S)
        outputs.append(_BANNER_RE.sub(b"", target.read_bytes()) if target.exists() else None)
        target.unlink(missing_ok=True)
    return outputs[0] is not None and outputs[0] == outputs[1]


def section_build(rows: list[str], work: Path, quick: bool) -> None:
    rows += ["## `mcar build` vs `xacro`", "",
             "Both write the URDF to /dev/null; xacro finds the package through an ament "
             "index prefix (as in ROS 2), mcar through its own package search. *Same URDF*: "
             "both outputs byte for byte equal but for xacro's banner comment, which names the "
             "input. Target: mcar at most 1.2x xacro's time.", "",
             "| input | xacro | mcar build | mcar / xacro | xacro peak | mcar peak | "
             "same URDF | target |", "|---|---:|---:|---:|---:|---:|---|---|"]
    env = _ament_prefix(work / "ament")
    macros = work / "macros_500.xacro"
    macros.write_text(generate.macros(500))
    inputs = [("complete robot (mobile_robot.xacro)", REPO / "urdf" / "mobile_robot.xacro"),
              ("tutorial car (tutorial/04_xacro.xacro)",
               REPO / "urdf" / "tutorial" / "04_xacro.xacro"),
              ("500 macro calls (generated)", macros)]
    runs = 3 if quick else 11
    for label, path in inputs:
        peer_cmd, ours_cmd = [XACRO, str(path)], [MCAR, "build", str(path)]
        peer = measure([*peer_cmd, "-o", os.devnull], runs, env=env)
        ours = measure([*ours_cmd, "-o", os.devnull], runs)
        ratio = ours.wall / peer.wall if peer.ok and ours.ok else None
        same = "yes" if _same_urdf(peer_cmd, ours_cmd, work, env) else "**no**"
        rows.append(f"| {label} | {time_cell(peer)} | {time_cell(ours)} | "
                    f"{'-' if ratio is None else f'{ratio:.2f}'} | {fmt_peak(peer)} | "
                    f"{fmt_peak(ours)} | {same} | "
                    f"{verdict(None if ratio is None else ratio <= 1.2)} |")
        progress(f"build {label}: xacro {fmt_time(peer.wall)}, mcar {fmt_time(ours.wall)}")
    rows.append("")
    rows += notes_for("build")


def section_startup(rows: list[str], work: Path, quick: bool) -> None:
    robot = work / "mobile_robot.urdf"
    subprocess.run([MCAR, "build", str(REPO / "urdf" / "mobile_robot.xacro"), "-o", str(robot)],
                   check=True)
    links = robot.read_text(encoding="utf-8").count("<link ")
    rows += ["## Start-up", "",
             f"The complete car ({links} links). Targets: `mcar --version` under 150 ms, "
             "`mcar check` of the complete robot under 250 ms. The `python -c` rows are the "
             "floor any Python command stands on.", "",
             "| command | median | peak memory | exit | target |", "|---|---:|---:|---|---|"]
    runs = 5 if quick else 21
    python = sys.executable
    commands = [
        ("python -c pass", [python, "-c", "pass"], None),
        ("python -c 'import click'", [python, "-c", "import click"], None),
        ("python -c 'import click, lxml.etree'", [python, "-c", "import click, lxml.etree"],
         None),
        ("mcar --version", [MCAR, "--version"], 0.150),
        ("check_urdf mobile_robot.urdf", ["check_urdf", str(robot)], None),
        ("mcar check mobile_robot.urdf", [MCAR, "check", str(robot)], 0.250),
        ("mcar build mobile_robot.xacro", [MCAR, "build", str(REPO / "urdf" / "mobile_robot.xacro"),
                                           "-o", os.devnull], None),
    ]
    for label, cmd, limit in commands:
        result = measure(cmd, runs)
        met = None if limit is None else (result.ok and result.wall < limit)
        rows.append(f"| `{label}` | {time_cell(result)} | {fmt_peak(result)} | "
                    f"{exit_text(result.codes)} | {verdict(met)} |")
    rows.append("")
    rows += notes_for("startup")
    progress("start-up measured")


def section_batch(rows: list[str], work: Path, quick: bool) -> None:
    count = 100 if quick else 1000
    folder = work / "batch"
    folder.mkdir()
    names = []
    for i in range(count):
        name = f"robot_{i:04d}.urdf"
        (folder / name).write_text(generate.robot(5 + i % 10, "tree", "distinct", seed=i))
        names.append(name)
    # The expected output of one mcar call: each file's check_urdf output under a header.
    expected = hashlib.sha256()
    codes = []
    start = time.perf_counter()
    for name in names:
        done = subprocess.run(["check_urdf", name], capture_output=True, cwd=folder,
                              timeout=RUN_TIMEOUT_S)
        codes.append(done.returncode)
        expected.update(f"==> {name} <==\n".encode() + done.stdout)
    peer = time.perf_counter() - start
    ours = measure([MCAR, "check", *names], 3, cwd=folder)
    same = "yes" if ours.digest == expected.hexdigest() else "**no**"
    ratio = peer / ours.wall if ours.ok and not any(codes) else None
    rows += ["## Batch", "",
             f"{count:,} small robots (5 to 14 links, every number distinct): one `mcar check` "
             f"call with every file vs {count:,} `check_urdf` processes (a CI job checking a "
             "folder). *Same output*: mcar's stdout equals each file's check_urdf output "
             "under a `==> FILE <==` header.", "",
             "| check_urdf x N | mcar check (one call) | speed-up | exit codes "
             "(check_urdf / mcar) | same output |", "|---:|---:|---:|---|---|",
             f"| {fmt_time(peer)} | {time_cell(ours)} | {fmt_ratio(ratio)} | "
             f"{exit_text(codes)} / {exit_text(ours.codes)} | {same} |", ""]
    rows += notes_for("batch")
    progress(f"batch: check_urdf x {count} {fmt_time(peer)}, mcar {fmt_time(ours.wall)}")


def section_folder(rows: list[str], work: Path, quick: bool) -> None:
    """`mcar check` and `mcar build` of one folder of N one-link robots, at N and 2N: both
    linear in the files (build checked each output against every input: 1,000 robots
    took ~45 s)."""
    sizes = (25, 50) if quick else (500, 1000)
    rows += ["## A folder of robots", "",
             "`mcar check DIR` and `mcar build DIR -o OUT/` of a folder of one-link robots, "
             "at two sizes. A plain URDF is only read by check, and build expands it in "
             "its own process (nothing in it can run); a `.xacro` goes through the "
             "sandboxed xacro child (one fork per file) in both. Target: linear, the time "
             "per file at 2N at most 1.3x that at N.", "",
             "| robots | mcar check | mcar build | build / check | build per file | exit "
             "(check / build) | target |", "|---|---:|---:|---:|---:|---|---|"]
    xacro_namespace = ' xmlns:xacro="http://www.ros.org/wiki/xacro"'
    for kind, suffix, namespace in (("URDF", ".urdf", ""),
                                    ("xacro", ".urdf.xacro", xacro_namespace)):
        per_file = None
        for count in sizes:
            folder = work / f"{kind}_{count}"
            folder.mkdir()
            for i in range(count):
                (folder / f"r{i:04d}{suffix}").write_text(
                    f'<robot name="r{i}"{namespace}>\n  <link name="base"/>\n</robot>\n')
            results = measure_rounds(
                {"check": [MCAR, "check", str(folder)],
                 "build": [MCAR, "build", str(folder), "-o", f"{work / 'out' / folder.name}/"]},
                3 if quick else 5)
            check, build = results["check"], results["build"]
            ratio = build.wall / check.wall if check.ok and build.ok else None
            met = None if per_file is None or not build.ok else (
                build.wall / count <= 1.3 * per_file)
            per_file = build.wall / count
            rows.append(f"| {count:,} {kind} | {time_cell(check)} | {time_cell(build)} | "
                        f"{'-' if ratio is None else f'{ratio:.1f}'} | {fmt_time(per_file)} | "
                        f"{exit_text(check.codes)} / {exit_text(build.codes)} | "
                        f"{verdict(met)} |")
            progress(f"folder {count} {kind}: check {fmt_time(check.wall)}, "
                     f"build {fmt_time(build.wall)}")
    rows.append("")
    rows += notes_for("folder")


def section_render(rows: list[str], work: Path, quick: bool) -> None:
    out = work / "renders"
    runs = 1 if quick else 3
    walls, codes = [], []
    for _ in range(runs):
        shutil.rmtree(out, ignore_errors=True)
        wall, code = run_timed([MCAR, "render", "--force", "-o", str(out), "--quiet"], cwd=work)
        walls.append(wall)
        codes.append(code)
    images = [p for p in out.rglob("*.png") if p.name != "index.png"]
    total = statistics.median(walls)
    one = measure([MCAR, "render", str(REPO / "urdf" / "wheel" / "test_wheel.urdf.xacro"),
                   "-o", str(work / "wheel.png"), "--force"], 3 if quick else 7)
    robot = measure([MCAR, "render", str(REPO / "urdf" / "mobile_robot.xacro"),
                     "-o", str(work / "robot.png"), "--force"], 3 if quick else 7)
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
    """`mcar render` and `mcar ci` of the bundled package with nothing changed (the
    pre-commit hook's case), and with one part file edited (only its pictures redrawn)."""
    package = work / "mobile_car_description"
    for name in ("urdf", "meshes"):
        shutil.copytree(REPO / name, package / name)
    shutil.copy(REPO / "package.xml", package / "package.xml")
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
        ("`mcar render`, motor.xacro edited (2 of 13 pictures redrawn)",
         timed_after(edit_motor, [MCAR, "render"]), None),
        ("`mcar ci`, motor.xacro edited (4 of 15 files built again)",
         timed_after(edit_motor, [MCAR, "ci"]), None),
        ("`mcar render --force` (all 13 drawn)", measure([MCAR, "render", "--force"],
                                                         3 if quick else 5, cwd=package), None),
    ]
    rows += ["## Nothing changed", "",
             "The bundled package, rendered and built once, then run again (the pre-commit "
             "hook's `mcar ci`). Targets: no-op `mcar render` under 200 ms, no-op `mcar ci` "
             "under 300 ms (before: 1.5-2.4 s). *x --version*: the time over `mcar --version` "
             f"in this run ({fmt_time(version.wall)}).", "",
             "| what | median | x --version | exit | target |", "|---|---:|---:|---|---|"]
    rows += rows_over_version(cases, version)
    rows.append("")
    rows += notes_for("noop")
    progress("no-op measured")


def section_sim(rows: list[str], work: Path, quick: bool) -> None:
    """A cold `mcar sim` of the car (a fresh process: MuJoCo imported, the model made,
    drop, drive and spin run), against `mcar --version` and the bare MuJoCo import."""
    runs = 5 if quick else 11
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


def section_sweep(rows: list[str], work: Path, quick: bool) -> None:
    """`mcar sweep` with 1 and 2 local workers and on a 2-worker Dask cluster, against a
    shell loop of `mcar sim` over the same points; then where one point's time goes."""
    import sweep_bench

    robot = str(REPO / "urdf" / "mobile_robot.xacro")
    runs = 1 if quick else 5
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


def section_meshes(rows: list[str], work: Path, quick: bool) -> None:
    import mesh_check_bench

    mesh_check_bench.section(rows, work, quick, sys.modules[__name__])


SECTIONS = {"check": section_check, "build": section_build, "startup": section_startup,
            "batch": section_batch, "folder": section_folder, "render": section_render,
            "noop": section_noop, "sim": section_sim, "sweep": section_sweep,
            "meshes": section_meshes}
NEEDS_CHECK_URDF = {"check", "startup", "batch"}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="smaller inputs, fewer runs (a smoke test; numbers are rough)")
    parser.add_argument("-o", "--output", type=Path,
                        help="where to write the tables (default: docs/benchmarks.md; with "
                             "--quick, build/benchmarks-quick.md)")
    parser.add_argument("sections", nargs="*", metavar="SECTION",
                        help=f"only these sections ({', '.join(SECTIONS)}); default all")
    args = parser.parse_args()
    unknown = [s for s in args.sections if s not in SECTIONS]
    if unknown:
        parser.error(f"unknown section(s) {', '.join(unknown)}; choose from {', '.join(SECTIONS)}")
    chosen = args.sections or list(SECTIONS)
    if NEEDS_CHECK_URDF & set(chosen) and shutil.which("check_urdf") is None:
        print("bench: check_urdf not found (Debian package liburdfdom-tools; `make bench` "
              "installs it)", file=sys.stderr)
        return 2
    output = args.output or (REPO / "build" / "benchmarks-quick.md" if args.quick
                             else REPO / "docs" / "benchmarks.md")
    rows = ["# Benchmarks", "",
            f"Measured {datetime.date.today().isoformat()} by `make bench` "
            f"(`bench/run.py{' --quick' if args.quick else ''}"
            f"{' ' + ' '.join(args.sections) if args.sections else ''}`) on: {machine()}.",
            "", f"Versions: {versions()}.", "",
            "Times are medians of repeated whole-process runs, output to /dev/null. Peak "
            "memory is the process's maximum resident set (GNU time). Speed-up = peer time / "
            "mcar time (above 1: mcar is faster). An exit code other than 0 is shown next to "
            "the time, and no ratio is computed from a failed run.", ""]
    if not HAVE_GNU_TIME:
        rows += ["(GNU time was not found at /usr/bin/time: no peak memory.)", ""]
    started = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="mcar-bench-") as tmp:
        for name in chosen:
            section_start = time.perf_counter()
            folder = Path(tmp) / name
            folder.mkdir()
            SECTIONS[name](rows, folder, args.quick)
            progress(f"{name} done in {time.perf_counter() - section_start:.0f} s")
    rows.append(f"Whole run: {time.perf_counter() - started:.0f} s.")
    text = "\n".join(rows) + "\n"
    output.parent.mkdir(parents=True, exist_ok=True)
    output.write_text(text, encoding="utf-8")
    print(text)
    progress(f"wrote {output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
