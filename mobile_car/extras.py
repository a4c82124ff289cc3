"""The optional extras (``pip install "mcar[view]"``, ``"mcar[sweep]"``): which modules each
command needs from them, checked before the command starts, so that a missing one is a
one-line install hint (exit 2) instead of an ImportError in the middle of a run.

Looked up with :func:`importlib.util.find_spec`, which imports nothing: the check costs a
few stat calls, not pandas' import time.
"""

from __future__ import annotations

import importlib.util
import sys

from .errors import UsageError

# extra -> the top-level modules it brings that mcar imports (pyproject.toml lists them)
EXTRAS = {"view": ("viser", "websockets"),
          "sweep": ("pandas", "pyarrow", "distributed", "matplotlib"),
          "usd": ("pxr", "urdf_usd_converter")}


def missing(modules) -> list[str]:
    """The modules of ``modules`` that cannot be imported."""
    return [name for name in modules if not _importable(name)]


def _importable(name: str) -> bool:
    if name in sys.modules:  # None there means "import fails" (how tests hide a module)
        return sys.modules[name] is not None
    try:
        return importlib.util.find_spec(name) is not None
    except (ImportError, ValueError):
        return False


def require(command: str, extra: str, modules=None) -> None:
    """UsageError naming the missing modules and the extra to install, if any of
    ``modules`` (default: all of the extra's) is not installed."""
    absent = missing(EXTRAS[extra] if modules is None else modules)
    if absent:
        names = ", ".join(absent)
        verb = "is" if len(absent) == 1 else "are"
        raise UsageError(f'{command} needs {names}, which {verb} not installed: '
                         f'pip install "mcar[{extra}]"')
