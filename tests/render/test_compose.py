"""Overlays and PNG output: grid spacing for people, deterministic bytes, the manifest."""

from __future__ import annotations

import json

import numpy as np
import pytest
from PIL import Image

from mobile_car.render.compose import format_length, nice_step, png_bytes
from mobile_car.render.manifest import Manifest


@pytest.mark.parametrize("length, step", [
    (0.05, 0.05), (0.0500001, 0.05), (0.051, 0.1), (0.0033, 0.005), (0.3, 0.5),
    (1.0, 1.0), (1.2, 2.0), (7, 10.0), (0.00012, 0.0002),
])
def test_grid_steps_are_one_two_or_five_times_a_power_of_ten(length, step):
    assert nice_step(length) == pytest.approx(step)


@pytest.mark.parametrize("metres, text", [
    (0.05, "5 cm"), (0.002, "2 mm"), (1.0, "1 m"), (2.0, "2 m"), (0.1, "10 cm"),
    (0.0005, "0.5 mm"),
])
def test_grid_spacing_is_printed_for_people(metres, text):
    assert format_length(metres) == text


def test_png_encoding_is_deterministic():
    pixels = np.random.default_rng(3).integers(0, 255, size=(30, 40, 3), dtype=np.uint8)
    first = png_bytes(Image.fromarray(pixels))
    assert first == png_bytes(Image.fromarray(pixels.copy()))
    assert first.startswith(b"\x89PNG") and b"tIME" not in first


def test_a_damaged_manifest_means_render_everything(tmp_path):
    (tmp_path / ".mcar-render.json").write_text("{ not json")
    manifest = Manifest(tmp_path)
    assert manifest.entries == {}
    picture = tmp_path / "a" / "b.png"
    picture.parent.mkdir()
    picture.write_bytes(b"png bytes")
    assert not manifest.is_current(picture, "f1")
    manifest.record(picture, "f1", b"png bytes", "a/b", renderer="gl")
    manifest.save()
    saved = json.loads((tmp_path / ".mcar-render.json").read_text())
    assert saved["outputs"]["a/b.png"]["caption"] == "a/b"
    reread = Manifest(tmp_path)
    assert reread.is_current(picture, "f1") and reread.is_current(picture, "f1", "gl")
    assert not reread.is_current(picture, "f1", "raycast")
    assert not reread.is_current(picture, "f2")
    picture.write_bytes(b"edited")
    assert not reread.is_current(picture, "f1")
