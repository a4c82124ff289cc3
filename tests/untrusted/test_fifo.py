"""No waiting for ever: a FIFO, socket or device named where mcar expects a file (an
INPUT, an include, ``--config``, a mesh) is refused with one line naming it and what it
is, without being opened for a blocking read.

Nothing ever writes to these FIFOs: ``open()`` of one blocks until a writer comes, so an
mcar that opened it the ordinary way would hang until the subprocess timeout (a xacro
include would end after the child's 60 s, saying "runaway expression"). Each run must
end well inside that.
"""

from __future__ import annotations

import os
import re
import socket
import threading
import time

import pytest

# Well under the xacro child's 60 s, with room for a loaded machine's start-up.
SECONDS = 15
ROBOT = '<robot name="r">\n  <link name="a"/>\n</robot>\n'
INCLUDER = ('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            '  <link name="a"/>\n'
            '  <xacro:include filename="inc.xacro"{optional}/>\n'
            '</robot>\n')
MESH_ROBOT = ('<robot name="r">\n  <link name="a">\n    <visual>\n      <geometry>\n'
              '        <mesh filename="pipe.stl"/>\n      </geometry>\n    </visual>\n'
              '  </link>\n</robot>\n')
_SUMMARY = re.compile(r"^(mcar check: |\d+ pictures? in |0 of \d+ files? built)")


def _run_quickly(run_mcar, *args, cwd, **kwargs):
    start = time.monotonic()
    result = run_mcar(*args, cwd=cwd, timeout=SECONDS, **kwargs)
    assert time.monotonic() - start < SECONDS
    assert "Traceback" not in result.stderr and "internal error" not in result.stderr, \
        result.stderr
    return result


def _error_lines(stderr: str) -> list[str]:
    return [line for line in stderr.splitlines() if not _SUMMARY.match(line)]


@pytest.fixture
def fifo(tmp_path):
    def make(name: str):
        os.mkfifo(tmp_path / name)
        return tmp_path / name

    return make


@pytest.mark.parametrize("command", [["check"], ["build", "-o", "out.urdf"],
                                     ["tree"]])
@pytest.mark.parametrize("name", ["pipe.urdf", "pipe.urdf.xacro"])
def test_fifo_as_input_is_refused(run_mcar, fifo, tmp_path, command, name):
    fifo(name)
    result = _run_quickly(run_mcar, command[0], name, *command[1:], cwd=tmp_path)
    assert result.returncode == 2, result.stderr
    assert _error_lines(result.stderr) == [f"{name}: error: is a FIFO, not a regular file"]
    assert not (tmp_path / "out.urdf").exists()


def test_fifo_as_config_is_refused(run_mcar, fifo, tmp_path, package_copy):
    fifo("pipe.yaml")
    result = _run_quickly(run_mcar, "config", "--config", tmp_path / "pipe.yaml",
                          cwd=package_copy)
    assert result.returncode == 2, result.stderr
    assert _error_lines(result.stderr) == [
        f"{tmp_path / 'pipe.yaml'}: error: is a FIFO, not a regular file"]
    result = _run_quickly(run_mcar, "build", "--config", tmp_path / "pipe.yaml",
                          cwd=package_copy)
    assert result.returncode == 2, result.stderr
    assert _error_lines(result.stderr) == [
        f"{tmp_path / 'pipe.yaml'}: error: is a FIFO, not a regular file"]
    assert not (package_copy / "build").exists()


@pytest.mark.parametrize("sandbox", [[], ["--no-sandbox"]], ids=["sandboxed", "trusted"])
@pytest.mark.parametrize("optional", ["", ' optional="true"'], ids=["plain", "optional"])
def test_fifo_as_include_is_refused_like_a_missing_include(run_mcar, fifo, tmp_path,
                                                             sandbox, optional):
    """Exit 1 and located at the include, as a missing include is; an optional include
    (skipped when missing) is refused too: the FIFO is there, and hostile."""
    fifo("inc.xacro")
    (tmp_path / "top.urdf.xacro").write_text(INCLUDER.format(optional=optional))
    result = _run_quickly(run_mcar, "build", "top.urdf.xacro", "-o", "out.urdf", *sandbox,
                          cwd=tmp_path)
    assert result.returncode == 1, result.stderr
    assert _error_lines(result.stderr) == [
        "top.urdf.xacro:3: error: cannot read inc.xacro: is a FIFO, not a regular file",
        "  when processing file: top.urdf.xacro"]
    assert not (tmp_path / "out.urdf").exists()


@pytest.mark.parametrize("sandbox", [[], ["--no-sandbox"]], ids=["sandboxed", "trusted"])
def test_fifo_as_xacro_load_yaml_is_refused(run_mcar, fifo, tmp_path, sandbox):
    """xacro opens a YAML file itself (``xacro.load_yaml``): refused there too."""
    fifo("dims.yaml")
    (tmp_path / "robot.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <link name="a"/>\n'
        """  <xacro:property name="dims" value="${xacro.load_yaml('dims.yaml')}"/>\n"""
        '  <link name="${dims.name}"/>\n</robot>\n')
    result = _run_quickly(run_mcar, "build", "robot.urdf.xacro", *sandbox, cwd=tmp_path)
    assert result.returncode == 1, result.stderr
    first = result.stderr.splitlines()[0]
    assert first.startswith("robot.urdf.xacro:3: error: dims.yaml: is a FIFO, not a "
                            "regular file"), result.stderr


