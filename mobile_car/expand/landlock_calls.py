"""Landlock's three system calls, called through ctypes: what the sandbox's read
confinement needs of the kernel, and nothing else.

The ``landlock`` package did the same through a dataclass, an ``IntFlag`` and a layer of
error explanations: importing it was ~3 ms of every build, a tenth of mcar's own start-up
over click and xacro. The ABI, the rights a ruleset handles and the order of the calls
are the package's (and the kernel documentation's, Documentation/userspace-api/
landlock.rst): every file system right the ABI knows is handled, so that whatever no rule
allows is refused.
"""

from __future__ import annotations

import ctypes
import os

_CREATE_RULESET, _ADD_RULE, _RESTRICT_SELF = 444, 445, 446  # the same on every arch
_CREATE_RULESET_VERSION = 1 << 0
_RULE_PATH_BENEATH = 1
_PR_SET_NO_NEW_PRIVS = 38

EXECUTE, WRITE_FILE, READ_FILE, READ_DIR = 1 << 0, 1 << 1, 1 << 2, 1 << 3
_MAKE_AND_REMOVE = sum(1 << bit for bit in range(4, 13))  # REMOVE_DIR ... MAKE_SYM
_REFER, _TRUNCATE, _IOCTL_DEV = 1 << 13, 1 << 14, 1 << 15  # ABI 2, 3, 5


class _RulesetAttr(ctypes.Structure):
    _fields_ = [("handled_access_fs", ctypes.c_uint64)]


class _PathBeneathAttr(ctypes.Structure):
    _pack_ = 1  # the kernel's struct is packed: the fd follows the 64-bit rights at once
    _fields_ = [("allowed_access", ctypes.c_uint64), ("parent_fd", ctypes.c_int32)]


_libc = None


def _lib() -> ctypes.CDLL:
    global _libc
    if _libc is None:
        _libc = ctypes.CDLL(None, use_errno=True)
        _libc.syscall.restype = ctypes.c_long
    return _libc


def _call(number: int, *args) -> int:
    """syscall(number, *args): its result, or OSError with the kernel's errno. Every
    integer goes as a C long: syscall() is variadic, and a plain int leaves the upper half
    of a 64-bit register undefined."""
    ctypes.set_errno(0)
    result = _lib().syscall(ctypes.c_long(number),
                            *(ctypes.c_long(a) if isinstance(a, int) else a for a in args))
    if result < 0:
        code = ctypes.get_errno()
        raise OSError(code, os.strerror(code))
    return result


def abi_version() -> int:
    """The Landlock ABI this kernel offers; OSError (ENOSYS, EOPNOTSUPP) when none."""
    return _call(_CREATE_RULESET, None, 0, _CREATE_RULESET_VERSION)


def handled_rights(abi: int) -> int:
    """Every file system right ABI ``abi`` knows (the landlock package's FSAccess.all())."""
    rights = EXECUTE | WRITE_FILE | READ_FILE | READ_DIR | _MAKE_AND_REMOVE
    if abi >= 2:
        rights |= _REFER
    if abi >= 3:
        rights |= _TRUNCATE
    if abi >= 5:
        rights |= _IOCTL_DEV
    return rights


def create_ruleset(abi: int) -> int:
    """A ruleset's descriptor, handling every right of ``abi``: refused unless allowed."""
    attr = _RulesetAttr(handled_rights(abi))
    return _call(_CREATE_RULESET, ctypes.byref(attr), ctypes.sizeof(attr), 0)


def allow_beneath(ruleset: int, path: str | os.PathLike, rights: int) -> None:
    """Allow ``rights`` on ``path`` and everything below it; OSError when it cannot be
    opened or the kernel refuses the rule."""
    fd = os.open(path, os.O_PATH | os.O_CLOEXEC)
    try:
        attr = _PathBeneathAttr(rights, fd)
        _call(_ADD_RULE, ruleset, _RULE_PATH_BENEATH, ctypes.byref(attr), 0)
    finally:
        os.close(fd)


def restrict_self(ruleset: int) -> None:
    """Confine this thread (the child has no other) to the ruleset, for good: no new
    privileges first, as the kernel requires of an unprivileged process."""
    ctypes.set_errno(0)
    if _lib().prctl(_PR_SET_NO_NEW_PRIVS, ctypes.c_ulong(1), ctypes.c_ulong(0),
                    ctypes.c_ulong(0), ctypes.c_ulong(0)) != 0:
        code = ctypes.get_errno()
        raise OSError(code, os.strerror(code))
    _call(_RESTRICT_SELF, ruleset, 0)
