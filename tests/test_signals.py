"""Ctrl-C, SIGTERM and SIGHUP end a run: exit 130 / 143 / 129, no temporary file left,
every output either whole or absent (issue 13, item 4). A seeded loop sends the signal at
random moments of real runs.

The loop runs mcar on one CPU beside a busy process (issue 30, item 8; at nice 10), as on
a loaded machine, whatever else runs at the time: a race hides in a window of microseconds (a
module half imported, a fork), and mcar preempted inside one holds it open for a time
slice. Even so a window that small is met about once in a thousand runs; each race found
gets a test of its own that hits its window every time (the last one below).
"""

from __future__ import annotations

import contextlib
import os
import random
import re
import signal
import subprocess
import sys
import textwrap
import time

import pytest
from conftest import MCAR, REPO
from lxml import etree


@contextlib.contextmanager
def _sharing_a_busy_cpu():
    """Processes started from this thread run on one CPU beside a CPU-bound process.
    sched_setaffinity(0) pins only the calling thread, and children inherit it: the other
    CPUs stay free for the rest of the suite."""
    pinned = getattr(os, "sched_setaffinity", None) is not None
    if pinned:
        cpus = os.sched_getaffinity(0)
        os.sched_setaffinity(0, {max(cpus)})
    # At nice 10 it still takes the CPU from mcar at moments the scheduler picks (what
    # holds a race's window open), without taking half of it: the two loops took 57 and
    # 51 s at nice 0 with nothing else running, 36 and 33 s at nice 10 beside other tests.
    busy = subprocess.Popen([sys.executable, "-c", "while True: pass"],
                            preexec_fn=lambda: os.nice(10))
    try:
        yield
    finally:
        busy.kill()
        busy.wait()
        if pinned:
            os.sched_setaffinity(0, cpus)


def _run_and_signal(args, cwd, delay, signum, stdin=subprocess.DEVNULL):
    process = subprocess.Popen([str(MCAR), *args], cwd=cwd, stdin=stdin,
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        process.wait(timeout=delay)  # done before the moment came: nothing to interrupt
    except subprocess.TimeoutExpired:
        process.send_signal(signum)
    _out, err = process.communicate(timeout=120)
    return process.returncode, err


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP])
def test_the_exit_code_names_the_signal(signum, tmp_path):
    code, err = _run_and_signal(["build", "-"], tmp_path, 0.6, signum, stdin=subprocess.PIPE)
    assert code == 128 + signum, err
    assert err.rstrip().endswith("mcar: terminated")


_FRAME = re.compile(r'File "([^"]*)", line (\d+), in (\S+)')


def _install_line() -> int:
    """The line of cli/main.py that installs mcar's handlers."""
    lines = (REPO / "cli" / "main.py").read_text().splitlines()
    return next(n for n, line in enumerate(lines, 1) if line.startswith("signals.install()"))


def _frames_before_mcar(text: str) -> bool:
    """Every frame of a traceback is Python's own start (site, the .pth files, importlib)
    or mcar's first module before the line that installs mcar's handlers (mcar's handler
    itself in a traceback means it was in)."""
    for path, line, function in _FRAME.findall(text):
        if path.endswith("/cli/signals.py") and function == "_on_signal":
            return False
        if "/mobile_car/" not in path or path.endswith(("/mobile_car/__init__.py",
                                                        "/cli/__init__.py", "/cli/signals.py")):
            continue
        if not (path.endswith("/cli/main.py") and int(line) <= _install_line()):
            return False
    return True


def _before_mcar_started(code: int, err: str, out) -> bool:
    """A Ctrl-C that ended the process before mcar's handler was in. Either it came before
    Python had put in its own handler, and the default action ended the process (-2,
    nothing printed: any program started that moment ends so), or while Python was
    starting (site, the .pth files) or importing mcar's first module: Python's own
    KeyboardInterrupt traceback, whose frames never reach past the handler's install."""
    if code == -2 and err == "" and not any(out.iterdir()):
        return True
    return err.rstrip().endswith("KeyboardInterrupt") and _frames_before_mcar(err)


