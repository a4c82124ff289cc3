"""Where a sweep's points run: a local process pool (the default) or a Dask cluster.

Both call ``on_row(row)`` in the calling thread as each point finishes, in the order
points finish. A point is evaluated by :func:`mobile_car.sweep.point.evaluate_point`
wherever it runs; a point whose process dies is retried once, alone, and then reported as
a ``crashed`` row. Ctrl-C (KeyboardInterrupt) or SIGTERM (Terminated) unwinds through
here: the workers are stopped, the rows already delivered stay with the caller.
"""

from __future__ import annotations

import os
import signal
from collections import deque
from collections.abc import Callable

from ..errors import McarError, UsageError
from .plan import Point
from .point import SweepJob, empty_row, evaluate_point


class ClusterError(McarError):
    """The Dask scheduler cannot be reached, or its workers cannot run mcar (exit 2)."""


def default_jobs() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not Linux
        return os.cpu_count() or 1


def crashed_row(point: Point, why: str, specs=()) -> dict:
    row = empty_row(point.index, point.values, specs)
    row.update({"status": "crashed", "reason": why, "attempts": 2, "worker": ""})
    return row


def _worker_started(scratch: str) -> None:
    """In each pool worker: Ctrl-C is the main process's to handle (the terminal sends it to
    the whole process group), and a worker must not outlive the sweep (its parent is the
    fork server, which ends with mcar). Its temporary files (a point's overrides file and
    config probe) go to the sweep's own folder, which mcar removes at the end: a worker
    stopped mid-point (Ctrl-C, SIGTERM, a crash) is killed and cleans up nothing."""
    import tempfile

    tempfile.tempdir = scratch
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.signal(signal.SIGHUP, signal.SIG_DFL)
    from ..expand.sandbox import die_with_parent

    die_with_parent()


def _pool(workers: int, scratch: str):
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor
    from multiprocessing import forkserver

    # forkserver: each worker starts from a small clean process, not a fork of this one
    # (its threads and open files). The server imports what a point needs once
    # (sweep/warm.py), and each worker is forked from it with that already imported. It
    # is started with PYTHONSAFEPATH (python -P): `python -c` would otherwise put the
    # working directory first on its sys.path, where a source checkout's mobile_car/ (or a
    # robot package's numpy.py) would be imported in place of the installed one.
    context = multiprocessing.get_context("forkserver")
    context.set_forkserver_preload(["mobile_car.sweep.warm"])
    before = os.environ.get("PYTHONSAFEPATH")
    os.environ["PYTHONSAFEPATH"] = "1"
    try:
        forkserver.ensure_running()
    finally:
        if before is None:
            os.environ.pop("PYTHONSAFEPATH", None)
        else:
            os.environ["PYTHONSAFEPATH"] = before
    return ProcessPoolExecutor(max_workers=workers, mp_context=context,
                               initializer=_worker_started, initargs=(scratch,))


def _stop(pool) -> None:
    """End the pool now: queued points cancelled, running workers killed."""
    processes = list(getattr(pool, "_processes", {}).values())  # no public way on 3.11
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        try:
            process.kill()
        except (OSError, ValueError, AttributeError):
            pass
    for process in processes:
        try:
            process.join(5)
        except (OSError, ValueError, AssertionError, AttributeError):
            pass


def run_local(job: SweepJob, points: list[Point], jobs: int,
              on_row: Callable[[dict], None]) -> None:
    """The points on ``jobs`` worker processes of this machine."""
    import shutil
    import tempfile

    scratch = tempfile.mkdtemp(prefix="mcar-sweep-")  # the workers' temporary files
    try:
        _run_pools(job, points, jobs, on_row, scratch)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


def _run_pools(job: SweepJob, points: list[Point], jobs: int,
               on_row: Callable[[dict], None], scratch: str) -> None:
    from concurrent.futures import FIRST_COMPLETED, wait
    from concurrent.futures.process import BrokenProcessPool

    todo = deque(points)
    while todo:
        pool = _pool(min(jobs, len(todo)), scratch)
        running: dict = {}
        hit: list[Point] = []  # running when a worker died: any of them may be the cause
        broken = False  # a worker died while rows were being written: submit refused
        try:
            while (todo or running) and not hit and not broken:
                while todo and len(running) < jobs:  # never more queued than running:
                    point = todo.popleft()           # a dying worker takes only these
                    try:
                        future = pool.submit(evaluate_point, job, point.index, point.values)
                    except BrokenProcessPool:
                        todo.appendleft(point)  # never started: it runs in the next pool
                        broken = True
                        break
                    running[future] = point
                if broken:
                    break
                done, _ = wait(running, return_when=FIRST_COMPLETED)
                for future in done:
                    point = running.pop(future)
                    try:
                        on_row(future.result())
                    except BrokenProcessPool:
                        hit.append(point)
            if hit or broken:
                wait(running)  # the others fail with the pool, or finished just before
                for future, point in running.items():
                    try:
                        on_row(future.result())
                    except BrokenProcessPool:
                        hit.append(point)
        finally:
            _stop(pool)
        for point in sorted(hit, key=lambda p: p.index):
            on_row(_alone(job, point, scratch))


