"""Render many robot files in one process: plan the outputs, skip unchanged ones, draw the rest.

A :class:`RenderSession` uses one renderer (one GL context for every picture), opened only
when the first picture actually needs drawing, so a run where nothing changed never
touches OpenGL. Jobs are run one by one and yield a :class:`JobResult` each, which lets the
command line show progress; a failing file is reported and the run goes on. The manifest
is saved even when the run is interrupted, so pictures already written are not redrawn.
"""

from __future__ import annotations

import io
import time
from collections import deque
from collections.abc import Iterable, Iterator
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

from PIL import Image

from ..atomic import atomic_write
from ..build import build_file, check_input_size, display_path
from ..discover import output_name, robot_files, source_base
from ..errors import InputError, McarError, RendererUnavailableError, UsageError
from ..packages import PackageSearch
from .backend import GLProbe, open_renderer
from .compose import png_bytes
from .manifest import DRAWING_VERSION, Manifest, input_fingerprint, sha256
from .options import RenderOptions
from .picture import DrawnView, draw_views, finish_picture
from .scene import ModelSource, load_scene, mesh_files, parse_urdf
from .sheet import THUMBNAIL_WIDTH, contact_sheet

CONTACT_SHEET = "index.png"
# Pictures finished (overlays, PNG, write) in parallel with drawing the next ones.
FINISH_THREADS = 1
URDF_SUFFIXES = (".urdf.xacro", ".xacro", ".urdf")


@dataclass
class RenderJob:
    """One input file and the PNG it becomes (None: return the bytes, write nothing)."""

    source: Path
    target: Path | None
    caption: str


@dataclass
class JobResult:
    """What happened to one job: ``status`` is rendered, unchanged or failed."""

    job: RenderJob
    status: str
    error: McarError | None = None
    warnings: list[str] = field(default_factory=list)
    png: bytes | None = None
    seconds: float = 0.0


@dataclass
class _Drawn:
    """A job between the two stages: drawn, not yet composed and written."""

    job: RenderJob
    views: list[DrawnView]
    bounds: object
    fingerprint: str
    renderer: str
    warnings: list[str]
    started: float


def _ready(item) -> bool:
    return not isinstance(item, Future) or item.done()


def _result(item) -> JobResult:
    return item.result() if isinstance(item, Future) else item


def _sheet_copy(image: Image.Image) -> Image.Image:
    """A picture reduced for the contact sheet, the same whether it was just drawn or read
    back from disk (so the sheet's bytes do not depend on which pictures were redrawn)."""
    copy = image.copy()
    copy.thumbnail((2 * THUMBNAIL_WIDTH, 2 * THUMBNAIL_WIDTH))
    return copy


def picture_name(path: Path) -> str:
    """``test_wheel.urdf.xacro`` -> ``test_wheel.png``."""
    name = path.name
    for suffix in URDF_SUFFIXES:
        if name.endswith(suffix) and len(name) > len(suffix):
            name = name[: -len(suffix)]
            break
    return name + ".png"


def package_parts(root: Path) -> list[str]:
    """The part folders of a description package (``urdf/wheel``, ...) holding robot files."""
    base = source_base(root)
    return sorted({source.relative_to(base).parts[0] for source in robot_files(root)
                   if len(source.relative_to(base).parts) > 1})


def package_jobs(root: Path, outdir: Path, parts: Iterable[str] = ()) -> list[RenderJob]:
    """A job per robot file of the package (or of the named part folders), mirrored."""
    base = source_base(root)
    sources = robot_files(root)
    parts = list(parts)
    if parts:
        known = package_parts(root)
        unknown = [part for part in parts if part not in known]
        if unknown:
            raise UsageError(f"no file or part named {', '.join(map(repr, unknown))}; parts of "
                             f"{display_path(base)}: {', '.join(known) or 'none'}")
        sources = [s for s in sources if s.relative_to(base).parts[0] in parts]
    if not sources:
        raise UsageError("no robot files (.xacro with <robot name=...>) in this folder",
                         file=display_path(base))
    jobs = []
    for source in sources:
        relative = output_name(source, base).with_name(picture_name(source))
        jobs.append(RenderJob(source, outdir / relative, relative.with_suffix("").as_posix()))
    return jobs


