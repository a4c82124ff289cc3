"""Find ROS packages without ROS, for ``$(find PKG)`` and ``package://PKG/...``.

A package is a directory holding a ``package.xml`` whose ``<name>`` is the package name.
The search order, first match wins:

1. the package that contains the input file (so a checkout being edited beats any copy);
2. directories given with ``--package-path`` (each searched recursively, like ROS 1);
3. ``ROS_PACKAGE_PATH`` (colon separated, searched recursively);
4. ``AMENT_PREFIX_PATH`` (colon separated, ``PREFIX/share/PKG``, as ROS 2 installs them);
5. the description bundled with mcar.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from ..errors import InputError, PackageNotFoundError
from ..load.bounded import read_head
from .asset_roots import OutsideRootsError, chosen_asset_paths, confine, real_path
from .bundled import PACKAGE_NAME, description_dir

_NAME_RE = re.compile(rb"<name>\s*([^<\s]+)\s*</name>")
_URL = re.compile(r"[A-Za-z][A-Za-z0-9+.-]*:")  # a scheme: what curl takes for a URL
# Directories never worth crawling for package.xml files.
_SKIP_DIRS = {".git", ".hg", ".svn", "__pycache__", "node_modules", "build", "install", "log"}
_MAX_CRAWL_DEPTH = 8


def package_name(package_xml: Path) -> str | None:
    """The ``<name>`` of a package.xml, or None if it has none or cannot be read."""
    try:
        head = read_head(package_xml, 65536)
    except (OSError, InputError):
        return None
    match = _NAME_RE.search(head)
    return match.group(1).decode("utf-8", "replace") if match else None


def enclosing_package(path: Path) -> tuple[str, Path] | None:
    """The (name, directory) of the package a file or folder lies in, walking up from it."""
    start = Path(path).resolve()
    for directory in ([start] if start.is_dir() else []) + list(start.parents):
        xml = directory / "package.xml"
        if xml.is_file():
            name = package_name(xml)
            return (name, directory) if name else None
    return None


def _crawl(root: Path, found: dict[str, Path]) -> None:
    """Record every package under root; like rospack, do not descend into a package."""
    stack = [(root, 0)]
    while stack:
        directory, depth = stack.pop()
        xml = directory / "package.xml"
        if xml.is_file():
            name = package_name(xml)
            if name:
                found.setdefault(name, directory)
            continue
        if depth >= _MAX_CRAWL_DEPTH or (directory / "CATKIN_IGNORE").exists():
            continue
        try:
            children = sorted(os.scandir(directory), key=lambda e: e.name, reverse=True)
        except OSError:
            continue
        for entry in children:
            if entry.is_dir(follow_symlinks=False) and entry.name not in _SKIP_DIRS \
                    and not entry.name.startswith("."):
                stack.append((Path(entry.path), depth + 1))


def _symlinked_dirs(folder: Path) -> list[Path]:
    try:
        return [Path(entry.path) for entry in os.scandir(folder) if entry.is_symlink()]
    except OSError:
        return []


def _split_path_list(value: str | None) -> list[Path]:
    """A ``PATH``-like variable's folders, made absolute where they are read: a relative
    one found a package whose relative path xacro then took from the including file's
    folder (``$(find husky)/...`` inside ``husky/urdf/``)."""
    return [Path(os.path.abspath(p)) for p in (value or "").split(os.pathsep) if p]


def _decoded_readings(rest: str, host: bool = False) -> set[str]:
    """The other paths a URI's ``rest`` names to the tools mcar hands the robot to: RViz's
    resource_retriever (curl) and urllib %-decode it (``%2e%2e`` is ``..``), and take
    ``file://HOST/`` as ``file:///``. mcar reads the name as it is; each of these
    must be allowed too, or ``mcar view --rviz`` would open RViz on a file mcar refused."""
    if "%" in rest:
        from urllib.parse import unquote

        readings = {rest, unquote(rest)}
    else:
        readings = {rest}
    if host:  # curl reads file://localhost/x, file://127.0.0.1/x... as /x
        readings |= {"/" + r.partition("/")[2] for r in readings if not r.startswith("/")}
    return readings - {rest}


class PackageSearch:
    """Resolves package names to directories; build one per command and reuse it."""

    # A plain class, not a dataclass: never compared, and a dataclass costs every run
    # that imports it the compiling of its methods (values.py).
    def __init__(self, package_paths: list[Path] | None = None, origin: Path | None = None,
                 environ: dict[str, str] | None = None, asset_paths: list[Path] | None = None):
        self.origin = origin  # the input file, whose own package wins
        self.environ = environ
        # Folders whose files a robot may name besides the packages (--asset-path).
        self.asset_paths = list(chosen_asset_paths()) if asset_paths is None else asset_paths
        for path in package_paths or ():
            if not Path(path).is_dir():
                raise InputError(f"--package-path {path}: not a directory")
        # Absolute once, here: see _split_path_list.
        self.package_paths = [Path(os.path.abspath(p)) for p in package_paths or ()]
        self._allowed: tuple | None = None
        self._package_assets: list[Path] | None = None
        # The mcar.yaml files whose assets.paths were consulted (a record of the run
        # stamps them).
        self.settings_read: list[Path] = []
        self._cache: dict[str, Path] = {}
        self._crawled: dict[str, Path] | None = None
        # package -> its CMakeLists.txt's install rules (installed_source)
        self._install_rules: dict[str, list] = {}

    @property
    def _env(self):
        """The environment the packages are found through (read only: no copy made)."""
        return os.environ if self.environ is None else self.environ

    def where_looked(self) -> list[str]:
        places = []
        if self.origin is not None:
            own = enclosing_package(self.origin)
            places.append(f"the package holding {self.origin} ({own[0] if own else 'none'})")
        places += [f"--package-path {p}" for p in self.package_paths]
        ros = self._env.get("ROS_PACKAGE_PATH")
        places.append(f"ROS_PACKAGE_PATH={ros}" if ros else "ROS_PACKAGE_PATH (unset)")
        ament = self._env.get("AMENT_PREFIX_PATH")
        places.append(f"AMENT_PREFIX_PATH={ament}" if ament else "AMENT_PREFIX_PATH (unset)")
        places.append(f"the bundled {PACKAGE_NAME}")
        return places

    def found_in(self, name: str) -> str:
        """Which of where_looked()'s places gave package ``name`` (call after find())."""
        root = self.find(name)
        if self.origin is not None:
            own = enclosing_package(self.origin)
            if own and own[0] == name:
                return f"the package holding {self.origin}"
        if self._crawled_packages().get(name) == root:
            for place in self.package_paths:
                if root == place or place in root.parents:
                    return f"--package-path {place}"
            return "ROS_PACKAGE_PATH"
        if root == description_dir():
            return f"the bundled {PACKAGE_NAME}"
        return "AMENT_PREFIX_PATH"

    def _crawled_packages(self) -> dict[str, Path]:
        if self._crawled is None:
            found: dict[str, Path] = {}
            for root in self.package_paths + _split_path_list(self._env.get("ROS_PACKAGE_PATH")):
                if root.is_dir():
                    _crawl(root, found)
            self._crawled = found
        return self._crawled

    def read_roots(self) -> list[Path]:
        """Every folder a package may be found in: what a sandboxed xacro may read."""
        own = None if self.origin is None else enclosing_package(self.origin)
        roots = [] if own is None else [own[1]]
        roots += self.package_paths + _split_path_list(self._env.get("ROS_PACKAGE_PATH"))
        for prefix in _split_path_list(self._env.get("AMENT_PREFIX_PATH")):
            roots.append(prefix / "share")
            roots += _symlinked_dirs(prefix / "share")  # an install links to the sources
        roots += list(self._cache.values()) + [description_dir()]
        # Landlock judges a file by its real path: a root given through a link is allowed
        # where it leads.
        return [root for root in dict.fromkeys(r.resolve() for r in roots) if root.exists()]

    def find(self, name: str) -> Path:
        """The directory of package ``name``; PackageNotFoundError names where it looked."""
        result = self.find_if_any(name)
        if result is None:
            raise PackageNotFoundError(
                f"package '{name}' not found; looked in: " + "; ".join(self.where_looked()))
        return result

    def find_if_any(self, name: str) -> Path | None:
        """The directory of package ``name``, None where there is none (a sibling package
        a robot may or may not have: its control or navigation package)."""
        if name in self._cache:
            return self._cache[name]
        result = self._lookup(name)
        if result is not None:
            self._cache[name] = result
        return result

    def _lookup(self, name: str) -> Path | None:
        if self.origin is not None:
            own = enclosing_package(self.origin)
            if own and own[0] == name:
                return own[1]
        crawled = self._crawled_packages().get(name)
        if crawled is not None:
            return crawled
        for prefix in _split_path_list(self._env.get("AMENT_PREFIX_PATH")):
            share = prefix / "share" / name
            if (share / "package.xml").is_file() or (
                    prefix / "share" / "ament_index" / "resource_index" / "packages" / name
            ).is_file():
                return share
        if name == PACKAGE_NAME:
            return description_dir()
        return None

    def installed_source(self, path: str | os.PathLike) -> Path | None:
        """The source file a missing ``path`` below a found package's folder names as
        that package installs it (:mod:`.install_layout`): ``$(find PKG)/urdf/x`` of a
        package that installs ``description/urdf``. None for any other path."""
        from .install_layout import install_rules, source_of

        path = Path(path)
        for name, root in self._cache.items():
            if root in path.parents and not path.exists():
                if name not in self._install_rules:  # CMakeLists.txt read once a run
                    self._install_rules[name] = install_rules(root, name)
                return source_of(root, name, path.relative_to(root).as_posix(),
                                 self._install_rules[name])
        return None

    def resolve_uri(self, uri: str, base: Path | None = None) -> Path:
        """A mesh or file URI (``package://``, ``file://``, an absolute or a relative path)
        as a path, confined to :meth:`allowed_roots` (every symlink followed):
        OutsideRootsError for one outside them, before anything opens it.

        A ``package://`` path may not climb out of its package with ``..`` either.
        """
        if uri.startswith("package://"):
            rest = uri[len("package://"):]
            name, _, inner = rest.partition("/")
            root = self.find(name).resolve()
            path = self.confined(uri, root / inner)
            if root != path and root not in path.parents:
                raise InputError(f"{uri}: path leaves package '{name}' ({root})")
            for other in _decoded_readings(inner):
                self.confined(uri, root / other)
            return path
        if uri.startswith("file://"):
            rest = uri[len("file://"):]
            path = Path(rest)
            for other in _decoded_readings(rest, host=True):
                self.confined(uri, Path(other))
        elif _URL.match(uri):
            # file:/x, FILE:///x, http://, gopher://: mcar reads none, RViz hands each to
            # curl, which reads the file or sends the request (to a local Redis, say)
            raise OutsideRootsError(f"'{uri}' is a URL mcar does not read, which RViz would "
                                    "fetch (through curl)", Path(uri), self.allowed_roots())
        else:
            path = Path(uri)
            if not path.is_absolute() and base is not None:
                path = Path(base) / path
        self.confined(uri, path)
        return path  # as named: messages show the name the robot gave

    def confined(self, uri: str, path: Path) -> Path:
        """The real path of ``path`` (named ``uri``) if it lies in the allowed roots, else
        OutsideRootsError; the package's mcar.yaml is read only for a file outside the
        others (UsageError when its assets.paths leave the repository)."""
        try:
            return confine(uri, path, self.allowed_roots())
        except OutsideRootsError:
            extra = self._package_asset_roots()
            if not extra:
                raise
            return confine(uri, path, self.allowed_roots() + extra)

    def allowed_roots(self) -> list[Path]:
        """The folders the files a robot names may lie in (:mod:`.asset_roots`): the
        package roots, the input's own folder and ``--asset-path``'s, as real paths."""
        known = tuple(self._cache)  # a package found since widens read_roots()
        if self._allowed is None or self._allowed[0] != known:
            folder = Path.cwd() if self.origin is None else Path(self.origin)
            if not folder.is_dir():
                folder = folder.parent
            roots = [*self.read_roots(), real_path(folder),
                     *(real_path(p) for p in self.asset_paths)]
            self._allowed = (known, list(dict.fromkeys(roots)))
        return self._allowed[1]

    def _package_asset_roots(self) -> list[Path]:
        """assets.paths of the mcar.yaml of the input's own package."""
        from .package_config import load_package_config

        if self._package_assets is None:
            own = None if self.origin is None else enclosing_package(self.origin)
            config = None if own is None else load_package_config(own[1])
            if config is not None and config.path is not None:
                self.settings_read.append(config.path)  # what was allowed depends on it
            self._package_assets = [] if config is None else list(config.asset_paths)
        return self._package_assets
