"""Bad input, for every command: a one-line error naming the file, the right exit code, no
traceback, bounded time; no secret read; nothing earlier lost."""

from __future__ import annotations

import errno
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest
from conftest import MCAR, REPO, clean_environ, mcar_process

SECRET = "secret-content-7f3a"
DEEP = 100_000


def _bomb() -> bytes:
    levels = ['<!ENTITY lol0 "lol">'] + [
        f'<!ENTITY lol{i} "{f"&lol{i - 1};" * 10}">' for i in range(1, 10)]
    return (f'<?xml version="1.0"?>\n<!DOCTYPE robot [\n{chr(10).join(levels)}\n]>\n'
            '<robot name="r"><link name="&lol9;"/></robot>\n').encode()


def _xxe(secret: Path) -> bytes:
    return (f'<?xml version="1.0"?>\n<!DOCTYPE robot [<!ENTITY x SYSTEM "file://{secret}">]>\n'
            '<robot name="r"><link name="a"/><gazebo>&x;</gazebo>'
            '<link name="b&x;"/></robot>\n').encode()


# name -> (content or None for "make no file" / "directory", exit codes allowed)
CASES = {
    "empty": (b"", {1}),
    "binary_garbage": (bytes(range(256)) * 8, {1}),
    "not_utf8": (b'<?xml version="1.0" encoding="UTF-8"?>\n<robot name="r\xff\xfe">'
                 b'<link name="a"/></robot>\n', {1}),
    "deeply_nested": (b'<robot name="r">' + b"<a>" * DEEP + b"</a>" * DEEP + b"</robot>", {1}),
    "entity_bomb": (_bomb(), {1}),
    "missing": (None, {2}),
    "directory": ("dir", {2}),
}
COMMANDS = {
    "build": lambda f, out: ["build", f, "-o", out / "out.urdf"],
    "check": lambda f, out: ["check", f],
    "tree": lambda f, out: ["tree", f],
    "render": lambda f, out: ["render", f, "-o", out / "out.png", "--renderer", "raycast"],
}


def run(args, cwd, timeout=60, prefix=()) -> subprocess.CompletedProcess:
    if not prefix:
        return mcar_process(*args, cwd=cwd, timeout=timeout)
    return subprocess.run([*prefix, str(MCAR), *map(str, args)], cwd=cwd, capture_output=True,
                          text=True, timeout=timeout, env=clean_environ())


def assert_clean_failure(result, name: str, codes: set[int]) -> None:
    assert result.returncode in codes, (result.returncode, result.stderr)
    assert "Traceback" not in result.stderr and "internal error" not in result.stderr
    first = result.stderr.splitlines()[0]
    assert first.startswith(name) and ": error: " in first, result.stderr
    assert len(first) < 400


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.parametrize("case", CASES)
def test_bad_file_gets_one_located_error(tmp_path, case, command):
    content, codes = CASES[case]
    for suffix in (".urdf", ".xacro") if command in ("build", "render") else (".urdf",):
        name = case + suffix
        if content == "dir":
            (tmp_path / name).mkdir()
        elif content is not None:
            (tmp_path / name).write_bytes(content)
        result = run(COMMANDS[command](name, tmp_path), tmp_path)
        assert_clean_failure(result, name, codes)
        assert not list(tmp_path.glob("out.*")), "a failed run wrote an output"


@pytest.mark.parametrize("command", COMMANDS)
def test_external_entities_are_never_read(tmp_path, command):
    secret = tmp_path / "secret.txt"
    secret.write_text(SECRET)
    for suffix in (".urdf", ".xacro"):
        (tmp_path / f"xxe{suffix}").write_bytes(_xxe(secret))
        result = run(COMMANDS[command](f"xxe{suffix}", tmp_path), tmp_path)
        assert result.returncode in (0, 1, 2) and "Traceback" not in result.stderr
        outputs = [p.read_bytes() for p in tmp_path.glob("out.*")]
        assert all(SECRET.encode() not in data for data in outputs)
        assert SECRET not in result.stdout + result.stderr


def test_package_uri_may_not_escape_its_package(tmp_path):
    robot = tmp_path / "escape.urdf"
    robot.write_text('<robot name="r"><link name="a"><visual><geometry><mesh filename='
                     '"package://mobile_car_description/../../../../../etc/passwd"/>'
                     '</geometry></visual></link></robot>\n')
    check = run(["check", "--strict", robot.name], tmp_path)
    assert check.returncode == 1
    # out of every folder a robot may name files in: W215 (tests/untrusted/test_outside_roots.py)
    assert "escape.urdf:1: warning: mesh 'package://mobile_car_description/../../../../../" \
           "etc/passwd' is outside the folders a robot may name files in: " in check.stderr
    # render says the same, and draws a marker where that mesh would be: nothing is read.
    render = run(["render", robot.name, "-o", "out.png", "--renderer", "raycast"], tmp_path)
    assert render.returncode == 0
    assert "etc/passwd' is outside the folders a robot may name files in: " in render.stderr
    assert (tmp_path / "out.png").read_bytes().startswith(b"\x89PNG")


