"""The real ROS 1 tools around a launched display.launch (roslaunch, robot_state_publisher,
the joint state publishers and RViz under Xvfb) and what they publish, for tests/ros/.

Each test module launches once (a module-scoped fixture) and its tests read what that
launch gave: the probe's JSON (tf_probe.py, run by Debian's python3) and a screenshot of
RViz. A launch is isolated for a parallel run: its own master port and display number
(both chosen free), its own HOME, ROS_HOME and ROS_LOG_DIR, its processes in process
groups of their own, every process below them noted by pid, all stopped at the end and
killed if they linger, even when a test fails. Nothing is installed here: `make test`
installs the Debian packages; without them the tests that launch skip, naming them.
"""

from __future__ import annotations

import contextlib
import functools
import json
import os
import re
import select
import shutil
import signal
import socket
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from conftest import REPO

HERE = Path(__file__).resolve().parent
DEBIAN_PYTHON = "/usr/bin/python3"
SCREEN = (1000, 640)  # pixels: rviz/urdf.rviz's window, at 0,0
SECONDS = 60  # every wait for the launched graph is bounded by this
STOP_SECONDS = 60  # everything must be gone this long after the stop begins
# Where a person looks at the picture the README shows (MCAR_SCREENSHOT_DIR=docs).
SCREENSHOT_DIR = os.environ.get("MCAR_SCREENSHOT_DIR")


def debian_packages() -> str:
    """What `make test` installs for these tests: the Makefile's ROS_APT_PACKAGES, xvfb."""
    makefile = (REPO / "Makefile").read_text().replace("\\\n", " ")
    listed = re.search(r"^ROS_APT_PACKAGES\s*:=\s*(.+)$", makefile, re.M).group(1).split()
    return " ".join([*listed, "xvfb"])


@functools.cache
def missing_ros() -> str | None:
    """Why the ROS tests cannot run here, or None."""
    absent = [tool for tool in ("roslaunch", "rospack", "rviz", "Xvfb")
              if shutil.which(tool) is None]
    if not absent and os.path.exists(DEBIAN_PYTHON):
        modules = ("rospy, tf2_ros, joint_state_publisher, joint_state_publisher_gui, "
                   "python_qt_binding")
        found = subprocess.run([DEBIAN_PYTHON, "-c", f"import {modules}"],
                               capture_output=True, text=True)
        if found.returncode != 0:
            absent.append(f"{DEBIAN_PYTHON}'s {found.stderr.strip().splitlines()[-1]}")
    elif not os.path.exists(DEBIAN_PYTHON):
        absent.append(DEBIAN_PYTHON)
    if not absent:
        return None
    return (f"ROS 1 and Xvfb are not installed ({', '.join(absent)} missing): `make test` "
            f"installs the Debian packages {debian_packages()}")


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def _process_table() -> dict[int, tuple[int, int, str, str]]:
    """pid -> (parent pid, process group, state, start time) of every process."""
    table = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            stat = Path(f"/proc/{entry}/stat").read_text()
        except OSError:
            continue
        fields = stat.rsplit(")", 1)[1].split()  # after the command name, which may hold ')'
        table[int(entry)] = (int(fields[1]), int(fields[2]), fields[0], fields[19])
    return table


