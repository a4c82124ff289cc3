"""Captioned grids of pictures: the contact sheet ``renders/index.png`` and ``--view all``.

A contact sheet lets a reviewer see every part, every chassis step and the complete robot
at a glance in a pull request. Thumbnails keep their aspect ratio and are centred in equal
cells; each caption names the picture (its path under ``renders/`` without ``.png``).
"""

from __future__ import annotations

import math

from PIL import Image, ImageDraw

from ..names import shown
from .compose import TEXT_COLOR, font

SHEET_BACKGROUND = (246, 247, 249)
THUMBNAIL_WIDTH = 320
MAX_COLUMNS = 4


def _fit(image: Image.Image, width: int, height: int) -> Image.Image:
    scale = min(width / image.width, height / image.height)
    size = (max(1, round(image.width * scale)), max(1, round(image.height * scale)))
    return image if size == image.size else image.resize(size, Image.LANCZOS)


def tile(images: list[Image.Image], captions: list[str], columns: int, cell: tuple[int, int],
         background=SHEET_BACKGROUND, caption_size: int = 14, pad: int = 8) -> Image.Image:
    """Images in a grid of ``columns``, each fitted into ``cell`` (w, h) with its caption."""
    rows = max(1, math.ceil(len(images) / columns))
    caption_font = font(caption_size)
    caption_height = caption_size + pad
    cell_w, cell_h = cell
    sheet = Image.new("RGB", (columns * (cell_w + pad) + pad,
                              rows * (cell_h + caption_height + pad) + pad), background)
    draw = ImageDraw.Draw(sheet)
    for index, (image, caption) in enumerate(zip(images, captions, strict=False)):
        row, column = divmod(index, columns)
        left = pad + column * (cell_w + pad)
        top = pad + row * (cell_h + caption_height + pad)
        thumb = _fit(image.convert("RGB"), cell_w, cell_h)
        sheet.paste(thumb, (left + (cell_w - thumb.width) // 2, top + (cell_h - thumb.height) // 2))
        text = shown(caption)  # one line: Pillow cannot centre (anchor) a caption of two
        while len(text) > 4 and draw.textlength(text, font=caption_font) > cell_w:
            text = "…" + text[2:]  # keep the end of a long path: the file name
        draw.text((left + cell_w // 2, top + cell_h + pad // 2), text, fill=TEXT_COLOR,
                  font=caption_font, anchor="mt")
    return sheet


def contact_sheet(entries: list[tuple[str, Image.Image]]) -> Image.Image:
    """Every (caption, picture) in a grid of up to four columns, sorted as given."""
    if not entries:
        return Image.new("RGB", (THUMBNAIL_WIDTH, THUMBNAIL_WIDTH * 3 // 4), SHEET_BACKGROUND)
    first = entries[0][1]
    cell = (THUMBNAIL_WIDTH, max(1, round(THUMBNAIL_WIDTH * first.height / first.width)))
    columns = min(MAX_COLUMNS, max(1, math.ceil(math.sqrt(len(entries)))))
    return tile([image for _, image in entries], [caption for caption, _ in entries],
                columns, cell)


def views_sheet(views: list[tuple[str, Image.Image]], width: int, height: int,
                background) -> Image.Image:
    """Four views in a 2x2 grid, captioned with their names, exactly ``width`` x ``height``."""
    caption_size = max(9, min(width, height) // 40)
    sheet = Image.new("RGB", (width, height), background)
    draw = ImageDraw.Draw(sheet)
    cell_w, cell_h = width // 2, height // 2
    for index, (name, image) in enumerate(views):
        row, column = divmod(index, 2)
        sheet.paste(image, (column * cell_w, row * cell_h))
        draw.text((column * cell_w + caption_size // 2, row * cell_h + caption_size // 2), name,
                  fill=TEXT_COLOR, font=font(caption_size))
    # Thin separators so the four frames do not run into each other.
    separator = tuple(int(c * 0.7) for c in background)
    draw.line([(cell_w, 0), (cell_w, height)], fill=separator, width=1)
    draw.line([(0, cell_h), (width, cell_h)], fill=separator, width=1)
    return sheet
