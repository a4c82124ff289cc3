"""`mcar view` against a hostile web page: another site open in the user's browser (a
foreign Origin, or a rebound DNS name: a foreign Host) is refused with 403, and whatever
reaches the server in viser's own wire format (msgpack), however wrong, is dropped with
one warning line and leaves the robot, and every later page, as they were.

The real viser server runs on 127.0.0.1, port 0; the attacks are made with the
`websockets` client viser itself depends on, and plain HTTP.
"""

from __future__ import annotations

import html
import http.client
import math
import os
import shutil
import socket
import sys
import time
from pathlib import Path

import numpy as np
import pytest

viser = pytest.importorskip("viser", reason='viser is not installed (pip install "mcar[view]";'
                                            " `make test` installs it)")
import msgspec  # noqa: E402  (viser's dependencies)
import websockets.exceptions  # noqa: E402
import zstandard  # noqa: E402
from websockets.sync.client import connect  # noqa: E402

ARM = Path(__file__).resolve().parent.parent / "view" / "arm"
EVIL = "http://evil.example.com"
SECONDS = 20  # every wait below is bounded by this
SLIDER_WARNING = ("mcar view: ignored what the page sent for the slider 'shoulder': 1e+308 "
                  "is not within -1.5..1.5 (more from it are ignored silently)")


@pytest.fixture
def served(tmp_path):
    """The arm robot served as `mcar view` serves it, its warnings written to stderr."""
    from mobile_car.load.inputs import RobotInput
    from mobile_car.load.robot import LoadOptions
    from mobile_car.view.model import load_model
    from mobile_car.view.server import RobotView

    shutil.copytree(ARM, tmp_path / "arm")
    inp, options = RobotInput(tmp_path / "arm" / "arm.urdf.xacro"), LoadOptions()
    view = RobotView(load_model(inp, options), lambda: load_model(inp, options),
                     host="127.0.0.1", port=0, warn=lambda text: print(text, file=sys.stderr))
    try:
        yield view
    finally:
        view.stop()


def _get(port: int, host: str) -> tuple[int, bytes]:
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=SECONDS)
    try:
        connection.putrequest("GET", "/", skip_host=True)
        connection.putheader("Host", host)
        connection.endheaders()
        response = connection.getresponse()
        return response.status, response.read()
    finally:
        connection.close()


def _page(port: int, host: str | None = None, origin: str | None = None):
    """A WebSocket to the server as viser's page opens it (Host from ``host``, default
    127.0.0.1:PORT; Origin ``origin``, default the page's own)."""
    host = host or f"127.0.0.1:{port}"
    sock = socket.create_connection(("127.0.0.1", port), timeout=SECONDS)
    return connect(f"ws://{host}/", sock=sock, origin=origin or f"http://{host}",
                   subprotocols=[f"viser-v{viser.__version__}"], open_timeout=SECONDS,
                   max_size=None)


def _scene(page) -> list[dict]:
    """The messages the server sends a new page, up to the end of its replay (viser's
    wire format: sizes, zstd-compressed msgpack, raw arrays)."""
    messages: list[dict] = []
    deadline = time.monotonic() + SECONDS
    while not any(message["type"] == "ReplayDoneMessage" for message in messages):
        frame = page.recv(timeout=max(0.0, deadline - time.monotonic()))
        inner = int.from_bytes(frame[:8], "little")
        packed = int.from_bytes(frame[8:16], "little")
        payload = zstandard.ZstdDecompressor().decompress(frame[16:16 + packed],
                                                          max_output_size=inner)
        messages += msgspec.msgpack.decode(payload)["messages"]
    return messages


def _slider(messages: list[dict], label: str) -> dict:
    (slider,) = [m for m in messages if m["type"] == "GuiSliderMessage"
                 and m["props"]["label"] == label]
    return slider


def _update(uuid: str, updates) -> bytes:
    return msgspec.msgpack.encode({"type": "GuiUpdateMessage", "uuid": uuid,
                                   "updates": updates})


def _until(condition, what: str) -> None:
    deadline = time.monotonic() + SECONDS
    while not condition():
        if time.monotonic() > deadline:
            pytest.fail(f"{what} within {SECONDS} s")
        time.sleep(0.02)


def _stderr_lines(capfd) -> list[str]:
    return capfd.readouterr().err.splitlines()


# -- who may connect ---------------------------------------------------------------------

