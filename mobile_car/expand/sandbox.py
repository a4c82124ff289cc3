"""Confine the child process that evaluates xacro: a xacro is code.

xacro evaluates ``${...}`` and ``$(eval ...)`` with Python's ``eval``; its guard against
``__`` names is easy to get round (a comprehension reaches ``os.system``), and ``$(eval)``
has every builtin. So the forked child that expands a file is confined before it reads the
first byte, in three layers:

* **seccomp** (libseccomp through ``pyseccomp``), the kernel's guarantee: no program runs
  (execve, fork, clone), no socket opens, no file opens for writing, nothing in the file
  system is created, renamed, removed or changed, no System V or POSIX IPC object is made
  or attached, and no call names another process: no signal (queued or not) but to
  itself, no tracing, no reading or writing its memory, no change to its priority, CPUs,
  scheduling or limits (nor to the child's own limits), nothing typed into a terminal
  (``TIOCSTI``). Each such call fails with EPERM (EACCES for the limits).
* **Landlock** (through ``landlock``), where the kernel offers it: files are read only below
  the roots the build needs (the packages it may use, the input's folder, Python's own
  library); reading ``/etc/passwd`` or ``~/.ssh`` fails, and so does reading a root's
  version-control folder (``.git/config`` holds a CI job's token).
* **an audit hook**, for the message only: Python reports ``os.system``, ``open(...,
  'w')``, ``socket`` and ``ctypes`` before they reach the kernel, and the hook refuses
  them with a :class:`SandboxViolation` that xacro reports at the expression's line.
  Audit hooks are no security boundary (the kernel layers are): the xacro can switch
  this one off from Python. They make the refusal readable, nothing more.

The child also dies with its parent (``PR_SET_PDEATHSIG``), and has only the result pipe
and ``/dev/null`` as open files. It holds no secret to find in its own memory: the record
key is never read into mcar (:mod:`mobile_car.seal_keeper`). ``trust_inputs()``
(``--no-sandbox``) turns it all off.
"""

from __future__ import annotations

import errno
import os
import signal
import sys
from functools import lru_cache
from pathlib import Path

from ..packages.asset_roots import VCS_FOLDERS
from ..values import Value

_trusted = False
_unconfined_runs: list[str] = []  # why a run went unconfined, for one notice per process


class SandboxViolation(PermissionError):
    """The xacro tried something the sandbox forbids. A PermissionError, so that code
    which copes with a refused write (Python's own bytecode cache) copes with this."""


class Support(Value):
    """What this machine's kernel offers the sandbox."""

    _fields = __slots__ = ("seccomp", "landlock_abi", "landlock_reason")
    seccomp: str | None  # None when available, else why not
    landlock_abi: int  # 0 when Landlock is unavailable
    landlock_reason: str | None

    def __init__(self, seccomp: str | None, landlock_abi: int,
                 landlock_reason: str | None = None):
        self._set(seccomp, landlock_abi, landlock_reason)

    def describe(self) -> list[str]:
        if _trusted:
            return ["sandbox: off (--no-sandbox)"]
        return [
            "sandbox seccomp: " + ("on (no programs, sockets, file writes "
                                   "or calls on other processes)"
                                   if self.seccomp is None else f"unavailable: {self.seccomp}"),
            "sandbox landlock: " + (f"on, ABI {self.landlock_abi} (reads below the package "
                                    "roots and the input's folder only)" if self.landlock_abi
                                    else f"unavailable: {self.landlock_reason}"),
        ]


def trust_inputs() -> None:
    """``--no-sandbox``: expand xacro without confinement (for trees you trust)."""
    global _trusted
    _trusted = True


def is_trusted() -> bool:
    return _trusted


@lru_cache(1)
def support() -> Support:
    """Probe (once) whether seccomp and Landlock can be used here."""
    seccomp_reason = None
    if not sys.platform.startswith("linux"):
        seccomp_reason = "not Linux"
    else:
        try:
            pyseccomp = import_pyseccomp()
            pyseccomp.SyscallFilter(pyseccomp.ALLOW)  # loads libseccomp.so.2
        except (ImportError, OSError, RuntimeError) as error:
            seccomp_reason = f"libseccomp could not be loaded ({error})"
    abi, landlock_reason = 0, None
    try:
        import landlock

        abi = landlock.landlock_abi_version()
    except ImportError as error:
        landlock_reason = f"the landlock package is missing ({error})"
    except (OSError, AttributeError) as error:  # ENOSYS, EOPNOTSUPP: the kernel has none
        landlock_reason = f"the kernel offers no Landlock ({error.__class__.__name__})"
    return Support(seccomp_reason, abi, landlock_reason)


