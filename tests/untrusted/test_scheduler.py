"""`mcar sweep --scheduler`: a value Dask cannot connect to is one line and exit 2, with
nothing after it.

A malformed address (``local``, ``tcp://``) reached ``distributed.Client``, which raised
the right error but stayed half-made (Dask closes a Client after a failed connection, not
after a ValueError from its address parser); at exit its ``__del__`` waited 20 s on a
stopped event loop and printed a traceback. ``--scheduler ''`` was silently ignored. The
only network address used here is a closed port on the loopback interface.
"""

from __future__ import annotations

import contextlib
import socket
import threading
import time

import pytest
from conftest import REPO

pytest.importorskip("distributed", reason="the sweep extra (pip install 'mcar[sweep]')")

ROBOT = REPO / "urdf" / "mobile_robot.xacro"
VARY = ["--vary", "wheel_radius=25mm..45mm:2"]
HINT = "give tcp://HOST:PORT"


def _sweep(run_mcar, tmp_path, scheduler: str, timeout: float):
    start = time.monotonic()
    result = run_mcar("sweep", ROBOT, *VARY, "--scheduler", scheduler, "-o", "r.csv",
                      cwd=tmp_path, timeout=timeout)
    return result, time.monotonic() - start


@pytest.mark.parametrize("scheduler, message", [
    ("", "mcar: error: --scheduler is empty: give the Dask scheduler's address, "
         "tcp://HOST:PORT"),
    ("local", "mcar: error: --scheduler local: not a Dask scheduler address (missing port "
              f"number in address 'local'); {HINT}"),
    ("tcp://", "mcar: error: --scheduler tcp://: not a Dask scheduler address (missing "
               f"port number in address ''); {HINT}"),
    ("tcp://127.0.0.1:http", "mcar: error: --scheduler tcp://127.0.0.1:http: not a Dask "
                             "scheduler address (invalid literal for int() with base 10: "
                             f"'http'); {HINT}"),
    ("tcp://127.0.0.1:99999", "mcar: error: --scheduler tcp://127.0.0.1:99999: port 99999 "
                              "is not 1 to 65535"),
])
def test_a_malformed_scheduler_is_one_line_and_nothing_after(run_mcar, tmp_path, scheduler,
                                                              message):
    # The process has exited (so nothing can print later) well before the 20 s the
    # half-made Client's __del__ used to wait.
    result, seconds = _sweep(run_mcar, tmp_path, scheduler, timeout=15)
    assert result.returncode == 2, result.stderr
    assert result.stderr.splitlines() == [message]
    assert seconds < 15
    assert not (tmp_path / "r.csv").exists()


def test_an_unknown_scheme_names_the_ones_dask_knows(run_mcar, tmp_path):
    result, _ = _sweep(run_mcar, tmp_path, "local://127.0.0.1:1", timeout=15)
    assert result.returncode == 2, result.stderr
    [line] = result.stderr.splitlines()
    assert line.startswith("mcar: error: --scheduler local://127.0.0.1:1: not a Dask "
                           "scheduler address (unknown address scheme 'local' (known "
                           "schemes: [")
    assert "'tcp'" in line and line.endswith(HINT)


def test_a_malformed_scheduler_never_makes_a_dask_client(cli, monkeypatch):
    """The cause itself, in-process: no Client is constructed for an address Dask's own
    parser refuses, so none is left half-made."""
    import distributed

    made = []

    class Recording:
        def __init__(self, *args, **kwargs):
            made.append(args)
            raise OSError("a test Client: never connects")

    monkeypatch.setattr(distributed, "Client", Recording)
    for scheduler in ("local", "tcp://", ""):
        result = cli("sweep", ROBOT, *VARY, "--scheduler", scheduler, "-o", "-")
        assert result.exit_code == 2, result.output
        assert made == []
    # The recorder is in place: a well-formed address where something listens reaches it.
    with _hanging_up() as address:
        result = cli("sweep", ROBOT, *VARY, "--scheduler", address, "-o", "-")
    assert result.exit_code == 2 and made == [(address,)]


@contextlib.contextmanager
def _hanging_up():
    """tcp://127.0.0.1:PORT where a thread accepts each connection and closes it."""
    listener = socket.socket()
    listener.bind(("127.0.0.1", 0))
    listener.listen()
    listener.settimeout(0.2)
    stop = threading.Event()

    def serve():
        while not stop.is_set():
            try:
                connection, _ = listener.accept()
            except OSError:
                continue
            connection.close()

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    try:
        yield f"tcp://127.0.0.1:{listener.getsockname()[1]}"
    finally:
        stop.set()
        thread.join()
        listener.close()


def _closed_loopback_port() -> int:
    with socket.socket() as probe:
        probe.settimeout(2)
        if probe.connect_ex(("127.0.0.1", 1)) == 0:
            pytest.skip("something listens on 127.0.0.1:1")
    return 1


def test_a_refused_scheduler_is_one_line_at_once(run_mcar, tmp_path):
    port = _closed_loopback_port()
    address = f"tcp://127.0.0.1:{port}"
    result, seconds = _sweep(run_mcar, tmp_path, address, timeout=40)
    assert result.returncode == 2, result.stderr
    assert result.stderr.splitlines() == [
        f"mcar: error: cannot reach the Dask scheduler at {address}: connection refused "
        "(nothing listens there)"]
    assert seconds < 5  # not Dask's 10 s of retries


def test_a_scheduler_that_hangs_up_is_one_line_and_nothing_after(run_mcar, tmp_path):
    """Something listens but hangs up on every connection: Dask's Client fails (its
    error, whatever Dask words it), Dask closes the Client itself, and mcar exits with
    the one line (the Client's traceback used to come 20 s after it)."""
    with _hanging_up() as address:
        result, seconds = _sweep(run_mcar, tmp_path, address, timeout=40)
    assert result.returncode == 2, result.stderr
    [line] = result.stderr.splitlines()
    assert line.startswith(f"mcar: error: cannot reach the Dask scheduler at {address}: ")
    assert seconds < 25