# What Python prints where its start-up code swallows a KeyboardInterrupt and goes on
# (importlib's module-lock weakref callback, zipimport's look at argv[0]): the Ctrl-C is
# lost before mcar's first line, and mcar then runs as if it had not come.
_SWALLOWED = re.compile(r"\A(?:Exception ignored in: |Failed checking if argv\[0\] is an "
                        r"import path entry\n)(?:.*\n)*?KeyboardInterrupt(?:: )?\n")


def _swallowed_by_python(err: str) -> str | None:
    """The rest of stderr after Python's start-up swallowed the Ctrl-C, or None."""
    noise = _SWALLOWED.match(err)
    if noise is None or not _frames_before_mcar(noise.group(0)):
        return None
    return err[noise.end():]


def _args(render: bool, out):
    """A build or a render of the chassis folder's 4 robot files (its test file and its
    three steps): a build expands each in the sandbox and writes each URDF atomically; a
    render draws four pictures, which finish on a second thread while the next is drawn,
    and writes the contact sheet last. (The folder, not the whole package's 13 files:
    every stage is there, and a build takes 0.25 s instead of 0.38 s.)"""
    folder = str(REPO / "urdf" / "chassis")
    return (["render", folder, "--size", "160x120", "-o", str(out / "renders")] if render
            else ["build", folder, "-o", str(out / "build")])


def _seconds(render: bool, folder, cwd) -> float:
    """How long one whole run takes on this machine: the moments to choose from. The
    median of three runs, each into a folder of its own (a second run into the same one
    would find it up to date): on a loaded machine one run may take twice another, and a
    moment drawn past the usual end interrupts nothing."""
    times = []
    for run in range(3):
        out = folder / f"{'render' if render else 'build'}{run}"
        out.mkdir(parents=True)
        started = time.monotonic()
        subprocess.run([str(MCAR), *_args(render, out)], cwd=cwd, capture_output=True,
                       check=True, timeout=120)
        times.append(time.monotonic() - started)
    return sorted(times)[1]


RUNS = 70
# Half the runs get Ctrl-C, the others SIGTERM and, one in seven, SIGHUP.
_SIGNAL_OF_RUN = (signal.SIGINT, signal.SIGTERM, signal.SIGINT, signal.SIGTERM,
                  signal.SIGINT, signal.SIGHUP, signal.SIGINT, signal.SIGTERM,
                  signal.SIGINT, signal.SIGTERM, signal.SIGINT, signal.SIGTERM,
                  signal.SIGINT, signal.SIGHUP)


@pytest.mark.slow
def test_a_signal_at_any_moment_ends_the_run_cleanly(tmp_path):
    """Ctrl-C, SIGTERM and SIGHUP at random moments of real runs: during Python's start,
    mcar's imports, click's parsing, the command, the cleanup (issue 13, items 4 and 6).
    Every run, whichever signal it got, leaves no temporary file and every output whole
    or absent; Ctrl-C exits 130 saying "interrupted", SIGTERM and SIGHUP 128 + N. (One
    loop for the three: each run checks everything, and the machine's busy neighbour is
    paid once.)"""
    rng = random.Random(13)
    (tmp_path / "timing").mkdir()
    ended = {signal.SIGINT: {130: 0, 0: 0, "python's start": 0, "lost in python's start": 0,
                             -2: 0},
             signal.SIGTERM: {143: 0, 0: 0, -15: 0}, signal.SIGHUP: {129: 0, 0: 0, -1: 0}}
    with _sharing_a_busy_cpu():
        whole = {render: min(2.5, _seconds(render, tmp_path / "timing", tmp_path))
                 for render in (False, True)}
        for run in range(RUNS):
            out = tmp_path / f"run{run}"
            out.mkdir()
            render = run % 4 == 3  # one run in four draws (pictures on a second thread)
            signum = _SIGNAL_OF_RUN[run % len(_SIGNAL_OF_RUN)]
            code, err = _run_and_signal(_args(render, out), out,
                                        rng.uniform(0.01, whole[render]), signum)
            if signum == signal.SIGINT:
                ended[signum][_judge_ctrl_c(run, code, err, out, render)] += 1
            else:
                ended[signum][_judge_termination(run, signum, code, err, out, render)] += 1
    # most runs were really interrupted
    ctrl_c, term, hup = (ended[signum] for signum in (signal.SIGINT, signal.SIGTERM,
                                                      signal.SIGHUP))
    assert ctrl_c[130] > sum(ctrl_c.values()) // 2, ended
    assert term[143] + hup[129] > (sum(term.values()) + sum(hup.values())) // 2, ended


