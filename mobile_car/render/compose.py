"""Lay a rendered model over its background, ground grid and axis triad; encode PNG.

The grid and the triad are drawn here with Pillow rather than inside each renderer, so the
OpenGL and ray-cast pictures get exactly the same overlays. The grid lies on the ground
plane under the model (its lowest point), with a round spacing (1, 2 or 5 times a power of
ten) printed in the corner so a viewer can read sizes; the triad shows the world axes
(x red, y green, z blue) as the camera sees them. Lines are drawn at twice the size and
scaled down, which anti-aliases them.
"""

from __future__ import annotations

import io
import math

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from .camera import Camera
from .options import RenderOptions

SUPERSAMPLE = 2
AXIS_COLORS = {"x": (214, 39, 40), "y": (44, 160, 44), "z": (31, 90, 220)}
TEXT_COLOR = (40, 44, 52)
# Grid cells across the model's largest size, roughly.
GRID_CELLS = 6


def nice_step(length: float) -> float:
    """The smallest of 1, 2, 5 x 10^k that is at least ``length``."""
    if length <= 0 or not math.isfinite(length):
        return 1.0
    power = 10.0 ** math.floor(math.log10(length))
    for factor in (1.0, 2.0, 5.0, 10.0):
        if factor * power >= length * (1 - 1e-4):  # float32 bounds: 0.3 is 0.30000001
            return factor * power
    return 10.0 * power


def format_length(metres: float) -> str:
    """A grid spacing for people: ``5 cm``, ``2 mm``, ``1 m``."""
    for unit, scale in (("m", 1.0), ("cm", 0.01)):
        if metres >= scale * (1 - 1e-9):
            return f"{metres / scale:g} {unit}"
    return f"{metres / 0.001:g} mm"


def font(size: int):
    return ImageFont.load_default(size=size)


def _grid_segments(camera: Camera, bounds: np.ndarray) -> tuple[list, float]:
    """Ground-grid line segments as world point pairs, and the grid spacing in metres."""
    extent = float((bounds[1] - bounds[0]).max())
    step = nice_step(extent / GRID_CELLS if extent > 0 else 0.01)
    ground = float(bounds[0][2])
    centre = np.round(0.5 * (bounds[0][:2] + bounds[1][:2]) / step) * step
    # Far enough to fill the frame even when the ground is seen at a grazing angle.
    reach = 3.0 * max(camera.half_width, camera.half_height, extent)
    count = int(min(math.ceil(reach / step), 400))
    ticks = np.arange(-count, count + 1) * step
    segments = []
    for tick in ticks:
        x, y = centre[0] + tick, centre[1] + tick
        low_x, high_x = centre[0] - count * step, centre[0] + count * step
        low_y, high_y = centre[1] - count * step, centre[1] + count * step
        segments.append(((x, low_y, ground), (x, high_y, ground)))
        segments.append(((low_x, y, ground), (high_x, y, ground)))
    return segments, step


def _line_width(camera: Camera) -> int:
    return max(1, round(min(camera.width, camera.height) / 400)) * SUPERSAMPLE


def _grid_mask(camera: Camera, bounds: np.ndarray) -> tuple[Image.Image, float]:
    """Coverage (mode L, 0..255) of the grid lines, and the grid spacing in metres."""
    mask = Image.new("L", (camera.width * SUPERSAMPLE, camera.height * SUPERSAMPLE), 0)
    draw = ImageDraw.Draw(mask)
    segments, step = _grid_segments(camera, bounds)
    ends = camera.to_pixels(np.array(segments, dtype=float).reshape(-1, 3)) * SUPERSAMPLE
    width = _line_width(camera) // 2 or 1
    for start, end in ends.reshape(-1, 2, 2):
        draw.line([tuple(start), tuple(end)], fill=255, width=width)
    return mask.reduce(SUPERSAMPLE), step


