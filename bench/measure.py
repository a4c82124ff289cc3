"""How bench/run.py measures and reports: whole commands run as a user runs them (a fresh
process, output to /dev/null), timed, watched for peak memory (GNU time) and for what they
print; and the formatting every section's table shares."""

from __future__ import annotations

import hashlib
import importlib.metadata
import os
import platform
import re
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
    """One watched run, then ``runs`` timed runs (fewer if they exceed ``budget_s``);
    with ``runs`` 0 (a --quick smoke test) the watched run is the one timed."""
    result = Result()
    started = time.perf_counter()
    result.peak_mib, code, result.digest = run_watched(cmd, env=env, cwd=cwd)
    result.codes.append(code)
    if runs == 0:
        result.walls.append(time.perf_counter() - started)
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
        started = time.perf_counter()
        results[key].peak_mib, code, results[key].digest = run_watched(cmd, cwd=cwd)
        results[key].codes.append(code)
        if runs == 0:  # --quick: the watched run is the one timed
            results[key].walls.append(time.perf_counter() - started)
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




def ament_prefix(root: Path, packages: dict) -> dict:
    """An environment in which the plain xacro command finds ``packages`` (name -> folder)
    the ROS 2 way: ``$(find)`` asks ament_index_python, here a shim of that module, and a
    prefix whose share/NAME links each package's folder."""
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
    for name, folder in packages.items():
        (share / name).symlink_to(folder)
    return {**os.environ, "PYTHONPATH": str(root / "shim"),
            "AMENT_PREFIX_PATH": str(root / "prefix")}
