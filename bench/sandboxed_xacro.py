"""The floor of any sandboxed xacro runner, for `bench/run.py floor`: xacro's own main() in a
forked child confined by mcar's sandbox (seccomp and Landlock, mobile_car.expand.sandbox),
its output sent back through a pipe and written by the parent: no click, no checks, no
source map, no result frame. What mcar build costs over this is mcar's own work; what this
costs over the plain xacro command is the sandbox's (its imports, the fork, the
confinement and the pipe).

    python bench/sandboxed_xacro.py FILE.xacro [xacro's arguments]

Packages are found as the plain xacro command finds them in the same environment (the
bench's ament prefix); the child may read below Python's own folders (as mcar's child), the
folders of AMENT_PREFIX_PATH, ROS_PACKAGE_PATH and $MCAR_BENCH_READ_ROOTS, and the input's
folder.
"""

import os
import sys
from pathlib import Path

import xacro

from mobile_car.expand import sandbox


def read_roots(path: str) -> list[Path]:
    roots = [Path(path).resolve().parent]
    for name in ("AMENT_PREFIX_PATH", "ROS_PACKAGE_PATH", "MCAR_BENCH_READ_ROOTS"):
        roots += [Path(p).resolve() for p in os.environ.get(name, "").split(os.pathsep) if p]
    return roots


def main() -> int:
    roots = sandbox.prepare(read_roots(sys.argv[1]))
    read_fd, write_fd = os.pipe()
    parent = os.getpid()
    pid = os.fork()
    if pid == 0:
        os.close(read_fd)
        sandbox.confine(roots, write_fd, parent)
        os.dup2(write_fd, 1)  # xacro's main() prints the document: into the pipe
        sys.argv = ["xacro", *sys.argv[1:]]
        try:
            code = xacro.main() or 0
        except SystemExit as end:
            code = end.code if isinstance(end.code, int) else 1
        sys.stdout.flush()
        os._exit(code)
    os.close(write_fd)
    with os.fdopen(read_fd, "rb") as result:
        document = result.read()
    _pid, status = os.waitpid(pid, 0)
    sys.stdout.buffer.write(document)
    return os.waitstatus_to_exitcode(status)


if __name__ == "__main__":
    sys.exit(main())
