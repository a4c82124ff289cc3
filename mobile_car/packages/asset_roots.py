"""The folders the files a robot names may lie in, and the one test every such file passes
before mcar opens it.

A description names files: meshes, textures, and through them ``.mtl`` libraries, maps and
COLLADA images. mcar reads them, hashes them, draws them and copies them into exports,
which CI jobs upload: a description that names ``file:///etc/shadow`` as a texture must
not get the runner's secrets into an artefact. So every name goes through
:meth:`~.search.PackageSearch.resolve_uri`, which confines it to the allowed roots:

* the folders a package may be found in (:meth:`~.search.PackageSearch.read_roots`: the
  input's own package, ``--package-path``, ``ROS_PACKAGE_PATH``, ``AMENT_PREFIX_PATH``'s
  share folders, the bundled car);
* the input's own folder (the working folder for stdin);
* the folders the user names: ``--asset-path DIR`` (any folder: the user typed it), and
  ``assets: {paths: [...]}`` in the input package's ``mcar.yaml`` (in CI a pull request
  writes that file, so it may only name folders inside the repository holding it).

The test is made on the real path, every symlink followed: a link inside a package that
leads out of it is outside. A version-control folder (``.git``...) is never inside, even in
a package at the root of its repository: CI checkouts keep a token in ``.git/config``
(``actions/checkout`` writes its ``extraheader`` there), and a texture
``package://pkg/.git/config`` copied it into an export.

A file refused is never opened, measured, hashed or copied: :class:`OutsideRootsError` is
raised before anything reads it, and every consumer treats it like a missing file (check
warns W215, pictures draw the magenta box, exports leave it out).

These roots are for the files a description names, not for what a sandboxed xacro may
read: its Landlock roots stay :meth:`~.search.PackageSearch.read_roots` (less their
version-control folders, :mod:`mobile_car.expand.sandbox`).
"""

from __future__ import annotations

import os
from pathlib import Path

from ..errors import EXIT_PROBLEMS, InputError

_chosen: tuple[Path, ...] = ()  # --asset-path of this run
# Version control's own folders: what they hold is the checkout's, not the robot's (a
# CI token in .git/config); lower case, for file systems that ignore case. The xacro
# sandbox keeps its Landlock rules off the same folders.
VCS_FOLDERS = frozenset({".git", ".hg", ".svn", ".bzr"})


class OutsideRootsError(InputError):
    """A file a description names lies outside every folder mcar may read for it."""

    exit_code = EXIT_PROBLEMS

    def __init__(self, message: str, path: Path, roots: list[Path]):
        super().__init__(message)
        self.path = path
        self.roots = roots


def allow_asset_paths(paths) -> None:
    """``--asset-path``: folders whose files a description may name, for this run (like
    ``--no-sandbox``, a choice of the command line, so it is kept for the process)."""
    global _chosen
    _chosen = tuple(Path(os.path.realpath(p)) for p in paths)


def chosen_asset_paths() -> tuple[Path, ...]:
    """The folders ``--asset-path`` named in this run (real paths)."""
    return _chosen


def real_path(path: Path) -> Path:
    """``path`` with every symlink followed (a loop is left as it is: it names nothing)."""
    return Path(os.path.realpath(path))


def in_vcs_folder(path: Path) -> bool:
    """Whether ``path`` names something in a version-control folder (``.git``...)."""
    return any(part.lower() in VCS_FOLDERS for part in Path(path).parts)


def link_out_of(path: Path, folder: Path) -> str | None:
    """Why ``path``, every link followed, is not a file of ``folder`` (a real path): it
    leads out of it, or into its version-control folder; None where it stays inside. A
    pull request commits links (``urdf/robot.urdf`` -> ``/proc/self/environ``, ``mcar.yaml``
    -> ``../.git/config``): discovery and mcar.yaml both ask this before reading."""
    real = real_path(path)
    if not within(real, [folder]):
        return f"a link to {real}, outside {folder}"
    if in_vcs_folder(real.relative_to(folder)):
        return f"a link to {real}, in a version-control folder"
    return None


def within(path: Path, roots) -> bool:
    """Whether the real ``path`` lies in one of ``roots`` (real paths themselves)."""
    text = str(path)
    # by text, not Path.is_relative_to: asked for every file a robot names
    return any(text == str(root) or text.startswith(str(root).rstrip("/") + "/")
               for root in roots)


def confine(uri: str, path: Path, roots: list[Path]) -> Path:
    """The real path of ``path`` when it lies in one of ``roots``; OutsideRootsError
    otherwise, naming the file and the roots."""
    real = real_path(path)
    if in_vcs_folder(real):
        raise OutsideRootsError(
            f"'{uri}' lies in a version-control folder ({real}), which holds the "
            "checkout's files, not the robot's", real, roots)
    cache = _cache_folder()
    if within(real, [cache]):
        raise OutsideRootsError(
            f"'{uri}' lies in mcar's own cache folder ({cache}), which holds the key that "
            "seals its records, not the robot's files", real, roots)
    if within(real, roots):
        return real
    # A folder inside another one adds nothing to read in a message.
    outer = [root for root in roots if not any(root != other and root.is_relative_to(other)
                                               for other in roots)]
    shown = ", ".join(str(root) for root in outer) or "none"
    leads = "" if real == Path(os.path.abspath(path)) else f" (it leads to {real})"
    raise OutsideRootsError(
        f"'{uri}' is outside the folders a robot may name files in{leads}: {shown}; "
        "--asset-path DIR (or assets.paths in the package's mcar.yaml) allows one",
        real, roots)


_cache_real: dict[Path, Path] = {}


def _cache_folder() -> Path:
    """The real path of mcar's cache folder (``MCAR_CACHE_DIR``, ``XDG_CACHE_HOME``): a CI
    job that restores a cache into its workspace puts the record key inside the package,
    and a texture naming it copied the key into an export. Resolved once per folder (every
    file a robot names passes here)."""
    from ..record_seal import cache_dir

    named = cache_dir()
    if named not in _cache_real:
        _cache_real[named] = real_path(named)
    return _cache_real[named]


# Where CI services put the checkout a job works in (GitHub Actions, GitLab, Bitbucket,
# Azure Pipelines): mcar.yaml is the pull request's, so what it may name stops there.
_CI_WORKSPACES = ("GITHUB_WORKSPACE", "CI_PROJECT_DIR", "BITBUCKET_CLONE_DIR",
                  "BUILD_SOURCESDIRECTORY")


def repository_of(package_root: Path) -> Path:
    """The repository holding a package (the nearest folder with ``.git`` at or above it),
    or the package itself outside any: what a package's mcar.yaml may name. Never above
    the CI job's workspace that holds the package: a checkout without a ``.git`` of its own
    (a downloaded archive) inside a folder kept in git would otherwise take that folder."""
    root = real_path(package_root)
    ceiling = _workspace_holding(root)
    for folder in [root, *root.parents]:
        if (folder / ".git").exists() or folder == ceiling:
            return folder
    return root


def _workspace_holding(root: Path) -> Path | None:
    for name in _CI_WORKSPACES:
        named = os.environ.get(name, "").strip()
        if named and os.path.isabs(named):
            workspace = real_path(Path(named))
            if within(root, [workspace]):
                return workspace
    return None
