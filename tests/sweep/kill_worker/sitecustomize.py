"""Put on PYTHONPATH by tests/sweep: every Python process of the run loads it (mcar and its
sweep workers). With SWEEP_TEST_KILL_POINT=N, the worker process that starts point N is
killed with SIGKILL, as the kernel's out-of-memory killer kills; with
SWEEP_TEST_KILL_ONCE=FILE only the first time (the file marks that it happened)."""

import os

_target = os.environ.get("SWEEP_TEST_KILL_POINT")
if _target:
    import functools
    import signal

    import mobile_car.sweep.point as _point

    _original = _point.evaluate_point

    @functools.wraps(_original)
    def evaluate_point(job, index, values):
        if index == int(_target):
            marker = os.environ.get("SWEEP_TEST_KILL_ONCE")
            try:
                if marker:
                    os.close(os.open(marker, os.O_CREAT | os.O_EXCL | os.O_WRONLY))
                os.kill(os.getpid(), signal.SIGKILL)
            except FileExistsError:
                pass
        return _original(job, index, values)

    _point.evaluate_point = evaluate_point
