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
from collections.abc import Iterator
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

from PIL import Image

from ..atomic import atomic_write
from ..check.colours import without_unusable_colours
from ..errors import McarError, RenderError, RendererUnavailableError
from ..freshness import Stamper, diagnostics_data, diagnostics_from
from ..load.outputs import refuse_overwriting
from ..load.robot import LoadedRobot, LoadOptions
from .backend import GLProbe, open_renderer, start_probe
from .compose import png_bytes
from .drawing import DrawingFailed
from .jobs import (  # noqa: F401
    JobResult,
    RenderJob,
    drawable_check,
    file_job,
    picture_name,
    picture_path,
    selection_jobs,
)
from .manifest import CONTACT_SHEET, Manifest, input_fingerprint, picture_key
from .options import RenderOptions
from .picture import DrawnView, draw_views, finish_picture
from .scene import ModelSource, load_scene
from .sheet import THUMBNAIL_WIDTH, contact_sheet

# The check's warnings shown with a picture: xacro's, and a mesh not read, missing or
# broken (W207), over a limit (W210) or outside the allowed folders (W215), drawn as a
# marker.
SHOWN_WARNINGS = ("W207", "W210", "W215", "W220")
# Pictures finished (overlays, PNG, write) in parallel with drawing the next ones.
FINISH_THREADS = 1


@dataclass
class _Drawn:
    """A job between the two stages: drawn, not yet composed and written."""

    job: RenderJob
    views: list[DrawnView]
    bounds: object
    labels: tuple  # link names laid over the picture (Scene.labels)
    fingerprint: str
    renderer: str
    warnings: list
    started: float
    key: str | None
    files: list[Path]


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


def _drawing_error(job: RenderJob, exc: Exception) -> RenderError:
    """An unforeseen failure while drawing one robot, as that robot's located error: the
    other robots of the run are still drawn, and the run ends with exit 1."""
    detail = str(exc) if isinstance(exc, DrawingFailed) else f"{type(exc).__name__}: {exc}"
    return RenderError(f"cannot draw this robot: {detail}", file=job.input.label)


def model_source(loaded: LoadedRobot) -> ModelSource:
    """The URDF a loaded robot became, for the scene: a plain URDF's lines are its file's.
    A colour urdfdom cannot read (W217) is left out, so the part is drawn grey as in rviz."""
    path = loaded.input.path if loaded.input.path is not None else Path.cwd() / "<stdin>"
    return ModelSource(without_unusable_colours(loaded.urdf), path,
                       lines_match=not loaded.from_xacro)


