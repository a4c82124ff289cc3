"""`mcar view` as a user runs it: the URL, the page served, reloads said on stderr,
Ctrl-C, and what it refuses (a robot check rejects, a port in use, no viser)."""

from __future__ import annotations

import os
import queue
import signal
import socket
import subprocess
import sys
import threading
import urllib.request
from pathlib import Path

import pytest

pytest.importorskip("viser", reason='viser is not installed (pip install "mcar[view]"; '
                                    "`make test` installs it)")

MCAR = Path(sys.executable).parent / "mcar"
SECONDS = 60


class Viewer:
    """`mcar view` in a subprocess, its stdout and stderr read line by line."""

    def __init__(self, *args, cwd):
        env = {k: v for k, v in os.environ.items() if k not in ("ROS_PACKAGE_PATH",
                                                                  "AMENT_PREFIX_PATH")}
        self.process = subprocess.Popen([str(MCAR), "view", "--no-browser", *map(str, args)],
                                        cwd=cwd, env=env, text=True, stdout=subprocess.PIPE,
                                        stderr=subprocess.PIPE)
        self.lines: dict[str, queue.Queue] = {"out": queue.Queue(), "err": queue.Queue()}
        for name, stream in (("out", self.process.stdout), ("err", self.process.stderr)):
            threading.Thread(target=self._read, args=(stream, self.lines[name]),
                             daemon=True).start()

    @staticmethod
    def _read(stream, lines: queue.Queue) -> None:
        for line in stream:
            lines.put(line.rstrip("\n"))

    def line(self, stream: str) -> str:
        try:
            return self.lines[stream].get(timeout=SECONDS)
        except queue.Empty:
            pytest.fail(f"no line on std{stream} within {SECONDS} s")

    def stop(self) -> int:
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGINT)
        try:
            return self.process.wait(timeout=SECONDS)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
            raise


@pytest.fixture
def viewer():
    started = []

    def start(*args, cwd):
        started.append(Viewer(*args, cwd=cwd))
        return started[-1]

    yield start
    for view in started:
        if view.process.poll() is None:
            view.process.kill()
            view.process.wait(timeout=SECONDS)


def _edit(path: Path, old: str, new: str) -> None:
    path.write_text(path.read_text().replace(old, new))
    stat = path.stat()
    os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns + 10**9))


def test_view_serves_the_page_reloads_on_edits_and_stops_on_ctrl_c(viewer, arm_copy):
    view = viewer(arm_copy.name, "--port", "0", cwd=arm_copy.parent)
    first = view.line("out")
    assert first.startswith("mcar view: arm.urdf.xacro at http://127.0.0.1:")
    assert first.endswith("/ (Ctrl-C stops)")
    url = first.split(" at ")[1].split(" ")[0]
    with urllib.request.urlopen(url, timeout=SECONDS) as response:
        assert response.status == 200 and b"<html" in response.read().lower()

    macro = arm_copy.parent / "arm_link.xacro"
    _edit(macro, 'value="0.3"', 'value="0.45"')
    assert view.line("err") == "mcar view: reloaded (arm_link.xacro changed)"
    _edit(macro, "</robot>", "</robt>")
    error = view.line("err")
    assert error.startswith("arm_link.xacro:") and "mismatched tag" in error, error
    assert view.line("err") == "mcar view: the last good robot stays on the page"

    assert view.stop() == 130
    assert view.line("err") == "mcar: interrupted"


def test_a_robot_check_rejects_is_not_served(viewer, arm_copy):
    _edit(arm_copy, 'upper="1.5"', 'upper="-2"')
    view = viewer(arm_copy.name, "--port", "0", cwd=arm_copy.parent)
    assert view.process.wait(timeout=SECONDS) == 1
    assert view.process.stdout.read() == ""
    assert view.line("err").startswith("arm.urdf.xacro:16: warning: ")
    assert view.line("err").startswith("arm.urdf.xacro:28: error: ")


def test_a_port_in_use_is_refused(viewer, arm_copy):
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        view = viewer(arm_copy.name, "--port", port, cwd=arm_copy.parent)
        assert view.process.wait(timeout=SECONDS) == 2
    assert view.process.stdout.read() == ""
    assert view.line("err") == (f"mcar: error: port {port} is in use; choose another with "
                                "--port (0: any)")


def test_without_viser_view_says_how_to_install_it(cli, monkeypatch, arm_copy):
    monkeypatch.setitem(sys.modules, "viser", None)  # import viser raises ImportError
    result = cli("view", arm_copy, "--no-browser")
    assert result.exit_code == 2
    assert result.output == ('mcar: error: mcar view needs viser, which is not installed: '
                             'pip install "mcar[view]"\n')


def test_view_shows_one_robot(run_mcar, arm_copy):
    second = arm_copy.parent / "second.urdf.xacro"
    second.write_bytes(arm_copy.read_bytes())
    result = run_mcar("view", "--no-browser", "--port", "0", arm_copy.parent,
                      cwd=arm_copy.parent)
    assert result.returncode == 2
    assert result.stderr.splitlines() == [
        "mcar: error: mcar view works on one robot, and there are 2 here: name one INPUT",
        "  arm.urdf.xacro",
        "  second.urdf.xacro"]


def test_the_bundled_robot_is_the_package_s_top_level_robot(viewer, tmp_path):
    view = viewer("--port", "0", "--bundled", cwd=tmp_path)
    line = view.line("out")
    assert "mobile_car/description/urdf/mobile_robot.xacro at http://127.0.0.1:" in line, line
    assert view.stop() == 130