# What ctypes.util.find_library answers for pyseccomp's two libraries on a glibc system.
_SONAMES = {"c": "libc.so.6", "seccomp": "libseccomp.so.2"}


def import_pyseccomp():
    """pyseccomp, which finds libc and libseccomp with ctypes.util.find_library: that
    runs ``ldconfig -p`` (a process) for each and imports shutil, subprocess and tempfile,
    a seventh of a small robot's build. Where the dynamic linker loads both by the names
    ldconfig would give, pyseccomp is handed those names instead; elsewhere (another libc,
    ctypes.util already imported) it imports as it is. Once per process, in the parent,
    before any thread of mcar's imports."""
    if "pyseccomp" in sys.modules or "ctypes.util" in sys.modules:
        import pyseccomp

        return pyseccomp
    import ctypes
    import types

    try:
        for soname in _SONAMES.values():
            ctypes.CDLL(soname)
    except OSError:  # not glibc's names here: ldconfig finds them
        import pyseccomp

        return pyseccomp
    names = types.ModuleType("ctypes.util")
    names.find_library = _SONAMES.get
    sys.modules["ctypes.util"] = ctypes.util = names
    try:
        import pyseccomp
    finally:
        del sys.modules["ctypes.util"], ctypes.util
    return pyseccomp


def note_unconfined(reason: str) -> None:
    _unconfined_runs.append(reason)


def unconfined_notice() -> str | None:
    """One line to tell the user that xacro ran without the kernel's confinement, if it
    did in this process (once)."""
    if not _unconfined_runs:
        return None
    reason = _unconfined_runs[0]
    _unconfined_runs.clear()
    return (f"xacro ran without a sandbox ({reason}): an untrusted .xacro could run programs "
            "and write files; see `mcar --version --verbose`")


def prepare(read_roots: list[Path]) -> list[Path] | None:
    """In the parent, before fork: the folders and files the child may read, or None when
    the run is not to be confined (``--no-sandbox``). Python's library is among them:
    xacro imports its substitution_args and PyYAML at the first ``$(...)`` (the bytecode
    cache it cannot write is skipped, as Python does on a read-only disk)."""
    if _trusted:
        return None
    info = support()
    if info.seccomp is not None:
        note_unconfined(f"seccomp {info.seccomp}")
    # An extension module the child loads may need a system library, which Landlock
    # keeps it from reading: PyYAML (xacro's, at the first $(...)) imports base64, whose
    # binascii needs libz. Loaded here, the child finds it mapped already.
    import binascii  # noqa: F401
    roots = [Path(p) for p in sys.path if p and os.path.isdir(p)]
    roots += [Path(sys.prefix), Path(sys.base_prefix), *read_roots]
    return list(dict.fromkeys(p for p in roots if p.exists()))


def confine(read_roots: list[Path], keep_fd: int, parent: int | None = None) -> None:
    """In the forked child: confine this process for good. Raises nothing it can avoid:
    a layer the kernel refuses is left out (``support()`` already said so). ``parent``:
    the pid of the process that forked it, taken before the fork (see die_with_parent)."""
    die_with_parent(parent)
    _only_fds(keep_fd)
    info = support()
    if info.landlock_abi:
        _restrict_reads(read_roots)
    if info.seccomp is None:
        _deny_syscalls()
    sys.addaudithook(_refuse_audited)


def die_with_parent(parent: int | None = None) -> None:
    """Be killed when the parent dies (PR_SET_PDEATHSIG), and leave at once if it already
    has. ``parent``, where the caller knows it (a fork: the pid before it), is the one to
    outlive: asked in the child, a parent killed before the child's first line reads as
    init (or a subreaper), and a runaway xacro then ran on with nobody to end it."""
    if parent is None:
        parent = os.getppid()
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL, 0, 0, 0)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass
    if os.getppid() != parent:  # the parent died before prctl took effect
        os._exit(1)


def _only_fds(keep_fd: int) -> None:
    """stdin, stdout and stderr on /dev/null (a xacro must not write into mcar's output),
    every other inherited file closed but the result pipe."""
    null = os.open(os.devnull, os.O_RDWR)
    for fd in (0, 1, 2):
        os.dup2(null, fd)
    os.close(null)
    os.closerange(3, keep_fd)
    os.closerange(keep_fd + 1, 65536)


