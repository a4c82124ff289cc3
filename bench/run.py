"""mcar against the tools a user would use instead, on the same inputs, in one run.

    python bench/run.py [--quick] [-o docs/benchmarks.md]

Every figure is the median wall time of several runs of a whole command (a fresh process,
as in a shell script or CI), with the peak resident memory of that process, and the ratio
to its peer measured in the same run. Peers: urdfdom's C++ check_urdf (Debian
liburdfdom-tools) and the plain `xacro` command (PyPI xacro, the same library mcar calls).
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import generate  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
BIN = Path(sys.executable).parent
MCAR = str(BIN / "mcar")
XACRO = str(BIN / "xacro")


def run_once(cmd: list[str], env=None, cwd=None) -> tuple[float, int, int]:
    """(wall seconds, peak RSS in MiB, exit code) of one run of cmd, output discarded."""
    start = time.perf_counter()
    process = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               stdin=subprocess.DEVNULL, env=env, cwd=cwd)
    _pid, status, usage = os.wait4(process.pid, 0)
    wall = time.perf_counter() - start
    return wall, usage.ru_maxrss // 1024, os.waitstatus_to_exitcode(status)


def measure(cmd: list[str], runs: int, env=None, cwd=None, timeout_s: float = 120) -> dict:
    """Median wall time and peak memory over runs; stops early when one run is very slow."""
    walls, peaks, codes = [], [], set()
    for _ in range(runs):
        wall, peak, code = run_once(cmd, env=env, cwd=cwd)
        walls.append(wall)
        peaks.append(peak)
        codes.add(code)
        if wall * runs > timeout_s:
            break
    return {"wall": statistics.median(walls), "rss": max(peaks), "codes": codes,
            "runs": len(walls)}


def fmt_time(seconds: float) -> str:
    return f"{seconds * 1000:.0f} ms" if seconds < 10 else f"{seconds:.1f} s"


def ratio(ours: float, theirs: float) -> str:
    return f"{theirs / ours:.2f}x" if ours > 0 else "-"


def exit_note(result: dict) -> str:
    codes = sorted(result["codes"])
    return "" if codes == [0] else f" (exit {','.join(map(str, codes))})"


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
    return (f"{cpu}, {os.cpu_count()} cores{memory}; {platform.platform()}; "
            f"Python {platform.python_version()}")


def section_check(rows: list[str], work: Path, quick: bool) -> None:
    rows += ["## `mcar check` vs `check_urdf`", "",
             "Generated URDFs (box visual and inertial on every link; `bench/generate.py`). "
             "Target: mcar faster from 1,000 links up, at least 2x at 20,000.", "",
             "| input | links | check_urdf | mcar check | speed-up | check_urdf peak | "
             "mcar peak |", "|---|---:|---:|---:|---:|---:|---:|"]
    sizes = [10, 100, 1000, 5000] + ([] if quick else [20000])
    for shape in ("tree", "chain"):
        for n in sizes:
            path = work / f"{shape}_{n}.urdf"
            path.write_text(getattr(generate, shape)(n))
            runs = 5 if n <= 5000 else 3
            peer = measure(["check_urdf", str(path)], runs)
            ours = measure([MCAR, "check", str(path)], runs)
            rows.append(f"| {shape} | {n:,} | {fmt_time(peer['wall'])}{exit_note(peer)} | "
                        f"{fmt_time(ours['wall'])}{exit_note(ours)} | "
                        f"{ratio(ours['wall'], peer['wall'])} | {peer['rss']} MiB | "
                        f"{ours['rss']} MiB |")
    rows.append("")


def _ament_shim(root: Path) -> dict:
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


def section_build(rows: list[str], work: Path, quick: bool) -> None:
    rows += ["## `mcar build` vs `xacro`", "",
             "Both write the URDF to /dev/null; xacro finds the package through an ament "
             "index prefix (as in ROS 2), mcar through its own package search. "
             "Target: mcar at most 1.2x xacro's time.", "",
             "| input | xacro | mcar build | mcar / xacro |", "|---|---:|---:|---:|"]
    env = _ament_shim(work / "ament")
    macros = work / "macros_500.xacro"
    macros.write_text(generate.macros(500))
    inputs = [("complete robot (mobile_robot.xacro)", REPO / "urdf" / "mobile_robot.xacro"),
              ("tutorial car (04_xacro.xacro)", REPO / "urdf" / "tutorial" / "04_xacro.xacro"),
              ("500 macro calls", macros)]
    runs = 5 if quick else 11
    for label, path in inputs:
        peer = measure([XACRO, str(path), "-o", os.devnull], runs, env=env)
        ours = measure([MCAR, "build", str(path), "-o", os.devnull], runs)
        rows.append(f"| {label} | {fmt_time(peer['wall'])}{exit_note(peer)} | "
                    f"{fmt_time(ours['wall'])}{exit_note(ours)} | "
                    f"{ours['wall'] / peer['wall']:.2f} |")
    rows.append("")


def section_startup(rows: list[str], work: Path, quick: bool) -> None:
    robot = work / "mobile_robot.urdf"
    subprocess.run([MCAR, "build", str(REPO / "urdf" / "mobile_robot.xacro"), "-o", str(robot)],
                   check=True)
    rows += ["## Cold start", "",
             "Targets: `mcar --version` under 150 ms, `mcar check` of the complete robot "
             "under 250 ms.", "",
             "| command | median | peak memory |", "|---|---:|---:|"]
    runs = 7 if quick else 21
    commands = [("python -c pass", [sys.executable, "-c", "pass"]),
                ("mcar --version", [MCAR, "--version"]),
                ("check_urdf mobile_robot.urdf", ["check_urdf", str(robot)]),
                ("mcar check mobile_robot.urdf", [MCAR, "check", str(robot)]),
                ("mcar build mobile_robot.xacro", [MCAR, "build",
                                                   str(REPO / "urdf" / "mobile_robot.xacro"),
                                                   "-o", os.devnull])]
    for label, cmd in commands:
        result = measure(cmd, runs)
        rows.append(f"| `{label}` | {fmt_time(result['wall'])}{exit_note(result)} | "
                    f"{result['rss']} MiB |")
    rows.append("")


def section_batch(rows: list[str], work: Path, quick: bool) -> None:
    count = 200 if quick else 1000
    folder = work / "batch"
    folder.mkdir()
    files = []
    for i in range(count):
        path = folder / f"robot_{i:04d}.urdf"
        path.write_text(generate.tree(5 + i % 10, seed=i))
        files.append(str(path))
    start = time.perf_counter()
    for path in files:
        subprocess.run(["check_urdf", path], stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
    peer = time.perf_counter() - start
    ours = measure([MCAR, "check", *files], 3)
    rows += ["## Batch", "",
             f"{count:,} small URDFs (5 to 14 links): one `mcar check` call with every file "
             f"vs {count:,} `check_urdf` processes.", "",
             "| check_urdf x N | mcar check (one call) | speed-up |", "|---:|---:|---:|",
             f"| {fmt_time(peer)} | {fmt_time(ours['wall'])}{exit_note(ours)} | "
             f"{ratio(ours['wall'], peer)} |", ""]


def section_render(rows: list[str], work: Path, quick: bool) -> None:
    out = work / "renders"
    runs = 1 if quick else 3
    walls = []
    for _ in range(runs):
        shutil.rmtree(out, ignore_errors=True)
        wall, peak, code = run_once([MCAR, "render", "--force", "-o", str(out), "--quiet"],
                                    cwd=work)
        walls.append(wall)
    images = [p for p in out.rglob("*.png") if p.name != "index.png"]
    one = measure([MCAR, "render", str(REPO / "urdf" / "wheel" / "test_wheel.urdf.xacro"),
                   "-o", str(work / "wheel.png"), "--force"], 5 if quick else 9)
    robot = measure([MCAR, "render", str(REPO / "urdf" / "mobile_robot.xacro"),
                     "-o", str(work / "robot.png"), "--force"], 5 if quick else 9)
    total = statistics.median(walls)
    rows += ["## `mcar render`", "",
             "800x600 PNGs through Mesa's llvmpipe (no GPU). Target: every part, step and the "
             "complete robot, cold, in one call, under 3 s.", "",
             "| what | median |", "|---|---:|",
             f"| all {len(images)} images + contact sheet, one call{' (exit %d)' % code if code else ''}"
             f" | {fmt_time(total)} ({len(images) / total:.1f} images/s) |",
             f"| one part (wheel), whole process | {fmt_time(one['wall'])}{exit_note(one)} |",
             f"| complete robot, whole process | {fmt_time(robot['wall'])}{exit_note(robot)} |",
             ""]


SECTIONS = {"check": section_check, "build": section_build, "startup": section_startup,
            "batch": section_batch, "render": section_render}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller inputs, fewer runs")
    parser.add_argument("-o", "--output", default=str(REPO / "docs" / "benchmarks.md"))
    parser.add_argument("sections", nargs="*", metavar="SECTION",
                        help=f"only these sections ({', '.join(SECTIONS)}); default all")
    args = parser.parse_args()
    unknown = [s for s in args.sections if s not in SECTIONS]
    if unknown:
        parser.error(f"unknown section(s) {', '.join(unknown)}; choose from {', '.join(SECTIONS)}")
    if shutil.which("check_urdf") is None:
        print("bench: check_urdf not found (Debian package liburdfdom-tools)", file=sys.stderr)
        return 2
    chosen = args.sections or list(SECTIONS)
    rows = ["# Benchmarks", "",
            f"Measured {datetime.date.today().isoformat()} by `make bench` "
            f"(`bench/run.py{' --quick' if args.quick else ''}`) on: {machine()}.", "",
            "Medians of repeated whole-process runs; peak memory is the process's maximum "
            "resident set. Speed-up = peer time / mcar time (above 1: mcar is faster).", ""]
    started = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="mcar-bench-") as tmp:
        for name in chosen:
            section_start = time.perf_counter()
            SECTIONS[name](rows, Path(tmp), args.quick)
            print(f"bench: {name} done in {time.perf_counter() - section_start:.1f} s",
                  file=sys.stderr)
    rows.append(f"Whole run: {time.perf_counter() - started:.0f} s.")
    text = "\n".join(rows) + "\n"
    Path(args.output).parent.mkdir(parents=True, exist_ok=True)
    Path(args.output).write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
