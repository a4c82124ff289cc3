"""What the drawing process sends back is data, checked and bounded (issue 32, items 1 and 3).

The drawing process works on an untrusted mesh in C code (llvmpipe, Embree); were that code
ever subverted, all it could do to mcar is answer. Here a stand-in drawing process, started
the way mcar starts the real one, answers as an attacker would: a pickle, garbage, a header
or a body of gigabytes, the wrong picture size, an answer out of turn, terminal escapes.
Each ends in DrawingFailed with a one-line reason, quickly, the child killed, nothing
executed; a well-behaved stand-in shows the same harness passing pixels through.
"""

from __future__ import annotations

import resource
import time

import numpy as np
import pytest

from mobile_car.render import drawing
from mobile_car.render.camera import fit_camera
from mobile_car.render.drawing import DrawingFailed, DrawingProcess, RemoteRenderer

# A stand-in for the drawing process; MCAR_TEST_ANSWER says how it misbehaves.
STAND_IN = r"""
import json, os, pickle, struct, sys, time

case = os.environ["MCAR_TEST_ANSWER"]
marker = os.environ["MCAR_TEST_MARKER"]


class Planted:
    def __reduce__(self):
        return (os.system, (f"touch {marker}",))


def send(header, body=b"", claimed=None):
    text = header if isinstance(header, bytes) else json.dumps(header).encode()
    length = len(body) if claimed is None else claimed
    os.write(1, struct.pack("!IQ", len(text), length) + text + body)


def exactly(count):
    data = b""
    while len(data) < count:
        chunk = os.read(0, count - len(data))
        if not chunk:
            sys.exit(0)
        data += chunk
    return data


def request():
    header_length, body_length = struct.unpack("!IQ", exactly(12))
    header = json.loads(exactly(header_length))
    exactly(body_length)
    return header


def draw_request():
    global scenes
    while True:
        header = request()
        if header["op"] == "draw":
            return header["camera"]
        scenes += 1


scenes = 0


def flood():
    chunk = bytes(1 << 20)
    try:
        while True:
            os.write(1, chunk)
    except OSError:
        sys.exit(0)


if case == "pickle":
    os.write(1, pickle.dumps(Planted()))
    time.sleep(60)
if case == "framed pickle":
    send(pickle.dumps(Planted()))
    time.sleep(60)
if case == "silent":
    sys.exit(3)
if case == "huge header":
    os.write(1, struct.pack("!IQ", 2**32 - 1, 0))
    flood()
send({"ok": True, "description": "stand-in"})
if case == "ready only":
    time.sleep(60)
if case == "early":
    camera = {"width": 40, "height": 30}
else:
    camera = draw_request()
size = {"width": camera["width"], "height": camera["height"]}
pixels = bytes(range(256)) * (camera["width"] * camera["height"] * 4 // 256 + 1)
pixels = pixels[:camera["width"] * camera["height"] * 4]
if case == "good":
    send({"ok": True, **size}, pixels)
    draw_request()
    if scenes == 1:
        send({"ok": True, **size}, pixels)
    else:
        send({"ok": False, "error": f"{scenes} scenes sent for one"})
elif case == "huge body":
    send({"ok": True, **size}, claimed=10 * 2**30)
    flood()
elif case == "wrong size":
    send({"ok": True, "width": camera["width"] + 1, "height": camera["height"]},
         pixels + bytes(camera["height"] * 4))
elif case == "ok is text":
    send({"ok": "yes", **size}, pixels)
elif case == "not an object":
    send([True, 1, 2])
elif case == "escapes":
    send({"ok": False, "error": "\x1b]0;owned\x07\x1b[2J" * 1000})
elif case == "early":
    send({"ok": True, **size}, pixels)
time.sleep(60)
"""


class _Scene:
    """The corner arrays of ``triangles`` triangles, as a Scene holds them."""

    def __init__(self, triangles: int):
        rng = np.random.default_rng(7)
        self.positions = rng.random((triangles * 3, 3), dtype=np.float32)
        self.normals = np.tile(np.float32([0, 0, 1]), (triangles * 3, 1))
        self.colors = np.ones((triangles * 3, 4), dtype=np.float32)

    @property
    def triangle_count(self) -> int:
        return len(self.positions) // 3


