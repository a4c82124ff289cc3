"""Ctrl-C and SIGTERM end ``mcar render`` and ``mcar ci`` within two seconds, also in the
middle of one long draw call (issue 32, item 3).

The hostile input is the shape the issue reports: an OBJ of 12 MB, three vertices and 1.5
million faces, each the same triangle across the whole picture. Drawn in mcar's own
process, one GL call (or one Embree call) ran for over 9 minutes and no signal ended it
short of SIGKILL. Here the mesh is a binary STL of 300,000 such faces: one draw call of
~20 s (ray casting ~12 s) on an idle machine, long past the moment the signal comes, and
five times cheaper to prepare (smoothing 1.5 million faces took the parent ~7 s of CPU
before the draw began, in each of the four tests).

Each test waits until mcar is really drawing (mcar asleep while a process it started
computes: see ``_wait_until_drawing``), signals, and then asserts what comes out: the exit
code, the one-line announcement, no traceback, the drawing process gone, the
earlier pictures in the output folder byte-identical and nothing added to it.
"""

from __future__ import annotations

import importlib.util
import os
import signal
import struct
import subprocess
import time
from pathlib import Path

import pytest
from conftest import MCAR

FACES = 300_000
EXIT_SECONDS = 2.0
# More CPU than a drawing process spends starting (importing trimesh and embreex: ~1 s):
# a process of mcar's past this, while mcar sleeps, is drawing.
DRAWING_CPU_SECONDS = 3.0
# Preparing the mesh takes ~1.5 s on an idle machine; much longer on a busy one.
START_DEADLINE = 240.0
TICKS = os.sysconf("SC_CLK_TCK")

URDF = """<?xml version="1.0"?>
<robot name="heavy">
  <link name="base_link">
    <visual><geometry><mesh filename="{mesh}"/></geometry></visual>
  </link>
</robot>
"""

pytestmark = pytest.mark.skipif(
    not Path(f"/proc/{os.getpid()}/task/{os.getpid()}/children").exists(),
    reason="needs Linux /proc/PID/task/TID/children to see mcar's drawing process")


@pytest.fixture(scope="module")
def heavy_package(tmp_path_factory) -> Path:
    """A description package whose one robot draws the 1.5-million-face mesh."""
    root = tmp_path_factory.mktemp("heavy") / "heavy_description"
    (root / "urdf").mkdir(parents=True)
    (root / "meshes").mkdir()
    triangle = struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0)
    (root / "meshes" / "heavy.stl").write_bytes(
        bytes(80) + struct.pack("<I", FACES) + triangle * FACES)
    (root / "urdf" / "heavy.urdf").write_text(URDF.format(mesh="../meshes/heavy.stl"))
    (root / "package.xml").write_text(
        '<?xml version="1.0"?>\n<package format="3"><name>heavy_description</name>'
        "<version>0.0.1</version><description>heavy</description>"
        '<maintainer email="a@b.c">a</maintainer><license>MIT</license></package>\n')
    return root


@pytest.fixture(scope="module")
def gl_available():
    from mobile_car.render.backend import GLProbe

    probe = GLProbe()
    reason = probe.wait()
    probe.cancel()
    if reason is not None:
        pytest.skip(f"OpenGL (EGL) is not available: {reason}")


@pytest.fixture(scope="module")
def raycast_available():
    if importlib.util.find_spec("embreex") is None:
        pytest.skip("the ray-casting renderer needs embreex (pip install embreex)")


def _children(pid: int) -> list[int]:
    found = []
    for task in Path(f"/proc/{pid}/task").glob("*"):
        try:
            found += [int(child) for child in (task / "children").read_text().split()]
        except OSError:  # the thread or the process ended meanwhile
            pass
    return found


def _descendants(pid: int) -> list[int]:
    found, todo = [], [pid]
    while todo:
        children = _children(todo.pop())
        found += children
        todo += children
    return found


