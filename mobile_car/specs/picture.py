"""``mcar specs --picture``: the figures drawn over the robot, a top view and a side view.

The robot is drawn as ``mcar render --collision`` draws it (same scene, same orthographic
cameras, same renderers and drawing process), joints at zero, its root level; the floor
lies ``body.com_height`` below the centre of mass. Over it, Pillow draws what the figures
say, so a reviewer sees whether they are right:

* top view (from above, x right, y up): the footprint polygon, the support polygon, the
  centre of mass, each lidar's blocked sectors as shaded wedges from its pose, a scale bar;
* side view (from the robot's right, x right, z up): the floor, the centre of mass, and
  the forward and backward tip angles as lines from the support polygon's front and back
  edges, each at its angle from the vertical: on flat ground a line of a right figure
  passes through the centre of mass.

Everything is taken from the Sections (keys in docs/specs.md); a figure that is None or
absent is not drawn. Without a robot (``scene`` None) the overlays are drawn alone, on the
background and grid. This module imports numpy and Pillow: the command line imports it
only when ``--picture`` is given.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from PIL import Image, ImageDraw

from ..names import shown
from ..render.camera import Camera, fit_camera
from ..render.compose import TEXT_COLOR, compose, font, format_length, nice_step, png_bytes
from ..render.options import RenderOptions
from ..render.sheet import tile

CELL = (640, 480)  # each view, in pixels
PAD = 8  # around and between the views (captions go below them)
CAPTION_SIZE = 14
SUPERSAMPLE = 2  # overlays are drawn this much larger and scaled down: anti-aliased lines

# Colours no robot part usually has (render draws collision geometry in its link's
# colour or grey), so a test and a reader can tell each overlay by its colour.
FOOTPRINT_COLOUR = (0, 114, 178)     # blue outline
SUPPORT_COLOUR = (230, 140, 0)       # orange outline, lightly filled
SUPPORT_FILL_ALPHA = 60
COM_COLOUR = (255, 214, 0)           # yellow disc in a black ring
COM_RING = (0, 0, 0)
BLOCKED_COLOUR = (128, 0, 160)       # purple wedges
BLOCKED_ALPHA = 110
LIDAR_COLOUR = (128, 0, 160)
TIP_COLOUR = (200, 20, 20)           # red lines from the support edges
FLOOR_COLOUR = (70, 70, 70)
# A lidar's wedges reach this share of the frame's half height (or its range, if less):
# its full range (metres) would cover the picture.
WEDGE_REACH = 0.9
FRAME_ROOM = 0.06  # free space around what is drawn, a share of its largest size


@dataclass
class Lidar:
    """A sensor with blocked sectors: pose [x, y, z, yaw_deg] (root frame), range [min,
    max] or None, blocked [[from_deg, to_deg], ...] in the sensor frame."""

    name: str
    pose: tuple
    range: tuple | None
    blocked: list


@dataclass
class Overlay:
    """What the picture draws, read from the Sections; None where a figure is absent."""

    footprint: list | None = None
    support: list | None = None
    com: tuple | None = None           # root frame
    floor_z: float = 0.0               # the floor's height in the root frame
    tip: dict = field(default_factory=dict)   # forward/backward/left/right -> deg
    lidars: list = field(default_factory=list)


@dataclass
class View:
    """One drawn view: its name (top, side), the RGB picture and the camera that made it
    (``camera.to_pixels`` says where a root-frame point lands)."""

    name: str
    image: Image.Image
    camera: Camera


def _figures(sections) -> dict:
    return {f.key: f.value for section in sections for f in section.figures}


def _polygon(value) -> list | None:
    if not isinstance(value, (list, tuple)) or len(value) < 2:
        return None
    try:
        return [(float(x), float(y)) for x, y in value]
    except (TypeError, ValueError):
        return None


def _number(value) -> float | None:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    return float(value) if math.isfinite(value) else None


def overlay_of(sections) -> Overlay:
    """The figures the picture draws, from the Sections ``mcar specs`` computed."""
    figures = _figures(sections)
    overlay = Overlay(footprint=_polygon(figures.get("body.footprint")),
                      support=_polygon(figures.get("statics.support")))
    com = figures.get("body.com")
    if isinstance(com, (list, tuple)) and len(com) == 3 and all(
            _number(c) is not None for c in com):
        overlay.com = tuple(float(c) for c in com)
        height = _number(figures.get("body.com_height"))
        if height is not None:
            overlay.floor_z = overlay.com[2] - height
    for side in ("forward", "backward", "left", "right"):
        angle = _number(figures.get(f"statics.tip.{side}"))
        if angle is not None:
            overlay.tip[side] = angle
    for key, value in figures.items():
        if key.startswith("sensors.") and key.endswith(".blocked") and isinstance(value, list):
            name = key[len("sensors."):-len(".blocked")]
            pose = figures.get(f"sensors.{name}.pose")
            if not isinstance(pose, (list, tuple)) or len(pose) != 4:
                continue
            reach = figures.get(f"sensors.{name}.range")
            overlay.lidars.append(Lidar(
                name, tuple(float(p) for p in pose),
                tuple(reach) if isinstance(reach, (list, tuple)) and len(reach) == 2 else None,
                [tuple(float(a) for a in sector) for sector in value]))
    return overlay


def _points(overlay: Overlay, bounds) -> np.ndarray:
    """Every point the views must show: the robot's box, polygons on the floor, the CoM."""
    points = [] if bounds is None else [list(p) for p in bounds]
    for polygon in (overlay.footprint, overlay.support):
        points += [[x, y, overlay.floor_z] for x, y in polygon or ()]
    if overlay.com is not None:
        points.append(list(overlay.com))
    points += [list(lidar.pose[:3]) for lidar in overlay.lidars]
    if not points:
        return np.array([[-0.1, -0.1, 0.0], [0.1, 0.1, 0.1]])
    points = np.array(points, dtype=float)
    low, high = points.min(axis=0), points.max(axis=0)
    low[2] = min(low[2], overlay.floor_z)
    room = FRAME_ROOM * float((high - low).max())  # for the labels at the edges
    return np.array([low - room, high + room])


