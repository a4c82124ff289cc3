"""The tests' launcher of mcar runs (`run_mcar`, `mcar_process`): each run is a new process
forked from one that has imported mcar and the libraries its commands load (numpy,
trimesh, MuJoCo, ...), instead of a new interpreter importing them again: ~0.1 s of CPU
saved on every run, ~1 s on every render, sim and ci, of the suite's ~1,300 runs.

What the run sees is what `mcar ARGS` sees: its own process, `sys.argv`, working folder,
environment, stdin, stdout and stderr pipes, exit code (or -N for a signal), and mcar's
start-up code (the console script's `main()`, its signal handlers). What it does not
exercise is the interpreter starting and importing: the tests that are about that (the
imports a command makes, Ctrl-C during start-up, the installed script) start real
processes of their own, and so does `run_mcar` whenever the environment it is given
changes how Python starts or a preloaded library is set up (PYTHON*, locale variables,
MUJOCO_GL).
"""

from __future__ import annotations

import json
import locale
import os
import selectors
import signal
import socket
import subprocess
import sys
import time

# Imported once in the launcher: what mcar's commands import on their way.
# (MuJoCo too, imported as mcar imports it: mobile_car.sim.engine sets MUJOCO_GL first.)
# pandas: what `mcar sweep` writes its results with (0.7 s of CPU to import); pyseccomp:
# the xacro sandbox's, whose import runs `ldconfig -p` twice. Not Dask's distributed: it
# adds exit handlers, which would run at the end of every run.
PRELOAD = ("mobile_car.cli.main", "lxml.etree", "xacro", "yaml", "numpy", "PIL.Image",
           "trimesh", "yourdfpy", "mobile_car.render.session", "mobile_car.check.checker",
           "pandas", "pyseccomp")
# Variables read as the interpreter starts (stream encodings, paths, flags), or as a
# preloaded library is imported and that change what a run does: a run given other values
# than the launcher's is started as a real process instead. Not PYTHONHASHSEED, nor the
# thread counts of OMP_* and OPENBLAS_*: they change no result, and a Dask LocalCluster
# sets them in the process that makes it, so a test worker that had made one would have
# started every later run as a new interpreter.
STARTUP_PREFIXES = ("PYTHON", "LC_", "LANG", "MUJOCO_GL")
NO_MATTER = {"PYTHONHASHSEED"}

_SERVER = r"""
import atexit, importlib, json, os, socket, sys, threading, traceback

# As the mcar script's: its own folder first on the module path, not the working folder.
sys.path[0] = os.path.dirname(sys.argv[3])
link = socket.socket(fileno=int(sys.argv[1]))
for name in json.loads(sys.argv[2]):
    try:
        importlib.import_module(name)
    except Exception:
        pass
try:
    from mobile_car.sim.engine import mujoco
    mujoco()
except Exception:
    pass
os.environ.pop("MUJOCO_GL", None)  # (each run has its own environment)
# What was preloaded is frozen: a run's garbage collections then never walk it, and so
# never write to its pages, which the run shares with this process until it writes to
# them (copy-on-write). Unfrozen, a launched `mcar ci` took 15 % more CPU (3.2 s, 2.7 s).
import gc
gc.collect()
gc.freeze()


def child(request, fds):
    link.close()
    for target, fd in enumerate(fds):
        os.dup2(fd, target)
        os.close(fd)
    code = 0
    try:
        os.chdir(request["cwd"])
        os.environ.clear()
        os.environ.update(request["env"])
        sys.argv = request["argv"]
        from mobile_car.cli.main import main
        main()
    except SystemExit as exit:
        code = exit.code
    except BaseException:
        traceback.print_exc()
        code = 1
    # What the interpreter does on its way out: wait for other threads, run atexit.
    try:
        threading._shutdown()
        atexit._run_exitfuncs()
    except BaseException:
        traceback.print_exc()
    if code is None:
        code = 0
    elif not isinstance(code, int):
        print(code, file=sys.stderr)
        code = 1
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except BaseException:
            pass
    os._exit(code & 0xFF)


while True:
    try:
        message, fds, _flags, _address = socket.recv_fds(link, 1 << 20, 3)
    except OSError:
        break
    if not message:
        break
    pid = os.fork()
    if pid == 0:
        child(json.loads(message), fds)
    for fd in fds:
        os.close(fd)
    link.send(json.dumps({"pid": pid}).encode())
    _, status, usage = os.wait4(pid, 0)
    link.send(json.dumps({"code": os.waitstatus_to_exitcode(status),
                          "cpu": usage.ru_utime + usage.ru_stime}).encode())
"""