def test_fifo_included_by_a_file_in_a_folder_fails_that_file_only(run_mcar, fifo, tmp_path):
    """A folder holding a FIFO among its robot files: the FIFO is no robot file (it is
    never read to find out), and a file including one fails alone."""
    fifo("inc.xacro")
    fifo("other.urdf")
    (tmp_path / "top.urdf.xacro").write_text(INCLUDER.format(optional=""))
    (tmp_path / "good.urdf").write_text(ROBOT)
    result = _run_quickly(run_mcar, "build", ".", "-o", "out/", cwd=tmp_path)
    assert result.returncode == 1, result.stderr
    assert "top.urdf.xacro:3: error: cannot read inc.xacro: is a FIFO" in result.stderr
    assert (tmp_path / "out" / "good.urdf").is_file()


def test_fifo_as_mesh_is_a_warning_in_check(run_mcar, fifo, tmp_path):
    fifo("pipe.stl")
    (tmp_path / "robot.urdf").write_text(MESH_ROBOT)
    result = _run_quickly(run_mcar, "check", "robot.urdf", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "W207" in result.stdout + result.stderr
    assert "mesh 'pipe.stl' is a FIFO, not a regular file" in result.stdout + result.stderr


def test_fifo_as_mesh_is_a_marker_in_render(run_mcar, fifo, tmp_path):
    """Never opened: the picture is drawn at once, a marker where the mesh belongs."""
    pytest.importorskip("trimesh")
    fifo("pipe.stl")
    (tmp_path / "robot.urdf").write_text(MESH_ROBOT)
    result = _run_quickly(run_mcar, "render", "robot.urdf", "-o", "out.png", "--renderer",
                          "raycast", "--size", "64x64", "-q", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert _error_lines(result.stderr) == [
        "robot.urdf:5: warning: mesh 'pipe.stl' is a FIFO, not a regular file [W207]"]
    assert (tmp_path / "out.png").read_bytes().startswith(b"\x89PNG")


def test_unix_socket_as_input_is_refused(run_mcar, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # a socket's path is limited to ~100 bytes: bind it short
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as server:
        server.bind("sock.urdf")
        server.listen()
        result = _run_quickly(run_mcar, "check", "sock.urdf", cwd=tmp_path)
    assert result.returncode == 2, result.stderr
    assert _error_lines(result.stderr) == ["sock.urdf: error: is a socket, not a regular file"]


@pytest.mark.parametrize("device", ["/dev/null", "/dev/zero"])
@pytest.mark.parametrize("stdin", ["", None], ids=["stdin-pipe", "stdin-inherited"])
def test_device_as_input_is_refused(run_mcar, tmp_path, device, stdin):
    result = _run_quickly(run_mcar, "build", device, "-o", "out.urdf", input=stdin,
                          cwd=tmp_path)
    assert result.returncode == 2, result.stderr
    assert _error_lines(result.stderr) == [
        f"{device}: error: is a character device, not a regular file"]


def test_dev_stdin_with_a_pipe_reads_like_dash(run_mcar, tmp_path):
    """docs/commands.md, Inputs: /dev/stdin named as INPUT is read as `-` is (a pipe is
    the point)."""
    result = _run_quickly(run_mcar, "build", "/dev/stdin", input=ROBOT, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert '<link name="a"/>' in result.stdout
    result = _run_quickly(run_mcar, "check", "/dev/stdin", "-", input=ROBOT, cwd=tmp_path)
    assert result.returncode == 2
    assert "- (stdin) can be given only once" in result.stderr


def test_a_name_swapped_for_a_fifo_after_stat_is_refused_without_blocking(tmp_path,
                                                                           monkeypatch):
    """The race: the name was a regular file when stat'ed and is a FIFO when opened. The
    open must not block, and the opened file's own fstat refuses it."""
    from mobile_car.load import bounded

    regular = tmp_path / "regular.urdf"
    regular.write_text(ROBOT)
    os.mkfifo(tmp_path / "swapped.urdf")
    real_stat = os.stat
    monkeypatch.setattr(bounded.os, "stat",
                        lambda path, *a, **k: real_stat(regular) if str(path).endswith(
                            "swapped.urdf") else real_stat(path, *a, **k))
    outcome: list = []

    def read():
        try:
            bounded.read_input(tmp_path / "swapped.urdf", "swapped.urdf")
        except Exception as error:  # what we assert on below
            outcome.append(error)

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    reader.join(SECONDS)
    if reader.is_alive():  # let the blocked open() return, then fail
        os.close(os.open(tmp_path / "swapped.urdf", os.O_WRONLY | os.O_NONBLOCK))
        pytest.fail("read_input blocked on a FIFO")
    assert isinstance(outcome[0], bounded.NotRegularFile)
    assert str(outcome[0]) == "swapped.urdf: is a FIFO, not a regular file"