class _Layer:
    """An RGBA overlay drawn SUPERSAMPLE times larger, in world coordinates."""

    def __init__(self, camera: Camera):
        self.camera = camera
        size = (camera.width * SUPERSAMPLE, camera.height * SUPERSAMPLE)
        self.image = Image.new("RGBA", size, (0, 0, 0, 0))
        self.draw = ImageDraw.Draw(self.image)
        self.line = max(2, round(min(camera.width, camera.height) / 240)) * SUPERSAMPLE
        self.text = font(max(10, round(min(camera.width, camera.height) / 36)) * SUPERSAMPLE)

    def px(self, points) -> list[tuple[float, float]]:
        pixels = self.camera.to_pixels(np.asarray(points, dtype=float).reshape(-1, 3))
        return [tuple(p) for p in pixels * SUPERSAMPLE]

    def polygon(self, points, outline, fill=None) -> None:
        corners = self.px(points)
        if fill is not None:
            filler = Image.new("RGBA", self.image.size, (0, 0, 0, 0))
            ImageDraw.Draw(filler).polygon(corners, fill=fill)
            self.image.alpha_composite(filler)
        self.draw.line([*corners, corners[0]], fill=outline, width=self.line, joint="curve")

    def marker(self, point) -> None:
        (x, y), = self.px([point])
        radius = self.line * 3
        ring = self.line
        self.draw.ellipse([x - radius - ring, y - radius - ring, x + radius + ring,
                           y + radius + ring], fill=COM_RING)
        self.draw.ellipse([x - radius, y - radius, x + radius, y + radius], fill=COM_COLOUR)

    def label(self, at, text: str, colour, anchor="ls") -> None:
        self.draw.text(at, text, fill=colour, font=self.text, anchor=anchor,
                       stroke_width=SUPERSAMPLE, stroke_fill=(255, 255, 255))

    def scale_bar(self) -> None:
        """A bar of a round length (1, 2 or 5 x 10^k m) near the top left corner."""
        metres = nice_step(self.camera.half_width * 2 / 6)
        length = metres / self.camera.pixel_size * SUPERSAMPLE
        margin = 12 * SUPERSAMPLE
        y = margin + self.line * 4
        ends = [(margin, y), (margin + length, y)]
        self.draw.line(ends, fill=TEXT_COLOR, width=self.line)
        for x, _ in ends:
            self.draw.line([(x, y - self.line * 2), (x, y + self.line * 2)], fill=TEXT_COLOR,
                           width=self.line)
        self.label((margin + length + self.line * 4, y + self.line * 2),
                   format_length(metres), TEXT_COLOR)

    def over(self, image: Image.Image) -> Image.Image:
        layer = self.image.convert("RGBa").reduce(SUPERSAMPLE).convert("RGBA")
        base = image.convert("RGBA")
        base.alpha_composite(layer)
        return base.convert("RGB")


def _on_floor(polygon, z) -> list:
    return [(x, y, z) for x, y in polygon]


def _top_overlays(layer: _Layer, overlay: Overlay) -> None:
    if overlay.support:
        layer.polygon(_on_floor(overlay.support, overlay.floor_z), SUPPORT_COLOUR,
                      fill=(*SUPPORT_COLOUR, SUPPORT_FILL_ALPHA))
    if overlay.footprint:
        layer.polygon(_on_floor(overlay.footprint, overlay.floor_z), FOOTPRINT_COLOUR)
    reach_limit = WEDGE_REACH * layer.camera.half_height
    for lidar in overlay.lidars:
        x, y, z, yaw = lidar.pose
        reach = reach_limit if lidar.range is None else min(reach_limit, lidar.range[1])
        radius = reach / layer.camera.pixel_size * SUPERSAMPLE
        (cx, cy), = layer.px([(x, y, z)])
        box = [cx - radius, cy - radius, cx + radius, cy + radius]
        wedges = Image.new("RGBA", layer.image.size, (0, 0, 0, 0))
        for start, end in lidar.blocked:
            # Pillow's angles run clockwise from the image's +x; on a map (y up) a
            # counter-clockwise azimuth a is -a, and a sector from..to is -to..-from.
            ImageDraw.Draw(wedges).pieslice(box, -(yaw + end), -(yaw + start),
                                            fill=(*BLOCKED_COLOUR, BLOCKED_ALPHA))
        layer.image.alpha_composite(wedges)
        dot = layer.line * 1.5
        layer.draw.ellipse([cx - dot, cy - dot, cx + dot, cy + dot], fill=LIDAR_COLOUR)
        layer.label((cx + dot * 2, cy - dot * 2), shown(lidar.name), LIDAR_COLOUR)
    if overlay.com is not None:
        layer.marker((overlay.com[0], overlay.com[1], overlay.floor_z))
    layer.scale_bar()