class Zygote:
    """One launcher process; `run` is `subprocess.run([mcar, *args], capture_output=True,
    text=True, ...)` for one run at a time."""

    def __init__(self, mcar_path, environ: dict):
        self.mcar = str(mcar_path)
        self.started_with = {name: value for name, value in environ.items()
                             if name.startswith(STARTUP_PREFIXES)}
        self.link, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        self.process = subprocess.Popen(
            [sys.executable, "-c", _SERVER, str(theirs.fileno()), json.dumps(PRELOAD), self.mcar],
            cwd="/", env=environ, pass_fds=[theirs.fileno()], stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        theirs.close()

    def usable(self, env: dict) -> bool:
        if self.process.poll() is not None:
            return False
        if env.get("MUJOCO_GL", "egl") != "egl":  # (what mcar sets when none is given)
            return False
        return all(env.get(name) == self.started_with.get(name)
                   for name in {*env, *self.started_with}
                   if name.startswith(STARTUP_PREFIXES) and name != "MUJOCO_GL"
                   and name not in NO_MATTER)

    def close(self) -> None:
        self.link.close()  # the launcher's loop ends
        try:
            self.process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()

    def run(self, args, cwd, input, env, timeout, text=True) -> subprocess.CompletedProcess:
        argv = [self.mcar, *args]
        encoding = locale.getpreferredencoding(False)
        out_r, out_w = os.pipe()
        err_r, err_w = os.pipe()
        if input is None:
            in_r, in_w = os.open(os.devnull, os.O_RDONLY), None
        else:
            in_r, in_w = os.pipe()
        request = {"argv": argv, "cwd": str(cwd or os.getcwd()), "env": env}
        try:
            socket.send_fds(self.link, [json.dumps(request).encode()], [in_r, out_w, err_w])
        finally:
            for fd in (in_r, out_w, err_w):
                os.close(fd)
        pid = json.loads(self.link.recv(1 << 16))["pid"]
        pending = (input.encode(encoding) if text else bytes(input)) if input is not None \
            else b""
        output = {out_r: [], err_r: []}
        deadline = time.monotonic() + timeout
        with selectors.DefaultSelector() as selector:
            for fd in output:
                selector.register(fd, selectors.EVENT_READ)
            if in_w is not None:
                if pending:
                    os.set_blocking(in_w, False)
                    selector.register(in_w, selectors.EVENT_WRITE)
                else:
                    os.close(in_w)
            while selector.get_map():
                left = deadline - time.monotonic()
                if left <= 0:
                    os.kill(pid, signal.SIGKILL)
                    for key in list(selector.get_map().values()):
                        os.close(key.fd)
                    self.link.recv(1 << 16)  # (reaped)
                    raise subprocess.TimeoutExpired(argv, timeout)
                for key, _ in selector.select(left):
                    if key.fd == in_w:
                        try:
                            sent = os.write(in_w, pending[:65536])
                        except BrokenPipeError:
                            sent = len(pending)
                        pending = pending[sent:]
                        if not pending:
                            selector.unregister(in_w)
                            os.close(in_w)
                        continue
                    chunk = os.read(key.fd, 65536)
                    if chunk:
                        output[key.fd].append(chunk)
                    else:
                        selector.unregister(key.fd)
                        os.close(key.fd)
        ended = json.loads(self.link.recv(1 << 16))
        code = ended["code"]
        cpu_seconds[0] += ended["cpu"]
        stdout, stderr = (b"".join(output[fd]) for fd in (out_r, err_r))
        if text:
            stdout, stderr = _text(stdout, encoding), _text(stderr, encoding)
        return subprocess.CompletedProcess(argv, code, stdout, stderr)


def _text(data: bytes, encoding: str) -> str:
    """As subprocess's text mode reads a pipe: decoded, universal newlines."""
    return data.decode(encoding).replace("\r\n", "\n").replace("\r", "\n")


_shared: list = []  # this test process's launcher
# The environment the launcher starts in: the test process's before any test changed it
# (a launcher started inside a test that set PYTHONPATH would have imported from there).
_environ: dict = {}
cpu_seconds = [0.0]  # CPU time of the runs it started (not counted as this process's child)


def run_mcar_process(mcar, args, cwd=None, input=None, env=None, timeout=120, text=True):
    """`subprocess.run([mcar, *args], capture_output=True, ...)` through the launcher when
    it may stand in for a new interpreter (``env``: the whole environment)."""
    env = dict(os.environ) if env is None else env
    if not _shared or _shared[0].process.poll() is not None:
        _shared[:] = [Zygote(mcar, _environ or dict(os.environ))]
    if _shared[0].usable(env):
        return _shared[0].run([str(a) for a in args], cwd=cwd, input=input, env=env,
                              timeout=timeout, text=text)
    return subprocess.run([str(mcar), *map(str, args)], cwd=cwd, input=input,
                          capture_output=True, text=text, env=env, timeout=timeout)


def start_shared(mcar) -> None:
    """Start the launcher now, in this environment (at the session's start)."""
    _environ.update(os.environ)
    _shared[:] = [Zygote(mcar, _environ)]


def close_shared() -> None:
    if _shared:
        _shared.pop().close()
