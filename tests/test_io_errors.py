"""A failed write is an I/O error, not a bug (issue 13, item 4): stdout on a full disk or
closed, an output on a full or read-only file system, under a file, in a folder mcar may
not write to. Each gives one line naming the file or stream, exit 2, no traceback, no
temporary file left, and an earlier good output untouched. A closed stdout pipe (the
reader went away: `mcar tree | head -1`) ends the run quietly with exit 0."""

from __future__ import annotations

import contextlib
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import pytest
from conftest import MCAR, REPO

ROBOT = REPO / "urdf" / "mobile_robot.xacro"
FULL = "mcar: error: cannot write <stdout>: No space left on device"

# name -> (arguments, the one error line); stdout is /dev/full
STDOUT_FULL = {
    "build": (["build", ROBOT], FULL),
    "build_deps": (["build", "--deps", ROBOT], FULL),
    "build_stdin": (["build", "-"], FULL),
    "tree": (["tree", ROBOT], FULL),
    "check": (["check", ROBOT], FULL),
    "check_json": (["check", "--format", "json", ROBOT], FULL),
    "config": (["config", ROBOT], FULL),
    "render": (["render", ROBOT, "-o", "-", "--size", "80x60", "-q"], FULL),
    "ci_junit": (["ci", REPO / "urdf" / "wheel", "--format", "junit", "--no-render",
                  "--no-sim", "--no-gazebo"], FULL),
    "help": (["--help"], FULL),
    "command_help": (["tree", "--help"], FULL),
    "version": (["--version"], FULL),
}


def _run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=None, user=None):
    env = {k: v for k, v in os.environ.items() if k not in ("ROS_PACKAGE_PATH",
                                                            "AMENT_PREFIX_PATH")}
    prefix = []
    if user is not None:
        prefix = [shutil.which("setpriv"), f"--reuid={user}", f"--regid={user}",
                  "--clear-groups"]
    with open(ROBOT, "rb") as stdin:
        return subprocess.run([*prefix, str(MCAR), *map(str, args)], stdin=stdin,
                              stdout=stdout, stderr=stderr, cwd=cwd, env=env, timeout=120)


def _lines(err: bytes) -> list[str]:
    return err.decode().splitlines()


@pytest.mark.parametrize("name", sorted(STDOUT_FULL))
def test_stdout_on_a_full_disk(name, tmp_path):
    args, line = STDOUT_FULL[name]
    with open("/dev/full", "wb") as full:
        done = _run(args, stdout=full, cwd=tmp_path)
    assert _lines(done.stderr) == [line], done.stderr.decode()
    assert done.returncode == 2
    assert [p for p in tmp_path.rglob("*") if p.name.endswith(".tmp")] == []


@pytest.mark.parametrize("name", ["build", "tree", "check_json", "config", "help"])
def test_stdout_closed(name, tmp_path):
    args, _line = STDOUT_FULL[name]
    done = subprocess.run(["sh", "-c", 'exec "$@" >&-', "sh", str(MCAR), *map(str, args)],
                          capture_output=True, cwd=tmp_path, timeout=120)
    if name == "help":  # click has nothing to report a closed stdout with: silent, exit 0
        assert (done.returncode, done.stderr) == (0, b"")
        return
    assert _lines(done.stderr) == ["mcar: error: cannot write <stdout>: Bad file descriptor"]
    assert done.returncode == 2


def _run_reader_gone(args, stream: str, cwd):
    """Run mcar with ``stream`` (stdout or stderr) a pipe whose reader has gone."""
    read_end, write_end = os.pipe()
    os.close(read_end)
    try:
        return _run(args, cwd=cwd, **{stream: write_end})
    finally:
        os.close(write_end)


@pytest.mark.parametrize("name", ["build", "build_stdin", "tree", "check", "check_json",
                                  "config", "render", "ci_junit", "help"])
def test_reader_gone_ends_quietly(name, tmp_path):
    """stdout is a pipe nobody reads any more: exit 0, not a word, not even at the
    interpreter's last flush ("Exception ignored ... BrokenPipeError")."""
    args, _line = STDOUT_FULL[name]
    done = _run_reader_gone(args, "stdout", cwd=tmp_path)
    assert (done.returncode, done.stderr.decode()) == (0, "")


@pytest.mark.parametrize("stderr", ["full", "closed", "reader_gone"])
@pytest.mark.parametrize("args", [["build", "nonexistent.xacro"], ["build", "--bogus"],
                                  ["build", REPO / "urdf", "-o", "out"]],
                         ids=["bad_input", "usage_error", "progress"])