def _restrict_reads(read_roots: list[Path]) -> None:
    import landlock

    ruleset = landlock.Ruleset()
    readable = landlock.FSAccess.READ_FILE | landlock.FSAccess.READ_DIR
    for root in read_roots:
        for path, listed_only in _readable_below(root):
            try:
                ruleset.allow(path, rules=landlock.FSAccess.READ_DIR if listed_only
                              else readable if path.is_dir() else landlock.FSAccess.READ_FILE)
            except OSError:
                continue  # vanished, or not a kind of file Landlock takes: stays unreadable
    ruleset.apply()
    # The ruleset's descriptor is not the child's to keep: it needs no handle but its pipe.
    fd = getattr(ruleset, "_fd", None)
    if isinstance(fd, int):
        try:
            os.close(fd)
        except OSError:
            pass


def _readable_below(root: Path) -> list[tuple[Path, bool]]:
    """What to allow for ``root``: (path, only listed). The root itself, or, when it holds a
    version-control folder (a package at the root of its repository holds .git, and a CI
    checkout keeps the job's token in .git/config), the root listed only and each of its
    entries but that folder (a rule is inherited below its folder, and Landlock has no rule
    that takes away).
    An entry that is a link is left out: its target is readable only where it lies within
    another rule (a rule given through a link would allow where it leads)."""
    if not any(os.path.lexists(os.path.join(root, name)) for name in VCS_FOLDERS):
        return [(root, False)]
    try:
        entries = [entry for entry in os.scandir(root)
                   if entry.name not in VCS_FOLDERS and not entry.is_symlink()]
    except OSError:
        return [(root, False)]
    return [(root, True), *((Path(entry.path), False) for entry in entries)]


# System calls the child never needs and an attacker wants, refused with EPERM.
_DENIED = (
    # programs and processes
    "execve", "execveat", "fork", "vfork", "clone",
    # other processes: tracing them, reading or writing their memory, comparing their
    # handles, moving their pages, their priority or I/O class (setpriority and
    # ioprio_set also name a whole process group, or every process of the user)
    "ptrace", "process_vm_readv", "process_vm_writev", "pidfd_open", "pidfd_getfd",
    "pidfd_send_signal", "process_madvise", "process_mrelease", "kcmp", "get_robust_list",
    "setpriority", "ioprio_set", "migrate_pages", "move_pages",
    # network
    "socket", "socketpair", "connect", "bind", "listen", "accept", "accept4",
    # System V and POSIX IPC, which neither Landlock nor the limits see: a shared memory
    # segment outlives the child (memory past its limit, kept after mcar ends), and
    # attaching one reads another process's (a desktop's X11 images)
    "shmget", "shmat", "shmctl", "msgget", "msgsnd", "msgrcv", "msgctl", "semget", "semop",
    "semtimedop", "semctl", "ipc", "mq_open", "mq_unlink", "mq_timedsend",
    "mq_timedreceive", "mq_notify", "mq_getsetattr",
    # changing the file system
    "creat", "rename", "renameat", "renameat2", "unlink", "unlinkat", "rmdir", "mkdir",
    "mkdirat", "link", "linkat", "symlink", "symlinkat", "chmod", "fchmod", "fchmodat",
    "chown", "fchown", "lchown", "fchownat", "truncate", "ftruncate", "mknod", "mknodat",
    "utime", "utimes", "utimensat", "futimesat", "setxattr", "lsetxattr", "fsetxattr",
    "removexattr", "lremovexattr", "fremovexattr", "fallocate",
    # ways around the filter or into the kernel
    "io_uring_setup", "userfaultfd", "bpf", "perf_event_open", "mount", "umount2",
    "pivot_root", "chroot", "unshare", "setns", "init_module", "finit_module",
    "delete_module", "kexec_load", "reboot", "swapon", "swapoff", "keyctl", "add_key",
    "request_key", "memfd_create", "name_to_handle_at", "open_by_handle_at",
)
# Signals go to the child itself only (its first argument, a process or thread group id,
# is its own pid: one thread), never to its parent, its group (0) or everyone (-1).
_SIGNALS = ("kill", "tkill", "tgkill", "rt_sigqueueinfo", "rt_tgsigqueueinfo")
# Calls that act on the pid of their first argument: 0 (the child itself, as libc names
# it) only.
_SELF_ONLY = ("sched_setaffinity", "sched_setparam", "sched_setscheduler", "sched_setattr",
              "setpgid")
