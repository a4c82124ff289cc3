"""``mcar diff --picture``: the old and the new robot side by side, changed links highlighted.

Both halves are drawn from one camera that frames the union of both robots' bounds, over
the same ground grid, so a part that grew or moved shows as a difference between the
halves and nothing else does: two equal robots give two identical halves. The links whose
own content changed (or that were added or renamed) are drawn in :data:`HIGHLIGHT`; the
others are faded towards grey, so the highlight is the only saturated magenta in the
picture whatever the robot's own colours.

This module imports numpy, trimesh and the renderers: the command line imports it only
when ``--picture`` is given.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from PIL import Image

from ..render.backend import GLProbe, open_renderer
from ..render.camera import fit_camera
from ..render.compose import compose, png_bytes
from ..render.options import RenderOptions
from ..render.scene import Scene, load_scene
from ..render.sheet import tile
from .compare import RobotDiff

HIGHLIGHT = (0.93, 0.10, 0.70, 1.0)  # magenta: no part of a robot is usually this colour
# Unchanged links: this much of their own colour, the rest a light grey.
FADE_KEEP, FADE_GREY = 0.35, 0.82
CELL = (640, 480)  # each half, in pixels
PAD = 8  # around and between the halves (the captions go below them)
CAPTION_SIZE = 16


def old_changed_links(diff: RobotDiff) -> set[str]:
    """The old robot's names of the links that changed, were removed or renamed."""
    back = {r.new: r.old for r in diff.renamed if r.what == "link"}
    names = {back.get(c.subject, c.subject) for c in diff.changes if c.section == "link"}
    names |= {name for what, name in diff.removed if what == "link"}
    names |= {r.old for r in diff.renamed if r.what == "link"}
    return names


def highlighted(scene: Scene, links: set[str]) -> Scene:
    """The scene with ``links`` in the highlight colour and the rest faded (unchanged
    when no link is to be highlighted)."""
    if not links or scene.link_of is None:
        return scene
    marked = np.array([name in links for name in scene.link_names], dtype=bool)
    if not marked.any():
        return scene
    chosen = marked[scene.link_of] if len(scene.link_of) else np.zeros(0, dtype=bool)
    colors = scene.colors.copy()
    colors[:, :3] = FADE_KEEP * colors[:, :3] + (1.0 - FADE_KEEP) * FADE_GREY
    colors[chosen] = HIGHLIGHT
    return replace(scene, colors=colors)


def _union_points(scenes: list[Scene]) -> np.ndarray | None:
    bounds = [scene.bounds for scene in scenes if scene.bounds is not None]
    return np.concatenate(bounds) if bounds else None


def _corners(points: np.ndarray) -> np.ndarray:
    """The eight corners of the box around ``points``: fitting the camera to the box
    frames both robots the same way whichever is bigger."""
    low, high = points.min(axis=0), points.max(axis=0)
    return np.array([[x, y, z] for x in (low[0], high[0]) for y in (low[1], high[1])
                     for z in (low[2], high[2])])


def diff_picture(old, new, diff: RobotDiff, renderer: str = "auto",
                 probe: GLProbe | None = None) -> tuple[bytes, list[str]]:
    """The PNG of two loaded robots (:class:`~mobile_car.load.robot.LoadedRobot`) side by
    side, captioned old and new, and the renderer's notes (a fallback taken)."""
    from ..render.session import model_source

    scenes = [load_scene(model_source(loaded), loaded.search, with_links=True)
              for loaded in (old, new)]
    scenes = [highlighted(scenes[0], old_changed_links(diff)),
              highlighted(scenes[1], diff.changed_links)]
    options = RenderOptions(width=CELL[0], height=CELL[1])
    points = _union_points(scenes)
    camera = fit_camera(options.view, None if points is None else _corners(points), *CELL)
    drawer, notes = open_renderer(renderer, probe)
    images = [compose(drawer.draw(scene, camera), camera, points if points is None
                      else np.array([points.min(axis=0), points.max(axis=0)]), options)
              for scene in scenes]
    captions = [f"old: {diff.old.label}", f"new: {diff.new.label}"]
    sheet = tile(images, captions, columns=2, cell=CELL, caption_size=CAPTION_SIZE, pad=PAD)
    return png_bytes(sheet), notes


def halves(image: Image.Image) -> tuple[Image.Image, Image.Image]:
    """The old and the new half of a picture :func:`diff_picture` made (for tests and
    scripts that compare them)."""
    width, height = CELL
    return tuple(image.crop((PAD + i * (width + PAD), PAD, PAD + i * (width + PAD) + width,
                             PAD + height)) for i in (0, 1))