def _stat(pid: int) -> tuple[str, float] | None:
    """(state, CPU seconds) of a process, or None once it is gone."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    fields = text.rsplit(")", 1)[1].split()
    return fields[0], (int(fields[11]) + int(fields[12])) / TICKS


def _started(pid: int) -> int | None:
    """When a process started (clock ticks after boot), or None once it is gone: a pid
    names the same process only while this stays the same (pid_max may be 32768, and a
    busy test run reuses a freed pid within seconds)."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    return int(text.rsplit(")", 1)[1].split()[19])


def _rasterising(pid: int) -> bool:
    """Mesa's llvmpipe threads (named llvmpipe-N) of ``pid`` have computed for a second:
    a draw is under way, in whichever process holds the GL context."""
    seconds = 0.0
    for task in Path(f"/proc/{pid}/task").glob("*"):
        try:
            if (task / "comm").read_text().startswith("llvmpipe"):
                fields = (task / "stat").read_text().rsplit(")", 1)[1].split()
                seconds += (int(fields[11]) + int(fields[12])) / TICKS
        except OSError:
            pass
    return seconds >= 1.0


def _wait_until_drawing(process: subprocess.Popen) -> list[int]:
    """The drawing processes, once mcar sleeps while one it started has computed for
    longer than starting takes (twice in a row, 0.2 s apart), or once llvmpipe is busy
    anywhere (in mcar itself, as before issue 32, too: the test then fails on the exit)."""
    deadline = time.monotonic() + START_DEADLINE
    streak = 0
    while time.monotonic() < deadline:
        if process.poll() is not None:
            pytest.fail(f"mcar ended (exit {process.returncode}) before it drew: "
                        f"{process.stderr.read()}")
        tree = [process.pid, *_descendants(process.pid)]
        if any(_rasterising(pid) for pid in tree):
            return tree[1:]
        drawing = [pid for pid in tree[1:]
                   if (_stat(pid) or ("", 0.0))[1] >= DRAWING_CPU_SECONDS]
        mcar = _stat(process.pid)
        streak = streak + 1 if drawing and mcar is not None and mcar[0] == "S" else 0
        if streak >= 2:
            return drawing
        time.sleep(0.2)
    pytest.fail(f"mcar did not start drawing in a child process within {START_DEADLINE:g} s")


def _earlier_pictures(folder: Path, names) -> dict[str, bytes]:
    """Good pictures of an earlier run, one of them at the path the run writes."""
    from PIL import Image

    folder.mkdir(parents=True, exist_ok=True)
    for index, name in enumerate(names):
        Image.new("RGB", (64, 48), (40 * index, 160, 90)).save(folder / name)
    return {path.name: path.read_bytes() for path in folder.iterdir()}


def _signal_while_drawing(args, cwd: Path, signum: int, whole_group: bool = False):
    """Run mcar, signal it mid-draw; (exit code, seconds to exit, stderr, (pid, start time)
    of each drawing process)."""
    # The face limit raised so the mesh is drawn: a user with a big mesh raises it too, and
    # a mesh under any limit can still fill every pixel with every face.
    env = {**os.environ, "MCAR_MAX_MESH_FACES": str(2 * FACES)}
    process = subprocess.Popen([str(MCAR), *map(str, args)], cwd=cwd, stdin=subprocess.DEVNULL,
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                               start_new_session=True, env=env)
    try:
        drawing = [(pid, _started(pid)) for pid in _wait_until_drawing(process)]
        sent = time.monotonic()
        if whole_group:  # as a terminal's Ctrl-C: mcar and its children alike
            os.killpg(process.pid, signum)
        else:
            process.send_signal(signum)
        try:
            process.wait(timeout=EXIT_SECONDS)
        except subprocess.TimeoutExpired:
            pytest.fail(f"mcar did not end within {EXIT_SECONDS:g} s of signal {signum}")
        seconds = time.monotonic() - sent
        return process.returncode, seconds, process.stderr.read(), drawing
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()
        process.stderr.close()