# ioctls that type into a terminal: where Landlock is missing, a xacro opens /dev/tty (the
# user's, when mcar runs in one) and pushes "curl ... | sh" into the shell's input, which
# runs it once mcar ends. TIOCLINUX pastes a console's selection the same way.
_TERMINAL_INPUT = ("TIOCSTI", "TIOCLINUX")
# clone3 and openat2 take their flags in a struct seccomp cannot read: ENOSYS makes libc
# fall back to clone and openat, whose flags it can.
_UNSUPPORTED = ("clone3", "openat2")
_WRITE_FLAGS = (os.O_WRONLY, os.O_RDWR, os.O_CREAT, os.O_TRUNC, os.O_APPEND)


def _deny_syscalls() -> None:
    sc = import_pyseccomp()

    rules = sc.SyscallFilter(sc.ALLOW)
    refuse = sc.ERRNO(errno.EPERM)
    for name in _DENIED:
        _add(rules, refuse, name)
    for name in _UNSUPPORTED:
        _add(rules, sc.ERRNO(errno.ENOSYS), name)
    for name, flags_arg in (("open", 1), ("openat", 2)):
        for flag in _WRITE_FLAGS:
            _add(rules, refuse, name, sc.Arg(flags_arg, sc.MASKED_EQ, flag, flag))
    own = os.getpid()
    for name in _SIGNALS:
        _add(rules, refuse, name, sc.Arg(0, sc.NE, own))
    for name in _SELF_ONLY:
        _add(rules, refuse, name, sc.Arg(0, sc.NE, 0))
    import termios

    for request in (getattr(termios, name) for name in _TERMINAL_INPUT if hasattr(termios, name)):
        _add(rules, refuse, "ioctl", sc.Arg(1, sc.MASKED_EQ, 0xFFFFFFFF, request))
    # Limits: the child's own are set before the filter, and are not the xacro's to
    # change (starving its own files or CPU), nor another process's. getrlimit reads
    # through prlimit64(0, resource, NULL, &old): that stays. EACCES, not EPERM: Python's
    # resource module words EPERM as "not allowed to raise maximum limit", even when
    # lowering it.
    limits = sc.ERRNO(errno.EACCES)
    _add(rules, limits, "setrlimit")
    _add(rules, limits, "prlimit64", sc.Arg(0, sc.NE, 0))
    _add(rules, limits, "prlimit64", sc.Arg(2, sc.NE, 0))  # a new limit given
    rules.load()


def _add(rules, action, name: str, *args) -> None:
    try:
        rules.add_rule(action, name, *args)
    except (ValueError, RuntimeError, OSError):
        pass  # a call this architecture does not have (x86-only names on arm64)


_RUNS_PROGRAMS = ("os.system", "os.exec", "os.posix_spawn", "os.spawn", "os.fork",
                  "os.forkpty", "subprocess.Popen", "pty.spawn", "os.startfile")
_CHANGES_FILES = ("os.remove", "os.rename", "os.rmdir", "os.mkdir", "os.chmod", "os.chown",
                  "os.truncate", "os.link", "os.symlink", "os.utime", "shutil.")
_WRITE_MODE = frozenset("wax+")


def _refuse_audited(event: str, args: tuple) -> None:
    if event == "open":
        path, mode, flags = (tuple(args) + (None, None, None))[:3]
        writes = (isinstance(mode, str) and _WRITE_MODE & set(mode)) or (
            isinstance(flags, int) and flags & (os.O_WRONLY | os.O_RDWR | os.O_CREAT))
        if writes:
            raise SandboxViolation(f"the xacro sandbox forbids writing files ({path})")
    elif event.startswith(_RUNS_PROGRAMS):
        raise SandboxViolation(f"the xacro sandbox forbids running programs ({event})")
    elif event.startswith("socket."):
        raise SandboxViolation(f"the xacro sandbox forbids network access ({event})")
    elif event.startswith("ctypes."):
        raise SandboxViolation(f"the xacro sandbox forbids native code ({event})")
    elif event.startswith(_CHANGES_FILES) or event in ("os.kill", "os.killpg"):
        raise SandboxViolation(f"the xacro sandbox forbids {event}")
