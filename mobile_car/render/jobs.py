"""What a render run will write: one job per robot input and the picture it becomes.

Kept free of numpy, PIL and the checker, so that a run can plan its pictures and find
them all unchanged (see :mod:`.manifest`), or its one robot failing its check
(:func:`check_first`), before anything heavy is imported.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import CheckFailed, McarError
from ..freshness import Basis
from ..load.inputs import RobotInput
from ..load.selection import Selection
from ..packages.discover import output_name

URDF_SUFFIXES = (".urdf.xacro", ".xacro", ".urdf")


@dataclass
class RenderJob:
    """One robot input and the PNG it becomes (None: return the bytes, write nothing)."""

    input: RobotInput
    target: Path | None
    caption: str
    checked: object = None  # a CheckResult, already loaded and checked (mcar ci): draw that
    # What besides the files it reads decides the robot (arguments, overrides, search);
    # None: no stamps are kept, the picture is judged by loading it.
    basis: Basis | None = None
    generated: tuple[Path, ...] = ()  # files the run wrote for the robot (overrides): no stamp


def picture_name(path: Path | None) -> str:
    """``test_wheel.urdf.xacro`` -> ``test_wheel.png``; stdin -> ``stdin.png``."""
    if path is None:
        return "stdin.png"
    name = path.name
    for suffix in URDF_SUFFIXES:
        # .urdf in any case (NAME.URDF -> NAME.png); xacro's suffix is always lower case
        if name.lower().endswith(suffix) and len(name) > len(suffix):
            name = name[: -len(suffix)]
            break
    return name + ".png"


def picture_path(inp: RobotInput) -> Path:
    """Where an input's picture goes below the output folder: mirrored below the folder
    it was found in (``wheel/test_wheel.png``), else just its name."""
    if inp.path is None or inp.base is None:
        return Path(picture_name(inp.path))
    return output_name(inp.path, inp.base).with_name(picture_name(inp.path))


def selection_jobs(selection: Selection, outdir: Path) -> list[RenderJob]:
    """A job per input, its picture mirrored into outdir."""
    jobs = []
    for inp in selection.inputs:
        relative = picture_path(inp)
        caption = relative.with_suffix("").as_posix() if inp.base is not None \
            else relative.stem
        jobs.append(RenderJob(inp, outdir / relative, caption))
    return jobs


def file_job(inp: RobotInput, target: Path | None) -> RenderJob:
    return RenderJob(inp, target, picture_name(inp.path)[: -len(".png")])


@dataclass
class JobResult:
    """What happened to one job: ``status`` is rendered, unchanged or failed."""

    job: RenderJob
    status: str
    error: McarError | None = None
    warnings: list = field(default_factory=list)  # the check's Diagnostics worth showing
    png: bytes | None = None
    seconds: float = 0.0


def blocking_diagnostics(result, collision: bool) -> list:
    """What stops a robot from being drawn (``result``, a CheckResult): any check error;
    all the check's diagnostics then, else none. A mesh that is missing or broken (W207)
    does not: it is drawn as a marker, as one over a limit is, and the warning shown with
    the picture."""
    if result.failure is not None:
        raise result.failure
    if result.errors or not result.tree_is_drawable:
        return result.diagnostics
    return []


def drawable_check(inp: RobotInput, load, collision: bool, stdin=None, checked=None):
    """``inp`` loaded (``load``: LoadOptions) and checked, or ``checked``, a CheckResult
    already made of it: the result, when the robot may be drawn; McarError when not
    (CheckFailed carrying check's diagnostics)."""
    if checked is None:
        from ..check.checker import check_input

        checked = check_input(inp, load, stdin=stdin)
    blocking = blocking_diagnostics(checked, collision)
    if blocking:
        raise CheckFailed(inp.label, blocking)
    return checked


def check_first(job: RenderJob, load, collision: bool, stdin=None) -> JobResult | None:
    """Load and check the job's robot now, as its drawing would: the failed result when
    nothing may be drawn, else None, with the check kept on the job for the drawing. A run
    of one robot calls this before it starts a drawing process and imports numpy and
    trimesh (~1 s of CPU): a broken file is answered in a tenth of it."""
    started = time.perf_counter()
    try:
        job.checked = drawable_check(job.input, load, collision, stdin)
    except McarError as error:
        return JobResult(job, "failed", error=error, seconds=time.perf_counter() - started)
    except Exception:  # unforeseen: the drawing meets it again and reports it, as before
        return None
    return None
