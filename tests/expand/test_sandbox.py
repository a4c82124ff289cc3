"""A xacro is code: the sandboxed child that evaluates it can neither run programs, open
sockets, write or change files, signal other processes, nor read outside the package.

Each attack is a file in sandbox/ (it reaches ``os`` through a comprehension, which xacro's
``__`` guard does not see); its second line says the error it must end in. Every attack
that would leave a trace targets the file PWNED in the working folder.
"""

from __future__ import annotations

import errno
import os
import re
import resource
import shutil
import signal
import socket
import subprocess
import time
from pathlib import Path

import pytest

from mobile_car.expand import sandbox

CASES = sorted((Path(__file__).parent / "sandbox").glob("*.xacro"))
SUPPORT = sandbox.support()
needs_seccomp = pytest.mark.skipif(SUPPORT.seccomp is not None,
                                   reason=f"seccomp unavailable: {SUPPORT.seccomp}")
needs_landlock = pytest.mark.skipif(not SUPPORT.landlock_abi,
                                    reason=f"Landlock unavailable: {SUPPORT.landlock_reason}")


def _expected(case: Path) -> str:
    return re.search(r"<!-- expect: (.*) -->", case.read_text()).group(1)


def _attack_line(case: Path) -> int:
    return next(n for n, line in enumerate(case.read_text().splitlines(), 1) if "${" in line)


@pytest.mark.parametrize("command", ["build", "check", "tree", "render"])
@pytest.mark.parametrize("case", CASES, ids=lambda p: p.stem)
def test_attack_fails_located_and_leaves_nothing(run_mcar, tmp_path, case, command):
    if case.stem == "read_secret" and not SUPPORT.landlock_abi:
        pytest.skip(f"reads are confined by Landlock only: {SUPPORT.landlock_reason}")
    shutil.copy(case, tmp_path / case.name)
    extra = {"build": ["-o", "out.urdf"], "render": ["-o", "out.png"]}.get(command, [])
    result = run_mcar(command, case.name, *extra, cwd=tmp_path)
    first = result.stderr.splitlines()[0]
    assert result.returncode == 1, result.stderr
    assert first.startswith(f"{case.name}:{_attack_line(case)}: error: {_expected(case)}"), first
    assert "Traceback" not in result.stderr and "internal error" not in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == [case.name]  # no PWNED, no output


def test_without_the_sandbox_the_attack_works(run_mcar, tmp_path):
    """The control: the attack files are real attacks, so the test above can fail."""
    case = next(c for c in CASES if c.stem == "run_program")
    shutil.copy(case, tmp_path / case.name)
    result = run_mcar("build", case.name, "-o", "out.urdf", "--no-sandbox", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "PWNED").exists()


def _syscall(name: str, *args) -> str:
    """Make system call ``name`` with ``args`` through libc: its errno's name, or "done"."""
    import ctypes

    import pyseccomp

    libc = ctypes.CDLL(None, use_errno=True)
    number = pyseccomp.resolve_syscall(pyseccomp.system_arch(), name)
    if libc.syscall(number, *args) == 0:
        return "done"
    return errno.errorcode[ctypes.get_errno()]


def _queued():
    """A siginfo as sigqueue(3) fills it (si_code SI_QUEUE): what a process may queue to
    another of its user's."""
    import ctypes

    info = (ctypes.c_int * 32)()
    info[2] = -1
    return info


def _in_confined_child(layer, probe) -> str:
    """Run probe() in a forked child confined by one layer only (no audit hook): what the
    kernel alone refuses. Returns the child's report."""
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(read)
        try:
            layer()
            report = probe()
        except BaseException as error:  # noqa: BLE001 - reported to the parent
            report = f"{type(error).__name__}: {error}"
        os.write(write, str(report).encode()[:4000])
        os._exit(0)
    os.close(write)
    with os.fdopen(read, "rb") as pipe:
        report = pipe.read().decode()
    os.waitpid(pid, 0)
    return report


