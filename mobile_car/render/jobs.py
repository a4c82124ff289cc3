"""What a render run will write: one job per robot input and the picture it becomes.

Kept free of numpy, PIL and the checker, so that a run can plan its pictures and find
them all unchanged (see :mod:`.manifest`) before anything heavy is imported.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

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
        if name.endswith(suffix) and len(name) > len(suffix):
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