def _alone(job: SweepJob, point: Point, scratch: str) -> dict:
    """A point that was running when a worker died, run again in a pool of its own: if it
    dies again, it is the one that kills its worker."""
    from concurrent.futures.process import BrokenProcessPool

    pool = _pool(1, scratch)
    try:
        row = pool.submit(evaluate_point, job, point.index, point.values).result()
    except BrokenProcessPool:
        return crashed_row(point, "its worker process died twice (killed, or crashed in "
                                  "native code): the point was retried once, alone", job.specs)
    finally:
        _stop(pool)
    row["attempts"] = 2
    return row


def check_scheduler_address(address: str) -> None:
    """UsageError unless ``address`` is one Dask could connect to (``tcp://HOST:PORT``,
    ``HOST:PORT``, ``tls://``, ``ws://``, ...), read by Dask's own address parser, before
    any Client exists. A Client whose address Dask cannot parse is left half-made (Dask
    closes it after a failed connection, not after a ValueError), and at exit its
    ``__del__`` waited 20 s on a stopped event loop and printed a traceback."""
    if not address.strip():
        raise UsageError("--scheduler is empty: give the Dask scheduler's address, "
                         "tcp://HOST:PORT")
    _require_distributed()
    from distributed.comm.addressing import get_address_host_port

    try:
        _host, port = get_address_host_port(address)
    except ValueError as error:
        raise UsageError(f"--scheduler {address}: not a Dask scheduler address ({error}); "
                         "give tcp://HOST:PORT") from None
    if not 0 < port < 65536:
        raise UsageError(f"--scheduler {address}: port {port} is not 1 to 65535")


def _refused_at_once(address: str) -> None:
    """ClusterError now when nothing listens at a tcp:// address: Dask's Client retries a
    refused connection for its whole 10 s timeout before saying so."""
    from distributed.comm.addressing import get_address_host_port, parse_address

    if parse_address(address, strict=False)[0] != "tcp":
        return
    import socket

    host, port = get_address_host_port(address)
    try:
        socket.create_connection((host, port), timeout=3).close()
    except ConnectionRefusedError:
        raise ClusterError(f"cannot reach the Dask scheduler at {address}: connection "
                           "refused (nothing listens there)") from None
    except OSError:
        return  # unreachable in another way: the Client tries and says how


def _require_distributed() -> None:
    try:
        import distributed  # noqa: F401
    except ImportError:
        raise ClusterError("--scheduler needs Dask distributed: pip install 'mcar[sweep]'") \
            from None


def run_dask(job: SweepJob, points: list[Point], address: str,
             on_row: Callable[[dict], None], wait_workers: float = 30.0) -> None:
    """The points on the workers of the Dask scheduler at ``address`` (tcp://HOST:PORT,
    see check_scheduler_address). Dask reschedules the point of a worker that died on
    another one; after the scheduler's ``allowed-failures`` it gives up on that point
    (KilledWorker): a ``crashed`` row."""
    check_scheduler_address(address)
    _refused_at_once(address)
    from distributed import Client, KilledWorker, as_completed

    try:
        client = Client(address, timeout=10, set_as_default=False)
    except (OSError, TimeoutError, ValueError, TypeError) as error:
        raise ClusterError(f"cannot reach the Dask scheduler at {address}: "
                           f"{str(error).splitlines()[0] if str(error) else type(error).__name__}"
                           ) from None
    running: dict = {}
    try:
        _require_mcar(client, address, wait_workers)
        window = max(64, 4 * sum(client.nthreads().values()))
        todo = deque(points)
        completed = as_completed(loop=client.loop)

        def submit(point: Point) -> None:
            future = client.submit(evaluate_point, job, point.index, point.values,
                                   key=f"mcar-sweep-{job.fingerprint([])}-{point.index}-"
                                       f"{os.getpid()}", pure=False)
            running[future] = point
            completed.add(future)

        while todo and len(running) < window:
            submit(todo.popleft())
        for future in completed:
            point = running.pop(future)
            try:
                row = future.result()
            except KilledWorker:
                row = crashed_row(point, "the Dask workers running it died; the scheduler "
                                         "retried it and gave up (allowed-failures)",
                                  job.specs)
            except McarError:  # the sweep's own error (see evaluate_point)
                raise
            except Exception as error:  # noqa: BLE001 - the cluster, not the point, failed
                raise ClusterError(f"a Dask worker could not run point {point.index}: "
                                   f"{type(error).__name__}: {error}") from None
            on_row(row)
            if todo:
                submit(todo.popleft())
    finally:
        if running:
            client.cancel(list(running))
        client.close(timeout=5)


def _require_mcar(client, address: str, wait_workers: float) -> None:
    """Every worker has the same mcar as this process, or a ClusterError that says which."""
    from .. import __version__

    try:
        client.wait_for_workers(1, timeout=wait_workers)
    except (TimeoutError, OSError):
        raise ClusterError(f"the Dask scheduler at {address} has no workers after "
                           f"{wait_workers:g} s: start them with `dask worker {address}` "
                           "where mcar is installed") from None

    def mcar_version():  # pickled by value: it runs where mcar may be missing
        import importlib.metadata

        try:
            return importlib.metadata.version("mcar")
        except importlib.metadata.PackageNotFoundError:
            return None

    versions = client.run(mcar_version)
    wrong = {worker: version for worker, version in versions.items()
             if version != __version__}
    if wrong:
        worker, version = sorted(wrong.items())[0]
        has = f"mcar {version}" if version else "no mcar"
        raise ClusterError(f"Dask worker {worker} has {has}, this is mcar {__version__}"
                           f"{f' (and {len(wrong) - 1} more workers)' if len(wrong) > 1 else ''}"
                           ": install the same mcar[sweep] on every worker")