def test_http_for_another_host_is_refused_and_the_page_is_served_to_its_own(served, capfd):
    port = served.port
    assert _get(port, "evil.example.com") == (403, b"Forbidden: mcar view answers only its "
                                                   b"own page.\n")
    assert _get(port, f"evil.example.com:{port}")[0] == 403  # DNS rebinding
    assert _get(port, "127.0.0.1:1")[0] == 403  # another port: not this page
    for host in (f"127.0.0.1:{port}", f"localhost:{port}", f"LOCALHOST:{port}"):
        status, body = _get(port, host)
        assert status == 200 and b"<html" in body.lower(), host
    assert _stderr_lines(capfd) == [
        "mcar view: refused a request (403): Host 'evil.example.com' is not this viewer's "
        "address",
        f"mcar view: refused a request (403): Host 'evil.example.com:{port}' is not this "
        "viewer's address",
        "mcar view: refused a request (403): Host '127.0.0.1:1' is not this viewer's address"]


def test_a_websocket_from_another_origin_is_refused(served, capfd):
    port = served.port
    with pytest.raises(websockets.exceptions.InvalidStatus) as refused:
        _page(port, origin=EVIL)
    assert refused.value.response.status_code == 403
    with pytest.raises(websockets.exceptions.InvalidStatus) as rebound:
        _page(port, host=f"evil.example.com:{port}")  # its own Origin, a rebound name
    assert rebound.value.response.status_code == 403
    with pytest.raises(websockets.exceptions.InvalidStatus) as null:
        _page(port, origin="null")  # a sandboxed frame, a file:// page
    assert null.value.response.status_code == 403
    # The same page again, asked a second time: refused again, said once.
    with pytest.raises(websockets.exceptions.InvalidStatus):
        _page(port, origin=EVIL)
    assert _stderr_lines(capfd) == [
        "mcar view: refused a request (403): a page at Origin 'http://evil.example.com' is "
        "not the viewer's own page",
        f"mcar view: refused a request (403): Host 'evil.example.com:{port}' is not this "
        "viewer's address",
        "mcar view: refused a request (403): a page at Origin 'null' is not the viewer's own "
        "page"]
    # Its own page connects and gets the robot.
    for host in (f"127.0.0.1:{port}", f"localhost:{port}"):
        with _page(port, host=host) as page:
            assert _slider(_scene(page), "shoulder")["value"] == 0.0


def test_who_may_connect_for_each_bind_address():
    from mobile_car.view.origin import PageOrigin

    loopback, v6, anywhere = PageOrigin("127.0.0.1"), PageOrigin("::1"), PageOrigin("0.0.0.0")
    assert loopback.allows("localhost") and not loopback.allows("::1")
    assert not loopback.allows("192.168.1.7") and not loopback.allows("evil.example.com")
    assert v6.allows("::1") and v6.allows("localhost") and not v6.allows("127.0.0.1")
    # Bound to every address: other machines use one of its addresses (a literal address
    # cannot be a rebound name) or its own name, never an arbitrary name.
    assert anywhere.allows("192.168.1.7") and anywhere.allows("fe80::1")
    assert anywhere.allows(socket.gethostname().lower())
    assert not anywhere.allows("evil.example.com")
    assert PageOrigin("robot-pc.lan").names == {"robot-pc.lan"}


# -- what the page may send --------------------------------------------------------------

@pytest.mark.parametrize("bad", [1e308, math.nan, -math.inf, "0.5", 2.0, True, None, [0.5]])
def test_a_bad_joint_value_is_dropped_with_one_warning(served, capfd, bad):
    port = served.port
    with _page(port) as page:
        uuid = _slider(_scene(page), "shoulder")["uuid"]
        for _ in range(50):  # a page sending as fast as it can: still one line
            page.send(_update(uuid, {"value": bad}))
        # Then a good update to another control: once it is applied, every bad one
        # before it on this connection has been handled.
        page.send(_update(served.show_frames._impl.uuid, {"value": True}))
        _until(lambda: served.show_frames.value is True, "the good update was not applied")
    assert served.joint_values() == {"shoulder": 0.0, "wrist": 0.0}
    assert np.allclose(served.frames["upper_arm"].wxyz, (1.0, 0.0, 0.0, 0.0))
    lines = _stderr_lines(capfd)
    assert len(lines) == 1, lines
    assert lines[0].startswith("mcar view: ignored what the page sent for the slider "
                               "'shoulder': ")
    if bad == 1e308:
        assert lines[0] == SLIDER_WARNING
    # A page that connects afterwards gets the whole robot, the joint where it was.
    with _page(port) as page:
        scene = _scene(page)
    assert _slider(scene, "shoulder")["value"] == 0.0
    assert not [m for m in scene if m["type"] == "GuiUpdateMessage" and m["uuid"] == uuid]
    assert any(m["type"] == "GuiCheckboxMessage" and m["props"]["label"] == "Link frames"
               for m in scene)


