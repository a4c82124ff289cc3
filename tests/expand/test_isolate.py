"""xacro runs in a guarded child: runaway expressions end in a located error, in bounded time
and memory, and the parent process is left as it was."""

from __future__ import annotations

import os
import subprocess
import sys
import threading

import pytest

from mobile_car.errors import BuildError
from mobile_car.expand.isolate import OutOfMemory, Timeout, run_isolated
from mobile_car.expand.wire import ChildCrashed


def test_result_and_exceptions_come_back_as_data():
    """Values come back as JSON, mcar's own errors with their fields, and any other
    exception only as its name and text: the parent never rebuilds an object the child
    chose."""
    assert run_isolated(sorted, [3, 1, 2]) == [1, 2, 3]
    with pytest.raises(ChildCrashed, match="^ZeroDivisionError: integer division"):
        run_isolated(divmod, 1, 0)

    def fails():
        raise BuildError("bad", file="a.xacro", line=3, details=["in macro m"])

    with pytest.raises(BuildError) as info:
        run_isolated(fails)
    assert (str(info.value), info.value.details) == ("a.xacro:3: bad", ["in macro m"])


def test_the_child_collects_garbage_every_100000_objects_and_the_parent_as_it_did():
    import gc

    before = gc.get_threshold()
    assert run_isolated(gc.get_threshold) == [100_000, 10, 10]
    assert gc.get_threshold() == before


def test_timeout_kills_the_child(monkeypatch):
    monkeypatch.setenv("MCAR_XACRO_TIMEOUT", "0.5")
    with pytest.raises(Timeout) as info:
        run_isolated(pow, 9, 9**9)
    assert info.value.seconds == 0.5


def test_memory_limit(monkeypatch):
    monkeypatch.setenv("MCAR_XACRO_MEMORY_MB", "300")
    with pytest.raises(OutOfMemory) as info:
        run_isolated(bytearray, 2 * 1024**3)
    assert info.value.megabytes == 300


def test_forks_also_while_other_threads_run():
    """render finishes pictures on a thread: xacro must still run guarded, in a child."""
    gate = threading.Event()
    worker = threading.Thread(target=gate.wait)
    worker.start()
    try:
        assert run_isolated(os.getpid) != os.getpid()
    finally:
        gate.set()
        worker.join()


@pytest.mark.parametrize("expression, env, message", [
    ("9**9**9", {"MCAR_XACRO_TIMEOUT": "1"}, "error: xacro did not finish within 1 s"),
    ("[0] * 10**10", {}, "error: out of memory when evaluating expression"),
])
def test_runaway_xacro_is_a_build_error(run_mcar, tmp_path, expression, env, message):
    source = tmp_path / "runaway.xacro"
    source.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                      f'  <link name="${{{expression}}}"/>\n</robot>\n')
    for command in ("build", "check"):
        result = run_mcar(command, source, env=env, timeout=30)
        assert result.returncode == 1, result.stderr
        assert message in result.stderr
        assert result.stderr.startswith(str(source))


def test_the_embedding_programs_gc_hooks_stay_out_of_the_child(repo):
    """A Dask worker measures memory through psutil at every garbage collection; in the
    sandboxed child that fails, and Python printed the failure among xacro's warnings, so
    a --strict check failed a good robot (W220). The child runs without such hooks."""
    import gc
    import sys

    from mobile_car.load.inputs import RobotInput
    from mobile_car.load.robot import LoadOptions, load_robot

    def noisy(phase, info):
        if phase == "start":
            print("a hook of the embedding program ran", file=sys.stderr)

    gc.callbacks.append(noisy)
    try:
        loaded = load_robot(RobotInput(repo / "urdf" / "mobile_robot.xacro"), LoadOptions())
        in_parent = run_isolated(lambda: list(gc.callbacks))
    finally:
        gc.callbacks.remove(noisy)
    assert loaded.warnings == [] and in_parent == []


def test_the_memory_limit_counts_from_the_parents_own_size(tmp_path):
    """A fork starts with its parent's address space: in a large program (a Dask worker,
    the viewer, a test run with USD and MuJoCo loaded) that alone passed a fixed 4 GB
    limit, and every xacro failed "out of memory", or stranger, on the first allocation."""
    script = tmp_path / "large_parent.py"
    script.write_text(
        "import mmap, sys\n"
        "from mobile_car.expand.isolate import run_isolated\n"
        "# address space that costs nothing: reserved, never touched\n"
        "held = mmap.mmap(-1, 1024 * 1024**2, prot=0)  # PROT_NONE\n"
        "def grab(size):\n"
        "    return len(bytearray(size))\n"
        "print(run_isolated(grab, 100 * 1024**2))\n")
    env = {**os.environ, "MCAR_XACRO_MEMORY_MB": "512"}
    result = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                            env=env, timeout=60, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stdout == f"{100 * 1024**2}\n"
