"""What a picture is asked to look like: view, size, geometry kind, background, overlays.

Kept free of numpy and GL so that the command line can parse and check its options
before anything heavy is imported.
"""

from __future__ import annotations

import math
import re
from dataclasses import asdict, dataclass

from ..errors import UsageError

VIEWS = ("iso", "front", "side", "top")
VIEW_CHOICES = VIEWS + ("all",)
RENDERERS = ("auto", "gl", "raycast")
# Which link frames get axes and names (see frames.py).
FRAME_CHOICES = ("auto", "bare", "all", "none")
RENDERER_ENV = "MCAR_RENDERER"

# A light slate grey: white plates and black wheels both stand out against it.
DEFAULT_BACKGROUND = (190, 196, 206)
DEFAULT_SIZE = (800, 600)
MIN_SIZE, MAX_SIZE = 16, 8192

# Peak memory per output pixel, measured (`/usr/bin/time`, 4000x4000 minus 2000x2000 of
# the bundled robot). OpenGL: a 4x multisampled RGBA colour and depth buffer (32 bytes),
# the resolved, read-back and flipped copies (12), compositing in float32 with 2x2
# supersampled overlays (~20). Ray casting keeps float64 rays, hits and shading per pixel.
BYTES_PER_PIXEL = {"gl": 64, "raycast": 216}
RENDER_MEMORY_MB = 1024  # a CI runner's share; 4096x4096 with OpenGL

_SIZE_RE = re.compile(r"\s*(\d+)\s*[xX]\s*(\d+)\s*")


@dataclass(frozen=True)
class RenderOptions:
    """How to draw one picture. ``view`` is one of VIEW_CHOICES; sizes are in pixels."""

    view: str = "iso"
    width: int = DEFAULT_SIZE[0]
    height: int = DEFAULT_SIZE[1]
    collision: bool = False
    background: tuple[int, int, int] = DEFAULT_BACKGROUND
    grid: bool = True
    axes: bool = True
    joints: tuple = ()  # --joint: (name, value text) pairs; the rest stay at zero
    frames: str = "auto"  # which link frames get axes and names (frames.FRAME_CHOICES)

    def __post_init__(self):
        if self.frames not in FRAME_CHOICES:
            raise UsageError(f"unknown --frames '{self.frames}'; choose one of "
                             f"{', '.join(FRAME_CHOICES)}")
        if self.view not in VIEW_CHOICES:
            raise UsageError(f"unknown view '{self.view}'; choose one of {', '.join(VIEW_CHOICES)}")
        smallest = 2 * MIN_SIZE if self.view == "all" else MIN_SIZE  # all: four frames
        for side in (self.width, self.height):
            if not smallest <= side <= MAX_SIZE:
                raise UsageError(f"image size {self.width}x{self.height} out of range for "
                                 f"--view {self.view} ({smallest}..{MAX_SIZE} pixels a side)")

    def fingerprint(self) -> dict:
        """The options as plain data, for the skip-unchanged manifest."""
        data = asdict(self)
        if not self.joints:  # pictures at joint zero keep the key they had before --joint
            del data["joints"]
        if self.frames == "auto":  # (DRAWING_VERSION says the skeleton's picture changed)
            del data["frames"]
        return data


def parse_size(text: str) -> tuple[int, int]:
    """``"800x600"`` -> ``(800, 600)``; anything else is a usage error."""
    match = _SIZE_RE.fullmatch(text)
    if not match:
        raise UsageError(f"--size '{text}' is not WIDTHxHEIGHT (e.g. 800x600)")
    width, height = int(match.group(1)), int(match.group(2))
    if not (MIN_SIZE <= width <= MAX_SIZE and MIN_SIZE <= height <= MAX_SIZE):
        raise UsageError(f"--size {width}x{height} out of range "
                         f"({MIN_SIZE}..{MAX_SIZE} pixels a side)")
    return width, height


def max_pixels(renderer: str) -> int:
    """The most pixels a picture may have for the renderer (``auto``: OpenGL's figure;
    the ray-casting fallback is the rare case and is told by its own figure only when
    chosen)."""
    per_pixel = BYTES_PER_PIXEL.get(renderer, BYTES_PER_PIXEL["gl"])
    return RENDER_MEMORY_MB * 1024 * 1024 // per_pixel


def check_pixels(width: int, height: int, renderer: str) -> None:
    """UsageError when the picture would need more than RENDER_MEMORY_MB to draw."""
    most = max_pixels(renderer)
    if width * height > most:
        side = math.isqrt(most)
        raise UsageError(f"--size {width}x{height} is {width * height / 1e6:.1f} megapixels; "
                         f"the {renderer} renderer draws at most {most / 1e6:.1f} (e.g. "
                         f"{side}x{side}) within its {RENDER_MEMORY_MB} MB memory budget")


def parse_color(text: str) -> tuple[int, int, int]:
    """A CSS colour name or ``#rrggbb`` as an RGB triple (Pillow's colour parser)."""
    from PIL import ImageColor  # small module; keeps Pillow off the start-up path

    try:
        rgb = ImageColor.getrgb(text.strip())
    except ValueError:
        raise UsageError(f"--background '{text}' is not a colour (a name like 'white' "
                         "or #rrggbb)") from None
    return tuple(rgb[:3])
