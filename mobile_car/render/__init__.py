"""``mcar render``: robot descriptions as PNG pictures, headless, with no display or GPU.

Pipeline: :mod:`.scene` (URDF -> coloured world-space triangles via yourdfpy + trimesh),
:mod:`.camera` (standard views, orthographic camera fitted to the model), a renderer
(:mod:`.gl`, OpenGL on EGL; or :mod:`.raycast`, the trimesh + embreex fallback, chosen by
:mod:`.backend`), :mod:`.compose` (background, ground grid, axis triad, PNG), :mod:`.sheet`
(contact sheet and 2x2 view sheet), :mod:`.session` (many files, skipping unchanged ones
recorded in :mod:`.manifest`).

Importing this package is cheap; numpy, trimesh and OpenGL load with the submodules that
need them.
"""

from __future__ import annotations

from pathlib import Path

from .options import RENDERERS, VIEW_CHOICES, VIEWS, RenderOptions, parse_color, parse_size

__all__ = ["RENDERERS", "VIEWS", "VIEW_CHOICES", "RenderOptions", "parse_color", "parse_size",
           "render_file"]


def render_file(path: str | Path, options: RenderOptions | None = None,
                renderer: str = "auto", package_paths=()) -> bytes:
    """One URDF or xacro file as PNG bytes (nothing is written).

    Raises the errors of :mod:`mobile_car.errors`: CheckFailed (with mcar check's
    diagnostics) or RenderError for a bad input, RendererUnavailableError when neither
    OpenGL nor ray casting can run.
    """
    from ..load.inputs import RobotInput
    from ..load.robot import LoadOptions
    from .session import RenderSession, file_job

    load = LoadOptions(package_paths=[Path(p) for p in package_paths])
    with RenderSession(options or RenderOptions(), renderer=renderer, load=load,
                       force=True) as session:
        result = session.render_one(file_job(RobotInput(Path(path)), None), manifest=None)
    if result.error is not None:
        raise result.error
    return result.png
