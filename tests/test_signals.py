"""Ctrl-C, SIGTERM and SIGHUP end a run: exit 130 / 143 / 129, no temporary file left,
every output either whole or absent (issue 13, item 4). A seeded loop sends the signal at
random moments of real runs."""

from __future__ import annotations

import random
import re
import signal
import subprocess
import time

import pytest
from conftest import MCAR, REPO
from lxml import etree

RUNS = 50


def _run_and_signal(args, cwd, delay, signum, stdin=subprocess.DEVNULL):
    process = subprocess.Popen([str(MCAR), *args], cwd=cwd, stdin=stdin,
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        process.wait(timeout=delay)  # done before the moment came: nothing to interrupt
    except subprocess.TimeoutExpired:
        process.send_signal(signum)
    _out, err = process.communicate(timeout=120)
    return process.returncode, err


def test_a_signal_at_any_moment_leaves_no_temporary_file(tmp_path):
    rng = random.Random(11)
    (tmp_path / "timing").mkdir()
    whole = {render: min(2.5, _seconds(_args(render, tmp_path / "timing"), tmp_path))
             for render in (False, True)}
    ended = {143: 0, 129: 0, 0: 0, -15: 0, -1: 0}
    for run in range(RUNS):
        out = tmp_path / f"run{run}"
        out.mkdir()
        render = run % 5 == 4  # one run in five draws (pictures written on a second thread)
        args = (["render", str(REPO / "urdf"), "--renderer", "raycast", "--size", "160x120",
                 "-o", str(out / "renders")] if render
                else ["build", str(REPO / "urdf"), "-o", str(out / "build")])
        signum = signal.SIGHUP if run % 7 == 6 else signal.SIGTERM
        code, err = _run_and_signal(args, out, rng.uniform(0.05, whole[render]), signum)
        # -signum: the signal came as the interpreter was shutting down, after every output
        # was written, when Python has given the default handlers back (a shell shows
        # 128 + signum for it as well).
        assert code in (0, 128 + signum, -signum), (run, code, err)
        assert "Traceback" not in err and "internal error" not in err, err
        ended[code] += 1
        leftovers = [p.name for p in out.rglob("*") if p.name.endswith(".tmp")]
        assert leftovers == [], (run, leftovers)
        for urdf in out.rglob("*.urdf"):
            etree.parse(str(urdf))  # whole, or it would not parse
    assert ended[143] + ended[129] > RUNS // 2, ended  # most runs were really interrupted


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP])
def test_the_exit_code_names_the_signal(signum, tmp_path):
    code, err = _run_and_signal(["build", "-"], tmp_path, 0.6, signum, stdin=subprocess.PIPE)
    assert code == 128 + signum, err
    assert err.rstrip().endswith("mcar: terminated")


SIGINT_RUNS = 50
_FRAME = re.compile(r'File "([^"]*)", line (\d+)')


def _install_line() -> int:
    """The line of cli/main.py that installs mcar's handlers."""
    lines = (REPO / "cli" / "main.py").read_text().splitlines()
    return next(n for n, line in enumerate(lines, 1) if line.startswith("signals.install()"))


def _before_mcar_started(err: str) -> bool:
    """A Ctrl-C that came while Python itself was starting (site, the .pth files) or
    importing mcar's first module, before mcar's handler was in: Python's own
    KeyboardInterrupt traceback, whose frames never reach past the handler's install."""
    if not err.rstrip().endswith("KeyboardInterrupt"):
        return False
    for path, line in _FRAME.findall(err):
        if "/mobile_car/" not in path or path.endswith(("/mobile_car/__init__.py",
                                                        "/cli/__init__.py", "/cli/signals.py")):
            continue
        if not (path.endswith("/cli/main.py") and int(line) <= _install_line()):
            return False
    return True


def _args(render: bool, out):
    return (["render", str(REPO / "urdf"), "--renderer", "raycast", "--size", "160x120",
             "-o", str(out / "renders")] if render
            else ["build", str(REPO / "urdf"), "-o", str(out / "build")])


def _seconds(args, cwd) -> float:
    """How long one whole run takes on this machine: the moments to choose from."""
    started = time.monotonic()
    subprocess.run([str(MCAR), *args], cwd=cwd, capture_output=True, check=True, timeout=120)
    return time.monotonic() - started


def test_ctrl_c_at_any_moment_exits_130(tmp_path):
    """Ctrl-C at random moments of real runs: during Python's start, mcar's imports,
    click's parsing, the command, the cleanup (issue 13, item 6)."""
    rng = random.Random(13)
    (tmp_path / "timing").mkdir()
    whole = {render: min(2.5, _seconds(_args(render, tmp_path / "timing"), tmp_path))
             for render in (False, True)}
    ended = {130: 0, 0: 0, "python's start": 0, -2: 0}
    for run in range(SIGINT_RUNS):
        out = tmp_path / f"run{run}"
        out.mkdir()
        render = run % 4 == 3
        code, err = _run_and_signal(_args(render, out), out,
                                    rng.uniform(0.01, whole[render]), signal.SIGINT)
        leftovers = [p.name for p in out.rglob("*") if p.name.endswith(".tmp")]
        assert leftovers == [], (run, leftovers)
        if _before_mcar_started(err):  # nothing of mcar ran: nothing it could clean up
            assert not any(out.iterdir()), (run, err)
            ended["python's start"] += 1
            continue
        for bad in ("Aborted!", "internal error", "Traceback", "Exception ignored"):
            assert bad not in err, (run, code, err)
        # -2: the signal came as the interpreter was shutting down, everything written (a
        # shell shows 130 for it as well).
        assert code in (0, 130, -2), (run, code, err)
        ended[code] += 1
        if code == 130:
            assert err.rstrip().endswith("mcar: interrupted"), (run, err)
        else:  # it had finished: every output is there and whole
            _assert_complete(out, render)
    assert ended[130] > SIGINT_RUNS // 2, ended


def _assert_complete(out, render: bool) -> None:
    if render:
        from PIL import Image

        pictures = sorted((out / "renders").rglob("*.png"))
        assert len(pictures) == 14, pictures  # 13 robots and the contact sheet
        for picture in pictures:
            with Image.open(picture) as image:
                image.load()  # whole, or it would not decode
        return
    built = sorted((out / "build").rglob("*.urdf"))
    assert len(built) == 13, built
    for urdf in built:
        assert etree.parse(str(urdf)).getroot().tag == "robot"


def test_ctrl_c_says_interrupted_and_exits_130(tmp_path):
    code, err = _run_and_signal(["build", "-"], tmp_path, 0.6, signal.SIGINT,
                                stdin=subprocess.PIPE)
    assert code == 130, err
    assert err.rstrip().endswith("mcar: interrupted")
    assert "Aborted!" not in err
