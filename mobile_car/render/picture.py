"""One picture of a scene: fit the camera, draw the model, lay it over the overlays.

Split in two so that a batch can overlap them: :func:`draw_views` needs the renderer
(the GL context lives on one thread), :func:`finish_picture` is Pillow and numpy work that
can run on another core while the next file is expanded and drawn.

``--view all`` draws the four views at half size each and tiles them 2x2, so the result
still has the requested size.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from PIL import Image

from .camera import Camera, fit_camera
from .compose import compose
from .options import VIEWS, RenderOptions
from .scene import Scene
from .sheet import views_sheet


@dataclass
class DrawnView:
    """One view as the renderer drew it: premultiplied RGBA pixels and the camera used."""

    options: RenderOptions
    camera: Camera
    model: np.ndarray


def draw_views(renderer, scene: Scene, options: RenderOptions) -> list[DrawnView]:
    """Draw the model for the requested view, or for each of the four with ``all``."""
    if options.view == "all":
        quarter = {"width": options.width // 2, "height": options.height // 2}
        wanted = [replace(options, view=view, **quarter) for view in VIEWS]
    else:
        wanted = [options]
    drawn = []
    for view_options in wanted:
        camera = fit_camera(view_options.view, scene.positions, view_options.width,
                            view_options.height)
        drawn.append(DrawnView(view_options, camera, renderer.draw(scene, camera)))
    return drawn


def finish_picture(drawn: list[DrawnView], bounds: np.ndarray | None,
                   options: RenderOptions, labels=()) -> Image.Image:
    """The final RGB picture from what :func:`draw_views` returned; ``labels``: link
    names to lay over it (Scene.labels)."""
    images = [compose(view.model, view.camera, bounds, view.options, labels)
              for view in drawn]
    if options.view != "all":
        return images[0]
    pairs = zip(drawn, images, strict=False)
    return views_sheet([(view.options.view, image) for view, image in pairs],
                       options.width, options.height, options.background)


def draw_picture(renderer, scene: Scene, options: RenderOptions) -> Image.Image:
    """The picture ``options`` ask for, in one go."""
    return finish_picture(draw_views(renderer, scene, options), scene.bounds, options,
                          scene.labels)