def test_a_good_joint_value_moves_the_joint(served, capfd):
    with _page(served.port) as page:
        uuid = _slider(_scene(page), "shoulder")["uuid"]
        page.send(_update(uuid, {"value": 1}))  # JavaScript sends whole numbers as ints
        _until(lambda: served.joint_values()["shoulder"] == 1.0, "the joint did not move")
    assert _stderr_lines(capfd) == []


def test_every_kind_of_bad_message_is_one_line_and_the_server_goes_on(served, capfd):
    port = served.port
    with _page(port) as page:
        scene = _scene(page)
        shoulder = _slider(scene, "shoulder")["uuid"]
        frames = served.show_frames._impl.uuid
        reset = served.reset._impl.uuid
        # Properties other than the value: viser would store them on the control (its
        # callbacks among them), for every page.
        page.send(_update(shoulder, {"value": 0.5, "sync_cb": 1}))
        page.send(_update(shoulder, {"max": 1e308}))
        page.send(_update(frames, {"value": "yes"}))  # a string for a checkbox
        page.send(_update(reset, {"value": 7}))  # a button press is true
        page.send(_update(shoulder, []))  # updates that are no mapping
        page.send(_update("no-such-control", {"value": 1.0}))  # quietly dropped
        page.send(_update(frames, {"value": True}))
        _until(lambda: served.show_frames.value is True, "the good update was not applied")
    assert served.joint_values()["shoulder"] == 0.0 and served.sliders["shoulder"].max == 1.5
    assert _stderr_lines(capfd) == [
        "mcar view: ignored what the page sent for the slider 'shoulder': it may change "
        "only its value, not ['sync_cb', 'value'] (more from it are ignored silently)",
        "mcar view: ignored what the page sent for the checkbox 'Link frames': 'yes' is not "
        "true or false (more from it are ignored silently)",
        "mcar view: ignored what the page sent for the button 'Reset joints': 7 is no button "
        "press (more from it are ignored silently)"]
    # A message viser cannot decode closes that connection only, with one line for all of
    # them. (A connection each: a second message on a connection the first closed may not
    # even be sent.)
    for garbage in (b"\xc1", msgspec.msgpack.encode({"type": "GuiUpdateMessage"})):
        with _page(port) as page:
            _scene(page)
            page.send(garbage)
            with pytest.raises(websockets.exceptions.ConnectionClosed):
                page.recv(timeout=SECONDS)
    lines = _stderr_lines(capfd)
    assert len(lines) == 1 and lines[0].startswith(
        "mcar view: closed a connection that sent a message viser cannot read ("), lines
    with _page(port) as page:
        assert _slider(_scene(page), "shoulder")["value"] == 0.0