def _overlay_strip(camera: Camera, axes: bool, grid_step: float | None):
    """The axis triad (lower left) and the grid spacing (lower right), drawn on a
    transparent strip along the bottom edge; returns (strip, its top row)."""
    scale = SUPERSAMPLE
    short_side = min(camera.width, camera.height)
    text_size = max(9, round(short_side / 32))
    length = max(12.0, short_side * 0.07)
    margin = max(6.0, short_side * 0.03)
    strip_height = min(camera.height, math.ceil(margin + 2.4 * length + text_size))
    top = camera.height - strip_height
    layer = Image.new("RGBA", (camera.width * scale, strip_height * scale), (0, 0, 0, 0))
    draw = ImageDraw.Draw(layer)
    text_font = font(text_size * scale)
    origin = np.array([margin + length, strip_height - margin - length]) * scale
    width = _line_width(camera)
    right, up, back = camera.rotation
    # Farthest axis first, so the nearer ones are drawn over it.
    for index in sorted(range(3), key=lambda i: back[i]) if axes else ():
        name = "xyz"[index]
        tip = origin + np.array([right[index], -up[index]]) * length * scale
        if np.hypot(right[index], up[index]) < 0.2:  # pointing at the viewer: draw a dot
            radius = width * 1.8
            draw.ellipse([*(origin - radius), *(origin + radius)], fill=AXIS_COLORS[name])
            label_at = origin + np.array([radius + 2 * scale, -radius - 2 * scale])
        else:
            draw.line([tuple(origin), tuple(tip)], fill=AXIS_COLORS[name], width=width)
            label_at = origin + (tip - origin) * 1.28
        draw.text(tuple(label_at), name, fill=AXIS_COLORS[name], font=text_font, anchor="mm")
    if grid_step is not None:
        draw.text((layer.width - margin * scale, layer.height - margin * scale),
                  f"grid {format_length(grid_step)}", fill=TEXT_COLOR, font=text_font,
                  anchor="rs")
    # Premultiplied while averaging, so transparent pixels do not darken line edges.
    return layer.convert("RGBa").reduce(scale).convert("RGBA"), top


def compose(model: np.ndarray, camera: Camera, bounds: np.ndarray | None,
            options: RenderOptions, labels=()) -> Image.Image:
    """The final RGB picture: background, grid, the model, link names (``labels``:
    (text, world point) pairs), then the triad.

    ``model`` is (H, W, 4) uint8 with colour premultiplied by coverage, as drawn.
    """
    image = Image.new("RGB", (camera.width, camera.height), options.background)
    grid_step = None
    if options.grid:
        grid_bounds = bounds if bounds is not None else np.array([[-0.1] * 3, [0.1] * 3])
        mask, grid_step = _grid_mask(camera, grid_bounds)
        image.paste(tuple(int(c * 0.78) for c in options.background), mask=mask)
    base = np.asarray(image, dtype=np.uint16)
    alpha = model[..., 3:4].astype(np.uint16)
    # "over" in 8-bit integers, rounded; cannot exceed 255 since colour <= alpha.
    pixels = model[..., :3] + (base * (255 - alpha) + 127) // 255
    image = Image.fromarray(pixels.astype(np.uint8), "RGB")
    if labels:
        _draw_labels(image, camera, labels)
    if options.axes or grid_step is not None:
        strip, top = _overlay_strip(camera, options.axes, grid_step)
        box = (0, top, camera.width, camera.height)
        region = image.crop(box).convert("RGBA")
        region.alpha_composite(strip)
        image.paste(region.convert("RGB"), box)
    return image


def _draw_labels(image: Image.Image, camera: Camera, labels) -> None:
    """Each text just above and right of its point's pixel, on a pale backing so it
    reads over the model and the grid."""
    size = max(9, round(min(camera.width, camera.height) / 40))
    text_font = font(size)
    draw = ImageDraw.Draw(image, "RGBA")
    points = camera.to_pixels(np.array([point for _, point in labels], dtype=float))
    for (text, _), (x, y) in zip(labels, points, strict=True):
        at = (float(x) + size * 0.6, float(y) - size * 0.6)
        box = draw.multiline_textbbox(at, text, font=text_font, anchor="ld", spacing=2)
        pad = max(1, size // 5)
        draw.rectangle([box[0] - pad, box[1] - pad, box[2] + pad, box[3] + pad],
                       fill=(255, 255, 255, 190))
        draw.multiline_text(at, text, fill=TEXT_COLOR, font=text_font, anchor="ld",
                            spacing=2)


def png_bytes(image: Image.Image) -> bytes:
    """PNG encoding with no timestamps or other varying chunks: same pixels, same bytes."""
    buffer = io.BytesIO()
    image.save(buffer, format="PNG", compress_level=6)
    return buffer.getvalue()
