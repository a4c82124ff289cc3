"""Which package a command works on when the user names no file: the one you stand in.

Walking up from the working directory to the nearest ``package.xml`` finds the package
being worked on; a folder (or its ``src/``) holding packages is a workspace, and all of
them are worked on; anywhere else it is the mobile car bundled with mcar (or the
``mobile_car_description`` on the ROS paths). A green run must never be a run over the
wrong robot, so the commands say which one it was.
"""

from __future__ import annotations

from pathlib import Path

from ..packages.search import PackageSearch, enclosing_package, package_name
from ..values import Value


class Package(Value):
    _fields = __slots__ = ("name", "root")
    name: str
    root: Path

    def __init__(self, name: str, root: Path):
        self._set(name, root)


class WorkingSet(Value):
    """The packages a command without INPUT works on."""

    _fields = __slots__ = ("packages", "folder", "output_root", "kind")
    packages: list[Package]
    folder: Path  # the package's root, or the workspace folder
    output_root: Path  # where build/ and renders/ go
    kind: str  # "package" (the one you stand in), "workspace" or "bundled"

    def __init__(self, packages: list[Package], folder: Path, output_root: Path, kind: str):
        self._set(packages, folder, output_root, kind)

    def describe(self) -> str:
        """One line for stderr: which robot this run is about."""
        if self.kind == "workspace":
            names = ", ".join(package.name for package in self.packages)
            return (f"workspace {self.folder}: {len(self.packages)} "
                    f"package{'s' * (len(self.packages) != 1)} ({names})")
        package = self.packages[0]
        own = "" if self.kind == "package" else ", bundled with mcar"
        return f"package {package.name} ({package.root}{own})"


def working_set(cwd: Path, package_paths=()) -> WorkingSet:
    """The package you stand in, else the workspace you stand in, else the bundled car."""
    own = enclosing_package(cwd)
    if own is not None:
        return WorkingSet([Package(*own)], own[1], own[1], "package")
    for folder in (cwd, cwd / "src"):
        packages = _packages_in(folder)
        if packages:
            return WorkingSet(packages, folder, cwd, "workspace")
    from ..packages.bundled import PACKAGE_NAME

    root = PackageSearch(package_paths=list(package_paths), origin=cwd).find(PACKAGE_NAME)
    return WorkingSet([Package(PACKAGE_NAME, root)], root, cwd, "bundled")


def _packages_in(folder: Path) -> list[Package]:
    """The packages directly inside a folder (each a subfolder with a package.xml)."""
    found = []
    try:
        children = sorted(child for child in folder.iterdir() if child.is_dir())
    except OSError:
        return []
    for child in children:
        xml = child / "package.xml"
        name = package_name(xml) if xml.is_file() else None
        if name:
            found.append(Package(name, child))
    return found