@dataclass
class Launch:
    """A launch command (roslaunch, or mcar view --rviz) run under its own Xvfb;
    ``stop`` ends it and everything it started."""

    folder: Path
    command: list[str]
    env: dict[str, str]
    cwd: Path
    processes: list[subprocess.Popen] = field(default_factory=list)
    # (pid, start time) of every process seen in their groups or below them: a process
    # that leaves its group (roslaunch under `mcar view --rviz` has a session of its own)
    # is still ours to stop
    known: set[tuple[int, str]] = field(default_factory=set)
    stopped: tuple[float, list[int]] | None = None

    @property
    def log(self) -> Path:
        return self.folder / "roslaunch.log"

    def log_tail(self, lines: int = 40) -> str:
        text = self.log.read_text(errors="replace") if self.log.exists() else ""
        return "\n".join(text.splitlines()[-lines:])

    def start(self) -> None:
        display = self._start_xvfb()
        port = free_port()
        home = self.folder / "home"
        runtime = self.folder / "xdg-runtime"
        for folder in (home, runtime):
            folder.mkdir(mode=0o700, exist_ok=True)
        self.env.update({
            "DISPLAY": f":{display}", "HOME": str(home), "XDG_RUNTIME_DIR": str(runtime),
            "ROS_MASTER_URI": f"http://127.0.0.1:{port}", "ROS_IP": "127.0.0.1",
            "ROS_HOME": str(home / ".ros"), "ROS_LOG_DIR": str(self.folder / "ros-log")})
        with open(self.log, "wb") as log:
            self.processes.append(subprocess.Popen(
                self.command, cwd=self.cwd, env=self.env, stdin=subprocess.DEVNULL,
                stdout=log, stderr=subprocess.STDOUT, start_new_session=True))

    def _start_xvfb(self) -> int:
        """Xvfb on the first free display number, which it writes to a pipe (-displayfd)."""
        read_end, write_end = os.pipe()
        with open(self.folder / "xvfb.log", "wb") as log:
            xvfb = subprocess.Popen(
                ["Xvfb", "-displayfd", str(write_end), "-screen", "0",
                 f"{SCREEN[0]}x{SCREEN[1]}x24", "-nolisten", "tcp"],
                pass_fds=(write_end,), stdin=subprocess.DEVNULL, stdout=log,
                stderr=subprocess.STDOUT, start_new_session=True)
        self.processes.append(xvfb)
        os.close(write_end)
        answer = b""
        deadline = time.monotonic() + SECONDS
        with open(read_end, "rb", buffering=0) as pipe:
            while not answer.endswith(b"\n") and time.monotonic() < deadline:
                if select.select([pipe], [], [], 0.5)[0]:
                    chunk = pipe.read(16)
                    if not chunk:
                        break
                    answer += chunk
        if not answer.strip().isdigit():
            raise RuntimeError("Xvfb gave no display number: "
                               + (self.folder / "xvfb.log").read_text(errors="replace"))
        return int(answer)

    def probe(self, root: str, frames: list[str]) -> dict:
        """What the graph publishes (see tf_probe.py), waiting at most SECONDS; fails at
        once, with roslaunch's output, if roslaunch ends first."""
        env = dict(self.env, PATH=f"/usr/bin:{self.env['PATH']}")
        with subprocess.Popen([DEBIAN_PYTHON, str(HERE / "tf_probe.py"), str(SECONDS), root,
                               *frames], env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True) as probe:
            deadline = time.monotonic() + SECONDS + 30
            while probe.poll() is None:
                ended = self.processes[-1].poll()
                if ended is not None or time.monotonic() > deadline:
                    probe.kill()
                    raise AssertionError(f"roslaunch ended (exit {ended}) before ROS answered:"
                                         f"\n{self.log_tail()}")
                time.sleep(0.1)
            out, err = probe.communicate()
        if probe.returncode != 0:
            raise AssertionError(f"tf_probe failed: {err[-2000:]}\nroslaunch:\n"
                                 f"{self.log_tail()}")
        self.note_processes()  # everything is up by now
        return json.loads(out)

    def screenshot(self):
        from PIL import ImageGrab

        return ImageGrab.grab(xdisplay=self.env["DISPLAY"]).convert("RGB")

    def screenshot_when(self, shows, what: str):
        """The first screenshot for which ``shows(image)`` holds, within SECONDS."""
        from ros.stacking import raise_windows

        deadline = time.monotonic() + SECONDS
        while True:
            image = self.screenshot()
            if shows(image):
                return image
            raise_windows(self.env["DISPLAY"], "joint_state_publisher_gui")  # stacking.py
            if time.monotonic() > deadline:
                image.save(self.folder / "last-screenshot.png")
                raise AssertionError(f"RViz never showed {what} in {SECONDS} s (last picture: "
                                     f"{self.folder / 'last-screenshot.png'})\n"
                                     f"roslaunch:\n{self.log_tail()}")
            time.sleep(0.3)

    def note_processes(self) -> None:
        """Remember every process our processes' groups hold or have started."""
        table = _process_table()
        mine = {proc.pid for proc in self.processes}
        grew = True
        while grew:
            more = {pid for pid, (parent, group, _, _) in table.items()
                    if pid not in mine and (parent in mine or group in mine)}
            mine |= more
            grew = bool(more)
        self.known |= {(pid, table[pid][3]) for pid in mine if pid in table}

    def running(self) -> list[int]:
        """The known processes still running (zombies, already dead, aside)."""
        table = _process_table()
        return sorted(pid for pid, started in self.known
                      if pid in table and table[pid][3] == started and table[pid][2] != "Z")

    def stop(self) -> tuple[float, list[int]]:
        """Stop the launch (SIGINT, as Ctrl-C: roslaunch stops its nodes and master), then
        Xvfb; kill what lingers. Returns (seconds taken, pids of ours still running
        STOP_SECONDS after the start of the stop). Calling it again returns the first
        answer."""
        if self.stopped is not None:
            return self.stopped
        began = time.monotonic()
        self.note_processes()
        for proc in reversed(self.processes):  # the launch first: RViz needs its display
            with contextlib.suppress(ProcessLookupError):
                os.killpg(proc.pid, signal.SIGINT if proc.args[0] != "Xvfb" else signal.SIGTERM)
            try:
                proc.wait(timeout=STOP_SECONDS / 2)
            except subprocess.TimeoutExpired:
                pass
        while self.running() and time.monotonic() - began < STOP_SECONDS:
            time.sleep(0.1)
        survivors = self.running()
        self.stopped = (time.monotonic() - began, survivors)
        for pid in survivors:  # whatever the answer, nothing is left behind
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)
        for proc in self.processes:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
        return self.stopped


@contextlib.contextmanager
def launched(folder: Path, command: list[str], cwd: Path, ros_package_path: Path):
    """Start ``command`` (a roslaunch) with a PATH as an active virtualenv makes it (its
    bin first: the trap the launch file must get past) under a fresh Xvfb; stop it after."""
    env = {key: value for key, value in os.environ.items()
           if not key.startswith(("ROS_", "AMENT_")) and key != "PYTHONPATH"}
    venv_bin = str(Path(sys.executable).parent)
    env.update(PATH=f"{venv_bin}{os.pathsep}{env.get('PATH', '')}", VIRTUAL_ENV=str(
        Path(sys.executable).parent.parent), PWD=str(cwd),
        ROS_PACKAGE_PATH=str(ros_package_path))
    launch = Launch(folder, command, env, cwd)
    try:
        launch.start()
        yield launch
    finally:
        launch.stop()


def save_screenshot(launch: Launch, image, name: str, readme: bool = False) -> None:
    """Keep the picture in the test's folder; the README's also in MCAR_SCREENSHOT_DIR,
    grabbed again a moment later (RViz's first frames say "0 fps")."""
    image.save(launch.folder / name)
    if readme and SCREENSHOT_DIR:
        time.sleep(2)
        launch.screenshot().save(Path(SCREENSHOT_DIR) / name, optimize=True)