def file_job(source: Path, target: Path | None) -> RenderJob:
    return RenderJob(source, target, picture_name(source)[: -len(".png")])


def load_source(path: Path, search: PackageSearch, mappings: dict[str, str] | None = None
                ) -> tuple[ModelSource, list[str]]:
    """The URDF for a file: a .xacro is expanded with xacro, anything else read as is.

    ``mappings`` (dimension overrides) reach the files that declare them and no others.
    """
    if path.name.endswith(".xacro"):
        mappings = dict(mappings or {})
        result = build_file(path, mappings, search, optional_args=frozenset(mappings))
        return ModelSource(result.xml.encode("utf-8"), path, lines_match=False), result.warnings
    try:
        check_input_size(path)
        data = path.read_bytes()
    except FileNotFoundError:
        raise InputError("no such file", file=display_path(path)) from None
    except IsADirectoryError:
        raise InputError("is a directory, not a URDF or xacro file",
                         file=display_path(path)) from None
    except OSError as exc:
        raise InputError(f"cannot read: {exc.strerror or exc}", file=display_path(path)) from None
    return ModelSource(data, path, lines_match=True), []


class RenderSession:
    """Renders jobs with one renderer, chosen lazily; use as a context manager."""

    def __init__(self, options: RenderOptions, renderer: str = "auto",
                 package_paths: Iterable[Path] = (), force: bool = False,
                 probe: GLProbe | None = None, mappings: dict[str, str] | None = None):
        self.options = options
        self.mappings = dict(mappings or {})  # xacro args for every file (overrides)
        self.renderer_choice = renderer
        self.package_paths = [Path(p) for p in package_paths]
        self.force = force
        self._probe = probe
        if self._probe is None and renderer != "raycast":
            self._probe = GLProbe()
        self.renderer = None
        self.notes: list[str] = []
        self.thumbnails: dict[str, Image.Image] = {}

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self.close()

    def close(self) -> None:
        """Stop an unneeded probe; the GL context stays for the next session."""
        if self._probe is not None:
            self._probe.cancel()

    @property
    def renderer_description(self) -> str | None:
        return self.renderer.description if self.renderer is not None else None

    def _renderer(self):
        if self.renderer is None:
            self.renderer, notes = open_renderer(self.renderer_choice, self._probe)
            self.notes.extend(notes)
        return self.renderer

    def settings(self) -> dict:
        return {"options": self.options.fingerprint()}

    def _draw(self, job: RenderJob, manifest: Manifest | None) -> JobResult | _Drawn:
        """First stage, on the calling thread: expand, check for changes, load, draw.

        Returns a finished JobResult (unchanged, or failed) or the drawn views to finish.
        """
        started = time.perf_counter()
        try:
            search = PackageSearch(package_paths=list(self.package_paths), origin=job.source)
            source, warnings = load_source(job.source, search, self.mappings)
            meshes = mesh_files(parse_urdf(source), source, search, self.options.collision)
            fingerprint = input_fingerprint(source.xml, meshes, self.settings())
            if (manifest is not None and job.target is not None and not self.force
                    and manifest.is_current(job.target, fingerprint, self.renderer_choice)):
                return JobResult(job, "unchanged", warnings=warnings,
                                 seconds=time.perf_counter() - started)
            scene = load_scene(source, search, collision=self.options.collision)
            if not scene.triangle_count:
                kind = "collision" if self.options.collision else "visual"
                warnings.append(f"no {kind} geometry to draw")
            renderer = self._renderer()
            views = draw_views(renderer, scene, self.options)
        except RendererUnavailableError:
            raise  # nothing else can be rendered either: the whole run stops
        except McarError as error:
            return JobResult(job, "failed", error=error, seconds=time.perf_counter() - started)
        return _Drawn(job, views, scene.bounds, fingerprint, renderer.name, warnings, started)

    def _finish(self, drawn: _Drawn, manifest: Manifest | None) -> JobResult:
        """Second stage, on any thread: overlays, PNG encoding, atomic write, manifest."""
        job = drawn.job
        try:
            image = finish_picture(drawn.views, drawn.bounds, self.options)
            png = png_bytes(image)
            if job.target is not None:
                atomic_write(job.target, png)
                if manifest is not None:
                    manifest.record(job.target, drawn.fingerprint, png, job.caption,
                                    drawn.renderer)
                    self.thumbnails[manifest.key(job.target)] = _sheet_copy(image)
        except McarError as error:
            return JobResult(job, "failed", error=error,
                             seconds=time.perf_counter() - drawn.started)
        return JobResult(job, "rendered", warnings=drawn.warnings, png=png,
                         seconds=time.perf_counter() - drawn.started)

    def render_one(self, job: RenderJob, manifest: Manifest | None) -> JobResult:
        """Render a job unless unchanged; errors in the input become a failed result."""
        outcome = self._draw(job, manifest)
        return outcome if isinstance(outcome, JobResult) else self._finish(outcome, manifest)

    def run(self, jobs: list[RenderJob], manifest: Manifest | None) -> Iterator[JobResult]:
        """Render every job, yielding results in order.

        Two stages overlap on the two cores: while one picture is finished (overlays, PNG,
        write) on a worker thread, the next file is expanded and drawn here. The manifest is
        saved at the end, also when interrupted (Ctrl-C): pictures whose write completed
        count as done next time, and nothing half-written is left (atomic writes).
        """
        pending: deque = deque()
        pool = ThreadPoolExecutor(max_workers=FINISH_THREADS, thread_name_prefix="mcar-finish")
        try:
            for job in jobs:
                outcome = self._draw(job, manifest)
                if isinstance(outcome, _Drawn):
                    outcome = pool.submit(self._finish, outcome, manifest)
                pending.append(outcome)
                # Hand back what is finished; keep at most two pictures in flight.
                while pending and (len(pending) > FINISH_THREADS + 1 or _ready(pending[0])):
                    yield _result(pending.popleft())
            while pending:
                yield _result(pending.popleft())
        finally:
            pool.shutdown(wait=True)  # a write in flight completes (atomically) or not at all
            if manifest is not None:
                manifest.save()

    def write_contact_sheet(self, manifest: Manifest) -> tuple[Path, bool]:
        """Redraw ``index.png`` from every picture the manifest lists, if any changed.

        Returns the sheet's path and whether it was written.
        """
        target = manifest.folder / CONTACT_SHEET
        listed = sorted((key, entry) for key, entry in manifest.entries.items()
                        if key != CONTACT_SHEET and (manifest.folder / key).is_file())
        fingerprint = sha256(repr((DRAWING_VERSION, [(key, entry.get("caption"), entry.get("png"))
                                                      for key, entry in listed])).encode())
        if not self.force and manifest.is_current(target, fingerprint):
            return target, False
        pictures = []
        for key, entry in listed:
            image = self.thumbnails.get(key)
            if image is None:
                try:
                    with Image.open(io.BytesIO((manifest.folder / key).read_bytes())) as opened:
                        image = _sheet_copy(opened.convert("RGB"))
                except (OSError, ValueError):
                    continue  # a damaged picture is left out, and redrawn when its input changes
            pictures.append((entry.get("caption") or key, image))
        png = png_bytes(contact_sheet(pictures))
        atomic_write(target, png)
        manifest.record(target, fingerprint, png, "contact sheet")
        manifest.save()
        return target, True
