"""One picture of a scene: fit the camera, draw the model, lay it over the overlays.

``--view all`` draws the four views at half size each and tiles them 2x2, so the result
still has the requested size.
"""

from __future__ import annotations

from dataclasses import replace

from PIL import Image

from .camera import fit_camera
from .compose import compose
from .options import VIEWS, RenderOptions
from .scene import Scene
from .sheet import views_sheet


def draw_view(renderer, scene: Scene, options: RenderOptions) -> Image.Image:
    """The scene from ``options.view`` (one of VIEWS) as an RGB image."""
    camera = fit_camera(options.view, scene.positions, options.width, options.height)
    model = renderer.draw(scene, camera)
    return compose(model, camera, scene.bounds, options)


def draw_picture(renderer, scene: Scene, options: RenderOptions) -> Image.Image:
    """The picture ``options`` ask for: one view, or the 2x2 sheet of all four."""
    if options.view != "all":
        return draw_view(renderer, scene, options)
    quarter = dict(width=options.width // 2, height=options.height // 2)
    views = [(view, draw_view(renderer, scene, replace(options, view=view, **quarter)))
             for view in VIEWS]
    return views_sheet(views, options.width, options.height, options.background)