def test_stderr_that_cannot_be_written(stderr, args, tmp_path):
    """Nowhere left to say anything: exit 2, nothing on stdout, nothing half-written."""
    if stderr == "full":
        with open("/dev/full", "wb") as full:
            done = _run(args, stderr=full, cwd=tmp_path)
    elif stderr == "closed":
        done = subprocess.run(["sh", "-c", 'exec "$@" 2>&-', "sh", str(MCAR), *map(str, args)],
                              capture_output=True, cwd=tmp_path, timeout=120)
    else:
        done = _run_reader_gone(args, "stderr", cwd=tmp_path)
    if stderr == "closed" and args[-1] == "out":  # no message fails: the build is complete
        assert done.returncode == 0
        assert len(list((tmp_path / "out").rglob("*.urdf"))) == 13
    else:
        assert done.returncode == 2
    assert done.stdout == b""
    assert [p for p in tmp_path.rglob("*") if p.name.endswith(".tmp")] == []


# --- outputs: one line naming the file, exit 2, no .tmp, the earlier output untouched ---

GOOD = b"an earlier good output\n"
# command -> the arguments that write TARGET
WRITERS = {
    "build": lambda target: ["build", ROBOT, "-o", target],
    # (ray casting: one case runs as another user, who may not start the venv's python)
    "render": lambda target: ["render", ROBOT, "-o", target, "--renderer", "raycast",
                              "--size", "80x60", "-q"],
    "tree_graphviz": lambda target: ["tree", ROBOT, "--graphviz", target, "-q"],
}
SUFFIX = {"build": ".urdf", "render": ".png", "tree_graphviz": ".dot"}


@contextlib.contextmanager
def _mounted_tmpfs(options: str):
    folder = Path(tempfile.mkdtemp(prefix="mcar-io-"))
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", str(folder)],
                             capture_output=True)
    if mounted.returncode != 0:
        folder.rmdir()
        pytest.skip(f"cannot mount a tmpfs here (needs root): {mounted.stderr.decode()}")
    try:
        yield folder
    finally:
        subprocess.run(["umount", str(folder)], check=True)
        folder.rmdir()


@contextlib.contextmanager
def _dev_full(suffix):
    yield Path("/dev/full"), "No space left on device", None


@contextlib.contextmanager
def _under_a_file(suffix):
    with tempfile.TemporaryDirectory() as folder:
        blocker = Path(folder) / "robot"
        blocker.write_bytes(GOOD)
        yield blocker / f"out{suffix}", f"{blocker} is a file, not a folder", blocker


@contextlib.contextmanager
def _full_filesystem(suffix):
    with _mounted_tmpfs("size=8k") as folder:  # two pages: one for the earlier output
        target = folder / f"out{suffix}"
        target.write_bytes(GOOD)
        (folder / "filler").write_bytes(b"x" * 4096)
        yield target, "No space left on device", target


@contextlib.contextmanager
def _read_only_filesystem(suffix):
    with _mounted_tmpfs("size=1m") as folder:
        target = folder / f"out{suffix}"
        target.write_bytes(GOOD)
        subprocess.run(["mount", "-o", "remount,ro", str(folder)], check=True)
        yield target, "Read-only file system", target


@contextlib.contextmanager
def _no_permission(suffix):
    with tempfile.TemporaryDirectory() as folder:
        os.chmod(folder, 0o755)
        locked = Path(folder) / "locked"
        locked.mkdir()
        target = locked / f"out{suffix}"
        target.write_bytes(GOOD)
        locked.chmod(0o555)
        try:
            yield target, "Permission denied", target
        finally:
            locked.chmod(0o755)


TARGETS = {"dev_full": _dev_full, "under_a_file": _under_a_file,
           "full_filesystem": _full_filesystem, "read_only_filesystem": _read_only_filesystem,
           "no_permission": _no_permission}


@pytest.mark.parametrize(("case", "writer"), [
    (case, writer) for case in sorted(TARGETS) for writer in sorted(WRITERS)
    # --graphviz picks its format by the name's ending: /dev/full is a usage error
    if (case, writer) != ("dev_full", "tree_graphviz")])
def test_an_output_that_cannot_be_written(case, writer):
    user = None
    if case == "no_permission" and os.geteuid() == 0:  # root writes anywhere: be nobody
        if shutil.which("setpriv") is None:
            pytest.skip("as root, EACCES needs setpriv to run mcar as nobody")
        user = 65534
    with TARGETS[case](SUFFIX[writer]) as (target, reason, earlier):
        done = _run(WRITERS[writer](target), cwd="/", user=user)
        # Here Python lives where nobody may not start it again (a 0700 home): render
        # says once that it draws in its own process; that is not this test's matter.
        lines = [line for line in _lines(done.stderr)
                 if not line.startswith("mcar: warning: the drawing process could not")]
        assert lines == [f"{target}: error: cannot write: {reason}"], done.stderr.decode()
        assert done.returncode == 2
        if earlier is not None:
            assert earlier.read_bytes() == GOOD
            assert [p.name for p in earlier.parent.iterdir()
                    if p.name.endswith(".tmp")] == []
