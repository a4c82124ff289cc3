"""Fixtures for the robot-description tests: the robot files found in urdf/, built once
with the installed ``mcar build``, loaded with yourdfpy, and posed by forward kinematics.

Robot files are discovered, never listed: every ``urdf/**/test_*.urdf.xacro`` (one part
alone), every ``urdf/**/steps/*.xacro`` (the chassis step by step) and
``urdf/mobile_robot.xacro`` (the complete car). A test that takes ``robot_file`` runs once
per file.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
URDF = REPO / "urdf"
COMPLETE_ROBOT = "mobile_robot.xacro"
# Links that are pure frames (REP 105): no visual, collision or inertial, by design.
FRAME_ONLY_LINKS = {"base_footprint", "base_link"}


def description_files() -> list[Path]:
    """The robot files of the description, relative to urdf/: parts, steps, complete robot."""
    parts = sorted(URDF.glob("**/test_*.urdf.xacro"))
    steps = sorted(URDF.glob("**/steps/*.xacro"))
    return [p.relative_to(URDF) for p in parts + steps + [URDF / COMPLETE_ROBOT]]


def built_name(relative: Path) -> Path:
    """Where `mcar build` puts a robot file's URDF: the .xacro suffix becomes .urdf."""
    name = relative.name.removesuffix(".xacro")
    return relative.with_name(name if name.endswith(".urdf") else name + ".urdf")


def pytest_generate_tests(metafunc):
    if "robot_file" in metafunc.fixturenames:
        files = description_files()
        metafunc.parametrize("robot_file", files, ids=[f.as_posix() for f in files])


@pytest.fixture(scope="session")
def built_dir(mcar_bin, tmp_path_factory) -> Path:
    """Every robot file of the checkout, built by one `mcar build REPO -o DIR` run."""
    out = tmp_path_factory.mktemp("built")
    from conftest import mcar_process  # (tests/conftest.py)

    done = mcar_process("build", REPO, "-o", out, "--quiet", timeout=120)
    assert done.returncode == 0, f"mcar build failed:\n{done.stderr}"
    assert done.stderr == "", f"mcar build warned:\n{done.stderr}"
    return out


@pytest.fixture(scope="session")
def load_urdf():
    """Load a built URDF with yourdfpy, package:// resolved by mcar's PackageSearch."""
    import yourdfpy

    from mobile_car.packages.search import PackageSearch

    search = PackageSearch(package_paths=[REPO])
    loaded: dict[Path, yourdfpy.URDF] = {}

    def load(path: Path) -> yourdfpy.URDF:
        if path not in loaded:
            loaded[path] = yourdfpy.URDF.load(
                str(path), load_meshes=True,
                filename_handler=lambda fname: str(search.resolve_uri(fname, base=path.parent)))
        return loaded[path]

    return load


@pytest.fixture(scope="session")
def complete_robot(built_dir, load_urdf):
    return load_urdf(built_dir / built_name(Path(COMPLETE_ROBOT)))


# ----------------------------------------------------------------------------------------
# Geometry posed by forward kinematics: each collision (or visual) element of a link as a
# world transform plus its primitive, and its extent along any direction (support function).


@dataclass
class Posed:
    """One geometry element placed in the world frame at the robot's zero configuration."""

    link: str
    transform: np.ndarray  # 4x4, element frame -> world
    geometry: object  # yourdfpy.Geometry
    mesh_vertices: np.ndarray | None = None  # world coordinates, for mesh geometry

    def support(self, direction) -> float:
        """max over the element's points p of p . direction (exact for primitives)."""
        d = np.asarray(direction, dtype=float)
        rotation, centre = self.transform[:3, :3], self.transform[:3, 3]
        g = self.geometry
        if g.box is not None:
            return float(centre @ d + np.abs(rotation.T @ d) @ (np.asarray(g.box.size) / 2))
        if g.cylinder is not None:
            along = float(rotation[:, 2] @ d)
            return float(centre @ d + abs(along) * g.cylinder.length / 2
                         + g.cylinder.radius * np.sqrt(max(0.0, d @ d - along * along)))
        if g.sphere is not None:
            return float(centre @ d + g.sphere.radius * np.linalg.norm(d))
        if self.mesh_vertices is not None:
            return float(np.max(self.mesh_vertices @ d))
        raise AssertionError(f"{self.link}: geometry of unknown kind {g}")

    def lowest(self) -> float:
        return -self.support([0, 0, -1])

    def highest(self) -> float:
        return self.support([0, 0, 1])

    def bounds(self) -> np.ndarray:
        """Axis-aligned bounds, [[xmin, ymin, zmin], [xmax, ymax, zmax]]."""
        axes = np.eye(3)
        return np.array([[-self.support(-a) for a in axes], [self.support(a) for a in axes]])


def _element_transform(origin) -> np.ndarray:
    return np.eye(4) if origin is None else np.asarray(origin, dtype=float)


@pytest.fixture(scope="session")
def posed():
    """posed(urdf, "collision"|"visual") -> list of Posed elements, root frame = world."""
    import trimesh

    from mobile_car.packages.search import PackageSearch

    search = PackageSearch(package_paths=[REPO])

    def pose(urdf, kind: str = "collision") -> list[Posed]:
        elements = []
        for link in urdf.robot.links:
            link_to_world = urdf.get_transform(frame_to=link.name, frame_from=urdf.base_link)
            for element in getattr(link, f"{kind}s"):
                transform = link_to_world @ _element_transform(element.origin)
                vertices = None
                if element.geometry.mesh is not None:
                    mesh = trimesh.load(str(search.resolve_uri(element.geometry.mesh.filename)),
                                        force="mesh")
                    scale = element.geometry.mesh.scale
                    if scale is not None:
                        mesh.apply_scale(scale)
                    vertices = trimesh.transform_points(mesh.vertices, transform)
                elements.append(Posed(link.name, transform, element.geometry, vertices))
        return elements

    return pose
