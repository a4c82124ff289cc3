"""The meshes (and the materials and textures they pull in) of an exported robot, copied
into the export's folder so that it loads on a machine that has none of the packages.

Every ``<mesh filename>`` of the URDF, visual and collision, is resolved the way every
command resolves it (``package://`` within its package, ``file://``, relative to the robot
file), measured within the mesh limits before anything reads it
(:func:`~mobile_car.load.mesh_limits.scan_mesh`), and written below ``meshes/``:

* ``package://PKG/a/b.stl`` -> ``meshes/PKG/a/b.stl``, a file path -> ``meshes/b.stl``
  (``b-2.stl`` where two files share a name);
* a format the target reads is copied byte for byte, with the ``.mtl`` and textures it
  names (found beside it, as trimesh finds them) at the same places relative to it; an
  OBJ's and a ``.mtl``'s names are rewritten to name only those copies
  (:mod:`.material_names`);
* any other is read by mcar's mesh reader (:func:`~mobile_car.load.mesh_reader.load_mesh`,
  within the same limits) into one mesh in metres, COLLADA's ``<unit>`` applied, and
  written as binary STL (an OBJ past MuJoCo's 200,000 triangles) named after the source
  (``wheel.dae`` -> ``wheel.dae.stl``: never the name of another file of the package); its
  colour is kept as the mean of its faces' (``colour``). A conversion is never silent:
  each is listed.

Nothing is written outside the folder it is given; each file is created, never replaced.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import InputError, McarError
from ..load.bounded import open_regular
from ..load.compressed import compressed_kind, max_mesh_bytes
from ..load.inputs import display_path
from ..load.mesh_facts import binary_stl_triangles
from ..load.mesh_limits import scan_mesh
from ..names import component_problem
from .material_names import portable_names

MESHES = "meshes"
STL_FACES = 200_000  # MuJoCo's STL reader refuses more ("between 1 and 200000")
_UNIT = re.compile(r"^\s*([0-9.eE+-]+)\s*\*\s*meters?\s*$")


@dataclass
class Asset:
    """One mesh as the export writes it: ``relative`` to the folder (with ``/``)."""

    uri: str             # as the URDF names it
    source: Path
    relative: str
    converted: bool = False
    colour: tuple[float, float, float, float] | None = None  # a converted mesh's
    extra: list[str] = field(default_factory=list)  # .mtl and textures copied beside it


@dataclass
class Assets:
    """The meshes written below ``folder``: uri -> Asset, and what could not be."""

    folder: Path
    readable: tuple[str, ...]  # suffixes the target reads as they are
    binary_stl_only: bool = True  # MuJoCo reads binary STL only, and 200,000 faces at most
    by_uri: dict[str, Asset] = field(default_factory=dict)
    taken: set[str] = field(default_factory=set)

    def add(self, uri: str, search, base: Path, label: str) -> Asset:
        """The asset for ``uri`` (written once per URI); InputError naming the mesh when it
        is missing, over a limit or unreadable."""
        if uri in self.by_uri:
            return self.by_uri[uri]
        source = _resolved(f"mesh {uri}", uri, search, base, label)
        try:
            scan = scan_mesh(source, str(source))
        except InputError as error:
            raise InputError(f"mesh {uri}: {error.message}", file=label) from None
        except OSError as error:
            raise InputError(f"mesh {uri}: cannot be read: {error.strerror or error}",
                             file=label) from None
        place = self._place_for(uri, source)
        if self._reads_as_it_is(source):
            asset = Asset(uri, source, self._claim(place))
            # The scan looked below the mesh's real folder: its names are rewritten
            # against that folder, naming only the copies (material_names).
            folder = source.resolve().parent
            copied = set()
            for extra in scan.reads:
                inside = _below(extra, folder)
                if inside is not None:
                    name = f"{asset.relative.rsplit('/', 1)[0]}/{inside}" \
                        if "/" in asset.relative else inside
                    if name not in self.taken:
                        self.taken.add(name)
                        self._copy(extra, name, folder, copied)
                        asset.extra.append(name)
                    copied.add(Path(extra).resolve())
            self._copy(source, asset.relative, folder, copied)
        else:
            asset = self._convert(uri, source, place, label)
        self.by_uri[uri] = asset
        return asset

    def add_file(self, uri: str, search, base: Path, label: str) -> str:
        """Copy a file the robot names that is no mesh (a ``<texture>``'s image) byte for
        byte, within the mesh size limit; its place in the folder. InputError naming it."""
        if uri in self.by_uri:
            return self.by_uri[uri].relative
        source = _resolved(f"file {uri}", uri, search, base, label)
        asset = Asset(uri, source, self._claim(self._place_for(uri, source)))
        try:
            self._copy(source, asset.relative)
        except OSError as error:
            raise InputError(f"file {uri}: cannot be read: {error.strerror or error}",
                             file=label) from None
        self.by_uri[uri] = asset
        return asset.relative

    def _reads_as_it_is(self, source: Path) -> bool:
        suffix = source.suffix.lower()
        if compressed_kind(source) is not None or suffix not in self.readable:
            return False
        if suffix == ".stl" and self.binary_stl_only:
            return binary_stl_triangles(source) in range(1, STL_FACES + 1)
        return True

    def _place_for(self, uri: str, source: Path) -> str:
        if uri.startswith("package://"):
            package, _, inner = uri[len("package://"):].partition("/")
            parts = [package, *[p for p in inner.split("/") if p not in ("", ".")]]
        else:
            parts = [source.name]
        for part in parts:
            problem = component_problem(part)
            if problem is not None or part == "..":
                parts = [source.name]
                break
        return "/".join([MESHES, *parts])

    def _claim(self, place: str) -> str:
        """``place``, or ``stem-N.suffix`` when another file has it."""
        stem, dot, suffix = place.rpartition(".")
        if not dot:
            stem, suffix = place, ""
        candidate, number = place, 1
        while candidate in self.taken:
            number += 1
            candidate = f"{stem}-{number}{dot}{suffix}"
        self.taken.add(candidate)
        return candidate

    def _copy(self, source: Path, relative: str, folder: Path | None = None,
              copied: set[Path] = frozenset()) -> None:
        """Copy ``source``; an OBJ or .mtl of a mesh in ``folder`` names only ``copied``."""
        with open_regular(source, str(source)) as handle:
            data = handle.read(max_mesh_bytes() + 1)
        if len(data) > max_mesh_bytes():
            raise InputError("grew past the mesh size limit while read", file=str(source))
        if folder is not None:
            data = portable_names(data, Path(source).suffix, folder, copied)
        self._write(relative, data)

    def _write(self, relative: str, data: bytes) -> None:
        target = self.folder / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        with open(target, "xb") as handle:
            handle.write(data)

    def _convert(self, uri: str, source: Path, place: str, label: str) -> Asset:
        from ..load.mesh_reader import load_mesh

        try:
            mesh, _ = load_mesh(source, str(source), force="mesh")
        except (InputError, OSError) as error:
            why = error.message if isinstance(error, InputError) else error.strerror or error
            raise InputError(f"mesh {uri}: cannot be read: {why}", file=label) from None
        except Exception as error:  # trimesh raises anything on a file it cannot parse
            raise InputError(f"mesh {uri}: cannot be read: {' '.join(str(error).split())[:200]}",
                             file=label) from None
        if getattr(mesh, "faces", None) is None or not len(mesh.faces):
            raise InputError(f"mesh {uri}: holds no triangles", file=label)
        in_metres(mesh)
        kind = "stl" if len(mesh.faces) <= STL_FACES else "obj"
        relative = self._claim(f"{place}.{kind}")  # wheel.dae -> wheel.dae.stl: no clash
        data = mesh.export(file_type=kind)
        self._write(relative, data.encode() if isinstance(data, str) else data)
        return Asset(uri, source, relative, converted=True, colour=mean_colour(mesh))


def _resolved(named: str, uri: str, search, base: Path, label: str) -> Path:
    """The file ``uri`` names, found by the package search; InputError starting with
    ``named`` (``mesh URI``, ``file URI``) when it names nothing there."""
    try:
        source = search.resolve_uri(uri, base)
    except McarError as error:
        raise InputError(f"{named}: {error.message}", file=label) from None
    if not source.is_file():
        raise InputError(f"{named}: no such file ({display_path(source)})", file=label)
    return source


def in_metres(mesh) -> None:
    """Scale a mesh whose file gave another unit (trimesh notes COLLADA's ``<unit>`` as
    ``"0.0254 * meters"`` and leaves the vertices as they are) to metres, in place."""
    match = _UNIT.match(str(mesh.metadata.get("units") or ""))
    if match:
        factor = float(match.group(1))
        if factor > 0 and factor != 1.0:
            mesh.apply_scale(factor)
        mesh.metadata["units"] = "meters"


def mean_colour(mesh) -> tuple[float, float, float, float] | None:
    """The area-weighted mean colour of a mesh's faces (0..1), or its material's main
    colour for a textured one; None when it has neither."""
    import numpy as np

    visual = getattr(mesh, "visual", None)
    try:
        if visual is not None and visual.kind == "texture":
            colour = visual.material.main_color
            return tuple(float(c) / 255 for c in colour)
        if visual is not None and visual.kind in ("face", "vertex"):
            colours = np.asarray(visual.face_colors, dtype=float)[:, :4] / 255
            areas = np.asarray(mesh.area_faces, dtype=float)
            if areas.sum() > 0:
                return tuple(float(c) for c in (colours * areas[:, None]).sum(0) / areas.sum())
    except (AttributeError, ValueError, IndexError):
        return None
    return None


def _below(path: Path, folder: Path) -> str | None:
    """``path`` relative to ``folder`` (with ``/``) when it lies below it, else None."""
    try:
        inside = Path(path).resolve().relative_to(Path(folder).resolve())
    except ValueError:
        return None
    return inside.as_posix() if inside.parts else None