class RenderSession:
    """Renders jobs with one renderer, chosen lazily; use as a context manager."""

    def __init__(self, options: RenderOptions, renderer: str = "auto",
                 load: LoadOptions | None = None, force: bool = False,
                 probe: GLProbe | None = None, stdin=None):
        self.options = options
        self.load = load or LoadOptions()  # how every input is loaded (arguments, overrides)
        self.stdin = stdin  # the binary stream an input "-" reads
        self.renderer_choice = renderer
        self.force = force
        self._probe = probe
        if self._probe is None:
            self._probe = start_probe(renderer)
        self.renderer = None
        self.notes: list[str] = []
        self.thumbnails: dict[str, Image.Image] = {}
        self.stamper = Stamper()

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self.close()

    def close(self) -> None:
        """Stop an unneeded probe; the drawing process stays for the next session."""
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

    def _key(self, job: RenderJob, manifest: Manifest | None) -> str | None:
        """The picture's key, when it is kept in a manifest with stamps (not stdin)."""
        if manifest is None or job.target is None or job.basis is None or job.input.path is None:
            return None
        return picture_key(job.basis, self.options)

    def _stamps(self, job: RenderJob, files: list[Path]) -> list | None:
        generated = [*job.generated, self.load.overrides.path if self.load.overrides else None]
        return self.stamper.stamps([*files, *job.basis.files], skip=generated)

    def _draw(self, job: RenderJob, manifest: Manifest | None) -> JobResult | _Drawn:
        """First stage, on the calling thread: look for changes, load and check, draw.

        Returns a finished JobResult (unchanged, or failed) or the drawn views to finish.
        A robot that ``mcar check`` rejects fails with the check's diagnostics.
        """
        started = time.perf_counter()
        key = self._key(job, manifest)
        if key is not None and not self.force:
            entry = manifest.fresh(job.target, key, self.renderer_choice)
            if entry is not None:  # nothing it was made from changed: nothing loaded
                return JobResult(job, "unchanged", seconds=time.perf_counter() - started,
                                 warnings=diagnostics_from(entry.get("warnings") or []))
        try:
            result = drawable_check(job.input, self.load, self.options.collision, self.stdin,
                                    job.checked)
            warnings = [d for d in result.diagnostics if d.rule in SHOWN_WARNINGS]
            kind = "collision" if self.options.collision else "visual"
            drawn = [mesh for mesh in result.mesh_files if mesh.kind == kind and mesh.path]
            # A mesh's materials and textures are inputs too: never overwritten, stamped.
            # One that is missing is stamped (as missing: the picture is redrawn until it
            # is there), not hashed.
            meshes = [*(mesh.path for mesh in drawn if mesh.path.is_file()),
                      *(p for mesh in drawn for p in mesh.reads)]
            files = [*result.loaded.deps, *meshes,
                     *(mesh.path for mesh in drawn if not mesh.path.is_file())]
            source = model_source(result.loaded)
            if job.target is not None:
                refuse_overwriting(job.target, files)
            fingerprint = input_fingerprint(source.xml, meshes, self.settings())
            if (manifest is not None and job.target is not None and not self.force
                    and manifest.is_current(job.target, fingerprint, self.renderer_choice)):
                if key is not None:  # a file changed, the robot did not: stamp it anew
                    manifest.stamp(job.target, key, self._stamps(job, files),
                                   diagnostics_data(warnings))
                return JobResult(job, "unchanged", warnings=warnings,
                                 seconds=time.perf_counter() - started)
            scene = load_scene(source, result.loaded.search, collision=self.options.collision,
                               joints=self.options.joints, frames=self.options.frames)
            if job.target is not None:  # what trimesh opened, should the scan have missed it
                refuse_overwriting(job.target, scene.reads)
            files = [*files, *scene.reads]
            if not scene.triangle_count:
                warnings.append(f"no {kind} geometry to draw")
            elif scene.frames_only:
                warnings.append(f"no {kind} geometry to draw: drew the link frames")
            renderer = self._renderer()
            views = draw_views(renderer, scene, self.options)
        except RendererUnavailableError:
            raise  # nothing else can be rendered either: the whole run stops
        except McarError as error:
            return JobResult(job, "failed", error=error, seconds=time.perf_counter() - started)
        except Exception as exc:  # trimesh, numpy or GL on input nothing checked for
            return JobResult(job, "failed", error=_drawing_error(job, exc),
                             seconds=time.perf_counter() - started)
        return _Drawn(job, views, scene.bounds, scene.labels, fingerprint, renderer.name,
                      warnings, started, key, files)

    def _finish(self, drawn: _Drawn, manifest: Manifest | None) -> JobResult:
        """Second stage, on any thread: overlays, PNG encoding, atomic write, manifest."""
        job = drawn.job
        try:
            image = finish_picture(drawn.views, drawn.bounds, self.options, drawn.labels)
            png = png_bytes(image)
            if job.target is not None:
                atomic_write(job.target, png)
                if manifest is not None:
                    manifest.record(job.target, drawn.fingerprint, png, job.caption,
                                    drawn.renderer)
                    if drawn.key is not None:
                        shown = [w for w in drawn.warnings if not isinstance(w, str)]
                        manifest.stamp(job.target, drawn.key, self._stamps(job, drawn.files),
                                       diagnostics_data(shown))
                    self.thumbnails[manifest.key(job.target)] = _sheet_copy(image)
        except McarError as error:
            return JobResult(job, "failed", error=error,
                             seconds=time.perf_counter() - drawn.started)
        except Exception as exc:  # e.g. numpy on a picture of non-finite bounds
            return JobResult(job, "failed", error=_drawing_error(job, exc),
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
        listed = manifest.sheet_pictures()
        fingerprint = manifest.sheet_fingerprint()
        if not self.force and manifest.is_current(target, fingerprint):
            return target, False
        pictures = []
        for key, _entry in listed:
            image = self.thumbnails.get(key)
            if image is None:
                try:
                    with Image.open(io.BytesIO((manifest.folder / key).read_bytes())) as opened:
                        image = _sheet_copy(opened.convert("RGB"))
                except (OSError, ValueError):
                    continue  # a damaged picture is left out, and redrawn when its input changes
            pictures.append((manifest.sheet_caption(key), image))
        png = png_bytes(contact_sheet(pictures))
        atomic_write(target, png)
        manifest.record(target, fingerprint, png, "contact sheet")
        manifest.save()
        return target, True
