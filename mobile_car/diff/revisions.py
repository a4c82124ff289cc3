"""A git revision of the package as a folder of its own: ``git archive`` unpacked into a
temporary folder, so that each side of ``mcar diff HEAD~1`` is built from its own sources
and nothing in the working tree (index, HEAD, files) is touched.
"""

from __future__ import annotations

import contextlib
import subprocess
import tarfile
import tempfile
from collections.abc import Iterator
from pathlib import Path

from ..errors import InputError, UsageError


def _git(args: list[str], cwd: Path, binary: bool = False):
    try:
        return subprocess.run(["git", *args], cwd=cwd, capture_output=True, text=not binary,
                              check=False)
    except FileNotFoundError:
        raise UsageError("git revisions need git, which is not installed") from None


def repository_top(cwd: Path) -> Path | None:
    """The top of the git work tree holding ``cwd``, or None outside one."""
    result = _git(["rev-parse", "--show-toplevel"], cwd)
    return Path(result.stdout.strip()) if result.returncode == 0 else None


def is_revision(word: str, cwd: Path) -> bool:
    """True when ``word`` names a commit of the repository holding ``cwd``."""
    if word.startswith("-") or repository_top(cwd) is None:
        return False
    result = _git(["rev-parse", "--verify", "--quiet", "--end-of-options",
                   f"{word}^{{commit}}"], cwd)
    return result.returncode == 0


@contextlib.contextmanager
def revision_tree(revision: str, cwd: Path) -> Iterator[Path]:
    """The repository's files at ``revision`` in a temporary folder (removed afterwards)."""
    top = repository_top(cwd)
    if top is None:
        raise UsageError(f"{revision}: not a file, and {cwd} is not in a git repository")
    with tempfile.TemporaryDirectory(prefix="mcar-diff-") as folder:
        archive = Path(folder) / "tree.tar"
        result = _git(["archive", "--format=tar", f"--output={archive}", "--end-of-options",
                       revision], top)
        if result.returncode != 0:
            message = (result.stderr.strip().splitlines() or ["git archive failed"])[-1]
            raise InputError(f"git archive {revision}: {message}")
        tree = Path(folder) / "tree"
        with tarfile.open(archive) as tar:
            tar.extractall(tree, filter="data")  # no links out, no device files
        archive.unlink()
        yield tree