def _side_overlays(layer: _Layer, overlay: Overlay) -> None:
    camera = layer.camera
    floor_y = layer.px([(camera.center[0], 0.0, overlay.floor_z)])[0][1]
    layer.draw.line([(0, floor_y), (layer.image.width, floor_y)], fill=FLOOR_COLOUR,
                    width=layer.line)
    base = overlay.support or overlay.footprint
    if base and overlay.com is not None:
        height = overlay.com[2] - overlay.floor_z
        xs = [x for x, _ in base]
        for side, edge, inward in (("forward", max(xs), -1.0), ("backward", min(xs), 1.0)):
            angle = overlay.tip.get(side)
            if angle is None or not 0 <= angle < 90:
                continue
            top = (edge + inward * height * math.tan(math.radians(angle)), 0.0,
                   overlay.floor_z + height)
            start, end = layer.px([(edge, 0.0, overlay.floor_z), top])
            layer.draw.line([start, end], fill=TIP_COLOUR, width=layer.line)
            layer.draw.line([start, (start[0], end[1])], fill=TIP_COLOUR,
                            width=max(1, layer.line // 2))  # the vertical it is measured from
            # Written inwards of its edge, above the line's top: inside the frame.
            anchor = "ls" if inward > 0 else "rs"
            layer.label((start[0] + inward * layer.line * 2, end[1] - layer.line * 3),
                        f"{side} {angle:.1f}°", TIP_COLOUR, anchor=anchor)
    if overlay.com is not None:
        layer.marker(overlay.com)
    layer.scale_bar()


def draw_views(sections, scene=None, drawer=None, size=CELL, views=("top", "side")) -> list[View]:
    """The top and side views (:class:`View`) of the figures in ``sections``, over the
    robot ``scene`` (a render Scene of its collision geometry, drawn by ``drawer``, a
    renderer) or over the bare background when ``scene`` is None."""
    overlay = overlay_of(sections)
    bounds = _points(overlay, None if scene is None else scene.bounds)
    drawn = []
    for name in views:
        options = RenderOptions(view=name, width=size[0], height=size[1], axes=True)
        camera = fit_camera(name, bounds, *size)
        if scene is not None and drawer is not None and scene.bounds is not None:
            model = drawer.draw(scene, camera)
        else:
            model = np.zeros((size[1], size[0], 4), dtype=np.uint8)
        image = compose(model, camera, bounds, options)
        layer = _Layer(camera)
        (_top_overlays if name == "top" else _side_overlays)(layer, overlay)
        drawn.append(View(name, layer.over(image), camera))
    return drawn


CAPTIONS = {
    "top": "top: footprint (blue), support (orange), centre of mass, lidar blocked (purple)",
    "side": "side: floor, centre of mass, tip angles forward/backward (red)",
}


def sheet(views: list[View]) -> Image.Image:
    """The views side by side, captioned."""
    return tile([view.image for view in views], [CAPTIONS[view.name] for view in views],
                columns=len(views), cell=CELL, caption_size=CAPTION_SIZE, pad=PAD)


def cell(image: Image.Image, index: int) -> Image.Image:
    """The ``index``-th view of a picture :func:`specs_picture` made (tests, scripts)."""
    width, height = CELL
    left = PAD + index * (width + PAD)
    return image.crop((left, PAD, left + width, PAD + height))


def robot_scene(checked):
    """The render Scene of a checked robot's collision geometry, joints at zero."""
    from ..render.scene import load_scene
    from ..render.session import model_source

    return load_scene(model_source(checked.loaded), checked.loaded.search, collision=True)


def specs_picture(sections, checked=None, renderer: str = "auto",
                  probe=None) -> tuple[bytes, list[str]]:
    """The PNG of the top and side views side by side, and the renderer's notes (a
    fallback taken). ``checked`` (a CheckResult with its loaded robot) gives the robot
    drawn under the figures; without it the figures are drawn alone. Raises RenderError
    for geometry that cannot be drawn, RendererUnavailableError when no renderer runs."""
    scene, drawer, notes = None, None, []
    if checked is not None and checked.loaded is not None:
        from ..render.backend import open_renderer

        scene = robot_scene(checked)
        if scene.bounds is not None:
            drawer, notes = open_renderer(renderer, probe)
    return png_bytes(sheet(draw_views(sections, scene, drawer))), notes