@needs_seccomp
@pytest.mark.parametrize("probe, expected", [
    (lambda: os.system("true"), "32512"),  # the shell ran, but not `true` (127 << 8)
    (lambda: os.open("PWNED", os.O_WRONLY | os.O_CREAT), "PermissionError: [Errno 1]"),
    (lambda: os.open("/etc/hostname", os.O_RDWR), "PermissionError: [Errno 1]"),
    (lambda: socket.socket(), "PermissionError: [Errno 1]"),
    (lambda: os.kill(os.getppid(), 0), "PermissionError: [Errno 1]"),
    (lambda: os.mkdir("PWNED"), "PermissionError: [Errno 1]"),
    (lambda: len(open("/etc/hostname", "rb").read()) > 0, "True"),  # reading is allowed
    # Nothing that names another process: each probe would leave the parent as it is.
    (lambda: os.kill(0, 0), "PermissionError: [Errno 1]"),  # its process group
    (lambda: _syscall("rt_sigqueueinfo", os.getppid(), 0, _queued()), "EPERM"),
    (lambda: _syscall("rt_tgsigqueueinfo", os.getppid(), os.getppid(), 0, _queued()), "EPERM"),
    (lambda: os.setpriority(os.PRIO_PROCESS, os.getppid(),
                            os.getpriority(os.PRIO_PROCESS, os.getppid())),
     "PermissionError: [Errno 1]"),
    (lambda: os.sched_setaffinity(os.getppid(), os.sched_getaffinity(os.getppid())),
     "PermissionError: [Errno 1]"),
    (lambda: resource.prlimit(os.getppid(), resource.RLIMIT_NOFILE),
     "PermissionError: [Errno 13]"),
    (lambda: os.pidfd_open(os.getppid()), "PermissionError: [Errno 1]"),
    (lambda: _syscall("kcmp", os.getpid(), os.getppid(), 0, 0, 0), "EPERM"),
    (lambda: _syscall("process_vm_readv", os.getppid(), None, 0, None, 0, 0), "EPERM"),
    (lambda: _syscall("ptrace", 16, os.getppid(), None, None), "EPERM"),  # PTRACE_ATTACH
    # Its own limits it reads, and may not change (starving its files or CPU).
    (lambda: resource.setrlimit(resource.RLIMIT_NOFILE,
                                resource.getrlimit(resource.RLIMIT_NOFILE)),
     "PermissionError: [Errno 13]"),
    (lambda: resource.getrlimit(resource.RLIMIT_NOFILE)[0] > 0, "True"),
    (lambda: os.kill(os.getpid(), 0) is None, "True"),  # itself, as Python may
])
def test_seccomp_alone_refuses(tmp_path, monkeypatch, probe, expected):
    monkeypatch.chdir(tmp_path)
    assert _in_confined_child(sandbox._deny_syscalls, probe).startswith(expected)
    assert not (tmp_path / "PWNED").exists()


@needs_landlock
def test_landlock_alone_confines_reads(tmp_path):
    (tmp_path / "inside.txt").write_text("ok")

    def probe():
        inside = (tmp_path / "inside.txt").read_text()
        try:
            open("/etc/hostname").read()
        except PermissionError as error:
            return f"{inside} {error.strerror}"
        return "read /etc/hostname"

    layer = lambda: sandbox._restrict_reads([tmp_path])  # noqa: E731
    assert _in_confined_child(layer, probe) == "ok Permission denied"


def test_version_verbose_says_what_the_sandbox_uses(run_mcar):
    result = run_mcar("--version", "--verbose")
    assert result.returncode == 0
    lines = result.stdout.splitlines()
    assert lines[0] == "mcar, version 0.1.0"
    assert lines[1] == ("sandbox seccomp: on (no programs, sockets, file writes or calls on "
                        "other processes)"
                        if SUPPORT.seccomp is None else
                        f"sandbox seccomp: unavailable: {SUPPORT.seccomp}")
    assert lines[2].startswith("sandbox landlock: on, ABI" if SUPPORT.landlock_abi
                               else "sandbox landlock: unavailable")


def _children(pid: int) -> list[int]:
    try:
        text = Path(f"/proc/{pid}/task/{pid}/children").read_text()
    except OSError:
        return []
    return [int(p) for p in text.split()]


def _alive(pid: int) -> bool:
    try:
        return Path(f"/proc/{pid}/stat").read_text().split(")")[-1].split()[0] != "Z"
    except OSError:
        return False