def _judge_termination(run: int, signum: int, code: int, err: str, out, render: bool) -> int:
    """What a run sent SIGTERM or SIGHUP came to, once what it printed and left is checked.
    -signum: the signal came before Python put its handlers in (nothing ran), or as the
    interpreter was shutting down, after every output was written, when Python has given
    the default handlers back (a shell shows 128 + signum)."""
    assert code in (0, 128 + signum, -signum), (run, code, err)
    assert "Traceback" not in err and "internal error" not in err, (run, err)
    _assert_no_temporary_file(run, out)
    for urdf in out.rglob("*.urdf"):
        etree.parse(str(urdf))  # whole, or it would not parse
    if code == 0:  # it had finished: every output is there and whole
        _assert_complete(out, render)
    return code


def _assert_no_temporary_file(run: int, out) -> None:
    leftovers = [p.name for p in out.rglob("*") if p.name.endswith(".tmp")]
    assert leftovers == [], (run, leftovers)


def _judge_ctrl_c(run: int, code: int, err: str, out, render: bool):
    """What one interrupted run came to, once what it printed and left is checked."""
    _assert_no_temporary_file(run, out)
    if _before_mcar_started(code, err, out):  # nothing of mcar ran: nothing to clean up
        assert not any(out.iterdir()), (run, err)
        return "python's start"
    rest = _swallowed_by_python(err)
    if rest is not None:  # then mcar ran, untouched: as a run that was not interrupted
        assert code == 0 and "Traceback" not in rest, (run, code, err)
        _assert_complete(out, render)
        return "lost in python's start"
    for bad in ("Aborted!", "internal error", "Traceback", "Exception ignored"):
        assert bad not in err, (run, code, err)
    # -2: the signal came as the interpreter was shutting down, everything written (a
    # shell shows 130 for it as well).
    assert code in (0, 130, -2), (run, code, err)
    if code == 130:
        assert err.rstrip().endswith("mcar: interrupted"), (run, err)
    else:  # it had finished: every output is there and whole
        _assert_complete(out, render)
    return code


def _assert_complete(out, render: bool) -> None:
    if render:
        from PIL import Image

        pictures = sorted((out / "renders").rglob("*.png"))
        assert len(pictures) == 5, pictures  # the chassis folder's 4 robots and the sheet
        for picture in pictures:
            with Image.open(picture) as image:
                image.load()  # whole, or it would not decode
        return
    built = sorted((out / "build").rglob("*.urdf"))
    assert len(built) == 4, built  # the chassis folder's 4 robots
    for urdf in built:
        assert etree.parse(str(urdf)).getroot().tag == "robot"


def test_ctrl_c_says_interrupted_and_exits_130(tmp_path):
    code, err = _run_and_signal(["build", "-"], tmp_path, 0.6, signal.SIGINT,
                                stdin=subprocess.PIPE)
    assert code == 130, err
    assert err.rstrip().endswith("mcar: interrupted")
    assert "Aborted!" not in err


def test_a_signal_while_the_hold_module_is_still_importing_unwinds_as_usual(tmp_path):
    """A signal that lands while mobile_car/held_signals.py runs its own imports finds it
    in sys.modules without its functions yet: the handler must take it as "nothing held"
    (it raised AttributeError there, an internal error or an "Exception ignored" line
    and a lost Ctrl-C, 1 loop in 4 under load)."""
    script = textwrap.dedent("""
        import os, signal, sys, types
        from mobile_car.cli import signals
        signals.install()
        signals.arm()
        sys.modules["mobile_car.held_signals"] = types.ModuleType("mobile_car.held_signals")
        try:
            os.kill(os.getpid(), signal.SIGINT)
            sum(range(1000))  # the handler runs at the next bytecode boundary
        except BaseException as error:
            print(type(error).__name__, flush=True)
            os._exit(0)
        print("nothing raised", flush=True)
    """)
    done = subprocess.run([sys.executable, "-c", script], cwd=tmp_path, capture_output=True,
                          text=True, timeout=60)
    assert (done.stdout, done.stderr) == ("KeyboardInterrupt\n", "")