def test_mcar_view_refuses_another_origin_and_says_so_on_stderr(run_mcar, tmp_path):
    """The command itself: its warnings reach stderr, one line each."""
    import subprocess

    shutil.copytree(ARM, tmp_path / "arm")
    mcar = Path(sys.executable).parent / "mcar"
    process = subprocess.Popen([str(mcar), "view", "--no-browser", "--port", "0",
                                "arm.urdf.xacro"], cwd=tmp_path / "arm", text=True,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        url = process.stdout.readline().split(" at ")[1].split(" ")[0]
        port = int(url.rstrip("/").rsplit(":", 1)[1])
        assert _get(port, f"evil.example.com:{port}")[0] == 403
        with pytest.raises(websockets.exceptions.InvalidStatus):
            _page(port, origin=EVIL)
        with _page(port) as page:
            uuid = _slider(_scene(page), "shoulder")["uuid"]
            page.send(_update(uuid, {"value": 1e308}))
            page.send(_update(uuid, {"value": math.nan}))
        with _page(port) as page:
            assert _slider(_scene(page), "shoulder")["value"] == 0.0
    finally:
        process.terminate()
        _, err = process.communicate(timeout=SECONDS)
    assert process.returncode == 143
    assert err.splitlines() == [
        f"mcar view: refused a request (403): Host 'evil.example.com:{port}' is not this "
        "viewer's address",
        "mcar view: refused a request (403): a page at Origin 'http://evil.example.com' is "
        "not the viewer's own page",
        SLIDER_WARNING,
        "mcar: terminated"], err


def test_an_upload_against_a_control_is_dropped_unread(served, capfd):
    """mcar's page has no upload control; viser would buffer the parts of an upload
    started against any of its input controls (a slider's id does), without a bound."""
    with _page(served.port) as page:
        uuid = _slider(_scene(page), "shoulder")["uuid"]
        page.send(msgspec.msgpack.encode({
            "type": "FileTransferStartUpload", "source_component_uuid": uuid,
            "transfer_uuid": "t", "filename": "x", "mime_type": "a/b",
            "part_count": 1000, "size_bytes": 1 << 30}))
        for index in range(20):
            page.send(msgspec.msgpack.encode({
                "type": "FileTransferPart", "source_component_uuid": uuid,
                "transfer_uuid": "t", "part_index": index, "content": b"x" * 100_000}))
        page.send(_update(uuid, {"value": 1}))  # processed after the upload's messages
        _until(lambda: served.joint_values()["shoulder"] == 1.0, "the joint did not move")
    assert served.server.gui._current_file_upload_states == {}
    assert _stderr_lines(capfd) == []


def test_markup_in_an_error_message_is_shown_as_text(served):
    """A file the viewer reloads is the attacker's: its names reach the page inside the
    error message. The error box is HTML (so that it wraps): every character of the
    message is text there, never an element, an attribute or a script."""
    robot = next(path for path in served.model.files if path.name == "arm.urdf.xacro")
    markup = "&lt;img src=x onerror=&quot;fetch('//evil.example.com')&quot;&gt;"
    text = robot.read_text()
    robot.write_text(text.replace('<child link="upper_arm"/>', f'<child link="{markup}"/>', 1))
    stat = robot.stat()  # (a later stamp than the one recorded, even on a coarse clock)
    os.utime(robot, ns=(stat.st_atime_ns, stat.st_mtime_ns + 10**9))
    _, error = served.reload_if_changed()
    assert error is not None
    # The control: the message itself holds the markup, as the file wrote it.
    quoted = "<img src=x onerror=\"fetch('//evil.example.com')\">"
    assert any(quoted in line for line in served.errors), served.errors
    box = served.error_box.content
    assert "<img" not in box and "onerror=\"" not in box
    assert html.escape(quoted, quote=True) in box
    assert box.startswith('<div class="mcar-errors" ') and box.endswith("</div>")
    assert box.count("<") == 2  # its own <div> and </div>, nothing of the file's


def test_a_dimension_takes_its_plausible_range_from_the_page_and_nothing_past_it(repo,
                                                                                 capfd):
    """A dimension's box takes values past its slider's ends (the slider spans only the
    neighbourhood of the value), but nothing outside the dimension's plausible range: the
    page's values are still checked before they touch the robot."""
    from mobile_car.load.inputs import RobotInput
    from mobile_car.load.robot import LoadOptions
    from mobile_car.view.dimensions import robot_dimensions
    from mobile_car.view.model import load_model
    from mobile_car.view.server import RobotView

    inp, options = RobotInput(repo / "urdf" / "mobile_robot.xacro"), LoadOptions()
    model = load_model(inp, options)
    dimensions = robot_dimensions(inp, options, model)
    view = RobotView(model, dimensions.load, host="127.0.0.1", port=0, dimensions=dimensions,
                     warn=lambda text: print(text, file=sys.stderr))
    try:
        from mobile_car.view.inbound import refusal

        wheel = view.dimension_sliders["wheel_radius"]
        assert wheel.max == 0.065  # its slider; the range is 5 mm..0.5 m
        # the check by the slider alone refuses 0.1; by the dimension's range, not 0.6
        assert refusal(wheel, {"value": 0.1}) == "0.1 is not within 0.0162..0.065"
        assert refusal(wheel, {"value": 0.6}, (0.005, 0.5)) == "0.6 is not within 0.005..0.5"
        with _page(view.port) as page:
            uuid = _slider(_scene(page), "wheel_radius (m)")["uuid"]
            for bad in (0.6, 1e308, -0.01):
                page.send(_update(uuid, {"value": bad}))
            page.send(_update(uuid, {"value": 0.1}))  # past the slider, inside the range
            # (viser applied it: a value the check refuses never reaches the slider)
            _until(lambda: wheel.value == 0.1, "the value past the slider's end was not taken")
        lines = _stderr_lines(capfd)
        assert lines == ["mcar view: ignored what the page sent for the slider "
                         "'wheel_radius (m)': 0.6 is not within 0.005..0.5 (more from it are "
                         "ignored silently)"], lines
    finally:
        view.stop()