@pytest.mark.parametrize("how", ["SIGKILL", "SIGTERM"])
def test_the_xacro_child_dies_with_mcar(mcar_bin, tmp_path, how):
    (tmp_path / "slow.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<link name="${9**9**9}"/></robot>')
    mcar = subprocess.Popen([str(mcar_bin), "build", "slow.xacro", "-o", "out.urdf"],
                            cwd=tmp_path, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 30
    while not _children(mcar.pid) and time.monotonic() < deadline:
        time.sleep(0.05)
    children = _children(mcar.pid)
    assert children, "mcar never started its xacro child"
    mcar.send_signal(getattr(signal, how))
    mcar.wait(timeout=10)
    deadline = time.monotonic() + 5
    while any(map(_alive, children)) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not any(map(_alive, children)), f"xacro child outlived mcar after {how}"
    assert mcar.returncode == (-signal.SIGKILL if how == "SIGKILL" else 143)
    assert not (tmp_path / "out.urdf").exists()


def _after_die_with_parent(parent_of) -> tuple[int, bytes]:
    """(exit status, what it wrote) of a forked child that calls die_with_parent with
    ``parent_of(its real parent's pid)``, then says it is alive."""
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(read)
        try:
            sandbox.die_with_parent(parent_of(os.getppid()))
            os.write(write, b"alive")
        finally:
            os._exit(0)
    os.close(write)
    with os.fdopen(read, "rb") as pipe:
        said = pipe.read()
    return os.waitstatus_to_exitcode(os.waitpid(pid, 0)[1]), said


def test_a_forked_child_whose_parent_is_already_gone_leaves_at_once():
    """The pid before the fork is the parent to outlive: a child that finds another one
    (mcar was killed before the child ran, and it was handed to init) ends at once."""
    assert _after_die_with_parent(lambda real: real + 1) == (1, b"")
    assert _after_die_with_parent(lambda real: real) == (0, b"alive")  # the control


def test_render_of_several_files_bounds_every_expansion(run_mcar, tmp_path, repo,
                                                        quiet_renderer):
    """render finishes pictures on a worker thread; the expansions after the first must
    still run in the confined, time-limited child."""
    good = repo / "urdf" / "tutorial" / "04_xacro.xacro"
    shutil.copy(good, tmp_path / "a.xacro")
    shutil.copy(good, tmp_path / "b.xacro")
    shutil.copy(next(c for c in CASES if c.stem == "run_program"), tmp_path / "c.xacro")
    (tmp_path / "d.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '<link name="${9**9**9}"/></robot>\n')
    result = run_mcar("render", "a.xacro", "b.xacro", "c.xacro", "d.xacro",
                      *quiet_renderer, "-o", "pictures", cwd=tmp_path,
                      env={"MCAR_XACRO_TIMEOUT": "3"}, timeout=120)
    assert result.returncode == 1, result.stderr
    assert "c.xacro:5: error: the xacro sandbox forbids running programs" in result.stderr
    assert "d.xacro: error: xacro did not finish within 3 s" in result.stderr
    assert not (tmp_path / "PWNED").exists()
    assert sorted(p.name for p in (tmp_path / "pictures").glob("*.png")) == ["a.png", "b.png"]


@needs_landlock
def test_a_fresh_mcar_finds_libseccomp_by_soname_and_runs_yaml_in_the_child(mcar_bin,
                                                                             tmp_path):
    """pyseccomp is imported without ctypes.util (no `ldconfig -p` process, no shutil or
    subprocess: sandbox.import_pyseccomp), so nothing mapped libz into mcar by the way:
    the sandboxed child, which Landlock keeps out of the system's library folder, must
    still import PyYAML (at xacro's first $(...)), whose base64 needs libz. A real
    process: the tests' launcher has preloaded both."""
    package = tmp_path / "demo_pkg"
    (package / "urdf").mkdir(parents=True)
    (package / "package.xml").write_text("<package><name>demo_pkg</name></package>\n")
    (package / "urdf" / "part.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="part"/></robot>\n')
    robot = package / "urdf" / "robot.urdf.xacro"
    robot.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                     '  <xacro:include filename="$(find demo_pkg)/urdf/part.xacro"/>\n'
                     '</robot>\n')
    done = subprocess.run([str(mcar_bin), "build", str(robot), "-o", "-"],
                          capture_output=True, text=True, timeout=120, cwd=tmp_path,
                          env={k: v for k, v in os.environ.items()
                               if k not in ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH")})
    assert done.returncode == 0, done.stderr
    assert '<link name="part"/>' in done.stdout
    spawned = subprocess.run(
        [str(mcar_bin.parent / "python"), "-c",
         "import sys\nfrom mobile_car.expand import sandbox\nsandbox.support()\n"
         "print(sorted(m for m in ('ctypes.util', 'subprocess', 'shutil') "
         "if m in sys.modules))"], capture_output=True, text=True, timeout=60)
    assert spawned.stdout.strip() == "[]", spawned.stderr