@pytest.fixture
def stand_in(monkeypatch, tmp_path):
    """stand_in(case) -> a started DrawingProcess that answers as ``case`` says."""
    monkeypatch.setattr(drawing, "_START", STAND_IN)
    marker = tmp_path / "unpickled"
    monkeypatch.setenv("MCAR_TEST_MARKER", str(marker))
    started = []

    def start(case: str) -> DrawingProcess:
        monkeypatch.setenv("MCAR_TEST_ANSWER", case)
        process = DrawingProcess("gl")
        started.append(process)
        return process

    yield start
    for process in started:
        process.kill()
    assert not marker.exists(), "the parent ran what the child sent"


def _draw(process: DrawingProcess, triangles: int = 4):
    scene = _Scene(triangles)
    camera = fit_camera("iso", scene.positions, 40, 30)
    renderer = RemoteRenderer(process, start_timeout=10)
    return renderer, scene, camera


@pytest.mark.parametrize("case, reason", [
    ("pickle", r"sent an answer with a header of \d+ bytes"),
    ("framed pickle", r"sent an unreadable answer \(UnicodeDecodeError\)"),
    ("huge header", r"sent an answer with a header of 4294967295 bytes"),
    ("silent", r"ended unexpectedly \(exit status 3\)"),
])
def test_a_bad_first_word_is_a_clean_failure(stand_in, case, reason):
    process = stand_in(case)
    started = time.monotonic()
    with pytest.raises(DrawingFailed, match=reason) as failure:
        process.first_answer(timeout=30)
    assert "\n" not in str(failure.value)
    assert time.monotonic() - started < 10
    assert not process.alive and process._popen.returncode is not None  # killed, reaped


def test_a_child_that_does_not_answer_is_killed_at_the_deadline(stand_in):
    process = stand_in("ready only")
    assert process.first_answer(timeout=30)["description"] == "stand-in"
    started = time.monotonic()
    with pytest.raises(TimeoutError):
        process.talk([b"a request it never answers"], timeout=0.5)
    assert time.monotonic() - started < 5
    assert not process.alive and process._popen.returncode is not None


@pytest.mark.parametrize("case, reason", [
    ("huge body", "an answer of 10737418240 bytes where 4800 were expected"),
    ("wrong size", "a picture of (41, 30) pixels where (40, 30) were asked for"),
    ("ok is text", "an answer that is not a drawing process's"),
    ("not an object", "an answer that is not a drawing process's"),
])
def test_a_bad_picture_is_a_clean_failure_and_is_not_read(stand_in, case, reason):
    process = stand_in(case)
    process.first_answer(timeout=30)
    renderer, scene, camera = _draw(process)
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    started = time.monotonic()
    with pytest.raises(DrawingFailed) as failure:
        renderer.draw(scene, camera)
    assert str(failure.value) == f"the drawing process sent {reason}"
    assert time.monotonic() - started < 10
    grown_mb = (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - peak) / 1024
    assert grown_mb < 64  # the 10 GB were not read
    assert not process.alive


def test_an_answer_before_the_request_is_read_is_refused(stand_in):
    process = stand_in("early")
    process.first_answer(timeout=30)
    renderer, scene, camera = _draw(process, triangles=20_000)  # 2.4 MB: more than a pipe
    with pytest.raises(DrawingFailed, match="an answer before it had read the request"):
        renderer.draw(scene, camera)


def test_the_childs_error_text_is_cut_and_shown_escaped(stand_in):
    process = stand_in("escapes")
    process.first_answer(timeout=30)
    renderer, scene, camera = _draw(process)
    with pytest.raises(DrawingFailed) as failure:
        renderer.draw(scene, camera)
    text = str(failure.value)
    assert text.startswith(r"\x1b]0;owned\x07\x1b[2J")
    assert all(c.isprintable() for c in text) and len(text) < 2000
    assert process.alive  # an error answer is in step: the process goes on


def test_a_well_behaved_child_passes_its_pixels_through(stand_in):
    process = stand_in("good")
    assert process.first_answer(timeout=30) == {"ok": True, "description": "stand-in"}
    renderer, scene, camera = _draw(process)
    first = renderer.draw(scene, camera)
    expected = (bytes(range(256)) * 19)[:40 * 30 * 4]
    assert first.shape == (30, 40, 4) and first.tobytes() == expected
    assert renderer.draw(scene, camera).tobytes() == expected  # (the scene sent once)