def test_too_large_for_xacro_is_refused_and_check_still_reads_it(tmp_path):
    sys.path.insert(0, str(REPO / "bench"))
    import generate

    big = tmp_path / "big.urdf"
    big.write_text(generate.robot(55_000, "tree", "repeated"))  # 50 MB
    assert big.stat().st_size > 50 * 1024 * 1024
    for args in (["build", big.name, "-o", "out.urdf"],
                 ["render", big.name, "-o", "out.png", "--renderer", "raycast"]):
        result = run(args, tmp_path, timeout=30)
        assert result.returncode == 2
        assert re.match(r"big\.urdf: error: 5\d MB is more than the 16 MB", result.stderr)
    check = run(["check", "-q", big.name], tmp_path, timeout=120)
    assert check.returncode == 0, check.stderr


def test_xacro_includes_that_include_each_other(tmp_path):
    (tmp_path / "a.xacro").write_text('<robot name="a" xmlns:xacro="http://www.ros.org/wiki/'
                                      'xacro"><xacro:include filename="b.xacro"/></robot>')
    (tmp_path / "b.xacro").write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
                                      '<xacro:include filename="a.xacro"/></robot>')
    for command in ("build", "check", "render"):
        result = run(COMMANDS[command]("a.xacro", tmp_path), tmp_path)
        assert_clean_failure(result, "", {1})
        assert "recursion too deep" in result.stderr
        assert len(result.stderr.splitlines()) < 12  # the repeated stack is collapsed


@pytest.fixture
def nobody():
    """Run a command as an unprivileged user (root reads and writes everything)."""
    if os.geteuid() != 0:
        return ()
    if shutil.which("setpriv") is None:
        pytest.skip("running as root without setpriv: cannot drop privileges")
    return ("setpriv", "--reuid=65534", "--regid=65534", "--clear-groups")


@pytest.fixture
def open_dir():
    """A folder every user can enter (pytest's tmp_path is private to its owner)."""
    path = Path(tempfile.mkdtemp(prefix="mcar-bad-"))
    path.chmod(0o755)
    yield path
    shutil.rmtree(path, ignore_errors=True)


@pytest.mark.parametrize("command", COMMANDS)
def test_unreadable_file(open_dir, nobody, command):
    source = open_dir / "secret.urdf"
    shutil.copy(REPO / "urdf" / "tutorial" / "01_skeleton.urdf", source)
    source.chmod(0o000)
    out = open_dir / "out"
    out.mkdir(mode=0o777)
    out.chmod(0o777)
    result = run(COMMANDS[command](source.name, out), open_dir, prefix=nobody)
    assert_clean_failure(result, "secret.urdf", {2})
    assert "permission denied" in result.stderr.lower()


@pytest.mark.parametrize("command", ["build", "render"])
def test_read_only_output_folder_keeps_nothing_half_written(open_dir, nobody, command):
    shutil.copy(REPO / "urdf" / "tutorial" / "04_xacro.xacro", open_dir / "car.xacro")
    (open_dir / "car.xacro").chmod(0o644)
    read_only = open_dir / "ro"
    read_only.mkdir()
    read_only.chmod(0o555)
    result = run(COMMANDS[command]("car.xacro", read_only), open_dir, prefix=nobody)
    assert result.returncode == 2, result.stderr
    assert "Traceback" not in result.stderr
    assert "ro/out." in result.stderr and ("cannot write" in result.stderr
                                          or "Permission denied" in result.stderr)
    assert os.listdir(read_only) == []


@pytest.mark.parametrize("command", ["build", "render"])
def test_full_disk_keeps_the_earlier_output(cli, tmp_path, monkeypatch, command):
    """A write that runs out of space (simulated) fails cleanly; the old output stays."""
    import mobile_car.atomic as atomic

    shutil.copy(REPO / "urdf" / "tutorial" / "04_xacro.xacro", tmp_path / "car.xacro")
    monkeypatch.chdir(tmp_path)
    args = [str(a) for a in COMMANDS[command]("car.xacro", tmp_path)]
    if command == "render":
        args.append("--force")
    first = cli(*args)
    assert first.exit_code == 0, first.output
    (output,) = tmp_path.glob("out.*")
    before = output.read_bytes()

    def no_space(fd):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(atomic.os, "fsync", no_space)
    second = cli(*args, "--quiet")
    assert second.exit_code == 2, second.output
    assert f"{output.name}: error: cannot write: No space left on device" in second.output
    assert output.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith(".out")) == []