def _assert_ended_cleanly(code, seconds, err, drawing, signum, folder, before):
    assert code == 128 + signum, err
    assert seconds < EXIT_SECONDS
    assert "Traceback" not in err and "Exception ignored" not in err, err
    assert "internal error" not in err and "cannot draw" not in err, err
    announcement = "mcar: interrupted" if signum == signal.SIGINT else "mcar: terminated"
    assert err.splitlines()[-1] == announcement, err
    # Killed and reaped, not left drawing on its own. Every process mcar had started is
    # looked at, the record keeper among them (a second interpreter that leaves when mcar's
    # socket closes: on a loaded machine it may still be leaving as mcar exits), so each is
    # given until a deadline to be gone; a drawing process left running stays and fails.
    deadline = time.monotonic() + EXIT_SECONDS
    for pid, started in drawing:
        while True:
            state = _stat(pid)
            if state is None or state[0] == "Z" or _started(pid) != started:
                break  # gone, reaped or not, or its pid another process's now
            assert time.monotonic() < deadline, (pid, state)
            time.sleep(0.02)
    after = {path.name: path.read_bytes() for path in folder.iterdir()}
    assert after == before  # earlier pictures whole, no temporary or half-written file


@pytest.mark.parametrize("signum, whole_group", [(signal.SIGTERM, False),
                                                 (signal.SIGINT, True)],
                         ids=["SIGTERM", "Ctrl-C"])
def test_a_signal_ends_an_opengl_draw_at_once(heavy_package, gl_available, tmp_path, signum,
                                              whole_group):
    out = tmp_path / "renders"
    before = _earlier_pictures(out, ["heavy.png", "earlier.png"])
    args = ["render", heavy_package / "urdf" / "heavy.urdf", "-o", out / "heavy.png",
            "--size", "400x300", "--renderer", "gl"]
    result = _signal_while_drawing(args, tmp_path, signum, whole_group)
    _assert_ended_cleanly(*result, signum, out, before)


def test_sigterm_ends_a_ray_cast_draw_at_once(heavy_package, raycast_available, tmp_path):
    out = tmp_path / "renders"
    before = _earlier_pictures(out, ["heavy.png"])
    args = ["render", heavy_package / "urdf" / "heavy.urdf", "-o", out / "heavy.png",
            "--size", "160x120", "--renderer", "raycast"]
    result = _signal_while_drawing(args, tmp_path, signal.SIGTERM)
    _assert_ended_cleanly(*result, signal.SIGTERM, out, before)


def test_sigterm_ends_mcar_ci_while_it_draws(heavy_package, gl_available, tmp_path):
    out = tmp_path / "renders"
    before = _earlier_pictures(out, ["earlier.png"])
    args = ["ci", heavy_package, "--no-sim", "--build-dir", tmp_path / "build",
            "--render-dir", out]
    result = _signal_while_drawing(args, tmp_path, signal.SIGTERM)
    _assert_ended_cleanly(*result, signal.SIGTERM, out, before)


@pytest.mark.parametrize("renderer", ["gl", "raycast"])
def test_the_drawing_process_imports_nothing_from_the_working_folder(
        run_mcar, repo, tmp_path, renderer, request):
    """`python -c` puts the working folder first on the module path: a package under test
    holding a moderngl.py or numpy.py ran it in the GL probe, as the user."""
    request.getfixturevalue("gl_available" if renderer == "gl" else "raycast_available")
    folder = tmp_path / "hostile_package"
    folder.mkdir()
    marker = tmp_path / "ran"
    for name in ("moderngl", "numpy", "trimesh", "embreex", "mobile_car"):
        (folder / f"{name}.py").write_text(
            f"open({str(marker)!r}, 'a').write({name!r})\nraise ImportError('planted')\n")
    result = run_mcar("render", repo / "urdf" / "tutorial" / "03_color.urdf", "-o",
                      tmp_path / "r.png", "--size", "160x120", "--renderer", renderer,
                      cwd=folder)
    assert result.returncode == 0, result.stderr
    assert not marker.exists(), marker.read_text()
    assert (tmp_path / "r.png").read_bytes().startswith(b"\x89PNG")
